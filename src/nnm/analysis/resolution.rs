//! A posteriori checks of a computed branch that the operator turns into alarms.
//!
//! The contact force of a stiff shock is a narrow pulse: its Fourier series decays slowly,
//! and when NB_HARM_NONL is too small the highest retained harmonics still carry a visible
//! part of the pulse. Code_Aster warns in that case and asks for more harmonics. We warn
//! on the same tail, but the advice comes from an estimate of which setting limits the
//! frequency (`error_sources.rs`): a stiff stop's pulse keeps a heavy tail at any
//! NB_HARM_NONL, and the frequency error may come from NB_HARM_LINE or PARA_REGUL.

use crate::nnm::analysis::error_sources;
use crate::nnm::model::unknowns::Unknowns;
use crate::nnm::{Point, Problem, Settings};

/// Amplitude of the highest tenth of the harmonics relative to the largest harmonic
/// amplitude, above which the force series counts as poorly resolved.
pub const TAIL_RATIO_ALARM: f64 = 1e-2;

/// Tail ratio above which the force series is not resolved at all: the rows then need not
/// be motions of the system, and the alarm says so. Measured on sdnd122a's wall with
/// RIGI_NOR 1e5, RESIDU 1e-13 on every row: 0.994 (NB_HARM_LINE 5), 0.428 (the same, 20
/// branches) and 0.442 (NB_HARM_NONL 1000), branches whose energy goes back and forth and
/// whose frequency falls below the linear one; 0.015 with NB_HARM_LINE 20, whose rows follow
/// the exact period to 5e-3. An alarm, not an error: Code_Aster completes such runs.
pub const UNRESOLVED_RATIO: f64 = 0.2;

/// Estimated truncation errors of the frequency (relative) above this are announced even
/// where every force series is resolved ([`accuracy_warning`]): four digits. The
/// regularisation's part is not counted: PARA_REGUL is part of the model MODE_NON_LINE
/// solves, and near first contact it always moves the frequency most (measured on
/// testcases/nnm_wall.comm: +1.7e-4 at grazing, the truncation's part 4e-6). The tail
/// alone misses the displacement's truncation: measured on generated case s2_c0017 (a
/// 5-DOF chain with a PLAN stop, NB_HARM_LINE 4, NB_HARM_NONL 924, force tail below 1 %),
/// its last row was 9.4e-4 from shooting on the same law with no alarm at all.
pub const ANNOUNCED_ERROR: f64 = 1e-4;

/// Said when the error's sources were asked for and could not be estimated.
const NOT_ESTIMATED: &str = " (the parts of the frequency error that come from NB_HARM_LINE, \
     NB_HARM_NONL and PARA_REGUL could not be estimated on these rows: the exact-law correction \
     did not converge, or the model is too large for it; on a stiff stop NB_HARM_LINE often \
     limits the frequency more than NB_HARM_NONL)";

/// At most this many points of a branch are examined (evenly spread, the last included).
const SAMPLED_POINTS: usize = 20;

/// Largest |c_k| over the last tenth of harmonics divided by the largest |c_k|, k ≥ 1, of
/// a series stored as 0, C1..CH, S1..SH.
pub fn tail_ratio(coefs: &[f64]) -> f64 {
    let h = coefs.len().saturating_sub(1) / 2;
    if h == 0 {
        return 0.0;
    }
    let amp = |k: usize| coefs[k].hypot(coefs[h + k]);
    let peak = (1..=h).map(amp).fold(0.0, f64::max);
    if peak == 0.0 {
        return 0.0;
    }
    let first_tail = h - (h / 10).max(1) + 1;
    (first_tail..=h).map(amp).fold(0.0, f64::max) / peak
}

/// The tail ratio of a force with several components (a ring's f_x, f_y): the largest
/// tail amplitude of any component over the largest harmonic of any. A component that
/// barely moves (round-off around a planar motion, 1e-55 of the other) has a spectrum of
/// noise whose own tail ratio is O(1); measured against the whole force it is nothing.
pub fn tail_ratio_of(components: &[&[f64]]) -> f64 {
    let amp = |c: &[f64], k: usize| {
        let h = c.len().saturating_sub(1) / 2;
        c[k].hypot(c[h + k])
    };
    let mut peak = 0.0f64;
    let mut tail = 0.0f64;
    for c in components {
        let h = c.len().saturating_sub(1) / 2;
        if h == 0 {
            continue;
        }
        let first_tail = h - (h / 10).max(1) + 1;
        peak = (1..=h).fold(peak, |m, k| m.max(amp(c, k)));
        tail = (first_tail..=h).fold(tail, |m, k| m.max(amp(c, k)));
    }
    if peak == 0.0 {
        0.0
    } else {
        tail / peak
    }
}

/// One message per shock whose force series is poorly resolved somewhere on `points`
/// (numbered from `first_order`). With `advise`, the message ends with the estimated parts
/// of the frequency error and the setting whose refinement lowers it most
/// (`error_sources.rs`): the tail says that the force is a narrow pulse, not which setting
/// limits the frequency. Without it (the alarm is ignored, or no estimate could be made) the
/// advice is the tail's own.
pub fn resolution_warnings(
    problem: &Problem,
    settings: &Settings,
    points: &[Point],
    first_order: i64,
    advise: bool,
) -> Vec<String> {
    let mut worst: Vec<(f64, f64)> = vec![(0.0, 0.0); problem.shocks.len()];
    if points.is_empty() || problem.shocks.is_empty() {
        return Vec::new();
    }
    let Ok(stored) = Unknowns::new(problem, settings) else {
        return Vec::new();
    };
    let stride = points.len().div_ceil(SAMPLED_POINTS).max(1);
    let picked = points
        .iter()
        .enumerate()
        .filter(|(i, _)| i % stride == 0 || *i + 1 == points.len());
    for (_, p) in picked {
        let Ok(per_shock) = stored.contact(&p.x) else {
            continue;
        };
        for ((s, unknowns), shock) in per_shock.iter().enumerate().zip(&problem.shocks) {
            // A law without an obstacle (a cubic spring) has no contact pulse: its force is
            // a polynomial of the displacement, exact on the structure's harmonics once
            // NB_HARM_NONL ≥ 2·NB_HARM_LINE (law/ressort_cubique.rs). Not judged.
            if !shock.law.has_obstacle() {
                continue;
            }
            // The force unknowns come first: PLAN, BI_PLAN f; CERCLE fx, fy.
            let n_force = shock.law.force_unknowns().len();
            let components: Vec<&[f64]> = unknowns
                .iter()
                .take(n_force)
                .map(|f| f.as_slice())
                .collect();
            if let Some(w) = worst.get_mut(s) {
                let r = tail_ratio_of(&components);
                if r > w.0 {
                    *w = (r, p.energy);
                }
            }
        }
    }
    let alarmed = worst.iter().any(|(r, _)| *r > TAIL_RATIO_ALARM);
    let sources = if alarmed && advise {
        error_sources::worst_row(problem, settings, points)
    } else {
        None
    };
    worst
        .iter()
        .enumerate()
        .filter(|(_, (r, _))| *r > TAIL_RATIO_ALARM)
        .map(|(s, (r, e))| {
            let unresolved = "; the force series is not resolved at all there, and rows with a \
                 converged RESIDU need not be motions of the system (energies that go back and \
                 forth, frequencies below the linear one, spurious bifurcations)";
            let advice = match (&sources, *r > UNRESOLVED_RATIO) {
                (Some(src), true) => format!("{unresolved}; {}", src.text(&settings.harmonics, first_order)),
                (Some(src), false) => format!("; {}", src.text(&settings.harmonics, first_order)),
                (None, true) => format!(
                    "{unresolved}: raise NB_HARM_NONL and, for a stiff stop, NB_HARM_LINE (the \
                     displacement must follow the short contact), or lower RIGI_NOR or raise \
                     PARA_REGUL{}",
                    if advise { NOT_ESTIMATED } else { "" }
                ),
                (None, false) => format!(
                    "; raise NB_HARM_NONL{}",
                    if advise { NOT_ESTIMATED } else { "" }
                ),
            };
            format!(
                "the contact force of shock {} is poorly resolved by NB_HARM_NONL={}: its last harmonics \
                 still carry {:.1}% of its largest harmonic (at ENERGIE={:.4e}){advice}",
                s + 1,
                settings.harmonics.h_nonl,
                100.0 * r,
                e
            )
        })
        .collect()
}

/// The accuracy alarm of a branch whose force series are all resolved (no message of
/// [`resolution_warnings`]) but whose estimated truncation error of the frequency at some
/// examined row is above [`ANNOUNCED_ERROR`] (error_sources.rs: mostly the displacements'
/// truncation, NB_HARM_LINE); None otherwise, or when no estimate could be made.
pub fn accuracy_warning(
    problem: &Problem,
    settings: &Settings,
    points: &[Point],
    first_order: i64,
) -> Option<String> {
    let worst = error_sources::worst_row_by(
        problem,
        settings,
        points,
        error_sources::Sources::truncation,
    )?;
    (worst.truncation().abs() > ANNOUNCED_ERROR).then(|| {
        format!(
            "the contact forces are resolved by NB_HARM_NONL={}, yet the frequency is not to \
             four digits: {}",
            settings.harmonics.h_nonl,
            worst.text(&settings.harmonics, first_order)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ring_force_is_judged_as_a_whole_not_by_a_component_of_round_off() {
        // f_y: a resolved series (geometric decay); f_x: round-off noise 1e-55 with a flat
        // spectrum, whose own tail ratio is 1. The ring's force is resolved.
        let h = 20;
        let mut fy = vec![0.0; 2 * h + 1];
        for (k, c) in fy.iter_mut().enumerate().take(h + 1).skip(1) {
            *c = 0.5f64.powi(k as i32);
        }
        let fx: Vec<f64> = (0..=2 * h)
            .map(|i| 1e-55 * (1.0 + (i % 3) as f64))
            .collect();
        assert!(tail_ratio(&fx) > 0.3);
        assert!(tail_ratio_of(&[&fx, &fy]) < 1e-5);
        // A component that does carry the force still counts: its tail against the peak.
        assert!((tail_ratio_of(&[&fy, &fy]) - tail_ratio(&fy)).abs() < 1e-15);
        let flat: Vec<f64> = (0..=2 * h)
            .map(|i| if i <= h { 1.0 } else { 0.0 })
            .collect();
        assert!((tail_ratio_of(&[&fy, &flat]) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn tail_ratio_of_a_resolved_and_of_a_truncated_series() {
        // Geometric decay 0.5^k: the last tenth of 20 harmonics is tiny.
        let h = 20;
        let mut c = vec![0.0; 2 * h + 1];
        for (k, ck) in c.iter_mut().enumerate().take(h + 1).skip(1) {
            *ck = 0.5f64.powi(k as i32);
        }
        assert!(tail_ratio(&c) < 1e-5);
        // A flat spectrum (a Dirac comb truncated): the tail is as large as the peak.
        let flat: Vec<f64> = (0..=2 * h)
            .map(|i| if i <= h { 1.0 } else { 0.0 })
            .collect();
        assert!((tail_ratio(&flat) - 1.0).abs() < 1e-12);
        assert_eq!(tail_ratio(&[3.0]), 0.0);
    }
}
