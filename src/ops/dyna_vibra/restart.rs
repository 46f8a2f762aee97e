//! ETAT_INIT=_F(RESULTAT=R, [INST_INIT | NUME_ORDRE]) on a modal basis, and reuse=R: the
//! run goes on from a stored instant of a DYNA_VIBRA result as Code_Aster's does
//! (routines `mdinit`, `dtminit`): the displacement, velocity and acceleration stored at
//! that instant (its last by default) and the shocks' internal variables there (stick/slip
//! memory, a buckled element's crush: `memory.rs`) are the start, nothing is re-evaluated;
//! the run starts at that instant, whatever INCREMENT/INST_INIT says. The shocks of the
//! call must be those of R, in number, order, relation and nodes (Code_Aster's
//! ALGORITH5_82, ALGORITH5_83). With reuse=R, R keeps its instants up to that one and the
//! new ones follow (those stored after it are dropped, as Code_Aster's `_APPND_SD` does).

use super::memory;
use super::shocks::ShockName;
use super::space::{instant, Space};
use crate::args::Args;
use crate::error::{Error, Result};
use crate::ops::common::tran_gene as common_tran_gene;
use crate::ops::OpContext;
use crate::store::tran_gene;
use crate::transient::{ShockSample, Trajectory};

/// The stored state a run goes on from.
pub struct Restart {
    /// The instant, and its index among R's archived instants.
    pub t0: f64,
    pub index: usize,
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
    /// Each shock's sample at t0, its internal variables included.
    pub samples: Vec<ShockSample>,
    /// reuse=: R's archived instants up to t0 included.
    pub history: Option<Trajectory>,
}

/// The start of a run on a modal basis from ETAT_INIT's RESULTAT (`init`), checked
/// against the call's shocks `names`; `keep` (reuse=) also returns R's history up to it.
pub fn read(
    ctx: &OpContext<'_>,
    init: &Args,
    space: &Space,
    names: &[ShockName],
    keep: bool,
) -> Result<Restart> {
    let Space::Gene {
        numbering,
        basis,
        modes,
    } = space
    else {
        return Err(Error::internal(
            "restart::read reads a result on a modal basis",
        ));
    };
    let c = init.req_concept("RESULTAT")?;
    let result = c.name.clone();
    let kw = init.key_path("RESULTAT");
    let payload = tran_gene::load_payload(ctx.store, &result)?;
    // Another numbering of the same basis gives the same coordinates (Code_Aster checks
    // the basis).
    if payload.numbering != *numbering && payload.basis != *basis {
        return Err(Error::input(format!(
            "{result} is computed on {}, this run on {numbering}",
            if payload.numbering.is_empty() {
                "the physical DOFs"
            } else {
                &payload.numbering
            }
        ))
        .keyword(kw));
    }
    same_shocks(&result, &payload.shocks, names, &kw)?;
    let n = modes.modes.len();
    let coords = tran_gene::load_coordinates(ctx.store, &result, n)?;
    let index = instant(init, &coords.t)?;
    let mut histories = Vec::with_capacity(payload.shocks.len());
    if !payload.shocks.is_empty() {
        let table = common_tran_gene::shock_table(ctx.store, &result, &payload)?;
        for shock in &payload.shocks {
            let (times, samples) = memory::samples(&table, &result, shock)?;
            if times.len() != coords.t.len() {
                return Err(Error::store(format!(
                    "{result}: shock '{}' has {} archived samples for {} instants (rows removed \
                     or added outside aster-nl)",
                    shock.intitule,
                    times.len(),
                    coords.t.len()
                )));
            }
            histories.push(samples);
        }
    }
    let at = |x: &[f64]| x[index * n..(index + 1) * n].to_vec();
    let history = keep.then(|| Trajectory {
        n,
        t: coords.t[..=index].to_vec(),
        q: coords.q[..(index + 1) * n].to_vec(),
        v: coords.v[..(index + 1) * n].to_vec(),
        a: coords.a[..(index + 1) * n].to_vec(),
        shocks: histories.iter().map(|h| h[..=index].to_vec()).collect(),
        ..Trajectory::default()
    });
    Ok(Restart {
        t0: coords.t[index],
        index,
        q: at(&coords.q),
        v: at(&coords.v),
        a: at(&coords.a),
        samples: histories.iter().map(|h| h[index]).collect(),
        history,
    })
}

/// The call's shocks must be the stored ones, in order (Code_Aster refuses a restart
/// otherwise: the internal variables belong to each nonlinearity).
fn same_shocks(
    result: &str,
    stored: &[tran_gene::StoredShock],
    names: &[ShockName],
    kw: &str,
) -> Result<()> {
    let describe = |relation: &str, n1: &str, n2: &Option<String>| {
        let relation = if relation.is_empty() {
            "DIS_CHOC"
        } else {
            relation
        };
        match n2 {
            Some(n2) => format!("{relation} between {n1} and {n2}"),
            None => format!("{relation} on {n1}"),
        }
    };
    if stored.len() != names.len() {
        return Err(Error::input(format!(
            "{result} was computed with {} shock(s), this call has {}: a run goes on with the \
             nonlinearities it started with (their internal variables carry over)",
            stored.len(),
            names.len()
        ))
        .keyword(kw.to_string())
        .hint("give the same COMPORTEMENT occurrences, in the same order, as the run that computed it"));
    }
    for (k, (s, n)) in stored.iter().zip(names).enumerate() {
        let there = describe(&s.relation, &s.node1, &s.node2);
        let here = describe(&n.relation, &n.node1, &n.node2);
        if there != here {
            return Err(Error::input(format!(
                "shock {} of {result} is a {there}, of this call a {here}: a run goes on with \
                 the nonlinearities it started with, in the same order",
                k + 1
            ))
            .keyword(kw.to_string())
            .hint("give the same COMPORTEMENT occurrences, in the same order, as the run that computed it"));
        }
    }
    Ok(())
}

/// reuse=: R's history up to the restart instant, then the new run's instants after it.
/// The new run's row at the restart instant is R's own, which is kept.
pub fn continued(history: Trajectory, new: Trajectory, t0: f64) -> Trajectory {
    let n = new.n;
    let span = new.t.last().map_or(0.0, |&t| (t - t0).abs());
    let tol = 1e-12 * span.max(t0.abs());
    let first = new
        .t
        .iter()
        .position(|&t| t > t0 + tol)
        .unwrap_or(new.t.len());
    let mut out = history;
    out.t.extend_from_slice(&new.t[first..]);
    out.q.extend_from_slice(&new.q[first * n..]);
    out.v.extend_from_slice(&new.v[first * n..]);
    out.a.extend_from_slice(&new.a[first * n..]);
    for (old, fresh) in out.shocks.iter_mut().zip(&new.shocks) {
        old.extend_from_slice(&fresh[first..]);
    }
    out.events = new.events;
    out.steps_taken = new.steps_taken;
    out.steps_rejected = new.steps_rejected;
    out.steps_forced = new.steps_forced;
    out
}
