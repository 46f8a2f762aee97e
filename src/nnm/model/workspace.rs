//! The scratch of the harmonic-balance system, owned by the caller and passed as `&mut`
//! (faer's way): the transforms' buffers, the sums of the sampled products and the time
//! samples of earlier series. `System` itself is read-only once built, so one problem can
//! serve several threads, each with its own workspace.

use crate::nnm::model::cosine_sampler::CosineScratch;
use crate::nnm::model::fourier::FftScratch;
use crate::nnm::model::system::Samples;

/// What `System`'s residual, sampled products and series need besides the system: made
/// once per system (`System::workspace`), reused at every order of every series and every
/// Newton iteration.
pub struct Workspace {
    /// The full grid's transform scratch (`System::samples_into`, `quad_sum_cached`).
    pub(in crate::nnm::model) fft: FftScratch,
    /// The cosine grid's (a time-symmetric branch's series).
    pub(in crate::nnm::model) cosine: CosineScratch,
    /// The structural sums and per-shock product buffers of `quad_sum_cached`.
    pub(in crate::nnm::model) quad: QuadWork,
    /// `Samples` given back by earlier series (`recycle_samples`), their buffers reused by
    /// the next `take_samples`.
    pub(in crate::nnm::model) pool: Vec<Samples>,
}

/// The buffers of `System::quad_sum_cached`.
pub(in crate::nnm::model) struct QuadWork {
    /// Structural sums (n·(2H_l+1) each) and one derivative (2H_l+1).
    pub su: Vec<f64>,
    pub sv: Vec<f64>,
    pub w: Vec<f64>,
    pub d: Vec<f64>,
    /// One equation's coefficients (2H_nl+1), and the sampled products of one shock's
    /// equations (the largest n_own times the full grid).
    pub c: Vec<f64>,
    pub acc: Vec<f64>,
}

impl Workspace {
    /// A `Samples` whose buffers come from an earlier one when some were given back: a
    /// series samples each of its terms, and every branch has a series.
    pub fn take_samples(&mut self) -> Samples {
        self.pool.pop().unwrap_or_default()
    }

    /// Give buffers back for the next `take_samples`.
    pub fn recycle_samples(&mut self, samples: impl IntoIterator<Item = Samples>) {
        self.pool.extend(samples);
    }
}
