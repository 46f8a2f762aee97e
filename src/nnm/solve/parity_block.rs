//! The contact block of a law with one own unknown (the Toeplitz route, contact.rs) at a
//! time-symmetric point, restricted to one parity: x ↦ Trunc_H(j(t)·x) on cosine series
//! or on sine series, with j even in time. These are the operators of the two generator
//! solves (T⁻¹(2 cos Hθ) is a cosine series, T⁻¹(2 sin Hθ) a sine series), each applied
//! on the n midpoints of half a period (cosine_sampler.rs: one real FFT of n per
//! transform, 2n > 3H so that the truncated products are exact), with vectors of H + 1
//! or H coefficients: each Krylov iteration costs about half one on the whole period with
//! both parities in one vector, and each solve needs fewer iterations than that joint one
//! (measured on sdnd122a: 6.6 per parity against 9.3 for the two together).
//!
//! The preconditioner x ↦ Trunc_H(x/j) has a grid of its own. The operator must be
//! applied exactly (its inverse is what the Toeplitz route represents and checks against),
//! the preconditioner need only approximate that inverse: on any n ≥ H + 1 midpoints it is
//! one fixed linear map of the series of H harmonics, and its transforms on the smallest
//! such grid cost about two thirds of the exact ones (216 against 320 midpoints at
//! H = 200; the engine time of sdnd122a 34.6 → 34.1 ms, docs/performance_history.md,
//! seventh round).

use crate::nnm::model::cosine_sampler::{CosineSampler, CosineScratch};
use crate::nnm::model::system::{Layout, ShockSys};
use crate::nnm::solve::contact::jacobians;
use crate::nnm::solve::gmres::Preconditioned;

/// Which series the operator acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::nnm) enum Parity {
    /// Cosine series: [x_0, c_1..c_H] (H + 1 coefficients).
    Even,
    /// Sine series: [s_1..s_H] (H coefficients).
    Odd,
}

/// The samples of the law at one grid of midpoints, and the product of a series by them.
struct Grid {
    tr: CosineSampler,
    ws: CosineScratch,
    /// Samples of j (or 1/j, `invert`), of the law's variables (own unknown, then the
    /// components), of J_u (unused: the coupling is built on the whole period), and of one
    /// series.
    m: Vec<f64>,
    xs: Vec<f64>,
    jac_u: Vec<f64>,
    s: Vec<f64>,
}

impl Grid {
    fn new(tr: CosineSampler, n_comp: usize) -> Grid {
        let ws = tr.scratch();
        let n = tr.n();
        Grid {
            tr,
            ws,
            m: vec![0.0; n],
            xs: vec![0.0; n * (1 + n_comp)],
            jac_u: vec![0.0; n * n_comp],
            s: vec![0.0; n],
        }
    }

    /// j at the time-symmetric `x0` (the cosine parts of its series; their sine parts are
    /// round-off).
    fn linearise(&mut self, sh: &ShockSys, lay: &Layout, x0: &[f64]) {
        let n = self.tr.n();
        let nc = sh.dofs.len();
        let o = sh.offset;
        self.tr
            .cos_synth(&x0[o..=o + lay.h_nonl], &mut self.xs[..n], &mut self.ws);
        for (c, &dof) in sh.dofs.iter().enumerate() {
            let u = lay.u(dof);
            let dst = &mut self.xs[(1 + c) * n..(2 + c) * n];
            self.tr.cos_synth(&x0[u..=u + lay.h_lin], dst, &mut self.ws);
        }
        jacobians(&sh.eqs, &self.xs, n, (1, nc), &mut self.m, &mut self.jac_u);
    }

    /// y = Trunc(m(t)·x(t)), x and y series of `parity`.
    fn mul(&mut self, parity: Parity, x: &[f64], y: &mut [f64]) {
        match parity {
            Parity::Even => self.tr.cos_synth(x, &mut self.s, &mut self.ws),
            Parity::Odd => self.tr.sin_synth(x, &mut self.s, &mut self.ws),
        }
        for (v, a) in self.s.iter_mut().zip(&self.m) {
            *v *= a;
        }
        match parity {
            Parity::Even => self.tr.cos_analyse(&self.s, y, &mut self.ws),
            Parity::Odd => self.tr.sin_analyse(&self.s, y, &mut self.ws),
        }
    }
}

/// j(t) on the half period (exact products) and 1/j(t) on the preconditioner's grid, and
/// the operators built on them.
pub(in crate::nnm) struct ParityBlock {
    h: usize,
    exact: Grid,
    coarse: Grid,
    /// Bound of the operator's norm (√2·max |j|, as the whole-period one).
    bound: f64,
    parity: Parity,
}

impl ParityBlock {
    /// For a law with one own unknown and `n_comp` displacement components, series of `h`
    /// harmonics.
    pub fn new(h: usize, n_comp: usize) -> ParityBlock {
        ParityBlock {
            h,
            exact: Grid::new(CosineSampler::for_products(h), n_comp),
            coarse: Grid::new(CosineSampler::at_least(h + 1), n_comp),
            bound: 0.0,
            parity: Parity::Even,
        }
    }

    /// Number of coefficients of a series of `parity`.
    pub fn dim(&self, parity: Parity) -> usize {
        match parity {
            Parity::Even => self.h + 1,
            Parity::Odd => self.h,
        }
    }

    /// j at the time-symmetric `x0`; false where j vanishes on either grid (no pointwise
    /// inverse).
    pub fn linearise(&mut self, sh: &ShockSys, lay: &Layout, x0: &[f64]) -> bool {
        self.exact.linearise(sh, lay, x0);
        let peak = self.exact.m.iter().fold(0.0f64, |b, v| b.max(v.abs()));
        self.bound = std::f64::consts::SQRT_2 * peak;
        let invertible = self.exact.m.iter().all(|&v| (1.0 / v).is_finite());
        self.coarse.linearise(sh, lay, x0);
        for v in &mut self.coarse.m {
            *v = 1.0 / *v;
        }
        invertible && self.coarse.m.iter().all(|v| v.is_finite())
    }

    /// The operator of one parity (the next solves' `Preconditioned`).
    pub fn select(&mut self, parity: Parity) -> &mut Self {
        self.parity = parity;
        self
    }
}

impl Preconditioned for ParityBlock {
    fn apply(&mut self, x: &[f64], y: &mut [f64]) {
        self.exact.mul(self.parity, x, y);
    }
    fn precondition(&mut self, x: &[f64], y: &mut [f64]) {
        self.coarse.mul(self.parity, x, y);
    }
    fn norm_bound(&self) -> f64 {
        self.bound
    }
}
