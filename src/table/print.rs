//! Printing tables as Code_Aster does: FORMAT='TABLEAU' (title lines starting with `#`,
//! aligned columns), FORMAT='ASTER' (the same between `#DEBUT_TABLE` and `#FIN_TABLE`,
//! with a line of types), FORMAT='CSV' and FORMAT='XMGRACE' (two columns as a Grace
//! file). Reals follow FORMAT_R (`E12.5` by default, i.e. C's `%12.5E` with a two-digit
//! exponent at least).

use super::{Cell, ColKind, Table};
use crate::error::{Error, Result};

/// A Fortran-style real format: `E12.5` or `F12.3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormatR {
    E { width: usize, prec: usize },
    F { width: usize, prec: usize },
}

impl Default for FormatR {
    fn default() -> Self {
        FormatR::E { width: 12, prec: 5 }
    }
}

impl FormatR {
    /// Parse `E12.5`, `F10.3`, `D12.5` (D is read as E, as Fortran does).
    pub fn parse(s: &str) -> Result<FormatR> {
        let bad = || {
            Error::validation(format!("FORMAT_R '{s}' is not a real format"))
                .keyword("FORMAT_R")
                .hint("write it like Code_Aster: 'E12.5' or 'F12.3'")
        };
        let s = s.trim();
        let mut chars = s.chars();
        let letter = chars.next().ok_or_else(bad)?.to_ascii_uppercase();
        let (w, p) = chars.as_str().split_once('.').ok_or_else(bad)?;
        let width: usize = w.parse().map_err(|_| bad())?;
        let prec: usize = p.parse().map_err(|_| bad())?;
        if width > 64 || prec > 30 {
            return Err(bad());
        }
        match letter {
            'E' | 'D' => Ok(FormatR::E { width, prec }),
            'F' => Ok(FormatR::F { width, prec }),
            _ => Err(bad()),
        }
    }

    pub fn width(self) -> usize {
        match self {
            FormatR::E { width, .. } | FormatR::F { width, .. } => width,
        }
    }

    /// The value right-aligned in the format's width (wider when it does not fit).
    pub fn format(self, x: f64) -> String {
        match self {
            FormatR::E { width, prec } => format!("{:>width$}", format_e(x, prec)),
            FormatR::F { width, prec } => format!("{x:>width$.prec$}"),
        }
    }
}

/// C's `%.{prec}E`: mantissa, `E`, sign, exponent with at least two digits.
pub fn format_e(x: f64, prec: usize) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    let s = format!("{x:.prec$E}");
    match s.split_once('E') {
        Some((mant, exp)) => {
            let (sign, digits) = match exp.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', exp),
            };
            format!("{mant}E{sign}{digits:0>2}")
        }
        None => s,
    }
}

fn cell_string(c: &Cell, fmt: FormatR) -> String {
    match c {
        Cell::Null => "-".to_string(),
        Cell::R(r) => fmt.format(*r),
        Cell::I(i) => i.to_string(),
        Cell::K(s) => s.clone(),
    }
}

/// The printed cells and the column widths shared by TABLEAU and ASTER: numbers are
/// right-aligned, texts, names and empty cells (`-`) left-aligned, columns at least as wide
/// as the real format.
struct Layout {
    header: Vec<String>,
    /// One entry per printed row (a row with only empty cells is not printed, as in
    /// Code_Aster).
    rows: Vec<Vec<String>>,
}

impl Layout {
    fn new(t: &Table, fmt: FormatR) -> Layout {
        let cells: Vec<Vec<String>> = t
            .rows
            .iter()
            .map(|r| r.iter().map(|c| cell_string(c, fmt)).collect())
            .collect();
        let widths: Vec<usize> = t
            .columns
            .iter()
            .enumerate()
            .map(|(j, c)| {
                let base = match c.kind {
                    ColKind::R | ColKind::I => fmt.width(),
                    ColKind::K => 0,
                };
                cells
                    .iter()
                    .filter_map(|r| r.get(j).map(|s| s.chars().count()))
                    .chain([c.name.chars().count(), base])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let header = t
            .columns
            .iter()
            .zip(&widths)
            .map(|(c, &w)| format!("{:<w$}", c.name))
            .collect();
        let rows = t
            .rows
            .iter()
            .zip(&cells)
            .filter(|(row, _)| !row.iter().all(Cell::is_null))
            .map(|(row, strs)| {
                row.iter()
                    .zip(strs)
                    .zip(&widths)
                    .map(|((c, s), &w)| match c {
                        Cell::R(_) | Cell::I(_) => format!("{s:>w$}"),
                        _ => format!("{s:<w$}"),
                    })
                    .collect()
            })
            .collect();
        Layout { header, rows }
    }
}

/// Code_Aster's header of a printed table: "#", a rule of 80 dashes, "#".
fn rule() -> String {
    format!("#\n#{}\n#\n", "-".repeat(80))
}

/// FORMAT='TABLEAU': the `#` header, one `#` line per title line, the parameter names,
/// the rows, a blank line.
pub fn tableau(t: &Table, title: &str, fmt: FormatR, sep: &str) -> String {
    let layout = Layout::new(t, fmt);
    let mut out = rule();
    for line in title.lines() {
        out.push('#');
        out.push_str(line);
        out.push('\n');
    }
    for line in std::iter::once(&layout.header).chain(&layout.rows) {
        out.push_str(line.join(sep).trim_end());
        out.push('\n');
    }
    // A blank line closes the table, so successive prints to one unit stay apart.
    out.push('\n');
    out
}

/// FORMAT='ASTER': the block Code_Aster's LIRE_TABLE reads back: the `#` header, then
/// `#DEBUT_TABLE`, one `#TITRE` line per title line, the parameter names, their types, the
/// rows and `#FIN_TABLE`; every line of the block after the markers starts with the
/// separator. The store keeps a text column's kind, not its declared length, so its type is
/// written as the shortest of Code_Aster's K8, K16, K24, K32, K80 that holds its longest
/// text.
pub fn aster(t: &Table, title: &str, fmt: FormatR, sep: &str) -> String {
    let layout = Layout::new(t, fmt);
    let types: Vec<String> = t
        .columns
        .iter()
        .enumerate()
        .zip(&layout.header)
        .map(|((j, c), h)| {
            let name = match c.kind {
                ColKind::R => "R".to_string(),
                ColKind::I => "I".to_string(),
                ColKind::K => text_type(t, j).to_string(),
            };
            format!("{name:<w$}", w = h.chars().count())
        })
        .collect();
    let mut out = rule();
    out.push_str("#DEBUT_TABLE\n");
    for line in title.lines() {
        out.push_str("#TITRE ");
        out.push_str(line);
        out.push('\n');
    }
    let lines = [&layout.header, &types].into_iter().chain(&layout.rows);
    for line in lines {
        out.push_str(sep);
        out.push_str(line.join(sep).trim_end());
        out.push('\n');
    }
    out.push_str("#FIN_TABLE\n\n");
    out
}

/// The shortest Code_Aster text type (K8 … K80) that holds column `j`'s longest text.
fn text_type(t: &Table, j: usize) -> &'static str {
    let longest = t
        .rows
        .iter()
        .filter_map(|r| r.get(j).and_then(Cell::as_text))
        .map(|s| s.chars().count())
        .max()
        .unwrap_or(0);
    match longest {
        0..=8 => "K8",
        9..=16 => "K16",
        17..=24 => "K24",
        25..=32 => "K32",
        _ => "K80",
    }
}

/// FORMAT='CSV': a header line of parameter names, then one line per row; no padding,
/// empty cells are empty fields, texts holding the separator or a quote are quoted.
pub fn csv(t: &Table, fmt: FormatR, sep: &str) -> String {
    let quote = |s: &str| {
        if (!sep.is_empty() && s.contains(sep)) || s.contains('"') || s.contains('\n') {
            format!("\"{}\"", s.replace('"', "\"\""))
        } else {
            s.to_string()
        }
    };
    let mut out = String::new();
    let names: Vec<String> = t.columns.iter().map(|c| quote(&c.name)).collect();
    out.push_str(&names.join(sep));
    out.push('\n');
    for row in &t.rows {
        let line: Vec<String> = row
            .iter()
            .map(|c| match c {
                Cell::Null => String::new(),
                Cell::K(s) => quote(s),
                other => cell_string(other, fmt).trim().to_string(),
            })
            .collect();
        out.push_str(&line.join(sep));
        out.push('\n');
    }
    out
}

/// FORMAT='XMGRACE': a two-column table as a Grace project file (xmgrace reads it): the
/// first column against the second, one xy set, rows with an empty cell left out as
/// Code_Aster does. Both columns must be numbers.
pub fn grace(t: &Table, title: &str, fmt: FormatR) -> Result<String> {
    let [x, y] = t.columns.as_slice() else {
        return Err(Error::validation(format!(
            "FORMAT='XMGRACE' draws two columns, the table has {}",
            t.columns.len()
        ))
        .keyword("NOM_PARA"));
    };
    for c in [x, y] {
        if c.kind == ColKind::K {
            return Err(Error::validation(format!(
                "FORMAT='XMGRACE' draws numbers; column {} holds texts",
                c.name
            ))
            .keyword("NOM_PARA"));
        }
    }
    let quoted = |s: &str| s.replace('"', "'");
    let mut out = String::from("# Grace project file (aster-nl, IMPR_TABLE)\n@version 50122\n");
    out.push_str(&format!(
        "@title \"{}\"\n@xaxis label \"{}\"\n@yaxis label \"{}\"\n",
        quoted(title.lines().next().unwrap_or("")),
        quoted(&x.name),
        quoted(&y.name)
    ));
    out.push_str(&format!(
        "@target G0.S0\n@type xy\n@s0 legend \"{}\"\n",
        quoted(&y.name)
    ));
    for row in &t.rows {
        if let (Some(a), Some(b)) = (row[0].as_f64(), row[1].as_f64()) {
            out.push_str(&format!("{} {}\n", fmt.format(a), fmt.format(b)));
        }
    }
    out.push_str("&\n");
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::tests::sample;

    #[test]
    fn e_format_matches_c_printf() {
        // Expected strings are what C's printf("%12.5E") prints for these values.
        let f = FormatR::default();
        assert_eq!(f.format(12.5), " 1.25000E+01");
        assert_eq!(f.format(-40.0), "-4.00000E+01");
        assert_eq!(f.format(0.0), " 0.00000E+00");
        assert_eq!(f.format(1.5e-7), " 1.50000E-07");
        assert_eq!(f.format(2.0e100), "2.00000E+100");
        assert_eq!(FormatR::parse("F8.3").unwrap().format(1.23456), "   1.235");
        assert!(FormatR::parse("X12.5").is_err());
        assert!(FormatR::parse("E12").is_err());
    }

    #[test]
    fn tableau_aligns_columns() {
        let mut t = sample();
        // An all-empty row is not printed.
        t.rows.push(vec![Cell::Null, Cell::Null, Cell::Null]);
        let s = tableau(&t, "modes\nsecond line", FormatR::default(), " ");
        let expected = concat!(
            "#\n#--------------------------------------------------------------------------------\n#\n",
            "#modes\n#second line\n",
            "NUME_ORDRE   FREQ         NOM_SD\n",
            "           1  1.25000E+01 M1\n",
            "           2 -4.00000E+01 M2\n",
            "           3  2.50000E+01 -\n",
            "\n",
        );
        assert_eq!(s, expected);
    }

    #[test]
    fn csv_uses_the_separator() {
        let mut t = sample();
        t.rows[2][2] = Cell::K("a;b".into());
        let s = csv(&t, FormatR::parse("E10.3").unwrap(), ";");
        assert_eq!(
            s,
            "NUME_ORDRE;FREQ;NOM_SD\n1;1.250E+01;M1\n2;-4.000E+01;M2\n3;2.500E+01;\"a;b\"\n"
        );
    }
}
