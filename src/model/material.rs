//! Materials (DEFI_MATERIAU) and material fields (AFFE_MATERIAU).

use super::select::model_select_cells;
use crate::error::Result;
use crate::mesh::select::Selection;
use crate::mesh::Mesh;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// ELAS: isotropic linear elasticity.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Elas {
    pub e: f64,
    pub nu: f64,
    /// Density; optional as in Code_Aster, required only by mass matrices.
    pub rho: Option<f64>,
    /// Rayleigh damping, Code_Aster's AMOR_ALPHA: the coefficient of the *stiffness* in
    /// the element damping matrix of OPTION='AMOR_MECA', C_e = AMOR_ALPHA K_e +
    /// AMOR_BETA M_e (absent: 0).
    #[serde(default)]
    pub amor_alpha: f64,
    /// Rayleigh damping, Code_Aster's AMOR_BETA: the coefficient of the *mass* (absent: 0).
    #[serde(default)]
    pub amor_beta: f64,
}

/// Why elastic constants are refused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ElasError {
    /// Young's modulus not positive.
    YoungModulus(f64),
    /// Poisson's ratio outside ]-1, 0.5[.
    PoissonRatio(f64),
    /// Negative density.
    Density(f64),
}

impl std::fmt::Display for ElasError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ElasError::YoungModulus(e) => write!(f, "E must be positive, got {e}"),
            ElasError::PoissonRatio(nu) => write!(f, "NU must lie in ]-1, 0.5[, got {nu}"),
            ElasError::Density(r) => write!(f, "RHO must not be negative, got {r}"),
        }
    }
}

impl Elas {
    /// Checked constants: the strain energy must be positive definite (E > 0,
    /// -1 < ν < 0.5) and a mass not negative.
    pub fn new(e: f64, nu: f64, rho: Option<f64>) -> std::result::Result<Elas, ElasError> {
        if e <= 0.0 {
            return Err(ElasError::YoungModulus(e));
        }
        if !(-1.0 < nu && nu < 0.5) {
            return Err(ElasError::PoissonRatio(nu));
        }
        if let Some(r) = rho.filter(|r| *r < 0.0) {
            return Err(ElasError::Density(r));
        }
        Ok(Elas {
            e,
            nu,
            rho,
            amor_alpha: 0.0,
            amor_beta: 0.0,
        })
    }

    /// The same constants with the Rayleigh damping coefficients AMOR_ALPHA (times the
    /// stiffness) and AMOR_BETA (times the mass) of OPTION='AMOR_MECA'; an absent one is 0,
    /// as in Code_Aster.
    pub fn with_rayleigh(self, amor_alpha: Option<f64>, amor_beta: Option<f64>) -> Elas {
        Elas {
            amor_alpha: amor_alpha.unwrap_or(0.0),
            amor_beta: amor_beta.unwrap_or(0.0),
            ..self
        }
    }

    /// Whether AMOR_MECA gets a Rayleigh part from this material (a coefficient not zero).
    pub fn has_rayleigh(&self) -> bool {
        self.amor_alpha != 0.0 || self.amor_beta != 0.0
    }

    /// Shear modulus G = E / (2 (1 + ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.e / (2.0 * (1.0 + self.nu))
    }
}

/// A material (DEFI_MATERIAU): its behaviours, each checked when it was built.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    pub elas: Option<Elas>,
}

/// One assignment of a material field: a material concept on some cells.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialAssignment {
    pub on: Selection,
    /// The material concept's name.
    pub name: String,
    pub material: Material,
}

/// AFFE_MATERIAU: the material of each cell.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MaterialField {
    pub mesh: String,
    /// Materials by concept name.
    pub materials: BTreeMap<String, Material>,
    /// Cell index -> material concept name (later AFFE occurrences override).
    pub cell_material: BTreeMap<usize, String>,
}

impl MaterialField {
    /// `affe` in the user's order: a later assignment overrides an earlier one on a cell.
    pub fn build(
        mesh_name: &str,
        mesh: &Mesh,
        affe: &[MaterialAssignment],
    ) -> Result<MaterialField> {
        let mut field = MaterialField {
            mesh: mesh_name.to_string(),
            materials: BTreeMap::new(),
            cell_material: BTreeMap::new(),
        };
        for a in affe {
            for c in model_select_cells(mesh, &a.on)? {
                field.cell_material.insert(c, a.name.clone());
            }
            field.materials.insert(a.name.clone(), a.material.clone());
        }
        Ok(field)
    }

    pub fn material_of(&self, cell: usize) -> Option<(&str, &Material)> {
        let name = self.cell_material.get(&cell)?;
        self.materials.get(name).map(|m| (name.as_str(), m))
    }
}
