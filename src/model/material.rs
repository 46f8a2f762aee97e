//! Materials (DEFI_MATERIAU) and material fields (AFFE_MATERIAU).

use super::select::model_select_cells;
use crate::args::Args;
use crate::error::{Error, Result};
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
}

impl Elas {
    /// Shear modulus G = E / (2 (1 + ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.e / (2.0 * (1.0 + self.nu))
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    pub elas: Option<Elas>,
}

impl Material {
    /// DEFI_MATERIAU(ELAS=_F(E=, NU=, RHO=)).
    pub fn from_args(args: &Args) -> Result<Material> {
        let elas = match args.fact("ELAS") {
            None => None,
            Some(f) => {
                let e = f.req_real("E")?;
                let nu = f.req_real("NU")?;
                if e <= 0.0 {
                    return Err(Error::input(format!("E must be positive, got {e}"))
                        .keyword(f.key_path("E")));
                }
                if !(-1.0 < nu && nu < 0.5) {
                    return Err(Error::input(format!("NU must lie in ]-1, 0.5[, got {nu}"))
                        .keyword(f.key_path("NU")));
                }
                let rho = f.real("RHO");
                if let Some(r) = rho {
                    if r < 0.0 {
                        return Err(Error::input(format!("RHO must not be negative, got {r}"))
                            .keyword(f.key_path("RHO")));
                    }
                }
                Some(Elas { e, nu, rho })
            }
        };
        Ok(Material { elas })
    }
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
    /// `affe`: the AFFE occurrences with, for each, the material concept (name, data).
    pub fn build(
        mesh_name: &str,
        mesh: &Mesh,
        affe: &[(Args, String, Material)],
    ) -> Result<MaterialField> {
        let mut field = MaterialField {
            mesh: mesh_name.to_string(),
            materials: BTreeMap::new(),
            cell_material: BTreeMap::new(),
        };
        for (occ, name, mat) in affe {
            for c in model_select_cells(mesh, mesh_name, occ)? {
                field.cell_material.insert(c, name.clone());
            }
            field.materials.insert(name.clone(), mat.clone());
        }
        Ok(field)
    }

    pub fn material_of(&self, cell: usize) -> Option<(&str, &Material)> {
        let name = self.cell_material.get(&cell)?;
        self.materials.get(name).map(|m| (name.as_str(), m))
    }
}
