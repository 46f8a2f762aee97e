//! DYNA_VIBRA's moving supports: each EXCIT with MULT_APPUI='OUI' names supports (NOEUD,
//! GROUP_NO) that move along DIRECTION by DEPL(t) (velocity VITE, acceleration ACCE); the
//! force it gives is its VECT_ASSE_GENE times ACCE (CALC_CHAR_SEISME's −M·ψ projected).
//! Its shocks see the absolute motion: ψ at their nodes times DEPL and VITE is added
//! (transient/support.rs). What the result must know to restore absolute fields
//! (REST_GENE_PHYS, RECU_FONCTION with MULT_APPUI='OUI') is stored with it.

use super::shocks::ShockName;
use super::space::Space;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::Cmp;
use crate::ops::common::supports::{support_nodes, ConstraintModes};
use crate::ops::OpContext;
use crate::store::function as function_store;
use crate::store::tran_gene::StoredSupport;
use crate::transient::{Shock, SupportMotion, SupportTerm, TimeFn};
use std::rc::Rc;

/// One moving support excitation: what is stored, and ψ in the full numbering.
pub struct Support {
    pub stored: StoredSupport,
    psi: Vec<f64>,
    modes: ConstraintModes,
}

/// The EXCIT occurrences with MULT_APPUI='OUI', in order.
pub fn read(ctx: &OpContext<'_>, args: &Args, space: &Space) -> Result<Vec<Support>> {
    let mut out = Vec::new();
    for occ in args.facts_or_empty("EXCIT") {
        if occ.text("MULT_APPUI") != Some("OUI") {
            continue;
        }
        let Some(ms) = args.concept("MODE_STAT") else {
            return Err(
                Error::validation("MULT_APPUI='OUI' needs the supports' constraint modes")
                    .keyword("DYNA_VIBRA/MODE_STAT")
                    .hint("give MODE_STAT=<MODE_STATIQUE result with MODE_STAT=_F(...)>"),
            );
        };
        let key = "DYNA_VIBRA/MODE_STAT";
        let modes = ConstraintModes::load(ctx.store, &ms.name, key)?;
        if modes.modes.numbering.mesh != space.mesh() {
            return Err(Error::input(format!(
                "{} is computed on mesh {}, the run's basis on {}",
                ms.name,
                modes.modes.numbering.mesh,
                space.mesh()
            ))
            .keyword(key));
        }
        let nodes = support_nodes(ctx.store, occ, space.mesh())?;
        if nodes.is_empty() {
            return Err(
                Error::validation("MULT_APPUI='OUI' needs the moving supports")
                    .keyword(occ.key_path("GROUP_NO"))
                    .hint("name the support nodes with GROUP_NO (or NOEUD)"),
            );
        }
        let direction = occ.reals("DIRECTION").ok_or_else(|| {
            Error::validation("MULT_APPUI='OUI' needs the DIRECTION of the supports' motion")
                .keyword(occ.key_path("DIRECTION"))
        })?;
        let psi = modes.combination(&nodes, &direction, &occ.key_path("DIRECTION"))?;
        let name = |k: &str| -> Result<String> {
            occ.concept(k).map(|c| c.name.clone()).ok_or_else(|| {
                Error::validation("MULT_APPUI='OUI' needs ACCE, VITE and DEPL")
                    .keyword(occ.key_path(k))
            })
        };
        out.push(Support {
            stored: StoredSupport {
                mode_stat: ms.name.clone(),
                nodes,
                direction,
                acce: name("ACCE")?,
                vite: name("VITE")?,
                depl: name("DEPL")?,
            },
            psi,
            modes,
        });
    }
    Ok(out)
}

/// Makes each shock follow the supports: ψ of every support at its nodes, with that
/// support's DEPL and VITE.
pub fn attach(
    ctx: &OpContext<'_>,
    supports: &[Support],
    shocks: &mut [Shock],
    names: &[ShockName],
) -> Result<()> {
    if supports.is_empty() {
        return Ok(());
    }
    let mut functions = Vec::with_capacity(supports.len());
    for s in supports {
        functions.push((time_fn(ctx, &s.stored.depl)?, time_fn(ctx, &s.stored.vite)?));
    }
    for (shock, name) in shocks.iter_mut().zip(names) {
        let mut terms = Vec::with_capacity(supports.len());
        for (s, (depl, vite)) in supports.iter().zip(&functions) {
            let at = |node: Option<&String>| -> [f64; 3] {
                let mut p = [0.0; 3];
                if let Some(node) = node {
                    for (c, v) in [Cmp::Dx, Cmp::Dy, Cmp::Dz].into_iter().zip(p.iter_mut()) {
                        if let Some(i) = s.modes.modes.numbering.index_of(node, c) {
                            *v = s.psi.get(i).copied().unwrap_or(0.0);
                        }
                    }
                }
                p
            };
            let psi = [at(Some(&name.node1)), at(name.node2.as_ref())];
            if psi.iter().flatten().all(|v| *v == 0.0) {
                continue;
            }
            terms.push(SupportTerm {
                psi,
                depl: depl.clone(),
                vite: vite.clone(),
            });
        }
        shock.set_support(SupportMotion::new(terms));
    }
    Ok(())
}

/// A function of INST as the integrator evaluates it. A value it cannot give (outside an
/// EXCLU domain) is NaN, which stops the run naming the instant.
fn time_fn(ctx: &OpContext<'_>, name: &str) -> Result<TimeFn> {
    let g = function_store::load_any_function(ctx.store, name)?;
    Ok(Rc::new(move |t| g.eval(t).unwrap_or(f64::NAN)))
}
