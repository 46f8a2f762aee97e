//! Code_Aster `.export` files: which file is the command file and which files are mapped to
//! logical units. Lines look like `F comm case.comm D 1` and `F mail case.mail D 20`
//! (`F <type> <path> <D|R|DR|...> <unit>`); other lines (`P ...`, `A ...`) are ignored.
//!
//! Results (`R` in the 4th field) as Code_Aster writes them: `F mess FILE R 6` is the
//! message file (everything the run prints), `F resu FILE R 8` the results file (what
//! IMPR_TABLE prints to its default unit 8), any other `F <type> FILE R <unit>` the file
//! of that unit (IMPR_TABLE, IMPR_RESU...), and `R base DIR <R|DC|...> 0` the study
//! database's location: `DIR/<command file's stem>.db` (a path ending in `.db` is the
//! database itself).

use crate::error::{Error, Result};
use crate::ops::Units;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// The `F comm` file (only one is accepted).
    pub comm: PathBuf,
    /// Logical unit → file, for the data files read by the study (`D` in the 4th field).
    pub units: Vec<(i64, PathBuf)>,
    /// Logical unit → file, for the result files the study writes (`R` without `D`),
    /// `F resu` (unit 8) among them.
    pub results: Vec<(i64, PathBuf)>,
    /// `F mess`: the message file.
    pub mess: Option<PathBuf>,
    /// `R base`: where the study database goes (a directory, or a `.db` file).
    pub base: Option<PathBuf>,
}

impl Export {
    /// The database the export asks for, if it names one (`R base`): inside the directory
    /// `base` as `<comm stem>.db`, or `base` itself when it ends in `.db`.
    pub fn database(&self) -> Option<PathBuf> {
        let base = self.base.as_ref()?;
        if base.extension().is_some_and(|e| e == "db") {
            return Some(base.clone());
        }
        let stem = self.comm.file_stem().map_or_else(
            || std::ffi::OsString::from("study"),
            std::ffi::OsStr::to_os_string,
        );
        let mut name = stem;
        name.push(".db");
        Some(base.join(name))
    }
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
    let mut results = Vec::new();
    let (mut mess, mut base_dir) = (None, None);
    for (i, line) in text.lines().enumerate() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.first() == Some(&"R") && fields.get(1) == Some(&"base") {
            let Some(p) = fields.get(2) else {
                return Err(Error::input(
                    "an R base line needs the database's directory: R base <dir> <R|DC> 0",
                )
                .at_line(&file, i + 1));
            };
            let p = PathBuf::from(p);
            base_dir = Some(if p.is_relative() { base.join(p) } else { p });
            continue;
        }
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
            // A result the study writes.
            match kind {
                "mess" => mess = Some(p),
                _ => results.push((unit, p)),
            }
            continue;
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
    Ok(Export {
        comm,
        units,
        results,
        mess,
        base: base_dir,
    })
}

/// Make `path` an empty file for the run to write (the export's message or results file):
/// refused when it is one of the run's inputs (`units.protected`, the command file), the
/// database `db`, or any SQLite file; its directory is created if missing.
pub fn prepare_result_file(
    units: &Units,
    path: &Path,
    db: Option<&Path>,
    comm: &Path,
) -> Result<()> {
    let same = |p: &Path| crate::store::study_file::same_path(p, path) || p == path;
    if same(comm) || db.is_some_and(same) {
        return Err(Error::input(format!(
            "the export names {} as a result file, and it is {}: the run will not write over it",
            path.display(),
            if same(comm) {
                "the command file"
            } else {
                "the study database"
            }
        ))
        .hint("give the F mess / F resu line another file"));
    }
    crate::ops::common::output::check_output_path(units, path)
        .map_err(|e| e.hint("give the export's result line another file"))?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| {
            Error::input(format!(
                "cannot create {} for {}: {e}",
                dir.display(),
                path.display()
            ))
        })?;
    }
    File::create(path)
        .map(|_| ())
        .map_err(|e| Error::input(format!("cannot write {}: {e}", path.display())))
}

/// What the run prints, to standard output and, when the export names one, to the message
/// file (`F mess`) as well.
pub struct Tee<W: Write> {
    out: W,
    file: Option<File>,
}

impl<W: Write> Tee<W> {
    pub fn new(out: W, file: Option<File>) -> Self {
        Tee { out, file }
    }

    /// A line printed elsewhere (an error on standard error) that the message file holds
    /// too. A message file that cannot be written to is not worth stopping the report.
    pub fn also_to_file(&mut self, line: &str) {
        if let Some(f) = &mut self.file {
            let _ = writeln!(f, "{line}");
        }
    }
}

impl<W: Write> Write for Tee<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.out.write_all(buf)?;
        if let Some(f) = &mut self.file {
            f.write_all(buf)?;
        }
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()?;
        if let Some(f) = &mut self.file {
            f.flush()?;
        }
        Ok(())
    }
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
        assert_eq!(e.mess, Some(PathBuf::from("/cases/sdnd122a.mess")));
        assert_eq!(e.database(), None);
    }

    /// `F mess`, `F resu`, other result files and `R base`, as Code_Aster's export names
    /// them (before, every R line was ignored).
    #[test]
    fn maps_the_result_files_and_the_database() {
        let text = "F comm case.comm D 1\nF mess out/case.mess R 6\nF resu out/case.resu R 8\n\
                    F rmed out/case.rmed R 80\nR base out/base DC 0\n";
        let e = parse_export(text, Path::new("/s/case.export")).unwrap();
        assert_eq!(e.mess, Some(PathBuf::from("/s/out/case.mess")));
        assert_eq!(
            e.results,
            vec![
                (8, PathBuf::from("/s/out/case.resu")),
                (80, PathBuf::from("/s/out/case.rmed"))
            ]
        );
        assert_eq!(e.database(), Some(PathBuf::from("/s/out/base/case.db")));
        let e = parse_export(
            "F comm c.comm D 1\nR base /x/study.db R 0\n",
            Path::new("e.export"),
        )
        .unwrap();
        assert_eq!(e.database(), Some(PathBuf::from("/x/study.db")));
        let err = parse_export("F comm c.comm D 1\nR base\n", Path::new("e.export")).unwrap_err();
        assert_eq!(err.location.unwrap().span.line, 2);
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
