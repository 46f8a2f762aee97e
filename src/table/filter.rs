//! Row selection with Code_Aster's CRIT_COMP (FILTRE of IMPR_TABLE, CALC_TABLE, TEST_TABLE...).
//!
//! Semantics (those of Code_Aster's table filters):
//! - `EQ`/`NE` on reals compare with a tolerance: CRITERE `RELATIF` keeps
//!   `|x - v| <= PRECISION * |v|` (so a reference 0 means exact equality), `ABSOLU` keeps
//!   `|x - v| <= PRECISION`. Integers compare exactly, texts after trimming blanks. With
//!   several values, `EQ` keeps a row equal to any of them, `NE` one equal to none of them.
//! - `GT`, `LT`, `GE`, `LE` compare numbers, or texts in lexicographic order; with several
//!   values `GT`/`GE` compare with the smallest, `LT`/`LE` with the largest.
//! - `VIDE` keeps empty cells, `NON_VIDE` the others.
//! - `MAXI`, `MINI`, `MAXI_ABS`, `MINI_ABS` keep the rows holding the extreme value of the
//!   column (all of them when tied). `ABS_MAXI`/`ABS_MINI` are accepted as aliases.
//!
//! Empty cells satisfy only `VIDE` and `NE` (an empty cell differs from any value, as in
//! Code_Aster's tables).

use super::{Cell, ColKind, Table};
use crate::error::{Error, Result};
use std::cmp::Ordering;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CritComp {
    Eq,
    Ne,
    Gt,
    Lt,
    Ge,
    Le,
    Vide,
    NonVide,
    Maxi,
    Mini,
    AbsMaxi,
    AbsMini,
}

impl CritComp {
    pub fn parse(s: &str) -> Option<CritComp> {
        Some(match s {
            "EQ" => CritComp::Eq,
            "NE" => CritComp::Ne,
            "GT" => CritComp::Gt,
            "LT" => CritComp::Lt,
            "GE" => CritComp::Ge,
            "LE" => CritComp::Le,
            "VIDE" => CritComp::Vide,
            "NON_VIDE" => CritComp::NonVide,
            "MAXI" => CritComp::Maxi,
            "MINI" => CritComp::Mini,
            "MAXI_ABS" | "ABS_MAXI" => CritComp::AbsMaxi,
            "MINI_ABS" | "ABS_MINI" => CritComp::AbsMini,
            _ => return None,
        })
    }
    pub const NAMES: &'static [&'static str] = &[
        "EQ", "NE", "GT", "LT", "GE", "LE", "VIDE", "NON_VIDE", "MAXI", "MINI", "MAXI_ABS",
        "MINI_ABS",
    ];
    /// Whether the criterion compares with given values.
    pub fn needs_value(self) -> bool {
        matches!(
            self,
            CritComp::Eq | CritComp::Ne | CritComp::Gt | CritComp::Lt | CritComp::Ge | CritComp::Le
        )
    }
}

/// How two reals are compared (CRITERE).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Critere {
    Relatif,
    Absolu,
}

impl Critere {
    pub fn parse(s: &str) -> Option<Critere> {
        match s {
            "RELATIF" => Some(Critere::Relatif),
            "ABSOLU" => Some(Critere::Absolu),
            _ => None,
        }
    }
}

/// Code_Aster's default PRECISION for real comparisons in filters.
pub const DEFAULT_PRECISION: f64 = 1.0e-3;

/// One FILTRE occurrence.
#[derive(Clone, Debug, PartialEq)]
pub struct Filter {
    pub nom_para: String,
    pub crit: CritComp,
    /// VALE / VALE_I / VALE_K (several values allowed for EQ and NE).
    pub values: Vec<Cell>,
    pub critere: Critere,
    pub precision: f64,
}

impl Filter {
    /// An `EQ` filter with Code_Aster's defaults (RELATIF, 1e-3).
    pub fn eq(nom_para: &str, value: Cell) -> Filter {
        Filter::new(nom_para, CritComp::Eq, vec![value])
    }
    pub fn new(nom_para: &str, crit: CritComp, values: Vec<Cell>) -> Filter {
        Filter {
            nom_para: nom_para.to_string(),
            crit,
            values,
            critere: Critere::Relatif,
            precision: DEFAULT_PRECISION,
        }
    }

    /// Short text for messages and test headers: `NUME_ORDRE=1`, `FREQ>2.0`, ...
    pub fn describe(&self) -> String {
        let vals: Vec<String> = self.values.iter().map(|c| c.to_string()).collect();
        let op = match self.crit {
            CritComp::Eq => "=",
            CritComp::Ne => "!=",
            CritComp::Gt => ">",
            CritComp::Lt => "<",
            CritComp::Ge => ">=",
            CritComp::Le => "<=",
            CritComp::Vide => return format!("{} VIDE", self.nom_para),
            CritComp::NonVide => return format!("{} NON_VIDE", self.nom_para),
            CritComp::Maxi => return format!("{} MAXI", self.nom_para),
            CritComp::Mini => return format!("{} MINI", self.nom_para),
            CritComp::AbsMaxi => return format!("{} MAXI_ABS", self.nom_para),
            CritComp::AbsMini => return format!("{} MINI_ABS", self.nom_para),
        };
        format!("{}{}{}", self.nom_para, op, vals.join("|"))
    }

    /// The rows of `t` that pass this filter, in their order.
    pub fn apply(&self, t: &Table) -> Result<Table> {
        let j = t
            .req_col(&self.nom_para)
            .map_err(|e| e.keyword("FILTRE/NOM_PARA"))?;
        let kind = t.columns.get(j).map(|c| c.kind).unwrap_or(ColKind::K);
        self.check_values(kind)?;
        let cells: Vec<&Cell> = t
            .rows
            .iter()
            .map(|r| r.get(j).unwrap_or(&Cell::Null))
            .collect();
        let keep: Vec<usize> = match self.crit {
            CritComp::Vide => indices(&cells, |c| c.is_null()),
            CritComp::NonVide => indices(&cells, |c| !c.is_null()),
            CritComp::Maxi | CritComp::Mini | CritComp::AbsMaxi | CritComp::AbsMini => {
                self.extreme(&cells)
            }
            _ => {
                let bound = self.bound();
                indices(&cells, |c| self.compare(c, bound))
            }
        };
        Ok(t.with_rows(&keep))
    }

    fn check_values(&self, kind: ColKind) -> Result<()> {
        if !self.crit.needs_value() {
            return Ok(());
        }
        if self.values.is_empty() {
            return Err(Error::validation(format!(
                "CRIT_COMP on {} needs a value to compare with",
                self.nom_para
            ))
            .keyword("FILTRE/VALE")
            .hint("give VALE (reals), VALE_I (integers) or VALE_K (texts)"));
        }
        for v in &self.values {
            let ok = match kind {
                ColKind::K => matches!(v, Cell::K(_)),
                ColKind::R | ColKind::I => matches!(v, Cell::R(_) | Cell::I(_)),
            };
            if !ok {
                let (kw, what) = match kind {
                    ColKind::K => ("VALE_K", "texts"),
                    ColKind::I => ("VALE_I", "integers"),
                    ColKind::R => ("VALE", "reals"),
                };
                return Err(Error::validation(format!(
                    "parameter {} holds {what}: cannot compare it with {}",
                    self.nom_para, v
                ))
                .keyword("FILTRE")
                .hint(format!("use {kw}")));
            }
        }
        Ok(())
    }

    /// The value GT/GE (smallest) or LT/LE (largest) compare with.
    fn bound(&self) -> Option<&Cell> {
        let want = match self.crit {
            CritComp::Gt | CritComp::Ge => Ordering::Less,
            _ => Ordering::Greater,
        };
        self.values
            .iter()
            .reduce(|a, b| if order(b, a) == Some(want) { b } else { a })
    }

    /// Whether a cell passes a comparison criterion.
    fn compare(&self, c: &Cell, bound: Option<&Cell>) -> bool {
        let any_equal = || !c.is_null() && self.values.iter().any(|v| self.equal(c, v));
        let cmp = || match (c.is_null(), bound) {
            (false, Some(b)) => order(c, b),
            _ => None,
        };
        match self.crit {
            CritComp::Eq => any_equal(),
            CritComp::Ne => !any_equal(),
            CritComp::Gt => cmp() == Some(Ordering::Greater),
            CritComp::Lt => cmp() == Some(Ordering::Less),
            CritComp::Ge => matches!(cmp(), Some(Ordering::Greater | Ordering::Equal)),
            CritComp::Le => matches!(cmp(), Some(Ordering::Less | Ordering::Equal)),
            _ => false,
        }
    }

    fn equal(&self, c: &Cell, v: &Cell) -> bool {
        match (c, v) {
            (Cell::I(a), Cell::I(b)) => a == b,
            (Cell::K(a), Cell::K(b)) => a.trim() == b.trim(),
            _ => match (c.as_f64(), v.as_f64()) {
                (Some(x), Some(r)) => {
                    let tol = match self.critere {
                        Critere::Relatif => self.precision * r.abs(),
                        Critere::Absolu => self.precision,
                    };
                    (x - r).abs() <= tol
                }
                _ => false,
            },
        }
    }

    fn extreme(&self, cells: &[&Cell]) -> Vec<usize> {
        let key = |c: &Cell| -> Option<f64> {
            let x = c.as_f64()?;
            Some(match self.crit {
                CritComp::AbsMaxi | CritComp::AbsMini => x.abs(),
                _ => x,
            })
        };
        let want_max = matches!(self.crit, CritComp::Maxi | CritComp::AbsMaxi);
        // Texts: lexicographic extreme (MAXI/MINI only make sense that way).
        if cells.iter().any(|c| matches!(c, Cell::K(_))) {
            let best = cells.iter().filter_map(|c| c.as_text()).reduce(|a, b| {
                if (b > a) == want_max {
                    b
                } else {
                    a
                }
            });
            return indices(cells, |c| c.as_text().is_some() && c.as_text() == best);
        }
        let best = cells
            .iter()
            .filter_map(|c| key(c))
            .filter(|x| !x.is_nan())
            .reduce(|a, b| if want_max { a.max(b) } else { a.min(b) });
        match best {
            Some(b) => indices(cells, |c| key(c) == Some(b)),
            None => Vec::new(),
        }
    }
}

/// Apply filters in order (they combine as AND, as Code_Aster's repeated FILTRE).
pub fn apply_all(t: &Table, filters: &[Filter]) -> Result<Table> {
    let mut cur = t.clone();
    for f in filters {
        cur = f.apply(&cur)?;
    }
    Ok(cur)
}

fn indices(cells: &[&Cell], pred: impl Fn(&Cell) -> bool) -> Vec<usize> {
    cells
        .iter()
        .enumerate()
        .filter(|(_, c)| pred(c))
        .map(|(i, _)| i)
        .collect()
}

/// Order of two non-empty cells: numbers numerically, texts lexicographically.
pub(crate) fn order(a: &Cell, b: &Cell) -> Option<Ordering> {
    match (a, b) {
        (Cell::I(x), Cell::I(y)) => Some(x.cmp(y)),
        (Cell::K(x), Cell::K(y)) => Some(x.cmp(y)),
        _ => a.as_f64()?.partial_cmp(&b.as_f64()?),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::tests::sample;

    fn ordres(t: &Table) -> Vec<i64> {
        t.rows
            .iter()
            .filter_map(|r| match r.first() {
                Some(Cell::I(i)) => Some(*i),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn eq_on_reals_is_relative_by_default() {
        let t = sample();
        // 12.5 * (1 + 0.9e-3) is within RELATIF 1e-3 of 12.5; 12.5 * (1 + 1.1e-3) is not.
        let f = Filter::eq("FREQ", Cell::R(12.5 * (1.0 + 0.9e-3)));
        assert_eq!(ordres(&f.apply(&t).unwrap()), vec![1]);
        let f = Filter::eq("FREQ", Cell::R(12.5 * (1.0 + 1.1e-3)));
        assert!(f.apply(&t).unwrap().rows.is_empty());
        // ABSOLU 0.02 accepts a 0.015 gap.
        let mut f = Filter::eq("FREQ", Cell::R(12.515));
        f.critere = Critere::Absolu;
        f.precision = 0.02;
        assert_eq!(ordres(&f.apply(&t).unwrap()), vec![1]);
    }

    #[test]
    fn comparisons_and_emptiness() {
        let t = sample();
        let run =
            |crit, v: Vec<Cell>, para: &str| ordres(&Filter::new(para, crit, v).apply(&t).unwrap());
        assert_eq!(run(CritComp::Gt, vec![Cell::R(12.5)], "FREQ"), vec![3]);
        assert_eq!(run(CritComp::Ge, vec![Cell::R(12.5)], "FREQ"), vec![1, 3]);
        assert_eq!(run(CritComp::Lt, vec![Cell::I(2)], "NUME_ORDRE"), vec![1]);
        assert_eq!(
            run(CritComp::Le, vec![Cell::I(2)], "NUME_ORDRE"),
            vec![1, 2]
        );
        assert_eq!(
            run(CritComp::Ne, vec![Cell::I(2)], "NUME_ORDRE"),
            vec![1, 3]
        );
        assert_eq!(
            run(CritComp::Eq, vec![Cell::I(1), Cell::I(3)], "NUME_ORDRE"),
            vec![1, 3]
        );
        // An empty cell differs from any value.
        assert_eq!(
            run(CritComp::Ne, vec![Cell::K("M1".into())], "NOM_SD"),
            vec![2, 3]
        );
        // Several values: GT compares with the smallest, LE with the largest.
        assert_eq!(
            run(CritComp::Gt, vec![Cell::R(20.0), Cell::R(0.0)], "FREQ"),
            vec![1, 3]
        );
        assert_eq!(
            run(CritComp::Le, vec![Cell::R(20.0), Cell::R(0.0)], "FREQ"),
            vec![1, 2]
        );
        assert_eq!(
            run(CritComp::Eq, vec![Cell::K(" M2 ".into())], "NOM_SD"),
            vec![2]
        );
        assert_eq!(run(CritComp::Vide, vec![], "NOM_SD"), vec![3]);
        assert_eq!(run(CritComp::NonVide, vec![], "NOM_SD"), vec![1, 2]);
        assert_eq!(
            run(CritComp::Eq, vec![Cell::K("M2".into())], "NOM_SD"),
            vec![2]
        );
    }

    #[test]
    fn extremes() {
        let t = sample();
        let run = |crit| ordres(&Filter::new("FREQ", crit, vec![]).apply(&t).unwrap());
        assert_eq!(run(CritComp::Maxi), vec![3]);
        assert_eq!(run(CritComp::Mini), vec![2]);
        assert_eq!(run(CritComp::AbsMaxi), vec![2]);
        assert_eq!(run(CritComp::AbsMini), vec![1]);
    }

    use proptest::prelude::*;

    proptest! {
        /// EQ and NE split a table in two: every row is in exactly one of them, empty
        /// cells included (they go to NE), whatever the value and the precision.
        #[test]
        fn eq_and_ne_partition_the_rows(
            xs in prop::collection::vec(prop::option::of(-10.0f64..10.0), 0..20),
            v in -10.0f64..10.0,
            precision in 0.0f64..0.5,
            absolu in any::<bool>(),
        ) {
            let mut t = Table::new("");
            t.add_column("X", ColKind::R).unwrap();
            for x in &xs {
                t.push_row(vec![x.map(Cell::R).unwrap_or(Cell::Null)]).unwrap();
            }
            let mut f = Filter::eq("X", Cell::R(v));
            f.precision = precision;
            f.critere = if absolu { Critere::Absolu } else { Critere::Relatif };
            let eq = f.apply(&t).unwrap().nrows();
            f.crit = CritComp::Ne;
            let ne = f.apply(&t).unwrap().nrows();
            prop_assert_eq!(eq + ne, xs.len());
        }
    }

    #[test]
    fn wrong_value_type_is_a_clear_error() {
        let t = sample();
        let err = Filter::eq("NOM_SD", Cell::R(1.0)).apply(&t).unwrap_err();
        assert!(err.message.contains("NOM_SD holds texts"), "{err}");
        assert_eq!(err.hint.as_deref(), Some("use VALE_K"));
        let err = Filter::eq("NOPE", Cell::R(1.0)).apply(&t).unwrap_err();
        assert!(err.message.contains("no parameter NOPE"), "{err}");
    }
}
