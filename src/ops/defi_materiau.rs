//! DEFI_MATERIAU: a material (ELAS).

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::material::{Elas, ElasError};
use crate::model::Material;
use crate::store::model::save_material;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let mat = material(args)?;
    ctx.create(&name, "mater_sdaster")?;
    save_material(ctx.store, &name, &mat)
}

/// The material of DEFI_MATERIAU(ELAS=_F(E=, NU=, RHO=, AMOR_ALPHA=, AMOR_BETA=)); refused
/// constants name the keyword that gave them.
pub(crate) fn material(args: &Args) -> Result<Material> {
    let elas = match args.fact("ELAS") {
        None => None,
        Some(f) => {
            let (e, nu, rho) = (f.req_real("E")?, f.req_real("NU")?, f.real("RHO"));
            let elas = Elas::new(e, nu, rho).map_err(|err| {
                let key = match err {
                    ElasError::YoungModulus(_) => "E",
                    ElasError::PoissonRatio(_) => "NU",
                    ElasError::Density(_) => "RHO",
                };
                Error::input(err.to_string()).keyword(f.key_path(key))
            })?;
            Some(elas.with_rayleigh(f.real("AMOR_ALPHA"), f.real("AMOR_BETA")))
        }
    };
    Ok(Material { elas })
}
