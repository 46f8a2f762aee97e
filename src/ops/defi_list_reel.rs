//! DEFI_LIST_REEL: a list of reals, bound as a Python tuple (`ctx.value`).

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::value::Value;

/// The most values a list may have (80 MB of reals): a NOMBRE or PAS asking for more is an
/// error before anything is allocated.
const MAX_VALUES: f64 = 1e7;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let values = match args.reals("VALE") {
        Some(v) => {
            if let Some(w) = v.windows(2).position(|w| w[1] <= w[0] || w[1].is_nan()) {
                return Err(Error::validation(format!(
                    "VALE must increase: value {} ({:e}) is not above value {} ({:e})",
                    w + 2,
                    v[w + 1],
                    w + 1,
                    v[w]
                ))
                .keyword("DEFI_LIST_REEL/VALE"));
            }
            v
        }
        None => from_intervals(args)?,
    };
    ctx.value = Some(Value::Seq(values.into_iter().map(Value::Real).collect()));
    Ok(())
}

fn from_intervals(args: &Args) -> Result<Vec<f64>> {
    let mut start = args.req_real("DEBUT")?;
    let mut out = vec![start];
    for occ in args.facts_or_empty("INTERVALLE") {
        let end = occ.req_real("JUSQU_A")?;
        if end <= start || end.is_nan() {
            return Err(Error::validation(format!(
                "JUSQU_A = {end:e} is not above the start of its interval, {start:e}"
            ))
            .keyword(occ.key_path("JUSQU_A")));
        }
        let steps = match occ.int("NOMBRE") {
            Some(n) => n as f64,
            None => {
                let pas = occ.req_real("PAS")?;
                let ratio = (end - start) / pas;
                if (ratio - ratio.round()).abs() > 1e-6 * ratio.max(1.0) {
                    return Err(Error::validation(format!(
                        "PAS = {pas:e} does not divide [{start:e}, {end:e}] ({ratio} steps)"
                    ))
                    .keyword(occ.key_path("PAS"))
                    .hint("give NOMBRE, or a PAS that divides the interval"));
                }
                ratio.round()
            }
        };
        if out.len() as f64 + steps > MAX_VALUES {
            return Err(Error::validation(format!(
                "the list would hold more than {MAX_VALUES:e} values"
            ))
            .keyword(occ.key_path(if occ.has("NOMBRE") { "NOMBRE" } else { "PAS" })));
        }
        let n = steps as usize;
        out.extend((1..=n).map(|i| {
            if i == n {
                end
            } else {
                start + (end - start) * i as f64 / n as f64
            }
        }));
        start = end;
    }
    Ok(out)
}
