//! One measurement: a timed branch over the case's energy range and its frequency error.

use super::cases::{Config, StudyCase};
use crate::error::{Error, Result};
use crate::nnm::exact::Oscillator;
use crate::nnm::exact_law::{self, ExactLawSettings, HeldEnergy};
use crate::nnm::{
    continue_while, start_from_mode, Continuation, Harmonics, Point, Problem, Settings,
};
use std::time::Instant;

/// NB_ORDRE_MAN (Code_Aster's default).
pub const ORDER: usize = 20;
/// NB_PAS_MAN of the measured runs: dense enough that every part of the range is checked.
pub const POINTS_PER_BRANCH: usize = 5;
/// PREC_NEWTON of the branch ends.
pub const PREC_NEWTON: f64 = 1e-9;
/// A run that has not reached the top of the range after this many branches is a failure.
pub const MAX_BRANCHES: usize = 3000;

/// Engine settings of a measurement; `det_test` is TEST_BIFURCATION = 'SERIE_DETERMINANT'
/// (Code_Aster's default, what the study measures) against 'SERIE' (false).
pub fn settings(cfg: &Config, points_per_branch: usize, det_test: bool) -> Settings {
    Settings {
        harmonics: Harmonics {
            h_lin: cfg.h_lin,
            h_nonl: cfg.h_nonl,
        },
        continuation: Continuation {
            n_branches: MAX_BRANCHES,
            n_points_per_branch: points_per_branch,
            order: ORDER,
            prec_man: cfg.prec_man,
            prec_newton: PREC_NEWTON,
            iter_newton_max: 15,
            bif_terms: 3,
            bif_tol: 1e-4,
            det_test,
            direction: -1,
        },
    }
}

#[derive(Clone, Debug)]
pub struct Measurement {
    pub config: Config,
    /// max |f/f_ref − 1| over the computed points with energy in the range (NaN on failure).
    pub max_rel_error: f64,
    /// Wall time of the whole run: start point and every branch up to the top of the range.
    pub seconds: f64,
    /// CPU time of the same run (the measuring thread; NaN where the OS does not say). On a
    /// shared machine it is the repeatable cost: wall time also counts the other processes.
    pub cpu_seconds: f64,
    pub branches: usize,
    pub points: usize,
    pub points_in_range: usize,
    /// Why the run did not measure (engine error, range not reached).
    pub failure: Option<String>,
}

impl Measurement {
    pub fn ok(&self) -> bool {
        self.failure.is_none() && self.max_rel_error.is_finite()
    }

    /// The cost the study ranks by: CPU time when known, else wall time.
    pub fn cost(&self) -> f64 {
        if self.cpu_seconds.is_finite() {
            self.cpu_seconds
        } else {
            self.seconds
        }
    }
}

/// CPU time (user + system) of the calling thread from /proc (Linux); None elsewhere.
/// `schedstat` gives it in nanoseconds; where the kernel does not keep it, `stat` gives it
/// in clock ticks, 100 per second on Linux (USER_HZ), too coarse for the cheapest runs.
pub fn thread_cpu_seconds() -> Option<f64> {
    schedstat_cpu_seconds().or_else(stat_cpu_seconds)
}

fn schedstat_cpu_seconds() -> Option<f64> {
    // First field: time spent on the CPU, ns.
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

fn stat_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    // Fields after the command name (which may hold spaces) closed by the last ')':
    // state is the first, utime the 12th, stime the 13th.
    let rest = &stat[stat.rfind(')')? + 1..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = f.get(11)?.parse().ok()?;
    let stime: f64 = f.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

/// The frequency (Hz) a computed point is compared with, at its energy.
pub enum Reference {
    ExactPlan(Oscillator),
    /// A computed branch: (ln E, ln f), sorted by energy.
    Curve(Vec<(f64, f64)>),
}

impl Reference {
    pub fn exact_plan(o: Oscillator) -> Reference {
        Reference::ExactPlan(o)
    }

    /// From computed points (sorted here); None if fewer than 3 usable points.
    pub fn from_points(points: &[Point]) -> Option<Reference> {
        let mut v: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.energy > 0.0 && p.frequency > 0.0)
            .map(|p| (p.energy.ln(), p.frequency.ln()))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v.dedup_by(|a, b| a.0 == b.0);
        (v.len() >= 3).then_some(Reference::Curve(v))
    }

    /// Reference frequency at energy e; None outside a computed curve.
    pub fn frequency(&self, e: f64) -> Option<f64> {
        match self {
            Reference::ExactPlan(o) => Some(o.frequency_plan(e)),
            Reference::Curve(v) => {
                let x = e.ln();
                let n = v.len();
                if n < 3 || x < v[0].0 || x > v[n - 1].0 {
                    return None;
                }
                // Quadratic through the three nearest points in (ln E, ln f): on the dense
                // reference branch its error is far below the errors measured.
                let i = v.partition_point(|p| p.0 < x).clamp(1, n - 1);
                let j = if i + 1 < n && (i == 1 || x - v[i - 1].0 > v[i].0 - x) {
                    i - 1
                } else {
                    i - 2
                };
                let (x0, x1, x2) = (v[j].0, v[j + 1].0, v[j + 2].0);
                let (y0, y1, y2) = (v[j].1, v[j + 1].1, v[j + 2].1);
                let l0 = (x - x1) * (x - x2) / ((x0 - x1) * (x0 - x2));
                let l1 = (x - x0) * (x - x2) / ((x1 - x0) * (x1 - x2));
                let l2 = (x - x0) * (x - x1) / ((x2 - x0) * (x2 - x1));
                Some((y0 * l0 + y1 * l1 + y2 * l2).exp())
            }
        }
    }
}

struct Run {
    points: Vec<Point>,
    branches: usize,
    seconds: f64,
    cpu_seconds: f64,
    failure: Option<String>,
}

/// Runs a branch until its energy passes the top of the range; returns the points, the
/// number of branches and the times, or the failure with what was computed.
fn timed_run(case: &StudyCase, cfg: &Config, points_per_branch: usize, det_test: bool) -> Run {
    let problem = case.problem_with(cfg.regul);
    let s = settings(cfg, points_per_branch, det_test);
    let (_, hi) = case.range();
    let c0 = thread_cpu_seconds();
    let t0 = Instant::now();
    let cpu = |c0: Option<f64>| match (c0, thread_cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    };
    let start_state = match start_from_mode(&problem, &s, &case.mode, 1.0, case.omega) {
        Ok(start_state) => start_state,
        Err(e) => {
            return Run {
                points: vec![],
                branches: 0,
                seconds: t0.elapsed().as_secs_f64(),
                cpu_seconds: cpu(c0),
                failure: Some(e.message),
            }
        }
    };
    let mut branches = 0;
    let out = continue_while(&problem, &s, start_state, &mut |r, _| {
        branches = r.branch;
        r.energy_range.1 <= hi
    });
    let seconds = t0.elapsed().as_secs_f64();
    let cpu_seconds = cpu(c0);
    let top = out.points.iter().map(|p| p.energy).fold(0.0, f64::max);
    let failure = match out.error {
        Some(e) => Some(e.message),
        None if top <= hi => Some(format!(
            "stopped at E = {top:.3e} below the top of the range {hi:.3e} after {branches} branches"
        )),
        None => None,
    };
    Run {
        points: out.points,
        branches,
        seconds,
        cpu_seconds,
        failure,
    }
}

/// Measures one setting against `reference`, with the default bifurcation test.
pub fn measure(case: &StudyCase, cfg: &Config, reference: &Reference) -> Measurement {
    measure_with(case, cfg, reference, true)
}

/// Measures one setting against `reference`, with (`det_test`) or without the
/// determinant-sign bifurcation test.
pub fn measure_with(
    case: &StudyCase,
    cfg: &Config,
    reference: &Reference,
    det_test: bool,
) -> Measurement {
    let Run {
        points,
        branches,
        seconds,
        cpu_seconds,
        mut failure,
    } = timed_run(case, cfg, POINTS_PER_BRANCH, det_test);
    let (lo, hi) = case.range();
    let mut err: f64 = 0.0;
    let mut in_range = 0;
    let mut seconds = seconds;
    let mut cpu_seconds = cpu_seconds;
    // (energy, frequency) of each point compared: EHMAN's (ENERGIE, FREQUENCE), or the
    // exact-law orbit's with ENERGIE_MOYENNE held.
    let mut compared: Vec<(f64, f64)> = Vec::new();
    let inside: Vec<&Point> = points
        .iter()
        .filter(|p| p.energy >= lo && p.energy <= hi)
        .collect();
    if cfg.exact_law > 0 && failure.is_none() {
        let c0 = thread_cpu_seconds();
        let t0 = Instant::now();
        let problem = case.problem_with(cfg.regul);
        for p in &inside {
            match correct_point(&problem, cfg, p) {
                Ok(ef) => compared.push(ef),
                Err(e) => {
                    failure = Some(e.message);
                    break;
                }
            }
        }
        seconds += t0.elapsed().as_secs_f64();
        cpu_seconds += match (c0, thread_cpu_seconds()) {
            (Some(a), Some(b)) => b - a,
            _ => f64::NAN,
        };
    } else {
        compared = inside.iter().map(|p| (p.energy, p.frequency)).collect();
    }
    for &(energy, frequency) in &compared {
        match reference.frequency(energy) {
            Some(f) => {
                err = err.max((frequency / f - 1.0).abs());
                in_range += 1;
            }
            None => {
                failure.get_or_insert(format!("no reference at E = {energy:.3e}"));
            }
        }
    }
    if in_range == 0 {
        failure.get_or_insert("no computed point inside the range".into());
    }
    Measurement {
        config: *cfg,
        max_rel_error: if failure.is_none() { err } else { f64::NAN },
        seconds,
        cpu_seconds,
        branches,
        points: points.len(),
        points_in_range: in_range,
        failure,
    }
}

/// A point corrected on the exact law with its ENERGIE_MOYENNE held (measured: holding
/// ENERGIE instead leaves its one-instant truncation ripple in the curve, docs/accuracy.md):
/// (ENERGIE_MOYENNE, frequency of the exact-law orbit).
pub fn correct_point(problem: &Problem, cfg: &Config, p: &Point) -> Result<(f64, f64)> {
    let set = ExactLawSettings {
        h_lin: cfg.h_lin,
        samples: exact_law_samples(cfg),
        prec: PREC_NEWTON,
        iter_max: 15,
        held: HeldEnergy::Mean,
    };
    let c = exact_law::correct_point(problem, &set, p)?;
    Ok((p.energy_mean, c.frequency))
}

/// Samples per period of the exact-law correction of `cfg`.
pub fn exact_law_samples(cfg: &Config) -> usize {
    crate::nnm::exact_law::samples_for(cfg.h_lin, cfg.exact_law)
}

/// Samples per coefficient of the exact-law correction of a reference run.
pub const EXACT_REFERENCE_SAMPLES: usize = 64;

/// NB_PAS_MAN of a reference run: a dense curve for the interpolation.
pub const REFERENCE_POINTS_PER_BRANCH: usize = 10;

/// Computes a reference curve (a branch slightly past the range so that interpolation never
/// needs to extrapolate); the measurement records its cost, its error is not known (NaN).
///
/// Also returns the reference of the exact-law variant: the same points corrected on the
/// exact law (`correct_point`, with `EXACT_REFERENCE_SAMPLES` per coefficient), as
/// (ENERGIE_MOYENNE, frequency).
pub fn reference_curve(
    case: &StudyCase,
    cfg: &Config,
) -> Result<(Reference, Reference, Measurement)> {
    let Run {
        points,
        branches,
        seconds,
        cpu_seconds,
        failure,
    } = timed_run(case, cfg, REFERENCE_POINTS_PER_BRANCH, true);
    if let Some(f) = &failure {
        return Err(Error::numerical(format!(
            "the reference run of {} failed: {f}",
            case.kind.name()
        )));
    }
    let (lo, _) = case.range();
    let reference = Reference::from_points(&points)
        .filter(|r| match r {
            Reference::Curve(v) => v.first().is_some_and(|p| p.0 <= lo.ln()),
            Reference::ExactPlan(_) => true,
        })
        .ok_or_else(|| {
            Error::numerical(format!(
                "the reference run of {} does not cover the range",
                case.kind.name()
            ))
        })?;
    let exact_cfg = Config {
        exact_law: EXACT_REFERENCE_SAMPLES,
        ..*cfg
    };
    let problem = case.problem_with(cfg.regul);
    let mut corrected = Vec::with_capacity(points.len());
    for p in &points {
        let (e, f) = correct_point(&problem, &exact_cfg, p)?;
        corrected.push((e.ln(), f.ln()));
    }
    corrected.sort_by(|a, b| a.0.total_cmp(&b.0));
    corrected.dedup_by(|a, b| a.0 == b.0);
    let exact = Reference::Curve(corrected);
    let m = Measurement {
        config: *cfg,
        max_rel_error: f64::NAN,
        seconds,
        cpu_seconds,
        branches,
        points: points.len(),
        points_in_range: points
            .iter()
            .filter(|p| p.energy >= lo && p.energy <= case.range().1)
            .count(),
        failure: None,
    };
    Ok((reference, exact, m))
}
