//! CREA_CHAMP (OPERATION='AFFE', TYPE_CHAM='NOEU_DEPL_R'): a nodal field given by hand.

use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::select::select_nodes;
use crate::store::gene::{self, NodalField};
use crate::store::{matrix, model};
use std::collections::BTreeMap;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let mesh_name = mesh_of(ctx, args)?;
    let mesh = model::load_mesh(ctx.store, &mesh_name)?;
    // (node index, component) -> value; a later occurrence overrides an earlier one.
    let mut values: BTreeMap<(usize, String), f64> = BTreeMap::new();
    for occ in args.facts_or_empty("AFFE") {
        let cmps = occ.req_texts("NOM_CMP")?;
        let vals = occ.req_reals("VALE")?;
        if cmps.len() != vals.len() {
            return Err(Error::validation(format!(
                "NOM_CMP has {} components and VALE {} values: give one value per component",
                cmps.len(),
                vals.len()
            ))
            .keyword(occ.key_path("VALE")));
        }
        for node in select_nodes(&mesh, &selection(occ))? {
            for (c, v) in cmps.iter().zip(&vals) {
                values.insert((node, c.clone()), *v);
            }
        }
    }
    let field = NodalField {
        mesh: mesh_name,
        values: values
            .into_iter()
            .map(|((node, cmp), v)| (mesh.nodes[node].name.clone(), cmp, v))
            .collect(),
    };
    ctx.create(&name, "cham_no_sdaster")?;
    gene::save_field(ctx.store, &name, &field)
}

/// The mesh the field lives on: that of each of MAILLAGE, MODELE, NUME_DDL and CHAM_NO
/// given, which must be the same.
fn mesh_of(ctx: &OpContext<'_>, args: &Args) -> Result<String> {
    let mut meshes: Vec<(&str, String)> = Vec::new();
    if let Some(m) = args.concept("MAILLAGE") {
        meshes.push(("MAILLAGE", m.name.clone()));
    }
    if let Some(m) = args.concept("MODELE") {
        meshes.push(("MODELE", model::load_model(ctx.store, &m.name)?.mesh));
    }
    if let Some(n) = args.concept("NUME_DDL") {
        meshes.push(("NUME_DDL", matrix::load_numbering(ctx.store, &n.name)?.mesh));
    }
    if let Some(f) = args.concept("CHAM_NO") {
        meshes.push(("CHAM_NO", gene::load_field(ctx.store, &f.name)?.mesh));
    }
    let Some((_, first)) = meshes.first().cloned() else {
        return Err(
            Error::validation("give MAILLAGE, MODELE, NUME_DDL or CHAM_NO").keyword("CREA_CHAMP"),
        );
    };
    if let Some((key, other)) = meshes.iter().find(|(_, m)| *m != first) {
        return Err(Error::input(format!(
            "{key} is on mesh {other}, {} on mesh {first}",
            meshes[0].0
        ))
        .keyword(format!("CREA_CHAMP/{key}")));
    }
    Ok(first)
}
