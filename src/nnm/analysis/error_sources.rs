//! Which setting limits the frequency of a computed row: its relative frequency error split
//! into the parts that come from the truncation of the displacements (NB_HARM_LINE), of the
//! contact unknowns (NB_HARM_NONL) and from the regularisation (PARA_REGUL), and the setting
//! whose refinement is predicted to lower the error most (alarm MODE_NON_LINE_1's advice).
//!
//! Why not the tail of the force series alone: a stiff stop's force is a narrow pulse whose
//! series keeps large high harmonics at any NB_HARM_NONL, while the frequency error may come
//! from the displacement (issue 34: a one-DOF wall, RIGI_NOR/k 1e7, PARA_REGUL 1e-8,
//! NB_HARM_LINE 20, NB_HARM_NONL 1000, 0.55–0.82 % low, halving when NB_HARM_LINE doubles).
//!
//! The estimates are small dense Newton solves of the harmonic balance at the row's ENERGIE
//! (`exact_law.rs`, alternating frequency–time: the force's harmonics are those of the law
//! evaluated in time, so no NB_HARM_NONL enters them), started from the row:
//! - ω_reg: NB_HARM_LINE harmonics, the regularised law (PARA_REGUL) in time. The row and
//!   this orbit differ only by the truncation of the contact unknowns, so
//!   e_nl = (ω_row − ω_reg)/ω_row. Its sign is that of the truncation's effect.
//! - ω_H: the same harmonics, the exact penalty law: e_reg = (ω_reg − ω_H)/ω_row, the
//!   regularisation's part (the regularised law is stiffer, e_reg > 0).
//! - ω_2H: the exact law with the displacement's harmonics doubled (padded with zeros, then
//!   corrected). The change d1 = (ω_H − ω_2H)/ω_row is what doubling NB_HARM_LINE does to
//!   the row, measured, not predicted. What remains after it, R = (ω_2H − ω_∞)/ω_row, is
//!   not known; for any order of convergence p ≥ 1 (a motion with impacts has velocity
//!   jumps, its harmonics decay like 1/k², p = 1 is the slowest) it lies between 0 and d1,
//!   so the displacement's part d1 + R lies between d1 and 2·d1. (An order estimated from a
//!   third solve at 4·NB_HARM_LINE was tried: near first contact the differences are not
//!   monotone, Aitken's extrapolation then misleads, and the interval needs no third solve.)
//!
//! The parts are signed and may cancel, so refining the largest one can make the row worse.
//! The advice names the setting whose refinement is predicted to lower |error| most for
//! every admissible remainder: doubling NB_HARM_LINE removes d1 (measured); doubling
//! NB_HARM_NONL leaves between 0 and half of e_nl (at least first order); halving PARA_REGUL
//! removes half of e_reg (its effect is linear in it, docs/accuracy.md). A setting is named
//! only when, for every remainder, the predicted |error| after its refinement is at most
//! [`WORTH`] of the |error| before; none is named where the error is below [`NEGLIGIBLE`]
//! for every remainder.

use crate::nnm::analysis::exact_law::{
    self, correct_on_law, ExactLawSettings, HeldEnergy, Variant,
};
use crate::nnm::error::{Error, Result};
use crate::nnm::model::fourier;
use crate::nnm::model::point::Point;
use crate::nnm::model::problem::Harmonics;
use crate::nnm::{Problem, Settings};

/// Below this estimated relative frequency error no setting is named: five digits, what the
/// accuracy study's users ask (docs/accuracy.md).
pub const NEGLIGIBLE: f64 = 1e-5;

/// A refinement is advised only when it is predicted to leave at most this fraction of the
/// |error|, whatever the unknown remainders.
pub const WORTH: f64 = 0.9;

/// Samples of each unknown remainder's interval in the worst-case prediction.
const SAMPLES: usize = 11;

/// Rows examined per run: evenly spread, the last (highest energy) included; [`FEW_ROWS`]
/// when the doubled correction's dense system exceeds [`SMALL_DENSE`] unknowns.
pub const ROWS: usize = 20;
pub const FEW_ROWS: usize = 4;
pub const SMALL_DENSE: usize = 400;
/// No estimate beyond this many unknowns in the doubled correction: its dense LU
/// (n·(4·NB_HARM_LINE + 1) + 2 unknowns) would cost seconds per row; the alarm then keeps
/// the tail's own advice.
pub const MAX_DENSE: usize = 800;

/// A setting the error comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    HarmLine,
    HarmNonl,
    Regul,
}

impl Source {
    /// The keyword a user changes.
    pub fn keyword(self) -> &'static str {
        match self {
            Source::HarmLine => "NB_HARM_LINE",
            Source::HarmNonl => "NB_HARM_NONL",
            Source::Regul => "PARA_REGUL",
        }
    }
}

/// Estimated signed relative frequency errors (ω_row − ω_exact)/ω_row of one row, per source.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sources {
    /// Index of the row among the points examined.
    pub row: usize,
    /// The row's ENERGIE (J).
    pub energy: f64,
    /// Measured change when NB_HARM_LINE doubles, d1 = (ω_H − ω_2H)/ω_row; the
    /// displacement's part lies between d1 and 2·d1.
    pub line_doubling: f64,
    /// The contact unknowns' part, (ω_row − ω_reg)/ω_row.
    pub harm_nonl: f64,
    /// The regularisation's part, (ω_reg − ω_H)/ω_row.
    pub regul: f64,
}

/// (before, after) of refining one setting, for one value of each unknown remainder.
type Prediction = (f64, f64);

impl Sources {
    /// The displacement's part, between d1 and 2·d1 (its two ends).
    pub fn harm_line(&self) -> (f64, f64) {
        (self.line_doubling, 2.0 * self.line_doubling)
    }

    /// The total error at the middle of the remainder's interval (what the message prints).
    pub fn total(&self) -> f64 {
        1.5 * self.line_doubling + self.harm_nonl + self.regul
    }

    /// The truncation's part of [`Sources::total`]: the displacements' and the contact
    /// unknowns', without the regularisation's. What the harmonic balance loses against the
    /// regularised law, which is the law MODE_NON_LINE solves (PARA_REGUL is part of the
    /// model, as in Code_Aster).
    pub fn truncation(&self) -> f64 {
        1.5 * self.line_doubling + self.harm_nonl
    }

    /// (error before, error after refining `s`) over the unknown remainders: R of the
    /// displacement in [0, d1], and for NB_HARM_NONL the part left after doubling in
    /// [0, e_nl/2].
    fn predictions(&self, s: Source) -> Vec<Prediction> {
        let grid = |v: f64| (0..SAMPLES).map(move |i| v * i as f64 / (SAMPLES - 1) as f64);
        let d1 = self.line_doubling;
        let mut out = Vec::new();
        for r in grid(d1) {
            let before = d1 + r + self.harm_nonl + self.regul;
            match s {
                Source::HarmLine => out.push((before, before - d1)),
                Source::HarmNonl => {
                    for left in grid(0.5 * self.harm_nonl) {
                        out.push((before, before - self.harm_nonl + left));
                    }
                }
                Source::Regul => out.push((before, before - 0.5 * self.regul)),
            }
        }
        out
    }

    /// The largest |error after| / |error before| refining `s`, over the remainders.
    pub fn worst_ratio(&self, s: Source) -> f64 {
        self.predictions(s)
            .into_iter()
            .map(|(b, a)| a.abs() / b.abs())
            .fold(
                0.0,
                |m: f64, r| if r.is_nan() { f64::INFINITY } else { m.max(r) },
            )
    }

    /// The error below [`NEGLIGIBLE`] whatever the remainder.
    pub fn negligible(&self) -> bool {
        self.predictions(Source::Regul)
            .iter()
            .all(|(b, _)| b.abs() <= NEGLIGIBLE)
    }

    /// The setting to refine: the one with the smallest worst ratio, when that is at most
    /// [`WORTH`]; None when the error is negligible or no single refinement is predicted
    /// to help for every remainder (the parts cancel).
    pub fn advised(&self) -> Option<Source> {
        if self.negligible() {
            return None;
        }
        [Source::HarmLine, Source::HarmNonl, Source::Regul]
            .into_iter()
            .map(|s| (s, self.worst_ratio(s)))
            .filter(|(_, w)| *w <= WORTH)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(s, _)| s)
    }

    /// The largest part (the dominant source), whatever its sign (the displacement's at the
    /// middle of its interval).
    pub fn dominant(&self) -> Source {
        [
            (Source::HarmLine, 1.5 * self.line_doubling),
            (Source::HarmNonl, self.harm_nonl),
            (Source::Regul, self.regul),
        ]
        .into_iter()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map_or(Source::HarmLine, |(s, _)| s)
    }

    /// The advice after the alarm's facts: the estimated parts at the row (numbered from
    /// `first_order`) and what to change.
    pub fn text(&self, harmonics: &Harmonics, first_order: i64) -> String {
        let h = harmonics.h_lin;
        let (l0, l1) = self.harm_line();
        let head = format!(
            "estimated relative frequency error at NUME_ORDRE {} (ENERGIE={:.4e}) {:+.1e}: \
             {:+.1e} to {:+.1e} from the truncation of the displacements (NB_HARM_LINE={h}), \
             {:+.1e} from that of the contact unknowns (NB_HARM_NONL={}), {:+.1e} from the \
             regularisation (PARA_REGUL)",
            first_order + self.row as i64,
            self.energy,
            self.total(),
            l0,
            l1,
            self.harm_nonl,
            harmonics.h_nonl,
            self.regul
        );
        match self.advised() {
            Some(s) => {
                let what = match s {
                    Source::HarmLine => format!(
                        "raise NB_HARM_LINE (doubled: {}{})",
                        2 * h,
                        if harmonics.h_nonl < 2 * h {
                            format!(", with NB_HARM_NONL at least {}", 2 * h)
                        } else {
                            String::new()
                        }
                    ),
                    Source::HarmNonl => {
                        format!("raise NB_HARM_NONL (doubled: {})", 2 * harmonics.h_nonl)
                    }
                    Source::Regul => "lower PARA_REGUL (halved)".to_string(),
                };
                format!(
                    "{head}; the largest part is {}'s, and refining {} is predicted to lower the \
                     error to at most {:.0}% of itself: {what}",
                    self.dominant().keyword(),
                    s.keyword(),
                    100.0 * self.worst_ratio(s)
                )
            }
            None if self.negligible() => format!(
                "{head}; below {NEGLIGIBLE:.0e} in all: these harmonics do not limit the \
                 frequency there, whatever the force series' tail"
            ),
            None => format!(
                "{head}; the largest part is {}'s, but the parts cancel and no single setting \
                 refined is predicted to lower the error: refine NB_HARM_LINE, NB_HARM_NONL and \
                 PARA_REGUL together",
                self.dominant().keyword()
            ),
        }
    }
}

/// The exact-law correction's settings for `h` harmonics.
fn law_settings(h: usize, settings: &Settings) -> ExactLawSettings {
    ExactLawSettings {
        h_lin: h,
        samples: 0,
        prec: settings.continuation.prec_newton.min(1e-9),
        iter_max: 60,
        held: HeldEnergy::Instant,
    }
}

/// `u` (n series of `from` harmonics, layout 0, C1..CH, S1..SH) with `to` ≥ `from`
/// harmonics, the new ones zero.
fn padded(u: &[f64], n: usize, from: usize, to: usize) -> Vec<f64> {
    let (lf, lt) = (fourier::len(from), fourier::len(to));
    let mut out = vec![0.0; n * lt];
    for i in 0..n {
        let (a, b) = (&u[i * lf..(i + 1) * lf], &mut out[i * lt..(i + 1) * lt]);
        b[0] = a[0];
        for k in 1..=from {
            b[fourier::ic(k)] = a[fourier::ic(k)];
            b[fourier::is(to, k)] = a[fourier::is(from, k)];
        }
    }
    out
}

/// The parts of the error of `point`, the row `row` of `problem` computed with `settings`.
pub fn estimate(
    problem: &Problem,
    settings: &Settings,
    point: &Point,
    row: usize,
) -> Result<Sources> {
    let n = problem.k.nrows();
    let h = settings.harmonics.h_lin;
    let nu = n * fourier::len(h);
    if point.x.len() < nu {
        return Err(Error::internal(
            "error sources: the row is shorter than its displacements",
        ));
    }
    exact_law::check_size(n, 2 * h)?;
    let (w, e) = (point.omega, point.energy);
    let solve = |hh: usize, u: &[f64], w0: f64, regularised: bool| {
        let variant = Variant {
            regularised,
            damped: true,
        };
        correct_on_law(problem, &law_settings(hh, settings), u, w0, e, variant)
    };
    let stage =
        |what: &'static str| move |e: Error| Error::numerical(format!("{what}: {}", e.message));
    let ex = solve(h, &point.x[..nu], w, false).map_err(stage("exact law"))?;
    let reg = solve(h, &point.x[..nu], w, true)
        .or_else(|_| solve(h, &ex.u, ex.omega, true))
        .map_err(stage("regularised law"))?;
    let ex2 = solve(2 * h, &padded(&ex.u, n, h, 2 * h), ex.omega, false)
        .map_err(stage("exact law, harmonics doubled"))?;
    Ok(Sources {
        row,
        energy: e,
        line_doubling: (ex.omega - ex2.omega) / w,
        harm_nonl: (w - reg.omega) / w,
        regul: (reg.omega - ex.omega) / w,
    })
}

/// The parts at up to [`ROWS`] rows of `points` (evenly spread, the last included); the row
/// of largest estimated |error| (at the middle of its interval) is returned. None without
/// shocks, without rows, or when no estimate could be made (a dense system above
/// [`MAX_DENSE`], a correction that failed at every row, or at some rows while the others
/// are negligible).
pub fn worst_row(problem: &Problem, settings: &Settings, points: &[Point]) -> Option<Sources> {
    worst_row_by(problem, settings, points, Sources::total)
}

/// As [`worst_row`], the row of largest |`part`| (e.g. [`Sources::truncation`]).
pub fn worst_row_by(
    problem: &Problem,
    settings: &Settings,
    points: &[Point],
    part: fn(&Sources) -> f64,
) -> Option<Sources> {
    if problem.shocks.is_empty() || points.is_empty() {
        return None;
    }
    let last = points.len() - 1;
    let dense = exact_law::dense_size(problem.k.nrows(), 2 * settings.harmonics.h_lin);
    if dense > MAX_DENSE {
        return None;
    }
    let small = dense <= SMALL_DENSE;
    let count = if small { ROWS } else { FEW_ROWS };
    let mut rows: Vec<usize> = (1..=count).map(|i| i * last / count).collect();
    rows.dedup();
    let all: Vec<Result<Sources>> = rows
        .into_iter()
        .map(|i| estimate(problem, settings, &points[i], i))
        .collect();
    let failed = all.iter().any(|r| r.is_err());
    let worst = all
        .into_iter()
        .filter_map(|r| r.ok())
        .max_by(|a, b| part(a).abs().total_cmp(&part(b).abs()))?;
    // "Negligible" is not said from the rows that could be estimated when others could not.
    (!(failed && worst.negligible())).then_some(worst)
}

#[cfg(test)]
#[path = "error_sources_tests.rs"]
mod tests;
