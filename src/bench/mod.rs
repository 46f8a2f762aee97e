//! `aster-nl bench`: the speed and memory of MODE_NON_LINE, printed as tables
//! (docs/performance.md has the method and the measured figures).
//!
//! Every measurement runs in its own child process, so that its CPU time (user + system)
//! and peak resident memory are its own: whole runs are `<binary> run case.comm` of an old
//! and the new binary side by side (medians of `repeats`); engine runs are this binary's
//! hidden `bench-case` subcommand, which runs the command-file prefix up to CALC_MODES
//! in-process, then times the engine alone (start + continuation) with the tangent solver
//! asked for. The old engine's linear algebra is also available inside the new binary
//! (`reference`: the whole tangent in one sparse LU, the dense determinant test), for
//! engine-level comparisons where the old binary cannot run the case. With `--reduce`,
//! `bench-case` runs the engine on a REDUCTION basis, the basis timed apart, and prints
//! every point's ENERGIE and FREQUENCE for comparison with the full model (curves.rs).

pub mod curves;
pub mod measure;
pub mod models;
mod transient;

use crate::error::{Error, ErrorKind, Result};
use crate::linalg::craig_bampton::ModeCut;
use crate::nnm::{self, ContactMethod, SolverKind};
use measure::{exponent, median, run_child, ChildRun};
use models::Case;
use std::io::Write;
use std::path::{Path, PathBuf};

/// What to run.
pub struct Options {
    /// A smoke run (small cases, new binary only): what CI may afford.
    pub quick: bool,
    /// The old binary for the side-by-side whole runs and the table comparison.
    pub old: Option<PathBuf>,
    pub repeats: usize,
    /// Scratch directory (case files, databases).
    pub dir: PathBuf,
    /// Sections to run (empty: all): whole, hnl, n, det, routes, compare, reduced, transient.
    pub only: Vec<String>,
    /// The old binary reads DIR_EVOLUTION=1 as forward (before the DIR_EVOLUTION change):
    /// its command files (generated ones and the sdnd122 copies) get the sign flipped.
    pub old_plus_forward: bool,
}

fn io(e: impl std::fmt::Display) -> Error {
    Error::new(ErrorKind::Io, format!("bench: {e}"))
}

/// REDUCTION/COEF_COUPURE's default, read from the catalog (commands/MODE_NON_LINE.toml):
/// the bench's default basis is MODE_NON_LINE's.
pub fn default_coef_coupure() -> Result<f64> {
    crate::catalog::get("MODE_NON_LINE")
        .and_then(|op| op.fact.iter().find(|f| f.name == "REDUCTION"))
        .and_then(|f| f.simp.iter().find(|s| s.name == "COEF_COUPURE"))
        .and_then(|s| s.default.as_ref())
        .and_then(|v| v.as_f64())
        .ok_or_else(|| io("the catalog has no default for MODE_NON_LINE/REDUCTION/COEF_COUPURE"))
}

/// Largest count (elements, masses, harmonics, branches, points) a model spec may give.
const MAX_COUNT: usize = 1_000_000;

/// A model named on the command line of `bench-case`:
/// wall:H_nl:branches | utube:H_nl:branches:points:offset |
/// beam:elements:H_l:H_nl:branches[:points] |
/// spans:spans:elements:H_l:H_nl:branches (the bar on spans + 1 supports, `elements` in
/// all, models::spans) | chain:masses:H_l:H_nl:branches.
pub fn parse_model(spec: &str) -> Result<Case> {
    let p: Vec<&str> = spec.split(':').collect();
    let num = |i: usize| -> Result<f64> {
        p.get(i)
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or_else(|| io(format!("model '{spec}': field {i} is not a number")))
    };
    // Counts are checked before anything is sized from them: a whole number from 1 to
    // MAX_COUNT (ten times the largest model the bench runs).
    let int = |i: usize| -> Result<usize> {
        let v = num(i)?;
        if v.fract() == 0.0 && (1.0..=MAX_COUNT as f64).contains(&v) {
            Ok(v as usize)
        } else {
            Err(io(format!(
                "model '{spec}': field {i} must be a whole number from 1 to {MAX_COUNT}, got {v}"
            )))
        }
    };
    match p.first().copied() {
        Some("wall") => Ok(models::wall(int(1)?, int(2)?)),
        Some("utube") => Ok(models::utube(int(1)?, int(2)?, int(3)?, num(4)?)),
        Some("beam") => {
            let mut case = models::beam(int(1)?, int(2)?, int(3)?, int(4)?);
            // An optional fifth number: points per branch (NB_PAS_MAN), 1 otherwise.
            if p.len() > 5 {
                case.mnl.points = int(5)?;
            }
            Ok(case)
        }
        Some("spans") => Ok(models::spans(int(1)?, int(2)?, int(3)?, int(4)?, int(5)?)),
        Some("chain") => Ok(models::chain(int(1)?, int(2)?, int(3)?, int(4)?)),
        _ => Err(io(format!(
            "unknown model '{spec}' (wall:…, utube:…, beam:…, spans:…, chain:…)"
        ))),
    }
}

pub fn parse_solver(s: &str) -> Result<SolverKind> {
    match s {
        "auto" => Ok(SolverKind::Structured),
        "dense" => Ok(SolverKind::StructuredWith(ContactMethod::Dense)),
        "krylov" => Ok(SolverKind::StructuredWith(ContactMethod::Krylov)),
        "toeplitz" => Ok(SolverKind::StructuredWith(ContactMethod::Toeplitz)),
        "reference" => Ok(SolverKind::Reference),
        _ => Err(io(format!(
            "unknown solver '{s}' (auto, dense, krylov, toeplitz, reference)"
        ))),
    }
}

/// REDUCTION of a `bench-case`: `coef:C` (cut-off C × H_l × the linear frequency, as
/// COEF_COUPURE), `modes:N` (NB_MODE), `freq:F` (FREQ_COUPURE, Hz).
pub fn parse_reduction(spec: &str, h_lin: usize, f_lin: f64) -> Result<ModeCut> {
    let bad = || io(format!("reduction '{spec}': coef:C, modes:N or freq:F"));
    let (kind, value) = spec.split_once(':').ok_or_else(bad)?;
    let v: f64 = value.parse().map_err(|_| bad())?;
    if !(v.is_finite() && v >= 0.0) {
        return Err(bad());
    }
    match kind {
        "coef" => Ok(ModeCut::UpTo(v * h_lin as f64 * f_lin)),
        "modes" if v.fract() == 0.0 && v <= MAX_COUNT as f64 => Ok(ModeCut::Count(v as usize)),
        "freq" => Ok(ModeCut::UpTo(v)),
        _ => Err(bad()),
    }
}

/// The child side: prepare the model, time the engine (and the reduction, when asked: its
/// basis, the projection and the start's coordinates), print one `BENCH` line.
pub fn run_case(
    model: &str,
    solver: &str,
    det: bool,
    reduction: Option<&str>,
    dir: &Path,
    out: &mut dyn Write,
) -> Result<()> {
    let mut case = parse_model(model)?;
    case.mnl.det_test = det;
    let kind = parse_solver(solver)?;
    let prep = models::prepare(&case, dir)?;
    let rss0 = measure::rss_kb();
    measure::reset_peak();
    let t0 = measure::self_cpu();
    let f_lin = prep.omega / (2.0 * std::f64::consts::PI);
    // ω² of the basis's modes, printed on a BASIS line: what a change of the eigensolver
    // is compared on, side by side with an older binary.
    let mut basis_omega2 = Vec::new();
    let (problem, mode, omega, coords) = match reduction {
        Some(spec) => {
            let cut = parse_reduction(spec, prep.settings.harmonics.h_lin, f_lin)?;
            let basis = nnm::shock_basis(&prep.problem, cut, usize::MAX)?;
            let problem = nnm::reduced_problem(&prep.problem, &basis)?;
            let coords = basis.size();
            basis_omega2.clone_from(&basis.omega2);
            let (q, omega) =
                nnm::Reduced::new(basis, &prep.problem)?.start_mode(&problem, &prep.mode)?;
            (problem, q, omega, coords)
        }
        None => (
            prep.problem.clone(),
            prep.mode.clone(),
            prep.omega,
            prep.problem.k.nrows(),
        ),
    };
    let reduce_cpu = measure::self_cpu() - t0;
    let mut error = String::from("-");
    let mut points = 0;
    // Frequency of the last point against the linear one: a shift says the shocks acted.
    let mut f_last = f64::NAN;
    // ENERGIE and FREQUENCE of every point: the reduced route is compared with the full one
    // at common energies (`aster-nl bench --only reduced`).
    let mut curve = String::new();
    match nnm::start_from_mode_using(&problem, &prep.settings, &mode, prep.coef_ampl, omega, kind) {
        Ok(start_state) => {
            let o = nnm::continue_branches(&problem, &prep.settings, start_state, &mut |_, _| {});
            points = o.points.len();
            if let Some(p) = o.points.last() {
                f_last = p.frequency;
            }
            curve = o
                .points
                .iter()
                .map(|p| format!("{:.17e}/{:.17e}", p.energy, p.frequency))
                .collect::<Vec<_>>()
                .join(",");
            if let Some(e) = o.error {
                error = e.message.replace(' ', "_");
            }
        }
        Err(e) => error = e.message.replace(' ', "_"),
    }
    let cpu = measure::self_cpu() - t0;
    let peak = measure::peak_kb();
    writeln!(
        out,
        "BENCH cpu={cpu:.6} peak_kb={peak} base_kb={rss0} points={points} n={} nnz={} unknowns={} f_lin={:.6} f_last={f_last:.6} reduce_cpu={reduce_cpu:.6} coords={coords} error={error}",
        prep.problem.k.nrows(),
        prep.nnz,
        nnm::unknown_count(&problem, &prep.settings),
        f_lin
    )
    .map_err(io)?;
    writeln!(out, "CURVE {curve}").map_err(io)?;
    let omega2: Vec<String> = basis_omega2.iter().map(|w| format!("{w:.17e}")).collect();
    writeln!(out, "BASIS {}", omega2.join(",")).map_err(io)
}

/// One engine measurement (parsed from a child's BENCH line).
#[derive(Clone, Debug, Default)]
struct EngineRun {
    cpu: f64,
    peak_kb: u64,
    base_kb: u64,
    points: usize,
    n: usize,
    nnz: usize,
    error: String,
    /// CPU of the reduction (basis, projection, start coordinates), included in `cpu`.
    reduce_cpu: f64,
    /// Coordinates the engine solved on (the DOFs without a reduction).
    coords: usize,
    /// (ENERGIE, FREQUENCE) of every point.
    curve: Vec<(f64, f64)>,
}

fn parse_bench_line(out: &str) -> Option<EngineRun> {
    let line = out.lines().find(|l| l.starts_with("BENCH "))?;
    let mut r = EngineRun::default();
    for kv in line.split_whitespace().skip(1) {
        let (k, v) = kv.split_once('=')?;
        match k {
            "cpu" => r.cpu = v.parse().ok()?,
            "peak_kb" => r.peak_kb = v.parse().ok()?,
            "base_kb" => r.base_kb = v.parse().ok()?,
            "points" => r.points = v.parse().ok()?,
            "n" => r.n = v.parse().ok()?,
            "nnz" => r.nnz = v.parse().ok()?,
            "error" => r.error = v.replace('_', " "),
            "reduce_cpu" => r.reduce_cpu = v.parse().ok()?,
            "coords" => r.coords = v.parse().ok()?,
            _ => {}
        }
    }
    if let Some(c) = out.lines().find_map(|l| l.strip_prefix("CURVE ")) {
        r.curve = c
            .split(',')
            .filter(|p| !p.is_empty())
            .map(|p| {
                let (e, f) = p.split_once('/')?;
                Some((e.parse().ok()?, f.parse().ok()?))
            })
            .collect::<Option<Vec<_>>>()?;
    }
    Some(r)
}

struct Bench<'a> {
    exe: PathBuf,
    opts: &'a Options,
    out: &'a mut dyn Write,
}

/// " (why)" after a count when the run failed, nothing otherwise.
fn error_note(r: &EngineRun) -> String {
    if r.error != "-" {
        format!(" ({})", r.error)
    } else {
        String::new()
    }
}

fn fmt_s(v: f64) -> String {
    if !v.is_finite() {
        "—".into()
    } else if v < 1e-2 {
        format!("{:.0} µs", 1e6 * v)
    } else if v < 1.0 {
        format!("{:.1} ms", 1e3 * v)
    } else {
        format!("{v:.2} s")
    }
}

fn fmt_mb(kb: u64) -> String {
    format!("{:.0} MB", kb as f64 / 1024.0)
}

impl Bench<'_> {
    fn say(&mut self, s: &str) -> Result<()> {
        writeln!(self.out, "{s}").map_err(io)?;
        self.out.flush().map_err(io)
    }

    fn wants(&self, section: &str) -> bool {
        self.opts.only.is_empty() || self.opts.only.iter().any(|s| s == section)
    }

    /// Median engine run of `model` (`repeats` child processes).
    fn engine(
        &mut self,
        model: &str,
        solver: &str,
        det: bool,
        repeats: usize,
    ) -> Result<EngineRun> {
        let exe = self.exe.clone();
        self.engine_of(&exe, model, solver, det, None, repeats)
    }

    /// Median engine run of `model` on the reduction `spec` (`bench-case --reduce`).
    fn reduced_engine(&mut self, model: &str, spec: &str, repeats: usize) -> Result<EngineRun> {
        let exe = self.exe.clone();
        self.engine_of(&exe, model, "auto", true, Some(spec), repeats)
    }

    /// Median engine run of the old binary (`--old`, its own `bench-case`), when there is
    /// one and it can run the model; None otherwise.
    fn old_engine(&mut self, model: &str, repeats: usize) -> Option<EngineRun> {
        let old = self.opts.old.clone()?;
        self.engine_of(&old, model, "auto", true, None, repeats)
            .ok()
    }

    /// Median engine run of `model` by `exe` (`repeats` child processes).
    fn engine_of(
        &mut self,
        exe: &Path,
        model: &str,
        solver: &str,
        det: bool,
        reduce: Option<&str>,
        repeats: usize,
    ) -> Result<EngineRun> {
        let dir = self.opts.dir.join(model.replace(':', "_"));
        std::fs::create_dir_all(&dir).map_err(io)?;
        let mut runs = Vec::new();
        for _ in 0..repeats.max(1) {
            let mut args = vec![
                "bench-case",
                model,
                "--solver",
                solver,
                if det { "--det" } else { "--no-det" },
                "--dir",
                dir.to_str().unwrap_or("."),
            ];
            if let Some(spec) = reduce {
                args.extend(["--reduce", spec]);
            }
            let c = run_child(exe, &args, &dir)?;
            let r = parse_bench_line(&c.stdout).ok_or_else(|| {
                io(format!(
                    "bench-case {model} {solver}: no result (exit {})",
                    c.code
                ))
            })?;
            runs.push(r);
        }
        let mut cpus: Vec<f64> = runs.iter().map(|r| r.cpu).collect();
        let cpu = median(&mut cpus);
        let mut r = runs.remove(0);
        r.cpu = cpu;
        Ok(r)
    }

    /// Whole runs of a command file by `binary`, medians of `repeats`.
    fn whole(
        &mut self,
        binary: &Path,
        dir: &Path,
        comm: &str,
        repeats: usize,
    ) -> Result<(f64, u64, i32)> {
        let mut cpus = Vec::new();
        let mut peak = 0;
        let mut code = 0;
        for _ in 0..repeats.max(1) {
            let db = dir.join("run.db");
            let _ = std::fs::remove_file(&db);
            let c: ChildRun = run_child(
                binary,
                &[
                    "run",
                    comm,
                    "--db",
                    db.to_str().unwrap_or("run.db"),
                    "--unit",
                    "20=case.mail",
                ],
                dir,
            )?;
            cpus.push(c.cpu);
            peak = peak.max(c.peak_kb);
            code = c.code;
        }
        Ok((median(&mut cpus), peak, code))
    }

    /// Write a case's mesh and whole command file into its directory.
    fn write_case(&mut self, case: &Case, tag: &str) -> Result<PathBuf> {
        let dir = self.opts.dir.join(tag);
        std::fs::create_dir_all(&dir).map_err(io)?;
        let coef = match case.mnl.coef_ampl {
            Some(c) => c,
            None => models::prepare(case, &dir)?.coef_ampl,
        };
        std::fs::write(dir.join("case.mail"), &case.mail).map_err(io)?;
        std::fs::write(dir.join("case.comm"), models::full_comm(case, coef, false)).map_err(io)?;
        std::fs::write(
            dir.join("case_old.comm"),
            models::full_comm(case, coef, self.opts.old_plus_forward),
        )
        .map_err(io)?;
        Ok(dir)
    }

    fn whole_section(&mut self) -> Result<()> {
        self.say("\n## Whole runs (`aster-nl run case.comm`), CPU s (user + sys), peak RSS\n")?;
        self.say("| case | old CPU | new CPU | speed-up | old peak | new peak |")?;
        self.say("|---|---|---|---|---|---|")?;
        let reps = self.opts.repeats;
        let cases: Vec<(Case, &str, usize)> = if self.opts.quick {
            vec![(models::wall(50, 20), "whole_wall50", reps)]
        } else {
            vec![
                (models::wall(200, 105), "whole_sdnd122a", reps),
                (models::wall(1000, 105), "whole_sdnd122a_h1000", 1),
                (models::utube(201, 10, 10, 0.3), "whole_utube", 1),
            ]
        };
        for (case, tag, old_reps) in cases {
            let dir = self.write_case(&case, tag)?;
            let exe = self.exe.clone();
            let (cn, pn, coden) = self.whole(&exe, &dir, "case.comm", reps)?;
            let (co, po) = match self.opts.old.clone() {
                Some(old) => {
                    let (c, p, _) = self.whole(&old, &dir, "case_old.comm", old_reps)?;
                    (c, Some(p))
                }
                None => (f64::NAN, None),
            };
            let note = if coden == 2 { " (new: error)" } else { "" };
            self.say(&format!(
                "| {}{note} | {} | {} | {} | {} | {} |",
                case.name,
                fmt_s(co),
                fmt_s(cn),
                if co.is_finite() {
                    format!("{:.1}×", co / cn)
                } else {
                    "—".into()
                },
                po.map_or("—".into(), fmt_mb),
                fmt_mb(pn)
            ))?;
        }
        Ok(())
    }

    fn hnl_section(&mut self) -> Result<()> {
        self.say("\n## Cost against NB_HARM_NONL (sdnd122a, 105 branches, engine only)\n")?;
        self.say("| H_nl | reference (old linear algebra) | old binary | new | speed-up over old | new peak |")?;
        self.say("|---|---|---|---|---|---|")?;
        let hs: &[usize] = if self.opts.quick {
            &[20, 50]
        } else {
            &[50, 100, 200, 400, 1000]
        };
        let branches = if self.opts.quick { 10 } else { 105 };
        let (mut new_pts, mut ref_pts, mut old_pts) = (Vec::new(), Vec::new(), Vec::new());
        for &h in hs {
            let model = format!("wall:{h}:{branches}");
            let reps = self.opts.repeats;
            let n = self.engine(&model, "auto", true, reps)?;
            let o = self.old_engine(&model, reps);
            if let Some(o) = &o {
                old_pts.push((h as f64, o.cpu));
            }
            let r = if self.opts.quick || h > 400 {
                None
            } else {
                Some(self.engine(&model, "reference", true, 1)?)
            };
            new_pts.push((h as f64, n.cpu));
            if let Some(r) = &r {
                ref_pts.push((h as f64, r.cpu));
            }
            self.say(&format!(
                "| {h} | {} | {} | {} | {} | {} |",
                r.as_ref().map_or("—".into(), |r| fmt_s(r.cpu)),
                o.as_ref().map_or("—".into(), |o| fmt_s(o.cpu)),
                fmt_s(n.cpu),
                o.as_ref()
                    .map_or("—".into(), |o| format!("{:.2}×", o.cpu / n.cpu)),
                fmt_mb(n.peak_kb)
            ))?;
        }
        self.say(&format!(
            "\nfitted exponent of CPU against H_nl: new {:.2}, old binary {:.2}, reference {:.2} (H·log H over the same range: {:.2})",
            exponent(&new_pts),
            exponent(&old_pts),
            exponent(&ref_pts),
            exponent(&hs.iter().map(|&h| (h as f64, h as f64 * (h as f64).ln())).collect::<Vec<_>>())
        ))
    }

    fn n_section(&mut self) -> Result<()> {
        self.say("\n## Cost against the number of DOFs (tube with two CERCLE rings, H_l 5, H_nl 200, engine only)\n")?;
        self.say("| DOFs | branches | points | old binary CPU | CPU | speed-up over old | CPU per branch | peak RSS | engine memory / nonzero of K∪M |")?;
        self.say("|---|---|---|---|---|---|---|---|---|")?;
        let sizes: &[(usize, usize)] = if self.opts.quick {
            &[(4, 2), (26, 2)]
        } else {
            &[
                (4, 10),
                (26, 10),
                (101, 10),
                (401, 10),
                (2501, 10),
                (2501, 50),
            ]
        };
        let mut pts = Vec::new();
        for &(el, br) in sizes {
            let model = format!("beam:{el}:5:200:{br}");
            let r = self.engine(&model, "auto", true, 1)?;
            let o = self.old_engine(&model, 1);
            if br == 10 {
                pts.push((r.n as f64, r.cpu / br as f64));
            }
            let per_nnz =
                (r.peak_kb.saturating_sub(r.base_kb) as f64 * 1024.0) / r.nnz.max(1) as f64;
            self.say(&format!(
                "| {} | {br} | {}{} | {} | {} | {} | {} | {} | {:.0} B |",
                r.n,
                r.points,
                error_note(&r),
                o.as_ref().map_or("—".into(), |o| fmt_s(o.cpu)),
                fmt_s(r.cpu),
                o.as_ref()
                    .map_or("—".into(), |o| format!("{:.2}×", o.cpu / r.cpu)),
                fmt_s(r.cpu / br as f64),
                fmt_mb(r.peak_kb),
                per_nnz
            ))?;
        }
        self.say(&format!(
            "\nfitted exponent of CPU per branch against DOFs (10 branches): {:.2}",
            exponent(&pts)
        ))?;
        if !self.opts.quick {
            self.scale_section()?;
        }
        Ok(())
    }

    /// 10⁵ DOFs: the same bar with 25 001 elements in its one span (condition number ∝ N⁴,
    /// about 4e17: refused by the reference-stiffness check, nnm::system::inverse_diag), the
    /// same bar on 15 supports (14 unequal spans, the longest of 2 498 elements: the
    /// condition number goes with one span's elements, models::spans), and a spring chain
    /// of 10⁵ masses (condition ∝ N²) with its stop; the last two complete.
    fn scale_section(&mut self) -> Result<()> {
        self.say("\n### 10⁵ DOFs (H_l 5, H_nl 200, engine only, one run each)\n")?;
        self.say("| model | DOFs | branches | points | CPU | CPU per branch | peak RSS | engine memory / nonzero of K∪M | outcome |")?;
        self.say("|---|---|---|---|---|---|---|---|---|")?;
        for (label, model, br) in [
            ("bar, one span of 25 001 POU_D_E", "beam:25001:5:200:1", 1),
            (
                "bar on 15 supports, 25 600 POU_D_E",
                "spans:14:25600:5:200:5",
                5,
            ),
            (
                "chain of 10⁵ masses, one PLAN stop",
                "chain:100000:5:200:5",
                5,
            ),
        ] {
            let r = self.engine(model, "auto", true, 1)?;
            let per_nnz =
                (r.peak_kb.saturating_sub(r.base_kb) as f64 * 1024.0) / r.nnz.max(1) as f64;
            let outcome = if r.error == "-" {
                "completed".to_string()
            } else {
                r.error.replace('_', " ")
            };
            self.say(&format!(
                "| {label} | {} | {br} | {} | {} | {} | {} | {per_nnz:.0} B | {outcome} |",
                r.n,
                r.points,
                fmt_s(r.cpu),
                fmt_s(r.cpu / br as f64),
                fmt_mb(r.peak_kb),
            ))?;
        }
        Ok(())
    }

    /// REDUCTION (issue 40): the bar of the `n` section on the default basis against the
    /// full model, cost against the DOFs with each stage's fitted exponent; and, on the
    /// 1000-DOF bar with 20 points per branch (rows dense enough to interpolate), how the
    /// frequency at common energies converges with the modes kept.
    fn reduced_section(&mut self) -> Result<()> {
        let default = format!("coef:{}", default_coef_coupure()?);
        self.say("\n## REDUCTION: the bar with two rings on a Craig–Bampton basis (H_l 5, H_nl 200, engine only)\n")?;
        self.say(&format!(
            "Default cut-off ({default}: COEF_COUPURE × NB_HARM_LINE × the linear frequency). \
             \"reduction\" is the basis, the projection and the start's coordinates; \
             \"nonlinear\" the continuation on the reduced problem.\n"
        ))?;
        self.say("| DOFs | branches | coordinates | reduction CPU | nonlinear CPU | CPU | peak RSS | full model CPU | full model peak RSS | speed-up |")?;
        self.say("|---|---|---|---|---|---|---|---|---|---|")?;
        // (model, branches, with the full model beside it). 10⁵ DOFs: the bar on 15
        // supports (a single span of 10⁵ DOFs has a stiffness no double precision solves,
        // the `n` section's 10⁵ row says why); its full model is the `n` section's.
        let sizes: &[(&str, usize, bool)] = if self.opts.quick {
            &[("beam:26:5:200:2", 2, true), ("beam:101:5:200:2", 2, true)]
        } else {
            &[
                ("beam:26:5:200:50", 50, true),
                ("beam:101:5:200:50", 50, true),
                ("beam:251:5:200:50", 50, true),
                ("beam:1001:5:200:50", 50, true),
                ("beam:2501:5:200:50", 50, true),
                ("spans:15:25600:5:200:50", 50, false),
            ]
        };
        let (mut red_pts, mut nl_pts) = (Vec::new(), Vec::new());
        for &(model, br, with_full) in sizes {
            let r = self.reduced_engine(model, &default, 1)?;
            let full = if with_full {
                Some(self.engine(model, "auto", true, 1)?)
            } else {
                None
            };
            // A run that failed says nothing about growth.
            if r.error == "-" {
                red_pts.push((r.n as f64, r.reduce_cpu));
                nl_pts.push((r.n as f64, r.cpu - r.reduce_cpu));
            }
            self.say(&format!(
                "| {} | {br} | {}{} | {} | {} | {} | {} | {} | {} | {} |",
                r.n,
                r.coords,
                error_note(&r),
                fmt_s(r.reduce_cpu),
                fmt_s(r.cpu - r.reduce_cpu),
                fmt_s(r.cpu),
                fmt_mb(r.peak_kb),
                full.as_ref().map_or("—".into(), |f| fmt_s(f.cpu)),
                full.as_ref().map_or("—".into(), |f| fmt_mb(f.peak_kb)),
                full.as_ref()
                    .map_or("—".into(), |f| format!("{:.1}×", f.cpu / r.cpu)),
            ))?;
        }
        self.say(&format!(
            "\nfitted exponents against the DOFs: reduction {:.2}, nonlinear stage {:.2}",
            exponent(&red_pts),
            exponent(&nl_pts)
        ))?;
        if self.opts.quick {
            return Ok(());
        }
        self.say(
            "\n### Convergence with the modes kept (1000-DOF bar, 50 branches × 20 points)\n",
        )?;
        self.say("Largest relative difference of FREQUENCE from the full model's at the same ENERGIE (local cubic interpolation of the full rows in log ENERGIE; its own error, every other row from the others, in the first line).\n")?;
        self.say("| basis | coordinates | largest difference | rows compared | CPU |")?;
        self.say("|---|---|---|---|---|")?;
        let model = "beam:251:5:200:50:20";
        let full = self.engine(model, "auto", true, 1)?;
        self.say(&format!(
            "| full model (interpolation error: {}) | {} | — | {} | {} |",
            curves::interpolation_error(&full.curve).map_or("—".into(), |e| format!("{e:.1e}")),
            full.n,
            full.curve.len(),
            fmt_s(full.cpu)
        ))?;
        for spec in [
            "modes:0", "modes:5", "modes:10", "modes:20", "modes:40", "coef:16", "coef:32",
            "coef:64",
        ] {
            let r = self.reduced_engine(model, spec, 1)?;
            let d = curves::worst_difference(&full.curve, &r.curve, f64::abs);
            self.say(&format!(
                "| {spec} | {} | {} | {} | {} |",
                r.coords,
                d.map_or("—".into(), |d| format!("{:.1e}", d.0)),
                d.map_or(0, |d| d.1),
                fmt_s(r.cpu)
            ))?;
        }
        Ok(())
    }

    fn det_section(&mut self) -> Result<()> {
        self.say("\n## Cost of the default bifurcation test (TEST_BIFURCATION='SERIE_DETERMINANT' against 'SERIE')\n")?;
        self.say("| case | with | without | share of the run |")?;
        self.say("|---|---|---|---|")?;
        let models: &[&str] = if self.opts.quick {
            &["wall:50:10"]
        } else {
            &[
                "wall:200:105",
                "utube:201:10:10:0.3",
                "beam:401:5:200:10",
                "beam:2501:5:200:10",
            ]
        };
        for m in models {
            let w = self.engine(m, "auto", true, self.opts.repeats)?;
            let wo = self.engine(m, "auto", false, self.opts.repeats)?;
            self.say(&format!(
                "| {m} | {} | {} | {:.1} % |",
                fmt_s(w.cpu),
                fmt_s(wo.cpu),
                100.0 * (w.cpu - wo.cpu) / w.cpu
            ))?;
        }
        Ok(())
    }

    fn routes_section(&mut self) -> Result<()> {
        self.say("\n## Contact-block routes: one factorisation (W) + 24 solves, per shock\n")?;
        self.say(
            "| law | H_nl | dense | Krylov | Krylov iterations per solve | Toeplitz | Toeplitz, time-symmetric | model picks | fastest |",
        )?;
        self.say("|---|---|---|---|---|---|---|---|---|")?;
        let hs: &[usize] = if self.opts.quick {
            &[10, 40]
        } else {
            &[10, 20, 40, 80, 160, 320, 640]
        };
        for row in nnm::contact_route_timings(hs, 24)? {
            // The model sees no symmetry: compared on the whole-period Toeplitz time.
            let mut fastest = (ContactMethod::Dense, row.dense_s);
            for (m, t) in [
                (ContactMethod::Krylov, Some(row.krylov_s)),
                (ContactMethod::Toeplitz, row.toeplitz_s),
            ] {
                if let Some(t) = t.filter(|&t| t < fastest.1) {
                    fastest = (m, t);
                }
            }
            let opt = |t: Option<f64>| t.map_or("—".to_string(), fmt_s);
            self.say(&format!(
                "| {} | {} | {} | {} | {:.1} | {} | {} | {:?} | {:?} |",
                row.law,
                row.h_nonl,
                fmt_s(row.dense_s),
                fmt_s(row.krylov_s),
                row.krylov_iterations,
                opt(row.toeplitz_s),
                opt(row.toeplitz_symmetric_s),
                row.model_choice,
                fastest.0
            ))?;
        }
        Ok(())
    }

    fn compare_section(&mut self) -> Result<()> {
        let Some(old) = self.opts.old.clone() else {
            return self.say("\n(table comparison skipped: no --old binary)");
        };
        self.say(
            "\n## Old and new tables of the sdnd122 cases (max relative difference per column)\n",
        )?;
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases");
        for (name, tables) in [
            ("sdnd122a", &["MNL"][..]),
            ("sdnd122b", &["MNL"][..]),
            ("sdnd122c", &["MNL", "MNL2"][..]),
        ] {
            let dir = self.opts.dir.join(format!("compare_{name}"));
            std::fs::create_dir_all(&dir).map_err(io)?;
            let mail = root.join(format!("{name}.mail"));
            if mail.exists() {
                std::fs::copy(&mail, dir.join(format!("{name}.mail"))).map_err(io)?;
            }
            let text = std::fs::read_to_string(root.join(format!("{name}.comm"))).map_err(io)?;
            std::fs::write(dir.join(format!("{name}.comm")), &text).map_err(io)?;
            // These files start forward (DIR_EVOLUTION=-1) and restart on in the stored
            // direction of travel, which an old binary spells DIR_EVOLUTION=1.
            let old_text = if self.opts.old_plus_forward {
                text.replace("DIR_EVOLUTION=-1", "DIR_EVOLUTION=1")
            } else {
                text
            };
            std::fs::write(dir.join(format!("{name}_old.comm")), old_text).map_err(io)?;
            let mut dbs = Vec::new();
            for (tag, bin) in [("old", old.clone()), ("new", self.exe.clone())] {
                let db = dir.join(format!("{tag}.db"));
                let _ = std::fs::remove_file(&db);
                let comm = if tag == "old" {
                    format!("{name}_old.comm")
                } else {
                    format!("{name}.comm")
                };
                run_child(
                    &bin,
                    &[
                        "run",
                        &comm,
                        "--db",
                        db.to_str().unwrap_or("x.db"),
                        "--unit",
                        &format!("20={name}.mail"),
                    ],
                    &dir,
                )?;
                dbs.push(db);
            }
            for t in tables {
                for line in compare_tables(&dbs[0], &dbs[1], t)? {
                    self.say(&format!("{name} {t}: {line}"))?;
                }
            }
        }
        Ok(())
    }
}

/// Max relative difference of every numeric column of table `t` between two databases,
/// and of the stored points (max |Δx| / max |x| per row). Columns that are round-off
/// themselves (RESIDU, AMOR_FICTIF, ECART_LOI_CHOC) get the absolute difference.
pub fn compare_tables(a: &Path, b: &Path, t: &str) -> Result<Vec<String>> {
    let ca = rusqlite::Connection::open(a).map_err(io)?;
    let cb = rusqlite::Connection::open(b).map_err(io)?;
    let read =
        |c: &rusqlite::Connection| -> Result<(Vec<String>, Vec<Vec<rusqlite::types::Value>>)> {
            let mut stmt = c
                .prepare(&format!("SELECT * FROM \"{t}\" ORDER BY NUME_ORDRE"))
                .map_err(io)?;
            let cols: Vec<String> = stmt.column_names().map(|s| s.to_string()).collect();
            let n = cols.len();
            let rows = stmt
                .query_map([], |r| {
                    (0..n)
                        .map(|i| r.get::<_, rusqlite::types::Value>(i))
                        .collect::<std::result::Result<Vec<_>, _>>()
                })
                .map_err(io)?
                .collect::<std::result::Result<Vec<_>, _>>()
                .map_err(io)?;
            Ok((cols, rows))
        };
    let (cols, ra) = read(&ca)?;
    let (_, rb) = read(&cb)?;
    let mut out = vec![format!("{} rows old, {} rows new", ra.len(), rb.len())];
    // Error measures (round-off themselves): ECART_LOI_CHOC is ~1e-9 where the law holds.
    let absolute = ["RESIDU", "AMOR_FICTIF", "ECART_LOI_CHOC"];
    let mut worst: Vec<(String, f64, bool)> = Vec::new();
    for (j, c) in cols.iter().enumerate() {
        let abs = absolute.contains(&c.as_str());
        let mut w = 0.0f64;
        let mut numeric = false;
        let mut text_diff = false;
        for (x, y) in ra.iter().zip(&rb) {
            use rusqlite::types::Value::*;
            match (&x[j], &y[j]) {
                (Real(u), Real(v)) => {
                    numeric = true;
                    let d = (u - v).abs();
                    w = w.max(if abs {
                        d
                    } else {
                        d / u.abs().max(v.abs()).max(1e-300)
                    });
                }
                (u, v) if u != v => text_diff = true,
                _ => {}
            }
        }
        if numeric {
            worst.push((c.clone(), w, abs));
        }
        if text_diff {
            out.push(format!("{c}: values differ"));
        }
    }
    out.push(
        worst
            .iter()
            .map(|(c, w, abs)| format!("{c} {w:.1e}{}", if *abs { " (abs)" } else { "" }))
            .collect::<Vec<_>>()
            .join(", "),
    );
    let points = |c: &rusqlite::Connection| -> Result<Vec<Vec<f64>>> {
        let mut stmt = c
            .prepare("SELECT x FROM mnl_points WHERE concept = ?1 ORDER BY NUME_ORDRE")
            .map_err(io)?;
        let rows = stmt
            .query_map([t], |r| r.get::<_, Vec<u8>>(0))
            .map_err(io)?
            .collect::<std::result::Result<Vec<_>, _>>()
            .map_err(io)?;
        Ok(rows
            .iter()
            .map(|b| {
                b.chunks_exact(8)
                    .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
                    .collect()
            })
            .collect())
    };
    let (pa, pb) = (points(&ca)?, points(&cb)?);
    let mut wp = 0.0f64;
    for (x, y) in pa.iter().zip(&pb) {
        let s = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let d = x
            .iter()
            .zip(y)
            .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()));
        wp = wp.max(d / s.max(1e-300));
    }
    out.push(format!("stored points: max |Δx|/max|x| = {wp:.1e}"));
    Ok(out)
}

/// The parent side: every section, tables on `out`.
pub fn run(opts: &Options, out: &mut dyn Write) -> Result<()> {
    let exe = std::env::current_exe().map_err(io)?;
    std::fs::create_dir_all(&opts.dir).map_err(io)?;
    let mut b = Bench { exe, opts, out };
    b.say(&format!(
        "# aster-nl bench ({}; old binary: {})",
        if opts.quick { "quick" } else { "full" },
        opts.old
            .as_ref()
            .map_or("none".into(), |p| p.display().to_string())
    ))?;
    if b.wants("whole") {
        b.whole_section()?;
    }
    if b.wants("hnl") {
        b.hnl_section()?;
    }
    if b.wants("n") {
        b.n_section()?;
    }
    if b.wants("det") {
        b.det_section()?;
    }
    if b.wants("routes") {
        b.routes_section()?;
    }
    if b.wants("compare") {
        b.compare_section()?;
    }
    if b.wants("reduced") {
        b.reduced_section()?;
    }
    if b.wants("transient") {
        b.transient_section()?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::dof::Cmp;
    use crate::store::{matrix, Store};

    /// The members of GROUP_NO `g` in a .mail text.
    fn group_no(mail: &str, g: &str) -> Vec<String> {
        let mut lines = mail.lines();
        while let Some(l) = lines.next() {
            if l == "GROUP_NO" && lines.next().map(str::trim) == Some(g) {
                return lines
                    .take_while(|l| *l != "FINSF")
                    .map(|l| l.trim().to_string())
                    .collect();
            }
        }
        Vec::new()
    }

    /// CALC_MODES on the clamped bar of 1000 free DOFs (dense solver): the top of the
    /// spectrum of its stiffness is beyond double precision (a non-positive μ of the
    /// inverse form), which once failed the whole command; those modes are dropped, and the
    /// first one is Euler-Bernoulli's clamped–clamped bending mode of the bar's thinner
    /// side, (4.730)²/(2π)·√(EI/(ρAL⁴)), within its discretisation error.
    #[test]
    fn calc_modes_of_the_thousand_dof_bar() {
        let dir = tempfile::tempdir().unwrap();
        let prep = models::prepare(&models::beam(251, 1, 8, 1), dir.path()).unwrap();
        assert_eq!(prep.problem.k.nrows(), 1000);
        let (e, rho, hy, hz): (f64, f64, f64, f64) = (2e11, 7800.0, 0.0137, 0.01);
        let i = hy * hz.powi(3) / 12.0;
        let f1 =
            4.730041f64.powi(2) / (2.0 * std::f64::consts::PI) * (e * i / (rho * hy * hz)).sqrt();
        let f = prep.omega / (2.0 * std::f64::consts::PI);
        // 250 Hermite elements: the error of mode 1 is about 1e-9 relative; the constant
        // 4.730041 carries 1e-7.
        assert!((f - f1).abs() < 1e-6 * f1, "{f} against {f1}");
    }

    #[test]
    fn spans_model_mesh_and_commands() {
        let per = models::span_elements(5, 500);
        assert_eq!(per.iter().sum::<usize>(), 500);
        // The longest in the middle, shorter toward both ends.
        assert!(per[0] < per[1] && per[1] < per[2], "{per:?}");
        assert!(per[2] > per[3] && per[3] > per[4], "{per:?}");
        let per14 = models::span_elements(14, 25600);
        assert_eq!(per14.iter().sum::<usize>(), 25600);
        assert_eq!(per14.iter().max(), Some(&per14[7]));
        assert!(per14[7] <= 2500, "{per14:?}");
        let case = parse_model("spans:5:500:5:200:3").unwrap();
        let coor = case.mail.split("COOR_3D\n").nth(1).unwrap();
        let nodes = coor.lines().take_while(|l| *l != "FINSF").count();
        assert_eq!(nodes, 501);
        let supports = group_no(&case.mail, "SUPPORTS");
        let mut end = 0;
        let expected: Vec<String> = per[..4]
            .iter()
            .map(|n| {
                end += n;
                format!("N{end}")
            })
            .collect();
        assert_eq!(supports, expected);
        assert_eq!(group_no(&case.mail, "ENDS"), ["N0", "N500"]);
        assert!(case
            .prefix
            .contains("_F(GROUP_NO='SUPPORTS', DY=0., DZ=0.)"));
        assert!(case.prefix.contains("_F(GROUP_NO='ALL', DX=0., DRX=0.)"));
        // Both rings in the longest (middle) span.
        let (a, b) = (per[0] + per[1], per[0] + per[1] + per[2]);
        for s in &case.shocks {
            let i: usize = s.node[1..].parse().unwrap();
            assert!(i > a && i < b, "{} not in ({a}, {b})", s.node);
        }
        assert_eq!(
            (case.mnl.h_lin, case.mnl.h_nonl, case.mnl.branches),
            (5, 200, 3)
        );
        assert_eq!(case.name, "bar on 6 supports, 1988 DOFs");
        assert!(parse_model("spans:5:500:5:200").is_err());
        // Counts out of range are refused before anything is sized from them.
        for bad in [
            "spans:0:500:5:200:3",
            "beam:1e12:5:200:1",
            "chain:2.5:5:200:1",
            "wall:-3:5",
        ] {
            let e = parse_model(bad).unwrap_err();
            assert!(
                e.message.contains("whole number from 1"),
                "{bad}: {}",
                e.message
            );
        }
    }

    /// The first mode is the longest span's first bending mode (XZ): its largest DZ is in
    /// that span, both rings move, the spans beyond its neighbours much less.
    #[test]
    fn spans_first_mode_is_the_longest_spans() {
        let dir = tempfile::tempdir().unwrap();
        let case = parse_model("spans:6:240:1:3:1").unwrap();
        let per = models::span_elements(6, 240);
        let prep = models::prepare(&case, dir.path()).unwrap();
        assert_eq!(prep.problem.k.nrows(), 4 * 239 - 2 * 5);
        let store = Store::open(&dir.path().join("prefix.db")).unwrap();
        let k = matrix::load_matrix(&store, "RIGIDITE").unwrap();
        let dz = |i: usize| -> f64 {
            k.numbering
                .index_of(&format!("N{i}"), Cmp::Dz)
                .and_then(|f| k.reduced_index(f))
                .map_or(0.0, |r| prep.mode[r].abs())
        };
        let mut start = 0;
        let span_max: Vec<f64> = per
            .iter()
            .map(|n| {
                let m = (start..=start + n).map(dz).fold(0.0, f64::max);
                start += n;
                m
            })
            .collect();
        let longest = per.len() / 2;
        let first = span_max[longest];
        // The neighbours follow (the supports pass the slope on), the next ones much less.
        for (j, m) in span_max.iter().enumerate() {
            assert!(j == longest || *m < first, "{span_max:?}");
            assert!(j.abs_diff(longest) < 2 || *m < 0.5 * first, "{span_max:?}");
        }
        for s in &case.shocks {
            let i: usize = s.node[1..].parse().unwrap();
            assert!(dz(i) > 0.5 * first, "{}: {:e} of {first:e}", s.node, dz(i));
        }
    }
}
