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

/// Scale making the largest |φ_i| over the masked DOFs equal to +1.
pub fn largest_component_scale(phi: &[f64], mask: &[bool]) -> Result<f64> {
    if mask.len() != phi.len() {
        return Err(Error::internal(format!(
            "normalisation mask has {} entries for a mode of {} DOFs",
            mask.len(),
            phi.len()
        )));
    }
    let mut best = 0.0f64;
    for (v, &keep) in phi.iter().zip(mask) {
        if keep && v.abs() > best.abs() {
            best = *v;
        }
    }
    if best == 0.0 || !best.is_finite() {
        return Err(Error::numerical(
            "the mode has no nonzero component among the DOFs selected for normalisation",
        )
        .keyword("NORM_MODE/NORME")
        .hint("choose a normalisation that includes the DOFs this mode moves (e.g. TRAN_ROTA)"));
    }
    Ok(1.0 / best)
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
            if gk <= 1e-10 * kscale * pp || !gk.is_finite() {
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
    fn rigi_gene_refuses_rigid_body_mode() {
        // Free-free 2-DOF spring: K = [[1,-1],[-1,1]], rigid mode (1, 1).
        let k = SymSparse::from_lower_triplets(2, &[(0, 0, 1.0), (1, 0, -1.0), (1, 1, 1.0)]);
        let m = SymSparse::from_lower_triplets(2, &[(0, 0, 1.0), (1, 1, 1.0)]);
        let mut phi = vec![1.0, 1.0];
        assert!(normalize(&mut phi, &k, &m, &ModeNorm::RigiGene).is_err());
    }
}
