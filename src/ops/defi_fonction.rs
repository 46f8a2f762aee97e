//! DEFI_FONCTION: a function of one parameter from points (VALE = x1, y1, x2, y2, ...,
//! or VALE_PARA + VALE_FONC), with INTERPOL, PROL_GAUCHE,
//! PROL_DROITE and VERIF ('CROISSANT': increasing abscissas required; 'NON': sorted).

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

fn reals(args: &Args, key: &str) -> Result<Vec<f64>> {
    args.reals(key)
        .ok_or_else(|| Error::validation("expected a list of reals").keyword(args.key_path(key)))
}

/// Points sorted by abscissa (stable: equal abscissas keep their order and are then
/// refused by the strict-increase check).
fn sort_points(x: Vec<f64>, y: Vec<f64>) -> (Vec<f64>, Vec<f64>) {
    let mut pts: Vec<(f64, f64)> = x.into_iter().zip(y).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.into_iter().unzip()
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
        (reals(args, "VALE_PARA")?, reals(args, "VALE_FONC")?)
    } else {
        return Err(Error::validation("give VALE, or VALE_PARA with VALE_FONC")
            .keyword("DEFI_FONCTION/VALE"));
    };
    // VERIF='NON': Code_Aster sorts the points by abscissa instead of refusing them.
    let (x, y) = match args.req_text("VERIF")? {
        "CROISSANT" => (x, y),
        "NON" => sort_points(x, y),
        other => {
            return Err(Error::validation(format!("unknown VERIF '{other}'"))
                .keyword("DEFI_FONCTION/VERIF")
                .hint("use 'CROISSANT' or 'NON'"))
        }
    };
    let mut f = Function {
        name: name.clone(),
        nom_para: args.req_text("NOM_PARA")?.to_string(),
        nom_resu: args.req_text("NOM_RESU")?.to_string(),
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
