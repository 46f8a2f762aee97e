//! Whether a modal basis holds the static flexibility of each shock: the shock's normal
//! direction at its node(s) over the physical DOFs of the stiffness the basis was computed
//! from, and the share of rᵀK⁻¹r the basis carries (`linalg::flexibility`). Below 95 %:
//! alarm DYNA_VIBRA_2, naming the shock and the share. With VERI_CHOC, the criterion
//! sqrt(1 − share) (the relative error, in the energy norm, of the static deformation under
//! the shock's normal force restricted to the basis) is held to SEUIL.

use super::shocks::ShockName;
use super::space::Space;
use crate::error::{Error, Result};
use crate::linalg::eigen::sym::SymSparse;
use crate::linalg::flexibility::flexibilities;
use crate::model::{AssembledMatrix, Cmp};
use crate::ops::OpContext;
use crate::store::{matrix, modes as mode_store};
use crate::transient::{ObstacleKind, Shock};

/// The share of the static flexibility below which the alarm is raised.
const LEAST_SHARE: f64 = 0.95;

/// VERI_CHOC: the largest criterion accepted, and whether exceeding it stops the run.
#[derive(Clone, Copy, Debug)]
pub struct VeriChoc {
    pub seuil: f64,
    pub stop: bool,
}

pub fn check(
    ctx: &mut OpContext<'_>,
    space: &Space,
    shocks: &[Shock],
    names: &[ShockName],
    veri: Option<VeriChoc>,
) -> Result<()> {
    let Space::Gene { basis, modes, .. } = space else {
        return Ok(());
    };
    if shocks.is_empty() {
        return Ok(());
    }
    // Without the stiffness the basis was computed from there is nothing to check against:
    // a VERI_CHOC asked for says so.
    let unchecked = |ctx: &mut OpContext<'_>, why: &str| -> Result<()> {
        match veri {
            Some(_) => ctx.say(&format!("DYNA_VIBRA: VERI_CHOC not checked: {why}")),
            None => Ok(()),
        }
    };
    let Some(matrices) = mode_store::load_matrices(ctx.store, basis)? else {
        return unchecked(
            ctx,
            &format!("{basis} does not name the stiffness it was computed from"),
        );
    };
    let k = match matrix::load_matrix(ctx.store, &matrices.rigi) {
        Ok(k) if k.numbering.dofs == modes.numbering.dofs => k,
        _ => {
            return unchecked(
                ctx,
                &format!(
                    "the stiffness {} of {basis} is no longer in the study",
                    matrices.rigi
                ),
            )
        }
    };
    let ks = SymSparse::from_faer(&k.reduced()?, "stiffness")?;
    let vectors: Vec<Vec<f64>> = modes
        .modes
        .iter()
        .filter_map(|m| k.restrict(&m.shape))
        .collect();
    for (shock, name) in shocks.iter().zip(names) {
        let rows: Vec<Vec<f64>> = normal_axes(shock.spec.obstacle)
            .iter()
            .map(|&axis| normal_row(&k, shock.frame.rows[axis], name))
            .collect();
        let Some(flex) = flexibilities(&ks, &rows, &vectors)? else {
            return unchecked(ctx, "the stiffness is singular along a shock's normal");
        };
        let share = flex.iter().map(|f| f.share()).fold(1.0f64, f64::min);
        let at = match &name.node2 {
            Some(n2) => format!("{} relative to {n2}", name.node1),
            None => name.node1.clone(),
        };
        if share < LEAST_SHARE {
            ctx.alarm(
                "DYNA_VIBRA_2",
                &format!(
                    "the basis {basis} holds {:.1} % of the static flexibility of {at} along the \
                     normal of shock {}: its contact acts on a structure stiffer than the real \
                     one there. Add the static mode of that DOF to the basis, or more modes",
                    100.0 * share,
                    name.intitule
                ),
            )?;
        }
        if let Some(v) = veri {
            let criterion = (1.0 - share).max(0.0).sqrt();
            let msg = format!(
                "VERI_CHOC: the static deformation under the normal force of shock {} ({at}) \
                 is represented by the basis {basis} to {criterion:.3e} (relative, energy norm), \
                 above SEUIL = {:e}",
                name.intitule, v.seuil
            );
            if criterion > v.seuil {
                if v.stop {
                    return Err(Error::input(msg)
                        .keyword("DYNA_VIBRA/VERI_CHOC/SEUIL")
                        .hint("add the static mode of the shock's DOF or more modes to the basis; STOP_CRITERE='NON' makes it an alarm"));
                }
                ctx.alarm("DYNA_VIBRA_3", &msg)?;
            } else if ctx.info >= 2 {
                ctx.say(&format!(
                    "DYNA_VIBRA: VERI_CHOC of shock {}: criterion {criterion:.3e} (SEUIL {:e})",
                    name.intitule, v.seuil
                ))?;
            }
        }
    }
    Ok(())
}

/// The local axes along which the obstacle's normal can lie.
fn normal_axes(kind: ObstacleKind) -> &'static [usize] {
    match kind {
        ObstacleKind::PlanY | ObstacleKind::BiPlanY => &[1],
        ObstacleKind::PlanZ | ObstacleKind::BiPlanZ => &[2],
        _ => &[1, 2],
    }
}

/// The direction `d` (global) at node 1, minus at node 2, over the free DOFs of `k`
/// (a DOF a LIAISON_DDL relation expresses counts through its expression).
fn normal_row(k: &AssembledMatrix, d: [f64; 3], name: &ShockName) -> Vec<f64> {
    let mut r = vec![0.0; k.size()];
    let cmps = [Cmp::Dx, Cmp::Dy, Cmp::Dz];
    for (node, sign) in [(Some(&name.node1), 1.0), (name.node2.as_ref(), -1.0)] {
        let Some(node) = node else { continue };
        for (c, cmp) in cmps.iter().enumerate() {
            let free = k
                .numbering
                .index_of(node, *cmp)
                .filter(|&i| !k.eliminated.get(i).copied().unwrap_or(true));
            if let Some(i) = free {
                r[i] += sign * d[c];
            }
        }
    }
    k.row_on_free(&r)
}
