//! The stored results IMPR_RESU writes to MED, as nodal fields on their mesh: a `mode_meca`
//! (field DEPL, one step per mode, its time the frequency) and a `dyna_trans` (DEPL, VITE,
//! ACCE, one step per NUME_ORDRE, its time INST). A DOF the result does not hold (blocked
//! by a boundary condition, or a component another node has) is 0, as in Code_Aster's
//! fields. Reading the store only; the file itself is `mesh::med_write`.

use crate::error::{Error, Result};
use crate::mesh::med_write::{NodalField, Step};
use crate::mesh::Mesh;
use crate::model::dof::Cmp;
use crate::store::dyna_trans as dyna_store;
use crate::store::modes::load_modes;
use crate::store::table::load_table;
use crate::store::Store;
use crate::table::Cell;
use std::collections::{BTreeMap, HashMap};

/// The MED field name Code_Aster gives a field of a result: the result's name padded to 8
/// characters with '_', then the field (MODES___DEPL).
pub fn field_name(result: &str, nom_cham: &str) -> String {
    format!("{result:_<8}{nom_cham}")
}

/// The components present among `names`, in Code_Aster's order (DX DY DZ DRX DRY DRZ).
fn ordered(names: impl IntoIterator<Item = String>) -> Vec<String> {
    let present: Vec<String> = names.into_iter().collect();
    Cmp::ALL
        .iter()
        .map(|c| c.name().to_string())
        .filter(|c| present.contains(c))
        .collect()
}

fn node_indices(mesh: &Mesh) -> HashMap<&str, usize> {
    mesh.nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.name.as_str(), i))
        .collect()
}

fn unknown_node(result: &str, node: &str, mesh: &str) -> Error {
    Error::store(format!(
        "{result} names node {node}, which mesh {mesh} does not have: the database was changed \
         outside aster-nl"
    ))
}

/// Whether step `n` is asked for (`None`: every step).
fn wanted(orders: Option<&[i64]>, n: i64) -> bool {
    orders.is_none_or(|o| o.contains(&n))
}

/// The mesh a result is on.
pub fn mesh_of(store: &Store, result: &str, ty: &str) -> Result<String> {
    match ty {
        "mode_meca" => Ok(load_modes(store, result)?.numbering.mesh),
        _ => dyna_store::load_layout(store, result)?
            .map(|l| l.mesh)
            .ok_or_else(|| {
                Error::input(format!(
                    "{result} was written before REST_MODE_NONL recorded its mesh: it cannot \
                     be written to MED"
                ))
                .hint("run REST_MODE_NONL again")
            }),
    }
}

/// DEPL of the modes of `result` (those of `orders`, else all) on `mesh` (named `mesh_name`).
pub fn mode_fields(
    store: &Store,
    result: &str,
    mesh: &Mesh,
    mesh_name: &str,
    orders: Option<&[i64]>,
) -> Result<Vec<NodalField>> {
    let modes = load_modes(store, result)?;
    let cmps = ordered(
        modes
            .numbering
            .dofs
            .iter()
            .map(|d| d.cmp.name().to_string()),
    );
    let index = node_indices(mesh);
    // (node index, component index) of every DOF of the numbering.
    let slots = modes
        .numbering
        .dofs
        .iter()
        .map(|d| {
            let node = *index
                .get(d.node.as_str())
                .ok_or_else(|| unknown_node(result, &d.node, mesh_name))?;
            let c = cmps.iter().position(|c| c == d.cmp.name()).unwrap_or(0);
            Ok((node, c))
        })
        .collect::<Result<Vec<_>>>()?;
    let width = cmps.len();
    let steps = modes
        .modes
        .iter()
        .filter(|m| wanted(orders, m.nume_ordre as i64))
        .map(|m| {
            let mut values = vec![0.0; mesh.nodes.len() * width];
            for (&(node, c), v) in slots.iter().zip(&m.shape) {
                values[node * width + c] = *v;
            }
            Step {
                number: m.nume_ordre as i64,
                time: m.freq,
                values,
            }
        })
        .collect();
    Ok(vec![NodalField {
        name: field_name(result, "DEPL"),
        components: cmps,
        unit: "m".into(),
        steps,
    }])
}

/// The fields `nom_cham` (else every stored one) of the time history `result`, at the
/// NUME_ORDRE of `orders` (else all), on `mesh`.
pub fn history_fields(
    store: &Store,
    result: &str,
    mesh: &Mesh,
    mesh_name: &str,
    nom_cham: Option<&[String]>,
    orders: Option<&[i64]>,
) -> Result<Vec<NodalField>> {
    let stored = dyna_store::stored_fields(store, result)?;
    let fields: Vec<&str> = match nom_cham {
        None => stored.clone(),
        Some(asked) => {
            if let Some(a) = asked.iter().find(|a| !stored.contains(&a.as_str())) {
                return Err(Error::validation(format!(
                    "NOM_CHAM='{a}' is not stored in {result}, which holds {}",
                    stored.join(", ")
                ))
                .keyword("IMPR_RESU/RESU/NOM_CHAM"));
            }
            asked.iter().map(String::as_str).collect()
        }
    };
    let t = load_table(store, result)?;
    let col = |c: &str| t.req_col(c);
    let (jo, ji, jn, jc) = (
        col("NUME_ORDRE")?,
        col("INST")?,
        col("NOEUD")?,
        col("NOM_CMP")?,
    );
    let text = |r: &[Cell], j: usize| {
        r.get(j)
            .and_then(Cell::as_text)
            .unwrap_or("")
            .trim()
            .to_string()
    };
    let real = |r: &[Cell], j: usize| r.get(j).and_then(Cell::as_f64).unwrap_or(f64::NAN);
    let layout = dyna_store::load_layout(store, result)?;
    let blocked = layout.map(|l| l.blocked).unwrap_or_default();
    let cmps = ordered(
        t.rows
            .iter()
            .map(|r| text(r, jc))
            .chain(blocked.into_iter().map(|(_, c)| c)),
    );
    let width = cmps.len();
    let index = node_indices(mesh);
    let mut out = Vec::new();
    for f in fields {
        let jf = col(f)?;
        // NUME_ORDRE -> (INST, values).
        let mut steps: BTreeMap<i64, (f64, Vec<f64>)> = BTreeMap::new();
        for r in &t.rows {
            let n = real(r, jo) as i64;
            if !wanted(orders, n) {
                continue;
            }
            let node = text(r, jn);
            let i = *index
                .get(node.as_str())
                .ok_or_else(|| unknown_node(result, &node, mesh_name))?;
            let cmp = text(r, jc);
            let c = cmps.iter().position(|x| *x == cmp).unwrap_or(0);
            let step = steps
                .entry(n)
                .or_insert_with(|| (real(r, ji), vec![0.0; mesh.nodes.len() * width]));
            step.1[i * width + c] = real(r, jf);
        }
        out.push(NodalField {
            name: field_name(result, f),
            components: cmps.clone(),
            unit: match f {
                "DEPL" => "m",
                "VITE" => "m/s",
                _ => "m/s2",
            }
            .into(),
            steps: steps
                .into_iter()
                .map(|(number, (time, values))| Step {
                    number,
                    time,
                    values,
                })
                .collect(),
        });
    }
    Ok(out)
}
