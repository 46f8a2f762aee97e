//! DEFI_FONCTION: a function of one parameter from points (VALE = x1, y1, x2, y2, ... or
//! VALE_PARA + VALE_FONC), with INTERPOL, PROL_GAUCHE, PROL_DROITE.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::{Function, Interp, Prol};
use crate::store::function::save_function;

/// INTERPOL (default LIN), PROL_GAUCHE and PROL_DROITE (default EXCLU) of `args` applied
/// to `f`, which is then checked.
pub fn apply_options(f: &mut Function, args: &Args) -> Result<()> {
    f.interpol = Interp::pair(&args.texts("INTERPOL").unwrap_or_default())
        .map_err(|e| e.keyword(args.key_path("INTERPOL")))?;
    for (key, slot) in [
        ("PROL_GAUCHE", &mut f.prol_gauche),
        ("PROL_DROITE", &mut f.prol_droite),
    ] {
        if let Some(s) = args.text(key) {
            *slot = Prol::parse(s).ok_or_else(|| {
                Error::validation(format!("unknown prolongation '{s}'"))
                    .keyword(args.key_path(key))
                    .hint("use 'CONSTANT', 'LINEAIRE' or 'EXCLU'")
            })?;
        }
    }
    f.check().map_err(|e| e.keyword(args.path.clone()))
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let (x, y) = if args.has("VALE") {
        let v = args.reals("VALE").ok_or_else(|| {
            Error::validation("expected a list of reals").keyword("DEFI_FONCTION/VALE")
        })?;
        if v.len() % 2 != 0 {
            return Err(Error::validation(format!(
                "VALE holds {} numbers: pairs (x, y) are expected",
                v.len()
            ))
            .keyword("DEFI_FONCTION/VALE")
            .hint("write VALE=(x1, y1, x2, y2, ...)"));
        }
        v.chunks_exact(2).map(|p| (p[0], p[1])).unzip()
    } else if args.has("VALE_PARA") {
        let x = args.reals("VALE_PARA").ok_or_else(|| {
            Error::validation("expected a list of reals").keyword("DEFI_FONCTION/VALE_PARA")
        })?;
        let y = args.reals("VALE_FONC").ok_or_else(|| {
            Error::validation("expected a list of reals").keyword("DEFI_FONCTION/VALE_FONC")
        })?;
        (x, y)
    } else {
        return Err(Error::validation("give VALE or VALE_PARA with VALE_FONC")
            .keyword("DEFI_FONCTION/VALE"));
    };
    let mut f = Function {
        name: name.clone(),
        nom_para: args.req_text("NOM_PARA")?.to_string(),
        nom_resu: args.text("NOM_RESU").unwrap_or("TOUTRESU").to_string(),
        x,
        y,
        interpol: (Interp::Lin, Interp::Lin),
        prol_gauche: Prol::Exclu,
        prol_droite: Prol::Exclu,
    };
    apply_options(&mut f, args)?;
    ctx.create(&name, "fonction_sdaster")?;
    save_function(ctx.store, &name, &f)
}
