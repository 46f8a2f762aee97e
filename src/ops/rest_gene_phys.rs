//! REST_GENE_PHYS: physical fields u = Φq of a DYNA_VIBRA (GENE) result at chosen instants
//! and nodes, as a `dyna_trans` (the table layout of REST_MODE_NONL); with MULT_APPUI='OUI'
//! the absolute motion of a multi-support run (the supports' share added).

use super::common::gene::numbering_and_basis;
use super::common::instants::{picks, value};
use super::common::selection::selection;
use super::common::supports::SupportShare;
use super::dyna_vibra::field_header;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::select::select_nodes;
use crate::store::tran_gene::{self, load_coordinates};
use crate::store::{dyna_trans as dyna_store, model, table as table_store};
use crate::table::Cell;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let src = args.req_concept("RESU_GENE")?.name.clone();
    let payload = tran_gene::load_payload(ctx.store, &src)?;
    if payload.base != "GENE" {
        return Err(
            Error::input(format!("{src} is not a result on a modal basis"))
                .keyword("REST_GENE_PHYS/RESU_GENE"),
        );
    }
    let (_, modes) = numbering_and_basis(ctx.store, &payload.numbering, None, "REST_GENE_PHYS")?;
    let n = modes.modes.len();
    let coords = load_coordinates(ctx.store, &src, n)?;
    // MULT_APPUI='OUI': the absolute motion, the supports' share added to Φq.
    let share = match args.text("MULT_APPUI") {
        Some("OUI") => Some(SupportShare::load(
            ctx.store,
            &src,
            &payload.supports,
            "REST_GENE_PHYS/MULT_APPUI",
        )?),
        _ => None,
    };
    let fields: Vec<&str> = match args.texts("NOM_CHAM") {
        Some(v) => dyna_store::FIELDS
            .into_iter()
            .filter(|f| v.iter().any(|g| g == f))
            .collect(),
        None => dyna_store::FIELDS.to_vec(),
    };
    let mesh = model::load_mesh(ctx.store, &modes.numbering.mesh)?;
    let sel = selection(args);
    let nodes: Option<std::collections::HashSet<&str>> =
        if sel.all || !(sel.names_nodes() || sel.cell_groups.given() || sel.cells.given()) {
            None
        } else {
            Some(
                select_nodes(&mesh, &sel)?
                    .into_iter()
                    .map(|i| mesh.nodes[i].name.as_str())
                    .collect(),
            )
        };
    // The DOFs restored: free DOFs of the basis's numbering at the chosen nodes.
    let dofs: Vec<usize> = (0..modes.numbering.len())
        .filter(|&i| !modes.numbering.eliminated[i])
        .filter(|&i| {
            nodes
                .as_ref()
                .is_none_or(|ns| ns.contains(&modes.numbering.dofs[i].node.as_str()))
        })
        .collect();
    let chosen = picks(args, &coords.t, "INTERPOL")?;
    let mut t = field_header(format!("REST_GENE_PHYS of {src}"), &fields)?;
    let series = [&coords.q, &coords.v, &coords.a];
    for (k, p) in chosen.iter().enumerate() {
        // The supports' DEPL, VITE, ACCE at this instant, per field asked: evaluated once,
        // not once per DOF.
        let mut support_values: Vec<Option<Vec<f64>>> = Vec::with_capacity(3);
        for f in dyna_store::FIELDS {
            support_values.push(match &share {
                Some(sh) if fields.contains(&f) => Some(
                    sh.values(f, p.t)
                        .map_err(|e| e.keyword("REST_GENE_PHYS/MULT_APPUI"))?,
                ),
                _ => None,
            });
        }
        for &i in &dofs {
            let dof = &modes.numbering.dofs[i];
            let mut row = vec![
                Cell::I(k as i64 + 1),
                Cell::R(p.t),
                Cell::K(dof.node.clone()),
                Cell::K(dof.cmp.name().to_string()),
            ];
            for ((f, s), g) in dyna_store::FIELDS.iter().zip(series).zip(&support_values) {
                if fields.contains(f) {
                    let phys = |at: usize| -> f64 {
                        modes
                            .modes
                            .iter()
                            .enumerate()
                            .map(|(j, m)| m.shape[i] * s[at * n + j])
                            .sum()
                    };
                    let support = match (&share, g) {
                        (Some(sh), Some(g)) => sh.combine(g, i),
                        _ => 0.0,
                    };
                    row.push(Cell::R(value(p, phys) + support));
                }
            }
            t.push_row(row)?;
        }
    }
    ctx.create(&name, "dyna_trans")?;
    table_store::save_table(ctx.store, &name, &t)?;
    dyna_store::save_layout(
        ctx.store,
        &name,
        &dyna_store::Layout::of(&modes.numbering, &modes.numbering.eliminated),
    )?;
    ctx.say(&format!(
        "REST_GENE_PHYS {name}: {} at {} instants and {} DOFs of {src}",
        fields.join(", "),
        chosen.len(),
        dofs.len()
    ))
}
