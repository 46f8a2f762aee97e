//! Writing to Code_Aster logical units (UNITE): 6 is the run's output, 8 the results file
//! when one is mapped (a .export's `F resu`) else the run's output, any other unit the
//! file mapped in `ctx.units`, else `fort.N` beside the command file. Successive
//! prints to one unit append, as Code_Aster's do. An output is a regular file (or a new
//! one): a FIFO, a device, a directory or a symbolic link is refused as `--db` refuses it,
//! and the file is opened without following a link and without blocking.

use crate::error::{Error, Result};
use crate::ops::{OpContext, Units};
use std::io::Write;
use std::os::unix::fs::OpenOptionsExt;
use std::path::{Path, PathBuf};

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

/// Refuse to write to `path` when it is a file of the run (the database, its journals, the
/// command file, a mesh read by the run) or any SQLite database: a print must never destroy
/// what the study is made of.
pub fn check_output_path(units: &Units, path: &Path) -> Result<()> {
    let same = |p: &Path| p == path || crate::store::study_file::same_path(p, path);
    if let Some((_, what)) = units.protected.iter().find(|(p, _)| same(p)) {
        return Err(Error::validation(format!(
            "{} is {what}: an operator will not write over it",
            path.display()
        ))
        .hint("give the output another file (FICHIER, or --unit N=PATH)"));
    }
    if units.read.borrow().iter().any(|p| same(p)) {
        return Err(Error::validation(format!(
            "{} is an input file this run read: an operator will not write over it",
            path.display()
        ))
        .hint("give the output another file (FICHIER, or --unit N=PATH)"));
    }
    if let crate::store::study_file::FileKind::NotRegular(what) =
        crate::store::study_file::file_kind(path)?
    {
        return Err(Error::validation(format!(
            "{} is {what}: an operator writes its output to a regular file only",
            path.display()
        ))
        .hint("give the output a regular file (FICHIER, or --unit N=PATH)"));
    }
    if path.is_file() && crate::store::study_file::has_sqlite_header(path) {
        return Err(Error::validation(format!(
            "{} is an SQLite database: an operator will not write over it",
            path.display()
        ))
        .hint("give the output another file (FICHIER, or --unit N=PATH)"));
    }
    Ok(())
}

/// Write `text` to unit `unite`.
pub fn write_unit(ctx: &mut OpContext<'_>, unite: i64, text: &str) -> Result<()> {
    // 8 is Code_Aster's results file: the file a .export's `F resu` line (or --unit 8=)
    // maps, else the run's output, as 6 (the message file) always is.
    if unite == 6 || (unite == 8 && !ctx.units.map.contains_key(&8)) {
        ctx.out.write_all(text.as_bytes())?;
        return Ok(());
    }
    // unite >= 1: the catalogs' bound (IMPR_TABLE, IMPR_FONCTION).
    let path = unit_path(ctx.units, unite);
    check_output_path(ctx.units, &path).map_err(|e| e.keyword("UNITE"))?;
    // No link followed and no wait on a FIFO even if the path changed since the check.
    let mut f = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK | libc::O_CLOEXEC)
        .mode(0o644)
        .open(&path)
        .map_err(|e| {
            Error::from(e)
                .keyword("UNITE")
                .hint(format!("unit {unite} writes to {}", path.display()))
        })?;
    if !f.metadata().is_ok_and(|m| m.file_type().is_file()) {
        return Err(Error::validation(format!(
            "{} is not a regular file: an operator writes its output to a regular file only",
            path.display()
        ))
        .keyword("UNITE"));
    }
    f.write_all(text.as_bytes())
        .map_err(|e| Error::from(e).keyword("UNITE"))?;
    Ok(())
}

/// Where a picture goes: FICHIER (relative to the command file's directory), else the file
/// mapped to unit `unite`, else `fort.<unite>.<ext>` beside the command file. A picture
/// replaces the file: it cannot be appended to.
pub fn picture_path(units: &Units, fichier: Option<&str>, unite: i64, ext: &str) -> PathBuf {
    let beside = |name: &str| match units.comm_file.as_ref().and_then(|c| c.parent()) {
        Some(dir) => dir.join(name),
        None => PathBuf::from(name),
    };
    if let Some(f) = fichier {
        let p = std::path::Path::new(f);
        return if p.is_absolute() {
            p.to_path_buf()
        } else {
            beside(f)
        };
    }
    if let Some(p) = units.map.get(&unite) {
        return p.clone();
    }
    beside(&format!("fort.{unite}.{ext}"))
}

/// A text file a command file writes by its name (`np.savetxt("x.csv", ...)`): the path
/// relative to the command file's directory (as FICHIER), replaced as numpy replaces it,
/// with the checks of every output (never a file of the run, a link or a device). Returns
/// the path written.
pub fn write_named_file(units: &Units, name: &str, text: &str) -> Result<PathBuf> {
    let path = picture_path(units, Some(name), 0, "");
    check_output_path(units, &path)?;
    let mut f = std::fs::OpenOptions::new()
        .create(true)
        .write(true)
        .truncate(true)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK | libc::O_CLOEXEC)
        .mode(0o644)
        .open(&path)
        .map_err(|e| Error::from(e).hint(format!("writing {}", path.display())))?;
    if !f.metadata().is_ok_and(|m| m.file_type().is_file()) {
        return Err(Error::validation(format!(
            "{} is not a regular file: a command file writes to a regular file only",
            path.display()
        )));
    }
    f.write_all(text.as_bytes())?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picture_paths() {
        let mut units = Units {
            comm_file: Some(PathBuf::from("/study/case.comm")),
            ..Units::default()
        };
        units.map.insert(30, PathBuf::from("/out/fe.png"));
        assert_eq!(
            picture_path(&units, Some("pics/a.svg"), 8, "svg"),
            PathBuf::from("/study/pics/a.svg")
        );
        assert_eq!(
            picture_path(&units, Some("/tmp/a.png"), 8, "png"),
            PathBuf::from("/tmp/a.png")
        );
        assert_eq!(
            picture_path(&units, None, 30, "png"),
            PathBuf::from("/out/fe.png")
        );
        assert_eq!(
            picture_path(&units, None, 31, "png"),
            PathBuf::from("/study/fort.31.png")
        );
        let bare = Units::default();
        assert_eq!(
            picture_path(&bare, None, 8, "svg"),
            PathBuf::from("fort.8.svg")
        );
    }
}
