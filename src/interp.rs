//! Runs a command file: evaluate statements, validate each operator call against its
//! catalog, run it inside one store transaction, keep the score of TEST_* checks.
//!
//! `DEBUT`, `POURSUITE` and `FIN` are handled here because they open and close the store.
//! Every other operator goes through [`crate::ops::lookup`].

use crate::args::Args;
use crate::catalog;
use crate::check_groups::MeshGroups;
use crate::error::{Error, Result};
use crate::lang::{self, Env, Host, Source};
use crate::ops::{self, OpContext, TestOutcome, Units};
use crate::process;
use crate::store::Store;
use crate::table::Cell;
use crate::value::{CommandCall, ConceptRef, Keyword, Span, TableValue, Value};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How to run a file.
pub struct RunOptions {
    /// Database file; default `<case>.db` beside the command file.
    pub db: Option<PathBuf>,
    pub units: Units,
    /// Draw progress bars (only when stderr is a terminal).
    pub progress: bool,
    /// `--tole-machine X`: every real non-regression tolerance (VALE_CALC) is at least X,
    /// for files whose VALE_CALC another code computed. None: Code_Aster's semantics.
    pub tole_machine: Option<f64>,
}

/// The time one operator call took, as Code_Aster reports it per command: CPU (user +
/// system, this process) and elapsed.
#[derive(Debug, Clone)]
pub struct OperatorTime {
    pub operator: String,
    /// The concept it produced ("" for none).
    pub result: String,
    pub cpu: Duration,
    pub elapsed: Duration,
}

/// What a run did, for the FIN summary and the exit code.
#[derive(Debug, Default)]
pub struct RunSummary {
    /// Concepts created, in order: (name, type, operator).
    pub created: Vec<(String, String, String)>,
    pub tests: Vec<TestOutcome>,
    /// Time per operator call, in order.
    pub timings: Vec<OperatorTime>,
    /// Database used, if any was opened.
    pub db: Option<PathBuf>,
    /// The error that stopped the run, if any.
    pub error: Option<Error>,
    /// FIN() was reached.
    pub finished: bool,
}

impl RunSummary {
    pub fn nook_count(&self) -> usize {
        self.tests.iter().filter(|t| !t.ok).count()
    }
    pub fn ok_count(&self) -> usize {
        self.tests.iter().filter(|t| t.ok).count()
    }
}

/// DEBUT/POURSUITE keywords accepted for compatibility with Code_Aster files that have no
/// effect in aster-nl; the run says so when a file gives them. IGNORE_ALARM and
/// ERREUR/ALARME have an effect and are not listed.
const DEBUT_NO_EFFECT: &[&str] = &[
    "CODE",
    "DEBUG",
    "PAR_LOT",
    "MEMOIRE",
    "RESERVE_CPU",
    "RESERVE_MEMOIRE",
    "LANG",
    "IMPR_MACRO",
    "ERREUR",
    "FORMAT_HDF",
    "BASE",
    "CATALOGUE",
    "MESURE_TEMPS",
    "HDF",
    "INFO",
];

/// `KEY` for a simple keyword, `KEY/SUB` for each keyword given inside a factor
/// (`CODE='OUI'`, the plain-value form of a factor, is `CODE`), of the keywords in `names`
/// that the call gives, in the call's order. ERREUR/ALARME is left out: it has an effect.
fn given_no_effect(call: &CommandCall, names: &[&str]) -> Vec<String> {
    fn occurrences(v: &Value) -> Vec<&[Keyword]> {
        match v {
            Value::Fact(k) => vec![k.as_slice()],
            Value::Seq(items) => items.iter().flat_map(occurrences).collect(),
            _ => Vec::new(),
        }
    }
    let mut out: Vec<String> = Vec::new();
    for a in call
        .args
        .iter()
        .filter(|a| names.contains(&a.name.as_str()))
    {
        let occ = occurrences(&a.value);
        if occ.is_empty() {
            out.push(a.name.clone());
            continue;
        }
        for k in occ.into_iter().flatten() {
            if a.name == "ERREUR" && k.name == "ALARME" {
                continue;
            }
            let key = format!("{}/{}", a.name, k.name);
            if !out.contains(&key) {
                out.push(key);
            }
        }
    }
    out
}

/// The line printed at the start of a run and in the FIN summary under `--tole-machine`.
fn tole_machine_note(t: f64) -> String {
    format!(
        "--tole-machine {t:e}: every real non-regression tolerance (VALE_CALC) is at least {t:e} \
         (files whose VALE_CALC another code computed); references (VALE_REFE) keep their PRECISION"
    )
}

struct Runner<'o> {
    file: String,
    default_db: PathBuf,
    units: Units,
    progress: bool,
    store: Option<Store>,
    ignored_alarms: Vec<String>,
    alarms_are_errors: bool,
    tole_machine: Option<f64>,
    summary: RunSummary,
    out: &'o mut dyn Write,
}

impl Runner<'_> {
    fn store(&self) -> Result<&Store> {
        self.store.as_ref().ok_or_else(|| {
            Error::validation("no study is open").hint(
                "a command file starts with DEBUT() (new study) or POURSUITE() (continue one)",
            )
        })
    }

    fn start_study(&mut self, call: &CommandCall, args: &Args) -> Result<Value> {
        if self.store.is_some() {
            return Err(Error::validation(format!(
                "{} may only appear once, at the start of the file",
                call.op
            )));
        }
        let purpose = format!("{} (started {})", self.file, started_at());
        let store = if call.op == "DEBUT" {
            Store::create_for(&self.default_db, &purpose)?
        } else {
            Store::open_for(&self.default_db, &purpose)?
        };
        if call.op == "POURSUITE" {
            let n = store.concepts()?.len();
            writeln!(
                self.out,
                "POURSUITE: continuing {} with {n} concept(s)",
                self.default_db.display()
            )?;
        }
        self.summary.db = Some(self.default_db.clone());
        self.store = Some(store);
        if let Some(alarms) = args.texts("IGNORE_ALARM") {
            self.ignored_alarms = alarms;
        }
        self.alarms_are_errors = args
            .fact("ERREUR")
            .and_then(|e| e.text("ALARME"))
            .is_some_and(|a| a == "EXCEPTION");
        if self.alarms_are_errors {
            writeln!(
                self.out,
                "{}: ERREUR/ALARME='EXCEPTION': an alarm not silenced by IGNORE_ALARM stops the run as an error",
                call.op
            )?;
        }
        let no_effect = given_no_effect(call, DEBUT_NO_EFFECT);
        if !no_effect.is_empty() {
            writeln!(
                self.out,
                "{}: keyword(s) {} accepted for compatibility, no effect in aster-nl",
                call.op,
                no_effect.join(", ")
            )?;
        }
        Ok(Value::None)
    }

    fn finish(&mut self) -> Result<Value> {
        // The study on disk before the run says it is done (store::Durability).
        if let Some(store) = self.store.as_mut() {
            store.close()?;
        }
        self.summary.finished = true;
        let s = &self.summary;
        let mut text = String::new();
        text.push_str("\n==================== FIN ====================\n");
        text.push_str(&format!("concepts created: {}\n", s.created.len()));
        for (name, ty, op) in &s.created {
            text.push_str(&format!("  {name:<16} {ty:<20} {op}\n"));
        }
        text.push_str(&format!(
            "tests: {} OK, {} NOOK\n",
            s.ok_count(),
            s.nook_count()
        ));
        if let Some(t) = self.tole_machine {
            text.push_str(&format!("{}\n", tole_machine_note(t)));
        }
        text.push_str("time per operator (CPU: user + system; elapsed):\n");
        let mut per_op: BTreeMap<&str, (usize, Duration, Duration)> = BTreeMap::new();
        for t in &s.timings {
            let e = per_op.entry(t.operator.as_str()).or_default();
            e.0 += 1;
            e.1 += t.cpu;
            e.2 += t.elapsed;
        }
        for (op, (n, cpu, wall)) in per_op {
            text.push_str(&format!(
                "  {op:<18} {n:>4} call(s)  CPU {:>9.4} s  elapsed {:>9.4} s\n",
                cpu.as_secs_f64(),
                wall.as_secs_f64()
            ));
        }
        if let Some(db) = &s.db {
            text.push_str(&format!("results: {}\n", db.display()));
        }
        write!(self.out, "{text}")?;
        Ok(Value::None)
    }

    fn run_operator(&mut self, call: &CommandCall, args: &Args) -> Result<Value> {
        let op_fn = ops::lookup(&call.op).ok_or_else(|| {
            Error::internal(format!(
                "{} is in the catalog but aster-nl does not implement it yet",
                call.op
            ))
        })?;
        let store = self.store.as_ref().ok_or_else(|| {
            Error::validation("no study is open").hint(
                "a command file starts with DEBUT() (new study) or POURSUITE() (continue one)",
            )
        })?;
        // INFO: the catalog's default where the operator has the keyword; an operator
        // without it (TEST_*, DEFI_MATERIAU...) reports at the ordinary level.
        let info = args.int("INFO").unwrap_or(1);
        let mut tests = Vec::new();
        // Every concept given to the operator must still be what it was computed from
        // (checked in the operator's transaction).
        let used = concept_arguments(args);
        let started = Instant::now();
        let cpu_started = process::self_cpu();
        let mut ctx = OpContext::new(store, &call.op, &mut *self.out, &self.units, &mut tests);
        ctx.result = call.result.as_deref();
        ctx.reuse = call.reuse.as_ref().map(|c| c.name.as_str());
        ctx.file = &self.file;
        ctx.line = call.span.line;
        ctx.info = info;
        ctx.ignored_alarms = &self.ignored_alarms;
        ctx.alarms_are_errors = self.alarms_are_errors;
        ctx.tole_machine = self.tole_machine;
        ctx.progress = self.progress;
        let outcome = ops::run_checked_in_transaction(op_fn, &mut ctx, args, &used);
        let created = std::mem::take(&mut ctx.created);
        let value = ctx.value.take();
        let deferred = ctx.deferred_error.take();
        let elapsed = started.elapsed();
        let cpu = Duration::from_secs_f64((process::self_cpu() - cpu_started).max(0.0));
        // TEST_* lines are printed by the operators; keep the score even if it failed later.
        self.summary.tests.extend(tests);
        outcome?;
        self.summary.timings.push(OperatorTime {
            operator: call.op.clone(),
            result: call.result.clone().unwrap_or_default(),
            cpu,
            elapsed,
        });
        for (name, ty) in &created {
            self.summary
                .created
                .push((name.clone(), ty.clone(), call.op.clone()));
        }
        if let Some(reused) = &ctx_reuse_name(call) {
            // Changed in place: what was computed from it no longer matches.
            store.new_generation(reused)?;
        }
        if let Some(e) = deferred {
            // The operator's results are committed; the run still stops here.
            return Err(e);
        }
        if let Some(v) = value {
            return Ok(v);
        }
        let bound = call
            .result
            .as_ref()
            .or(call.reuse.as_ref().map(|c| &c.name));
        match bound {
            Some(name) => {
                let ty = created
                    .iter()
                    .find(|(n, _)| n == name)
                    .map(|(_, t)| t.clone())
                    .or_else(|| store.concept_type(name).ok().flatten());
                Ok(match ty {
                    Some(ty) => Value::Concept(ConceptRef {
                        name: name.clone(),
                        ty,
                    }),
                    None => Value::None,
                })
            }
            None => Ok(Value::None),
        }
    }
}

impl Host for Runner<'_> {
    fn is_operator(&self, name: &str) -> bool {
        catalog::get(name).is_some()
    }

    fn map_file(&mut self, path: &str) -> Result<i64> {
        self.units.map_named_file(path)
    }

    fn function_value(&mut self, function: &ConceptRef, x: f64) -> Result<Value> {
        let f = crate::store::function::load_any_function(self.store()?, &function.name)?;
        Ok(Value::Real(f.eval(x)?))
    }

    fn result_method(
        &mut self,
        result: &ConceptRef,
        method: crate::value::ResultMethod,
    ) -> Result<Value> {
        let (v, lines) = ops::common::result_api::call(self.store()?, &result.name, method)?;
        for l in lines {
            let _ = writeln!(self.out, "{l}");
        }
        Ok(v)
    }

    fn save_text(&mut self, path: &str, text: &str) -> Result<()> {
        let written = ops::common::output::write_named_file(&self.units, path, text)?;
        let _ = writeln!(self.out, "np.savetxt: {} written", written.display());
        Ok(())
    }

    fn record_test(&mut self, ok: bool, line: &str) {
        let _ = writeln!(self.out, "{line}");
        self.summary.tests.push(ops::TestOutcome {
            ok,
            line: line.to_string(),
        });
    }

    fn operator_names(&self) -> Vec<String> {
        catalog::operator_names()
            .into_iter()
            .map(str::to_string)
            .collect()
    }

    fn unsupported_operator(&self, name: &str) -> Option<String> {
        catalog::unsupported(name).map(str::to_string)
    }

    fn lookup_concept(&self, name: &str) -> Option<ConceptRef> {
        let store = self.store.as_ref()?;
        let ty = store.concept_type(name).ok().flatten()?;
        Some(ConceptRef {
            name: name.to_string(),
            ty,
        })
    }

    fn warn(&mut self, id: &str, text: &str) {
        if !self.ignored_alarms.iter().any(|a| a == id) {
            let _ = writeln!(self.out, "<A> <{id}> {text}");
        }
    }

    fn table_contents(&mut self, table: &ConceptRef) -> Result<Value> {
        let t = crate::store::table::load_table(self.store()?, &table.name)?;
        let rows = t
            .rows
            .iter()
            .map(|r| {
                r.iter()
                    .map(|c| match c {
                        Cell::Null => Value::None,
                        Cell::R(x) => Value::Real(*x),
                        Cell::I(i) => Value::Int(*i),
                        Cell::K(s) => Value::Str(s.clone()),
                    })
                    .collect()
            })
            .collect();
        Ok(Value::Table(std::sync::Arc::new(TableValue {
            name: table.name.clone(),
            columns: t.columns.iter().map(|c| c.name.clone()).collect(),
            rows,
        })))
    }

    fn call(&mut self, call: CommandCall) -> Result<Value> {
        if self.summary.finished {
            return Ok(Value::None);
        }
        let args = catalog::validate(&call, &self.file).map_err(|errors| {
            // Report every problem of the call; stop on the first.
            let mut errors = errors.into_iter();
            let first = errors
                .next()
                .unwrap_or_else(|| Error::validation("invalid call"));
            for e in errors {
                let _ = writeln!(self.out, "{e}");
            }
            first
        })?;
        if self.store.is_none() && !matches!(call.op.as_str(), "DEBUT" | "POURSUITE") {
            return Err(Error::validation(format!(
                "{} before DEBUT() or POURSUITE()",
                call.op
            ))
            .at(&self.file, call.op_span)
            .hint("a command file starts with DEBUT() (new study) or POURSUITE() (continue one)"));
        }
        let result = match call.op.as_str() {
            "DEBUT" | "POURSUITE" => self.start_study(&call, &args),
            "FIN" => self.finish(),
            _ => {
                let _ = self.store()?;
                self.run_operator(&call, &args)
            }
        };
        result.map_err(|e| at_keyword(e, &args, &self.file, call.op_span))
    }
}

/// An operator's error, located: the keyword it names (in whatever style the operator or the
/// engine wrote it) in one style, `OP/FACT[i]/KEY`, at the span where the user wrote that
/// keyword; an error naming no keyword, or one not in the call, falls back to the
/// operator's name. A location the operator set itself (a mesh file's line) is kept.
fn at_keyword(mut e: Error, args: &Args, file: &str, op_span: Span) -> Error {
    let (keyword, span) = match e.keyword.take() {
        Some(k) => args.locate(&k),
        None => (args.path.clone(), None),
    };
    e.keyword = Some(keyword);
    e.at(file, span.unwrap_or(op_span))
}

/// Now, as seconds since the Unix epoch (what the lock file records; no time zone needed).
fn started_at() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    format!("at Unix time {secs}")
}

/// Run a command file. Errors that stop the run are in `RunSummary::error`; the
/// `Err` case is reserved for failures before anything ran (unreadable file).
pub fn run_file(path: &Path, opts: RunOptions, out: &mut dyn Write) -> Result<RunSummary> {
    let (src, note) = Source::read(path)?;
    if let Some(note) = note {
        writeln!(out, "<A> <ENCODING_1> {note}")?;
    }
    let default_db = opts.db.clone().unwrap_or_else(|| path.with_extension("db"));
    let mut units = opts.units;
    units.comm_file.get_or_insert_with(|| path.to_path_buf());
    units
        .protected
        .push((path.to_path_buf(), "the command file of the run".into()));
    run_source(
        &src,
        default_db,
        units,
        opts.progress,
        opts.tole_machine,
        out,
    )
}

/// Run source text (the file name in `src` is used in messages and in the `concepts` table).
pub fn run_source(
    src: &Source,
    db: PathBuf,
    units: Units,
    progress: bool,
    tole_machine: Option<f64>,
    out: &mut dyn Write,
) -> Result<RunSummary> {
    let program = match lang::parse(src) {
        Ok(p) => p,
        Err(e) => {
            return Ok(RunSummary {
                error: Some(e),
                ..RunSummary::default()
            })
        }
    };
    let mut units = units;
    units
        .protected
        .push((db.clone(), "the database of the study".into()));
    units.protected.push((
        crate::store::study_file::lock_path(&db),
        "the lock file of the study".into(),
    ));
    for j in crate::store::study_file::journal_paths(&db) {
        units
            .protected
            .push((j, "a journal of the study's database".into()));
    }
    let mut runner = Runner {
        file: src.name.clone(),
        default_db: db,
        units,
        progress,
        store: None,
        ignored_alarms: Vec::new(),
        alarms_are_errors: false,
        tole_machine,
        summary: RunSummary::default(),
        out,
    };
    if let Some(t) = tole_machine {
        let _ = writeln!(runner.out, "{}", tole_machine_note(t));
    }
    let mut env = Env::default();
    if let Err(e) = lang::execute(&program, src, &mut env, &mut runner) {
        runner.summary.error = Some(e);
    } else if !runner.summary.finished && runner.store.is_some() {
        // Code_Aster closes the study at the end of the file even without FIN().
        let _ = writeln!(runner.out, "note: no FIN() at the end of the file");
    }
    Ok(runner.summary)
}

/// How to check a file.
#[derive(Default)]
pub struct CheckOptions {
    /// Database a POURSUITE file continues (default: `<case>.db` beside the file).
    pub db: Option<PathBuf>,
    /// Logical units, to check the mesh files LIRE_MAILLAGE would read.
    pub units: Units,
}

/// A host for `check`: validates every call, runs nothing, collects all errors.
struct Checker {
    file: String,
    errors: Vec<Error>,
    /// Concepts the file would create, or that the continued database holds: name -> type.
    concepts: BTreeMap<String, String>,
    /// The database a POURSUITE continues (opened read-only in effect: only queried).
    store: Option<Store>,
    /// Concepts that come from `store` (not created by this file).
    from_db: Vec<String>,
    /// POURSUITE without a database: names no statement binds are taken as concepts of an
    /// unknown type (one error says so) rather than reported one by one.
    names_unknown: bool,
    default_db: PathBuf,
    explicit_db: Option<PathBuf>,
    units: Units,
    /// The meshes the file reads and the groups its calls create (GROUP_NO/GROUP_MA names).
    groups: MeshGroups,
}

impl Checker {
    fn start(&mut self, call: &CommandCall) {
        if call.op != "POURSUITE" {
            return;
        }
        let path = self
            .explicit_db
            .clone()
            .unwrap_or_else(|| self.default_db.clone());
        match Store::open(&path) {
            Ok(store) => match store.concepts() {
                Ok(list) => {
                    for c in list {
                        if c.ty == "maillage_sdaster" {
                            match crate::store::mesh::load_mesh(&store, &c.name) {
                                Ok(m) => self.groups.add(&c.name, m),
                                Err(_) => self.groups.give_up(),
                            }
                        }
                        self.from_db.push(c.name.clone());
                        self.concepts.insert(c.name, c.ty);
                    }
                    self.store = Some(store);
                }
                Err(e) => self.errors.push(e.at(&self.file, call.op_span)),
            },
            Err(_) => {
                self.names_unknown = true;
                self.groups.give_up();
                self.errors.push(
                    Error::validation(format!(
                        "no database to continue at {}: the concepts this file takes from an \
                         earlier run cannot be checked",
                        path.display()
                    ))
                    .at(&self.file, call.op_span)
                    .keyword("POURSUITE")
                    .hint("give the database: aster-nl check FILE --db STUDY.db"),
                );
            }
        }
    }

    /// Problems a run would meet that the file and the database show without running:
    /// a mesh file that is missing or of the wrong kind, a restart row that the stored
    /// table does not have.
    fn static_checks(&mut self, call: &CommandCall, args: &Args) {
        let at = |e: Error| e.at(&self.file, call.op_span);
        match call.op.as_str() {
            "LIRE_MAILLAGE" => {
                // FORMAT and UNITE: the catalog's defaults; absent here only when the
                // file computes them (known when it runs), and then checked by the run.
                let format = args
                    .text("FORMAT")
                    .and_then(crate::mesh::MeshFormat::from_keyword);
                let (Some(format), Some(unit)) = (format, args.int("UNITE")) else {
                    self.groups.give_up();
                    return;
                };
                match ops::lire_maillage::resolve_file(&self.units, unit, format) {
                    Ok((path, _)) => {
                        if let Some(e) = mesh_file_problem(&path, format) {
                            self.groups.give_up();
                            self.errors
                                .push(at(e.keyword(format!("{}/FORMAT", call.op))));
                            return;
                        }
                        // Read as the run reads it: its errors now, its groups for the
                        // GROUP_NO/GROUP_MA names of later calls.
                        match (
                            crate::mesh::read_file(&path, format, args.text("NOM_MED")),
                            &call.result,
                        ) {
                            (Ok(mesh), Some(name)) => self.groups.add(name, mesh),
                            (Ok(_), None) => self.groups.give_up(),
                            (Err(e), _) => {
                                self.groups.give_up();
                                self.errors.push(at(e));
                            }
                        }
                    }
                    Err(e) => {
                        self.groups.give_up();
                        self.errors
                            .push(at(e.keyword(format!("{}/UNITE", call.op))))
                    }
                }
            }
            "MODE_NON_LINE" | "REST_MODE_NONL" | "CALC_STABILITE" => {
                let (table, rows, key) = match call.op.as_str() {
                    "MODE_NON_LINE" => {
                        let Some(etat) = args.fact("ETAT_INIT") else {
                            return;
                        };
                        (
                            etat.concept("MODE_NON_LINE").map(|c| c.name.clone()),
                            etat.int("NUME_ORDRE").into_iter().collect::<Vec<_>>(),
                            "ETAT_INIT/NUME_ORDRE",
                        )
                    }
                    "REST_MODE_NONL" => (
                        args.concept("MODE_NON_LINE").map(|c| c.name.clone()),
                        args.int("NUME_ORDRE").into_iter().collect(),
                        "NUME_ORDRE",
                    ),
                    _ => (
                        args.concept("MODE_NON_LINE").map(|c| c.name.clone()),
                        args.fact("FILTRE")
                            .and_then(|f| f.ints("NUME_ORDRE"))
                            .unwrap_or_default(),
                        "FILTRE/NUME_ORDRE",
                    ),
                };
                let (Some(table), Some(store)) = (table, self.store.as_ref()) else {
                    return;
                };
                if !self.from_db.contains(&table) || rows.is_empty() {
                    return;
                }
                let Ok(t) = crate::store::table::load_table(store, &table) else {
                    return;
                };
                let Ok(col) = t.req_col("NUME_ORDRE") else {
                    return;
                };
                let present: Vec<i64> = t
                    .rows
                    .iter()
                    .filter_map(|r| r.get(col).and_then(|c| c.as_f64()))
                    .map(|x| x as i64)
                    .collect();
                for n in rows.iter().filter(|n| !present.contains(n)) {
                    let (lo, hi) = (
                        present.iter().min().copied().unwrap_or(0),
                        present.iter().max().copied().unwrap_or(0),
                    );
                    self.errors.push(at(Error::validation(format!(
                        "NUME_ORDRE {n} is not a row of table {table} in the database (rows {lo}..{hi})"
                    ))
                    .keyword(format!("{}/{key}", call.op))));
                }
            }
            _ => {}
        }
    }
}

/// The concepts an operator creates beside its result, under names derived from it: the
/// shocks' table `<result>_CHOC` of a DYNA_VIBRA (or DYNA_TRAN_MODAL) with shocks.
fn owned_outputs(op: &str, args: &Args, result: &str) -> Vec<(String, String)> {
    let shocks = args.has("COMPORTEMENT") || args.has("CHOC");
    if matches!(op, "DYNA_VIBRA" | "DYNA_TRAN_MODAL") && shocks {
        vec![(
            crate::store::tran_gene::shock_table_name(result),
            "table_sdaster".to_string(),
        )]
    } else {
        Vec::new()
    }
}

/// Why a mesh file cannot be read in `format`, as far as its first bytes show.
fn mesh_file_problem(path: &Path, format: crate::mesh::MeshFormat) -> Option<Error> {
    use std::io::Read;
    let mut head = [0u8; 8];
    let n = std::fs::File::open(path)
        .and_then(|mut f| f.read(&mut head))
        .ok()?;
    let hdf5 = n == 8 && head == *b"\x89HDF\r\n\x1a\n";
    match format {
        crate::mesh::MeshFormat::Med if !hdf5 => Some(
            Error::input(format!(
                "{} is not a MED file (MED files are HDF5 files)",
                path.display()
            ))
            .hint("FORMAT='ASTER' reads .mail files, FORMAT='GMSH' .msh files"),
        ),
        crate::mesh::MeshFormat::Aster | crate::mesh::MeshFormat::Gmsh if hdf5 => Some(
            Error::input(format!("{} is a MED (HDF5) file", path.display()))
                .hint("read it with FORMAT='MED'"),
        ),
        _ => None,
    }
}

impl Host for Checker {
    fn is_operator(&self, name: &str) -> bool {
        catalog::get(name).is_some()
    }
    fn map_file(&mut self, path: &str) -> Result<i64> {
        self.units.map_named_file(path)
    }
    fn function_value(&mut self, _function: &ConceptRef, _x: f64) -> Result<Value> {
        Ok(Value::Unknown)
    }
    /// `check` runs no operator: an assertion that could be evaluated is not a test.
    fn record_test(&mut self, _ok: bool, _line: &str) {}
    /// A result's values exist only when the file runs.
    fn result_method(
        &mut self,
        _result: &ConceptRef,
        _method: crate::value::ResultMethod,
    ) -> Result<Value> {
        Ok(Value::Unknown)
    }
    /// `check` writes nothing.
    fn save_text(&mut self, _path: &str, _text: &str) -> Result<()> {
        Ok(())
    }
    fn operator_names(&self) -> Vec<String> {
        catalog::operator_names()
            .into_iter()
            .map(str::to_string)
            .collect()
    }

    fn unsupported_operator(&self, name: &str) -> Option<String> {
        catalog::unsupported(name).map(str::to_string)
    }
    fn lookup_concept(&self, name: &str) -> Option<ConceptRef> {
        match self.concepts.get(name) {
            Some(ty) => Some(ConceptRef {
                name: name.to_string(),
                ty: ty.clone(),
            }),
            None if self.names_unknown => Some(ConceptRef {
                name: name.to_string(),
                ty: catalog::UNKNOWN_CONCEPT_TYPE.to_string(),
            }),
            None => None,
        }
    }
    fn table_contents(&mut self, _table: &ConceptRef) -> Result<Value> {
        // Nothing runs: the rows are known only when the file runs.
        Ok(Value::Unknown)
    }
    fn recover(&mut self, error: &Error) -> bool {
        // Every error of the file, in one pass: what failed is carried on as unknown. A
        // loop body is checked once per item: its errors are reported once.
        let seen = self
            .errors
            .iter()
            .any(|e| e.message == error.message && e.location == error.location);
        if !seen {
            self.errors.push(error.clone());
        }
        true
    }
    fn call(&mut self, call: CommandCall) -> Result<Value> {
        self.start(&call);
        match catalog::validate(&call, &self.file) {
            Ok(args) => {
                self.static_checks(&call, &args);
                self.groups.note_created(&call.op, &args);
                for (e, span) in self.groups.unknown_names(&args) {
                    self.errors.push(e.at(&self.file, span));
                }
                let outputs = catalog::get(&call.op)
                    .map(|def| co_outputs(&def.simp, &def.fact, &args))
                    .unwrap_or_default();
                for (name, ty) in outputs {
                    self.concepts.insert(name, ty);
                }
                let ty = catalog::result_type(&call.op, &args);
                match (&call.result, ty) {
                    (Some(name), Some(ty)) if !matches!(ty.as_str(), "R" | "I" | "TXM") => {
                        self.concepts.insert(name.clone(), ty.clone());
                        self.from_db.retain(|n| n != name);
                        for (owned, ty) in owned_outputs(&call.op, &args, name) {
                            self.concepts.insert(owned, ty);
                        }
                        Ok(Value::Concept(ConceptRef {
                            name: name.clone(),
                            ty,
                        }))
                    }
                    // A plain value (EXTR_TABLE...) is only known when the file runs.
                    (_, Some(ty)) if matches!(ty.as_str(), "R" | "I" | "TXM") => Ok(Value::Unknown),
                    _ => Ok(Value::None),
                }
            }
            Err(errors) => {
                self.errors.extend(errors);
                // Keep going so that every error of the file is reported; bind the name to
                // a concept of the type the operator would have produced.
                let ty = catalog::get(&call.op).and_then(|d| d.result.clone());
                match (&call.result, ty) {
                    (Some(name), Some(ty)) => {
                        self.concepts.insert(name.clone(), ty.clone());
                        Ok(Value::Concept(ConceptRef {
                            name: name.clone(),
                            ty,
                        }))
                    }
                    _ => Ok(Value::None),
                }
            }
        }
    }
}

/// Check a file without running it: every syntax and validation error, all together,
/// and what the file and the continued database show statically (mesh files, restart
/// rows).
pub fn check_source(src: &Source, opts: CheckOptions) -> Vec<Error> {
    let program = match lang::parse(src) {
        Ok(p) => p,
        Err(e) => return vec![e],
    };
    let mut units = opts.units;
    units
        .comm_file
        .get_or_insert_with(|| PathBuf::from(&src.name));
    let mut checker = Checker {
        file: src.name.clone(),
        errors: Vec::new(),
        concepts: BTreeMap::new(),
        store: None,
        from_db: Vec::new(),
        names_unknown: false,
        default_db: Path::new(&src.name).with_extension("db"),
        explicit_db: opts.db,
        units,
        groups: MeshGroups::default(),
    };
    let mut env = Env::default();
    if let Err(e) = lang::execute(&program, src, &mut env, &mut checker) {
        checker.errors.push(e);
    }
    checker.errors
}

/// Names of the concepts given to a call (every keyword, at every level).
fn concept_arguments(args: &Args) -> Vec<String> {
    fn walk(v: &Value, out: &mut Vec<String>) {
        match v {
            Value::Concept(c) => out.push(c.name.clone()),
            Value::Seq(items) => items.iter().for_each(|i| walk(i, out)),
            _ => {}
        }
    }
    let mut out = Vec::new();
    for (_, v, _) in &args.simple {
        walk(v, &mut out);
    }
    for (_, occurrences, _) in &args.factor {
        for occ in occurrences {
            out.extend(concept_arguments(occ));
        }
    }
    out.sort();
    out.dedup();
    out
}

/// The concept a call changes in place (`reuse=`), if any.
fn ctx_reuse_name(call: &CommandCall) -> Option<String> {
    call.reuse.as_ref().map(|c| c.name.clone())
}

/// Concepts a macro command creates through `CO('NAME')` keywords, with their types (for
/// `check`, which runs nothing): the catalog's `co_type` of the keyword (ASSEMBLAGE:
/// NUME_DDL gives a numbering, MATR_ASSE/MATRICE an assembled matrix).
fn co_outputs(
    simp: &[catalog::SimpDef],
    fact: &[catalog::FactDef],
    args: &Args,
) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for (key, value, _) in &args.simple {
        if let Value::Co(name) = value {
            let ty = simp
                .iter()
                .find(|s| s.name == *key)
                .and_then(|s| s.co_type.as_deref())
                .unwrap_or("unknown");
            out.push((name.clone(), ty.to_string()));
        }
    }
    for (key, occurrences, _) in &args.factor {
        let Some(def) = fact.iter().find(|f| f.name == *key) else {
            continue;
        };
        for occ in occurrences {
            out.extend(co_outputs(&def.simp, &def.fact, occ));
        }
    }
    out
}
