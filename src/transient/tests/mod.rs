//! Tests of the transient module, one concern per file: an exact event-driven reference
//! (reference.rs) and the convergence against it (impact.rs), energy (energy.rs), the
//! Coulomb oscillator of sdnd100a (coulomb.rs), obstacle geometry and forces
//! (geometry.rs), a start from rest under a force (from_rest.rs), stability
//! (stability.rs), the sparse structure (sparse.rs), impact and wear statistics
//! (impact_stats.rs), PAS_ARCH with INST (archive_union.rs), moving supports on generated cases (support.rs),
//! Code_Aster's ADAPT_ORDRE1/2 (adapt.rs), Code_Aster's DEVOGE (devoge.rs), the buckling law FLAMBAGE against the
//! exact motion and a split run (flambage.rs), Code_Aster's
//! RUNGE_KUTTA_32/54 (runge_kutta.rs).

mod adapt;
mod archive_union;
mod coulomb;
mod devoge;
mod energy;
mod flambage;
mod from_rest;
mod geometry;
mod impact;
mod impact_stats;
mod reference;
mod runge_kutta;
mod sparse;
mod stability;
mod support;

use super::*;

/// sdnd100a's shock on one generalized coordinate moving the node along X: pressed on a
/// PLAN_Z plane (penetration 0.5, F_N = 10 N) with Coulomb friction μ = 0.1, a stick
/// spring RIGI_TAN 4e5 and the stick damper `amor_tan`. Shared by the unit tests of the
/// DEVOGE and Runge–Kutta loops.
pub(crate) fn sdnd100a_friction_shock(amor_tan: f64) -> Shock {
    let spec = ShockSpec {
        obstacle: ObstacleKind::PlanZ,
        orig_obst: [0.0, 0.0, 1.0],
        norm_obst: [1.0, 0.0, 0.0],
        angl_vril: None,
        node1: [0.0; 3],
        node2: None,
        jeu: 0.5,
        dist1: 0.0,
        dist2: 0.0,
        rigi_nor: 20.0,
        amor_nor: 0.0,
        rigi_tan: 4e5,
        amor_tan,
        friction: Friction::Coulomb { mu: 0.1 },
        friction_along_x_only: false,
    };
    Shock::new(spec, NodeRows::from_modes(&[1.0], &[0.0], &[0.0]), None).unwrap()
}

/// One DOF along global Y against a one-sided stop at y = g: a PLAN_Y obstacle whose
/// walls are at g and g − 2J, J = 10 (never reached), stiffness `kn`, damping `cn`.
pub(super) fn stop_shock(g: f64, kn: f64, cn: f64) -> Shock {
    Shock::new(
        stop_spec(g, kn, cn),
        NodeRows::from_modes(&[0.0], &[1.0], &[0.0]),
        None,
    )
    .unwrap()
}

/// The obstacle of [`stop_shock`], for rows of other coordinates.
pub(super) fn stop_spec(g: f64, kn: f64, cn: f64) -> ShockSpec {
    let j = 10.0;
    ShockSpec {
        obstacle: ObstacleKind::PlanY,
        orig_obst: [0.0, g - j, 0.0],
        norm_obst: [0.0, 0.0, 1.0],
        angl_vril: None,
        node1: [0.0; 3],
        node2: None,
        jeu: j,
        dist1: 0.0,
        dist2: 0.0,
        rigi_nor: kn,
        amor_nor: cn,
        rigi_tan: 0.0,
        amor_tan: 0.0,
        friction: Friction::None,
        friction_along_x_only: false,
    }
}

/// m = 1, k given, no damping.
pub(super) fn one_dof(k: f64) -> DenseStructure {
    DenseStructure::diagonal(vec![1.0], vec![k], None).unwrap()
}

pub(super) fn run(
    structure: &dyn Structure,
    shocks: &mut [Shock],
    init: (&[f64], &[f64]),
    scheme: Scheme,
    grid: TimeGrid,
    archive: &Archive,
) -> Result<Trajectory, TransientError> {
    integrate(
        structure,
        shocks,
        &[],
        init,
        scheme,
        grid,
        archive,
        &mut |_| {},
    )
}
