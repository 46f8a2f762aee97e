//! Rows that reach no obstacle, yet sit off the linear frequency: what the regularisation
//! alone does (alarm MODE_NON_LINE_9).
//!
//! Below first contact the nonsmooth law exerts no force, so the family of linear mode j is
//! the linear motion at f_j. The regularised law (PARA_REGUL = η) already pushes there:
//! PLAN and BI_PLAN with the slope η/JEU² (or 2η/JEU²) at rest, a ring with a force of
//! magnitude about η/JEU at its centre whatever the amplitude, which stiffens a small motion
//! through the centre without bound (a conical potential). A row whose orbit stays clear of
//! every obstacle and whose FREQUENCE is off f_j shows that shift, not contact: measured on
//! generated case 359 of seed 1 (a centred ring, 4 DOFs, PARA_REGUL 5.8e-7, DIR_EVOLUTION
//! toward zero), FREQUENCE climbs from f_1 = 0.494 Hz to 0.912 Hz as ENERGIE falls from
//! 5e-8 J to 2e-14 J, every row clear of the ring. The shift falls with PARA_REGUL (to first
//! order in proportion); a ring's LOI_CERCLE='SECANTE' has no force at its centre. The
//! engine computes those rows less accurately than the others (the force flips across the
//! centre, a jump its truncated series resolves poorly), and MODE_NON_LINE_1's advice,
//! which is about resolving contact, does not apply to them. A model with a cubic spring
//! (RESSORT_CUBIQUE) is not judged: the spring moves the frequency at every amplitude.

use crate::nnm::model::problem::ShockLaw;
use crate::nnm::Problem;

/// Shifts below this (relative to f_j) are not reported: five digits, the level below
/// which the accuracy advice names no setting (error_sources.rs).
pub const NEGLIGIBLE: f64 = crate::nnm::analysis::error_sources::NEGLIGIBLE;

/// Only rows that stay clear of every obstacle by at least this fraction of its JEU are
/// judged. Nearer, the regularised law rounds the onset of contact (its force is about
/// η/δ at a clearance δ): a shift there belongs to contact and its regularisation, which
/// MODE_NON_LINE_1's estimate splits. Measured on testcases/: 19 of the files that run
/// MODE_NON_LINE have rows clear of contact and off f_j by more than five digits; at half
/// a JEU of clearance only the U-tube's (utube.comm, two rings: up to 5.0e-3 above f_j at
/// 5.2e-5 J).
pub const CLEARANCE: f64 = 0.5;

/// One stored row as the alarm reads it.
#[derive(Clone, Copy, Debug)]
pub struct ClearRow {
    pub order: i64,
    pub energy: f64,
    pub frequency: f64,
    /// Largest penetration of the nonsmooth law along the orbit, units of JEU
    /// (`PostProcessor::largest_penetration`); negative: no obstacle reached.
    pub penetration: f64,
}

/// The alarm's text, if some row reaches no obstacle and is off `f_linear` (Hz, the
/// frequency of the linear mode the branch started from) by more than [`NEGLIGIBLE`].
pub fn regularisation_alarm(problem: &Problem, f_linear: f64, rows: &[ClearRow]) -> Option<String> {
    // A law without an obstacle (a cubic spring) moves the frequency off f_j at every
    // amplitude: the shift of a row clear of the stops is not the regularisation's alone.
    if problem.stops().count() < problem.shocks.len() {
        return None;
    }
    let off: Vec<&ClearRow> = rows
        .iter()
        .filter(|r| {
            r.penetration <= -CLEARANCE && (r.frequency / f_linear - 1.0).abs() > NEGLIGIBLE
        })
        .collect();
    let worst = off.iter().max_by(|a, b| {
        let shift = |r: &ClearRow| (r.frequency / f_linear - 1.0).abs();
        shift(a).total_cmp(&shift(b))
    })?;
    let first = off.iter().map(|r| r.order).min()?;
    let last = off.iter().map(|r| r.order).max()?;
    let ring = problem
        .shocks
        .iter()
        .any(|s| matches!(s.law, ShockLaw::Cercle { .. }));
    let why = if ring {
        "a ring's regularised force does not vanish inside the ring: its magnitude is about \
         η/(JEU − r) at a distance r from the centre (η = PARA_REGUL·k·JEU²), and it flips \
         direction across the centre, which stiffens a motion through it the more, the smaller \
         the motion"
    } else {
        "the regularised stop already has the stiffness η/JEU² (η = PARA_REGUL·k·JEU²) at rest"
    };
    let cure = if ring {
        "lower PARA_REGUL (the shift falls with it), or use LOI_CERCLE='SECANTE', whose force \
         vanishes at the centre"
    } else {
        "lower PARA_REGUL (the shift falls with it)"
    };
    Some(format!(
        "{} row(s) between NUME_ORDRE {first} and {last} reach no obstacle (their orbit stays \
         clear of every obstacle by at least {CLEARANCE} JEU) yet their FREQUENCE is off the \
         linear frequency {f_linear:.6e} Hz of the mode by up to {:+.3e} (NUME_ORDRE {}, \
         ENERGIE {:.4e} J): below contact the \
         nonsmooth law exerts no force, and that shift is the regularisation's alone ({why}). \
         With the nonsmooth law these rows are the linear mode; the truncated series resolves \
         the regularised force there less well than contact, and the advice of MODE_NON_LINE_1 \
         does not apply to them: {cure}",
        off.len(),
        worst.frequency / f_linear - 1.0,
        worst.order,
        worst.energy,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::tests::one_dof;

    fn row(order: i64, frequency: f64, penetration: f64) -> ClearRow {
        ClearRow {
            order,
            energy: 1e-3 * order as f64,
            frequency,
            penetration,
        }
    }

    /// Only rows clear of the obstacle by half a JEU and off f_j by more than five digits
    /// are reported, the largest shift named; a row in contact or near it is contact's
    /// business, whatever its shift.
    #[test]
    fn only_clear_rows_off_the_linear_frequency_are_reported() {
        let problem = one_dof(ShockLaw::Plan, 1e-5);
        let f = 1.0;
        let quiet = [
            row(1, 1.0 + 5e-6, -0.5),
            row(2, 1.3, 0.1),
            row(3, 1.0, -1.0),
            row(4, 1.0 + 3e-3, -0.4),
        ];
        assert_eq!(regularisation_alarm(&problem, f, &quiet), None);
        let rows = [
            row(1, 1.0 + 2e-5, -0.5),
            row(2, 1.0 + 4e-4, -0.9),
            row(3, 1.5, 0.2),
            row(4, 1.0 + 1e-2, -0.1),
            row(5, 1.0, -0.9),
        ];
        let text = regularisation_alarm(&problem, f, &rows).expect("alarm");
        assert!(
            text.starts_with("2 row(s) between NUME_ORDRE 1 and 2"),
            "{text}"
        );
        assert!(text.contains("+4.000e-4 (NUME_ORDRE 2"), "{text}");
        assert!(
            text.contains("lower PARA_REGUL") && !text.contains("SECANTE"),
            "{text}"
        );
    }

    /// A ring's advice names LOI_CERCLE='SECANTE' as well.
    #[test]
    fn a_ring_is_told_of_its_centre() {
        let ring = ShockLaw::Cercle {
            origin: [0.0, 0.0],
            form: crate::nnm::CercleForm::Radial,
        };
        let problem = one_dof(ring, 1e-5);
        let text = regularisation_alarm(&problem, 1.0, &[row(7, 1.2, -0.9)]).expect("alarm");
        assert!(
            text.contains("SECANTE") && text.contains("centre"),
            "{text}"
        );
    }
}
