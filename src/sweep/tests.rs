//! Tests of the sweep's parts that need no aster-nl process: study files, templates, point
//! names, the merge on hand-made databases, the error line of a failed run, the colours.
//! The end-to-end runs (local pool and Slurm) are in tests/sweep.rs.

use super::layout::{point_id, Outcome};
use super::merge::{merge, RunInput};
use super::point::first_error_line;
use super::study::{Scheduler, Study};
use super::template::Template;
use super::value::ParamValue;
use rusqlite::Connection;
use std::path::{Path, PathBuf};

/// A directory with `case.comm` (the template) and `study.toml`.
fn study_dir(template: &str, study: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.comm"), template).unwrap();
    let p = dir.path().join("study.toml");
    std::fs::write(&p, study).unwrap();
    (dir, p)
}

const TEMPLATE: &str = "JEU = 0.01\nK = 50.\nNAME = 'x'\nDEBUT()\nFIN()\n";

fn err_of(study: &str) -> String {
    let (_d, p) = study_dir(TEMPLATE, study);
    let e = Study::load(&p).unwrap_err();
    let at = e
        .location
        .as_ref()
        .map(|l| format!(" @{}", l.span.line))
        .unwrap_or_default();
    format!("{}{at}", e.message)
}

#[test]
fn grid_varies_the_first_parameter_slowest_in_file_order() {
    // Names out of alphabetical order: the file's order must win.
    let (_d, p) = study_dir(
        TEMPLATE,
        "template = 'case.comm'\n[grid]\nK = [1, 2]\nJEU = [0.1, 0.2, 0.3]\n",
    );
    let s = Study::load(&p).unwrap();
    assert_eq!(s.params, ["K", "JEU"]);
    assert_eq!(s.points.len(), 6);
    let pairs: Vec<(i64, f64)> = s
        .points
        .iter()
        .map(|p| match (&p.values[0], &p.values[1]) {
            (ParamValue::Int(k), ParamValue::Real(j)) => (*k, *j),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        pairs,
        [(1, 0.1), (1, 0.2), (1, 0.3), (2, 0.1), (2, 0.2), (2, 0.3)]
    );
    assert_eq!(s.scheduler, Scheduler::Local);
    assert_eq!(s.out, p.parent().unwrap().join("study.sweep"));
}

#[test]
fn list_pairs_the_ith_values_and_a_scalar_is_fixed() {
    let (_d, p) = study_dir(
        TEMPLATE,
        "template = 'case.comm'\n[list]\nJEU = [0.1, 0.2]\nK = [5.0, 6.0]\nNAME = 'plan'\n",
    );
    let s = Study::load(&p).unwrap();
    assert_eq!(s.points.len(), 2);
    assert_eq!(
        s.points[1].values,
        [
            ParamValue::Real(0.2),
            ParamValue::Real(6.0),
            ParamValue::Text("plan".into())
        ]
    );
}

#[test]
fn study_errors_name_the_line_and_what_was_expected() {
    let e = err_of("template = 'case.comm'\n[list]\nJEU = [0.1, 0.2]\nK = [5.0]\n");
    assert!(
        e.contains("K has 1 value(s) but JEU has 2") && e.ends_with("@4"),
        "{e}"
    );
    let e = err_of("template = 'case.comm'\n[grid]\nJEU = [0.1, 0.1]\n");
    assert!(e.contains("points 1 and 2 are the same"), "{e}");
    let e = err_of("template = 'case.comm'\n");
    assert!(e.contains("needs a [grid] or a [list]"), "{e}");
    let e = err_of("template = 'case.comm'\n[grid]\nJEU = []\n");
    assert!(e.contains("empty list") && e.ends_with("@3"), "{e}");
    let e = err_of("template = 'case.comm'\n[grid]\nJEU = [nan]\n");
    assert!(e.contains("finite numbers only"), "{e}");
    let e = err_of("template = 'missing.comm'\n[grid]\nJEU = [1]\n");
    assert!(
        e.contains("missing.comm does not exist") && e.ends_with("@1"),
        "{e}"
    );
    let e = err_of("template = 'case.comm'\nsweep = 1\n[grid]\nJEU = [1]\n");
    assert!(
        e.contains("unknown field `sweep`") && e.ends_with("@2"),
        "{e}"
    );
    let e = err_of("template = 'case.comm'\n[grid]\nJEU = [1]\n[run]\nscheduler = 'pbs'\n");
    assert!(
        e.contains("expected 'local' or 'slurm'") && e.ends_with("@5"),
        "{e}"
    );
    let e = err_of("template = 'case.comm'\n[grid]\nJEU = [1]\n[run]\njobs = 0\n");
    assert!(e.contains("run.jobs: 0, expected at least 1"), "{e}");
    let e = err_of("template = 'case.comm'\n[grid]\nJEU = [1]\n[units]\n20 = 'no.mail'\n");
    assert!(
        e.contains("no.mail does not exist") && e.ends_with("@5"),
        "{e}"
    );
    let e = err_of("template = 'case.comm'\n[grid]\nJEU = [1]\n[plot]\ncolour = 'K'\n");
    assert!(
        e.contains("'K' is not a parameter of the study (JEU)"),
        "{e}"
    );
    let e = err_of("template = 'case.comm'\n[grid]\n2JEU = [1]\n");
    assert!(e.contains("not a Python name"), "{e}");
    let e = err_of("template = 'case.comm'\n[grid]\nJEU = [1]\n[grid]\n");
    assert!(e.contains("study file:") && e.ends_with("@4"), "{e}");
}

fn template_of(text: &str, study: &str) -> Result<(Study, Template), String> {
    let (d, p) = study_dir(text, study);
    let s = Study::load(&p).map_err(|e| e.message)?;
    let t = Template::load(&s).map_err(|e| e.message);
    drop(d);
    t.map(|t| (s, t))
}

#[test]
fn a_point_replaces_only_the_values_and_keeps_every_line_number() {
    let text = "# header\nJEU = (0.01 +\n       0.0)   # gap\nK = 50.\nfor i in range(2):\n    K2 = K\nNAME = 'x'; M = 1\nDEBUT()\nX = JEU\n";
    let (s, t) = template_of(
        text,
        "template = 'case.comm'\n[grid]\nJEU = [0.5]\nK = [7]\nNAME = [\"it's\"]\n",
    )
    .unwrap();
    let out = t.render(&s.points[0].values);
    assert_eq!(
        out,
        "# header\nJEU = 0.5\n   # gap\nK = 7\nfor i in range(2):\n    K2 = K\nNAME = 'it\\'s'; M = 1\nDEBUT()\nX = JEU\n"
    );
    assert_eq!(out.lines().count(), text.lines().count());
    // The result is a valid file of the language.
    let src = crate::lang::Source {
        name: "p.comm".into(),
        text: out,
    };
    crate::lang::parse(&src).unwrap();
}

#[test]
fn a_parameter_must_be_assigned_once_at_top_level() {
    let study = "template = 'case.comm'\n[grid]\nJEU = [0.5]\n";
    let e = template_of("for i in range(2):\n    JEU = 1.\nDEBUT()\n", study).unwrap_err();
    assert!(e.contains("JEU is not assigned at the top level"), "{e}");
    let e = template_of("JEU = 1.\nJEU = 2.\nDEBUT()\n", study).unwrap_err();
    assert!(
        e.contains("assigned 2 times") && e.contains("lines 1, 2"),
        "{e}"
    );
    // `JEU += 1` after the assignment is the user's arithmetic, not a second value.
    template_of("JEU = 1.\nJEU += 1.\nDEBUT()\n", study).unwrap();
    let e = template_of("JEU = (1.\nDEBUT()\n", study).unwrap_err();
    assert!(!e.is_empty());
}

#[test]
fn point_directories_are_readable_or_hashed_and_stable() {
    let params = vec!["JEU".to_string(), "NAME".to_string()];
    let p = |v: Vec<ParamValue>| super::study::Point { values: v };
    let a = point_id(
        &params,
        &p(vec![
            ParamValue::Real(0.01),
            ParamValue::Text("PLAN".into()),
        ]),
    );
    assert_eq!(a, "JEU=0.01,NAME=PLAN");
    let b = point_id(
        &params,
        &p(vec![ParamValue::Real(0.01), ParamValue::Text("a/b".into())]),
    );
    assert!(b.starts_with("p-") && b.len() == 18, "{b}");
    let c = point_id(
        &params,
        &p(vec![ParamValue::Real(0.01), ParamValue::Text("a/c".into())]),
    );
    assert_ne!(b, c);
    // The hash must never change, or a rerun of an existing sweep would run everything
    // again: FNV-1a 64 of "JEU=1" as computed by a separate implementation (Python, from
    // the published offset basis and prime).
    assert_eq!(super::layout::fnv1a(b"JEU=1"), 0x4f02_fa0e_de1e_428d);
}

#[test]
fn the_error_line_of_a_failed_run_keeps_message_and_place() {
    let stderr = "  × MODE_NON_LINE/CHOC/JEU: expected a value > 0.0, got -0.01\n    ╭─[/tmp/x/points/p/wall.comm:24:29]\n 23 │ ...\n";
    assert_eq!(
        first_error_line(stderr).unwrap(),
        "MODE_NON_LINE/CHOC/JEU: expected a value > 0.0, got -0.01 (wall.comm:24:29)"
    );
    let stderr = "Error: cannot read /x.comm\n  --> /a/b/x.comm:3:1\n";
    assert_eq!(
        first_error_line(stderr).unwrap(),
        "cannot read /x.comm (x.comm:3:1)"
    );
    assert_eq!(first_error_line("\n\n"), None);
}

/// A small run database with a table `T(A, JEU)` of `n` rows and a table `ONLY_<tag>`.
fn run_db(dir: &Path, name: &str, n: i64, extra_col: bool) -> PathBuf {
    let p = dir.join(name);
    let c = Connection::open(&p).unwrap();
    c.execute_batch(&format!(
        "CREATE TABLE T (A INTEGER, JEU REAL{});
         CREATE TABLE \"ONLY_{name}\" (X TEXT);
         INSERT INTO \"ONLY_{name}\" VALUES ('{name}');",
        if extra_col { ", B TEXT" } else { "" }
    ))
    .unwrap();
    for i in 0..n {
        if extra_col {
            c.execute("INSERT INTO T VALUES (?1, 9.5, 'b')", [i])
                .unwrap();
        } else {
            c.execute("INSERT INTO T VALUES (?1, 9.5)", [i]).unwrap();
        }
    }
    p
}

fn input(point: &str, jeu: f64, k: i64, outcome: Outcome, db: Option<PathBuf>) -> RunInput {
    RunInput {
        point: point.into(),
        values: vec![Some(ParamValue::Real(jeu)), Some(ParamValue::Int(k))],
        outcome: Some(outcome),
        error: if outcome == Outcome::Failed {
            "boom".into()
        } else {
            String::new()
        },
        seconds: Some(0.5),
        db,
    }
}

#[test]
fn merge_unions_columns_prefixes_clashing_parameters_and_skips_failed_runs() {
    let d = tempfile::tempdir().unwrap();
    let a = run_db(d.path(), "a.db", 3, false);
    let b = run_db(d.path(), "b.db", 2, true);
    let f = run_db(d.path(), "f.db", 4, false);
    let out = d.path().join("m.db");
    let params = vec!["JEU".to_string(), "K".to_string()];
    let runs = vec![
        input("pa", 0.1, 1, Outcome::Ok, Some(a)),
        input("pb", 0.2, 2, Outcome::Nook, Some(b)),
        input("pf", 0.3, 3, Outcome::Failed, Some(f)),
        RunInput {
            point: "pm".into(),
            values: vec![Some(ParamValue::Real(0.4)), None],
            outcome: None,
            error: String::new(),
            seconds: None,
            db: None,
        },
    ];
    let r = merge(&out, &params, &runs).unwrap();
    assert_eq!((r.runs, r.tables, r.rows), (2, 3, 3 + 1 + 2 + 1));
    let c = Connection::open(&out).unwrap();
    // T has its own JEU: the parameter is SWEEP_JEU; K is K; B came with the second run.
    let cols: Vec<String> = c
        .prepare("PRAGMA table_info(T)")
        .unwrap()
        .query_map([], |r| r.get(1))
        .unwrap()
        .collect::<rusqlite::Result<_>>()
        .unwrap();
    assert_eq!(cols, ["SWEEP_POINT", "SWEEP_JEU", "K", "A", "JEU", "B"]);
    let rows: Vec<(String, f64, i64, i64, Option<String>)> = c
        .prepare("SELECT SWEEP_POINT, SWEEP_JEU, K, A, B FROM T ORDER BY rowid")
        .unwrap()
        .query_map([], |r| {
            Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?, r.get(4)?))
        })
        .unwrap()
        .collect::<rusqlite::Result<_>>()
        .unwrap();
    assert_eq!(
        rows,
        [
            ("pa".into(), 0.1, 1, 0, None),
            ("pa".into(), 0.1, 1, 1, None),
            ("pa".into(), 0.1, 1, 2, None),
            ("pb".into(), 0.2, 2, 0, Some("b".into())),
            ("pb".into(), 0.2, 2, 1, Some("b".into())),
        ]
    );
    let points: Vec<(String, String, Option<i64>)> = c
        .prepare("SELECT SWEEP_POINT, STATUS, K FROM SWEEP_POINTS ORDER BY rowid")
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .collect::<rusqlite::Result<_>>()
        .unwrap();
    assert_eq!(
        points,
        [
            ("pa".into(), "ok".into(), Some(1)),
            ("pb".into(), "nook".into(), Some(2)),
            ("pf".into(), "failed".into(), Some(3)),
            ("pm".into(), "missing".into(), None),
        ]
    );
    let failed_tables: i64 = c
        .query_row(
            "SELECT count(*) FROM sqlite_master WHERE name = 'ONLY_f.db'",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(failed_tables, 0);
    // The column types follow the values: K only integers, JEU reals.
    let ty: String = c
        .query_row(
            "SELECT type FROM pragma_table_info('SWEEP_POINTS') WHERE name = 'K'",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(ty, "INTEGER");
}

#[test]
fn merge_refuses_what_it_must_not_replace_and_leaves_no_half_file() {
    let d = tempfile::tempdir().unwrap();
    let a = run_db(d.path(), "a.db", 1, false);
    let params = vec!["JEU".to_string(), "K".to_string()];
    let runs = vec![input("pa", 0.1, 1, Outcome::Ok, Some(a.clone()))];
    // Over itself.
    let e = merge(&a, &params, &runs).unwrap_err();
    assert!(
        e.message
            .contains("both the merged database and one of the runs"),
        "{}",
        e.message
    );
    // Over a file that is not a merged database.
    let other = d.path().join("other.db");
    std::fs::write(&other, b"not sqlite").unwrap();
    let e = merge(&other, &params, &runs).unwrap_err();
    assert!(e.message.contains("not a merged database"), "{}", e.message);
    assert_eq!(std::fs::read(&other).unwrap(), b"not sqlite");
    // A run that is not a database: an error naming it, and the previous merge stays.
    let out = d.path().join("m.db");
    merge(&out, &params, &runs).unwrap();
    let before = std::fs::read(&out).unwrap();
    let junk = d.path().join("junk.db");
    std::fs::write(&junk, b"junk junk junk junk junk junk junk junk").unwrap();
    let bad = vec![input("pj", 0.1, 1, Outcome::Ok, Some(junk))];
    let e = merge(&out, &params, &bad).unwrap_err();
    assert!(e.message.contains("junk.db"), "{}", e.message);
    assert_eq!(std::fs::read(&out).unwrap(), before);
    let leftovers: Vec<_> = std::fs::read_dir(d.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
        .collect();
    assert!(leftovers.is_empty());
    // A merged database as a run.
    let e = merge(
        &d.path().join("m2.db"),
        &params,
        &[input("pm", 0.1, 1, Outcome::Ok, Some(out))],
    )
    .unwrap_err();
    assert!(
        e.message.contains("itself a merged database"),
        "{}",
        e.message
    );
}

#[test]
fn colour_scale_is_ordered_in_lightness() {
    let lum = |t: f64| {
        let (r, g, b) = super::plot::colour_scale(t);
        0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b)
    };
    let mut last = -1.0;
    for i in 0..=20 {
        let l = lum(f64::from(i) / 20.0);
        assert!(l > last, "not increasing at {i}");
        last = l;
    }
    assert_eq!(
        super::plot::colour_scale(-1.0),
        super::plot::colour_scale(0.0)
    );
    assert_eq!(
        super::plot::colour_scale(f64::NAN),
        super::plot::colour_scale(0.5)
    );
}
