//! IMPR_RESU: FORMAT='MED' writes a mesh and the nodal fields of results (mode shapes,
//! NNM orbits) to a MED file for ParaVis, SALOME or meshio (`ops::common::med_fields`
//! builds the fields, `mesh::med_write` writes the file). Code_Aster's other formats are
//! an alarm: the results stay in the database.

use super::common::med_fields::{history_fields, mesh_of, mode_fields};
use super::common::output::{check_output_path, unit_path};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::med_write::{write_file, NodalField};
use crate::store::mesh::load_mesh;
use std::io::Read;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let format = args.req_text("FORMAT")?;
    if format != "MED" {
        return ctx.alarm(
            "IMPR_RESU_1",
            &format!(
                "FORMAT='{format}' is not written by aster-nl: nothing printed; the results \
                 stay in the database (query them with SQL, docs/store.md), or write them \
                 with FORMAT='MED'"
            ),
        );
    }
    let mut mesh_name: Option<String> = None;
    let mut wanted: Vec<(&Args, Option<(String, String)>)> = Vec::new();
    // The mesh of every occurrence: one file holds one mesh.
    for occ in args.facts_or_empty("RESU") {
        let (mesh, result) = match occ.concept("RESULTAT") {
            Some(c) => (
                mesh_of(ctx.store, &c.name, &c.ty)?,
                Some((c.name.clone(), c.ty.clone())),
            ),
            None => (occ.req_concept("MAILLAGE")?.name.clone(), None),
        };
        // Both given (Code_Aster accepts it): the result must be on that mesh.
        if let Some(m) = occ
            .concept("MAILLAGE")
            .filter(|m| result.is_some() && m.name != mesh)
        {
            return Err(Error::validation(format!(
                "the result is on mesh {mesh}, not on MAILLAGE={}",
                m.name
            ))
            .keyword(occ.key_path("MAILLAGE"))
            .hint("give the result's own mesh, or drop MAILLAGE"));
        }
        match &mesh_name {
            Some(m) if *m != mesh => {
                return Err(Error::validation(format!(
                    "the results of one IMPR_RESU are on meshes {m} and {mesh}: a MED file \
                     written by aster-nl holds one mesh"
                ))
                .keyword(occ.key_path("RESULTAT"))
                .hint("write them with two IMPR_RESU calls to two units"));
            }
            _ => mesh_name = Some(mesh),
        }
        wanted.push((occ, result));
    }
    let Some(mesh_name) = mesh_name else {
        return Err(
            Error::validation("IMPR_RESU needs a RESU occurrence").keyword("IMPR_RESU/RESU")
        );
    };
    let mesh = load_mesh(ctx.store, &mesh_name)?;
    let mut fields: Vec<NodalField> = Vec::new();
    for (occ, result) in wanted {
        let Some((name, ty)) = result else { continue };
        let orders = occ.ints("NUME_ORDRE");
        let new = if ty == "mode_meca" {
            mode_fields(ctx.store, &name, &mesh, &mesh_name, orders.as_deref())?
        } else {
            let cham = occ.texts("NOM_CHAM");
            history_fields(
                ctx.store,
                &name,
                &mesh,
                &mesh_name,
                cham.as_deref(),
                orders.as_deref(),
            )?
        };
        if let Some(orders) = &orders {
            let have: Vec<i64> = new
                .first()
                .map_or(Vec::new(), |f| f.steps.iter().map(|s| s.number).collect());
            if let Some(o) = orders.iter().find(|o| !have.contains(o)) {
                return Err(Error::input(format!("{name} has no NUME_ORDRE {o}"))
                    .keyword(occ.key_path("NUME_ORDRE")));
            }
        }
        fields.extend(new);
    }
    let unite = args.req_int("UNITE")?;
    let path = unit_path(ctx.units, unite);
    check_output_path(ctx.units, &path).map_err(|e| e.keyword("IMPR_RESU/UNITE"))?;
    refuse_non_hdf5(&path).map_err(|e| e.keyword("IMPR_RESU/UNITE"))?;
    write_file(&path, &mesh_name, &mesh, &fields)?;
    ctx.say(&format!(
        "IMPR_RESU: mesh {mesh_name} ({} nodes) and {} field(s) written to {}{}",
        mesh.nodes.len(),
        fields.len(),
        path.display(),
        if fields.is_empty() {
            String::new()
        } else {
            format!(
                ": {}",
                fields
                    .iter()
                    .map(|f| f.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    ))?;
    if ctx.info >= 2 {
        for f in &fields {
            ctx.say(&format!(
                "  {}: components {}, {} step(s)",
                f.name,
                f.components.join(" "),
                f.steps.len()
            ))?;
        }
    }
    Ok(())
}

/// A file that exists and is not HDF5 is not a MED file of an earlier run: it is not ours
/// to replace.
fn refuse_non_hdf5(path: &std::path::Path) -> Result<()> {
    let Ok(mut f) = std::fs::File::open(path) else {
        return Ok(());
    };
    let mut head = [0u8; 8];
    let n = f.read(&mut head).unwrap_or(0);
    if n == 0 || head == *b"\x89HDF\r\n\x1a\n" {
        return Ok(());
    }
    Err(Error::validation(format!(
        "{} exists and is not a MED (HDF5) file: IMPR_RESU will not write over it",
        path.display()
    ))
    .hint("map the unit to another file (a .export F line, or --unit N=PATH)"))
}
