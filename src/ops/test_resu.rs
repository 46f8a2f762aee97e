//! TEST_RESU: checks a value of a result concept, Code_Aster style.
//!
//! RESU=_F(RESULTAT=..., NUME_ORDRE|NUME_MODE=n, PARA='FREQ'|'MASS_GENE'|'RIGI_GENE'|'OMEGA2')
//! tests a modal quantity of a `mode_meca`; RESU=_F(RESULTAT=..., NUME_ORDRE=n|INST=t,
//! NOM_CHAM='DEPL'|'VITE'|'ACCE', NOEUD=|GROUP_NO=, NOM_CMP=) tests one value of a field (a mode
//! shape, or a `dyna_trans` time history).

use crate::args::Args;
use crate::error::{Error, Result};
use crate::ops::common::dyna_trans;
use crate::ops::common::nodes::{one_node_of_group, OneNode};
use crate::ops::common::testing::{self, checks_with_floor, TestValue};
use crate::ops::OpContext;
use crate::store::modes as mode_store;
use crate::table::filter::Critere;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    for (i, resu) in args.facts_or_empty("RESU").iter().enumerate() {
        let kw = |k: &str| format!("TEST_RESU/RESU[{}]/{k}", i + 1);
        let result = resu.req_concept("RESULTAT")?;
        let computed = match result.ty.as_str() {
            "mode_meca" => mode_value(ctx, resu, &result.name, &kw)?,
            "dyna_trans" => dyna_value(ctx, resu, &result.name, &kw)?,
            other => {
                return Err(Error::validation(format!(
                    "TEST_RESU cannot test a concept of type {other}"
                ))
                .keyword(kw("RESULTAT")))
            }
        };
        for outcome in checks_with_floor(resu, &TestValue::R(computed), ctx.tole_machine)? {
            ctx.say(&outcome.line)?;
            ctx.tests.push(outcome);
        }
    }
    Ok(())
}

fn order(resu: &Args, kw: &dyn Fn(&str) -> String) -> Result<i64> {
    resu.int("NUME_ORDRE")
        .or_else(|| resu.int("NUME_MODE"))
        .ok_or_else(|| {
            Error::validation("expected NUME_ORDRE or NUME_MODE").keyword(kw("NUME_ORDRE"))
        })
}

/// The node named by NOEUD or by a one-node GROUP_NO.
fn node_name(
    ctx: &OpContext<'_>,
    resu: &Args,
    mesh: &str,
    kw: &dyn Fn(&str) -> String,
) -> Result<String> {
    if let Some(n) = resu.text("NOEUD") {
        return Ok(n.to_string());
    }
    let group = resu
        .text("GROUP_NO")
        .ok_or_else(|| Error::validation("expected NOEUD or GROUP_NO").keyword(kw("NOEUD")))?;
    one_node_of_group(
        ctx.store,
        mesh,
        group,
        OneNode {
            reason: "TEST_RESU tests one value",
            hint: None,
        },
        kw("GROUP_NO"),
    )
}

fn mode_value(
    ctx: &OpContext<'_>,
    resu: &Args,
    name: &str,
    kw: &dyn Fn(&str) -> String,
) -> Result<f64> {
    let modes = mode_store::load_modes(ctx.store, name)?;
    let n = order(resu, kw)?;
    let mode = usize::try_from(n)
        .ok()
        .and_then(|n| modes.mode(n))
        .ok_or_else(|| {
            Error::validation(format!(
                "{name} has no mode {n} (available: {})",
                modes.available()
            ))
            .keyword(kw("NUME_ORDRE"))
        })?;
    if let Some(para) = resu.text("PARA") {
        return match para {
            "FREQ" => Ok(mode.freq),
            "MASS_GENE" => Ok(mode.mass_gene),
            "RIGI_GENE" => Ok(mode.rigi_gene),
            "OMEGA2" => Ok(mode.omega2),
            other => Err(
                Error::validation(format!("PARA='{other}' is not stored in a mode_meca"))
                    .keyword(kw("PARA"))
                    .hint("use FREQ, MASS_GENE, RIGI_GENE or OMEGA2"),
            ),
        };
    }
    let cmp = resu.text("NOM_CMP").ok_or_else(|| {
        Error::validation("expected PARA, or NOM_CHAM with NOM_CMP").keyword(kw("NOM_CMP"))
    })?;
    let node = node_name(ctx, resu, &modes.numbering.mesh, kw)?;
    let idx = modes
        .numbering
        .dofs
        .iter()
        .position(|d| d.node == node && d.cmp.name() == cmp)
        .ok_or_else(|| {
            Error::validation(format!("{name} has no DOF {cmp} on node {node}"))
                .keyword(kw("NOM_CMP"))
        })?;
    Ok(mode.shape[idx])
}

fn dyna_value(
    ctx: &OpContext<'_>,
    resu: &Args,
    name: &str,
    kw: &dyn Fn(&str) -> String,
) -> Result<f64> {
    let c = dyna_trans::component(ctx.store, resu, name, kw, "TEST_RESU tests one value")?;
    let (field, node, cmp) = (c.field, c.node.as_str(), c.cmp.as_str());
    let by_inst = resu.real("INST");
    let n = resu.int("NUME_ORDRE");
    // Instants are found as Code_Aster finds them: to the second TOLE_MACHINE value with
    // the second CRITERE (the only ones if one is given: 1e-6 relative by default;
    // PRECISION is the test's own tolerance).
    let (prec, critere) = testing::extraction(resu)?;
    // The row of this DOF at the instant: by NUME_ORDRE exactly, or by INST the nearest
    // one within the extraction's precision (a coarse precision can hold several).
    let mut best: Option<(f64, usize)> = None;
    for (r, (&ti, &nr)) in c.samples.inst.iter().zip(&c.samples.nume_ordre).enumerate() {
        let distance = match (by_inst, n) {
            (Some(inst), _) => Some((ti - inst).abs()).filter(|d| match critere {
                Critere::Relatif => *d <= prec * inst.abs().max(1e-300),
                Critere::Absolu => *d <= prec,
            }),
            (None, Some(n)) => (nr == n).then_some(0.0),
            (None, None) => None,
        };
        if let Some(d) = distance {
            if best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, r));
            }
        }
    }
    if let Some((_, r)) = best {
        return Ok(c.samples.values[r]);
    }
    Err(Error::validation(format!(
        "{name} has no {field} value of {node} {cmp} at the requested instant"
    ))
    .keyword(kw("INST"))
    .hint(format!(
        "give NUME_ORDRE (1..NB_INST) or an INST of the stored time history; an INST is \
         found to the last value of TOLE_MACHINE with the last of CRITERE (here {prec:e} {}), \
         as in Code_Aster",
        match critere {
            Critere::Relatif => "RELATIF",
            Critere::Absolu => "ABSOLU",
        }
    )))
}
