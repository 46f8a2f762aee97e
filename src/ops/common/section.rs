//! The section keywords of AFFE_CARA_ELEM's POUTRE and BARRE (SECTION, CARA, VALE) read
//! into the model's [`Section`]: which dimensions each shape takes, and that they are
//! positive. The properties themselves are computed by `model::cara`.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::cara::Section;

/// CARA names paired with VALE values, in the user's order.
fn named_values(occ: &Args) -> Result<Vec<(String, f64)>> {
    let names = occ.texts("CARA").unwrap_or_default();
    let vals = occ.reals("VALE").unwrap_or_default();
    if names.len() != vals.len() {
        return Err(Error::input(format!(
            "CARA has {} names but VALE has {} values",
            names.len(),
            vals.len()
        ))
        .keyword(occ.key_path("VALE"))
        .hint("give one value per CARA name, in the same order"));
    }
    Ok(names.into_iter().zip(vals).collect())
}

fn positive(occ: &Args, name: &str, v: f64) -> Result<f64> {
    if v > 0.0 && v.is_finite() {
        Ok(v)
    } else {
        Err(Error::input(format!("{name} must be positive, got {v}")).keyword(occ.key_path("VALE")))
    }
}

/// A beam section (POUTRE): CERCLE (R, EP), RECTANGLE (H, or HY and HZ) or GENERALE
/// (A, IY, IZ, JX).
pub(crate) fn beam_section(occ: &Args) -> Result<Section> {
    let kind = occ.req_text("SECTION")?.to_string();
    let vals = named_values(occ)?;
    let get = |n: &str| vals.iter().find(|(k, _)| k == n).map(|(_, v)| *v);
    let allowed: &[&str] = match kind.as_str() {
        "CERCLE" => &["R", "EP"],
        "RECTANGLE" => &["H", "HY", "HZ"],
        "GENERALE" => &["A", "IY", "IZ", "JX"],
        other => {
            return Err(Error::input(format!("SECTION {other} is not supported"))
                .keyword(occ.key_path("SECTION"))
                .hint("use CERCLE, RECTANGLE or GENERALE"))
        }
    };
    if let Some((bad, _)) = vals.iter().find(|(k, _)| !allowed.contains(&k.as_str())) {
        return Err(
            Error::input(format!("CARA {bad} is not available for SECTION='{kind}'"))
                .keyword(occ.key_path("CARA"))
                .hint(format!("expected among {}", allowed.join(", "))),
        );
    }
    let need = |n: &str| {
        get(n).ok_or_else(|| {
            Error::input(format!("SECTION='{kind}' needs CARA '{n}'")).keyword(occ.key_path("CARA"))
        })
    };
    let s = match kind.as_str() {
        "CERCLE" => {
            let r = positive(occ, "R", need("R")?)?;
            let ep = match get("EP") {
                None => None,
                Some(ep) => {
                    let ep = positive(occ, "EP", ep)?;
                    if ep > r {
                        return Err(Error::input(format!("EP = {ep} is larger than R = {r}"))
                            .keyword(occ.key_path("VALE")));
                    }
                    Some(ep)
                }
            };
            Section::circle(r, ep)
        }
        "RECTANGLE" => {
            let (hy, hz) = match (get("H"), get("HY"), get("HZ")) {
                (Some(h), None, None) => (h, h),
                (None, Some(hy), Some(hz)) => (hy, hz),
                _ => {
                    return Err(Error::input(
                        "SECTION='RECTANGLE' needs either H, or both HY and HZ",
                    )
                    .keyword(occ.key_path("CARA")))
                }
            };
            Section::rectangle(positive(occ, "HY", hy)?, positive(occ, "HZ", hz)?)
        }
        _ => {
            // Checked one after the other, as given: a missing property is reported
            // after the invalid ones before it.
            let a = positive(occ, "A", need("A")?)?;
            let iy = positive(occ, "IY", need("IY")?)?;
            let iz = positive(occ, "IZ", need("IZ")?)?;
            let jx = positive(occ, "JX", need("JX")?)?;
            Section::general(a, iy, iz, jx)
        }
    };
    Ok(s)
}

/// A bar section (BARRE): GENERALE with CARA 'A' alone, or CERCLE with 'R' (and 'EP').
pub(crate) fn bar_section(occ: &Args) -> Result<Section> {
    let kind = occ.req_text("SECTION")?;
    if kind == "GENERALE" {
        let vals = named_values(occ)?;
        return match vals.as_slice() {
            [(n, a)] if n == "A" => Ok(Section::bar(positive(occ, "A", *a)?)),
            _ => Err(
                Error::input("BARRE with SECTION='GENERALE' needs CARA='A' alone")
                    .keyword(occ.key_path("CARA")),
            ),
        };
    }
    if kind != "CERCLE" {
        return Err(
            Error::input(format!("SECTION {kind} is not supported for BARRE"))
                .keyword(occ.key_path("SECTION"))
                .hint("use GENERALE (CARA='A') or CERCLE (CARA='R')"),
        );
    }
    beam_section(occ)
}
