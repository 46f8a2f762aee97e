//! 3D Euler-Bernoulli beam (POU_D_E) and bar (BARRE) element matrices in local axes.
//! Local DOF order per node: DX DY DZ DRX DRY DRZ (node 1 then node 2).

/// Beam properties needed by the matrices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BeamProps {
    pub e: f64,
    pub g: f64,
    pub a: f64,
    pub iy: f64,
    pub iz: f64,
    pub jx: f64,
}

fn put(m: &mut [f64], n: usize, dofs: &[usize], block: &[&[f64]]) {
    for (i, row) in block.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            if let (Some(&r), Some(&c)) = (dofs.get(i), dofs.get(j)) {
                m[r * n + c] += v;
            }
        }
    }
}

/// Local 12×12 stiffness (row-major): axial EA/L, torsion GJ/L, bending in xy (v, θz) with
/// Iz and in xz (w, θy) with Iy, shear deformation neglected.
pub fn beam_stiffness_local(p: &BeamProps, l: f64) -> Vec<f64> {
    let mut k = vec![0.0; 144];
    let ea = p.e * p.a / l;
    let gj = p.g * p.jx / l;
    put(&mut k, 12, &[0, 6], &[&[ea, -ea], &[-ea, ea]]);
    put(&mut k, 12, &[3, 9], &[&[gj, -gj], &[-gj, gj]]);
    let (l2, l3) = (l * l, l * l * l);
    // xy plane: (v1, θz1, v2, θz2), θz = dv/dx.
    let c = p.e * p.iz / l3;
    put(
        &mut k,
        12,
        &[1, 5, 7, 11],
        &[
            &[12.0 * c, 6.0 * l * c, -12.0 * c, 6.0 * l * c],
            &[6.0 * l * c, 4.0 * l2 * c, -6.0 * l * c, 2.0 * l2 * c],
            &[-12.0 * c, -6.0 * l * c, 12.0 * c, -6.0 * l * c],
            &[6.0 * l * c, 2.0 * l2 * c, -6.0 * l * c, 4.0 * l2 * c],
        ],
    );
    // xz plane: (w1, θy1, w2, θy2), θy = −dw/dx flips the coupling signs.
    let c = p.e * p.iy / l3;
    put(
        &mut k,
        12,
        &[2, 4, 8, 10],
        &[
            &[12.0 * c, -6.0 * l * c, -12.0 * c, -6.0 * l * c],
            &[-6.0 * l * c, 4.0 * l2 * c, 6.0 * l * c, 2.0 * l2 * c],
            &[-12.0 * c, 6.0 * l * c, 12.0 * c, 6.0 * l * c],
            &[-6.0 * l * c, 2.0 * l2 * c, 6.0 * l * c, 4.0 * l2 * c],
        ],
    );
    k
}

/// Local 12×12 consistent mass: linear shape functions for the axial displacement and the
/// torsion (rotational inertia ρ (Iy + Iz) L, the polar moment of the section), cubic
/// Hermite functions for bending; the rotary inertia of bending is neglected
/// (Euler-Bernoulli).
pub fn beam_mass_local(rho: f64, a: f64, iy: f64, iz: f64, l: f64) -> Vec<f64> {
    let mut m = vec![0.0; 144];
    let ma = rho * a * l / 6.0;
    put(&mut m, 12, &[0, 6], &[&[2.0 * ma, ma], &[ma, 2.0 * ma]]);
    let mt = rho * (iy + iz) * l / 6.0;
    put(&mut m, 12, &[3, 9], &[&[2.0 * mt, mt], &[mt, 2.0 * mt]]);
    let c = rho * a * l / 420.0;
    let l2 = l * l;
    put(
        &mut m,
        12,
        &[1, 5, 7, 11],
        &[
            &[156.0 * c, 22.0 * l * c, 54.0 * c, -13.0 * l * c],
            &[22.0 * l * c, 4.0 * l2 * c, 13.0 * l * c, -3.0 * l2 * c],
            &[54.0 * c, 13.0 * l * c, 156.0 * c, -22.0 * l * c],
            &[-13.0 * l * c, -3.0 * l2 * c, -22.0 * l * c, 4.0 * l2 * c],
        ],
    );
    put(
        &mut m,
        12,
        &[2, 4, 8, 10],
        &[
            &[156.0 * c, -22.0 * l * c, 54.0 * c, 13.0 * l * c],
            &[-22.0 * l * c, 4.0 * l2 * c, -13.0 * l * c, -3.0 * l2 * c],
            &[54.0 * c, -13.0 * l * c, 156.0 * c, 22.0 * l * c],
            &[13.0 * l * c, -3.0 * l2 * c, 22.0 * l * c, 4.0 * l2 * c],
        ],
    );
    m
}

/// Local 6×6 bar stiffness (DX DY DZ per node): EA/L on the axial component only.
pub fn bar_stiffness_local(e: f64, a: f64, l: f64) -> Vec<f64> {
    let mut k = vec![0.0; 36];
    let ea = e * a / l;
    put(&mut k, 6, &[0, 3], &[&[ea, -ea], &[-ea, ea]]);
    k
}

/// 6×6 consistent bar mass: linear interpolation of all three translations,
/// ρAL/6 [[2, 1], [1, 2]] ⊗ I₃ (the same in every frame).
pub fn bar_mass(rho: f64, a: f64, l: f64) -> Vec<f64> {
    let mut m = vec![0.0; 36];
    let c = rho * a * l / 6.0;
    for i in 0..3 {
        put(&mut m, 6, &[i, 3 + i], &[&[2.0 * c, c], &[c, 2.0 * c]]);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_translations_and_rotation_have_no_strain_energy() {
        let p = BeamProps {
            e: 2.1e11,
            g: 8e10,
            a: 1e-2,
            iy: 2e-5,
            iz: 3e-5,
            jx: 4e-5,
        };
        let l = 1.7;
        let k = beam_stiffness_local(&p, l);
        // rigid rotation about z by θ: v = x θ, θz = θ at both nodes.
        let mut u = [0.0; 12];
        u[5] = 1.0;
        u[11] = 1.0;
        u[7] = l;
        for r in 0..12 {
            let f: f64 = (0..12).map(|c| k[r * 12 + c] * u[c]).sum();
            assert!(f.abs() < 1e-6 * p.e * p.iz, "row {r}: {f}");
        }
        // rigid rotation about y: w = −x θ, θy = θ.
        let mut u = [0.0; 12];
        u[4] = 1.0;
        u[10] = 1.0;
        u[8] = -l;
        for r in 0..12 {
            let f: f64 = (0..12).map(|c| k[r * 12 + c] * u[c]).sum();
            assert!(f.abs() < 1e-6 * p.e * p.iy, "row {r}: {f}");
        }
    }

    #[test]
    fn consistent_mass_total_is_rho_a_l() {
        // A unit rigid translation in y carries kinetic mass uᵀ M u = ρ A L exactly.
        let (rho, a, l) = (7800.0, 0.01, 2.0);
        let m = beam_mass_local(rho, a, 1e-5, 1e-5, l);
        let mut u = [0.0; 12];
        u[1] = 1.0;
        u[7] = 1.0;
        let e: f64 = (0..12)
            .flat_map(|r| (0..12).map(move |c| (r, c)))
            .map(|(r, c)| u[r] * m[r * 12 + c] * u[c])
            .sum();
        assert!((e - rho * a * l).abs() < 1e-9 * rho * a * l);
    }
}
