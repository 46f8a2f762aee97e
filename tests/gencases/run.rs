//! One generated case end to end: write it, run the `aster-nl` binary on it with a timeout,
//! read its table back from the database, compute the references at chosen rows and give
//! the verdict.
//!
//! Verdicts:
//! - REACHED: exit 0, the table reaches the target energy, every compared row within its
//!   bound;
//! - SHORT: exit 0, every compared row within its bound, NB_BRANCHE spent before the target
//!   (the budget the user gave; not an error);
//! - STOPPED-CLEAR: exit 2 before the target, with an error naming MODE_NON_LINE;
//! - EXIT2-AFTER-COMPUTING: exit 2 although the table reaches the target (issue 34, point 1);
//! - WRONG: exit 0 with a compared row outside its bound, and the run said nothing of an
//!   error that large (the worst outcome);
//! - WRONG-ANNOUNCED: exit 0 with a compared row outside its bound, but within
//!   [`ANNOUNCED_FACTOR`] times the largest relative frequency error the run's alarm
//!   MODE_NON_LINE_1 estimated (the user was told how far off the rows may be, and which
//!   setting to refine): still outside the bound, counted apart from WRONG;
//! - CRASH (a panic, a signal, another exit code), TIMEOUT;
//! - REF-FAIL: a reference could not be computed (reported, never counted as right);
//! - MODEL?: the program's linear frequency differs from the reference model's by more than
//!   1e-6: a generator bug, the case says nothing about the engine.

use super::exact::OneDof;
use super::laws::{Kind, Shock};
use super::model::Model;
use super::sample::{Case, Law, Structure};
use super::shooting::{self, Dynamics, Orbit};
use super::write;
use rusqlite::Connection;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The reference at one energy and the bound a row there must meet.
#[derive(Debug, Clone)]
pub struct Reference {
    /// Frequency (Hz) of the regularised law's orbit at that ENERGIE.
    pub freq: f64,
    /// The nonsmooth law's (η = 0) frequency at the same ENERGIE.
    pub freq_nonsmooth: f64,
    /// For one DOF with PLAN or BI_PLAN: the closed form's frequency (η = 0).
    pub freq_exact: Option<f64>,
    pub accuracy: f64,
    pub slope: f64,
    pub tail_v: f64,
    pub tail_f: f64,
    pub tail_r: f64,
    pub ripple: f64,
    pub bound: f64,
}

/// Floor of every bound: the engine's Newton (PREC_NEWTON) and the reference's own accuracy
/// are far below; 1e-6 is what a comparison of two independent computations can promise.
pub const FLOOR: f64 = 1e-6;
/// Safety factor on the truncation estimates (each is an order of magnitude, not a bound).
pub const SAFETY: f64 = 3.0;

pub fn shock_of(case: &Case, model: &Model, regularised: bool) -> Shock {
    let kind = match case.law {
        Law::Plan => Kind::Plan,
        Law::BiPlan => Kind::BiPlan,
        Law::Cercle { centre } => Kind::Cercle { centre },
    };
    Shock {
        kind,
        px: model.shock_dofs.0,
        py: model.shock_dofs.1.unwrap_or(model.shock_dofs.0),
        gap: case.gap,
        alpha: case.rigi_nor,
        eta: case.para_regul * case.k_ref * case.gap * case.gap,
        regularised,
    }
}

/// The one-DOF oscillator of a case, if it is one.
pub fn one_dof(case: &Case, model: &Model) -> Option<OneDof> {
    (model.n == 1 && !matches!(case.law, Law::Cercle { .. })).then(|| OneDof {
        m: model.m[0],
        k: model.k[0],
        g: case.gap,
        alpha: case.rigi_nor,
    })
}

/// The reference at ENERGIE `energy`, Newton started from `guess`.
pub fn reference(
    case: &Case,
    model: &Model,
    guess: &Orbit,
    energy: f64,
) -> Result<Reference, String> {
    let reg = Dynamics::new(model, shock_of(case, model, true))?;
    let (o, accuracy) = shooting::solve_from(&reg, guess, energy)?;
    let de = 1e-3;
    let o2 = shooting::solve(&reg, &o, energy * (1.0 + de), 1e-11)?;
    let slope = (o2.freq() / o.freq()).ln() / (1.0 + de).ln();
    let t = shooting::tails(&reg, &o, case.h_lin, case.h_nonl)?;
    let smooth = Dynamics::new(model, shock_of(case, model, false))?;
    let o0 = shooting::solve(&smooth, &o, energy, 1e-10)?;
    let o0 = shooting::solve(&smooth, &o0, energy, 1e-12)?;
    let freq_exact = one_dof(case, model).map(|osc| match case.law {
        Law::Plan => 1.0 / osc.period_plan(energy),
        _ => 1.0 / osc.period_biplan(energy),
    });
    // The engine's ring law is eq. (12) (LOI_CERCLE='RAYON', the default the generated
    // files use), the law of this reference: no allowance for another regularisation.
    let bound = FLOOR
        + SAFETY * (t.tail_v + t.tail_f + t.tail_r + slope.abs() * t.ripple)
        + 10.0 * accuracy;
    Ok(Reference {
        freq: o.freq(),
        freq_nonsmooth: o0.freq(),
        freq_exact,
        accuracy,
        slope,
        tail_v: t.tail_v,
        tail_f: t.tail_f,
        tail_r: t.tail_r,
        ripple: t.ripple,
        bound,
    })
}

/// The reference at the row's FREQUENCE (the energy free, `shooting::solve_at_period`): the
/// comparison where ENERGIE folds or barely moves along the family, so that the orbit at
/// the row's ENERGIE sits on another part of the curve (a stiff stop at grazing), and where
/// the Newton at fixed ENERGIE stalls. The row's ENERGIE is compared with the orbit's, as
/// a frequency error through the slope d ln f / d ln E there: |ln(E_row/E)|·|slope|.
#[derive(Debug, Clone)]
pub struct AtFrequency {
    pub energy: f64,
    pub slope: f64,
    pub accuracy: f64,
    pub tail_v: f64,
    pub tail_f: f64,
    pub tail_r: f64,
    pub ripple: f64,
    pub bound: f64,
}

/// The reference orbit with the row's frequency, from the row's state.
pub fn reference_at_frequency(
    case: &Case,
    model: &Model,
    guess: &Orbit,
) -> Result<AtFrequency, String> {
    let reg = Dynamics::new(model, shock_of(case, model, true))?;
    let o1 = shooting::solve_at_period(&reg, &guess.u0, guess.tau, 1e-8)?;
    let o2 = shooting::solve_at_period(&reg, &o1.u0, guess.tau, 1e-10)?;
    let o3 = shooting::solve_at_period(&reg, &o2.u0, guess.tau, 1e-12)?;
    let (e2, e3) = (
        shooting::energy_of(&reg, &o2, 1e-12)?,
        shooting::energy_of(&reg, &o3, 1e-12)?,
    );
    let df = 1e-3;
    let o4 = shooting::solve_at_period(&reg, &o3.u0, guess.tau / (1.0 + df), 1e-12)?;
    let e4 = shooting::energy_of(&reg, &o4, 1e-12)?;
    let slope = (1.0 + df).ln() / (e4 / e3).ln();
    if !slope.is_finite() {
        return Err("the energy does not change with the frequency there".into());
    }
    let accuracy = (e3 / e2).ln().abs() * slope.abs();
    let t = shooting::tails(&reg, &o3, case.h_lin, case.h_nonl)?;
    let bound = FLOOR
        + SAFETY * (t.tail_v + t.tail_f + t.tail_r + slope.abs() * t.ripple)
        + 10.0 * accuracy;
    Ok(AtFrequency {
        energy: e3,
        slope,
        accuracy,
        tail_v: t.tail_v,
        tail_f: t.tail_f,
        tail_r: t.tail_r,
        ripple: t.ripple,
        bound,
    })
}

#[derive(Debug, Clone)]
pub struct Row {
    pub nume: i64,
    pub freq: f64,
    pub energy: f64,
}

#[derive(Debug, Clone)]
pub struct Compared {
    pub row: Row,
    pub reference: Result<Reference, String>,
    /// The reference at the row's frequency, computed when the one at its ENERGIE failed
    /// or put the row outside its bound.
    pub at_frequency: Option<Result<AtFrequency, String>>,
}

impl Compared {
    /// (error, bound) at equal ENERGIE, if that reference was computed.
    fn at_energy(&self) -> Option<(f64, f64)> {
        let r = self.reference.as_ref().ok()?;
        Some(((self.row.freq / r.freq - 1.0).abs(), r.bound))
    }
    /// (error, bound) at equal FREQUENCE, if that reference was computed.
    fn at_freq(&self) -> Option<(f64, f64)> {
        let a = self.at_frequency.as_ref()?.as_ref().ok()?;
        Some((
            (self.row.energy / a.energy).ln().abs() * a.slope.abs(),
            a.bound,
        ))
    }
    /// The comparison that judges the row: the one within its bound if either is, else
    /// the one with the smaller error over bound.
    pub fn judged(&self) -> Option<(f64, f64)> {
        match (self.at_energy(), self.at_freq()) {
            (Some(a), Some(b)) => Some(if a.0 / a.1 <= b.0 / b.1 { a } else { b }),
            (a, b) => a.or(b),
        }
    }
    pub fn error(&self) -> Option<f64> {
        self.judged().map(|(e, _)| e)
    }
    pub fn within(&self) -> Option<bool> {
        self.judged().map(|(e, b)| e <= b)
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Verdict {
    Reached,
    Short,
    StoppedClear,
    Exit2AfterComputing,
    Wrong,
    WrongAnnounced,
    Crash,
    Timeout,
    RefFail,
    Model,
}

impl Verdict {
    pub fn name(&self) -> &'static str {
        match self {
            Verdict::Reached => "REACHED",
            Verdict::Short => "SHORT",
            Verdict::StoppedClear => "STOPPED-CLEAR",
            Verdict::Exit2AfterComputing => "EXIT2-AFTER-COMPUTING",
            Verdict::Wrong => "WRONG",
            Verdict::WrongAnnounced => "WRONG-ANNOUNCED",
            Verdict::Crash => "CRASH",
            Verdict::Timeout => "TIMEOUT",
            Verdict::RefFail => "REF-FAIL",
            Verdict::Model => "MODEL?",
        }
    }
    pub const ALL: [Verdict; 10] = [
        Verdict::Reached,
        Verdict::Short,
        Verdict::StoppedClear,
        Verdict::Exit2AfterComputing,
        Verdict::Wrong,
        Verdict::WrongAnnounced,
        Verdict::Crash,
        Verdict::Timeout,
        Verdict::RefFail,
        Verdict::Model,
    ];
}

#[derive(Debug, Clone)]
pub struct Outcome {
    pub case: Case,
    pub verdict: Verdict,
    pub exit: Option<i32>,
    pub seconds: f64,
    pub rows: usize,
    /// Largest ENERGIE of the table over the first-contact energy.
    pub reach: f64,
    pub compared: Vec<Compared>,
    pub message: String,
    /// The largest |relative frequency error| the run's MODE_NON_LINE_1 alarms estimated
    /// ([`announced_error`]); None when no alarm gave one.
    pub announced: Option<f64>,
}

impl Outcome {
    /// The compared row with the largest error over its bound: (error, bound).
    pub fn worst(&self) -> Option<(f64, f64)> {
        self.compared
            .iter()
            .filter_map(Compared::judged)
            .max_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)))
    }

    /// One line for a test's report or failure: case, verdict, rows, reach, worst row and
    /// the run's last message.
    pub fn summary(&self) -> String {
        format!(
            "{}: {} ({} rows, reach {:.3e} E_c, worst {:?}) {}",
            self.case.name(),
            self.verdict.name(),
            self.rows,
            self.reach,
            self.worst(),
            self.message
        )
    }
}

fn read_rows(c: &Connection) -> Result<Vec<Row>, rusqlite::Error> {
    let mut st = c.prepare("SELECT NUME_ORDRE, FREQUENCE, ENERGIE FROM MNL ORDER BY NUME_ORDRE")?;
    let rows = st
        .query_map([], |r| {
            Ok(Row {
                nume: r.get(0)?,
                freq: r.get(1)?,
                energy: r.get(2)?,
            })
        })?
        .collect::<Result<Vec<_>, _>>()?;
    Ok(rows)
}

/// The row's displacement at t = 0 (sum of its cosine coefficients) in the model's DOFs.
fn start_of(c: &Connection, model: &Model, nume: i64) -> Result<Vec<f64>, rusqlite::Error> {
    let mut st = c.prepare(
        "SELECT NOEUD, NOM_CMP, SUM(COEF_C) FROM mnl_fourier WHERE concept = 'MNL' AND NUME_ORDRE = ?1 GROUP BY NOEUD, NOM_CMP",
    )?;
    let mut u = vec![0.0; model.n];
    let it = st.query_map([nume], |r| {
        Ok((
            r.get::<_, String>(0)?,
            r.get::<_, String>(1)?,
            r.get::<_, f64>(2)?,
        ))
    })?;
    for x in it {
        let (node, cmp, v) = x?;
        if let Some(i) = model.dofs.iter().position(|d| d.0 == node && d.1 == cmp) {
            u[i] = v;
        }
    }
    Ok(u)
}

/// The rows compared with the reference: the first reaching 1.5 E_c, the geometric middle
/// of that and the target, the target, and the last row; at most four, no repeats.
pub fn rows_to_compare(case: &Case, rows: &[Row]) -> Vec<usize> {
    let mut pick = Vec::new();
    let e1 = 1.5 * case.e_contact;
    for e in [e1, (e1 * case.e_target).sqrt(), case.e_target] {
        if let Some(i) = rows.iter().position(|r| r.energy >= e) {
            pick.push(i);
        }
    }
    if !rows.is_empty() {
        pick.push(rows.len() - 1);
    }
    pick.sort_unstable();
    pick.dedup();
    pick
}

/// Runs `bin run dir/name.comm --db dir/name.db` with a timeout, its output kept in
/// dir/name.out; (exit code, timed out, seconds, output).
pub fn run_binary(
    bin: &Path,
    dir: &Path,
    name: &str,
    timeout: Duration,
) -> (Option<i32>, bool, f64, String) {
    let out_path = dir.join(format!("{name}.out"));
    let Ok(out_file) = std::fs::File::create(&out_path) else {
        return (None, false, 0.0, "cannot create the output file".into());
    };
    let err_file = match out_file.try_clone() {
        Ok(f) => f,
        Err(e) => return (None, false, 0.0, e.to_string()),
    };
    let start = Instant::now();
    let child = Command::new(bin)
        .arg("run")
        .arg(dir.join(format!("{name}.comm")))
        .arg("--db")
        .arg(dir.join(format!("{name}.db")))
        .stdout(Stdio::from(out_file))
        .stderr(Stdio::from(err_file))
        .spawn();
    let mut child = match child {
        Ok(c) => c,
        Err(e) => {
            return (
                None,
                false,
                0.0,
                format!("cannot start {}: {e}", bin.display()),
            )
        }
    };
    let (code, timed_out) = loop {
        match child.try_wait() {
            Ok(Some(st)) => break (st.code(), false),
            Ok(None) if start.elapsed() > timeout => {
                let _ = child.kill();
                let _ = child.wait();
                break (None, true);
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(_) => break (None, false),
        }
    };
    let secs = start.elapsed().as_secs_f64();
    let text = std::fs::read_to_string(&out_path).unwrap_or_default();
    (code, timed_out, secs, text)
}

/// The last error line of the run's output (or its last line).
fn message_of(text: &str) -> String {
    text.lines()
        .rfind(|l| l.contains('×'))
        .or_else(|| text.lines().rev().find(|l| !l.trim().is_empty()))
        .unwrap_or("")
        .trim()
        .chars()
        .take(160)
        .collect()
}

/// Writes, runs and judges one case in `dir`.
pub fn judge(case: &Case, bin: &Path, dir: &Path, timeout: Duration) -> Outcome {
    let name = case.name();
    let mut outcome = Outcome {
        case: case.clone(),
        verdict: Verdict::Crash,
        exit: None,
        seconds: 0.0,
        rows: 0,
        reach: 0.0,
        compared: Vec::new(),
        message: String::new(),
        announced: None,
    };
    if let Err(e) = std::fs::write(dir.join(format!("{name}.comm")), write::comm(case))
        .and_then(|_| std::fs::write(dir.join(format!("{name}.mail")), write::mesh(case)))
    {
        outcome.message = format!("cannot write the case: {e}");
        return outcome;
    }
    let (code, timed_out, secs, text) = run_binary(bin, dir, &name, timeout);
    outcome.exit = code;
    outcome.seconds = secs;
    outcome.message = message_of(&text);
    outcome.announced = announced_error(&text);
    if timed_out {
        outcome.verdict = Verdict::Timeout;
        return outcome;
    }
    if text.contains("panicked") || !matches!(code, Some(0) | Some(2)) {
        outcome.verdict = Verdict::Crash;
        return outcome;
    }
    let model = Model::of(case);
    let Ok(c) = Connection::open(dir.join(format!("{name}.db"))) else {
        outcome.message = "no database".into();
        return outcome;
    };
    // The program's linear frequency against the reference model's.
    let f_mode: Option<f64> = c
        .query_row(
            "SELECT FREQ FROM modes WHERE concept = 'MODES' AND NUME_ORDRE = ?1",
            [case.mode as i64],
            |r| r.get(0),
        )
        .ok();
    if let Some(f) = f_mode {
        if (f / case.f_linear - 1.0).abs() > 1e-6 {
            outcome.verdict = Verdict::Model;
            outcome.message = format!("CALC_MODES {f} Hz, reference model {} Hz", case.f_linear);
            return outcome;
        }
    }
    let rows = read_rows(&c).unwrap_or_default();
    outcome.rows = rows.len();
    let emax = rows.iter().map(|r| r.energy).fold(0.0f64, f64::max);
    outcome.reach = emax / case.e_contact;
    let reached = emax >= case.e_target;
    for i in rows_to_compare(case, &rows) {
        let row = rows[i].clone();
        let guess = start_of(&c, &model, row.nume)
            .map_err(|e| e.to_string())
            .map(|u0| Orbit {
                u0,
                tau: 0.5 / row.freq,
            });
        let reference = guess
            .clone()
            .and_then(|g| reference(case, &model, &g, row.energy));
        let mut compared = Compared {
            row,
            reference,
            at_frequency: None,
        };
        if compared.within() != Some(true) {
            compared.at_frequency = Some(
                guess
                    .clone()
                    .and_then(|g| reference_at_frequency(case, &model, &g)),
            );
        }
        outcome.compared.push(compared);
    }
    let all_right = outcome.compared.iter().all(|c| c.within() == Some(true));
    let any_wrong = outcome.compared.iter().any(|c| c.within() == Some(false));
    let ref_fail = outcome.compared.iter().any(|c| c.within().is_none());
    // Every row outside its bound is within what the run announced.
    let announced = outcome.announced.is_some_and(|a| {
        outcome
            .compared
            .iter()
            .filter_map(Compared::judged)
            .filter(|(e, b)| e > b)
            .all(|(e, _)| e <= ANNOUNCED_FACTOR * a)
    });
    outcome.verdict = match code {
        Some(0) if any_wrong && announced => Verdict::WrongAnnounced,
        Some(0) if any_wrong => Verdict::Wrong,
        Some(0) if ref_fail => Verdict::RefFail,
        Some(0) if rows.is_empty() => Verdict::Crash,
        Some(0) if reached && all_right => Verdict::Reached,
        // MODE_NON_LINE ended before NB_BRANCHE with its alarm (why and where), rows
        // kept and the file run to its end: a clear stop, not a spent budget.
        Some(0) if !reached && text.contains("<MODE_NON_LINE_8>") => Verdict::StoppedClear,
        Some(0) => Verdict::Short,
        _ if reached => Verdict::Exit2AfterComputing,
        _ if text.contains('×') => Verdict::StoppedClear,
        _ => Verdict::Crash,
    };
    if ref_fail {
        if let Some(c) = outcome.compared.iter().find(|c| c.within().is_none()) {
            let at_freq = match &c.at_frequency {
                Some(Err(e)) => format!("; at its frequency: {e}"),
                _ => String::new(),
            };
            if let Err(e) = &c.reference {
                outcome.message = format!("reference: {e}{at_freq}");
            }
        }
    }
    outcome
}

/// How many times the run's estimated error a row may be off and still count as announced
/// (WRONG-ANNOUNCED): the estimate's displacement part is an interval [d1, 2·d1] around
/// which it prints the middle, so the error may be a third above it; twice covers that
/// and an estimate made at another row than the one compared.
pub const ANNOUNCED_FACTOR: f64 = 2.0;

/// The largest |relative frequency error| estimated in the run's output, from the alarm
/// MODE_NON_LINE_1's words "estimated relative frequency error at NUME_ORDRE n
/// (ENERGIE=e) ±x:".
pub fn announced_error(text: &str) -> Option<f64> {
    const KEY: &str = "estimated relative frequency error at NUME_ORDRE ";
    text.match_indices(KEY)
        .filter_map(|(i, _)| {
            let rest = &text[i + KEY.len()..];
            let after = &rest[rest.find(") ")? + 2..];
            after[..after.find(':')?].trim().parse::<f64>().ok()
        })
        .map(f64::abs)
        .reduce(f64::max)
}

/// Stiffness decade of a case, as printed in the summary ("1e0".."1e7").
pub fn decade(case: &Case) -> String {
    format!("1e{}", case.ratio.log10().floor() as i32)
}

/// NB_BRANCHE range of a case.
pub fn budget(case: &Case) -> &'static str {
    match case.nb_branche {
        0..=31 => "10-31",
        32..=99 => "32-99",
        100..=315 => "100-315",
        _ => "316-1000",
    }
}

/// Structure label: chain1..chain5, beam.
pub fn structure(case: &Case) -> String {
    match &case.structure {
        Structure::Chain { masses, .. } => format!("chain{}", masses.len()),
        Structure::Beam { .. } => "beam".into(),
    }
}
