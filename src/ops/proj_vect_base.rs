//! PROJ_VECT_BASE: a nodal field on a basis: Φᵀf for a force (TYPE_VECT='FORC'), the
//! coordinates of a displacement, velocity or acceleration otherwise.

use super::common::gene::{numbering_and_basis, vectors};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::linalg::projection::{coordinates, project_vector};
use crate::model::modes::ModeMeca;
use crate::model::Cmp;
use crate::model::DofNumbering;
use crate::store::gene::{self, GeneMeta, GeneVector, NodalField};
use crate::store::{matrix, modes as mode_store, Store};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let num_name = args.req_concept("NUME_DDL_GENE")?.name.clone();
    let base = args.req_concept("BASE")?.name.clone();
    let f_name = args.req_concept("VECT_ASSE")?.name.clone();
    let kind = args.req_text("TYPE_VECT")?.to_string();
    project(
        ctx,
        &name,
        &num_name,
        &base,
        (&f_name, "PROJ_VECT_BASE/VECT_ASSE"),
        &kind,
        "PROJ_VECT_BASE",
    )
}

/// Create `name`, the generalized vector of the nodal field `field` (its name and keyword
/// path) on the basis `base` numbered by `num_name`, as TYPE_VECT `kind` asks (PROJ_VECT_BASE,
/// and PROJ_BASE for each VECT_ASSE_GENE). `op` prefixes the paths of other errors.
pub(crate) fn project(
    ctx: &mut OpContext<'_>,
    name: &str,
    num_name: &str,
    base: &str,
    (f_name, field_key): (&str, &str),
    kind: &str,
    op: &str,
) -> Result<()> {
    let (num, modes) = numbering_and_basis(ctx.store, num_name, Some(base), op)?;
    let field = gene::load_field(ctx.store, f_name)?;
    let u = on_numbering(&field, &modes, f_name).map_err(|e| e.keyword(field_key))?;
    let basis = vectors(&modes);
    let values = if kind == "FORC" {
        project_vector(&basis, &u)?
    } else {
        let mass = mass_entries(ctx.store, base)?;
        if mass.is_none() {
            ctx.say(&format!(
                "{op} {name}: {base} does not name the mass matrix it was computed \
                 with; the coordinates are those of the Euclidean metric"
            ))?;
        }
        coordinates(&basis, mass.as_deref(), &u).map_err(|e| e.keyword(format!("{op}/BASE")))?
    };
    ctx.create(name, "vect_asse_gene")?;
    ctx.store.record_dependency(name, num_name)?;
    gene::save_vector(
        ctx.store,
        name,
        &GeneVector {
            meta: GeneMeta {
                numbering: num_name.to_string(),
                basis: base.to_string(),
                size: num.size,
                kind: kind.to_string(),
            },
            values,
        },
    )
}

/// The field as a vector of the basis's full numbering. DOFs a boundary condition
/// eliminated are imposed zero and read as zero; a nonzero value of a component the
/// numbering does not have is an error (without keyword: the caller names its own).
pub(crate) fn on_numbering(field: &NodalField, modes: &ModeMeca, f_name: &str) -> Result<Vec<f64>> {
    field_on_numbering(field, &modes.numbering, f_name)
}

/// [`on_numbering`] for a DOF numbering of its own.
pub(crate) fn field_on_numbering(
    field: &NodalField,
    numbering: &DofNumbering,
    f_name: &str,
) -> Result<Vec<f64>> {
    if field.mesh != numbering.mesh {
        return Err(Error::input(format!(
            "{f_name} is a field of mesh {} and the basis's DOFs are on mesh {}",
            field.mesh, numbering.mesh
        )));
    }
    let mut u = vec![0.0; numbering.len()];
    let index = numbering.index_map();
    for (node, cmp, v) in &field.values {
        let at = Cmp::parse(cmp).and_then(|c| index.get(&(node.as_str(), c)).copied());
        match at {
            Some(i) if !numbering.eliminated[i] => u[i] = *v,
            Some(_) => {}
            None if *v == 0.0 => {}
            None => {
                return Err(Error::input(format!(
                    "{f_name} gives {cmp} = {v:e} at node {node}, a DOF the basis's numbering does not have"
                ))
                .hint("give only components of the model's elements at that node"));
            }
        }
    }
    Ok(u)
}

/// The entries of the mass matrix the basis was computed with, if it names one that is
/// still on the basis's numbering (the name may have been given to another matrix since).
fn mass_entries(store: &Store, base: &str) -> Result<Option<Vec<(usize, usize, f64)>>> {
    match mode_store::load_matrices(store, base)? {
        Some(m) => {
            let mass = matrix::load_matrix(store, &m.mass)?;
            let same = mode_store::load_modes(store, base)?.numbering.dofs == mass.numbering.dofs;
            Ok(same.then_some(mass.triplets))
        }
        None => Ok(None),
    }
}
