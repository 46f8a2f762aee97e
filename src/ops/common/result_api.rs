//! The methods of Code_Aster's Python API on a DYNA_VIBRA result that a command file calls
//! (`R.LIST_ARCH()`, `R.FORCE_NORMALE(i)`, `R.VARI_INTERNE(i)`; the language checks their
//! arguments, src/lang/eval/result_api.rs): the archived instants, a shock's normal force
//! and its internal variables in Code_Aster's order (shock_vint.rs), with the lines
//! Code_Aster prints beside them. Nonlinearity i is the i-th shock of the result.

use crate::error::{Error, Result};
use crate::ops::common::{shock_vint, tran_gene as common_tran_gene};
use crate::store::tran_gene::{self, StoredShock};
use crate::store::Store;
use crate::value::{ResultMethod, Value};

/// The value of `method` on the result `result`, and the lines to print before it.
pub fn call(store: &Store, result: &str, method: ResultMethod) -> Result<(Value, Vec<String>)> {
    let reals = |v: Vec<f64>| Value::Seq(v.into_iter().map(Value::Real).collect());
    let mut lines = Vec::new();
    match method {
        ResultMethod::ListArch => Ok((reals(tran_gene::archived_instants(store, result)?), lines)),
        ResultMethod::NormalForce(index) => {
            let payload = tran_gene::load_payload(store, result)?;
            let shock = nonlinearity(&payload.shocks, result, index, &mut lines)?;
            let t = common_tran_gene::shock_table(store, result, &payload)?;
            let (_, mut cols) = shock_vint::history(&t, result, shock, Some(1))?;
            Ok((reals(cols.pop().unwrap_or_default()), lines))
        }
        ResultMethod::InternalVariables { index, describe } => {
            let payload = tran_gene::load_payload(store, result)?;
            let shock = nonlinearity(&payload.shocks, result, index, &mut lines)?;
            let t = common_tran_gene::shock_table(store, result, &payload)?;
            let (times, cols) = shock_vint::history(&t, result, shock, None)?;
            if describe {
                let i = index.unwrap_or(1);
                lines.extend(description(shock, i));
            }
            let rows = (0..times.len())
                .map(|k| Value::Seq(cols.iter().map(|c| Value::Real(c[k])).collect()))
                .collect();
            Ok((Value::Seq(rows), lines))
        }
    }
}

/// The shock of index `index` (1-based, Code_Aster's `inoli`; `None`: the first, with
/// Code_Aster's note), or Code_Aster's errors.
fn nonlinearity<'a>(
    shocks: &'a [StoredShock],
    result: &str,
    index: Option<i64>,
    lines: &mut Vec<String>,
) -> Result<&'a StoredShock> {
    if shocks.is_empty() {
        return Err(Error::input(format!(
            "{result} is a linear calculation (no shock): no nonlinearity's values can be \
             retrieved"
        )));
    }
    let i = match index {
        Some(i) => i,
        None => {
            lines.push(
                "Nonlinearity index not specified, by default the first nonlinearity will be \
                 considered."
                    .to_string(),
            );
            1
        }
    };
    usize::try_from(i)
        .ok()
        .and_then(|i| i.checked_sub(1))
        .and_then(|i| shocks.get(i))
        .ok_or_else(|| {
            Error::input(format!(
                "the nonlinearity's index is {i}: it should be between 1 and {}, the number of \
                 nonlinearities of {result} ({})",
                shocks.len(),
                shocks
                    .iter()
                    .map(|s| s.intitule.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        })
}

/// The names of the internal variables, eight a line under their indices, as Code_Aster's
/// VARI_INTERNE prints them.
fn description(shock: &StoredShock, index: i64) -> Vec<String> {
    let rule = "-".repeat(104);
    let mut out = vec![
        rule.clone(),
        format!(
            "Information regarding the saved internal variables for {} non linearity \
             (index={index}, {})",
            shock_vint::law(shock),
            shock.intitule
        ),
        rule.clone(),
    ];
    let names = shock_vint::names(shock);
    for (k, chunk) in names.chunks(8).enumerate() {
        let idx: Vec<String> = (0..chunk.len())
            .map(|j| format!("{:^10}", k * 8 + j + 1))
            .collect();
        let nm: Vec<String> = chunk.iter().map(|n| format!("{n:^10}")).collect();
        out.push(idx.join(" | "));
        out.push(nm.join(" | "));
        out.push(rule.clone());
    }
    out
}
