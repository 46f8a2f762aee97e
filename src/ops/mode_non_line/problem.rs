//! Shared by MODE_NON_LINE, REST_MODE_NONL and CALC_STABILITE: turning stored shocks and
//! matrices back into the engine's problem.

use crate::error::{Error, Result};
use crate::linalg::craig_bampton::Reduction;
use crate::model::assembly::AssembledMatrix;
use crate::model::dof::Cmp;
use crate::nnm::{CercleForm, Harmonics, Problem, Shock, ShockLaw};
use crate::store::mnl::{self as mnl_store, MnlSetup, StoredShock};
use crate::store::Store;
use crate::table::{Cell, ColKind, Table};

/// The stored form of a cubic spring (MODE_NON_LINE/RESSORT_CUBIQUE): its TYPE_CHOC in
/// CARA_CHOC, where RIGI_NOR holds its RAIDEUR and JEU, PARA_REGUL are 0.
pub const RESSORT_CUBIQUE: &str = "RESSORT_CUBIQUE";

/// The stored shocks in the engine's reduced-DOF form, each error naming its occurrence:
/// CHOC[i] or RESSORT_CUBIQUE[j], numbered per factor keyword in the order given.
pub fn engine_shocks(stored: &[StoredShock], k: &AssembledMatrix) -> Result<Vec<Shock>> {
    let (mut chocs, mut springs) = (0, 0);
    stored
        .iter()
        .map(|s| {
            let occurrence = if s.obstacle == RESSORT_CUBIQUE {
                springs += 1;
                format!("MODE_NON_LINE/{RESSORT_CUBIQUE}[{springs}]")
            } else {
                chocs += 1;
                format!("MODE_NON_LINE/CHOC[{chocs}]")
            };
            engine_shock(s, &occurrence, k)
        })
        .collect()
}

/// Translate a stored shock into the engine's reduced-DOF form (the DOFs left free by the
/// boundary conditions of `k`); `occurrence` is its keyword path (errors name it).
pub fn engine_shock(s: &StoredShock, occurrence: &str, k: &AssembledMatrix) -> Result<Shock> {
    let kw = |key: &str| format!("{occurrence}/{key}");
    let mut dofs = Vec::new();
    for c in &s.cmps {
        let cmp = Cmp::parse(c).ok_or_else(|| {
            Error::validation(format!(
                "'{c}' is not a displacement component (DX, DY, DZ, ...)"
            ))
            .keyword(kw("NOM_CMP"))
        })?;
        let full = k.numbering.index_of(&s.node, cmp).ok_or_else(|| {
            Error::validation(format!(
                "node {} has no DOF {c} in the numbering of the matrices",
                s.node
            ))
            .keyword(kw("NOEUD"))
            .hint("the node must carry this component in the model (and exist in the mesh)")
        })?;
        let reduced = k.reduced_index(full).ok_or_else(|| {
            Error::validation(format!(
                "DOF {c} of node {} is blocked by a boundary condition: a {} cannot act on it",
                s.node,
                if s.obstacle == RESSORT_CUBIQUE {
                    "spring"
                } else {
                    "shock"
                }
            ))
            .keyword(kw("NOM_CMP"))
        })?;
        dofs.push(reduced);
    }
    let law = match s.obstacle.as_str() {
        "PLAN" => ShockLaw::Plan,
        "BI_PLAN" => ShockLaw::BiPlan,
        RESSORT_CUBIQUE => ShockLaw::RESSORT_CUBIQUE,
        "CERCLE" => {
            // The ring centre in the plane of the two components.
            let pick = |c: &str| match c {
                "DX" | "DRX" => s.origin[0],
                "DY" | "DRY" => s.origin[1],
                _ => s.origin[2],
            };
            let form = match s.loi_cercle.as_str() {
                "RAYON" => CercleForm::Radial,
                "SECANTE" => CercleForm::Secant,
                other => {
                    return Err(Error::validation(format!(
                        "unknown LOI_CERCLE '{other}': 'RAYON' or 'SECANTE'"
                    ))
                    .keyword(kw("LOI_CERCLE")))
                }
            };
            ShockLaw::Cercle {
                origin: [pick(&s.cmps[0]), pick(&s.cmps[1])],
                form,
            }
        }
        other => {
            return Err(
                Error::validation(format!("unknown OBSTACLE '{other}'")).keyword(kw("OBSTACLE"))
            )
        }
    };
    Ok(Shock {
        law,
        dofs,
        gap: s.gap,
        stiffness: s.stiffness,
        regul: s.regul,
    })
}

/// What reading a stored MODE_NON_LINE run back needs.
pub struct StoredRun {
    /// The problem its points solve (on the reduction basis for a run with REDUCTION).
    pub problem: Problem,
    /// Its harmonic counts (all that reading its rows back needs).
    pub harmonics: Harmonics,
    /// The free DOFs of its matrices.
    pub free: Vec<usize>,
    /// REDUCTION's basis: expands the problem's coordinates to the free DOFs.
    pub basis: Option<Reduction>,
}

impl StoredRun {
    /// Per free DOF, the series given per coordinate of the problem (identity without a
    /// basis).
    pub fn on_free_dofs(&self, per_coordinate: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
        match &self.basis {
            Some(b) => b.expand_series(&per_coordinate),
            None => per_coordinate,
        }
    }
}

/// The engine problem of the stored MODE_NON_LINE run `name`.
pub fn engine_problem(
    store: &Store,
    name: &str,
    setup: &MnlSetup,
    k: &AssembledMatrix,
    m: &AssembledMatrix,
) -> Result<StoredRun> {
    let free = k.free_dofs();
    let shocks = engine_shocks(&setup.shocks, k)?;
    let full = Problem {
        forcing: None,
        k: k.reduced()?,
        m: m.reduced()?,
        shocks,
    };
    let harmonics = Harmonics {
        h_lin: setup.h_lin,
        h_nonl: setup.h_nonl,
    };
    let (problem, basis) = match &setup.reduction {
        Some(r) => {
            let basis = mnl_store::load_basis(store, name, r)?;
            (crate::nnm::reduced_problem(&full, &basis)?, Some(basis))
        }
        None => (full, None),
    };
    Ok(StoredRun {
        problem,
        harmonics,
        free,
        basis,
    })
}

/// Index of the row with NUME_ORDRE = `order`.
pub fn row_of(t: &Table, order: i64) -> Option<usize> {
    let col = t.col("NUME_ORDRE")?;
    t.rows
        .iter()
        .position(|r| matches!(r.get(col), Some(Cell::I(i)) if *i == order))
}

/// The columns of a CARA_CHOC sub-table, as MODE_NON_LINE writes it and
/// [`shocks_from_cara_choc`] reads it: Code_Aster's, then LOI_CERCLE (ours; tables written
/// before it existed lack it).
pub const CARA_CHOC_COLUMNS: &[(&str, ColKind)] = &[
    ("NUME_CHOC", ColKind::I),
    ("TYPE_CHOC", ColKind::K),
    ("NOEUD_CHOC", ColKind::K),
    ("NOM_CMP_1", ColKind::K),
    ("NOM_CMP_2", ColKind::K),
    ("RIGI_NOR", ColKind::R),
    ("PARA_REGUL", ColKind::R),
    ("JEU", ColKind::R),
    ("ORIG_OBST_X", ColKind::R),
    ("ORIG_OBST_Y", ColKind::R),
    ("ORIG_OBST_Z", ColKind::R),
    ("LOI_CERCLE", ColKind::K),
];

/// The shocks described by a CARA_CHOC sub-table.
pub fn shocks_from_cara_choc(t: &Table, name: &str) -> Result<Vec<StoredShock>> {
    let text = |r: usize, c: &str| -> Option<String> {
        t.cell(r, c).and_then(Cell::as_text).map(str::to_string)
    };
    let real = |r: usize, c: &str| -> Result<f64> {
        t.cell(r, c).and_then(Cell::as_f64).ok_or_else(|| {
            Error::store(format!("CARA_CHOC table {name}: row {} has no {c}", r + 1))
        })
    };
    (0..t.nrows())
        .map(|r| {
            let obstacle = text(r, "TYPE_CHOC").ok_or_else(|| {
                Error::store(format!(
                    "CARA_CHOC table {name}: row {} has no TYPE_CHOC",
                    r + 1
                ))
            })?;
            let node = text(r, "NOEUD_CHOC").ok_or_else(|| {
                Error::store(format!(
                    "CARA_CHOC table {name}: row {} has no NOEUD_CHOC",
                    r + 1
                ))
            })?;
            let cmps: Vec<String> = ["NOM_CMP_1", "NOM_CMP_2"]
                .iter()
                .filter_map(|c| text(r, c))
                .filter(|c| !c.is_empty())
                .collect();
            Ok(StoredShock {
                obstacle,
                node,
                cmps,
                gap: real(r, "JEU")?,
                stiffness: real(r, "RIGI_NOR")?,
                regul: real(r, "PARA_REGUL")?,
                origin: [
                    real(r, "ORIG_OBST_X")?,
                    real(r, "ORIG_OBST_Y")?,
                    real(r, "ORIG_OBST_Z")?,
                ],
                // A table written before LOI_CERCLE existed: the form it was computed with;
                // an empty cell (a cubic spring's): none.
                loi_cercle: match t.col("LOI_CERCLE") {
                    Some(_) => text(r, "LOI_CERCLE").unwrap_or_default(),
                    None => crate::store::mnl::form_of_older_studies(),
                },
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cara_choc(with_form: Option<&str>) -> Table {
        let mut t = Table::new("CARA_CHOC");
        for &(n, k) in CARA_CHOC_COLUMNS {
            if n != "LOI_CERCLE" || with_form.is_some() {
                t.add_column(n, k).unwrap();
            }
        }
        let mut row = vec![
            Cell::I(1),
            Cell::K("CERCLE".into()),
            Cell::K("N1".into()),
            Cell::K("DX".into()),
            Cell::K("DY".into()),
            Cell::R(50.0),
            Cell::R(1e-4),
            Cell::R(0.01),
            Cell::R(0.0),
            Cell::R(0.0),
            Cell::R(0.0),
        ];
        if let Some(f) = with_form {
            row.push(Cell::K(f.into()));
        }
        t.push_row(row).unwrap();
        t
    }

    /// A restart goes on with the ring law the stored run used: the CARA_CHOC column, or
    /// 'SECANTE' for a table written before the column existed (the law of those studies).
    #[test]
    fn a_stored_ring_keeps_its_law_and_older_tables_read_as_secant() {
        let new = shocks_from_cara_choc(&cara_choc(Some("RAYON")), "C").unwrap();
        assert_eq!(new[0].loi_cercle, "RAYON");
        let old = shocks_from_cara_choc(&cara_choc(None), "C").unwrap();
        assert_eq!(old[0].loi_cercle, "SECANTE");
        // And an older study's stored setup (JSON without the field) too.
        let json = r#"{"obstacle":"CERCLE","node":"N1","cmps":["DX","DY"],"gap":0.01,
            "stiffness":50.0,"regul":1e-4,"origin":[0.0,0.0,0.0]}"#;
        let s: StoredShock = serde_json::from_str(json).unwrap();
        assert_eq!(s.loi_cercle, "SECANTE");
    }
}
