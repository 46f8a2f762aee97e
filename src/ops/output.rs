//! Writing to Code_Aster logical units (UNITE): 6 and 8 are the run's output, any other
//! unit the file mapped in `ctx.units`, else `fort.N` beside the command file. Successive
//! prints to one unit append, as Code_Aster's do.

use super::{OpContext, Units};
use crate::error::{Error, Result};
use std::io::Write;
use std::path::PathBuf;

/// The file behind unit `unite` (not called for 6 and 8).
pub fn unit_path(units: &Units, unite: i64) -> PathBuf {
    if let Some(p) = units.map.get(&unite) {
        return p.clone();
    }
    let name = format!("fort.{unite}");
    match units.comm_file.as_ref().and_then(|c| c.parent()) {
        Some(dir) => dir.join(name),
        None => PathBuf::from(name),
    }
}

/// Write `text` to unit `unite`.
pub fn write_unit(ctx: &mut OpContext<'_>, unite: i64, text: &str) -> Result<()> {
    if unite == 6 || unite == 8 {
        ctx.out.write_all(text.as_bytes())?;
        return Ok(());
    }
    if unite <= 0 {
        return Err(
            Error::validation(format!("UNITE={unite} is not a logical unit")).keyword("UNITE"),
        );
    }
    let path = unit_path(ctx.units, unite);
    let mut f = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&path)
        .map_err(|e| {
            Error::from(e)
                .keyword("UNITE")
                .hint(format!("unit {unite} writes to {}", path.display()))
        })?;
    f.write_all(text.as_bytes())
        .map_err(|e| Error::from(e).keyword("UNITE"))?;
    Ok(())
}
