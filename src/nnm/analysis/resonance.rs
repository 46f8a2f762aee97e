//! Internal resonances along a branch: where n times the branch frequency crosses the
//! frequency f_j of a linear mode j that the contact forces can drive (MODE_NON_LINE's alarm
//! MODE_NON_LINE_7, docs/mode_non_line.md "Internal resonances").
//!
//! Near n·f = f_j harmonic n of the contact force drives mode j at its own frequency: the
//! family of the starting mode meets the family that carries mode j at harmonic n, and the
//! continuation may go on along either. The harmonic balance holds harmonic n only when
//! NB_HARM_LINE ≥ n; with fewer it does not see the resonance and runs through it on its
//! own truncated family, so two settings may follow different, equally real families.
//!
//! The rule (chosen so that it neither floods nor misses):
//! - the linear modes are the generalized eigenpairs of the stored K and M, computed densely
//!   (up to `MAX_DENSE_DOFS` DOFs of model/linear_modes.rs; beyond, no check);
//! - a pair (j, n) is met between two consecutive rows when n·f − f_j changes sign between
//!   them (the row past the change is named), or at a row where |n·f − f_j| ≤ [`BAND`]·f_j
//!   (a branch that locks onto the resonance without crossing it); n = 1 with the mode the
//!   branch starts from (the mode nearest the first row's frequency) is the branch itself;
//! - it is reported only if the contact can drive mode j at harmonic n there: n ≤
//!   NB_HARM_NONL (the force is known to that harmonic) and the strength
//!   s = c_j·|F_n|/(k_ref·A) ≥ [`STRENGTH_MIN`] at the row, or, for a crossing, at the row
//!   before or after it (|F_n| swings with the contact angle), with c_j² the largest kinetic
//!   weight φ_i²·M_ii of the mode at the shock DOFs over its largest one anywhere (weights,
//!   not components, so that a beam's rotations in rad do not outweigh its displacements in
//!   m; 0 for a mode the shocks cannot touch, e.g. bending in the other plane), |F_n| the amplitude of harmonic n of the contact
//!   force projected on mode j's shock components (normalised by c_j's norm), k_ref =
//!   1/(K⁻¹)ₚₚ at the shock DOF and A the first-harmonic amplitude there. A harmonic the
//!   force does not carry (the even ones of a symmetric BI_PLAN orbit) is not reported, nor a
//!   row whose force is still at its regularisation level (before contact: first-harmonic
//!   force below [`CONTACT_MARGIN`]·PARA_REGUL·k_ref·A);
//! - one alarm per run lists the pairs met, strongest first, at most [`LISTED`] of them;
//! - a pair met within [`BRANCH_POINT_ROWS`] rows of a row flagged BIFURCATION='OUI' is a
//!   branch point between the two families and is said so.

use crate::nnm::error::Result;
use crate::nnm::model::linear_modes::LinearMode;
use crate::nnm::{contact_coefficients, displacement_coefficients, Harmonics, Point, Problem};
use std::ops::Div;

/// Relative distance |n·f − f_j|/f_j under which a row counts as on the resonance.
pub const BAND: f64 = 1e-3;
/// Smallest strength c_j·|F_n|/(k_ref·A) reported (module doc). Measured: a harmonic the
/// force does not carry (the even ones of a symmetric BI_PLAN orbit) stays below 2e-9; the
/// 17:1 of the cantilever of testcases/hard, over eight sets of RIGI_NOR, PARA_REGUL and JEU,
/// from 9.9e-4 to 2e-2 (the larger of the two rows around the crossing).
pub const STRENGTH_MIN: f64 = 1e-4;
/// A row is in contact when the first harmonic of a shock's force exceeds this many times
/// PARA_REGUL·k_ref·A, the level of the regularised force before contact (measured on the
/// cantilever of testcases/hard: 2.9·PARA_REGUL at its first row, at the linear amplitude).
pub const CONTACT_MARGIN: f64 = 10.0;
/// Pairs listed in the alarm (the others are counted).
pub const LISTED: usize = 8;
/// Rows either side of a met pair searched for a BIFURCATION flag.
pub const BRANCH_POINT_ROWS: usize = 2;

/// An n:1 internal resonance met along the rows.
#[derive(Clone, Debug, PartialEq)]
pub struct Resonance {
    pub mode: usize,
    pub mode_frequency: f64,
    pub order: usize,
    /// Index (0-based) of the row where it is met.
    pub row: usize,
    pub energy: f64,
    pub frequency: f64,
    /// NB_HARM_LINE ≥ n: the harmonic balance can represent the resonance.
    pub represented: bool,
    pub strength: f64,
    /// Index of a row flagged BIFURCATION within [`BRANCH_POINT_ROWS`] rows.
    pub branch_point: Option<usize>,
}

/// The force components of each shock and the DOFs they act on: (shock, unknown, DOF).
fn force_components(problem: &Problem) -> Vec<(usize, usize, usize)> {
    problem
        .shocks
        .iter()
        .enumerate()
        .flat_map(|(s, sh)| {
            let comps = sh.law.n_comp();
            (0..comps.min(sh.dofs.len())).map(move |c| (s, c, sh.dofs[c]))
        })
        .collect()
}

/// The n:1 resonances met along `points` (module doc), in row order.
pub fn internal_resonances(
    problem: &Problem,
    harmonics: &Harmonics,
    points: &[Point],
    modes: &[LinearMode],
) -> Result<Vec<Resonance>> {
    let comps = force_components(problem);
    if points.is_empty() || comps.is_empty() || modes.is_empty() {
        return Ok(Vec::new());
    }
    let f0 = points[0].frequency;
    let own = modes
        .iter()
        .min_by(|a, b| {
            (a.frequency - f0)
                .abs()
                .total_cmp(&(b.frequency - f0).abs())
        })
        .map(|m| m.number);
    // k_ref = 1/(K⁻¹)ₚₚ = 1/Σ_j φ_j[p]²/ω_j² at each shock DOF (mass-normalised modes).
    let k_ref: Vec<f64> = comps
        .iter()
        .map(|&(_, _, d)| {
            let flex: f64 = modes
                .iter()
                .filter(|m| m.frequency > 0.0)
                .map(|m| (m.shape[d] / (2.0 * std::f64::consts::PI * m.frequency)).powi(2))
                .sum();
            1.0 / flex
        })
        .collect();
    let mass_diag: Vec<f64> = (0..problem.m.nrows())
        .map(|i| problem.m.get(i, i).copied().unwrap_or(0.0))
        .collect();
    let h_nl = harmonics.h_nonl;
    let mut met: Vec<Resonance> = Vec::new();
    for m in modes {
        // Kinetic weights φ_i²·M_ii: dimensionally consistent across translations and
        // rotations (a beam's rotation DOFs are in rad, its displacements in m).
        let weight = |i: usize| m.shape[i] * m.shape[i] * mass_diag[i];
        let largest = (0..m.shape.len()).fold(0.0f64, |a, i| a.max(weight(i)));
        let at_shocks: Vec<f64> = comps.iter().map(|&(_, _, d)| m.shape[d]).collect();
        let coupling = comps
            .iter()
            .fold(0.0f64, |a, &(_, _, d)| a.max(weight(d)))
            .div(largest)
            .sqrt();
        if coupling.is_nan() || coupling <= 1e-8 || m.frequency <= 0.0 {
            continue;
        }
        let fj = m.frequency;
        let mut seen: Vec<usize> = Vec::new();
        for i in 0..points.len() {
            let fi = points[i].frequency;
            let prev = if i > 0 { points[i - 1].frequency } else { fi };
            if fi.is_nan() || prev.is_nan() || fi <= 0.0 || prev <= 0.0 {
                continue;
            }
            let (lo, hi) = (fi.min(prev), fi.max(prev));
            // Orders whose n·f − f_j changes sign over [lo, hi], or sits in the band at fi.
            let n_lo = ((fj / hi).ceil() as usize).max(1);
            let n_hi = (fj / lo).floor() as usize;
            let near = (fj / fi).round() as usize;
            let mut orders: Vec<usize> = if i > 0 && n_lo <= n_hi {
                (n_lo..=n_hi.min(h_nl)).collect()
            } else {
                Vec::new()
            };
            if near >= 1 && (near as f64 * fi - fj).abs() <= BAND * fj && !orders.contains(&near) {
                orders.push(near);
            }
            for n in orders {
                if n > h_nl || seen.contains(&n) || (n == 1 && Some(m.number) == own) {
                    continue;
                }
                // The force's harmonic n swings with the contact angle from row to row
                // (measured on the cantilever of testcases/hard: 1.5e-4 to 2.7e-3 along one
                // branch): a crossing takes the larger drive of the two rows around it.
                let crossed = i > 0 && (n as f64 * prev - fj) * (n as f64 * fi - fj) <= 0.0;
                let mut strength = drive(
                    problem, harmonics, &points[i], &comps, &at_shocks, coupling, &k_ref, n,
                )?;
                if crossed {
                    strength = strength.max(drive(
                        problem,
                        harmonics,
                        &points[i - 1],
                        &comps,
                        &at_shocks,
                        coupling,
                        &k_ref,
                        n,
                    )?);
                }
                if strength < STRENGTH_MIN {
                    continue;
                }
                seen.push(n);
                let window = i.saturating_sub(BRANCH_POINT_ROWS)
                    ..=(i + BRANCH_POINT_ROWS).min(points.len() - 1);
                met.push(Resonance {
                    mode: m.number,
                    mode_frequency: fj,
                    order: n,
                    row: i,
                    energy: points[i].energy,
                    frequency: fi,
                    represented: harmonics.h_lin >= n,
                    strength,
                    branch_point: window.into_iter().find(|&r| points[r].bifurcation),
                });
            }
        }
    }
    met.sort_by(|a, b| a.row.cmp(&b.row).then(a.mode.cmp(&b.mode)));
    Ok(met)
}

/// c_j·|F_n|/(k_ref·A) at one row (module doc), `coupling` = c_j; 0 at a row not in contact.
#[allow(clippy::too_many_arguments)]
fn drive(
    problem: &Problem,
    harmonics: &Harmonics,
    p: &Point,
    comps: &[(usize, usize, usize)],
    at_shocks: &[f64],
    coupling: f64,
    k_ref: &[f64],
    n: usize,
) -> Result<f64> {
    let force = contact_coefficients(problem, harmonics, &p.x)?;
    let disp = displacement_coefficients(problem, harmonics, &p.x)?;
    let (h_nl, h_l) = (harmonics.h_nonl, harmonics.h_lin);
    let norm = at_shocks.iter().map(|v| v * v).sum::<f64>().sqrt();
    let (mut c, mut s) = (0.0, 0.0);
    let mut scale = 0.0f64;
    let mut contact = false;
    for (k, &(sh, un, d)) in comps.iter().enumerate() {
        let f = &force[sh][un];
        let w = at_shocks[k] / norm;
        c += w * f[n];
        s += w * f[h_nl + n];
        let u = &disp[d];
        let restoring = k_ref[k] * u[1].hypot(u[h_l + 1]);
        scale = scale.max(restoring);
        contact |= f[1].hypot(f[h_nl + 1]) > CONTACT_MARGIN * problem.shocks[sh].regul * restoring;
    }
    Ok(if scale > 0.0 && contact {
        coupling * c.hypot(s) / scale
    } else {
        0.0
    })
}

/// The alarm text for the resonances met along `points` (rows numbered from `first_order`),
/// or None when there is none or `modes` is None ([`linear_modes`]: the model is too large
/// for the dense check).
pub fn resonance_alarm(
    problem: &Problem,
    harmonics: &Harmonics,
    points: &[Point],
    first_order: i64,
    modes: Option<&[LinearMode]>,
) -> Result<Option<String>> {
    let Some(modes) = modes else {
        return Ok(None);
    };
    let mut met = internal_resonances(problem, harmonics, points, modes)?;
    if met.is_empty() {
        return Ok(None);
    }
    let total = met.len();
    met.sort_by(|a, b| b.strength.total_cmp(&a.strength));
    met.truncate(LISTED);
    met.sort_by(|a, b| a.row.cmp(&b.row).then(a.mode.cmp(&b.mode)));
    let h = harmonics.h_lin;
    let lines: Vec<String> = met
        .iter()
        .map(|r| {
            let order = first_order + r.row as i64;
            let held = if r.represented {
                format!("NB_HARM_LINE={h} >= {} holds it", r.order)
            } else {
                format!(
                    "NB_HARM_LINE={h} < {n} cannot represent it: the branch runs through it on \
                     its truncated family; NB_HARM_LINE={n} or more would hold it",
                    n = r.order
                )
            };
            let bp = match r.branch_point {
                Some(b) => format!(
                    "; row {} is flagged BIFURCATION: a branch point between the family of the \
                     starting mode and the family that carries mode {} at harmonic {}, the rows \
                     after it may follow either",
                    first_order + b as i64,
                    r.mode,
                    r.order
                ),
                None => String::new(),
            };
            format!(
                "  {}:1 with linear mode {} ({:.6e} Hz) at NUME_ORDRE {order} (FREQUENCE \
                 {:.6e} Hz, ENERGIE {:.6e} J, strength {:.1e}): {held}{bp}",
                r.order, r.mode, r.mode_frequency, r.frequency, r.energy, r.strength
            )
        })
        .collect();
    let more = if total > met.len() {
        format!("\n  ... and {} weaker one(s)", total - met.len())
    } else {
        String::new()
    };
    Ok(Some(format!(
        "the branch meets {total} internal resonance(s) n:1 (n x FREQUENCE crosses the frequency \
         of a linear mode the shocks drive, with harmonic n of the contact force):\n{}{more}\n\
         Near such a point two families of periodic orbits meet; where NB_HARM_LINE < n the \
         computed branch ignores the resonance, and a larger NB_HARM_LINE may follow the other \
         family (check the rows past it with a larger NB_HARM_LINE, or by REST_MODE_NONL and a \
         time integration)",
        lines.join("\n")
    )))
}
