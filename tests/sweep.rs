//! `aster-nl sweep` and `aster-nl merge` end to end, with the real binary: the one-DOF wall
//! of testcases/sweep/ over 3 gaps x 2 contact stiffnesses plus an impossible gap, run by
//! the local pool and (when a Slurm cluster answers) as a Slurm job array. Every check of
//! the merged database is against the points' own databases, read independently.
//!
//! The Slurm test needs `sbatch` and `squeue` of a running cluster (CI starts one with
//! .ci/slurm-setup.sh and sets ASTER_NL_TEST_SLURM=1, which turns a missing cluster into a
//! failure instead of a skip).

use rusqlite::types::Value;
use rusqlite::{Connection, OpenFlags};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_aster-nl"))
}

fn text(o: &Output) -> String {
    format!(
        "exit {:?}\n--- stdout\n{}\n--- stderr\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

const GAPS: [f64; 3] = [0.005, 0.01, 0.02];
const STIFFNESSES: [f64; 2] = [50.0, 500.0];
/// JEU has `val_min = 0` in MODE_NON_LINE's catalog: these points must fail.
const IMPOSSIBLE_GAP: f64 = -0.01;

/// The template and its mesh copied into a fresh directory, with a study of
/// `gaps` x STIFFNESSES.
fn setup(gaps: &[f64], extra: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/sweep");
    for f in ["wall.comm", "wall.mail"] {
        std::fs::copy(src.join(f), dir.path().join(f)).unwrap();
    }
    let study = dir.path().join("study.toml");
    write_study(&study, gaps, extra);
    (dir, study)
}

fn write_study(study: &Path, gaps: &[f64], extra: &str) {
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    std::fs::write(
        study,
        format!(
            "template = \"wall.comm\"\n\
             [units]\n20 = \"wall.mail\"\n\
             [grid]\nJEU = [{}]\nRIGI_NOR = [{}]\n\
             [run]\njobs = 2\n{extra}",
            list(gaps),
            list(&STIFFNESSES)
        ),
    )
    .unwrap();
}

fn all_gaps() -> Vec<f64> {
    let mut g = GAPS.to_vec();
    g.push(IMPOSSIBLE_GAP);
    g
}

fn open_ro(p: &Path) -> Connection {
    Connection::open_with_flags(p, OpenFlags::SQLITE_OPEN_READ_ONLY).unwrap()
}

fn tables(c: &Connection) -> Vec<String> {
    let mut st = c
        .prepare(
            "SELECT name FROM sqlite_master WHERE type = 'table' \
             AND name NOT LIKE 'sqlite_%' ORDER BY name",
        )
        .unwrap();
    st.query_map([], |r| r.get(0))
        .unwrap()
        .collect::<rusqlite::Result<_>>()
        .unwrap()
}

/// The order a run's rows were stored in, as the merge copies them: by rowid, or for a
/// WITHOUT ROWID table (matrix_entries) its primary key's, the order of a plain scan.
fn stored_order(c: &Connection, table: &str) -> &'static str {
    let sql: String = c
        .query_row(
            "SELECT sql FROM sqlite_master WHERE type = 'table' AND name = ?1",
            [table],
            |r| r.get(0),
        )
        .unwrap();
    if sql.to_ascii_uppercase().contains("WITHOUT ROWID") {
        ""
    } else {
        " ORDER BY rowid"
    }
}

fn columns(c: &Connection, table: &str) -> Vec<String> {
    let mut st = c
        .prepare(&format!("PRAGMA table_info(\"{table}\")"))
        .unwrap();
    st.query_map([], |r| r.get(1))
        .unwrap()
        .collect::<rusqlite::Result<_>>()
        .unwrap()
}

fn rows(c: &Connection, sql: &str, arg: Option<&str>) -> Vec<Vec<Value>> {
    let mut st = c.prepare(sql).unwrap();
    let n = st.column_count();
    let map = |r: &rusqlite::Row| (0..n).map(|i| r.get::<_, Value>(i)).collect();
    match arg {
        Some(a) => st
            .query_map([a], map)
            .unwrap()
            .collect::<rusqlite::Result<_>>(),
        None => st
            .query_map([], map)
            .unwrap()
            .collect::<rusqlite::Result<_>>(),
    }
    .unwrap()
}

fn real(v: &Value) -> f64 {
    match v {
        Value::Real(x) => *x,
        Value::Integer(i) => *i as f64,
        other => panic!("not a number: {other:?}"),
    }
}

/// The checks every finished sweep of `all_gaps()` x STIFFNESSES must pass, whatever ran
/// it. Returns the merged MNL rows (JEU, RIGI_NOR, NUME_ORDRE, FREQUENCE, ENERGIE).
fn check_merged(out: &Path) -> Vec<Vec<Value>> {
    let merged = open_ro(&out.join("sweep.db"));

    // Every point listed, the impossible gap failed with the catalog's reason.
    let points = rows(
        &merged,
        "SELECT SWEEP_POINT, JEU, RIGI_NOR, STATUS, ERROR, DB FROM SWEEP_POINTS ORDER BY rowid",
        None,
    );
    assert_eq!(points.len(), all_gaps().len() * STIFFNESSES.len());
    let mut ok_points = Vec::new();
    for p in &points {
        let (jeu, status) = (real(&p[1]), &p[3]);
        if jeu == IMPOSSIBLE_GAP {
            assert_eq!(*status, Value::Text("failed".into()), "{p:?}");
            let Value::Text(err) = &p[4] else {
                panic!("{p:?}")
            };
            assert!(err.contains("JEU") && err.contains("> 0"), "{err}");
        } else {
            assert_eq!(*status, Value::Text("ok".into()), "{p:?}");
            let (Value::Text(id), Value::Text(db)) = (&p[0], &p[5]) else {
                panic!("{p:?}")
            };
            ok_points.push((id.clone(), jeu, real(&p[2]), PathBuf::from(db)));
        }
    }
    assert_eq!(ok_points.len(), GAPS.len() * STIFFNESSES.len());

    // Every table of every run, row for row, with the point's values in front.
    let merged_tables = tables(&merged);
    for (id, jeu, rigi, db) in &ok_points {
        let run = open_ro(db);
        for t in tables(&run) {
            assert!(merged_tables.contains(&t), "{t} of {id} not merged");
            let cols = columns(&run, &t);
            let quoted: Vec<String> = cols.iter().map(|c| format!("\"{c}\"")).collect();
            let mine = rows(
                &run,
                &format!(
                    "SELECT {} FROM \"{t}\"{}",
                    quoted.join(", "),
                    stored_order(&run, &t)
                ),
                None,
            );
            let theirs = rows(
                &merged,
                &format!(
                    "SELECT {} FROM \"{t}\" WHERE SWEEP_POINT = ?1 ORDER BY rowid",
                    quoted.join(", ")
                ),
                Some(id),
            );
            assert_eq!(mine, theirs, "table {t} of point {id}");
            // The parameter columns (SWEEP_ prefixed where the table has its own JEU).
            let mcols = columns(&merged, &t);
            let jcol = if cols.iter().any(|c| c == "JEU") {
                "SWEEP_JEU"
            } else {
                "JEU"
            };
            let rcol = if cols.iter().any(|c| c == "RIGI_NOR") {
                "SWEEP_RIGI_NOR"
            } else {
                "RIGI_NOR"
            };
            assert!(mcols.contains(&jcol.to_string()), "{t}: {mcols:?}");
            let bad = rows(
                &merged,
                &format!(
                    "SELECT count(*) FROM \"{t}\" WHERE SWEEP_POINT = ?1 AND \
                     ({jcol} IS NOT {jeu:?} OR {rcol} IS NOT {rigi:?})"
                ),
                Some(id),
            );
            assert_eq!(bad[0][0], Value::Integer(0), "{t} of {id}");
        }
        // The value reached the engine: the shock table MODE_NON_LINE wrote has it.
        let choc = rows(&run, "SELECT JEU, RIGI_NOR FROM MNL_CHOC", None);
        assert_eq!(choc.len(), 1);
        assert_eq!(real(&choc[0][0]), *jeu);
        assert_eq!(real(&choc[0][1]), *rigi);
    }
    // Nothing of the failed points in the run tables.
    let stray = rows(
        &merged,
        &format!("SELECT count(*) FROM MNL WHERE JEU = {IMPOSSIBLE_GAP:?}"),
        None,
    );
    assert_eq!(stray[0][0], Value::Integer(0));

    // The question of the issue, answered by SQL.
    let by_gap = rows(
        &merged,
        "SELECT JEU, RIGI_NOR, MAX(FREQUENCE), COUNT(*) FROM MNL GROUP BY JEU, RIGI_NOR ORDER BY JEU, RIGI_NOR",
        None,
    );
    assert_eq!(by_gap.len(), 6);
    for g in &by_gap {
        // Above the linear frequency sqrt(10)/2pi: the wall stiffens the mode.
        assert!(
            real(&g[2]) > 10f64.sqrt() / (2.0 * std::f64::consts::PI),
            "{g:?}"
        );
    }

    // The family picture.
    let png = image::open(out.join("curves.png")).unwrap();
    assert!(png.width() >= 640 && png.height() >= 480);
    assert!(out.join("curves.svg").is_file());

    rows(
        &merged,
        "SELECT JEU, RIGI_NOR, NUME_ORDRE, FREQUENCE, ENERGIE FROM MNL ORDER BY rowid",
        None,
    )
}

fn point_json(out: &Path, id: &str) -> serde_json::Value {
    let p = out.join("points").join(id).join("point.json");
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

#[test]
fn local_sweep_merges_every_run_and_lists_the_failed_points() {
    let (dir, study) = setup(&all_gaps(), "");
    let out = dir.path().join("study.sweep");
    let o = bin().arg("sweep").arg(&study).output().unwrap();
    // 3: the sweep ran to its end, some points failed.
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("6 ok, 0 nook, 2 failed"), "{}", text(&o));
    assert!(
        stdout.contains("failed JEU=-0.01, RIGI_NOR=50.0"),
        "{}",
        text(&o)
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("8 to run"), "{}", text(&o));
    assert!(stderr.contains("[8/8]"), "{}", text(&o));
    let first = check_merged(&out);
    // One row per branch (NB_PAS_MAN=1), NB_BRANCHE of the template's.
    assert_eq!(first.len(), 6 * 35, "35 branches x 6 points");

    // A rerun runs only the failed points; the others keep their outcome untouched.
    let ok_id = "JEU=0.01,RIGI_NOR=50.0";
    let before = point_json(&out, ok_id);
    let o = bin().arg("sweep").arg(&study).output().unwrap();
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("2 to run on local processes, 6 up to date"),
        "{}",
        text(&o)
    );
    assert_eq!(point_json(&out, ok_id), before);
    assert_eq!(check_merged(&out), first);

    // A change of the template reruns every point it changes (all of them).
    let t = dir.path().join("wall.comm");
    let template = std::fs::read_to_string(&t).unwrap();
    assert!(
        template.contains("NB_HARM_NONL=100"),
        "the template changed"
    );
    let changed = template.replace("NB_HARM_NONL=100", "NB_HARM_NONL=101");
    std::fs::write(&t, changed).unwrap();
    let o = bin().arg("sweep").arg(&study).output().unwrap();
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("8 to run"),
        "{}",
        text(&o)
    );
    check_merged(&out);

    // Without the impossible gap, nothing runs and the exit code is 0.
    write_study(&study, &GAPS, "");
    let o = bin().arg("sweep").arg(&study).output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("0 to run"),
        "{}",
        text(&o)
    );

    // `--status` reads without writing.
    let o = bin()
        .arg("sweep")
        .arg(&study)
        .arg("--status")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("6 point(s): 6 ok"),
        "{}",
        text(&o)
    );
}

#[test]
fn merge_command_merges_run_databases_and_keeps_foreign_files() {
    let (dir, study) = setup(&[0.01, IMPOSSIBLE_GAP], "");
    let out = dir.path().join("study.sweep");
    let o = bin().arg("sweep").arg(&study).output().unwrap();
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    let dbs: Vec<PathBuf> = ["JEU=0.01,RIGI_NOR=50.0", "JEU=0.01,RIGI_NOR=500.0"]
        .iter()
        .map(|id| out.join("points").join(id).join("wall.db"))
        .collect();
    let merged = dir.path().join("by_hand.db");
    let o = bin().arg("merge").arg(&merged).args(&dbs).output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("parameters: JEU, RIGI_NOR"));
    let m = open_ro(&merged);
    let counts = rows(
        &m,
        "SELECT RIGI_NOR, COUNT(*) FROM MNL GROUP BY RIGI_NOR ORDER BY RIGI_NOR",
        None,
    );
    for (k, db) in dbs.iter().enumerate() {
        let n = rows(&open_ro(db), "SELECT COUNT(*) FROM MNL", None);
        assert_eq!(counts[k][1], n[0][0]);
        assert_eq!(real(&counts[k][0]), STIFFNESSES[k]);
    }
    drop(m);
    // A merged database is replaced by a new merge...
    let o = bin()
        .arg("merge")
        .arg(&merged)
        .arg(&dbs[0])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    // ...a file that is not one is left alone.
    let foreign = dir.path().join("notes.db");
    std::fs::write(&foreign, "my notes").unwrap();
    let o = bin()
        .arg("merge")
        .arg(&foreign)
        .arg(&dbs[0])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(String::from_utf8_lossy(&o.stderr).contains("not a merged database"));
    assert_eq!(std::fs::read_to_string(&foreign).unwrap(), "my notes");
    // A run database is not a merged one either.
    let o = bin()
        .arg("merge")
        .arg(&dbs[1])
        .arg(&dbs[0])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
}

#[test]
fn a_directory_that_is_not_a_sweeps_is_refused() {
    let (dir, study) = setup(&[0.01], "");
    let out = dir.path().join("results");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("thesis.tex"), "chapter 1").unwrap();
    let o = bin()
        .arg("sweep")
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(String::from_utf8_lossy(&o.stderr).contains("not a sweep's directory"));
    let left: Vec<_> = std::fs::read_dir(&out).unwrap().collect();
    assert_eq!(left.len(), 1);
    assert_eq!(
        std::fs::read_to_string(out.join("thesis.tex")).unwrap(),
        "chapter 1"
    );
}

#[test]
fn a_parameter_the_template_does_not_assign_is_named_with_its_line() {
    let (dir, study) = setup(&[0.01], "");
    let mut s = std::fs::read_to_string(&study).unwrap();
    s = s.replace("RIGI_NOR = [", "RIGI_NORM = [");
    std::fs::write(&study, s).unwrap();
    let o = bin().arg("sweep").arg(&study).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("RIGI_NORM is not assigned at the top level"),
        "{err}"
    );
    assert!(err.contains("study.toml:6"), "{err}");
    // Nothing was written.
    assert!(!dir.path().join("study.sweep").exists());
}

#[test]
fn points_past_their_timeout_are_stopped_and_listed() {
    // 2000 branches take seconds even in a release build: both points (two stiffnesses)
    // are stopped at half a second, and the sweep ends and lists them.
    let (dir, study) = setup(&[0.01], "timeout = 0.5\n");
    // Far up the branch the steps collapse and the no-progress guard would end the run
    // (about 0.5 s in, racing the timeout on a quiet machine): off, so that the point is
    // long and only the timeout can stop it.
    let comm = dir.path().join("wall.comm");
    let template = std::fs::read_to_string(&comm).unwrap();
    assert!(template.contains("NB_BRANCHE=NB_BRANCHE,"));
    // A PLAN stop is followed to its homogeneous limit and ends there (issue 34): BI_PLAN's
    // long branch crawls.
    assert!(template.contains("OBSTACLE='PLAN'"));
    std::fs::write(
        &comm,
        template
            .replace(
                "NB_BRANCHE=NB_BRANCHE,",
                "NB_BRANCHE=NB_BRANCHE, NB_BRANCHE_SANS_PROGRES=0,",
            )
            .replace("OBSTACLE='PLAN'", "OBSTACLE='BI_PLAN'"),
    )
    .unwrap();
    let s = std::fs::read_to_string(&study)
        .unwrap()
        .replace("[run]", "NB_BRANCHE = [2000]\n[run]");
    std::fs::write(&study, s).unwrap();
    let started = Instant::now();
    let o = bin().arg("sweep").arg(&study).output().unwrap();
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("0 ok, 0 nook, 2 failed"), "{}", text(&o));
    assert!(
        stdout.contains("stopped after 0.5 s (run.timeout of the study)"),
        "{}",
        text(&o)
    );
    // Two points of 0.5 s each on two processes, plus start-up: far below a full run.
    assert!(
        started.elapsed() < Duration::from_secs(30),
        "{:?}",
        started.elapsed()
    );
    let merged = open_ro(&dir.path().join("study.sweep/sweep.db"));
    let failed = rows(
        &merged,
        "SELECT COUNT(*) FROM SWEEP_POINTS WHERE STATUS = 'failed'",
        None,
    );
    assert_eq!(failed[0][0], Value::Integer(2));
}

/// A process with a deadline: the test fails instead of hanging on a stuck scheduler.
fn output_within(mut cmd: Command, limit: Duration) -> Output {
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let o = child.wait_with_output().unwrap();
            panic!("no end after {limit:?}\n{}", text(&o));
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn slurm_answers() -> bool {
    Command::new("squeue")
        .arg("-h")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

#[test]
fn slurm_sweep_gives_the_local_sweeps_database() {
    let required = std::env::var_os("ASTER_NL_TEST_SLURM").is_some_and(|v| v == "1");
    if !slurm_answers() {
        assert!(
            !required,
            "ASTER_NL_TEST_SLURM=1 but squeue does not answer (is SLURM_CONF set? .ci/slurm-setup.sh)"
        );
        eprintln!("skipped: no Slurm cluster answers (set up one with .ci/slurm-setup.sh)");
        return;
    }
    let (dir, study) = setup(&all_gaps(), "");
    let local_out = dir.path().join("local.sweep");
    let slurm_out = dir.path().join("slurm.sweep");
    let mut cmd = bin();
    cmd.arg("sweep")
        .arg(&study)
        .arg("--out")
        .arg(&slurm_out)
        .arg("--slurm");
    let o = output_within(cmd, Duration::from_secs(240));
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("submitted Slurm job array"),
        "{}",
        text(&o)
    );
    let from_slurm = check_merged(&slurm_out);
    // Every point ran as a task of the array, each its own writer.
    for p in std::fs::read_dir(slurm_out.join("points")).unwrap() {
        let id = p.unwrap().file_name().to_string_lossy().to_string();
        let ran_on = point_json(&slurm_out, &id)["ran_on"].clone();
        assert!(
            ran_on.as_str().is_some_and(|r| r.starts_with("slurm ")),
            "{id}: {ran_on}"
        );
    }
    // Same binary, same files: the very numbers of the local pool.
    let mut cmd = bin();
    cmd.arg("sweep")
        .arg(&study)
        .arg("--out")
        .arg(&local_out)
        .arg("--local");
    let o = output_within(cmd, Duration::from_secs(240));
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert_eq!(check_merged(&local_out), from_slurm);
}

#[test]
fn the_shipped_demo_reaches_far_into_contact_with_distinct_curves_and_no_alarm() {
    // testcases/sweep/wall.toml as docs/sweeps.md runs it. Its earlier settings barely
    // reached contact (every curve ended below 0.504 Hz, on top of one another).
    let dir = tempfile::tempdir().unwrap();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/sweep");
    for f in ["wall.comm", "wall.mail", "wall.toml"] {
        std::fs::copy(src.join(f), dir.path().join(f)).unwrap();
    }
    let o = bin()
        .arg("sweep")
        .arg(dir.path().join("wall.toml"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let out = dir.path().join("wall.sweep");
    for entry in std::fs::read_dir(out.join("points")).unwrap() {
        let log = std::fs::read_to_string(entry.unwrap().path().join("run.log")).unwrap();
        // The only alarm: MODE_NON_LINE_1's estimate where every force is resolved, on the
        // stiffer points' rows just past first contact (docs/sweeps.md: measured 1.3e-4
        // from the exact period there, estimated 2.0e-4).
        assert_eq!(
            log.matches("<A>").count(),
            log.matches("<A> <MODE_NON_LINE_1> the contact forces are resolved")
                .count(),
            "{log}"
        );
    }
    let merged = open_ro(&out.join("sweep.db"));
    let per_point = rows(
        &merged,
        "SELECT JEU, RIGI_NOR, MIN(ENERGIE), MAX(ENERGIE), MAX(FREQUENCE) FROM MNL \
         GROUP BY JEU, RIGI_NOR ORDER BY RIGI_NOR, JEU",
        None,
    );
    assert_eq!(per_point.len(), 6);
    let f_lin = 10f64.sqrt() / (2.0 * std::f64::consts::PI);
    for p in &per_point {
        let (jeu, e_min, e_max) = (real(&p[0]), real(&p[2]), real(&p[3]));
        let contact = 0.5 * 10.0 * jeu * jeu;
        // Each curve starts at first contact and goes ten times past it in energy.
        assert!((e_min / contact - 1.0).abs() < 0.05, "{p:?}");
        assert!(e_max > 10.0 * contact, "{p:?}");
        // Well above the linear frequency: the stop shapes the curve.
        assert!(real(&p[4]) > f_lin + 0.15, "{p:?}");
    }
    // The two contact stiffnesses end apart (toward 0.715 and 0.826 Hz).
    let soft = real(&per_point[0][4]);
    let stiff = real(&per_point[3][4]);
    assert!(stiff - soft > 0.1, "{per_point:?}");
}
