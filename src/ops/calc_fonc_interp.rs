//! CALC_FONC_INTERP: the tabulated function (`fonction_sdaster`) of the values of a formula
//! of one parameter, or of a function, at VALE_PARA or LIST_PARA, with INTERPOL,
//! PROL_GAUCHE and PROL_DROITE (their defaults are the catalog's).

use super::defi_fonction::function_with_options;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::function::{load_any_function, save_function};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let fc = args.req_concept("FONCTION")?;
    let f =
        load_any_function(ctx.store, &fc.name).map_err(|e| e.keyword(args.key_path("FONCTION")))?;
    let key = if args.has("VALE_PARA") {
        "VALE_PARA"
    } else {
        "LIST_PARA"
    };
    let xs = args.req_reals(key)?;
    if let Some(i) = xs.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::validation(format!(
            "the abscissas must increase strictly: value {} ({:e}) does not exceed value {} ({:e})",
            i + 2,
            xs[i + 1],
            i + 1,
            xs[i]
        ))
        .keyword(args.key_path(key)));
    }
    let nom_para = match args.text("NOM_PARA") {
        Some(p) if p != f.nom_para() => {
            return Err(Error::validation(format!(
                "{} is a function of {}, not of {p}",
                f.name(),
                f.nom_para()
            ))
            .keyword(args.key_path("NOM_PARA")))
        }
        _ => f.nom_para().to_string(),
    };
    let ys = f
        .sample(&xs)
        .map_err(|e| e.keyword(args.key_path("FONCTION")))?;
    let nom_resu = args.req_text("NOM_RESU")?;
    let out = function_with_options(args, &name, &nom_para, nom_resu, xs, ys)?;
    ctx.create(&name, "fonction_sdaster")?;
    save_function(ctx.store, &name, &out)
}
