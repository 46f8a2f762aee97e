//! Issue 34's long campaign: `cargo build --release && cargo run --release --example campaign
//! -- --cases 500 --seed 1 --jobs 1 [--timeout 60] [--first 0] [--bin target/release/aster-nl]
//! [--keep DIR]`. Generates the cases (tests/gencases), runs the release `aster-nl` binary
//! on each with a per-case timeout, compares the rows with the independent references and
//! prints one line per case and the counts per verdict and per family (law, structure,
//! stiffness decade RIGI_NOR/k_ref, NB_BRANCHE range). docs/hard_cases.md, "Generated
//! campaign", has the method and the figures.

#[path = "../tests/gencases/mod.rs"]
mod gencases;

use gencases::run::{self, Outcome, Verdict};
use gencases::sample;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Duration;

struct Options {
    cases: usize,
    first: usize,
    seed: u64,
    jobs: usize,
    timeout: f64,
    bin: PathBuf,
    keep: Option<PathBuf>,
}

fn options() -> Result<Options, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    // target/release/examples/campaign -> target/release/aster-nl
    let default_bin = exe
        .parent()
        .and_then(|p| p.parent())
        .map(|p| p.join("aster-nl"))
        .ok_or("cannot locate the aster-nl binary; give --bin")?;
    let mut o = Options {
        cases: 20,
        first: 0,
        seed: 1,
        jobs: 1,
        timeout: 60.0,
        bin: default_bin,
        keep: None,
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut i = 0;
    while i < args.len() {
        let v = args
            .get(i + 1)
            .ok_or(format!("{} needs a value", args[i]))?;
        let num = |s: &str| s.parse::<f64>().map_err(|e| format!("{}: {e}", args[i]));
        match args[i].as_str() {
            "--cases" => o.cases = num(v)? as usize,
            "--first" => o.first = num(v)? as usize,
            "--seed" => o.seed = num(v)? as u64,
            "--jobs" => o.jobs = (num(v)? as usize).max(1),
            "--timeout" => o.timeout = num(v)?,
            "--bin" => o.bin = PathBuf::from(v),
            "--keep" => o.keep = Some(PathBuf::from(v)),
            other => return Err(format!("unknown option {other}")),
        }
        i += 2;
    }
    if !o.bin.is_file() {
        return Err(format!(
            "{} not found: build it first (cargo build --release) or give --bin",
            o.bin.display()
        ));
    }
    Ok(o)
}

fn line(o: &Outcome) -> String {
    let c = &o.case;
    let (err, bound) = o.worst().unwrap_or((f64::NAN, f64::NAN));
    format!(
        "| {} | {} | {} | {} | {:.1e} | {:.0e} | {}/{} | {}x{} | {:+} | {:.2} | {} | {:.1} | {} | {:.3e} | {} | {:.1} | {:.1e} | {:.1e} | {} |",
        c.name(),
        run::structure(c),
        c.dofs(),
        c.law.name(),
        c.ratio,
        c.para_regul,
        c.h_lin,
        c.h_nonl,
        c.nb_branche,
        c.nb_pas_man,
        c.dir_evolution,
        c.coef_ampl,
        c.mode,
        c.e_target / c.e_contact,
        o.rows,
        o.reach,
        o.exit.map_or("-".into(), |e| e.to_string()),
        o.seconds,
        err,
        bound,
        o.verdict.name()
    )
}

fn count_table(title: &str, outcomes: &[Outcome], key: &dyn Fn(&Outcome) -> String) {
    let mut m: BTreeMap<String, BTreeMap<Verdict, usize>> = BTreeMap::new();
    for o in outcomes {
        *m.entry(key(o)).or_default().entry(o.verdict).or_default() += 1;
    }
    let used: Vec<Verdict> = Verdict::ALL
        .iter()
        .copied()
        .filter(|v| outcomes.iter().any(|o| o.verdict == *v))
        .collect();
    println!(
        "\n| {title} | cases | {} |",
        used.iter()
            .map(|v| v.name())
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!("|---|---|{}", "---|".repeat(used.len()));
    for (k, row) in &m {
        let total: usize = row.values().sum();
        let cells: Vec<String> = used
            .iter()
            .map(|v| row.get(v).copied().unwrap_or(0).to_string())
            .collect();
        println!("| {k} | {total} | {} |", cells.join(" | "));
    }
}

fn main() {
    let o = match options() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("campaign: {e}");
            std::process::exit(2);
        }
    };
    let tmp = match &o.keep {
        Some(d) => {
            if let Err(e) = std::fs::create_dir_all(d) {
                eprintln!("campaign: {}: {e}", d.display());
                std::process::exit(2);
            }
            None
        }
        None => match tempfile::tempdir() {
            Ok(t) => Some(t),
            Err(e) => {
                eprintln!("campaign: {e}");
                std::process::exit(2);
            }
        },
    };
    let dir = o.keep.clone().unwrap_or_else(|| {
        tmp.as_ref()
            .map(|t| t.path().to_path_buf())
            .unwrap_or_default()
    });
    println!(
        "campaign: {} cases from index {} of seed {}, {} job(s), timeout {} s, binary {}",
        o.cases,
        o.first,
        o.seed,
        o.jobs,
        o.timeout,
        o.bin.display()
    );
    println!("\n| case | structure | DOFs | law | RIGI_NOR/k | PARA_REGUL | H_l/H_nl | NB_BRANCHE x NB_PAS_MAN | DIR | COEF_AMPL | mode | target/E_c | rows | reach/E_c | exit | s | worst err | its bound | verdict |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let next = AtomicUsize::new(0);
    let done = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..o.jobs {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::SeqCst);
                if i >= o.cases {
                    break;
                }
                let case = sample::sample(o.seed, (o.first + i) as u64);
                let out = run::judge(&case, &o.bin, &dir, Duration::from_secs_f64(o.timeout));
                println!("{}", line(&out));
                if std::env::var_os("CAMPAIGN_DETAIL").is_some() {
                    for c in &out.compared {
                        println!(
                            "|  | row {} E {:e} F {:e}: {:?} |",
                            c.row.nume, c.row.energy, c.row.freq, c.reference
                        );
                        if let Some(a) = &c.at_frequency {
                            println!("|  | at its frequency: {a:?} |");
                        }
                        println!("|  | judged (error, bound): {:?} |", c.judged());
                    }
                }
                if !matches!(out.verdict, Verdict::Reached | Verdict::Short) {
                    println!("|  | {} |", out.message.replace('|', "/"));
                }
                if let Ok(mut d) = done.lock() {
                    d.push(out);
                }
            });
        }
    });
    let mut outcomes = done.into_inner().unwrap_or_default();
    outcomes.sort_by_key(|o| o.case.index);
    println!("\n## Summary");
    count_table("all", &outcomes, &|_| "all".into());
    count_table("law", &outcomes, &|o| o.case.law.name().into());
    count_table("structure", &outcomes, &|o| run::structure(&o.case));
    count_table("RIGI_NOR/k_ref", &outcomes, &|o| run::decade(&o.case));
    count_table("NB_BRANCHE", &outcomes, &|o| run::budget(&o.case).into());
    let secs: Vec<f64> = {
        let mut v: Vec<f64> = outcomes.iter().map(|o| o.seconds).collect();
        v.sort_by(f64::total_cmp);
        v
    };
    if !secs.is_empty() {
        println!(
            "\nrun time per case (aster-nl only): median {:.2} s, 90 % {:.2} s, max {:.2} s, total {:.0} s",
            secs[secs.len() / 2],
            secs[(secs.len() * 9) / 10],
            secs[secs.len() - 1],
            secs.iter().sum::<f64>()
        );
    }
    let worst_right = outcomes
        .iter()
        .filter(|o| matches!(o.verdict, Verdict::Reached | Verdict::Short))
        .filter_map(|o| o.worst())
        .map(|(e, _)| e)
        .fold(0.0f64, f64::max);
    println!("largest error of a row within its bound: {worst_right:.2e}");
}
