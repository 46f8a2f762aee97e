//! The frequency floor of a branch that starts from a linear mode: every contact law of
//! aster-nl only stiffens the structure, so the family of mode j stays at or above the
//! mode's linear frequency f_j; a row well below it, with no internal resonance near to
//! explain the dip, is a root of the truncated harmonic balance, not a motion
//! (RESOLUTION/BAISSE_FREQ_MAXI, StepControl::frequency_floor).
//!
//! Why the floor holds: PLAN, BI_PLAN and CERCLE (with the structure at rest inside the
//! clearance) push the structure back and their force grows with the penetration; the
//! regularised law is stiffer still; a cubic spring (RESSORT_CUBIQUE, k₃ > 0) adds the
//! stiffness 3k₃u² ≥ 0 at every amplitude. A conservative structure with added restoring
//! stiffness vibrates faster: for one DOF the period ∮ dx/v shrinks wherever the potential
//! grows, and along the family of mode j the motion is mode j's until contact. What can
//! lower the frequency of a multi-DOF family is an internal resonance: where n·f nears the
//! frequency f_k of another mode k, the family bends toward f_k/n (measured on
//! testcases/hard/chain20_stiff.comm: a dip of 1.2e-3 toward f_2/3, 1.95e-3 below f_1).
//! The harmonic balance shows such a bend only for n ≤ NB_HARM_LINE. A stiffened mode k
//! keeps n·f ≥ f_k, so the bend does not go much past f_k/n.
//!
//! The rule: a row at frequency f with dip d = (f_j − f)/f_j above the tolerance is not a
//! motion unless some f_k/n (k any mode, 1 ≤ n ≤ NB_HARM_LINE, except n = 1 with k = j)
//! lies below f_j by a distance d_kn = (f_j − f_k/n)/f_j with d/[`SLACK`] ≤ d_kn ≤
//! [`NEAR`]: a resonance close enough to bend the family near first contact, and not so
//! close that the row would have passed it. The row's frequency error is then at least d,
//! whatever the settings: the true family is at or above f_j. Measured (docs/hard_cases.md,
//! "The frequency floor"): branches of generated cases that turn at first contact into
//! roots of the truncated balance reach dips of 4e-6 to 2e-2 there; chain20_stiff's bend
//! starts at its first row (a dip of 8e-5, 24 times less than d_kn).
//!
//! Far below first contact the family of mode j is its linear motion at f_j, shifted only
//! by the slope of the regularised force at rest: a row there at another frequency lies on
//! the trivial line of the harmonic balance (the equilibrium, which solves it at any
//! frequency), onto which a branch that folds back to zero amplitude can run.
//! [`OffTheFamily::Linear`]. This is checked for planes only (PLAN, BI_PLAN), whose
//! regularised force is smooth at rest; not with a cubic spring in the model, which has no
//! linear range (its stiffness grows from 0 with the amplitude). A ring's is not at its centre: the regularised
//! force keeps the magnitude η/JEU there and stiffens small motions without bound
//! (measured on generated case 171 of seed 1, a centred ring: shooting on the same law
//! puts the family 1.5e-4 above f_3 at 2e-7 times the first-contact energy).

use crate::nnm::model::linear_modes::LinearMode;
use crate::nnm::model::point_law::eta_phys;
use crate::nnm::Problem;

/// The farthest internal resonance below f_j that explains a dip (relative): the bend of
/// a family toward f_k/n near first contact, where the contact force is weak, is seen only
/// for close resonances; chain20_stiff's is 1.95e-3 below f_1.
pub const NEAR: f64 = 1e-2;

/// A dip explained by a resonance at d_kn is at most this many times d_kn: a stiffened
/// mode k keeps n·f above f_k, so the family does not pass f_k/n (by more than a
/// regularisation's or truncation's shift).
pub const SLACK: f64 = 2.0;

/// ENERGIE below this fraction of the first-contact energy counts as far below contact:
/// the amplitude at the shocks is below 1 % of the gap.
pub const LINEAR_ENERGY: f64 = 1e-4;
/// There, the relative distance from f_j allowed is this many times the shift the
/// regularised planes' stiffness at rest gives to f_j by first-order perturbation,
/// ½·Σ k_reg·φ_p²/ω_j² (k_reg = η/JEU² for PLAN, 2η/JEU² for BI_PLAN, the slope of the
/// regularised force at the rest position; at least the tolerance).
pub const LINEAR_SAFETY: f64 = 4.0;

/// With a ring, a descending branch end far below contact (ENERGIE under [`LINEAR_ENERGY`]
/// times the first-contact energy) more than this far above f_j (relative) has gone into
/// the regularised ring's cone ([`OffTheFamily::Cone`]). At the ring's centre the
/// regularised force keeps the magnitude of about η/JEU whatever the amplitude, so a motion
/// through the centre is stiffened the more, the smaller it is: along the descent the
/// frequency climbs without bound, the nonsmooth law's motion there is the linear mode at
/// f_j, and the truncated force series resolves the flipping force poorly (alarm
/// MODE_NON_LINE_9). Measured on the generated cases of seed 2 (docs/hard_cases.md): three
/// descents through a centred ring went on into the cone, to 4.7e-2 (s2_c0084), 3.2e-1
/// (s2_c0055) and 2.2e-1 (s2_c0104) above f_j at 1e-13 to 2e-15 J, their last rows 2e-3 to
/// 2e-2 from shooting on the same law, and s2_c0104 wandered there for 500 branches. Three
/// digits: a shift above 1e-3 is the regularisation's, not contact's.
pub const CONE_SHIFT: f64 = 1e-3;

/// Modes below this fraction of the highest frequency count as rigid-body modes (the
/// frequency of a zero eigenvalue computed in floating point is ~1e-8 of the highest).
pub const RIGID: f64 = 1e-6;

/// The floor of one branch, built once per run.
#[derive(Clone, Debug)]
pub struct FrequencyFloor {
    /// f_j, Hz.
    linear: f64,
    /// The f_k/n within [`NEAR`] below f_j, increasing (Hz): the only ones that can explain
    /// a dip.
    resonances: Vec<f64>,
    /// Dips at or below this are not judged (BAISSE_FREQ_MAXI).
    tolerance: f64,
    /// The energy at which mode j's linear motion first reaches an obstacle, J (the
    /// smallest over the shocks; infinite when the mode does not move any shock DOF); 0
    /// (no check far below contact) with a ring, whose regularised law is not smooth at its
    /// centre (module doc).
    contact_energy: f64,
    /// The relative distance from f_j allowed far below contact ([`LINEAR_SAFETY`]).
    linear_band: f64,
    /// The first-contact energy, J, when some stop is not a plane (a ring: the cone check,
    /// [`CONE_SHIFT`]) and every law has an obstacle; 0 otherwise.
    cone_energy: f64,
}

/// Why a branch end is not a motion of the family.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OffTheFamily {
    /// Below f_j by this relative dip, no resonance in reach (module doc).
    Below(f64),
    /// Far below first contact (ENERGIE under [`LINEAR_ENERGY`] times the contact energy),
    /// yet this relative distance from f_j, more than the regularisation's shift allows
    /// ([`LINEAR_SAFETY`]; planes only): the motion reaches no obstacle, so it is mode j's
    /// linear one at f_j; a row there at another frequency is on the trivial line of the
    /// harmonic balance (the equilibrium, which any frequency solves), not a motion.
    Linear(f64),
    /// Far below first contact with a ring, going down, and this relative distance above
    /// f_j, more than [`CONE_SHIFT`]: the branch has gone into the regularised ring's
    /// cone, where the regularisation alone sets the frequency.
    Cone(f64),
}

impl FrequencyFloor {
    /// The floor of the family of the linear mode nearest `start_frequency` (Hz), or None
    /// where the rule does not hold: no shock, a ring whose origin puts the structure in
    /// contact at rest, a rigid-body mode (a free structure), no linear modes (a model too
    /// large for the dense check).
    pub fn new(
        problem: &Problem,
        modes: Option<&[LinearMode]>,
        start_frequency: f64,
        h_lin: usize,
        tolerance: f64,
    ) -> Option<FrequencyFloor> {
        let modes = modes?;
        if problem.shocks.is_empty() || !problem.shocks.iter().all(rest_inside) {
            return None;
        }
        // A rigid-body mode (a free structure) has no rest position for the regularised
        // force to stiffen about: it pushes the structure away, no floor.
        let highest = modes.iter().map(|m| m.frequency).fold(0.0, f64::max);
        if modes.iter().any(|m| m.frequency <= RIGID * highest) {
            return None;
        }
        let start = modes.iter().min_by(|a, b| {
            (a.frequency - start_frequency)
                .abs()
                .total_cmp(&(b.frequency - start_frequency).abs())
        })?;
        let linear = start.frequency;
        if !(linear > 0.0 && linear.is_finite()) {
            return None;
        }
        let mut resonances: Vec<f64> = modes
            .iter()
            .flat_map(|m| {
                (1..=h_lin.max(1))
                    .filter(move |&n| !(n == 1 && m.number == start.number))
                    .map(move |n| m.frequency / n as f64)
            })
            .filter(|&f| f <= linear && (linear - f) / linear <= NEAR)
            .collect();
        resonances.sort_by(f64::total_cmp);
        let planes = problem.shocks.iter().all(|sh| {
            sh.law
                .with(|l| l.stiffness_at_rest(sh.gap, sh.regul).is_some())
        });
        let (contact_energy, linear_band) = match (planes, eta_phys(problem)) {
            (true, Ok(eta)) => (
                contact_energy(problem, &start.shape, linear),
                (LINEAR_SAFETY * regularisation_shift(problem, &eta, &start.shape, linear))
                    .max(tolerance),
            ),
            _ => (0.0, f64::INFINITY),
        };
        // The cone: a ring's regularised force is not smooth at its centre. Every law must
        // have an obstacle (a cubic spring moves the frequency at every amplitude).
        let rings = !planes && problem.stops().count() == problem.shocks.len();
        let cone_energy = if rings {
            self::contact_energy(problem, &start.shape, linear)
        } else {
            0.0
        };
        Some(FrequencyFloor {
            linear,
            resonances,
            tolerance,
            contact_energy,
            linear_band,
            cone_energy,
        })
    }

    /// The linear frequency f_j of the family (Hz).
    pub fn linear(&self) -> f64 {
        self.linear
    }

    /// The dips not judged (BAISSE_FREQ_MAXI).
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// Why a row at `frequency` (Hz) and `energy` (ENERGIE, J) is not a motion of the
    /// family, if it is not; `descending`: the branch's energy fell over its last step (the
    /// cone is judged only going down: a branch started in it climbs out of it).
    pub fn off_the_family(
        &self,
        frequency: f64,
        energy: f64,
        descending: bool,
    ) -> Option<OffTheFamily> {
        let distance = (frequency / self.linear - 1.0).abs();
        if energy < LINEAR_ENERGY * self.contact_energy && distance > self.linear_band {
            return Some(OffTheFamily::Linear(distance));
        }
        let above = frequency / self.linear - 1.0;
        // BAISSE_FREQ_MAXI above CONE_SHIFT raises it (1.0 turns every check off).
        let cone = CONE_SHIFT.max(self.tolerance);
        if descending && energy < LINEAR_ENERGY * self.cone_energy && above > cone {
            return Some(OffTheFamily::Cone(above));
        }
        self.broken_by(frequency).map(OffTheFamily::Below)
    }

    /// The dip (f_j − f)/f_j of a row at `frequency` (Hz) when it breaks the floor (module
    /// doc): above the tolerance and no resonance within reach; None otherwise.
    pub fn broken_by(&self, frequency: f64) -> Option<f64> {
        let dip = (self.linear - frequency) / self.linear;
        if dip.is_nan() {
            return Some(f64::INFINITY);
        }
        if dip <= self.tolerance {
            return None;
        }
        let explained = self
            .resonances
            .iter()
            .any(|&r| (self.linear - r) / self.linear * SLACK >= dip);
        (!explained).then_some(dip)
    }
}

/// The ENERGIE (½ω²a² for the mass-normalised `shape` at amplitude a) at which mode j's
/// linear motion first reaches an obstacle: a·|φ at the shock| = JEU − |origin|.
fn contact_energy(problem: &Problem, shape: &[f64], frequency: f64) -> f64 {
    let omega = 2.0 * std::f64::consts::PI * frequency;
    problem
        .shocks
        .iter()
        .map(|sh| {
            let reach = sh
                .dofs
                .iter()
                .take(sh.law.force_unknowns().len())
                .map(|&d| shape.get(d).copied().unwrap_or(0.0).powi(2))
                .sum::<f64>()
                .sqrt();
            let room = sh.room();
            if reach > 0.0 {
                0.5 * (omega * room / reach).powi(2)
            } else {
                f64::INFINITY
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// The first-order relative shift of f_j by the regularised planes' stiffness at rest,
/// ½·Σ k_reg·φ_p²/ω_j² ([`LINEAR_SAFETY`]).
fn regularisation_shift(problem: &Problem, eta: &[f64], shape: &[f64], frequency: f64) -> f64 {
    let omega2 = (2.0 * std::f64::consts::PI * frequency).powi(2);
    problem
        .shocks
        .iter()
        .zip(eta)
        .map(|(sh, &eta)| {
            let stiffness = sh
                .law
                .with(|l| l.stiffness_at_rest(sh.gap, eta))
                .unwrap_or(0.0);
            let phi = sh
                .dofs
                .first()
                .and_then(|&d| shape.get(d))
                .copied()
                .unwrap_or(0.0);
            stiffness * phi * phi
        })
        .sum::<f64>()
        / (2.0 * omega2)
}

/// Whether the structure at rest is inside the clearance of `shock` (every law then only
/// stiffens it as it moves).
fn rest_inside(shock: &crate::nnm::Shock) -> bool {
    shock.room() > 0.0 && shock.stiffness > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::ShockLaw;
    use crate::nnm::{CercleForm, Shock};
    use faer::sparse::{SparseColMat, Triplet};

    fn diagonal(values: &[f64]) -> SparseColMat<usize, f64> {
        let t: Vec<Triplet<usize, usize, f64>> = values
            .iter()
            .enumerate()
            .map(|(i, &v)| Triplet::new(i, i, v))
            .collect();
        SparseColMat::try_new_from_triplets(values.len(), values.len(), &t).unwrap()
    }

    fn problem(law: ShockLaw) -> Problem {
        Problem {
            forcing: None,
            k: diagonal(&[1.0, 9.0]),
            m: diagonal(&[1.0, 1.0]),
            shocks: vec![Shock {
                law,
                dofs: vec![0, 1],
                gap: 0.01,
                stiffness: 10.0,
                regul: 1e-5,
            }],
        }
    }

    fn modes(frequencies: &[f64]) -> Vec<LinearMode> {
        frequencies
            .iter()
            .enumerate()
            .map(|(i, &f)| LinearMode {
                number: i + 1,
                frequency: f,
                shape: vec![],
            })
            .collect()
    }

    #[test]
    fn a_dip_with_no_resonance_in_reach_breaks_the_floor() {
        // f_2/n = 2.9/n: 1.45, 0.967, 0.725 ...: the nearest below f_1 = 1 is 3.3e-2 away,
        // beyond NEAR, so the dip is the row's certified error.
        let m = modes(&[1.0, 2.9]);
        let floor = FrequencyFloor::new(&problem(ShockLaw::Plan), Some(&m), 1.0, 5, 1e-6).unwrap();
        assert_eq!(floor.broken_by(1.0 + 1e-3), None);
        assert_eq!(floor.broken_by(1.0 - 5e-7), None);
        let dip = floor.broken_by(1.0 - 2e-3).unwrap();
        assert!((dip - 2e-3).abs() < 1e-15);
        assert!(floor.broken_by(1.0 - 0.2).is_some());
    }

    #[test]
    fn a_dip_toward_a_held_subharmonic_is_explained() {
        // f_2/3 = 0.998, 2e-3 below f_1 (chain20_stiff's shape): dips from 8e-5 to past it
        // by less than SLACK are heading for it, unless NB_HARM_LINE < 3 cannot show it.
        let m = modes(&[1.0, 2.994]);
        let held = FrequencyFloor::new(&problem(ShockLaw::Plan), Some(&m), 1.0, 3, 1e-6).unwrap();
        for dip in [8e-5, 1.2e-3, 3.9e-3] {
            assert_eq!(held.broken_by(1.0 - dip), None, "{dip}");
        }
        assert!(held.broken_by(1.0 - 4.1e-3).is_some());
        let unheld = FrequencyFloor::new(&problem(ShockLaw::Plan), Some(&m), 1.0, 2, 1e-6).unwrap();
        assert!(unheld.broken_by(1.0 - 1.2e-3).is_some());
    }

    #[test]
    fn the_family_is_that_of_the_nearest_mode() {
        // Mode 2's family: mode 1 lies 66 % below, too far to explain a dip.
        let m = modes(&[1.0, 2.9]);
        let floor =
            FrequencyFloor::new(&problem(ShockLaw::BiPlan), Some(&m), 2.8, 1, 1e-6).unwrap();
        assert_eq!(floor.linear(), 2.9);
        assert_eq!(floor.broken_by(2.95), None);
        assert!(floor.broken_by(2.85).is_some());
        // A mode of the same frequency within NEAR (a degenerate pair) explains small dips.
        let m = modes(&[1.0, 2.9, 2.9 * (1.0 - 1e-3)]);
        let floor =
            FrequencyFloor::new(&problem(ShockLaw::BiPlan), Some(&m), 2.9, 1, 1e-6).unwrap();
        assert_eq!(floor.broken_by(2.9 * (1.0 - 1.5e-3)), None);
    }

    /// The modes of (K, M) = (diag(1, 9), I): f_1 and 3·f_1, shapes along DOFs 0 and 1.
    fn diagonal_modes(f1: f64) -> Vec<LinearMode> {
        vec![
            LinearMode {
                number: 1,
                frequency: f1,
                shape: vec![1.0, 0.0],
            },
            LinearMode {
                number: 2,
                frequency: 3.0 * f1,
                shape: vec![0.0, 1.0],
            },
        ]
    }

    #[test]
    fn far_below_contact_the_family_is_the_linear_mode() {
        // Mode 1 of a diagonal (K, M) = (1, 1): shape (1, 0), f_1 = 1/2π; the PLAN stop on
        // DOF 0 with JEU 0.01 is reached at ENERGIE ½·ω²·JEU² = 5e-5.
        let p = problem(ShockLaw::Plan);
        let f1 = 1.0 / (2.0 * std::f64::consts::PI);
        let m = diagonal_modes(f1);
        let floor = FrequencyFloor::new(&p, Some(&m), f1, 3, 1e-6).unwrap();
        assert!((floor.contact_energy - 5e-5).abs() < 1e-18);
        // At 1e-12 J a row 5 % above f_1 is on the trivial line; at f_1 it is the mode.
        match floor.off_the_family(1.05 * f1, 1e-12, true) {
            Some(OffTheFamily::Linear(d)) => assert!((d - 0.05).abs() < 1e-12, "{d}"),
            other => panic!("{other:?}"),
        }
        // The band: 4 × ½·k_reg·φ²/ω² with k_reg = PARA_REGUL·k_ref = 1e-5·9 (k_ref the
        // static stiffness at the shock's last DOF): 1.8e-4.
        assert!(
            (floor.linear_band - 1.8e-4).abs() < 1e-12,
            "{}",
            floor.linear_band
        );
        assert_eq!(floor.off_the_family(f1 * (1.0 + 1.7e-4), 1e-12, true), None);
        assert!(floor
            .off_the_family(f1 * (1.0 + 1.9e-4), 1e-12, true)
            .is_some());
        // In contact the same frequency is the stiffened family.
        assert_eq!(floor.off_the_family(1.05 * f1, 1e-4, true), None);
        // Below f_1 in contact: the floor.
        assert!(matches!(
            floor.off_the_family(f1 * (1.0 - 1e-3), 1e-4, true),
            Some(OffTheFamily::Below(_))
        ));
    }

    #[test]
    fn a_descent_through_a_centred_ring_stops_in_the_cone() {
        // Mode 1 of (K, M) = (1, 1) moves DOF 0 (shape (1, 0)); the ring on DOFs (0, 1),
        // centred, JEU 0.01, is reached at ENERGIE ½·ω²·JEU² = 5e-5, so "far below contact"
        // is under LINEAR_ENERGY × 5e-5 = 5e-9 J.
        let f1 = 1.0 / (2.0 * std::f64::consts::PI);
        let m = diagonal_modes(f1);
        let ring = ShockLaw::Cercle {
            origin: [0.0, 0.0],
            form: CercleForm::Radial,
        };
        let floor = FrequencyFloor::new(&problem(ring), Some(&m), f1, 3, 1e-6).unwrap();
        assert!((floor.cone_energy - 5e-5).abs() < 1e-18);
        let above = f1 * (1.0 + 2.0 * CONE_SHIFT);
        match floor.off_the_family(above, 1e-10, true) {
            Some(OffTheFamily::Cone(d)) => assert!((d - 2.0 * CONE_SHIFT).abs() < 1e-12, "{d}"),
            other => panic!("{other:?}"),
        }
        // Climbing (a start in the cone, going up into contact): not judged.
        assert_eq!(floor.off_the_family(above, 1e-10, false), None);
        // A shift of three digits or less, or an energy nearer contact: kept.
        assert_eq!(
            floor.off_the_family(f1 * (1.0 + 0.5 * CONE_SHIFT), 1e-10, true),
            None
        );
        assert_eq!(floor.off_the_family(above, 1e-8, true), None);
        // A plane has no cone: far below contact it is judged by its band (Linear).
        let plane = FrequencyFloor::new(&problem(ShockLaw::Plan), Some(&m), f1, 3, 1e-6).unwrap();
        assert_eq!(plane.cone_energy, 0.0);
        assert!(matches!(
            plane.off_the_family(above, 1e-10, true),
            Some(OffTheFamily::Linear(_))
        ));
    }

    #[test]
    fn no_floor_for_a_ring_the_structure_rests_against_a_free_structure_or_without_modes() {
        let m = modes(&[1.0, 2.9]);
        let outside = ShockLaw::Cercle {
            origin: [0.012, 0.0],
            form: CercleForm::Radial,
        };
        assert!(FrequencyFloor::new(&problem(outside), Some(&m), 1.0, 3, 1e-6).is_none());
        let inside = ShockLaw::Cercle {
            origin: [0.003, 0.004],
            form: CercleForm::Radial,
        };
        assert!(FrequencyFloor::new(&problem(inside), Some(&m), 1.0, 3, 1e-6).is_some());
        assert!(FrequencyFloor::new(&problem(ShockLaw::Plan), None, 1.0, 3, 1e-6).is_none());
        let free = modes(&[1e-9, 1.0, 2.9]);
        assert!(FrequencyFloor::new(&problem(ShockLaw::Plan), Some(&free), 1.0, 3, 1e-6).is_none());
    }
}
