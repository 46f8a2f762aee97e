//! Obstacle frames and forces on hand-computed states: sdnd100a's frame, ANGL_VRIL, a
//! node in a CERCLE ring (DY, DZ), a BI_PLAN_Y between two nodes (equal and opposite
//! generalized forces), the output names.

use super::*;
use crate::transient::obstacle::obstacle_frame;

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tol)
}

/// NORM_OBST = global Y: local x = Y, y = −X, z = Z (Code_Aster's rot3d rule); with
/// ANGL_VRIL = 90° local y turns to z. Exact to 1e-15.
#[test]
fn frames_follow_code_aster_rule() {
    let f = obstacle_frame(ObstacleKind::PlanZ, [0.0, 1.0, 0.0], None, [0.0; 3], None).unwrap();
    assert!(close(f.rows[0], [0.0, 1.0, 0.0], 1e-15));
    assert!(close(f.rows[1], [-1.0, 0.0, 0.0], 1e-15));
    assert!(close(f.rows[2], [0.0, 0.0, 1.0], 1e-15));
    let f = obstacle_frame(
        ObstacleKind::PlanY,
        [1.0, 0.0, 0.0],
        Some(90.0),
        [0.0; 3],
        None,
    )
    .unwrap();
    assert!(close(f.rows[1], [0.0, 0.0, 1.0], 1e-15), "{:?}", f.rows);
    assert!(close(f.rows[2], [0.0, -1.0, 0.0], 1e-15), "{:?}", f.rows);
    // BI_PLAN_Z without ANGL_VRIL: local z along node 2 − node 1 (here global Y).
    let f = obstacle_frame(
        ObstacleKind::BiPlanZ,
        [1.0, 0.0, 0.0],
        None,
        [0.0; 3],
        Some([0.0, 2.0, 0.0]),
    )
    .unwrap();
    assert!(close(f.rows[2], [0.0, 1.0, 0.0], 1e-15), "{:?}", f.rows);
    // A general axis: the rows are orthonormal and x is NORM_OBST normalised.
    let n = [1.0, 2.0, -2.0];
    let f = obstacle_frame(ObstacleKind::Cercle, n, Some(30.0), [0.0; 3], None).unwrap();
    assert!(close(f.rows[0], [1.0 / 3.0, 2.0 / 3.0, -2.0 / 3.0], 1e-15));
    for i in 0..3 {
        for j in 0..3 {
            let d: f64 = (0..3).map(|c| f.rows[i][c] * f.rows[j][c]).sum();
            assert!((d - if i == j { 1.0 } else { 0.0 }).abs() < 1e-15);
        }
    }
}

fn ring(cn: f64) -> Shock {
    let spec = ShockSpec {
        obstacle: ObstacleKind::Cercle,
        orig_obst: [0.0; 3],
        norm_obst: [1.0, 0.0, 0.0],
        angl_vril: None,
        node1: [0.0; 3],
        node2: None,
        jeu: 1.0,
        dist1: 0.0,
        dist2: 0.0,
        rigi_nor: 1000.0,
        amor_nor: cn,
        rigi_tan: 0.0,
        amor_tan: 0.0,
        friction: Friction::None,
        friction_along_x_only: false,
    };
    // q = (DY, DZ).
    Shock::new(
        spec,
        NodeRows::from_modes(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0]),
        None,
    )
    .unwrap()
}

/// A node at r = 1.5 in a ring of radius 1 along (0.6, 0.8): penetration 0.5, force
/// 1000 × 0.5 toward the centre, −(0.6, 0.8) × 500; moving outward at 2 with AMOR_NOR = 10
/// adds 10 × 2; moving inward at 100 the damped force would pull: clipped to 0.
#[test]
fn cercle_force_points_to_the_centre() {
    let q = [0.9, 1.2];
    let s = ring(0.0);
    let e = s.evaluate(&q, &[0.0, 0.0], &ShockState::default());
    assert!((e.gap.dnorm + 0.5).abs() < 1e-12);
    assert!(close(e.force, [0.0, -300.0, -400.0], 1e-9), "{:?}", e.force);
    let mut gen = [0.0; 2];
    s.add_generalized(&e, &mut gen);
    assert!((gen[0] + 300.0).abs() < 1e-9 && (gen[1] + 400.0).abs() < 1e-9);
    let s = ring(10.0);
    let out = s.evaluate(&q, &[1.2, 1.6], &ShockState::default());
    assert!((out.sample.f_n - 520.0).abs() < 1e-9, "{}", out.sample.f_n);
    assert!((out.sample.v_n + 2.0).abs() < 1e-12);
    let inward = s.evaluate(&q, &[-60.0, -80.0], &ShockState::default());
    assert_eq!(inward.sample.f_n, 0.0);
    assert_eq!(inward.force, [0.0; 3]);
    // Inside the ring: no force.
    let free = s.evaluate(&[0.3, 0.4], &[1.0, 1.0], &ShockState::default());
    assert_eq!(free.force, [0.0; 3]);
    assert!((free.gap.dnorm - 0.5).abs() < 1e-12);
}

/// BI_PLAN_Y between node 1 at the origin and node 2 at (0, 1, 0), DIST_1 0.3, DIST_2 0.4
/// (gap 0.3 at rest); node 1 moved by 0.5 toward node 2: penetration 0.2, node 1 pushed
/// back (−Y) by 1000 × 0.2, node 2 by the opposite: generalized forces (−200, +200).
#[test]
fn two_node_shock_forces_are_equal_and_opposite() {
    let spec = ShockSpec {
        obstacle: ObstacleKind::BiPlanY,
        orig_obst: [0.0; 3],
        norm_obst: [1.0, 0.0, 0.0],
        angl_vril: None,
        node1: [0.0; 3],
        node2: Some([0.0, 1.0, 0.0]),
        jeu: 0.0,
        dist1: 0.3,
        dist2: 0.4,
        rigi_nor: 1000.0,
        amor_nor: 0.0,
        rigi_tan: 0.0,
        amor_tan: 0.0,
        friction: Friction::None,
        friction_along_x_only: false,
    };
    let r1 = NodeRows::from_modes(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 0.0]);
    let r2 = NodeRows::from_modes(&[0.0, 0.0], &[0.0, 1.0], &[0.0, 0.0]);
    let s = Shock::new(spec.clone(), r1.clone(), Some(r2.clone())).unwrap();
    let rest = s.evaluate(&[0.0, 0.0], &[0.0, 0.0], &ShockState::default());
    assert!((rest.gap.dnorm - 0.3).abs() < 1e-12);
    let e = s.evaluate(&[0.5, 0.0], &[0.0, 0.0], &ShockState::default());
    assert!((e.gap.dnorm + 0.2).abs() < 1e-12);
    assert!(close(e.force, [0.0, -200.0, 0.0], 1e-9), "{:?}", e.force);
    let mut gen = [0.0; 2];
    s.add_generalized(&e, &mut gen);
    assert!((gen[0] + 200.0).abs() < 1e-9 && (gen[1] - 200.0).abs() < 1e-9);
    // The same penetration by moving node 2 instead: same forces.
    let e2 = s.evaluate(&[0.0, -0.5], &[0.0, 0.0], &ShockState::default());
    assert!(close(e2.force, e.force, 1e-9));
    // Outputs: node 2's local position in VINT7..9, node 1's in DXLOC..DZLOC.
    assert_eq!(e2.sample.get("VINT8"), Some(0.5));
    assert_eq!(e2.sample.get("DYLOC"), Some(0.0));
    // BI_CERCLE of the same nodes and radii: repulsion along node 1 − node 2.
    let sc = Shock::new(
        ShockSpec {
            obstacle: ObstacleKind::BiCercle,
            ..spec
        },
        r1,
        Some(r2),
    )
    .unwrap();
    let ec = sc.evaluate(&[0.5, 0.0], &[0.0, 0.0], &ShockState::default());
    assert!(close(ec.force, [0.0, -200.0, 0.0], 1e-9), "{:?}", ec.force);
}

/// RECU_FONCTION's names and the 20 internal variables.
#[test]
fn sample_names() {
    let s = ShockSample {
        f_n: 1.0,
        f_t1: 2.0,
        v_t2: 6.0,
        loc1: [7.0, 8.0, 9.0],
        ..ShockSample::default()
    };
    assert_eq!(s.get("FN"), Some(1.0));
    assert_eq!(s.get("FT1"), Some(2.0));
    assert_eq!(s.get("VT2"), Some(6.0));
    assert_eq!(s.get("DZLOC"), Some(9.0));
    assert_eq!(s.get("VINT1"), Some(1.0));
    assert_eq!(s.get("VINT12"), Some(6.0));
    assert_eq!(s.get("VINT21"), None);
    assert_eq!(s.get("FOO"), None);
    assert_eq!(ObstacleKind::from_name("DISCRET"), None);
    assert_eq!(Scheme::from_name("ITMI"), None);
}
