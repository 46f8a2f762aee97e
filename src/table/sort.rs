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

    use proptest::prelude::*;

    proptest! {
        /// Sorting gives a permutation of the rows, ordered on the key, and rows with equal
        /// keys keep their original order (checked through a row id column).
        #[test]
        fn sort_is_an_ordered_stable_permutation(
            keys in prop::collection::vec(prop::option::of(-3i64..3), 0..30),
            down in any::<bool>(),
        ) {
            let mut t = Table::new("");
            t.add_column("K", ColKind::I).unwrap();
            t.add_column("ID", ColKind::I).unwrap();
            for (id, k) in keys.iter().enumerate() {
                let c = k.map(Cell::I).unwrap_or(Cell::Null);
                t.push_row(vec![c, Cell::I(id as i64)]).unwrap();
            }
            let ordre = if down { Ordre::Decroissant } else { Ordre::Croissant };
            sort(&mut t, &["K".into()], ordre).unwrap();
            let mut ids: Vec<i64> = t.rows.iter().map(|r| match r[1] { Cell::I(i) => i, _ => -1 }).collect();
            for w in t.rows.windows(2) {
                let o = cmp_cells(&w[0][0], &w[1][0]);
                let o = if down { o.reverse() } else { o };
                prop_assert!(o != Ordering::Greater);
                if o == Ordering::Equal {
                    prop_assert!(w[0][1].as_f64() < w[1][1].as_f64());
                }
            }
            ids.sort();
            prop_assert_eq!(ids, (0..keys.len() as i64).collect::<Vec<_>>());
        }
    }

    #[test]
    fn unknown_key_is_an_error() {
        let mut t = table();
        let err = sort(&mut t, &["Z".into()], Ordre::Croissant).unwrap_err();
        assert_eq!(err.keyword.as_deref(), Some("TRI/NOM_PARA"));
    }
}
