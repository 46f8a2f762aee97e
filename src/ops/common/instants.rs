//! The archived instants a reader of a transient result asks for (REST_GENE_PHYS,
//! RECU_FONCTION): every one, some by NUME_ORDRE, or instants matched within PRECISION or
//! interpolated linearly between the two archived ones around them.

use crate::args::Args;
use crate::error::{Error, Result};

/// One instant of the output: a weighted pair of archived instants (w on `lo`, 1 − w on
/// `hi`; an archived instant has lo = hi).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    pub t: f64,
    pub lo: usize,
    pub hi: usize,
    pub w: f64,
}

/// The index of order number `k` (1-based) among `times`; errors name `kw`.
pub fn by_order(k: i64, times: &[f64], kw: String) -> Result<usize> {
    usize::try_from(k)
        .ok()
        .filter(|&k| (1..=times.len()).contains(&k))
        .map(|k| k - 1)
        .ok_or_else(|| {
            Error::validation(format!(
                "NUME_ORDRE={k}: the result has {} archived instants (1 to {})",
                times.len(),
                times.len()
            ))
            .keyword(kw)
        })
}

/// The index of the archived instant within PRECISION of `t` (relative to |t| unless
/// `a`'s CRITERE is 'ABSOLU'), if any.
pub fn matching(a: &Args, times: &[f64], t: f64) -> Result<Option<usize>> {
    let precision = a.req_real("PRECISION")?;
    let tol = if a.text("CRITERE") == Some("ABSOLU") {
        precision
    } else {
        precision * t.abs()
    };
    Ok(times.iter().position(|&s| (s - t).abs() <= tol))
}

/// The instants `a` asks for among the archived `times` (increasing); `interp_key` is the
/// keyword whose 'LIN' allows interpolation between archived instants (REST_GENE_PHYS's
/// INTERPOL, RECU_FONCTION's INTERP_NUME).
pub fn picks(a: &Args, times: &[f64], interp_key: &str) -> Result<Vec<Pick>> {
    let exact = |i: usize| Pick {
        t: times[i],
        lo: i,
        hi: i,
        w: 1.0,
    };
    if let Some(orders) = a.ints("NUME_ORDRE") {
        return orders
            .iter()
            .map(|&k| by_order(k, times, a.key_path("NUME_ORDRE")).map(exact))
            .collect();
    }
    let Some(wanted) = a.reals("INST").or_else(|| a.reals("LIST_INST")) else {
        return Ok((0..times.len()).map(exact).collect());
    };
    let interpolate = a.text(interp_key) == Some("LIN");
    let precision = a.req_real("PRECISION")?;
    wanted
        .iter()
        .map(|&t| {
            if let Some(i) = matching(a, times, t)? {
                return Ok(exact(i));
            }
            let hi = times.partition_point(|&s| s < t);
            if interpolate && hi > 0 && hi < times.len() {
                let (t0, t1) = (times[hi - 1], times[hi]);
                return Ok(Pick {
                    t,
                    lo: hi - 1,
                    hi,
                    w: (t1 - t) / (t1 - t0),
                });
            }
            let (first, last) = (times.first().copied(), times.last().copied());
            Err(Error::validation(match (interpolate, first, last) {
                (true, Some(f), Some(l)) => {
                    format!("INST = {t:e} is outside the archived interval [{f:e}, {l:e}]")
                }
                _ => format!(
                    "INST = {t:e} is not an archived instant (within PRECISION = {precision:e})"
                ),
            })
            .keyword(a.key_path(if a.has("INST") { "INST" } else { "LIST_INST" }))
            .hint(format!("give {interp_key}='LIN' to interpolate between archived instants, or archive it (DYNA_VIBRA's ARCHIVAGE/INST)")))
        })
        .collect()
}

/// The value at `p` of a quantity sampled at the archived instants by `at`.
pub fn value(p: &Pick, at: impl Fn(usize) -> f64) -> f64 {
    if p.lo == p.hi {
        at(p.lo)
    } else {
        p.w * at(p.lo) + (1.0 - p.w) * at(p.hi)
    }
}
