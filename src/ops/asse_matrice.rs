//! ASSE_MATRICE: assemble element matrices on a numbering, eliminating CHAR_CINE DOFs.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::assembly::AssemblyError;
use crate::model::{assemble, AssembledMatrix, ElemMatrices, KinematicLoad, LoadKind};
use crate::store::matrix::{load_numbering, save_matrix};
use crate::store::model::{load_elem_matrices, load_load, load_mesh, same_model};
use crate::store::Store;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let mats: Vec<String> = names(args, "MATR_ELEM");
    let numbering = args.req_concept("NUME_DDL")?.name.clone();
    let cine = names(args, "CHAR_CINE");
    let m = assemble_named(ctx.store, &mats, &numbering, &cine)?;
    ctx.create(&name, "matr_asse_depl_r")?;
    save_matrix(ctx.store, &name, &m, &numbering)
}

fn names(args: &Args, key: &str) -> Vec<String> {
    args.concepts(key)
        .unwrap_or_default()
        .into_iter()
        .map(|c| c.name)
        .collect()
}

/// Load the element matrices, numbering and AFFE_CHAR_CINE loads by name and assemble.
pub(crate) fn assemble_named(
    store: &Store,
    mats: &[String],
    numbering: &str,
    cine: &[String],
) -> Result<AssembledMatrix> {
    let num = load_numbering(store, numbering)?;
    let mats: Vec<ElemMatrices> = mats
        .iter()
        .map(|n| load_elem_matrices(store, n))
        .collect::<Result<_>>()?;
    let loads: Vec<KinematicLoad> = cine
        .iter()
        .map(|n| {
            let l = load_load(store, n)?;
            same_model("CHAR_CINE", n, &l.model, &num.model).map_err(|e| e.keyword("CHAR_CINE"))?;
            if l.kind != LoadKind::Cine {
                return Err(
                    Error::input(format!("{n} is not an AFFE_CHAR_CINE load")).keyword("CHAR_CINE")
                );
            }
            Ok(l)
        })
        .collect::<Result<_>>()?;
    let mesh = load_mesh(store, &num.mesh)?;
    let mrefs: Vec<&ElemMatrices> = mats.iter().collect();
    let lrefs: Vec<&KinematicLoad> = loads.iter().collect();
    assemble(&num, &mesh, &mrefs, &lrefs).map_err(assembly_error)
}

/// An assembly failure named by its keyword: the element matrices (MATR_ELEM) or the
/// numbering (NUME_DDL).
pub(crate) fn assembly_error(e: AssemblyError) -> Error {
    let message = e.to_string();
    match e {
        AssemblyError::NoMatrix | AssemblyError::MixedKinds(..) => {
            Error::input(message).keyword("MATR_ELEM")
        }
        AssemblyError::NotNumbered { .. } => Error::input(message)
            .keyword("NUME_DDL")
            .hint("build NUME_DDL from the same model as the element matrices"),
        AssemblyError::Other(e) => e,
    }
}
