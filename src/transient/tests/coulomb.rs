//! Code_Aster's sdnd100a: one node (m = 1, k = 1e4 in X, Y, Z), DZ blocked, DX = DY, a
//! PLAN_Z obstacle (ORIG_OBST (0,0,1), NORM_OBST (0,1,0), JEU 0.5, RIGI_NOR 20, RIGI_TAN
//! 4e5, COULOMB 0.1), U0 = 0.85e-3 along the DX = DY line, DIFF_CENTRE, PAS 5e-4. The node
//! stays 1 from the plane's origin along local z with a gap of 0.5: constant penetration
//! 0.5, F_N = 10 N = m g, and the motion is a Coulomb oscillator whose amplitude drops by
//! 2C = 2 μ m g / k per half period. Reduced here to its one mode φ = (cos π/4, cos π/4, 0).

use super::*;

/// The sdnd100a slider reduced to its one mode, run with DIFF_CENTRE over 0.3 s and
/// archived at the half periods jπ/ω₀, j = 1..4; `one_axis`: UNIDIRECTIONNEL='OUI'
/// (sdnd100d). Returns the trajectory and the instants.
fn diagonal_slider(one_axis: bool, dt: f64) -> (Trajectory, Vec<f64>) {
    let (m, k, u0, mu) = (1.0, 1e4, 0.85e-3, 0.1);
    let c = (std::f64::consts::PI / 4.0).cos();
    // Mass-normalised mode on (DX, DY): φᵀ M φ = 2c² m = 1, φᵀ K φ = k.
    let s = DenseStructure::diagonal(vec![2.0 * c * c * m], vec![2.0 * c * c * k], None).unwrap();
    let spec = ShockSpec {
        obstacle: ObstacleKind::from_name("PLAN_Z").unwrap(),
        orig_obst: [0.0, 0.0, 1.0],
        norm_obst: [0.0, 1.0, 0.0],
        angl_vril: None,
        node1: [0.0; 3],
        node2: None,
        jeu: 0.5,
        dist1: 0.0,
        dist2: 0.0,
        rigi_nor: 20.0,
        amor_nor: 0.0,
        rigi_tan: 4e5,
        amor_tan: 0.0,
        friction: Friction::Coulomb { mu },
        friction_along_x_only: one_axis,
    };
    let rows = NodeRows::from_modes(&[c], &[c], &[0.0]);
    let probe = Shock::new(spec.clone(), rows.clone(), None).unwrap();
    // AMOR_TAN not given: Code_Aster's optimised value (mode mass 1, ω² = k, ξ = 0).
    let amor_tan = optimized_tangential_damping(&probe, &[1.0], &[k], &[0.0]).unwrap();
    assert!((amor_tan - 2.0 * (k + 4e5f64).sqrt()).abs() < 1e-9);
    let mut shocks = vec![Shock::new(ShockSpec { amor_tan, ..spec }, rows, None).unwrap()];
    // DEPINI = projection of U1 = U0 cos π/4 on DX and DY: q0 = φᵀ M u = U0.
    let q0 = 2.0 * c * c * u0;
    let w0 = (k / m).sqrt();
    let tj: Vec<f64> = (1..=4)
        .map(|j| j as f64 * std::f64::consts::PI / w0)
        .collect();
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 0.3,
        dt,
    };
    let traj = run(
        &s,
        &mut shocks,
        (&[q0], &[0.0]),
        Scheme::from_name("DIFF_CENTRE").unwrap(),
        grid,
        &Archive::Instants(tj.clone()),
    )
    .unwrap();
    (traj, tj)
}

#[test]
fn sdnd100a_coulomb_oscillator() {
    let (m, k, g, u0, mu) = (1.0, 1e4, 10.0, 0.85e-3, 0.1);
    let c = (std::f64::consts::PI / 4.0).cos();
    let (traj, _) = diagonal_slider(false, 5e-4);
    let cc = mu * m * g / k;
    let reference = [
        (2.0 * cc - u0) * c,
        (u0 - 4.0 * cc) * c,
        (6.0 * cc - u0) * c,
        (u0 - 8.0 * cc) * c,
    ];
    // Code_Aster's published references are these rounded: -4.596e-4, 3.182e-4, ...
    for (r, p) in reference
        .iter()
        .zip([-4.596e-4, 3.182e-4, -1.768e-4, 3.536e-5])
    {
        assert!((r - p).abs() < 1e-7);
    }
    // The shock: constant penetration 0.5 (FN = 10 N) at every archived instant.
    for s in &traj.shocks[0] {
        assert!((s.f_n - 10.0).abs() < 1e-9, "FN = {}", s.f_n);
        assert!((s.get("DZLOC").unwrap() + 1.0).abs() < 1e-12);
    }
    // DY = φ_DY q. Code_Aster's test: 1e-3 relative for the first three, 5e-3 for the
    // last (the smallest value, 3.5e-5, where the absolute error weighs most).
    for (i, (&r, prec)) in reference.iter().zip([1e-3, 1e-3, 1e-3, 5e-3]).enumerate() {
        let dy = c * traj.q_at(i)[0];
        let rel = (dy - r).abs() / r.abs();
        eprintln!(
            "t = {:.6}: DY = {dy:e}, reference {r:e}, relative {rel:e}",
            traj.t[i]
        );
        assert!(rel < prec, "instant {i}: {dy:e} vs {r:e} ({rel:e})");
    }
}

/// UNIDIRECTIONNEL='OUI' (Code_Aster's sdnd100d): the friction acts along the local x axis
/// (NORM_OBST = global Y) only. The slider moves along DX = DY, so the friction force μ F_N
/// on Y has the share cos π/4 along the motion: the amplitude drops by 2C per half period
/// with C = μ (√2/2) m g / k instead of μ m g / k. The component across the axis (FT1) is
/// zero at every archived instant. Tolerances as Code_Aster's file: 1e-3 relative, 5e-3 on
/// the smallest value; the step 1e-5 keeps DIFF_CENTRE's stick/slip error below them.
#[test]
fn one_axis_friction_acts_along_norm_obst_only() {
    let (m, k, g, u0, mu) = (1.0, 1e4, 10.0, 0.85e-3, 0.1);
    let c = (std::f64::consts::PI / 4.0).cos();
    let (traj, _) = diagonal_slider(true, 1e-5);
    let cc = mu * c * m * g / k;
    let reference = [
        (2.0 * cc - u0) * c,
        (u0 - 4.0 * cc) * c,
        (6.0 * cc - u0) * c,
        (u0 - 8.0 * cc) * c,
    ];
    for s in &traj.shocks[0] {
        assert!(s.f_t1.abs() < 1e-12, "FT1 = {:e}", s.f_t1);
    }
    for (i, (&r, prec)) in reference.iter().zip([1e-3, 1e-3, 1e-3, 5e-3]).enumerate() {
        let dy = c * traj.q_at(i)[0];
        let rel = (dy - r).abs() / r.abs();
        assert!(rel < prec, "instant {i}: {dy:e} vs {r:e} ({rel:e})");
    }
    // Without the flag the same run decays by the full μ m g / k: the flag matters.
    let (both, _) = diagonal_slider(false, 1e-5);
    let dy4 = c * both.q_at(3)[0];
    assert!((dy4 - reference[3]).abs() / reference[3].abs() > 0.5);
}
