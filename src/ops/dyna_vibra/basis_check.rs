//! Whether a modal basis holds the static flexibility of each shock: the shock's normal
//! direction at its node(s) over the physical DOFs of the stiffness the basis was computed
//! from, and the share of rᵀK⁻¹r the basis carries (`linalg::flexibility`). Below 95 %:
//! alarm DYNA_VIBRA_2, naming the shock and the share.

use super::shocks::ShockName;
use super::space::Space;
use crate::error::Result;
use crate::linalg::eigen::sym::SymSparse;
use crate::linalg::flexibility::flexibilities;
use crate::model::{AssembledMatrix, Cmp};
use crate::ops::OpContext;
use crate::store::{matrix, modes as mode_store};
use crate::transient::{ObstacleKind, Shock};

/// The share of the static flexibility below which the alarm is raised.
const LEAST_SHARE: f64 = 0.95;

pub fn check(
    ctx: &mut OpContext<'_>,
    space: &Space,
    shocks: &[Shock],
    names: &[ShockName],
) -> Result<()> {
    let Space::Gene { basis, modes, .. } = space else {
        return Ok(());
    };
    if shocks.is_empty() {
        return Ok(());
    }
    // A basis stored without its matrices, or whose stiffness was renamed since: no check.
    let Some(matrices) = mode_store::load_matrices(ctx.store, basis)? else {
        return Ok(());
    };
    let Ok(k) = matrix::load_matrix(ctx.store, &matrices.rigi) else {
        return Ok(());
    };
    if k.numbering.dofs != modes.numbering.dofs {
        return Ok(());
    }
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
            return Ok(());
        };
        let share = flex.iter().map(|f| f.share()).fold(1.0f64, f64::min);
        if share < LEAST_SHARE {
            ctx.alarm(
                "DYNA_VIBRA_2",
                &format!(
                    "the basis {basis} holds {:.1} % of the static flexibility of {} along the \
                     normal of shock {}: its contact acts on a structure stiffer than the real \
                     one there. Add the static mode of that DOF to the basis, or more modes",
                    100.0 * share,
                    match &name.node2 {
                        Some(n2) => format!("{} relative to {n2}", name.node1),
                        None => name.node1.clone(),
                    },
                    name.intitule
                ),
            )?;
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
