//! In-memory tables, the Code_Aster way (`table_sdaster`, `table_container`).
//!
//! A [`Table`] is a title, typed columns (parameters such as `NUME_ORDRE`, `FREQ`) and rows
//! of [`Cell`]s. A `K` cell may name another concept (a sub-table, a set of mode shapes...):
//! that is how a table carries per-row objects. The operations are split by job:
//! [`filter`] (CRIT_COMP), [`sort`] (TRI), [`print`] (TABLEAU / CSV). No SQL here: the
//! persistence lives in `store::table`.

pub mod aggregate;
pub mod cross;
pub mod filter;
pub mod print;
pub mod sort;

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// Type of a column, as Code_Aster's table parameters: real, integer, text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum ColKind {
    R,
    I,
    K,
}

impl ColKind {
    pub fn name(self) -> &'static str {
        match self {
            ColKind::R => "R",
            ColKind::I => "I",
            ColKind::K => "K",
        }
    }
    pub fn parse(s: &str) -> Option<ColKind> {
        match s {
            "R" => Some(ColKind::R),
            "I" => Some(ColKind::I),
            "K" => Some(ColKind::K),
            _ => None,
        }
    }
    /// Words for messages.
    fn describe(self) -> &'static str {
        match self {
            ColKind::R => "reals",
            ColKind::I => "integers",
            ColKind::K => "texts",
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Column {
    pub name: String,
    pub kind: ColKind,
}

/// One cell. `Null` is Code_Aster's empty cell (printed `-`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Cell {
    Null,
    R(f64),
    I(i64),
    K(String),
}

impl Cell {
    /// Numeric value of an `R` or `I` cell.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Cell::R(r) => Some(*r),
            Cell::I(i) => Some(*i as f64),
            _ => None,
        }
    }
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Cell::K(s) => Some(s),
            _ => None,
        }
    }
    pub fn is_null(&self) -> bool {
        matches!(self, Cell::Null)
    }
    /// Whether the cell may live in a column of kind `kind`.
    pub fn fits(&self, kind: ColKind) -> bool {
        matches!(
            (self, kind),
            (Cell::Null, _)
                | (Cell::R(_), ColKind::R)
                | (Cell::I(_), ColKind::I)
                | (Cell::K(_), ColKind::K)
        )
    }
}

/// For messages: `-` (empty), `12.5`, `3`, `'M1'`.
impl std::fmt::Display for Cell {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Cell::Null => write!(f, "-"),
            Cell::R(r) => write!(f, "{r}"),
            Cell::I(i) => write!(f, "{i}"),
            Cell::K(s) => write!(f, "'{s}'"),
        }
    }
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Table {
    pub title: String,
    pub columns: Vec<Column>,
    /// Each row has exactly one cell per column.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    pub fn new(title: impl Into<String>) -> Table {
        Table {
            title: title.into(),
            ..Table::default()
        }
    }

    pub fn nrows(&self) -> usize {
        self.rows.len()
    }

    /// Column names, in order.
    pub fn names(&self) -> Vec<&str> {
        self.columns.iter().map(|c| c.name.as_str()).collect()
    }

    /// Position of the column `name`.
    pub fn col(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c.name == name)
    }

    pub fn column(&self, name: &str) -> Option<&Column> {
        self.columns.iter().find(|c| c.name == name)
    }

    /// Position of the column `name`, or an error listing the parameters the table has.
    pub fn req_col(&self, name: &str) -> Result<usize> {
        self.col(name).ok_or_else(|| {
            Error::input(format!("the table has no parameter {name}")).hint(format!(
                "its parameters are: {}",
                if self.columns.is_empty() {
                    "(none)".to_string()
                } else {
                    self.names().join(", ")
                }
            ))
        })
    }

    /// Add a column; rows already present get empty cells.
    pub fn add_column(&mut self, name: &str, kind: ColKind) -> Result<usize> {
        if self.col(name).is_some() {
            return Err(Error::input(format!(
                "the table already has a parameter {name}"
            )));
        }
        self.columns.push(Column {
            name: name.to_string(),
            kind,
        });
        for r in &mut self.rows {
            r.push(Cell::Null);
        }
        Ok(self.columns.len() - 1)
    }

    /// Append a row; its length and the kinds of its cells must match the columns.
    pub fn push_row(&mut self, row: Vec<Cell>) -> Result<()> {
        if row.len() != self.columns.len() {
            return Err(Error::internal(format!(
                "a row of {} cells given to a table of {} columns",
                row.len(),
                self.columns.len()
            )));
        }
        for (c, col) in row.iter().zip(&self.columns) {
            if !c.fits(col.kind) {
                return Err(Error::input(format!(
                    "parameter {} holds {}, got {}",
                    col.name,
                    col.kind.describe(),
                    c
                )));
            }
        }
        self.rows.push(row);
        Ok(())
    }

    /// Build a table from whole columns (CREA_TABLE): shorter columns are completed with
    /// empty cells, as Code_Aster does.
    pub fn from_columns(title: &str, cols: Vec<(Column, Vec<Cell>)>) -> Result<Table> {
        let mut t = Table::new(title);
        let n = cols.iter().map(|(_, v)| v.len()).max().unwrap_or(0);
        let mut data = Vec::with_capacity(cols.len());
        for (col, cells) in cols {
            t.add_column(&col.name, col.kind)?;
            data.push(cells);
        }
        for i in 0..n {
            let row = data
                .iter()
                .map(|cells| cells.get(i).cloned().unwrap_or(Cell::Null))
                .collect();
            t.push_row(row)?;
        }
        Ok(t)
    }

    /// The cell of parameter `name` in row `row`.
    pub fn cell(&self, row: usize, name: &str) -> Option<&Cell> {
        let j = self.col(name)?;
        self.rows.get(row)?.get(j)
    }

    /// All cells of parameter `name`, in row order.
    pub fn column_cells(&self, name: &str) -> Result<Vec<&Cell>> {
        let j = self.req_col(name)?;
        Ok(self.rows.iter().filter_map(|r| r.get(j)).collect())
    }

    /// Keep only the given parameters, in the given order (CALC_TABLE EXTR, NOM_PARA of
    /// IMPR_TABLE).
    pub fn extract(&self, names: &[String]) -> Result<Table> {
        let idx = names
            .iter()
            .map(|n| self.req_col(n))
            .collect::<Result<Vec<_>>>()?;
        let mut seen = std::collections::HashSet::new();
        for n in names {
            if !seen.insert(n) {
                return Err(Error::input(format!("parameter {n} is asked twice")));
            }
        }
        let columns = idx
            .iter()
            .filter_map(|&j| self.columns.get(j).cloned())
            .collect();
        let rows = self
            .rows
            .iter()
            .map(|r| idx.iter().filter_map(|&j| r.get(j).cloned()).collect())
            .collect();
        Ok(Table {
            title: self.title.clone(),
            columns,
            rows,
        })
    }

    /// Rename a parameter (CALC_TABLE RENOMME).
    pub fn rename(&mut self, old: &str, new: &str) -> Result<()> {
        let j = self.req_col(old)?;
        if old != new && self.col(new).is_some() {
            return Err(Error::input(format!(
                "cannot rename {old} to {new}: the table already has a parameter {new}"
            )));
        }
        if let Some(c) = self.columns.get_mut(j) {
            c.name = new.to_string();
        }
        Ok(())
    }

    /// Keep the rows whose index is in `keep` (in that order).
    pub(crate) fn with_rows(&self, keep: &[usize]) -> Table {
        Table {
            title: self.title.clone(),
            columns: self.columns.clone(),
            rows: keep
                .iter()
                .filter_map(|&i| self.rows.get(i).cloned())
                .collect(),
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Three modes: NUME_ORDRE, FREQ, NOM_SD (a K column naming per-row objects).
    pub fn sample() -> Table {
        let mut t = Table::new("modes");
        t.add_column("NUME_ORDRE", ColKind::I).unwrap();
        t.add_column("FREQ", ColKind::R).unwrap();
        t.add_column("NOM_SD", ColKind::K).unwrap();
        t.push_row(vec![Cell::I(1), Cell::R(12.5), Cell::K("M1".into())])
            .unwrap();
        t.push_row(vec![Cell::I(2), Cell::R(-40.0), Cell::K("M2".into())])
            .unwrap();
        t.push_row(vec![Cell::I(3), Cell::R(25.0), Cell::Null])
            .unwrap();
        t
    }

    #[test]
    fn push_row_checks_kinds() {
        let mut t = sample();
        let err = t
            .push_row(vec![Cell::R(1.0), Cell::R(1.0), Cell::Null])
            .unwrap_err();
        assert!(err.message.contains("NUME_ORDRE holds integers"), "{err}");
    }

    #[test]
    fn from_columns_pads_with_empty_cells() {
        let t = Table::from_columns(
            "",
            vec![
                (
                    Column {
                        name: "A".into(),
                        kind: ColKind::I,
                    },
                    vec![Cell::I(1), Cell::I(2)],
                ),
                (
                    Column {
                        name: "B".into(),
                        kind: ColKind::R,
                    },
                    vec![Cell::R(0.5)],
                ),
            ],
        )
        .unwrap();
        assert_eq!(
            t.rows,
            vec![vec![Cell::I(1), Cell::R(0.5)], vec![Cell::I(2), Cell::Null]]
        );
    }

    #[test]
    fn extract_and_rename() {
        let mut t = sample();
        let e = t.extract(&["FREQ".into(), "NUME_ORDRE".into()]).unwrap();
        assert_eq!(e.names(), vec!["FREQ", "NUME_ORDRE"]);
        assert_eq!(e.rows[1], vec![Cell::R(-40.0), Cell::I(2)]);
        let err = t.extract(&["NOPE".into()]).unwrap_err();
        assert!(err.hint.unwrap().contains("NUME_ORDRE, FREQ, NOM_SD"));
        t.rename("FREQ", "FREQ_HZ").unwrap();
        assert_eq!(t.cell(0, "FREQ_HZ"), Some(&Cell::R(12.5)));
        assert!(t.rename("FREQ_HZ", "NOM_SD").is_err());
    }
}
