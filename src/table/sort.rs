//! TRI: stable sort on one or several parameters (Code_Aster ORDRE CROISSANT/DECROISSANT).
//!
//! Empty cells come first in increasing order (last in decreasing order), as Python 2's
//! `None` did in Code_Aster's tables. Rows that compare equal keep their order.

use super::filter::order;
use super::{Cell, Table};
use crate::error::{Error, Result};
use std::cmp::Ordering;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ordre {
    Croissant,
    Decroissant,
}

impl Ordre {
    pub fn parse(s: &str) -> Option<Ordre> {
        match s {
            "CROISSANT" => Some(Ordre::Croissant),
            "DECROISSANT" => Some(Ordre::Decroissant),
            _ => None,
        }
    }
}

fn cmp_cells(a: &Cell, b: &Cell) -> Ordering {
    match (a.is_null(), b.is_null()) {
        (true, true) => Ordering::Equal,
        (true, false) => Ordering::Less,
        (false, true) => Ordering::Greater,
        // NaN (the only incomparable case in a typed column) sorts as equal: stable.
        (false, false) => order(a, b).unwrap_or(Ordering::Equal),
    }
}

/// Sort the rows of `t` on the parameters `keys` (first key first).
pub fn sort(t: &mut Table, keys: &[String], ordre: Ordre) -> Result<()> {
    if keys.is_empty() {
        return Err(Error::validation("TRI needs at least one parameter").keyword("TRI/NOM_PARA"));
    }
    let idx = keys
        .iter()
        .map(|k| t.req_col(k).map_err(|e| e.keyword("TRI/NOM_PARA")))
        .collect::<Result<Vec<_>>>()?;
    t.rows.sort_by(|a, b| {
        let mut o = Ordering::Equal;
        for &j in &idx {
            o = match (a.get(j), b.get(j)) {
                (Some(x), Some(y)) => cmp_cells(x, y),
                _ => Ordering::Equal,
            };
            if o != Ordering::Equal {
                break;
            }
        }
        match ordre {
            Ordre::Croissant => o,
            Ordre::Decroissant => o.reverse(),
        }
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::ColKind;

    fn table() -> Table {
        let mut t = Table::new("");
        t.add_column("A", ColKind::I).unwrap();
        t.add_column("B", ColKind::R).unwrap();
        t.add_column("TAG", ColKind::K).unwrap();
        for (a, b, tag) in [
            (2, 1.0, "p"),
            (1, 5.0, "q"),
            (2, 0.5, "r"),
            (1, 5.0, "s"),
            (0, f64::NAN, "t"),
        ] {
            let b = if b.is_nan() { Cell::Null } else { Cell::R(b) };
            t.push_row(vec![Cell::I(a), b, Cell::K(tag.into())])
                .unwrap();
        }
        t
    }

    fn tags(t: &Table) -> String {
        t.rows
            .iter()
            .filter_map(|r| r.get(2).and_then(|c| c.as_text()))
            .collect()
    }

    #[test]
    fn sorts_on_several_keys_stably() {
        let mut t = table();
        sort(&mut t, &["A".into(), "B".into()], Ordre::Croissant).unwrap();
        // q and s tie on (1, 5.0): they keep their order.
        assert_eq!(tags(&t), "tqsrp");
        let mut t = table();
        sort(&mut t, &["B".into()], Ordre::Decroissant).unwrap();
        // Empty B (t) last in decreasing order; ties q, s kept in order.
        assert_eq!(tags(&t), "qsprt");
        let mut t = table();
        sort(&mut t, &["TAG".into()], Ordre::Decroissant).unwrap();
        assert_eq!(tags(&t), "tsrqp");
    }

    #[test]
    fn unknown_key_is_an_error() {
        let mut t = table();
        let err = sort(&mut t, &["Z".into()], Ordre::Croissant).unwrap_err();
        assert_eq!(err.keyword.as_deref(), Some("TRI/NOM_PARA"));
    }
}
