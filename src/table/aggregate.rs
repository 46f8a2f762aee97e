//! Column aggregates (TEST_TABLE TYPE_TEST): SOMM_ABS, SOMM, MAX, MIN over the non-empty
//! cells of a numeric column. An integer column gives an integer, a real column a real.

use super::{Cell, ColKind, Table};
use crate::error::{Error, Result};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Aggregate {
    SommAbs,
    Somm,
    Max,
    Min,
}

impl Aggregate {
    pub fn parse(s: &str) -> Option<Aggregate> {
        match s {
            "SOMM_ABS" => Some(Aggregate::SommAbs),
            "SOMM" => Some(Aggregate::Somm),
            "MAX" => Some(Aggregate::Max),
            "MIN" => Some(Aggregate::Min),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Aggregate::SommAbs => "SOMM_ABS",
            Aggregate::Somm => "SOMM",
            Aggregate::Max => "MAX",
            Aggregate::Min => "MIN",
        }
    }
}

/// The aggregate of parameter `para` (sums of no value are 0; MAX/MIN need a value).
pub fn aggregate(t: &Table, para: &str, agg: Aggregate) -> Result<Cell> {
    let j = t.req_col(para)?;
    let kind = t.columns.get(j).map(|c| c.kind).unwrap_or(ColKind::K);
    let cells: Vec<&Cell> = t
        .rows
        .iter()
        .filter_map(|r| r.get(j))
        .filter(|c| !c.is_null())
        .collect();
    if kind == ColKind::K {
        return Err(Error::input(format!(
            "{} needs numbers, {para} holds texts",
            agg.name()
        )));
    }
    if cells.is_empty() && matches!(agg, Aggregate::Max | Aggregate::Min) {
        return Err(Error::input(format!(
            "{para} has no value to take the {} of",
            agg.name()
        )));
    }
    if kind == ColKind::I {
        let mut v = cells.iter().filter_map(|c| match c {
            Cell::I(i) => Some(*i),
            _ => None,
        });
        let overflow = || {
            Error::input(format!(
                "the {} of {para} overflows 64-bit integers",
                agg.name()
            ))
        };
        let r = match agg {
            Aggregate::SommAbs => v
                .map(i64::checked_abs)
                .try_fold(0i64, |s, x| s.checked_add(x?))
                .ok_or_else(overflow)?,
            Aggregate::Somm => v
                .try_fold(0i64, |s, x| s.checked_add(x))
                .ok_or_else(overflow)?,
            Aggregate::Max => v.max().unwrap_or(0),
            Aggregate::Min => v.min().unwrap_or(0),
        };
        return Ok(Cell::I(r));
    }
    let v = cells.iter().filter_map(|c| c.as_f64());
    Ok(Cell::R(match agg {
        Aggregate::SommAbs => v.map(f64::abs).sum(),
        Aggregate::Somm => v.sum(),
        Aggregate::Max => v.fold(f64::NEG_INFINITY, f64::max),
        Aggregate::Min => v.fold(f64::INFINITY, f64::min),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::tests::sample;

    #[test]
    fn aggregates_of_the_sample() {
        // FREQ = 12.5, -40, 25: sums and extremes by hand.
        let t = sample();
        let r = |a| aggregate(&t, "FREQ", a).unwrap();
        assert_eq!(r(Aggregate::SommAbs), Cell::R(77.5));
        assert_eq!(r(Aggregate::Somm), Cell::R(-2.5));
        assert_eq!(r(Aggregate::Max), Cell::R(25.0));
        assert_eq!(r(Aggregate::Min), Cell::R(-40.0));
        assert_eq!(
            aggregate(&t, "NUME_ORDRE", Aggregate::Somm).unwrap(),
            Cell::I(6)
        );
        assert!(aggregate(&t, "NOM_SD", Aggregate::Max).is_err());
    }

    #[test]
    fn integer_overflow_is_an_error() {
        let mut t = Table::new("");
        t.add_column("N", ColKind::I).unwrap();
        t.push_row(vec![Cell::I(i64::MAX)]).unwrap();
        t.push_row(vec![Cell::I(1)]).unwrap();
        assert!(aggregate(&t, "N", Aggregate::Somm).is_err());
        t.rows[1][0] = Cell::I(i64::MIN);
        assert!(aggregate(&t, "N", Aggregate::SommAbs).is_err());
    }
}
