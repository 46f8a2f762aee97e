//! LIRE_MAILLAGE: read a mesh file into a `maillage_sdaster` concept.

use super::{OpContext, Units};
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::{self, check, MeshFormat};
use crate::store::mesh::save_mesh;
use std::path::PathBuf;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    // Defaults are the catalog's (commands/LIRE_MAILLAGE.toml), filled by the validation.
    let fmt_kw = args.req_text("FORMAT")?;
    let format = MeshFormat::from_keyword(fmt_kw).ok_or_else(|| {
        Error::validation(format!("unknown mesh format '{fmt_kw}'"))
            .keyword(args.key_path("FORMAT"))
            .hint("ASTER, GMSH or MED")
    })?;
    let unit = args.req_int("UNITE")?;
    let (path, beside) =
        resolve_file(ctx.units, unit, format).map_err(|e| e.keyword(args.key_path("UNITE")))?;
    if beside {
        ctx.say(&format!(
            "LIRE_MAILLAGE: unit {unit} is not mapped; reading {} (beside the command file)",
            path.display()
        ))?;
    }
    ctx.units.read.borrow_mut().push(path.clone());
    let mesh = mesh::read_file(&path, format, args.text("NOM_MED"))?;

    let v = args.req_fact("VERI_MAIL")?;
    if v.req_text("VERIF")? == "OUI" {
        for f in check::verify(&mesh, v.req_real("APLAT")?) {
            ctx.alarm(f.id, &f.message)?;
        }
    }
    ctx.say(&format!("{name}: {}", mesh.summary()))?;
    if ctx.info >= 2 {
        for g in &mesh.cell_groups {
            ctx.say(&format!(
                "  GROUP_MA {:<24} {} cell(s)",
                g.name,
                g.members.len()
            ))?;
        }
        for g in &mesh.node_groups {
            ctx.say(&format!(
                "  GROUP_NO {:<24} {} node(s)",
                g.name,
                g.members.len()
            ))?;
        }
    }
    ctx.create(&name, "maillage_sdaster")?;
    save_mesh(ctx.store, &name, &mesh)
}

/// The file of logical unit `unit`: the mapped file, or else the file beside the command
/// file with one of the format's extensions. The flag says whether the latter was used.
pub fn resolve_file(units: &Units, unit: i64, format: MeshFormat) -> Result<(PathBuf, bool)> {
    if let Some(p) = units.map.get(&unit) {
        if p.is_file() {
            return Ok((p.clone(), false));
        }
        return Err(Error::input(format!(
            "unit {unit} is mapped to {}, which does not exist",
            p.display()
        ))
        .hint("check the path given with --unit or in the .export file"));
    }
    let candidates: Vec<PathBuf> = units
        .comm_file
        .as_ref()
        .map(|c| {
            format
                .extensions()
                .iter()
                .map(|e| c.with_extension(e))
                .collect()
        })
        .unwrap_or_default();
    if let Some(p) = candidates.iter().find(|p| p.is_file()) {
        return Ok((p.clone(), true));
    }
    match candidates.first().cloned() {
        Some(p) => Err(Error::input(format!(
            "no mesh file for unit {unit}: the unit is not mapped and {} does not exist",
            p.display()
        ))
        .hint(format!(
            "map the unit (--unit {unit}=FILE or a line `F {} FILE D {unit}` in the .export), \
             or put the mesh beside the command file",
            format.extension()
        ))),
        None => Err(Error::input(format!(
            "no mesh file for unit {unit}: the unit is not mapped and there is no command file to look beside"
        ))
        .hint(format!("map the unit: --unit {unit}=FILE"))),
    }
}
