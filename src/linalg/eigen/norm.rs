//! Mode normalisation (Code_Aster NORM_MODE) and generalized mass/stiffness.

use super::sym::SymSparse;
use crate::error::{Error, Result};

/// How to scale a mode shape.
#[derive(Clone, Debug, PartialEq)]
pub enum ModeNorm {
    /// 'MASS_GENE': φᵀMφ = 1.
    MassGene,
    /// 'RIGI_GENE': φᵀKφ = 1 (impossible for rigid-body modes).
    RigiGene,
    /// Largest |component| = 1 among the DOFs where `mask` is true: 'TRAN' (translations
    /// only), 'TRAN_ROTA', and the default 'SANS_CMP=LAGR' (every physical DOF). The
    /// largest component is made +1.
    LargestComponent { mask: Vec<bool> },
    /// Euclidean norm over the DOFs where `mask` is true = 1: 'EUCL' (every DOF),
    /// 'EUCL_TRAN' (translations only). The factor is positive: the sign is kept.
    Euclidean { mask: Vec<bool> },
}

/// Generalized quantities of a scaled mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Normalized {
    /// The factor the input vector was multiplied by.
    pub scale: f64,
    /// φᵀMφ after scaling.
    pub gen_mass: f64,
    /// φᵀKφ after scaling.
    pub gen_stiff: f64,
}

/// An error unless `mask` has one entry per value of `phi`.
fn check_mask(phi: &[f64], mask: &[bool]) -> Result<()> {
    if mask.len() != phi.len() {
        return Err(Error::internal(format!(
            "normalisation mask has {} entries for a mode of {} DOFs",
            mask.len(),
            phi.len()
        )));
    }
    Ok(())
}

/// The value of largest magnitude among the masked DOFs, with its sign (the first of
/// equal magnitudes); 0 when they are all zero or none is masked.
pub fn largest_component(phi: &[f64], mask: &[bool]) -> Result<f64> {
    check_mask(phi, mask)?;
    let mut best = 0.0f64;
    for (v, &keep) in phi.iter().zip(mask) {
        if keep && v.abs() > best.abs() {
            best = *v;
        }
    }
    Ok(best)
}

/// √(Σ φ_i²) over the masked DOFs (0 when they are all zero or none is masked).
pub fn euclidean_norm(phi: &[f64], mask: &[bool]) -> Result<f64> {
    check_mask(phi, mask)?;
    Ok(phi
        .iter()
        .zip(mask)
        .filter(|(_, &keep)| keep)
        .map(|(v, _)| v * v)
        .sum::<f64>()
        .sqrt())
}

/// The error for a shape that is zero where a normalisation looks.
fn zero_norm() -> Error {
    Error::numerical("the mode has no nonzero component among the DOFs selected for normalisation")
        .keyword("NORM_MODE/NORME")
        .hint("choose a normalisation that includes the DOFs this mode moves (e.g. TRAN_ROTA)")
}

/// Scale making the largest |φ_i| over the masked DOFs equal to +1.
pub fn largest_component_scale(phi: &[f64], mask: &[bool]) -> Result<f64> {
    let best = largest_component(phi, mask)?;
    if best == 0.0 || !best.is_finite() {
        return Err(zero_norm());
    }
    Ok(1.0 / best)
}

/// Scale (positive) making the Euclidean norm over the masked DOFs equal to 1.
pub fn euclidean_scale(phi: &[f64], mask: &[bool]) -> Result<f64> {
    let norm = euclidean_norm(phi, mask)?;
    if norm == 0.0 || !norm.is_finite() {
        return Err(zero_norm());
    }
    Ok(1.0 / norm)
}

/// The factor making a generalized mass or stiffness `value` (φᵀAφ before scaling) equal
/// to 1: 1/√value; `None` when `value` is not positive and finite.
pub fn generalized_scale(value: f64) -> Option<f64> {
    (value > 0.0 && value.is_finite()).then(|| 1.0 / value.sqrt())
}

/// Whether a generalized stiffness `gen_stiff` = φᵀKφ is round-off (a rigid-body mode, or
/// a shape K does not strain): at most 1e-10 of `k_scale`·Σφ², `k_scale` the largest
/// |K_ii|, `phi_sq` = Σφ². Not positive is zero too.
pub fn stiffness_is_round_off(gen_stiff: f64, k_scale: f64, phi_sq: f64) -> bool {
    gen_stiff <= 1e-10 * k_scale * phi_sq || !gen_stiff.is_finite()
}

/// φᵀAφ for a matrix given by its entries (row, col, value) with both triangles stored
/// (an assembled matrix's full triplets). An error if an entry is outside `phi`.
pub fn quadratic_form(triplets: &[(usize, usize, f64)], phi: &[f64]) -> Result<f64> {
    let mut sum = 0.0;
    for &(i, j, v) in triplets {
        match (phi.get(i), phi.get(j)) {
            (Some(a), Some(b)) => sum += a * v * b,
            _ => {
                return Err(Error::internal(format!(
                    "matrix entry ({i}, {j}) outside a mode of {} DOFs",
                    phi.len()
                )))
            }
        }
    }
    Ok(sum)
}

/// (φᵀMφ, φᵀKφ).
fn generalized(phi: &[f64], k: &SymSparse, m: &SymSparse) -> (f64, f64) {
    (m.form(phi, phi), k.form(phi, phi))
}

/// Scales `phi` in place and returns the scale and generalized mass/stiffness.
pub fn normalize(
    phi: &mut [f64],
    k: &SymSparse,
    m: &SymSparse,
    norm: &ModeNorm,
) -> Result<Normalized> {
    if phi.len() != k.n || m.n != k.n {
        return Err(Error::internal(format!(
            "mode of {} DOFs for matrices of {} and {} DOFs",
            phi.len(),
            k.n,
            m.n
        )));
    }
    let (gm, gk) = generalized(phi, k, m);
    let scale = match norm {
        ModeNorm::MassGene => {
            if gm <= 0.0 || !gm.is_finite() {
                return Err(Error::numerical(format!(
                    "generalized mass {gm:e} is not positive: cannot normalise to MASS_GENE"
                ))
                .keyword("NORM_MODE/NORME"));
            }
            1.0 / gm.sqrt()
        }
        ModeNorm::RigiGene => {
            // A rigid-body mode has φᵀKφ at round-off level relative to the stiffness scale.
            let kscale = k.diag().iter().fold(0.0f64, |a, d| a.max(d.abs()));
            let pp: f64 = phi.iter().map(|x| x * x).sum();
            if stiffness_is_round_off(gk, kscale, pp) {
                return Err(Error::numerical(format!(
                    "generalized stiffness {gk:e} is zero or negative (rigid-body mode?): \
                     cannot normalise to RIGI_GENE"
                ))
                .keyword("NORM_MODE/NORME")
                .hint("use NORME='MASS_GENE' for free-free structures"));
            }
            1.0 / gk.sqrt()
        }
        ModeNorm::LargestComponent { mask } => largest_component_scale(phi, mask)?,
        ModeNorm::Euclidean { mask } => euclidean_scale(phi, mask)?,
    };
    phi.iter_mut().for_each(|x| *x *= scale);
    Ok(Normalized {
        scale,
        gen_mass: gm * scale * scale,
        gen_stiff: gk * scale * scale,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_dof() -> (SymSparse, SymSparse) {
        // K = [[3, -1], [-1, 2]], M = diag(2, 1): small enough to check by hand.
        let k = SymSparse::from_lower_triplets(2, &[(0, 0, 3.0), (1, 0, -1.0), (1, 1, 2.0)]);
        let m = SymSparse::from_lower_triplets(2, &[(0, 0, 2.0), (1, 1, 1.0)]);
        (k, m)
    }

    #[test]
    fn mass_and_stiffness_normalisations_hit_their_targets() {
        let (k, m) = two_dof();
        let mut phi = vec![1.0, 2.0];
        // φᵀMφ = 2 + 4 = 6, φᵀKφ = 3 - 4 + 8 = 7 (computed by hand).
        let r = normalize(&mut phi, &k, &m, &ModeNorm::MassGene).unwrap();
        assert!((r.scale - 1.0 / 6f64.sqrt()).abs() < 1e-15);
        assert!((r.gen_mass - 1.0).abs() < 1e-14);
        assert!((r.gen_stiff - 7.0 / 6.0).abs() < 1e-14);
        let mut phi = vec![1.0, 2.0];
        let r = normalize(&mut phi, &k, &m, &ModeNorm::RigiGene).unwrap();
        assert!((r.gen_stiff - 1.0).abs() < 1e-14);
        assert!((r.gen_mass - 6.0 / 7.0).abs() < 1e-14);
    }

    #[test]
    fn largest_component_respects_mask_and_sign() {
        let (k, m) = two_dof();
        let mut phi = vec![0.5, -4.0];
        let r = normalize(
            &mut phi,
            &k,
            &m,
            &ModeNorm::LargestComponent {
                mask: vec![true, true],
            },
        )
        .unwrap();
        assert_eq!(phi, vec![-0.125, 1.0]);
        assert_eq!(r.scale, -0.25);
        // Masking the second DOF out: the first one becomes 1.
        let s = largest_component_scale(&[0.5, -4.0], &[true, false]).unwrap();
        assert_eq!(s, 2.0);
        assert!(largest_component_scale(&[0.0, 3.0], &[true, false]).is_err());
    }

    #[test]
    fn euclidean_norms_respect_mask_and_keep_the_sign() {
        // (3, -4, 12): |.| = 13 over all; 5 over the first two.
        let phi = [3.0, -4.0, 12.0];
        assert_eq!(euclidean_norm(&phi, &[true, true, true]).unwrap(), 13.0);
        assert_eq!(euclidean_norm(&phi, &[true, true, false]).unwrap(), 5.0);
        assert_eq!(euclidean_scale(&phi, &[true, true, false]).unwrap(), 0.2);
        assert!(euclidean_scale(&phi, &[false, false, false]).is_err());
        assert!(euclidean_scale(&[0.0, 0.0, 1.0], &[true, true, false]).is_err());
        assert!(euclidean_norm(&phi, &[true]).is_err());
        // Through normalize: the factor is positive and the norm becomes 1.
        let (k, m) = two_dof();
        let mut phi = vec![-3.0, 4.0];
        let r = normalize(
            &mut phi,
            &k,
            &m,
            &ModeNorm::Euclidean {
                mask: vec![true, true],
            },
        )
        .unwrap();
        assert_eq!(r.scale, 0.2);
        assert!((phi[0] + 0.6).abs() < 1e-15 && (phi[1] - 0.8).abs() < 1e-15);
        // φᵀMφ = 2·9 + 16 = 34 before, ×0.04 after.
        assert!((r.gen_mass - 34.0 * 0.04).abs() < 1e-14);
    }

    #[test]
    fn largest_component_is_signed_and_first_of_equals() {
        assert_eq!(
            largest_component(&[1.0, -3.0, 3.0], &[true, true, true]).unwrap(),
            -3.0
        );
        assert_eq!(
            largest_component(&[1.0, -3.0, 3.0], &[true, false, true]).unwrap(),
            3.0
        );
        assert_eq!(
            largest_component(&[1.0, -3.0], &[false, false]).unwrap(),
            0.0
        );
        // A one-DOF mask is NOEUD/NOM_CMP: that component becomes 1.
        assert_eq!(
            largest_component_scale(&[1.0, -4.0, 2.0], &[false, false, true]).unwrap(),
            0.5
        );
    }

    #[test]
    fn generalized_scale_and_round_off_stiffness() {
        assert_eq!(generalized_scale(4.0), Some(0.5));
        assert_eq!(generalized_scale(0.0), None);
        assert_eq!(generalized_scale(-1.0), None);
        assert_eq!(generalized_scale(f64::NAN), None);
        assert_eq!(generalized_scale(f64::INFINITY), None);
        assert!(stiffness_is_round_off(1e-12, 1.0, 1.0));
        assert!(!stiffness_is_round_off(1e-9, 1.0, 1.0));
        assert!(stiffness_is_round_off(-1.0, 1.0, 1.0));
        assert!(stiffness_is_round_off(f64::NAN, 1.0, 1.0));
    }

    #[test]
    fn quadratic_form_of_full_triplets_matches_the_symmetric_form() {
        // K = [[3, -1], [-1, 2]] with both triangles: (1, 2)ᵀK(1, 2) = 3 - 4 + 8 = 7.
        let t = [(0, 0, 3.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 2.0)];
        assert_eq!(quadratic_form(&t, &[1.0, 2.0]).unwrap(), 7.0);
        let (k, _) = two_dof();
        assert_eq!(k.form(&[1.0, 2.0], &[1.0, 2.0]), 7.0);
        assert!(quadratic_form(&t, &[1.0]).is_err());
    }

    #[test]
    fn rigi_gene_refuses_rigid_body_mode() {
        // Free-free 2-DOF spring: K = [[1,-1],[-1,1]], rigid mode (1, 1).
        let k = SymSparse::from_lower_triplets(2, &[(0, 0, 1.0), (1, 0, -1.0), (1, 1, 1.0)]);
        let m = SymSparse::from_lower_triplets(2, &[(0, 0, 1.0), (1, 1, 1.0)]);
        let mut phi = vec![1.0, 1.0];
        assert!(normalize(&mut phi, &k, &m, &ModeNorm::RigiGene).is_err());
    }
}
