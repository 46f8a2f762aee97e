//! The basis of a generalized numbering as PROJ_MATR_BASE, PROJ_VECT_BASE and DYNA_VIBRA
//! read it: the numbering, and the basis's vectors checked to be the ones it was built on.

use crate::error::{Error, Result};
use crate::model::modes::ModeMeca;
use crate::store::gene::{self, GeneNumbering};
use crate::store::{modes as mode_store, Store};

/// The generalized numbering `numbering` and its basis; `base`, when the call names one
/// (BASE=), must be the numbering's. `op` prefixes the keyword paths of errors.
pub fn numbering_and_basis(
    store: &Store,
    numbering: &str,
    base: Option<&str>,
    op: &str,
) -> Result<(GeneNumbering, ModeMeca)> {
    let num = gene::load_numbering(store, numbering)?;
    if let Some(b) = base.filter(|b| *b != num.basis) {
        return Err(Error::input(format!(
            "BASE={b} is not the basis of {numbering}, which was built on {}",
            num.basis
        ))
        .keyword(format!("{op}/BASE"))
        .hint(format!(
            "give BASE={} or number {b} with NUME_DDL_GENE",
            num.basis
        )));
    }
    let modes = mode_store::load_modes(store, &num.basis)?;
    if modes.modes.len() != num.size {
        return Err(Error::store(format!(
            "{numbering} numbers {} vectors but its basis {} holds {}",
            num.size,
            num.basis,
            modes.modes.len()
        )));
    }
    Ok((num, modes))
}

/// The basis's vectors, in the full numbering of its DOFs.
pub fn vectors(modes: &ModeMeca) -> Vec<Vec<f64>> {
    modes.modes.iter().map(|m| m.shape.clone()).collect()
}
