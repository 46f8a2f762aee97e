//! The `aster-nl` command: a thin layer over the library.
// Large `Error` on purpose: the reason is given once, at the top of src/lib.rs.
#![allow(clippy::result_large_err)]

use aster_nl::error::{Error, ErrorKind};
use aster_nl::interp::{self, RunOptions};
use aster_nl::lang::{self, Source};
use aster_nl::ops::Units;
use aster_nl::{catalog, export, store};
use clap::{Parser, Subcommand};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Exit codes: 0 all good, 1 a TEST_* was NOOK, 2 an error stopped the run or the check.
const EXIT_NOOK: u8 = 1;
const EXIT_ERROR: u8 = 2;

#[derive(Parser)]
#[command(
    name = "aster-nl",
    version,
    about = "Code_Aster-style command files for nonlinear modal analysis, results in SQLite"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a command file (.comm) or a Code_Aster export file (.export).
    Run {
        file: PathBuf,
        /// Database file (default: <case>.db beside the command file).
        #[arg(long)]
        db: Option<PathBuf>,
        /// Map a logical unit to a file, e.g. --unit 20=mesh.mail (repeatable).
        #[arg(long = "unit", value_name = "N=PATH")]
        units: Vec<String>,
        /// Raise every real non-regression tolerance (VALE_CALC) to at least X, for files
        /// whose VALE_CALC another code computed (e.g. 1e-4). Default: Code_Aster's
        /// semantics (TOLE_MACHINE, 1e-6 unless the file says otherwise).
        #[arg(long = "tole-machine", value_name = "X", value_parser = parse_tole)]
        tole_machine: Option<f64>,
    },
    /// Check a command file (or a .export) against the catalogs without running it;
    /// reports every error, including the mesh files it reads and, for a POURSUITE file,
    /// the concepts and rows of the database it continues.
    Check {
        file: PathBuf,
        /// Database a POURSUITE file continues (default: <case>.db beside the file).
        #[arg(long)]
        db: Option<PathBuf>,
        /// Map a logical unit to a file, e.g. --unit 20=mesh.mail (repeatable).
        #[arg(long = "unit", value_name = "N=PATH")]
        units: Vec<String>,
    },
    /// Print an operator's keywords (or the list of operators).
    Catalog { operator: Option<String> },
    /// List the concepts and SQL tables of a database.
    Tables { db: PathBuf },
    /// Speed and memory of MODE_NON_LINE, old and new side by side (docs/performance.md).
    /// A developer's tool: hidden from `--help`, `aster-nl bench --help` describes it.
    #[command(hide = true)]
    Bench {
        /// Small cases only, new binary only (a smoke run).
        #[arg(long)]
        quick: bool,
        /// An older aster-nl binary for the side-by-side whole runs and table comparison.
        #[arg(long)]
        old: Option<PathBuf>,
        /// Repeats of each timed run (medians).
        #[arg(long, default_value_t = 3)]
        repeats: usize,
        /// Scratch directory for case files and databases.
        #[arg(long, default_value = "target/bench")]
        dir: PathBuf,
        /// Sections to run: whole, hnl, n, det, routes, compare, reduced, transient (default: all).
        #[arg(long)]
        only: Vec<String>,
        /// The --old binary reads DIR_EVOLUTION=1 as forward (before the DIR_EVOLUTION
        /// change): its command files get the sign flipped.
        #[arg(long)]
        old_plus_forward: bool,
    },
    /// One engine measurement of `bench` (run in a child process).
    #[command(hide = true)]
    BenchCase {
        model: String,
        #[arg(long, default_value = "auto")]
        solver: String,
        #[arg(long)]
        det: bool,
        #[arg(long)]
        no_det: bool,
        /// Run on a reduction basis: coef:C, modes:N or freq:F (as REDUCTION).
        #[arg(long)]
        reduce: Option<String>,
        #[arg(long, default_value = "target/bench")]
        dir: PathBuf,
    },
    /// Measure accuracy against time of MODE_NON_LINE settings (tables, CSV, plots).
    /// A developer's tool (docs/accuracy.md): hidden from `--help`, `aster-nl accuracy
    /// --help` describes it (`study`, its former name, is an alias).
    #[command(hide = true, alias = "study")]
    Accuracy {
        /// Grid of settings: small (a quick look) or full (the documented study).
        #[arg(long, value_enum, default_value = "small")]
        grid: GridArg,
        /// Directory receiving accuracy_<case>.csv/.md/.png/.svg (created if missing;
        /// no default, so that a study never writes into a source tree unasked).
        #[arg(long)]
        out: PathBuf,
        /// Which system: the one-DOF wall (exact reference), the 2-DOF chain, or both.
        #[arg(long, value_enum, default_value = "both")]
        case: CaseArg,
    },
    /// Run a parametric sweep of a .comm template: one run per point, locally or on Slurm,
    /// merged into one SQLite database (docs/sweeps.md).
    Sweep(aster_nl::sweep::cli::SweepArgs),
    /// Merge run databases into one, the sweep's parameters as columns.
    Merge(aster_nl::sweep::cli::MergeArgs),
    /// One task of a sweep's Slurm job array (what the job script runs).
    #[command(hide = true)]
    SweepTask(aster_nl::sweep::cli::TaskArgs),
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum GridArg {
    Small,
    Full,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum CaseArg {
    Wall,
    Chain2,
    Both,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Run {
            file,
            db,
            units,
            tole_machine,
        } => run(&file, db, &units, tole_machine),
        Command::Check { file, db, units } => check(&file, db, &units),
        Command::Catalog { operator } => print_catalog(operator.as_deref()),
        Command::Tables { db } => tables(&db),
        Command::Accuracy { grid, out, case } => accuracy(grid, &out, case),
        Command::Bench {
            quick,
            old,
            repeats,
            dir,
            only,
            old_plus_forward,
        } => {
            let opts = aster_nl::bench::Options {
                quick,
                old,
                repeats,
                dir,
                only,
                old_plus_forward,
            };
            match aster_nl::bench::run(&opts, &mut std::io::stdout()) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => fail(&e, None),
            }
        }
        Command::BenchCase {
            model,
            solver,
            det,
            no_det,
            reduce,
            dir,
        } => {
            let det = det || !no_det;
            let out = &mut std::io::stdout();
            match aster_nl::bench::run_case(&model, &solver, det, reduce.as_deref(), &dir, out) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => fail(&e, None),
            }
        }
        Command::Sweep(args) => aster_nl::sweep::cli::sweep(&args),
        Command::Merge(args) => aster_nl::sweep::cli::merge(&args),
        Command::SweepTask(args) => aster_nl::sweep::cli::task(&args),
    }
}

fn fail(e: &Error, src: Option<&Source>) -> ExitCode {
    eprintln!("{}", lang::render(e, src));
    ExitCode::from(EXIT_ERROR)
}

fn parse_units(specs: &[String], base: &Path) -> Result<Units, Error> {
    let mut units = Units::default();
    for spec in specs {
        let (n, path) = spec.split_once('=').ok_or_else(|| {
            Error::new(
                ErrorKind::Io,
                format!("--unit {spec}: expected N=PATH, e.g. 20=mesh.mail"),
            )
        })?;
        let n: i64 = n.trim().parse().map_err(|_| {
            Error::new(
                ErrorKind::Io,
                format!("--unit {spec}: '{n}' is not a unit number"),
            )
        })?;
        let p = PathBuf::from(path);
        let p = if p.is_relative() && !p.exists() {
            base.join(p)
        } else {
            p
        };
        units.map.insert(n, p);
    }
    Ok(units)
}

/// A tolerance: a finite positive real.
fn parse_tole(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("'{s}' is not a positive real (e.g. 1e-4)")),
    }
}

fn run(
    file: &Path,
    db: Option<PathBuf>,
    unit_specs: &[String],
    tole_machine: Option<f64>,
) -> ExitCode {
    let cwd = PathBuf::from(".");
    let mut units = match parse_units(unit_specs, &cwd) {
        Ok(u) => u,
        Err(e) => return fail(&e, None),
    };
    let mut db = db;
    let mut mess_path = None;
    let comm = if file.extension().is_some_and(|e| e == "export") {
        match export::read_export(file) {
            Ok(exp) => {
                units
                    .protected
                    .push((file.to_path_buf(), "the export file of the run".into()));
                for (n, p) in &exp.units {
                    units.protected.push((
                        p.clone(),
                        format!("the input file of unit {n} in the export"),
                    ));
                    units.map.entry(*n).or_insert(p.clone());
                }
                // The result files the export names (F resu is unit 8); --unit wins.
                for (n, p) in &exp.results {
                    units.map.entry(*n).or_insert(p.clone());
                }
                // R base: the database (its directory created), unless --db says otherwise.
                if db.is_none() {
                    if let Some(base) = exp.database() {
                        if let Some(dir) = base.parent().filter(|d| !d.as_os_str().is_empty()) {
                            if let Err(e) = std::fs::create_dir_all(dir) {
                                return fail(
                                    &Error::new(
                                        ErrorKind::Io,
                                        format!("cannot create {} (R base): {e}", dir.display()),
                                    ),
                                    None,
                                );
                            }
                        }
                        db = Some(base);
                    }
                }
                mess_path = exp.mess.clone();
                exp.comm
            }
            Err(e) => return fail(&e, None),
        }
    } else {
        file.to_path_buf()
    };
    units.comm_file = Some(comm.clone());
    // The files the export asks the run to write from scratch: the message file and the
    // results file (unit 8, which IMPR_TABLE appends to). Never one of the run's inputs,
    // its database or another SQLite file.
    let fresh = [mess_path.clone(), units.map.get(&8).cloned()];
    for p in fresh.iter().flatten() {
        if let Err(e) = export::prepare_result_file(&units, p, db.as_deref(), &comm) {
            return fail(&e, None);
        }
    }
    let mess = match mess_path.as_deref().map(std::fs::File::create).transpose() {
        Ok(f) => f,
        Err(e) => {
            return fail(
                &Error::new(ErrorKind::Io, format!("cannot write the message file: {e}")),
                None,
            )
        }
    };
    let mut out = export::Tee::new(std::io::stdout(), mess);
    let opts = RunOptions {
        db,
        units,
        progress: std::io::stderr().is_terminal(),
        tole_machine,
    };
    let summary = match interp::run_file(&comm, opts, &mut out) {
        Ok(s) => s,
        Err(e) => {
            out.also_to_file(&lang::render_plain(&e, None));
            return fail(&e, None);
        }
    };
    if let Some(e) = &summary.error {
        let src = Source::read(&comm).ok().map(|(src, _)| src);
        eprintln!("{}", lang::render(e, src.as_ref()));
        out.also_to_file(&lang::render_plain(e, src.as_ref()));
        if let Some(db) = &summary.db {
            let line = format!(
                "the run stopped; every concept created before the failing command is kept in {}",
                db.display()
            );
            eprintln!("{line}");
            out.also_to_file(&line);
        }
        return ExitCode::from(EXIT_ERROR);
    }
    if summary.nook_count() > 0 {
        let line = format!("{} test(s) NOOK", summary.nook_count());
        eprintln!("{line}");
        out.also_to_file(&line);
        return ExitCode::from(EXIT_NOOK);
    }
    ExitCode::SUCCESS
}

fn check(file: &Path, db: Option<PathBuf>, unit_specs: &[String]) -> ExitCode {
    let mut units = match parse_units(unit_specs, &PathBuf::from(".")) {
        Ok(u) => u,
        Err(e) => return fail(&e, None),
    };
    let file = if file.extension().is_some_and(|e| e == "export") {
        match export::read_export(file) {
            Ok(exp) => {
                for (n, p) in exp.units {
                    units.map.entry(n).or_insert(p);
                }
                exp.comm
            }
            Err(e) => return fail(&e, None),
        }
    } else {
        file.to_path_buf()
    };
    let src = match Source::read(&file) {
        Ok((src, note)) => {
            if let Some(note) = note {
                println!("<A> <ENCODING_1> {note}");
            }
            src
        }
        Err(e) => return fail(&e, None),
    };
    units.comm_file = Some(file.clone());
    let errors = interp::check_source(&src, interp::CheckOptions { db, units });
    if errors.is_empty() {
        println!("{}: OK", file.display());
        return ExitCode::SUCCESS;
    }
    for e in &errors {
        eprintln!("{}", lang::render(e, Some(&src)));
    }
    eprintln!("{}: {} error(s)", file.display(), errors.len());
    ExitCode::from(EXIT_ERROR)
}

fn print_catalog(op: Option<&str>) -> ExitCode {
    match op {
        None => {
            print!("{}", catalog::summary());
            ExitCode::SUCCESS
        }
        Some(op) => match catalog::describe(&op.to_uppercase()) {
            Some(text) => {
                print!("{text}");
                ExitCode::SUCCESS
            }
            None => fail(
                &Error::validation(format!("unknown operator '{op}'"))
                    .hint("`aster-nl catalog` lists the operators"),
                None,
            ),
        },
    }
}

fn tables(db: &Path) -> ExitCode {
    let s = match store::Store::open_read_only(db) {
        Ok(s) => s,
        Err(e) => return fail(&e, None),
    };
    match store::listing(&s) {
        Ok(text) => {
            print!("{text}");
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e, None),
    }
}

fn accuracy(grid: GridArg, out: &Path, case: CaseArg) -> ExitCode {
    use aster_nl::accuracy::{self, CaseKind, GridSize};
    let size = match grid {
        GridArg::Small => GridSize::Small,
        GridArg::Full => GridSize::Full,
    };
    let kinds: &[CaseKind] = match case {
        CaseArg::Wall => &[CaseKind::Wall],
        CaseArg::Chain2 => &[CaseKind::Chain2],
        CaseArg::Both => &[CaseKind::Wall, CaseKind::Chain2],
    };
    if let Err(e) = std::fs::create_dir_all(out) {
        return fail(
            &Error::new(
                ErrorKind::Io,
                format!("cannot create {}: {e}", out.display()),
            ),
            None,
        );
    }
    for &kind in kinds {
        let mut progress = |m: &accuracy::Measurement| {
            let c = &m.config;
            eprintln!(
                "{} {:>9} H_l {:>2} H_nl {:>4} eta {:.0e} PREC_MAN {:.0e}: error {:.3e}, {:.2} s, {} branches{}",
                kind.name(),
                c.sweep,
                c.h_lin,
                c.h_nonl,
                c.regul,
                c.prec_man,
                m.max_rel_error,
                m.seconds,
                m.branches,
                m.failure.as_deref().map(|f| format!(" ({f})")).unwrap_or_default()
            );
        };
        let r = match accuracy::run_case(kind, size, &mut progress) {
            Ok(r) => r,
            Err(e) => return fail(&e, None),
        };
        let stem = out.join(format!("accuracy_{}", kind.name()));
        let md = accuracy::report::markdown(&r);
        let files = [
            (stem.with_extension("md"), md.clone()),
            (stem.with_extension("csv"), accuracy::report::csv(&r)),
        ];
        for (path, text) in files {
            if let Err(e) = std::fs::write(&path, text) {
                return fail(
                    &Error::new(
                        ErrorKind::Io,
                        format!("cannot write {}: {e}", path.display()),
                    ),
                    None,
                );
            }
        }
        if let Err(e) = accuracy::plot::plot(&r, &stem) {
            return fail(&e, None);
        }
        println!("{md}");
        println!("written: {}.{{md,csv,png,svg}}\n", stem.display());
    }
    ExitCode::SUCCESS
}
