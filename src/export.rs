//! Code_Aster `.export` files: which file is the command file and which files are mapped to
//! logical units. Lines look like `F comm case.comm D 1` and `F mail case.mail D 20`
//! (`F <type> <path> <D|R|DR|...> <unit>`); other lines (`P ...`, `A ...`) are ignored.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// The `F comm` file (only one is accepted).
    pub comm: PathBuf,
    /// Logical unit → file, for the data files read by the study (`D` in the 4th field).
    pub units: Vec<(i64, PathBuf)>,
}

pub fn read_export(path: &Path) -> Result<Export> {
    let text = crate::text_file::read(path, "the export file")?;
    parse_export(&text, path)
}

pub fn parse_export(text: &str, path: &Path) -> Result<Export> {
    let base = path.parent().unwrap_or_else(|| Path::new("."));
    let file = path.display().to_string();
    let mut comm = None;
    let mut units = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.first() != Some(&"F") {
            continue;
        }
        if fields.len() < 5 {
            return Err(
                Error::input("an F line needs 5 fields: F <type> <path> <D|R|DR> <unit>")
                    .at_line(&file, i + 1),
            );
        }
        if fields.len() > 5 {
            return Err(Error::input(format!(
                "an F line has 5 fields, this one has {}: a path with a space cannot be written in an .export file",
                fields.len()
            ))
            .at_line(&file, i + 1)
            .hint("rename the file or its directory without spaces, or use --unit N=PATH"));
        }
        let (kind, p, mode, unit) = (fields[1], fields[2], fields[3], fields[4]);
        let unit: i64 = unit.parse().map_err(|_| {
            Error::input(format!("'{unit}' is not a logical unit number")).at_line(&file, i + 1)
        })?;
        let p = PathBuf::from(p);
        let p = if p.is_relative() { base.join(p) } else { p };
        if !mode.contains('D') {
            continue; // results written by Code_Aster: nothing to read
        }
        // What the study reads must be a regular file (not a directory or a device).
        match std::fs::metadata(&p) {
            Ok(m) if !m.is_file() => {
                return Err(Error::input(format!(
                    "{} (unit {unit}) is not a regular file",
                    p.display()
                ))
                .at_line(&file, i + 1));
            }
            _ => {}
        }
        if kind == "comm" {
            if comm.is_some() {
                return Err(Error::input(
                    "a second F comm line: aster-nl runs one command file per study",
                )
                .at_line(&file, i + 1)
                .hint("run the files one after the other, the second with POURSUITE()"));
            }
            comm = Some(p);
        } else {
            units.push((unit, p));
        }
    }
    let comm = comm.ok_or_else(|| {
        Error::input(format!("{file} names no command file"))
            .hint("add a line like `F comm case.comm D 1`")
    })?;
    Ok(Export { comm, units })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maps_comm_and_units_relative_to_the_export() {
        let text = "P actions make_etude\nF comm sdnd122a.comm D 1\nF mail sdnd122a.mail D 20\nF mess sdnd122a.mess R 6\n";
        let e = parse_export(text, Path::new("/cases/sdnd122a.export")).unwrap();
        assert_eq!(e.comm, PathBuf::from("/cases/sdnd122a.comm"));
        assert_eq!(e.units, vec![(20, PathBuf::from("/cases/sdnd122a.mail"))]);
    }

    #[test]
    fn a_second_comm_a_directory_and_a_path_with_a_space_are_refused() {
        let e = parse_export(
            "F comm a.comm D 1\nF comm b.comm D 1\n",
            Path::new("x.export"),
        )
        .unwrap_err();
        assert_eq!(e.location.as_ref().unwrap().span.line, 2);
        assert!(e.message.contains("a second F comm"), "{e}");
        let e = parse_export(
            "F comm a.comm D 1\nF mail /tmp D 20\n",
            Path::new("x.export"),
        )
        .unwrap_err();
        assert!(e.message.contains("not a regular file"), "{e}");
        let e = parse_export("F comm my case.comm D 1\n", Path::new("x.export")).unwrap_err();
        assert!(e.message.contains("a path with a space"), "{e}");
    }

    #[test]
    fn bad_unit_names_the_line() {
        let err = parse_export(
            "F comm a.comm D 1\nF mail a.mail D twenty\n",
            Path::new("x.export"),
        )
        .unwrap_err();
        assert_eq!(err.location.unwrap().span.line, 2);
        assert!(err.message.contains("twenty"));
    }
}
