//! TABLEAU_CROISE: a table of three parameters (P1, P2, P3) turned into the cross table
//! P3(P2, P1), as Code_Aster's IMPR_TABLE prints it: one row per distinct value of P2 (in
//! increasing order), one column per distinct value of P1 (in increasing order, named by
//! that value), the cell holding P3 of the row with these two values (the last such row
//! when several have them). The first column is named `P2/P1`.

use super::print::FormatR;
use super::{Cell, Column, Table};
use std::cmp::Ordering;

/// The cross table, or `None` when the table does not have exactly three columns.
/// `fmt` names the columns made from real values (as they would be printed).
pub fn cross(t: &Table, fmt: FormatR) -> Option<Table> {
    let [p1, p2, p3] = t.columns.as_slice() else {
        return None;
    };
    let distinct = |j: usize| {
        let mut v: Vec<&Cell> = t
            .rows
            .iter()
            .map(|r| &r[j])
            .filter(|c| !c.is_null())
            .collect();
        v.sort_by(|a, b| order(a, b));
        v.dedup_by(|a, b| order(a, b) == Ordering::Equal);
        v
    };
    let ys = distinct(0);
    let xs = distinct(1);
    let mut columns = vec![Column {
        name: format!("{}/{}", p2.name, p1.name),
        kind: p2.kind,
    }];
    columns.extend(ys.iter().map(|y| Column {
        name: label(y, fmt),
        kind: p3.kind,
    }));
    let rows = xs
        .iter()
        .map(|&x| {
            let mut row = vec![x.clone()];
            row.extend(ys.iter().map(|&y| {
                t.rows
                    .iter()
                    .rev()
                    .find(|r| order(&r[1], x).is_eq() && order(&r[0], y).is_eq())
                    .map_or(Cell::Null, |r| r[2].clone())
            }));
            row
        })
        .collect();
    let mut title = t.title.clone();
    if !title.is_empty() {
        title.push('\n');
    }
    title.push_str(&format!(
        "{} FONCTION DE {} ET {}",
        p3.name, p2.name, p1.name
    ));
    Some(Table {
        title,
        columns,
        rows,
    })
}

/// Order of two cells of one column (one kind, nulls apart).
fn order(a: &Cell, b: &Cell) -> Ordering {
    match (a, b) {
        (Cell::R(x), Cell::R(y)) => x.total_cmp(y),
        (Cell::I(x), Cell::I(y)) => x.cmp(y),
        (Cell::K(x), Cell::K(y)) => x.cmp(y),
        (Cell::Null, Cell::Null) => Ordering::Equal,
        (Cell::Null, _) => Ordering::Less,
        (_, Cell::Null) => Ordering::Greater,
        // Kinds never mix in one column; order them by kind for a total order.
        _ => rank(a).cmp(&rank(b)),
    }
}

fn rank(c: &Cell) -> u8 {
    match c {
        Cell::Null => 0,
        Cell::I(_) => 1,
        Cell::R(_) => 2,
        Cell::K(_) => 3,
    }
}

/// A column name made from a value.
fn label(c: &Cell, fmt: FormatR) -> String {
    match c {
        Cell::R(r) => fmt.format(*r).trim().to_string(),
        Cell::I(i) => i.to_string(),
        Cell::K(s) => s.clone(),
        Cell::Null => "-".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::ColKind;

    fn col(name: &str, kind: ColKind) -> Column {
        Column {
            name: name.into(),
            kind,
        }
    }

    #[test]
    fn cross_table_of_three_parameters() {
        // P3 = 10·P1 + P2 on a grid given out of order, one cell missing, one repeated.
        let mut t = Table::new("grid");
        t.columns = vec![
            col("NOEUD", ColKind::K),
            col("INST", ColKind::R),
            col("DX", ColKind::R),
        ];
        let row = |n: &str, i: f64, v: f64| vec![Cell::K(n.into()), Cell::R(i), Cell::R(v)];
        t.rows = vec![
            row("N2", 1.0, 21.0),
            row("N1", 0.5, 0.0),
            row("N1", 0.5, 10.5),
            row("N1", 1.0, 11.0),
            vec![Cell::Null, Cell::R(2.0), Cell::R(9.0)],
        ];
        let c = cross(&t, FormatR::default()).unwrap();
        assert_eq!(c.title, "grid\nDX FONCTION DE INST ET NOEUD");
        assert_eq!(c.names(), ["INST/NOEUD", "N1", "N2"]);
        assert_eq!(c.columns[0].kind, ColKind::R);
        assert_eq!(
            c.rows,
            vec![
                vec![Cell::R(0.5), Cell::R(10.5), Cell::Null],
                vec![Cell::R(1.0), Cell::R(11.0), Cell::R(21.0)],
                vec![Cell::R(2.0), Cell::Null, Cell::Null],
            ]
        );
        t.columns.pop();
        for r in &mut t.rows {
            r.pop();
        }
        assert!(cross(&t, FormatR::default()).is_none());
    }
}
