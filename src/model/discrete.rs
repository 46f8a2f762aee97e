//! Element matrices of discrete elements (DIS_T, DIS_TR, 2D_DIS_T) from their CARA values.

use super::cara::{DiscreteForm, DiscreteValue, Repere};
use super::frame::{rotate_to_global, Frame};

/// Dense row-major matrix of the discrete element, in global axes. `nd` is the number of
/// components per node (2, 3 or 6); `frame` is the local frame of a SEG2 (required when
/// the value is given with REPERE='LOCAL'; a POI1 has the global axes as local axes).
/// The caller has checked the value count against the CARA (`DiscreteSpec::value_count`).
pub fn discrete_matrix(dv: &DiscreteValue, nd: usize, frame: Option<&Frame>) -> Vec<f64> {
    let nodes = if dv.spec.on_segment { 2 } else { 1 };
    let n = nd * nodes;
    let v = |i: usize| dv.values.get(i).copied().unwrap_or(0.0);
    let mut m = vec![0.0; n * n];
    let ntr = nd.min(3);
    match dv.spec.form {
        DiscreteForm::Diagonal => {
            for i in 0..nd {
                for a in 0..nodes {
                    for b in 0..nodes {
                        let sign = if a == b { 1.0 } else { -1.0 };
                        m[(a * nd + i) * n + b * nd + i] = sign * v(i);
                    }
                }
            }
        }
        DiscreteForm::NodalMass | DiscreteForm::SegmentMass => {
            let share = v(0) / nodes as f64;
            for a in 0..nodes {
                for i in 0..ntr {
                    m[(a * nd + i) * n + a * nd + i] = share;
                }
            }
        }
        DiscreteForm::RigidBodyMass => {
            // Kinetic energy of a rigid body whose centre of gravity sits at c from the
            // node: ½ m |v + ω × c|² + ½ ωᵀ J ω, J the inertia tensor at the centre of
            // gravity (Ixy... are its off-diagonal components). With S(c) ω = c × ω:
            // M = [[m I, −m S], [m S, J + m (|c|² I − c cᵀ)]].
            let mass = v(0);
            let c = [v(1), v(2), v(3)];
            let j = [[v(4), v(7), v(8)], [v(7), v(5), v(9)], [v(8), v(9), v(6)]];
            let s = [[0.0, -c[2], c[1]], [c[2], 0.0, -c[0]], [-c[1], c[0], 0.0]];
            let c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
            for i in 0..3 {
                m[i * n + i] = mass;
                for k in 0..3 {
                    m[i * n + 3 + k] = -mass * s[i][k];
                    m[(3 + i) * n + k] = mass * s[i][k];
                    let delta = if i == k { c2 } else { 0.0 };
                    m[(3 + i) * n + 3 + k] = j[i][k] + mass * (delta - c[i] * c[k]);
                }
            }
        }
        DiscreteForm::Symmetric => {
            // Upper triangle column by column: (0,0), (0,1), (1,1), (0,2), (1,2), (2,2)...
            let mut k = 0;
            for col in 0..n {
                for row in 0..=col {
                    let x = v(k);
                    m[row * n + col] = x;
                    m[col * n + row] = x;
                    k += 1;
                }
            }
        }
    }
    match (dv.repere, frame) {
        (Repere::Local, Some(f)) => rotate_to_global(&m, n, f, if nd == 2 { 2 } else { 3 }),
        _ => m,
    }
}

#[cfg(test)]
mod tests {
    use super::super::cara::DiscreteSpec;
    use super::super::frame::segment_frame;
    use super::*;

    fn dv(cara: &str, values: Vec<f64>, repere: Repere) -> DiscreteValue {
        DiscreteValue {
            cara: cara.into(),
            spec: DiscreteSpec::parse(cara).unwrap(),
            values,
            repere,
        }
    }

    #[test]
    fn segment_spring_is_k_minus_k() {
        let m = discrete_matrix(
            &dv("K_T_D_L", vec![10.0, 2.0, 3.0], Repere::Global),
            3,
            None,
        );
        assert_eq!(m[0], 10.0);
        assert_eq!(m[3], -10.0);
        assert_eq!(m[6 + 1 + 6 * 3 + 3], 2.0); // row 4 col 4 (node 2, DY)
        assert_eq!(m[6 + 1 + 3], -2.0); // row 1 col 4
    }

    #[test]
    fn local_spring_along_diagonal_rotates() {
        // A spring k along the local axis of a segment at 45° in XY gives the global
        // block k n nᵀ with n = (1,1,0)/√2: all four XY entries k/2.
        let f = segment_frame([0.0; 3], [1.0, 1.0, 0.0], None).unwrap();
        let m = discrete_matrix(
            &dv("K_T_D_L", vec![4.0, 0.0, 0.0], Repere::Local),
            3,
            Some(&f),
        );
        for (r, c) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            assert!((m[r * 6 + c] - 2.0).abs() < 1e-14);
            assert!((m[r * 6 + c + 3] + 2.0).abs() < 1e-14);
        }
        assert!(m[2 * 6 + 2].abs() < 1e-14);
    }

    #[test]
    fn rigid_body_mass_with_offset() {
        // m at c = (0, 0, h): rotation about X moves the mass along -Y by h θ, so
        // M[DY][DRX] = −m h and M[DRX][DRX] = Ixx + m h².
        let (m, h) = (2.0, 0.5);
        let mm = discrete_matrix(
            &dv(
                "M_TR_D_N",
                vec![m, 0.0, 0.0, h, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
                Repere::Global,
            ),
            6,
            None,
        );
        assert!((mm[6 + 3] + m * h).abs() < 1e-15);
        assert!((mm[3 * 6 + 1] + m * h).abs() < 1e-15);
        assert!((mm[3 * 6 + 3] - (1.0 + m * h * h)).abs() < 1e-15);
        assert!((mm[5 * 6 + 5] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn symmetric_form_column_order() {
        let m = discrete_matrix(
            &dv("K_T_N", vec![1., 2., 3., 4., 5., 6.], Repere::Global),
            3,
            None,
        );
        assert_eq!(m, vec![1., 2., 4., 2., 3., 5., 4., 5., 6.]);
    }

    proptest::proptest! {
        /// Any segment direction and local spring values: the global matrix is symmetric,
        /// a rigid translation of both nodes produces no force, and the trace (invariant
        /// under rotation) is that of the local matrix, 2 (kx + ky + kz).
        #[test]
        fn local_spring_rotation_invariants(
            dx in -1.0f64..1.0, dy in -1.0f64..1.0, dz in -1.0f64..1.0,
            kx in 0.0f64..100.0, ky in 0.0f64..100.0, kz in 0.0f64..100.0,
            tx in -1.0f64..1.0, ty in -1.0f64..1.0, tz in -1.0f64..1.0,
        ) {
            proptest::prop_assume!((dx * dx + dy * dy + dz * dz).sqrt() > 1e-3);
            let f = segment_frame([0.0; 3], [dx, dy, dz], None).unwrap();
            let m = discrete_matrix(&dv("K_T_D_L", vec![kx, ky, kz], Repere::Local), 3, Some(&f));
            let scale = 1e-12 * (kx + ky + kz + 1.0);
            for i in 0..6 {
                for j in 0..6 {
                    proptest::prop_assert!((m[i * 6 + j] - m[j * 6 + i]).abs() < scale);
                }
                let t = [tx, ty, tz, tx, ty, tz];
                let force: f64 = (0..6).map(|j| m[i * 6 + j] * t[j]).sum();
                proptest::prop_assert!(force.abs() < 10.0 * scale);
            }
            let trace: f64 = (0..6).map(|i| m[i * 6 + i]).sum();
            proptest::prop_assert!((trace - 2.0 * (kx + ky + kz)).abs() < 10.0 * scale);
        }
    }
}
