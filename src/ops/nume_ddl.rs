//! NUME_DDL: DOF numbering from element matrices (MATR_RIGI) or from a model and loads.

use super::calc_matr_elem::Inputs;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::numbering::NumberingError;
use crate::model::{DofNumbering, ElemMatrices};
use crate::store::matrix::save_numbering;
use crate::store::model::{load_elem_matrices, load_mesh, load_model_and_mesh};
use crate::store::Store;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let num = if let Some(mats) = args.concepts("MATR_RIGI") {
        let names: Vec<String> = mats.into_iter().map(|c| c.name).collect();
        from_elem_matrices(ctx.store, &names)?
    } else if args.has("MODELE") {
        let inputs = Inputs::from_args(args)?;
        from_model(ctx.store, &inputs)?
    } else {
        return Err(Error::validation("give MATR_RIGI or MODELE").keyword("NUME_DDL"));
    };
    ctx.create(&name, "nume_ddl_sdaster")?;
    save_numbering(ctx.store, &name, &num)
}

pub(crate) fn from_elem_matrices(store: &Store, names: &[String]) -> Result<DofNumbering> {
    let mats: Vec<ElemMatrices> = names
        .iter()
        .map(|n| load_elem_matrices(store, n))
        .collect::<Result<_>>()?;
    let first = mats
        .first()
        .ok_or_else(|| Error::validation("no element matrix").keyword("MATR_RIGI"))?;
    let mesh = load_mesh(store, &first.mesh)?;
    let refs: Vec<&ElemMatrices> = mats.iter().collect();
    DofNumbering::from_elem_matrices(&mesh, &refs).map_err(numbering_error)
}

/// A numbering failure of the element matrices, named by their keyword (MATR_RIGI).
pub(crate) fn numbering_error(e: NumberingError) -> Error {
    match e {
        NumberingError::Other(e) => e,
        e => Error::input(e.to_string()).keyword("MATR_RIGI"),
    }
}

pub(crate) fn from_model(store: &Store, inputs: &Inputs) -> Result<DofNumbering> {
    let (model, mesh) = load_model_and_mesh(store, &inputs.model)?;
    let loads = inputs.loads(store)?;
    let refs: Vec<_> = loads.iter().map(|(_, l)| l).collect();
    DofNumbering::from_model(&inputs.model, &model, &mesh, &refs)
}
