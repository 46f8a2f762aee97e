//! Persistence of DYNA_VIBRA's results besides their time-history tables:
//! - a `tran_gene` (BASE_CALCUL='GENE') is a table concept with one row per archived instant
//!   and generalized coordinate: NUME_ORDRE, INST, NUME_CMP (1..n), DEPL, VITE, ACCE;
//! - the shocks' samples are the table concept `<name>_CHOC`: NUME_ORDRE, INST, INTITULE,
//!   NOEUD, FN, FT1, FT2, VN, VT1, VT2, DXLOC, DYLOC, DZLOC, node 2's local position
//!   ([`NODE2_POSITION`], when a shock has a node 2) and the shocks' internal variables a
//!   restart goes on from ([`FRICTION_MEMORY`] when a shock has friction,
//!   [`BUCKLING_MEMORY`] when one is a FLAMBAGE);
//! - `concept_data(concept, 'tran_gene')`: [`Payload`], what a reader needs to restore
//!   physical fields (the basis) and to find a shock by node or INTITULE.

use super::Store;
use crate::error::Result;
use serde::{Deserialize, Serialize};

const KEY: &str = "tran_gene";

/// A shock of the result.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StoredShock {
    pub intitule: String,
    pub node1: String,
    pub node2: Option<String>,
    pub obstacle: String,
    /// RELATION: 'DIS_CHOC' or 'FLAMBAGE' (empty in results stored before FLAMBAGE: DIS_CHOC).
    #[serde(default)]
    pub relation: String,
}

impl StoredShock {
    /// Whether the shock is a FLAMBAGE one.
    pub fn is_buckling(&self) -> bool {
        self.relation == "FLAMBAGE"
    }
}

/// The columns of a shock's stick/slip memory in `<name>_CHOC`: Code_Aster's internal
/// variables 13 to 20 of DIS_CHOC (sticking flag, tangential force at the anchor (2), the
/// anchor's local position (3), the previous tangential velocity (2)).
pub const FRICTION_MEMORY: [&str; 8] = [
    "VINT13", "VINT14", "VINT15", "VINT16", "VINT17", "VINT18", "VINT19", "VINT20",
];

/// The columns of node 2's local position in `<name>_CHOC` (Code_Aster's internal variables
/// 7 to 9 of DIS_CHOC, 5 to 7 of FLAMBAGE), written when a shock has a node 2 (zero for
/// the one-node shocks of the same result).
pub const NODE2_POSITION: [&str; 3] = ["DXLOC_N2", "DYLOC_N2", "DZLOC_N2"];

/// The columns of a FLAMBAGE shock's internal variables in `<name>_CHOC`: the crush
/// (Code_Aster's DEFPLA, POST_DYNA_MODA_T's ECRAS_RESI), the unloading stiffness, the
/// largest penetration and the damping of the current segment.
pub const BUCKLING_MEMORY: [&str; 4] = ["ECRAS_RESI", "RIGI_FL", "ENFO_MAX", "AMOR_FL"];

/// What a DYNA_VIBRA result is computed on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Payload {
    /// 'GENE' or 'PHYS'.
    pub base: String,
    /// GENE: the NUME_DDL_GENE and its basis (mode_meca); PHYS: empty.
    pub numbering: String,
    pub basis: String,
    pub shocks: Vec<StoredShock>,
    /// The table concept of the shocks' samples, if there are shocks.
    pub shock_table: Option<String>,
    /// The moving supports (EXCIT with MULT_APPUI='OUI'), in order; empty for fixed ones.
    #[serde(default)]
    pub supports: Vec<StoredSupport>,
}

/// A moving support excitation: its constraint modes (MODE_STATIQUE), the support nodes,
/// DIRECTION, and the functions of its acceleration, velocity and displacement, which
/// restore the absolute motion (u_abs = Φq + ψ·DEPL(t), ψ = Σ DIRECTION_c ψ_node,c).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StoredSupport {
    pub mode_stat: String,
    pub nodes: Vec<String>,
    pub direction: Vec<f64>,
    pub acce: String,
    pub vite: String,
    pub depl: String,
}

pub fn save_payload(store: &Store, concept: &str, p: &Payload) -> Result<()> {
    store.put_json(concept, KEY, p)
}

pub fn load_payload(store: &Store, concept: &str) -> Result<Payload> {
    store.get_json(concept, KEY)
}

/// The name of the shocks' table of result `concept`.
pub fn shock_table_name(concept: &str) -> String {
    format!("{concept}_CHOC")
}

/// Concepts that belong to `concept` and go with it (DETRUIRE): its shocks' table.
pub fn owned_concepts(store: &Store, concept: &str) -> Result<Vec<String>> {
    let has: i64 = store
        .row(
            "SELECT COUNT(*) FROM concept_data WHERE concept = ?1 AND key = ?2",
            rusqlite::params![concept, KEY],
            |r| r.get(0),
        )?
        .unwrap_or(0);
    if has == 0 {
        return Ok(Vec::new());
    }
    Ok(load_payload(store, concept)?
        .shock_table
        .into_iter()
        .collect())
}

/// The archived generalized coordinates of a `tran_gene`: instants, and q, v, a row-major
/// (`n` values per instant).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coordinates {
    pub n: usize,
    pub t: Vec<f64>,
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
}

/// The coordinates of `concept` with `n` generalized unknowns, read from its table.
pub fn load_coordinates(store: &Store, concept: &str, n: usize) -> Result<Coordinates> {
    let mut stmt = store.conn().prepare(&format!(
        "SELECT NUME_ORDRE, INST, NUME_CMP, DEPL, VITE, ACCE FROM {} ORDER BY NUME_ORDRE, NUME_CMP",
        super::table::quote_ident(concept)
    ))?;
    let mut out = Coordinates {
        n,
        ..Coordinates::default()
    };
    let mut rows = stmt.query([])?;
    let mut expected = 0usize;
    while let Some(r) = rows.next()? {
        let (order, t, cmp): (i64, f64, i64) = (r.get(0)?, r.get(1)?, r.get(2)?);
        let at = expected % n.max(1);
        if cmp != at as i64 + 1 || order != (expected / n.max(1)) as i64 + 1 {
            return Err(crate::error::Error::store(format!(
                "{concept}: row NUME_ORDRE={order}, NUME_CMP={cmp} out of sequence (rows removed or added outside aster-nl)"
            )));
        }
        if at == 0 {
            out.t.push(t);
        }
        out.q.push(r.get(3)?);
        out.v.push(r.get(4)?);
        out.a.push(r.get(5)?);
        expected += 1;
    }
    if n == 0 || !expected.is_multiple_of(n) {
        return Err(crate::error::Error::store(format!(
            "{concept}: {expected} rows for {n} generalized unknowns"
        )));
    }
    Ok(out)
}

/// The archived instants of the `tran_gene` `concept`, in order (Code_Aster's DISC:
/// `R.LIST_ARCH()`).
pub fn archived_instants(store: &Store, concept: &str) -> Result<Vec<f64>> {
    let mut stmt = store.conn().prepare(&format!(
        "SELECT INST FROM {} WHERE NUME_CMP = 1 ORDER BY NUME_ORDRE",
        super::table::quote_ident(concept)
    ))?;
    let rows = stmt.query_map([], |r| r.get::<_, f64>(0))?;
    Ok(rows.collect::<rusqlite::Result<Vec<f64>>>()?)
}
