//! Alarm MODE_NON_LINE_7 (internal resonances, src/nnm/analysis/resonance.rs) on the steel cantilever
//! of issue 34 point 5, `testcases/hard/cantilever_17to1.comm`, run by the `aster-nl`
//! binary. Where the alarm must fire is computed here from Euler-Bernoulli's closed-form
//! frequencies and the table's FREQUENCE column, independently of the engine.

use rusqlite::Connection;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Command;

fn case(ext: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("testcases/hard")
        .join(format!("cantilever_17to1.{ext}"))
}

/// Euler-Bernoulli cantilever frequency of mode j (1-based), the file's beam.
fn f_eb(j: usize) -> f64 {
    let beta_l = [1.87510407, 4.69409113, 7.85475744, 10.99554073][j - 1];
    let (e, rho, r, l): (f64, f64, f64, f64) = (2.1e11, 7800.0, 0.01, 1.0);
    let (a, i) = (PI * r * r, PI * r.powi(4) / 4.0);
    beta_l * beta_l * (e * i / (rho * a * l.powi(4))).sqrt() / (2.0 * PI)
}

/// Runs the case with `edit` applied to its text; (exit code, output, (FREQUENCE, ENERGIE)
/// rows in NUME_ORDRE order, starting at NUME_ORDRE 1).
fn run(edit: &dyn Fn(String) -> String) -> (Option<i32>, String, Vec<(f64, f64)>) {
    let dir = tempfile::tempdir().unwrap();
    let comm = dir.path().join("c.comm");
    std::fs::write(&comm, edit(std::fs::read_to_string(case("comm")).unwrap())).unwrap();
    std::fs::copy(case("mail"), dir.path().join("c.mail")).unwrap();
    let db = dir.path().join("c.db");
    let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
        .arg("run")
        .arg(&comm)
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let c = Connection::open(&db).unwrap();
    let mut st = c
        .prepare("SELECT NUME_ORDRE, FREQUENCE, ENERGIE FROM MNL ORDER BY NUME_ORDRE")
        .unwrap();
    let rows: Vec<(i64, f64, f64)> = st
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .map(|r| r.unwrap())
        .collect();
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(r.0, k as i64 + 1);
    }
    (
        o.status.code(),
        out,
        rows.iter().map(|r| (r.1, r.2)).collect(),
    )
}

/// The number after `key` in `line`, up to the next space, comma or parenthesis.
fn number_after(line: &str, key: &str) -> f64 {
    let s = &line[line.find(key).unwrap_or_else(|| panic!("{key} in {line}")) + key.len()..];
    let end = s.find([' ', ',', ')']).unwrap_or(s.len());
    s[..end].parse().unwrap()
}

// The file's CALC_MODES frequencies are within PREC = 5e-4 of Euler-Bernoulli (its TEST_RESU,
// measured 2.5e-4 on mode 3, 9e-4 on mode 4 with ten elements): the crossings are computed
// over that band.
const MODE3_TOL: f64 = 5e-4;
const MODE4_TOL: f64 = 2e-3;

#[test]
fn the_seventeen_to_one_resonance_with_bending_mode_3_is_announced() {
    let (code, out, rows) = run(&|s| s);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 3 OK, 0 NOOK"), "{out}");
    // 17·f crosses f3 between rows k−1 and k: unambiguous over the band of f3.
    let (lo, hi) = (f_eb(3) * (1.0 - MODE3_TOL), f_eb(3) * (1.0 + MODE3_TOL));
    let k = rows
        .iter()
        .position(|r| 17.0 * r.0 > lo)
        .expect("17 f reaches f3");
    assert!(k > 0 && 17.0 * rows[k].0 > hi, "{rows:?}");
    let line = out
        .lines()
        .find(|l| l.contains("17:1 with linear mode 3 "))
        .unwrap_or_else(|| panic!("no 17:1 with mode 3 in:\n{out}"));
    assert!(out.contains("<MODE_NON_LINE_7>"), "{out}");
    assert_eq!(number_after(line, "NUME_ORDRE ") as usize, k + 1, "{line}");
    let e = number_after(line, "ENERGIE ");
    assert!(rows[k - 1].1 < e && e <= rows[k].1, "{e} {rows:?}");
    // The alarm prints 7 significant digits.
    assert!((e / rows[k].1 - 1.0).abs() < 1e-6, "{e} {:?}", rows[k]);
    assert!(
        line.contains("NB_HARM_LINE=15 < 17 cannot represent it")
            && line.contains("NB_HARM_LINE=17 or more would hold it"),
        "{line}"
    );
    // 6·f crosses f2 too (f2/6 = 15.16 Hz, below the last row), but a symmetric stop's force
    // has no even harmonic: not reported.
    let last = rows.iter().map(|r| r.0).fold(0.0, f64::max);
    assert!(6.0 * last > f_eb(2) * (1.0 + MODE3_TOL), "{last}");
    assert!(!out.contains(":1 with linear mode 2 "), "{out}");
}

#[test]
fn no_alarm_on_a_branch_that_stops_before_the_resonance() {
    // Ten branches stop below f3/17; the branch still crosses 34 f = f4 (even: the BI_PLAN
    // force does not carry harmonic 34), which a rule on frequencies alone would report.
    let (code, out, rows) = run(&|s| s.replace("NB_BRANCHE=20", "NB_BRANCHE=10"));
    assert_eq!(code, Some(0), "{out}");
    let last = rows.iter().map(|r| r.0).fold(0.0, f64::max);
    assert!(17.0 * last < f_eb(3) * (1.0 - MODE3_TOL), "{last}");
    assert!(34.0 * last > f_eb(4) * (1.0 + MODE4_TOL), "{last}");
    assert!(!out.contains("MODE_NON_LINE_7"), "{out}");
}

#[test]
fn with_enough_harmonics_the_branch_locks_on_the_resonance_and_the_alarm_says_it_holds() {
    // NB_HARM_LINE 20 holds harmonic 17: the branch goes on along the family that carries
    // mode 3 (measured: FREQUENCE stays within 1e-3 of f3/17 while ENERGIE grows).
    let (code, out, rows) = run(&|s| {
        s.replace("NB_HARM_LINE=15", "NB_HARM_LINE=20")
            .replace("NB_BRANCHE=20", "NB_BRANCHE=30")
    });
    assert_eq!(code, Some(0), "{out}");
    let line = out
        .lines()
        .find(|l| l.contains("17:1 with linear mode 3 "))
        .unwrap_or_else(|| panic!("{out}"));
    assert!(line.contains("NB_HARM_LINE=20 >= 17 holds it"), "{line}");
    let last = rows.last().unwrap();
    assert!(
        (17.0 * last.0 / f_eb(3) - 1.0).abs() < 1e-3 + MODE3_TOL,
        "{last:?}"
    );
    assert!(last.1 > 3.0 * number_after(line, "ENERGIE "), "{last:?}");
}
