//! CALC_CHAR_SEISME: the load −M·Δ (MONO_APPUI) or −M·ψ (MODE_STAT, the named supports'
//! constraint modes along DIRECTION) of a unit support acceleration, as a nodal field.

use super::common::supports::{support_nodes, ConstraintModes};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::static_shapes::{mul_full, rigid_translation};
use crate::store::gene::{self, NodalField};
use crate::store::matrix;

const OP: &str = "CALC_CHAR_SEISME";

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let m_name = args.req_concept("MATR_MASS")?.name.clone();
    let m = matrix::load_matrix(ctx.store, &m_name)?;
    m.refuse_damping(&m_name, &format!("{OP}/MATR_MASS"))?;
    let dir = args.reals("DIRECTION").unwrap_or_default();
    if let Some(r) = dir.iter().skip(3).find(|v| **v != 0.0) {
        return Err(
            Error::validation(format!("a rotational direction ({r}) is not computed"))
                .keyword(format!("{OP}/DIRECTION"))
                .hint("give the translation (x, y, z) only"),
        );
    }
    let motion = match args.concept("MODE_STAT") {
        None => rigid_translation(
            &m,
            [
                dir.first().copied().unwrap_or(0.0),
                dir.get(1).copied().unwrap_or(0.0),
                dir.get(2).copied().unwrap_or(0.0),
            ],
        ),
        Some(c) => {
            let key = format!("{OP}/MODE_STAT");
            let modes = ConstraintModes::load(ctx.store, &c.name, &key)?;
            if modes.modes.numbering.dofs != m.numbering.dofs {
                return Err(
                    Error::input(format!("{} is not on the DOFs of {m_name}", c.name)).keyword(key),
                );
            }
            let nodes = support_nodes(ctx.store, args, &m.numbering.mesh)?;
            modes.combination(&nodes, &dir, &key)?
        }
    };
    let load = mul_full(&m, &motion);
    let values = m
        .numbering
        .dofs
        .iter()
        .zip(&load)
        .zip(&m.eliminated)
        .map(|((d, &f), &blocked)| {
            let v = if blocked { 0.0 } else { -f };
            (d.node.clone(), d.cmp.name().to_string(), v)
        })
        .collect();
    ctx.create(&name, "cham_no_sdaster")?;
    gene::save_field(
        ctx.store,
        &name,
        &NodalField {
            mesh: m.numbering.mesh.clone(),
            values,
        },
    )
}
