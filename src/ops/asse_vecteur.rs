//! ASSE_VECTEUR: the nodal forces of CALC_VECT_ELEM's loads summed on a numbering's DOFs.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::DofNumbering;
use crate::store::gene::{self, NodalField};
use crate::store::{matrix, model, Store};
use std::collections::BTreeMap;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let num_name = args.req_concept("NUME_DDL")?.name.clone();
    let numbering = matrix::load_numbering(ctx.store, &num_name)?;
    let mut charges = Vec::new();
    for v in args.concepts("VECT_ELEM").unwrap_or_default() {
        charges.extend(gene::load_vect_elem(ctx.store, &v.name)?.charges);
    }
    let field = nodal_forces(
        ctx.store,
        &numbering,
        &num_name,
        &charges,
        1.0,
        ("ASSE_VECTEUR/VECT_ELEM", "ASSE_VECTEUR/NUME_DDL"),
    )?;
    ctx.create(&name, "cham_no_sdaster")?;
    gene::save_field(ctx.store, &name, &field)
}

/// The nodal forces of the loads `charges`, times `factor`, summed on the DOFs of
/// `numbering` (named `num_name`), as a nodal field (ASSE_VECTEUR, ASSEMBLAGE/VECT_ASSE).
/// Errors name `keys`: the loads' keyword, then the numbering's.
pub(crate) fn nodal_forces(
    store: &Store,
    numbering: &DofNumbering,
    num_name: &str,
    charges: &[String],
    factor: f64,
    (load_key, numbering_key): (&str, &str),
) -> Result<NodalField> {
    // (DOF index in the numbering) -> summed value, in the numbering's order.
    let mut sums: BTreeMap<usize, f64> = BTreeMap::new();
    let index = numbering.index_map();
    for charge in charges {
        let load = model::load_load(store, charge)?;
        if load.model != numbering.model {
            return Err(Error::input(format!(
                "load {charge} is on model {}, the numbering {num_name} on model {}",
                load.model, numbering.model
            ))
            .keyword(load_key));
        }
        for f in &load.forces {
            let i = index
                .get(&(f.node.as_str(), f.cmp))
                .copied()
                .ok_or_else(|| {
                    Error::input(format!(
                        "load {charge} has a force on {} {}, a DOF {num_name} does not number",
                        f.node, f.cmp
                    ))
                    .keyword(numbering_key)
                })?;
            *sums.entry(i).or_insert(0.0) += factor * f.value;
        }
    }
    Ok(NodalField {
        mesh: numbering.mesh.clone(),
        values: sums
            .into_iter()
            .map(|(i, v)| {
                let d = &numbering.dofs[i];
                (d.node.clone(), d.cmp.name().to_string(), v)
            })
            .collect(),
    })
}
