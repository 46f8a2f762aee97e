//! DYNA_LINE's loads as assembled nodal fields: the nodal forces of CHARGE, each EXCIT's
//! load (CALC_VECT_ELEM and ASSE_VECTEUR) or support acceleration (CALC_CHAR_SEISME).

use super::chain::Call;
use super::Assembled;
use crate::args::Args;
use crate::error::Result;
use crate::ops::OpContext;
use crate::store::gene;
use crate::value::Value;

/// One load of the transient: an assembled nodal field times a function or a constant.
pub(super) struct Load {
    pub(super) field: String,
    pub(super) fonc: Option<Value>,
    pub(super) coef: Option<f64>,
    /// An EXCIT with CHARGE: ENRI_STAT adds its static response to the basis.
    pub(super) enriches: bool,
}

/// The loads as assembled nodal fields: the nodal forces of CHARGE (constant, when there
/// are any, as Code_Aster applies them), then each EXCIT (CHARGE's forces or the support
/// acceleration's −M·Δ).
pub(super) fn loads(
    ctx: &mut OpContext<'_>,
    args: &Args,
    prefix: &str,
    mats: &Assembled,
) -> Result<Vec<Load>> {
    let mut out = Vec::new();
    let meca: Vec<Value> = args
        .concepts("CHARGE")
        .unwrap_or_default()
        .into_iter()
        .filter(|c| c.ty != "char_cine_meca")
        .map(Value::Concept)
        .collect();
    if !meca.is_empty() {
        let field = format!("{prefix}.F0");
        nodal_forces(
            ctx,
            args,
            Value::Seq(meca),
            &field,
            mats,
            "DYNA_LINE/CHARGE",
        )?;
        if gene::load_field(ctx.store, &field)?
            .values
            .iter()
            .any(|v| v.2 != 0.0)
        {
            out.push(Load {
                field,
                fonc: None,
                coef: Some(1.0),
                enriches: false,
            });
        }
    }
    for (i, occ) in args.facts_or_empty("EXCIT").iter().enumerate() {
        let field = format!("{prefix}.F{}", i + 1);
        let charge = occ.value("CHARGE").filter(|v| **v != Value::None);
        let enriches = charge.is_some();
        match charge {
            Some(charge) => nodal_forces(
                ctx,
                args,
                charge.clone(),
                &field,
                mats,
                &occ.key_path("CHARGE"),
            )?,
            None => {
                let direction = occ.value("DIRECTION").cloned().unwrap_or(Value::None);
                Call::new("CALC_CHAR_SEISME")
                    .concept(ctx, "MATR_MASS", &mats.mass)?
                    .set("DIRECTION", direction)
                    .text("MONO_APPUI", "OUI")
                    .run(ctx, Some(&field), &occ.key_path("DIRECTION"), &[])?
            }
        }
        out.push(Load {
            field,
            fonc: occ
                .value("FONC_MULT")
                .cloned()
                .filter(|v| *v != Value::None),
            coef: None,
            enriches,
        });
    }
    Ok(out)
}

/// CALC_VECT_ELEM and ASSE_VECTEUR: the nodal forces of `charge` on the numbering.
fn nodal_forces(
    ctx: &mut OpContext<'_>,
    args: &Args,
    charge: Value,
    field: &str,
    mats: &Assembled,
    blame: &str,
) -> Result<()> {
    let elem = format!("{field}.ELEM");
    let mut call = Call::new("CALC_VECT_ELEM")
        .text("OPTION", "CHAR_MECA")
        .set("CHARGE", charge);
    for key in ["CHAM_MATER", "CARA_ELEM"] {
        if let Some(v) = args.value(key).filter(|v| **v != Value::None) {
            call = call.set(key, v.clone());
        }
    }
    call.run(ctx, Some(&elem), blame, &[])?;
    Call::new("ASSE_VECTEUR")
        .concept(ctx, "VECT_ELEM", &elem)?
        .concept(ctx, "NUME_DDL", &mats.nume)?
        .run(ctx, Some(field), blame, &[])
}
