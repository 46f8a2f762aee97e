//! Models, materials, element characteristics, element matrices, kinematic conditions,
//! DOF numbering and assembly, as Code_Aster users write them (AFFE_MODELE,
//! DEFI_MATERIAU, AFFE_MATERIAU, AFFE_CARA_ELEM, AFFE_CHAR_CINE/MECA, CALC_MATR_ELEM,
//! NUME_DDL, ASSE_MATRICE). No SQL here: persistence is in `store::model` / `store::matrix`.

pub mod assembly;
pub mod beam;
pub mod cara;
pub mod discrete;
pub mod dof;
pub mod elem;
pub mod fe_model;
pub mod frame;
pub mod loads;
pub mod material;
pub mod modes;
pub mod numbering;
pub mod relations;
pub mod select;
pub mod static_shapes;

pub use assembly::{assemble, AssembledMatrix};
pub use cara::CaraElem;
pub use dof::Cmp;
pub use elem::{compute_elem_matrices, ElemInputs, ElemMatrices, MatrixKind};
pub use fe_model::{Model, Modelisation};
pub use loads::{KinematicLoad, LoadKind};
pub use material::{Material, MaterialField};
pub use numbering::DofNumbering;

#[cfg(test)]
pub(crate) mod tests;
