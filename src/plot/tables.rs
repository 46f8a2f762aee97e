//! Pictures of tables: which picture a table calls for, and its data read from the table.
//!
//! - A MODE_NON_LINE table (ENERGIE, FREQUENCE, STABILITE, BIFURCATION) gives the
//!   frequency–energy plot.
//! - A REST_MODE_NONL time history (long format: NUME_ORDRE, INST, NOEUD, NOM_CMP, DEPL,
//!   VITE) gives the time history or the phase portrait of one node component, one curve
//!   per NUME_ORDRE.
//! - Any table gives curves of columns against a column (NOM_PARA=(x, y1, y2, ...)).
//!
//! Empty cells become NaN, which the drawing skips and counts.

use super::nnm::{FePoint, History, Stability};
use super::units::{unit, with_unit};
use super::{Series, XyPlot};
use crate::error::{Error, Result};
use crate::table::{Cell, Table};
use std::collections::BTreeMap;

/// Columns that make a table a MODE_NON_LINE result.
pub const MODE_NON_LINE_COLUMNS: [&str; 4] = ["ENERGIE", "FREQUENCE", "STABILITE", "BIFURCATION"];
/// Columns that make a table a time history.
pub const HISTORY_COLUMNS: [&str; 3] = ["INST", "DEPL", "VITE"];

pub fn is_mode_non_line(t: &Table) -> bool {
    MODE_NON_LINE_COLUMNS.iter().all(|c| t.col(c).is_some())
}

pub fn is_time_history(t: &Table) -> bool {
    HISTORY_COLUMNS.iter().all(|c| t.col(c).is_some())
}

fn real(row: &[Cell], j: usize) -> f64 {
    row.get(j).and_then(Cell::as_f64).unwrap_or(f64::NAN)
}

fn text(row: &[Cell], j: usize) -> &str {
    row.get(j).and_then(Cell::as_text).unwrap_or("")
}

/// The rows of a MODE_NON_LINE table, in table order.
pub fn fe_points(t: &Table) -> Result<Vec<FePoint>> {
    let (e, f) = (t.req_col("ENERGIE")?, t.req_col("FREQUENCE")?);
    let (s, b) = (t.req_col("STABILITE")?, t.req_col("BIFURCATION")?);
    // A table without NUME_REPRISE (one built by hand) is one run.
    let reprise = t.col("NUME_REPRISE");
    Ok(t.rows
        .iter()
        .map(|r| FePoint {
            energy: real(r, e),
            freq: real(r, f),
            stability: Stability::parse(text(r, s)),
            bifurcation: text(r, b).trim() == "OUI",
            reprise: reprise
                .and_then(|j| r.get(j))
                .and_then(Cell::as_f64)
                .map_or(0, |v| v as i64),
        })
        .collect())
}

/// The curves of one node component of a time-history table, one per NUME_ORDRE (a single
/// curve when the table has no NUME_ORDRE), sorted by INST. `noeud` / `nom_cmp` choose
/// the component; they may be omitted when the table holds only one. Returns the curves
/// and the component's name (`N2 DX`).
pub fn histories(
    t: &Table,
    noeud: Option<&str>,
    nom_cmp: Option<&str>,
) -> Result<(Vec<History>, String)> {
    let (ji, jd, jv) = (t.req_col("INST")?, t.req_col("DEPL")?, t.req_col("VITE")?);
    let (jn, jc, jo) = (t.col("NOEUD"), t.col("NOM_CMP"), t.col("NUME_ORDRE"));
    let key = |r: &[Cell], j: Option<usize>| j.map(|j| text(r, j).trim().to_string());
    // The components present, to choose from.
    let mut pairs: Vec<(Option<String>, Option<String>)> = Vec::new();
    for r in &t.rows {
        let p = (key(r, jn), key(r, jc));
        if !pairs.contains(&p) {
            pairs.push(p);
        }
    }
    let wanted = |p: &(Option<String>, Option<String>)| {
        noeud.is_none_or(|n| p.0.as_deref() == Some(n))
            && nom_cmp.is_none_or(|c| p.1.as_deref() == Some(c))
    };
    let chosen: Vec<&(Option<String>, Option<String>)> =
        pairs.iter().filter(|p| wanted(p)).collect();
    let describe = |p: &(Option<String>, Option<String>)| {
        [p.0.as_deref(), p.1.as_deref()]
            .into_iter()
            .flatten()
            .collect::<Vec<_>>()
            .join(" ")
    };
    let listing = || pairs.iter().map(&describe).collect::<Vec<_>>().join(", ");
    let pair = match chosen.as_slice() {
        [one] => (*one).clone(),
        [] => {
            return Err(Error::input(format!(
                "the table has no time history for{}{}",
                noeud.map(|n| format!(" NOEUD={n}")).unwrap_or_default(),
                nom_cmp.map(|c| format!(" NOM_CMP={c}")).unwrap_or_default()
            ))
            .hint(format!("it has: {}", listing())))
        }
        _ => {
            return Err(Error::input(format!(
                "the table holds {} node components: choose one",
                chosen.len()
            ))
            .hint(format!(
                "give NOEUD and NOM_CMP (or a FILTRE); the table has: {}",
                listing()
            )))
        }
    };
    // Group the rows of that component by NUME_ORDRE.
    let mut groups: BTreeMap<i64, Vec<(f64, f64, f64)>> = BTreeMap::new();
    for r in &t.rows {
        if (key(r, jn), key(r, jc)) != pair {
            continue;
        }
        let order = jo
            .and_then(|j| r.get(j))
            .and_then(Cell::as_f64)
            .map_or(0, |v| v as i64);
        groups
            .entry(order)
            .or_default()
            .push((real(r, ji), real(r, jd), real(r, jv)));
    }
    let curves = groups
        .into_iter()
        .map(|(order, mut pts)| {
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            History {
                label: if jo.is_some() {
                    format!("NUME_ORDRE {order}")
                } else {
                    String::new()
                },
                inst: pts.iter().map(|p| p.0).collect(),
                depl: pts.iter().map(|p| p.1).collect(),
                vite: pts.iter().map(|p| p.2).collect(),
            }
        })
        .collect();
    Ok((curves, describe(&pair)))
}

/// Columns `ys` against column `x`, one curve each, labelled by the column name.
pub fn columns_plot(t: &Table, x: &str, ys: &[String]) -> Result<XyPlot> {
    let jx = t.req_col(x)?;
    if ys.is_empty() {
        return Err(Error::validation(
            "a plot of a table needs NOM_PARA=(x, y, ...): the abscissa then the ordinates",
        )
        .keyword("NOM_PARA"));
    }
    let xs: Vec<f64> = t.rows.iter().map(|r| real(r, jx)).collect();
    let series = ys
        .iter()
        .map(|y| {
            let jy = t.req_col(y)?;
            let kind = t.columns.get(jy).map(|c| c.kind);
            if kind == Some(crate::table::ColKind::K) {
                return Err(
                    Error::input(format!("parameter {y} holds texts: it cannot be drawn"))
                        .keyword("NOM_PARA"),
                );
            }
            Ok(Series::new(
                y,
                xs.clone(),
                t.rows.iter().map(|r| real(r, jy)).collect(),
            ))
        })
        .collect::<Result<Vec<_>>>()?;
    // The y axis is named when it holds one column, or several of one unit.
    let y_unit = ys.iter().map(|y| unit(y, None)).collect::<Vec<_>>();
    Ok(XyPlot {
        x_label: with_unit(x, x, None),
        y_label: match ys {
            [y] => with_unit(y, y, None),
            _ if y_unit.windows(2).all(|w| w[0] == w[1]) => {
                y_unit[0].map_or_else(String::new, |u| format!("({u})"))
            }
            _ => String::new(),
        },
        series,
        ..XyPlot::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::ColKind;

    fn history_table() -> Table {
        let mut t = Table::new("th");
        for (n, k) in [
            ("NUME_ORDRE", ColKind::I),
            ("INST", ColKind::R),
            ("NOEUD", ColKind::K),
            ("NOM_CMP", ColKind::K),
            ("DEPL", ColKind::R),
            ("VITE", ColKind::R),
        ] {
            t.add_column(n, k).unwrap();
        }
        // Two rows (orders 1, 2), two components, instants given out of order for order 2.
        for (o, inst) in [(1, 0.0), (1, 0.5), (2, 0.5), (2, 0.0)] {
            for (cmp, sign) in [("DX", 1.0), ("DY", -1.0)] {
                t.push_row(vec![
                    Cell::I(o),
                    Cell::R(inst),
                    Cell::K("N2".into()),
                    Cell::K(cmp.into()),
                    Cell::R(sign * (inst + o as f64)),
                    Cell::R(sign * 10.0 * inst),
                ])
                .unwrap();
            }
        }
        t
    }

    #[test]
    fn histories_choose_a_component_and_group_by_order() {
        let t = history_table();
        assert!(is_time_history(&t) && !is_mode_non_line(&t));
        let err = histories(&t, None, None).unwrap_err();
        assert!(err.message.contains("2 node components"), "{err}");
        assert!(err.hint.unwrap().contains("N2 DX, N2 DY"));
        let (curves, what) = histories(&t, Some("N2"), Some("DY")).unwrap();
        assert_eq!(what, "N2 DY");
        assert_eq!(curves.len(), 2);
        assert_eq!(curves[1].label, "NUME_ORDRE 2");
        // Sorted by INST: order 2 at 0 then 0.5; DEPL = -(inst + 2).
        assert_eq!(curves[1].inst, vec![0.0, 0.5]);
        assert_eq!(curves[1].depl, vec![-2.0, -2.5]);
        assert_eq!(curves[1].vite, vec![-0.0, -5.0]);
        assert!(histories(&t, Some("N9"), None).is_err());
    }

    #[test]
    fn mode_non_line_rows() {
        let mut t = Table::new("mnl");
        for (n, k) in [
            ("NUME_ORDRE", ColKind::I),
            ("ENERGIE", ColKind::R),
            ("FREQUENCE", ColKind::R),
            ("STABILITE", ColKind::K),
            ("BIFURCATION", ColKind::K),
        ] {
            t.add_column(n, k).unwrap();
        }
        t.push_row(vec![
            Cell::I(1),
            Cell::R(0.1),
            Cell::R(0.5),
            Cell::K("INSTABLE".into()),
            Cell::K("OUI".into()),
        ])
        .unwrap();
        t.push_row(vec![
            Cell::I(2),
            Cell::Null,
            Cell::R(0.6),
            Cell::Null,
            Cell::K("NON".into()),
        ])
        .unwrap();
        assert!(is_mode_non_line(&t));
        let p = fe_points(&t).unwrap();
        assert_eq!(p[0].stability, Stability::Unstable);
        assert!(p[0].bifurcation && !p[1].bifurcation);
        assert!(p[1].energy.is_nan());
        assert_eq!(p[1].stability, Stability::NotEvaluated);
    }

    #[test]
    fn columns_against_a_column() {
        let t = crate::table::tests::sample();
        let spec = columns_plot(&t, "NUME_ORDRE", &["FREQ".into()]).unwrap();
        assert_eq!(spec.series[0].x, vec![1.0, 2.0, 3.0]);
        assert_eq!(spec.series[0].y, vec![12.5, -40.0, 25.0]);
        // With its unit (before: "FREQ").
        assert_eq!(spec.y_label, "FREQ (Hz)");
        let err = columns_plot(&t, "NUME_ORDRE", &["NOM_SD".into()]).unwrap_err();
        assert!(err.message.contains("holds texts"), "{err}");
        assert!(columns_plot(&t, "NUME_ORDRE", &[]).is_err());
    }
}
