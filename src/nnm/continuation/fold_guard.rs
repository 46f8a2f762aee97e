//! A branch that turns back in ENERGIE where its contact law has come apart: the rows past
//! the turn are not motions, and the run stops there (driver.rs).
//!
//! A family of nonlinear modes may turn back in ENERGIE: near an internal resonance it
//! bends into a tongue and comes back (measured over the 500 generated cases of seed 1:
//! 268 of the 477 runs that stored at least two rows turn back somewhere). At such a turn
//! the force series still follows its law in time: the law defect of the branch end past
//! the turn (column ECART_LOI_CHOC, in units of RIGI_NOR·JEU) was at most 0.51 in all but
//! four runs.
//!
//! Far into a BI_PLAN stop a branch may also turn back, and there the law has come apart:
//! the defect at the top of the turn was 1.63 in each of those four (cases 72, 141, 290
//! and 385: one to three DOFs, RIGI_NOR/k_ref 6.1e2 to 9.5e7, NB_HARM_NONL 27 to 665), and
//! 1.63 to 2.10 at the branch ends past it. RIGI_NOR·JEU is the force by which the law's
//! roots differ (BI_PLAN's f = α(u ∓ g) and f = 0): a series that misses the law by more
//! than that no longer tells contact from clearance, and past the turn the branch follows
//! a root of the truncated balance. Measured on case 290 (H 11/27) against the same file
//! with NB_HARM_NONL 108: the rows from 1.4e5 J to the turn at 3.0e5 J are 5e-4 to 1.5e-3
//! off in frequency, and the rows after it 1.5e-3, going back down in ENERGIE for as many
//! branches as were left (case 72: 1800 rows between 16 200 J and 70 J, 60 s). With
//! NB_HARM_NONL 33 the turn moves to 4.5e5 J; with 54 the branch goes on to its
//! homogeneous limit.
//!
//! The rule: at a turn (the first decrease of ENERGIE after an increase), the run stops
//! when the defect of the branch end exceeds [`CLEARANCE_DEFECT`]·RIGI_NOR·JEU; the rows
//! after the highest are not stored. Between the 0.51 of the physical turns and the 1.63 of
//! the broken ones.

use crate::nnm::Point;

/// The law defect (units of RIGI_NOR·JEU) above which a turn in ENERGIE is not a turn of
/// the family (module doc).
pub const CLEARANCE_DEFECT: f64 = 1.0;

/// Whether ENERGIE was rising along the branch, from point to point.
#[derive(Clone, Debug, Default)]
pub struct EnergyTrend {
    /// ENERGIE and FREQUENCE of the last point seen.
    last: Option<(f64, f64)>,
    rising: bool,
}

/// A turn past which the rows are not motions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrokenTurn {
    /// The points of the branch to keep: those up to the highest ENERGIE.
    pub keep: usize,
    /// The absolute law defect of the branch end, units of RIGI_NOR·JEU.
    pub defect: f64,
    /// ENERGIE (J) and FREQUENCE (Hz) at the top of the turn.
    pub energy: f64,
    pub frequency: f64,
}

impl EnergyTrend {
    /// Follows the points of one branch (the last one its corrected end); returns the turn
    /// if ENERGIE turns back in them, or between the previous branch's end and them, with
    /// the end's law broken ([`CLEARANCE_DEFECT`]). A turn with the law held is passed.
    pub fn branch(&mut self, points: &[Point]) -> Option<BrokenTurn> {
        let end_defect = points
            .last()
            .and_then(|p| p.law_defect)
            .map(|(absolute, _)| absolute);
        self.scan(points.iter().map(|p| (p.energy, p.frequency)), end_defect)
    }

    /// [`EnergyTrend::branch`] on (ENERGIE, FREQUENCE) pairs.
    fn scan(
        &mut self,
        points: impl Iterator<Item = (f64, f64)>,
        end_defect: Option<f64>,
    ) -> Option<BrokenTurn> {
        let mut turn = None;
        for (i, (energy, frequency)) in points.enumerate() {
            if let Some(last) = self.last {
                if energy > last.0 {
                    self.rising = true;
                } else if energy < last.0 && self.rising {
                    self.rising = false;
                    turn.get_or_insert((i, last));
                }
            }
            self.last = Some((energy, frequency));
        }
        let (keep, top) = turn?;
        // A NaN defect is not a held law.
        let defect = end_defect.filter(|d| d.is_nan() || *d > CLEARANCE_DEFECT)?;
        Some(BrokenTurn {
            keep,
            defect,
            energy: top.0,
            frequency: top.1,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn branch(
        t: &mut EnergyTrend,
        energies: &[f64],
        end_defect: Option<f64>,
    ) -> Option<BrokenTurn> {
        t.scan(energies.iter().map(|&e| (e, 10.0 * e)), end_defect)
    }

    /// A physical turn (a tongue, law held) is passed, and the trend goes on from it.
    #[test]
    fn a_turn_with_the_law_held_is_passed() {
        let mut t = EnergyTrend::default();
        assert_eq!(branch(&mut t, &[1.0, 2.0, 3.0], Some(0.02)), None);
        assert_eq!(branch(&mut t, &[2.5, 2.0], Some(CLEARANCE_DEFECT)), None);
        // Rising again, then a broken turn: caught.
        assert_eq!(branch(&mut t, &[2.2, 3.5], Some(0.1)), None);
        let turn = branch(&mut t, &[4.0, 3.9], Some(1.63)).expect("broken turn");
        assert_eq!(turn.keep, 1);
        assert_eq!(
            (turn.energy, turn.frequency, turn.defect),
            (4.0, 40.0, 1.63)
        );
    }

    /// A branch that falls from its start (DIR_EVOLUTION toward zero, a restart going
    /// down) has no turn, whatever its defect.
    #[test]
    fn a_branch_that_only_falls_has_no_turn() {
        let mut t = EnergyTrend::default();
        for b in 0..5 {
            let e0 = 100.0 - 10.0 * b as f64;
            assert_eq!(branch(&mut t, &[e0, e0 - 3.0, e0 - 6.0], Some(5.0)), None);
        }
    }

    /// The turn at the boundary of two branches keeps none of the second and reports the
    /// previous end as its top; a turn inside a branch keeps the points up to the highest;
    /// an end without a law check (no shocks) is never judged; a NaN defect is.
    #[test]
    fn the_rows_after_the_top_are_dropped() {
        let mut t = EnergyTrend::default();
        assert_eq!(branch(&mut t, &[1.0, 2.0], Some(0.5)), None);
        let turn = branch(&mut t, &[1.9, 1.5], Some(2.0)).expect("turn");
        assert_eq!((turn.keep, turn.energy, turn.frequency), (0, 2.0, 20.0));
        let mut t = EnergyTrend::default();
        let turn = branch(&mut t, &[1.0, 2.0, 3.0, 2.9, 2.5], Some(1.7)).expect("turn");
        assert_eq!((turn.keep, turn.energy), (3, 3.0));
        let mut t = EnergyTrend::default();
        assert_eq!(branch(&mut t, &[1.0, 2.0, 1.0], None), None);
        let mut t = EnergyTrend::default();
        assert!(branch(&mut t, &[1.0, 2.0, 1.0], Some(f64::NAN)).is_some());
    }
}
