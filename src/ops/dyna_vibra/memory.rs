//! The shocks' internal variables as columns of `<result>_CHOC` (store/tran_gene.rs): node
//! 2's local position, the stick/slip memory of DIS_CHOC with friction ([`tran_gene::FRICTION_MEMORY`]) and the
//! state of a FLAMBAGE shock ([`tran_gene::BUCKLING_MEMORY`]), written at every archived
//! instant and read back by a restart (ETAT_INIT=_F(RESULTAT=...)), so that a run split in
//! two goes on as one run does.

use crate::error::{Error, Result};
use crate::ops::common::tran_gene as common_tran_gene;
use crate::store::tran_gene::{self, StoredShock};
use crate::table::Table;
use crate::transient::{BucklingState, ShockSample, ShockState};

/// The values of [`tran_gene::FRICTION_MEMORY`] for a state.
pub fn friction(s: &ShockState) -> [f64; 8] {
    s.friction_memory()
}

/// The values of [`tran_gene::BUCKLING_MEMORY`] for a state.
pub fn buckling(s: &ShockState) -> [f64; 4] {
    let b = &s.buckling;
    [b.crush, b.stiffness, b.max_penetration, b.damping]
}

fn set_friction(s: &mut ShockState, v: &[f64]) {
    let mut m = [0.0; 8];
    m.copy_from_slice(&v[..8]);
    s.set_friction_memory(&m);
}

fn set_buckling(s: &mut ShockState, v: &[f64]) {
    s.buckling = BucklingState {
        crush: v[0],
        stiffness: v[1],
        max_penetration: v[2],
        damping: v[3],
    };
}

/// Every archived sample of `shock` in the shocks' table `t` of `result`, with its
/// internal variables where the table has them (a table written before they were stored,
/// or for a law without them, reads zero: the state of a shock that never touched).
pub fn samples(
    t: &Table,
    result: &str,
    shock: &StoredShock,
) -> Result<(Vec<f64>, Vec<ShockSample>)> {
    let mut names: Vec<&str> = ShockSample::NAMES.to_vec();
    let node2 = tran_gene::NODE2_POSITION.iter().all(|p| t.col(p).is_some());
    if node2 {
        names.extend(tran_gene::NODE2_POSITION);
    }
    let friction = tran_gene::FRICTION_MEMORY
        .iter()
        .all(|p| t.col(p).is_some());
    let buckling = tran_gene::BUCKLING_MEMORY
        .iter()
        .all(|p| t.col(p).is_some());
    if friction {
        names.extend(tran_gene::FRICTION_MEMORY);
    }
    if buckling {
        names.extend(tran_gene::BUCKLING_MEMORY);
    }
    let (times, cols) = common_tran_gene::shock_samples(t, &shock.intitule, &names)?;
    let mut out = Vec::with_capacity(times.len());
    let mut row = vec![0.0; names.len()];
    for i in 0..times.len() {
        for (r, c) in row.iter_mut().zip(&cols) {
            *r = c[i];
        }
        if row.iter().any(|x| !x.is_finite()) {
            return Err(Error::store(format!(
                "the samples of shock '{}' in {result}'s shocks' table are not all numbers \
                 (instant {})",
                shock.intitule,
                i + 1
            )));
        }
        let mut s = ShockSample {
            f_n: row[0],
            f_t1: row[1],
            f_t2: row[2],
            v_n: row[3],
            v_t1: row[4],
            v_t2: row[5],
            loc1: [row[6], row[7], row[8]],
            ..ShockSample::default()
        };
        let mut k = ShockSample::NAMES.len();
        if node2 {
            s.loc2 = [row[k], row[k + 1], row[k + 2]];
            k += 3;
        }
        if friction {
            set_friction(&mut s.state, &row[k..k + 8]);
            k += 8;
        }
        if buckling && shock.is_buckling() {
            set_buckling(&mut s.state, &row[k..k + 4]);
        }
        out.push(s);
    }
    Ok((times, out))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What is written is what is read: every variable of the state has its column.
    // Field by field from the default: a field added to the state later (not stored yet,
    // so a restart starts it at its default) leaves this test compiling.
    #[allow(clippy::field_reassign_with_default)]
    #[test]
    fn the_columns_hold_the_whole_state() {
        let mut state = ShockState::default();
        state.sticking = true;
        state.old_ft = [1.0, 2.0];
        state.old_xl = [3.0, 4.0, 5.0];
        state.old_vt = [6.0, 7.0];
        state.buckling = BucklingState {
            crush: 8.0,
            stiffness: 9.0,
            max_penetration: 10.0,
            damping: 11.0,
        };
        let mut back = ShockState::default();
        set_friction(&mut back, &friction(&state));
        set_buckling(&mut back, &buckling(&state));
        assert_eq!(back, state);
    }
}
