//! REDUCTION (aster-nl extension): MODE_NON_LINE on a Craig–Bampton basis of the structure
//! (linalg/craig_bampton.rs, nnm/model/reduced.rs). Reads the keyword, chooses the cut-off
//! within the memory available, says what the stored setup keeps of the basis, and words
//! the cut-off's alarm.

use crate::args::Args;
use crate::error::Result;
use crate::linalg::craig_bampton::{highest_frequency, ModeCut, Reduction};
use crate::nnm::{self, Problem};
use crate::store::mnl::StoredReduction;

/// The cut-off REDUCTION asks for, read once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum CutAsk {
    /// NB_MODE.
    Count(usize),
    /// FREQ_COUPURE (Hz).
    UpTo(f64),
    /// COEF_COUPURE: the cut-off is this × NB_HARM_LINE × the start's linear frequency.
    Coef(f64),
}

impl CutAsk {
    /// The modes to keep, given NB_HARM_LINE and the frequency of the starting linear mode.
    pub(super) fn cut(self, h_lin: usize, f_start: f64) -> ModeCut {
        match self {
            CutAsk::Count(n) => ModeCut::Count(n),
            CutAsk::UpTo(f) => ModeCut::UpTo(f),
            CutAsk::Coef(c) => ModeCut::UpTo(c * h_lin as f64 * f_start),
        }
    }
}

/// REDUCTION's cut-off, or `None` without the keyword (defaults are the catalog's).
pub(super) fn ask(args: &Args) -> Result<Option<CutAsk>> {
    let Some(r) = args.fact("REDUCTION") else {
        return Ok(None);
    };
    Ok(Some(if let Some(n) = r.count("NB_MODE")? {
        CutAsk::Count(n)
    } else if let Some(f) = r.real("FREQ_COUPURE") {
        CutAsk::UpTo(f)
    } else {
        CutAsk::Coef(r.req_real("COEF_COUPURE")?)
    }))
}

/// Bytes per basis entry while the basis is built and used: its columns, and as much again
/// twice for the eigensolver's and the projection's work vectors (an allowance, not a
/// measurement: the basis is what grows with the DOFs and the modes).
const BYTES_PER_BASIS_ENTRY: f64 = 3.0 * 8.0;

/// Most columns a basis may have: a reduced problem of this many coordinates carries as
/// many unknowns per harmonic as a model of that many DOFs, and shift-invert Lanczos for
/// that many modes of a large model runs for hours (364 modes of a 10⁵-DOF model: 137 s).
const MAX_BASIS_COLUMNS: usize = 2000;

/// The Craig–Bampton basis of `full` retaining its shock DOFs, in the memory available and
/// at most [`MAX_BASIS_COLUMNS`] columns.
pub(super) fn basis(full: &Problem, cut: ModeCut) -> Result<Reduction> {
    let n = full.k.nrows().max(1) as f64;
    let bytes = crate::process::memory_limit().map_or(f64::INFINITY, |(b, _)| b);
    let in_memory = (bytes / (n * BYTES_PER_BASIS_ENTRY)).min(usize::MAX as f64) as usize;
    let max_columns = in_memory.min(MAX_BASIS_COLUMNS);
    nnm::shock_basis(full, cut, max_columns)
        .map_err(|e| crate::error::Error::from(e).keyword("MODE_NON_LINE/REDUCTION"))
}

/// What the setup stores of a basis (its columns go to `mnl_basis`).
pub(super) fn stored(red: &Reduction) -> StoredReduction {
    StoredReduction {
        retained: red.retained.clone(),
        modes: red.omega2.len(),
    }
}

/// MODE_NON_LINE_10: the rows whose NB_HARM_LINE-th harmonic lies above the cut-off, where
/// the basis represents the structure's response only quasi-statically.
pub(super) fn cut_off_alarm(red: &Reduction, h_lin: usize, rows: &[(i64, f64)]) -> Option<String> {
    // A static condensation (no mode) has every harmonic above its cut-off.
    let cut = highest_frequency(red).unwrap_or(0.0);
    let above: Vec<&(i64, f64)> = rows
        .iter()
        .filter(|(_, f)| h_lin as f64 * f > cut)
        .collect();
    let (first, last) = (above.first()?, above.last()?);
    let asked = h_lin as f64 * above.iter().map(|r| r.1).fold(0.0f64, f64::max);
    let basis = match red.omega2.len() {
        0 => "no fixed-interface mode: a static condensation".to_string(),
        m => format!("{m} fixed-interface mode(s), the highest at {cut:.6e} Hz"),
    };
    Some(format!(
        "{} row(s) between NUME_ORDRE {} and {} have NB_HARM_LINE x FREQUENCE above the cut-off \
         of the reduction basis ({basis}; up to {asked:.6e} Hz asked there): the modes above \
         the cut-off enter those harmonics only statically; raise REDUCTION/COEF_COUPURE, \
         FREQ_COUPURE or NB_MODE so that the cut-off is well above {asked:.6e} Hz",
        above.len(),
        first.0,
        last.0,
    ))
}
