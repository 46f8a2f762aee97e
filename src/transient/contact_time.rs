//! How long a contact lasts, to judge a fixed step: each shock's normal stiffness against
//! the mass its node carries, ω_c² = RIGI_NOR · rᵀM⁻¹r with r the row of the normal
//! displacement (the largest over the directions the obstacle's normal can take), and the
//! contact duration π/ω_c of a mass pressed on that spring alone. The structure's own
//! stiffness shortens a real contact a little; the estimate ignores it.

use super::dis_choc::Shock;
use super::error::TransientError;
use super::obstacle::ObstacleKind;
use super::structure::Structure;

/// ω_c of each shock (0 for a shock whose normal the coordinates cannot move).
pub fn contact_pulsations(
    structure: &dyn Structure,
    shocks: &[Shock],
) -> Result<Vec<f64>, TransientError> {
    let n = structure.n();
    let mut r = vec![0.0; n];
    let mut x = vec![0.0; n];
    let mut out = Vec::with_capacity(shocks.len());
    for shock in shocks {
        let axes: &[usize] = match shock.spec.obstacle {
            ObstacleKind::PlanY | ObstacleKind::BiPlanY => &[1],
            ObstacleKind::PlanZ | ObstacleKind::BiPlanZ => &[2],
            _ => &[1, 2],
        };
        let mut flexibility = 0.0f64;
        for &axis in axes {
            // r = Σ_c (local axis)_c · (row c of the relative displacement).
            r.fill(0.0);
            let direction = shock.frame.rows[axis];
            for (c, row) in shock.relative_rows().rows.iter().enumerate() {
                for &(j, v) in row {
                    if j < n {
                        r[j] += direction[c] * v;
                    }
                }
            }
            x.copy_from_slice(&r);
            structure.solve_mass(&mut x)?;
            flexibility = flexibility.max(r.iter().zip(&x).map(|(a, b)| a * b).sum());
        }
        out.push((shock.spec.rigi_nor * flexibility).max(0.0).sqrt());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transient::dis_choc::Friction;
    use crate::transient::{DenseStructure, NodeRows, ShockSpec};

    /// A 2 kg mass on a PLAN_Y stop of RIGI_NOR 800: ω_c = √(800/2) = 20 rad/s exactly,
    /// whatever the structure's stiffness; a shock on a node the coordinates do not move
    /// along its normal has none.
    #[test]
    fn a_mass_on_its_contact_spring() {
        let s = DenseStructure::diagonal(vec![2.0, 3.0], vec![50.0, 70.0], None).unwrap();
        let spec = |norm: [f64; 3]| ShockSpec {
            obstacle: ObstacleKind::PlanY,
            orig_obst: [0.0; 3],
            norm_obst: norm,
            angl_vril: None,
            node1: [0.0; 3],
            node2: None,
            jeu: 1.0,
            dist1: 0.0,
            dist2: 0.0,
            rigi_nor: 800.0,
            amor_nor: 0.0,
            rigi_tan: 0.0,
            amor_tan: 0.0,
            friction: Friction::None,
            friction_along_x_only: false,
        };
        // NORM_OBST = Y: local y is -X; coordinate 0 is the node's DX.
        let along_x = NodeRows::from_modes(&[1.0, 0.0], &[0.0, 0.0], &[0.0, 0.0]);
        let moving = Shock::new(spec([0.0, 1.0, 0.0]), along_x.clone(), None).unwrap();
        // NORM_OBST = X: local y is Y, which no coordinate moves.
        let still = Shock::new(spec([1.0, 0.0, 0.0]), along_x, None).unwrap();
        let w = contact_pulsations(&s, &[moving, still]).unwrap();
        assert!((w[0] - 20.0).abs() < 1e-12, "{w:?}");
        assert_eq!(w[1], 0.0);
    }
}
