//! ASSE_VECTEUR: the nodal forces of CALC_VECT_ELEM's loads summed on a numbering's DOFs.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::gene::{self, NodalField};
use crate::store::{matrix, model};
use std::collections::BTreeMap;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let num_name = args.req_concept("NUME_DDL")?.name.clone();
    let numbering = matrix::load_numbering(ctx.store, &num_name)?;
    // (DOF index in the numbering) -> summed value, in the numbering's order.
    let mut sums: BTreeMap<usize, f64> = BTreeMap::new();
    let index = numbering.index_map();
    for v in args.concepts("VECT_ELEM").unwrap_or_default() {
        for charge in gene::load_vect_elem(ctx.store, &v.name)?.charges {
            let load = model::load_load(ctx.store, &charge)?;
            if load.model != numbering.model {
                return Err(Error::input(format!(
                    "load {charge} is on model {}, the numbering {num_name} on model {}",
                    load.model, numbering.model
                ))
                .keyword("ASSE_VECTEUR/VECT_ELEM"));
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
                        .keyword("ASSE_VECTEUR/NUME_DDL")
                    })?;
                *sums.entry(i).or_insert(0.0) += f.value;
            }
        }
    }
    let field = NodalField {
        mesh: numbering.mesh.clone(),
        values: sums
            .into_iter()
            .map(|(i, v)| {
                let d = &numbering.dofs[i];
                (d.node.clone(), d.cmp.name().to_string(), v)
            })
            .collect(),
    };
    ctx.create(&name, "cham_no_sdaster")?;
    gene::save_field(ctx.store, &name, &field)
}
