//! Internal resonance detection (resonance.rs) on two DOFs whose linear modes are set by
//! hand: a 3:1 crossing the contact drives (must be reported), the same system without
//! reaching it, and a 2:1 crossing that a symmetric BI_PLAN orbit cannot drive (no even
//! harmonic in its force: must not be reported).

use crate::nnm::analysis::resonance::{internal_resonances, resonance_alarm, BAND};
use crate::nnm::model::linear_modes::linear_modes;
use crate::nnm::{continue_branches, start_from_mode, Point, Problem, Settings, Shock, ShockLaw};
use faer::sparse::{SparseColMat, Triplet};
use std::f64::consts::PI;

fn settings(hl: usize, hn: usize, branches: usize) -> Settings {
    let mut s = crate::nnm::tests::settings(hl, hn, branches, 3);
    s.continuation.prec_man = 1e-10;
    s
}

/// M = I, K = Φ diag(ω₁², ω₂²) Φᵀ with Φ = [[1, 1], [1, −1]]/√2 (both modes move DOF 0
/// equally), ω₁² = 10, ω₂ = `ratio`·ω₁, and one stop on DOF 0.
fn two_modes(ratio: f64, law: ShockLaw) -> Problem {
    let (a, b) = (10.0, 10.0 * ratio * ratio);
    let (d, o) = (0.5 * (a + b), 0.5 * (a - b));
    let t: Vec<Triplet<usize, usize, f64>> = [(0, 0, d), (0, 1, o), (1, 0, o), (1, 1, d)]
        .iter()
        .map(|&(r, c, v)| Triplet::new(r, c, v))
        .collect();
    let m: Vec<Triplet<usize, usize, f64>> = vec![Triplet::new(0, 0, 1.0), Triplet::new(1, 1, 1.0)];
    Problem {
        forcing: None,
        k: SparseColMat::try_new_from_triplets(2, 2, &t).unwrap(),
        m: SparseColMat::try_new_from_triplets(2, 2, &m).unwrap(),
        shocks: vec![Shock {
            law,
            dofs: vec![0],
            gap: 0.01,
            stiffness: 50.0,
            regul: 1e-4,
        }],
    }
}

fn branch(p: &Problem, s: &Settings) -> Vec<Point> {
    let st = start_from_mode(p, s, &[1.0, 1.0], 0.9, 10f64.sqrt()).unwrap();
    let mut pts = vec![st.point.clone()];
    let out = continue_branches(p, s, st, &mut |_, _| {});
    assert!(out.error.is_none(), "{:?}", out.error);
    pts.extend(out.points);
    pts
}

#[test]
fn the_linear_modes_are_the_ones_set_by_hand() {
    let p = two_modes(3.03, ShockLaw::Plan);
    let modes = linear_modes(&p).unwrap().unwrap();
    let f1 = 10f64.sqrt() / (2.0 * PI);
    assert_eq!((modes[0].number, modes[1].number), (1, 2));
    assert!((modes[0].frequency / f1 - 1.0).abs() < 1e-13);
    assert!((modes[1].frequency / (3.03 * f1) - 1.0).abs() < 1e-13);
    // Mass-normalised, both at 1/√2 on DOF 0.
    for m in &modes {
        assert!((m.shape[0].abs() - 0.5f64.sqrt()).abs() < 1e-13, "{m:?}");
    }
}

#[test]
fn a_three_to_one_crossing_driven_by_the_stop_is_reported_once() {
    // f₂ = 3.03 f₁: the stiffening branch of mode 1 crosses f₂/3 = 1.01 f₁.
    let p = two_modes(3.03, ShockLaw::Plan);
    let f2 = 3.03 * 10f64.sqrt() / (2.0 * PI);
    for hl in [2, 5] {
        let s = settings(hl, 60, 25);
        let pts = branch(&p, &s);
        let fmax = pts.iter().map(|q| q.frequency).fold(0.0, f64::max);
        assert!(fmax > f2 / 3.0 * 1.002, "the branch must pass f2/3: {fmax}");
        let modes = linear_modes(&p).unwrap().unwrap();
        let met = internal_resonances(&p, &s.harmonics, &pts, &modes).unwrap();
        eprintln!("H_l {hl}: {met:?}");
        let three: Vec<_> = met.iter().filter(|r| r.order == 3 && r.mode == 2).collect();
        assert_eq!(three.len(), 1, "{met:?}");
        let r = three[0];
        // The named row is the first one on the resonance: within BAND of it, or past the
        // sign change of 3f − f₂.
        let on = |i: usize| {
            (3.0 * pts[i].frequency - f2).abs() <= BAND * f2 || 3.0 * pts[i].frequency >= f2
        };
        assert!(on(r.row) && !on(r.row - 1), "row {}", r.row);
        assert_eq!(r.represented, hl >= 3);
        let text = resonance_alarm(
            &p,
            &s.harmonics,
            &pts,
            1,
            linear_modes(&p).unwrap().as_deref(),
        )
        .unwrap()
        .unwrap();
        assert!(text.contains("3:1 with linear mode 2"), "{text}");
        let held = if hl >= 3 {
            "holds it"
        } else {
            "cannot represent it"
        };
        assert!(text.contains(held), "{text}");
    }
}

#[test]
fn no_alarm_where_no_resonance_is_reached_or_driven() {
    // f₂ = 2.5 f₁ with a branch that stays below 1.25 f₁: 2:1 and 3:1 are not crossed.
    let p = two_modes(2.5, ShockLaw::Plan);
    let s = settings(5, 60, 12);
    let alarm = |p: &Problem, pts: &[Point]| {
        resonance_alarm(p, &s.harmonics, pts, 1, linear_modes(p).unwrap().as_deref()).unwrap()
    };
    let pts = branch(&p, &s);
    let f1 = 10f64.sqrt() / (2.0 * PI);
    let fmax = pts.iter().map(|q| q.frequency).fold(0.0, f64::max);
    assert!(fmax > 1.005 * f1 && fmax < 1.2 * f1, "{fmax}");
    assert_eq!(alarm(&p, &pts), None);
    // f₂ = 2.02 f₁ with a symmetric stop (BI_PLAN): the branch crosses f₂/2 but its contact
    // force has no even harmonic, so mode 2 is not driven at harmonic 2: no report. (A
    // rule on frequencies alone would report it.)
    let p = two_modes(2.02, ShockLaw::BiPlan);
    let pts = branch(&p, &s);
    let f2 = 2.02 * f1;
    let fmax = pts.iter().map(|q| q.frequency).fold(0.0, f64::max);
    assert!(2.0 * fmax > f2, "the branch must pass f2/2: {fmax}");
    assert_eq!(alarm(&p, &pts), None);
}
