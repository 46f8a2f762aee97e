//! CALC_FONCTION: COMB (Σ COEF x FONCTION), MULT (Π FONCTION), ABS, DERIVE and INTEGRE of
//! tabulated functions (`function::calc`). The result takes the first function's
//! NOM_PARA, NOM_RESU, INTERPOL and prolongations unless the keywords of the same names are
//! given; with COMB and MULT, LIST_PARA gives its abscissas.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::{calc, Function, Interp, Prol};
use crate::store::function::{load_function, save_function};

/// The function FONCTION of the factor keyword occurrence `occ`.
fn function_of(ctx: &OpContext<'_>, occ: &Args) -> Result<Function> {
    let c = occ.req_concept("FONCTION")?;
    load_function(ctx.store, &c.name).map_err(|e| e.keyword(occ.key_path("FONCTION")))
}

/// The first function's settings, replaced by the keywords given.
fn apply_options(args: &Args, f: &mut Function) -> Result<()> {
    if let Some(p) = args.text("NOM_PARA") {
        f.nom_para = p.to_string();
    }
    if let Some(r) = args.text("NOM_RESU") {
        f.nom_resu = r.to_string();
    }
    if let Some(v) = args.texts("INTERPOL") {
        let parse = |s: &String| {
            Interp::parse(s).ok_or_else(|| {
                Error::validation(format!("unknown interpolation '{s}'"))
                    .keyword(args.key_path("INTERPOL"))
            })
        };
        f.interpol = match v.as_slice() {
            [a] => (parse(a)?, parse(a)?),
            [a, b] => (parse(a)?, parse(b)?),
            _ => {
                return Err(
                    Error::internal("INTERPOL: its catalog allows 1 or 2 values")
                        .keyword(args.key_path("INTERPOL")),
                )
            }
        };
    }
    for (key, side) in [
        ("PROL_GAUCHE", &mut f.prol_gauche),
        ("PROL_DROITE", &mut f.prol_droite),
    ] {
        if let Some(s) = args.text(key) {
            *side = Prol::parse(s).ok_or_else(|| {
                Error::validation(format!("unknown prolongation '{s}'")).keyword(args.key_path(key))
            })?;
        }
    }
    Ok(())
}

/// COMB or MULT: the first function with the points of the combination.
fn combined(ctx: &OpContext<'_>, args: &Args, key: &str) -> Result<Function> {
    let occs = args.facts_or_empty(key);
    let fs = occs
        .iter()
        .map(|o| function_of(ctx, o))
        .collect::<Result<Vec<_>>>()?;
    let Some(first) = fs.first() else {
        return Err(Error::internal(format!("{key} has no occurrence")).keyword(key));
    };
    let (x, y) = if key == "COMB" {
        let coefs = occs
            .iter()
            .map(|o| o.req_real("COEF"))
            .collect::<Result<Vec<_>>>()?;
        let terms: Vec<(&Function, f64)> = fs.iter().zip(coefs).collect();
        calc::combine(&terms)
    } else {
        calc::multiply(&fs.iter().collect::<Vec<_>>())
    }
    .map_err(|e| e.keyword(args.key_path(key)))?;
    Ok(Function {
        x,
        y,
        ..first.clone()
    })
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let one = |key: &str| -> Result<&Args> { args.req_fact(key) };
    let mut f = if args.has("COMB") {
        combined(ctx, args, "COMB")?
    } else if args.has("MULT") {
        combined(ctx, args, "MULT")?
    } else if args.has("ABS") {
        calc::abs(&function_of(ctx, one("ABS")?)?)
    } else if args.has("DERIVE") {
        let occ = one("DERIVE")?;
        calc::derive(&function_of(ctx, occ)?).map_err(|e| e.keyword(occ.key_path("FONCTION")))?
    } else if args.has("INTEGRE") {
        let occ = one("INTEGRE")?;
        if occ.req_text("METHODE")? != "TRAPEZE" {
            return Err(Error::validation("METHODE='SIMPSON' is not available")
                .keyword(occ.key_path("METHODE"))
                .hint("use METHODE='TRAPEZE'"));
        }
        calc::integrate_trapeze(&function_of(ctx, occ)?, occ.req_real("COEF")?)
    } else {
        return Err(
            Error::validation("give one of COMB, MULT, ABS, DERIVE, INTEGRE").keyword("COMB"),
        );
    };
    f.name = name.clone();
    apply_options(args, &mut f)?;
    if let Some(xs) = args.reals("LIST_PARA") {
        if !(args.has("COMB") || args.has("MULT")) {
            return Err(Error::validation("LIST_PARA goes with COMB or MULT only")
                .keyword(args.key_path("LIST_PARA")));
        }
        if let Some(i) = xs.windows(2).position(|w| w[1] <= w[0]) {
            return Err(Error::validation(format!(
                "LIST_PARA must increase strictly: value {} ({:e}) does not exceed value {} ({:e})",
                i + 2,
                xs[i + 1],
                i + 1,
                xs[i]
            ))
            .keyword(args.key_path("LIST_PARA")));
        }
        f.check().map_err(|e| e.keyword(args.path.clone()))?;
        let ys = xs
            .iter()
            .map(|&x| f.eval(x))
            .collect::<Result<Vec<_>>>()
            .map_err(|e| e.keyword(args.key_path("LIST_PARA")))?;
        f.x = xs;
        f.y = ys;
    }
    f.check().map_err(|e| e.keyword(args.path.clone()))?;
    ctx.create(&name, "fonction_sdaster")?;
    save_function(ctx.store, &name, &f)
}
