//! A shock's internal variables VINT1..VINTn in Code_Aster's order, read from the shocks'
//! table `<result>_CHOC` (store/tran_gene.rs): what RECU_FONCTION's PARA_Y='VINTi' and the
//! Python API's `R.VARI_INTERNE(i)` and `R.FORCE_NORMALE(i)` give. DIS_CHOC has 20, FLAMBAGE
//! 11; their names are those Code_Aster prints with VARI_INTERNE.

use crate::error::{Error, Result};
use crate::ops::common::tran_gene::shock_samples;
use crate::store::tran_gene::{self, StoredShock};
use crate::table::Table;

/// Where one internal variable is stored: a column of the shocks' table, or nowhere when
/// the law keeps none for this shock (no friction: its stick memory is zero).
#[derive(Clone, Copy)]
struct Var {
    /// Code_Aster's name of the variable (VARI_INTERNE's description).
    name: &'static str,
    /// The column of `<result>_CHOC` that holds it.
    column: &'static str,
}

const fn var(name: &'static str, column: &'static str) -> Var {
    Var { name, column }
}

/// DIS_CHOC's 20 variables: forces, the two nodes' local positions, velocities, then the
/// stick/slip memory ([`tran_gene::FRICTION_MEMORY`]).
const DIS_CHOC: [Var; 20] = [
    var("F_NORMAL", "FN"),
    var("F_TANGE1", "FT1"),
    var("F_TANGE2", "FT2"),
    var("DXLOC_N1", "DXLOC"),
    var("DYLOC_N1", "DYLOC"),
    var("DZLOC_N1", "DZLOC"),
    var("DXLOC_N2", "DXLOC_N2"),
    var("DYLOC_N2", "DYLOC_N2"),
    var("DZLOC_N2", "DZLOC_N2"),
    var("V_NORMAL", "VN"),
    var("V_TANGE1", "VT1"),
    var("V_TANGE2", "VT2"),
    var("IND_ADHE", "VINT13"),
    var("VINT_FR1", "VINT14"),
    var("VINT_FR2", "VINT15"),
    var("VINT_FR3", "VINT16"),
    var("VINT_FR4", "VINT17"),
    var("VINT_FR5", "VINT18"),
    var("VINT_FR6", "VINT19"),
    var("VINT_FR7", "VINT20"),
];

/// FLAMBAGE's 11 variables: the normal force, the two nodes' local positions, the normal
/// velocity, then the buckling state ([`tran_gene::BUCKLING_MEMORY`] but its damping).
const FLAMBAGE: [Var; 11] = [
    var("F_NORMAL", "FN"),
    var("DXLOC_N1", "DXLOC"),
    var("DYLOC_N1", "DYLOC"),
    var("DZLOC_N1", "DZLOC"),
    var("DXLOC_N2", "DXLOC_N2"),
    var("DYLOC_N2", "DYLOC_N2"),
    var("DZLOC_N2", "DZLOC_N2"),
    var("V_NORMAL", "VN"),
    var("ENFO_PLA", "ECRAS_RESI"),
    var("RIGI_P_F", "RIGI_FL"),
    var("ENFO_MAX", "ENFO_MAX"),
];

fn vars(shock: &StoredShock) -> &'static [Var] {
    if shock.is_buckling() {
        &FLAMBAGE
    } else {
        &DIS_CHOC
    }
}

/// The law's name as Code_Aster's VARI_INTERNE prints it.
pub fn law(shock: &StoredShock) -> &'static str {
    if shock.is_buckling() {
        "FLAMBAGE"
    } else {
        "DIS_CHOC"
    }
}

/// The names of the shock's internal variables, in order.
pub fn names(shock: &StoredShock) -> Vec<&'static str> {
    vars(shock).iter().map(|v| v.name).collect()
}

/// The archived instants and the internal variables `which` (1-based; all of them when
/// `None`) of `shock`, one column per variable, from the shocks' table `t` of `result`.
/// A column the table lacks reads zero where the shock cannot use it (node 2 of a one-node
/// shock, the stick memory when no shock of the result has friction); node 2 of a two-node
/// shock stored before aster-nl kept it is an error.
pub fn history(
    t: &Table,
    result: &str,
    shock: &StoredShock,
    which: Option<usize>,
) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    let all = vars(shock);
    let chosen: Vec<Var> = match which {
        None => all.to_vec(),
        Some(i) if (1..=all.len()).contains(&i) => vec![all[i - 1]],
        Some(i) => {
            return Err(Error::validation(format!(
                "VINT{i}: a {} shock has {} internal variables (VINT1 to VINT{})",
                law(shock),
                all.len(),
                all.len()
            )))
        }
    };
    for v in &chosen {
        if t.col(v.column).is_none()
            && tran_gene::NODE2_POSITION.contains(&v.column)
            && shock.node2.is_some()
        {
            return Err(Error::store(format!(
                "{result} was stored without node 2's local position (a study of an \
                 earlier aster-nl): run its DYNA_VIBRA again to read {}",
                v.name
            )));
        }
    }
    let stored: Vec<&str> = chosen
        .iter()
        .map(|v| v.column)
        .filter(|c| t.col(c).is_some())
        .collect();
    let (times, cols) = shock_samples(t, &shock.intitule, &stored)?;
    let mut cols = cols.into_iter();
    let out = chosen
        .iter()
        .map(|v| match t.col(v.column) {
            Some(_) => cols.next().unwrap_or_default(),
            None => vec![0.0; times.len()],
        })
        .collect();
    Ok((times, out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::{Cell, ColKind};

    fn shock(relation: &str, node2: Option<&str>) -> StoredShock {
        StoredShock {
            intitule: "C1".into(),
            node1: "N1".into(),
            node2: node2.map(str::to_string),
            obstacle: "OBS".into(),
            relation: relation.into(),
        }
    }

    /// A shocks' table of one instant: FN=1, ..., each column its own value.
    fn table(with_node2: bool) -> Table {
        let mut t = Table::new("t");
        let mut cols = vec!["INST", "INTITULE"];
        cols.extend(crate::transient::ShockSample::NAMES);
        if with_node2 {
            cols.extend(tran_gene::NODE2_POSITION);
        }
        let mut row = vec![];
        for (k, c) in cols.iter().enumerate() {
            let kind = if *c == "INTITULE" {
                ColKind::K
            } else {
                ColKind::R
            };
            t.add_column(c, kind).unwrap();
            row.push(match kind {
                ColKind::K => Cell::K("C1".into()),
                _ => Cell::R(k as f64),
            });
        }
        t.push_row(row).unwrap();
        t
    }

    #[test]
    fn variables_follow_code_aster_order() {
        let t = table(true);
        let (times, cols) = history(&t, "R", &shock("DIS_CHOC", Some("N2")), None).unwrap();
        assert_eq!(times, vec![0.0]);
        assert_eq!(cols.len(), 20);
        // FN is column 2 of the table, VN column 5, DXLOC_N2 column 11.
        assert_eq!(cols[0], vec![2.0]);
        assert_eq!(cols[9], vec![5.0]);
        assert_eq!(cols[6], vec![11.0]);
        // No friction column: the stick memory reads zero.
        assert_eq!(cols[12], vec![0.0]);
        let (_, one) = history(&t, "R", &shock("FLAMBAGE", None), Some(8)).unwrap();
        assert_eq!(one, vec![vec![5.0]]);
    }

    #[test]
    fn out_of_range_and_missing_node2_are_errors() {
        let t = table(false);
        let e = history(&t, "R", &shock("FLAMBAGE", None), Some(12)).unwrap_err();
        assert!(e.message.contains("11 internal variables"), "{}", e.message);
        let e = history(&t, "R", &shock("DIS_CHOC", Some("N2")), Some(7)).unwrap_err();
        assert!(e.message.contains("node 2"), "{}", e.message);
        // A one-node shock has node 2 at zero.
        let (_, z) = history(&t, "R", &shock("DIS_CHOC", None), Some(7)).unwrap();
        assert_eq!(z, vec![vec![0.0]]);
    }
}
