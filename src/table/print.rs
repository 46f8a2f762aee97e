//! Printing tables as Code_Aster does: FORMAT='TABLEAU' (title lines starting with `#`,
//! aligned columns) and FORMAT='CSV'. Reals follow FORMAT_R (`E12.5` by default, i.e. C's
//! `%12.5E` with a two-digit exponent at least).

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

/// FORMAT='TABLEAU': the `#` header, one `#` line per title line, the parameter names,
/// the rows, a blank line. Numbers are right-aligned, texts, names and empty cells (`-`)
/// left-aligned, columns at least as wide as the real format.
pub fn tableau(t: &Table, title: &str, fmt: FormatR, sep: &str) -> String {
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
    // Code_Aster's header: "#", a rule of 80 dashes, "#", then the title lines.
    let mut out = format!("#\n#{}\n#\n", "-".repeat(80));
    for line in title.lines() {
        out.push('#');
        out.push_str(line);
        out.push('\n');
    }
    let header: Vec<String> = t
        .columns
        .iter()
        .zip(&widths)
        .map(|(c, &w)| format!("{:<w$}", c.name))
        .collect();
    out.push_str(header.join(sep).trim_end());
    out.push('\n');
    for (row, strs) in t.rows.iter().zip(&cells) {
        // Like Code_Aster, a row with only empty cells is not printed.
        if row.iter().all(Cell::is_null) {
            continue;
        }
        let line: Vec<String> = row
            .iter()
            .zip(strs)
            .zip(&widths)
            .map(|((c, s), &w)| match c {
                Cell::R(_) | Cell::I(_) => format!("{s:>w$}"),
                _ => format!("{s:<w$}"),
            })
            .collect();
        out.push_str(line.join(sep).trim_end());
        out.push('\n');
    }
    // A blank line closes the table, so successive prints to one unit stay apart.
    out.push('\n');
    out
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
