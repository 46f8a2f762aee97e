//! Accuracy against cost of the EHMAN engine: a measured study, not a claim.
//!
//! For each setting of (NB_HARM_LINE, NB_HARM_NONL, PARA_REGUL, PREC_MAN) a whole branch is
//! run over a fixed energy range and timed; its error is the largest relative deviation of
//! the frequency of the computed points from a reference curve at the same energy (every
//! computed point with its energy inside the range is compared, corrected branch ends and
//! uncorrected intermediate series points alike, so no interpolation of the computed curve
//! enters the error). The references:
//! - `wall`: the one-DOF oscillator of sdnd122 against its exact nonsmooth f(E)
//!   (`nnm::exact`, docs/ehman.md §5);
//! - `chain2`: two masses (wall–m1–m2 springs) with a BI_PLAN stop on m2, against the
//!   branch computed at the finest settings (`cases::chain2_reference_config`).
//!
//! Pure numerics and files: no SQL. `run_case` measures, `pareto` ranks, `report` writes the
//! table and CSV, `plot` draws error against time.

pub mod cases;
pub mod measure;
pub mod pareto;
pub mod plot;
pub mod report;

#[cfg(test)]
mod tests;

pub use cases::Config;
pub use cases::{det_test_grid, grid, CaseKind, GridSize, StudyCase};
pub use measure::{measure, measure_with, Measurement, Reference};
pub use pareto::{pareto_front, recommend, Recommendation};

use crate::error::Result;

/// Everything measured for one case.
pub struct CaseResult {
    pub case: StudyCase,
    pub measurements: Vec<Measurement>,
    /// The reference run (chain2 only): its settings and cost.
    pub reference: Option<Measurement>,
    /// The cost of the determinant-sign bifurcation test at a few settings.
    pub det_cost: Vec<DetCost>,
}

/// One setting run without and with TEST_BIFURCATION = 'SERIE_DETERMINANT'; of the
/// `DET_REPEATS` runs of each, the one with the least CPU time (the others only add the
/// load of the shared machine).
pub struct DetCost {
    pub config: Config,
    /// TEST_BIFURCATION = 'SERIE'.
    pub off: Measurement,
    /// TEST_BIFURCATION = 'SERIE_DETERMINANT'.
    pub on: Measurement,
}

/// Runs per setting and per value of the test, alternated so that a change in the load of
/// the machine hits both.
pub const DET_REPEATS: usize = 3;

/// Runs the whole grid of one case; `progress` is told about each measurement as it ends.
pub fn run_case(
    kind: CaseKind,
    size: GridSize,
    progress: &mut dyn FnMut(&Measurement),
) -> Result<CaseResult> {
    // Single-threaded for repeatable timings on a shared machine.
    faer::set_global_parallelism(faer::Par::Seq);
    let case = StudyCase::new(kind);
    // The reference of EHMAN's points (FREQUENCE at ENERGIE) and that of the points
    // corrected on the exact law (at ENERGIE_MOYENNE): the same closed form for the wall.
    let (reference, exact_reference, ref_run) = match kind {
        CaseKind::Wall => (
            Reference::exact_plan(cases::WALL),
            Reference::exact_plan(cases::WALL),
            None,
        ),
        CaseKind::Chain2 => {
            let cfg = cases::chain2_reference_config(size);
            let (curve, exact, m) = measure::reference_curve(&case, &cfg)?;
            progress(&m);
            (curve, exact, Some(m))
        }
    };
    let mut measurements = Vec::new();
    for cfg in grid(kind, size) {
        let r = if cfg.exact_law > 0 {
            &exact_reference
        } else {
            &reference
        };
        let m = measure(&case, &cfg, r);
        progress(&m);
        measurements.push(m);
    }
    let mut det_cost = Vec::new();
    for cfg in det_test_grid(kind, size) {
        let mut best: [Option<Measurement>; 2] = [None, None];
        for _ in 0..DET_REPEATS {
            for (slot, det) in best.iter_mut().zip([false, true]) {
                let c = Config {
                    sweep: if det { "SERIE_DET" } else { "SERIE" },
                    ..cfg
                };
                let m = measure_with(&case, &c, &reference, det);
                progress(&m);
                if slot.as_ref().is_none_or(|b| m.cost() < b.cost()) {
                    *slot = Some(m);
                }
            }
        }
        if let [Some(off), Some(on)] = best {
            det_cost.push(DetCost {
                config: cfg,
                off,
                on,
            });
        }
    }
    Ok(CaseResult {
        case,
        measurements,
        reference: ref_run,
        det_cost,
    })
}
