//! Persistence of model-side concepts as json payloads in `concept_data`: models,
//! materials, material fields, element characteristics, kinematic loads, element matrices.

use super::Store;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::model::{CaraElem, ElemMatrices, KinematicLoad, Material, MaterialField, Model};

pub const KEY_MODEL: &str = "model";
pub const KEY_MATERIAL: &str = "material";
pub const KEY_CHAM_MATER: &str = "cham_mater";
pub const KEY_CARA_ELEM: &str = "cara_elem";
pub const KEY_LOAD: &str = "load";
pub const KEY_MATR_ELEM: &str = "matr_elem";

/// The mesh of a concept (stored by `store::mesh`).
pub fn load_mesh(store: &Store, name: &str) -> Result<Mesh> {
    super::mesh::load_mesh(store, name)
}

pub fn save_model(store: &Store, name: &str, m: &Model) -> Result<()> {
    store.put_json(name, KEY_MODEL, m)
}
pub fn load_model(store: &Store, name: &str) -> Result<Model> {
    store.get_json(name, KEY_MODEL)
}
/// A model and its mesh, completed with the model's own point cells.
pub fn load_model_and_mesh(store: &Store, name: &str) -> Result<(Model, Mesh)> {
    let model = load_model(store, name)?;
    let mut mesh = load_mesh(store, &model.mesh)?;
    model.extend_mesh(&mut mesh)?;
    Ok((model, mesh))
}

pub fn save_material(store: &Store, name: &str, m: &Material) -> Result<()> {
    store.put_json(name, KEY_MATERIAL, m)
}
pub fn load_material(store: &Store, name: &str) -> Result<Material> {
    store.get_json(name, KEY_MATERIAL)
}

pub fn save_material_field(store: &Store, name: &str, f: &MaterialField) -> Result<()> {
    store.put_json(name, KEY_CHAM_MATER, f)
}
pub fn load_material_field(store: &Store, name: &str) -> Result<MaterialField> {
    store.get_json(name, KEY_CHAM_MATER)
}

pub fn save_cara_elem(store: &Store, name: &str, c: &CaraElem) -> Result<()> {
    store.put_json(name, KEY_CARA_ELEM, c)
}
pub fn load_cara_elem(store: &Store, name: &str) -> Result<CaraElem> {
    store.get_json(name, KEY_CARA_ELEM)
}

pub fn save_load(store: &Store, name: &str, l: &KinematicLoad) -> Result<()> {
    store.put_json(name, KEY_LOAD, l)
}
pub fn load_load(store: &Store, name: &str) -> Result<KinematicLoad> {
    store.get_json(name, KEY_LOAD)
}

pub fn save_elem_matrices(store: &Store, name: &str, m: &ElemMatrices) -> Result<()> {
    store.put_json(name, KEY_MATR_ELEM, m)
}
pub fn load_elem_matrices(store: &Store, name: &str) -> Result<ElemMatrices> {
    store.get_json(name, KEY_MATR_ELEM)
}

/// Check that a concept built on `model` is used with that model.
pub fn same_model(what: &str, concept: &str, found: &str, expected: &str) -> Result<()> {
    if found == expected {
        Ok(())
    } else {
        Err(Error::input(format!(
            "{what} {concept} was built on model {found}, not on {expected}"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::beam::{beam_mass_local, beam_stiffness_local, BeamProps};
    use crate::model::elem::{ElemMatrix, MatrixKind};

    #[test]
    fn element_matrices_round_trip_bit_exactly() {
        // Real beam values (irrational-looking doubles) must come back bit for bit, so a
        // matrix assembled from stored element matrices equals one assembled fresh.
        let p = BeamProps {
            e: 2.1e11,
            g: 2.1e11 / 2.6,
            a: 3.0e-4 / 7.0,
            iy: 1.0 / 3.0e7,
            iz: 2.0 / 3.0e7,
            jx: 1.0e-7 / 3.0,
        };
        let mut values = beam_stiffness_local(&p, 0.1 / 3.0);
        values.extend(beam_mass_local(7800.0, p.a, p.iy, p.iz, 0.1 / 3.0));
        let m = ElemMatrices {
            kind: MatrixKind::RigiMeca,
            model: "MO".into(),
            mesh: "MA".into(),
            elements: vec![ElemMatrix {
                cell: 0,
                dofs: vec![],
                values,
            }],
            load_names: vec![],
            loads: vec![],
        };
        let store = Store::in_memory().unwrap();
        store
            .register_concept("KEL", "matr_elem_depl_r", "CALC_MATR_ELEM", "t.comm", 1)
            .unwrap();
        save_elem_matrices(&store, "KEL", &m).unwrap();
        let back = load_elem_matrices(&store, "KEL").unwrap();
        let bits = |x: &ElemMatrices| -> Vec<u64> {
            x.elements[0].values.iter().map(|v| v.to_bits()).collect()
        };
        assert_eq!(bits(&back), bits(&m));
    }
}
