//! MODE_NON_LINE with REDUCTION against the same run on the full model:
//! `testcases/beam_rings_reduced.comm` (a clamped steel bar of 156 free DOFs, two CERCLE
//! rings) computes the branch on every DOF (FULL), on a basis keeping every fixed-interface
//! mode (RED_ALL: a change of basis), on the default basis (RED) and restarts from RED
//! (RED_ON). The runs land their rows at different energies, so the tables are compared at
//! common energies by local cubic interpolation of FULL's rows in log ENERGIE; what that
//! interpolation itself may err is measured here on FULL's own rows.

use aster_nl::bench::{curves, models};
use aster_nl::linalg::craig_bampton::ModeCut;
use aster_nl::nnm;
use rusqlite::Connection;
use std::path::Path;
use std::process::Command;

/// `aster-nl run comm --db db`: (exit code, output).
fn run_file(comm: &Path, db: &Path) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
        .arg("run")
        .arg(comm)
        .arg("--db")
        .arg(db)
        .output()
        .unwrap();
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (o.status.code(), out)
}

fn run_case(db: &Path) -> String {
    let comm = Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/beam_rings_reduced.comm");
    let (code, out) = run_file(&comm, db);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 6 OK, 0 NOOK"), "{out}");
    out
}

/// (ENERGIE, value) of a table's rows in NUME_ORDRE order.
fn rows(c: &Connection, sql: &str) -> Vec<(f64, f64)> {
    let mut st = c.prepare(sql).unwrap();
    st.query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
        .unwrap()
        .map(Result::unwrap)
        .collect()
}

fn curve(c: &Connection, table: &str) -> Vec<(f64, f64)> {
    rows(
        c,
        &format!("SELECT ENERGIE, FREQUENCE FROM {table} ORDER BY NUME_ORDRE"),
    )
}

/// H1 cosine coefficient of one DOF, against the row's ENERGIE.
fn first_harmonic(c: &Connection, table: &str, node: &str, cmp: &str) -> Vec<(f64, f64)> {
    rows(
        c,
        &format!(
            "SELECT t.ENERGIE, f.COEF_C FROM mnl_fourier f JOIN {table} t ON t.NUME_ORDRE = f.NUME_ORDRE \
             WHERE f.concept = '{table}' AND f.NOEUD = '{node}' AND f.NOM_CMP = '{cmp}' AND f.HARM = 1 \
             ORDER BY f.NUME_ORDRE"
        ),
    )
}

/// Largest |value − reference(E)| / scale over the rows of `other` inside `reference`'s
/// energies (bench/curves.rs), at least 20 rows compared.
fn worst(reference: &[(f64, f64)], other: &[(f64, f64)], scale: impl Fn(f64) -> f64) -> f64 {
    let (w, compared) = curves::worst_difference(reference, other, scale).unwrap();
    assert!(compared > 20, "only {compared} rows to compare");
    w
}

#[test]
fn reduced_branches_match_the_full_model() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("r.db");
    let out = run_case(&db);
    assert!(out.contains("156 free DOF(s) -> 37 coordinate(s)"), "{out}");
    let c = Connection::open(&db).unwrap();
    let full = curve(&c, "FULL");
    assert!(
        full.windows(2).all(|w| w[1].0 > w[0].0),
        "FULL not increasing in ENERGIE"
    );

    // What the interpolation errs: every other row of FULL interpolated from the others.
    // A cubic's error falls as the fourth power of the spacing, so at FULL's own spacing it
    // is about 1/16 of this (measured: 7.1e-7 here, 6.3e-8 the largest RED_ALL difference).
    let interpolation = curves::interpolation_error(&full).unwrap();
    assert!(
        interpolation < 2e-6,
        "interpolation error {interpolation:e}"
    );

    // Every interior mode kept: the same structure in other coordinates, so the same branch
    // up to the interpolation (a truncated basis of 10 modes differs by 7e-5 on a bar of
    // this kind, 20 by 5e-6).
    let all = worst(&full, &curve(&c, "RED_ALL"), f64::abs);
    assert!(all < interpolation / 4.0, "RED_ALL {all:e}");
    // The default cut-off: within 1e-6 (its documented promise; measured 5.2e-7).
    let red_rows = curve(&c, "RED");
    let red = worst(&full, &red_rows, f64::abs);
    assert!(red < 1e-6, "RED {red:e}");
    // A restart on the stored basis takes the same steps from the same point: its rows are
    // RED's from NUME_ORDRE 61 on, to round-off (measured: equal to the last digit).
    let on = curve(&c, "RED_ON");
    assert_eq!(on.len(), 30);
    for (a, b) in on.iter().zip(red_rows.iter().skip(60)) {
        assert!((a.1 - b.1).abs() <= 1e-12 * b.1, "{a:?} against {b:?}");
    }

    // Every DOF's Fourier coefficients are expanded from the reduced coordinates: the middle
    // of the bar, a ring node and a rotation, against FULL's, relative to their largest
    // value. A shape converges at the first order of the truncation where the frequency
    // (a Rayleigh quotient) does at the second: RED within 1e-4 (measured 2.5e-5 at most).
    for (node, cmp) in [("N20", "DZ"), ("N13", "DZ"), ("N5", "DRY")] {
        let f = first_harmonic(&c, "FULL", node, cmp);
        let scale = f.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        assert!(scale > 1e-4, "{node} {cmp} barely moves: {scale:e}");
        let all = worst(&f, &first_harmonic(&c, "RED_ALL", node, cmp), |_| scale);
        assert!(all < 1e-6, "{node} {cmp} RED_ALL {all:e}");
        let red = worst(&f, &first_harmonic(&c, "RED", node, cmp), |_| scale);
        assert!(red < 1e-4, "{node} {cmp} RED {red:e}");
    }

    // REST_MODE_NONL of the reduced run writes every free DOF at every instant.
    let n: i64 = c
        .query_row("SELECT count(*) FROM HIST", [], |r| r.get(0))
        .unwrap();
    assert_eq!(n, 64 * 156);
    // CALC_STABILITE stored the reduced model's multipliers: 2 per coordinate and row.
    let n: i64 = c
        .query_row(
            "SELECT count(*) FROM mnl_floquet WHERE concept = 'STAB'",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(n, 3 * 2 * 37);
}

/// The linear modes the engine's checks use (frequency floor, resonance alarm) on a basis
/// keeping every interior mode are the full model's: its frequencies reach 5000 times the
/// first, where the dense direct form once gave 51.38 Hz for 52.05 Hz.
#[test]
fn the_engines_linear_modes_of_a_wide_basis_are_the_full_models() {
    let dir = tempfile::tempdir().unwrap();
    let prep = models::prepare(&models::beam(40, 3, 64, 1), dir.path()).unwrap();
    let full = nnm::linear_modes(&prep.problem).unwrap().unwrap();
    let basis = nnm::shock_basis(&prep.problem, ModeCut::Count(1000), usize::MAX).unwrap();
    assert_eq!(basis.size(), prep.problem.k.nrows());
    let reduced = nnm::linear_modes(&nnm::reduced_problem(&prep.problem, &basis).unwrap())
        .unwrap()
        .unwrap();
    for (a, b) in full.iter().zip(&reduced).take(6) {
        // Two dense solves of the same pencil in other coordinates: round-off of the
        // projection, far below any truncation error.
        assert!(
            (a.frequency - b.frequency).abs() <= 1e-8 * a.frequency,
            "{} against {}",
            a.frequency,
            b.frequency
        );
    }
}

/// The test case with its REDUCTION of RED replaced by `reduction`, run in a directory of
/// its own: (exit code, output).
fn run_with_reduction(reduction: &str) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases");
    std::fs::copy(
        src.join("beam_rings_reduced.mail"),
        dir.path().join("c.mail"),
    )
    .unwrap();
    let text = std::fs::read_to_string(src.join("beam_rings_reduced.comm")).unwrap();
    let edited = text.replace("REDUCTION=_F()", reduction);
    assert_ne!(edited, text);
    let comm = dir.path().join("c.comm");
    std::fs::write(&comm, edited).unwrap();
    run_file(&comm, &dir.path().join("c.db"))
}

/// Bad input to REDUCTION: two cut-offs at once (a structure its shock DOFs do not hold,
/// and a basis larger than allowed: linalg/craig_bampton/tests.rs).
#[test]
fn reduction_refuses_two_cut_offs() {
    let (code, out) = run_with_reduction("REDUCTION=_F(NB_MODE=4, FREQ_COUPURE=1000.)");
    assert_ne!(code, Some(0), "{out}");
    assert!(
        out.contains("REDUCTION") && out.contains("NB_MODE"),
        "{out}"
    );
}

/// A cut-off below the harmonics the rows carry is announced (MODE_NON_LINE_10): 100 Hz
/// keeps no fixed-interface mode of the bar held at its rings (the first is at 253 Hz),
/// while NB_HARM_LINE 3 × 52 Hz asks for more; the default basis does not raise it.
#[test]
fn a_cut_off_below_the_harmonics_is_announced() {
    let (_, out) = run_with_reduction("REDUCTION=_F(FREQ_COUPURE=100.)");
    assert!(
        out.contains("-> 4 coordinate(s): 4 shock DOF(s) and 0 fixed-interface mode(s)"),
        "{out}"
    );
    // Every row of RED (120) and of its restart on the same basis; none of the other runs.
    assert_eq!(out.matches("<MODE_NON_LINE_10>").count(), 2, "{out}");
    assert!(out.contains("a static condensation"), "{out}");
    assert!(
        out.contains("120 row(s) between NUME_ORDRE 1 and 120"),
        "{out}"
    );
}
