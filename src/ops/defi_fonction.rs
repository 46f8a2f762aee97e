//! DEFI_FONCTION: a function of one parameter from points (VALE = x1, y1, x2, y2, ...,
//! or VALE_PARA + VALE_FONC), with INTERPOL, PROL_GAUCHE,
//! PROL_DROITE and VERIF ('CROISSANT': increasing abscissas required; 'NON': sorted);
//! their defaults are the catalog's (commands/DEFI_FONCTION.toml).

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::{Function, Interp, Prol};
use crate::store::function::save_function;

/// The function of the points `x`, `y` with the INTERPOL, PROL_GAUCHE and PROL_DROITE
/// of `args` (DEFI_FONCTION, RECU_FONCTION; their defaults are the catalog's), checked.
pub fn function_with_options(
    args: &Args,
    name: &str,
    nom_para: &str,
    nom_resu: &str,
    x: Vec<f64>,
    y: Vec<f64>,
) -> Result<Function> {
    let interpol = interpolation(args)?;
    let prol = |key: &str| -> Result<Prol> {
        let s = args.req_text(key)?;
        Prol::parse(s).ok_or_else(|| {
            Error::validation(format!("unknown prolongation '{s}'"))
                .keyword(args.key_path(key))
                .hint("use 'CONSTANT', 'LINEAIRE' or 'EXCLU'")
        })
    };
    let f = Function {
        name: name.to_string(),
        nom_para: nom_para.to_string(),
        nom_resu: nom_resu.to_string(),
        x,
        y,
        interpol,
        prol_gauche: prol("PROL_GAUCHE")?,
        prol_droite: prol("PROL_DROITE")?,
    };
    f.check().map_err(|e| e.keyword(args.path.clone()))?;
    Ok(f)
}

/// INTERPOL: one value for both axes, or two (abscissa, ordinate); one or two values is
/// the catalog's bound.
fn interpolation(args: &Args) -> Result<(Interp, Interp)> {
    let values = args.req_texts("INTERPOL")?;
    let parse = |s: &String| {
        Interp::parse(s).ok_or_else(|| {
            Error::validation(format!("unknown interpolation '{s}'"))
                .keyword(args.key_path("INTERPOL"))
                .hint("use 'LIN', 'LOG' or 'NON'")
        })
    };
    match values.as_slice() {
        [a] => parse(a).map(|a| (a, a)),
        [a, b] => Ok((parse(a)?, parse(b)?)),
        _ => Err(Error::internal(format!(
            "INTERPOL has {} values: its catalog needs min = 1, max = 2",
            values.len()
        ))
        .keyword(args.key_path("INTERPOL"))),
    }
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
    let nom_para = args.req_text("NOM_PARA")?;
    let nom_resu = args.req_text("NOM_RESU")?;
    let f = function_with_options(args, &name, nom_para, nom_resu, x, y)?;
    ctx.create(&name, "fonction_sdaster")?;
    save_function(ctx.store, &name, &f)
}
