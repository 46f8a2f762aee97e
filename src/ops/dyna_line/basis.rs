//! DYNA_LINE's modal basis (BASE_CALCUL='GENE'), as Code_Aster's macro builds it: the
//! modes of BANDE_ANALYSE (CALC_MODES OPTION='BANDE'); with ENRI_STAT='OUI' the static
//! modes after them, the pseudo-modes of the support accelerations (TYPE_APPUI='MONO'),
//! the static responses to the loads of EXCIT, then the attachment modes of the shocks'
//! nodes (MODE_STATIQUE), orthonormalised in the
//! stiffness (DEFI_BASE_MODALE); with ORTHO='OUI' the modes of the structure reduced on
//! that basis (`linalg::ritz::rayleigh_ritz`). Each step is the operator's own run.

use super::chain::{occurrence, Call};
use super::Assembled;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::linalg::ritz::{self, Metric};
use crate::model::modes::{Mode, ModeMeca};
use crate::ops::OpContext;
use crate::store::{matrix, modes as mode_store};
use crate::value::Value;

/// The basis built: its concept and the storage of its generalized matrices.
pub struct Basis {
    pub name: String,
    /// DIAG for normal modes (their generalized matrices are diagonal), PLEIN for the
    /// enriched basis as it is (orthonormal in the stiffness only).
    pub storage: &'static str,
}

/// Build the basis under `final_name` (BASE_RESU's name, or one of DYNA_LINE's own).
pub fn build(
    ctx: &mut OpContext<'_>,
    args: &Args,
    prefix: &str,
    mats: &Assembled,
    load_fields: &[String],
    final_name: &str,
) -> Result<Basis> {
    let band = band(args)?;
    let statics = static_sets(args, load_fields);
    let ortho = args.text("ORTHO") == Some("OUI");
    // The modes go straight to the final name when nothing follows them.
    let modes_name = if statics.is_empty() {
        final_name.to_string()
    } else {
        format!("{prefix}.MODES")
    };
    Call::new("CALC_MODES")
        .concept(ctx, "MATR_RIGI", &mats.rigi)?
        .concept(ctx, "MATR_MASS", &mats.mass)?
        .text("OPTION", "BANDE")
        .fact(
            "CALC_FREQ",
            vec![occurrence(
                "CALC_MODES",
                "CALC_FREQ",
                vec![(
                    "FREQ",
                    Value::Seq(vec![Value::Real(band.0), Value::Real(band.1)]),
                )],
            )],
        )
        .text("STOP_BANDE_VIDE", "NON")
        .run(ctx, Some(&modes_name), "DYNA_LINE/BANDE_ANALYSE", &[])?;
    let found = mode_store::load_modes(ctx.store, &modes_name)?.modes.len();
    if found == 0 {
        return Err(empty_band(ctx, mats, prefix, band));
    }
    let mut current = modes_name;
    let steps = statics.len() + usize::from(ortho && !statics.is_empty());
    for (i, set) in statics.iter().enumerate() {
        let stat_name = format!("{prefix}.STAT{}", i + 1);
        match set {
            StaticSet::Pseudo(directions) => Call::new("MODE_STATIQUE")
                .concept(ctx, "MATR_RIGI", &mats.rigi)?
                .concept(ctx, "MATR_MASS", &mats.mass)?
                .fact(
                    "PSEUDO_MODE",
                    directions
                        .iter()
                        .enumerate()
                        .map(|(j, d)| {
                            occurrence(
                                "MODE_STATIQUE",
                                "PSEUDO_MODE",
                                vec![
                                    ("DIRECTION", reals(d)),
                                    ("NOM_DIR", Value::Str(format!("DIR{}", j + 1))),
                                ],
                            )
                        })
                        .collect(),
                )
                .run(ctx, Some(&stat_name), "DYNA_LINE/EXCIT/DIRECTION", &[])?,
            StaticSet::Loads(fields) => crate::ops::mode_statique::save_load_responses(
                ctx,
                &stat_name,
                (&mats.rigi, &mats.mass),
                fields,
            )
            .map_err(|e| e.keyword("DYNA_LINE/EXCIT/CHARGE"))?,
            StaticSet::Shocks(nodes) => Call::new("MODE_STATIQUE")
                .concept(ctx, "MATR_RIGI", &mats.rigi)?
                .concept(ctx, "MATR_MASS", &mats.mass)?
                .fact("FORCE_NODALE", nodes.clone())
                .run(ctx, Some(&stat_name), "DYNA_LINE/COMPORTEMENT", &[])?,
        }
        let out = if i + 1 == steps {
            final_name.to_string()
        } else {
            format!("{prefix}.RITZ{}", i + 1)
        };
        let first = if i == 0 { "MODE_MECA" } else { "BASE_MODALE" };
        let ritz = vec![
            occurrence(
                "DEFI_BASE_MODALE",
                "RITZ",
                vec![(first, super::chain::concept(ctx, &current)?)],
            ),
            occurrence(
                "DEFI_BASE_MODALE",
                "RITZ",
                vec![("MODE_INTF", super::chain::concept(ctx, &stat_name)?)],
            ),
        ];
        Call::new("DEFI_BASE_MODALE")
            .fact("RITZ", ritz)
            .concept(ctx, "NUME_REF", &mats.nume)?
            .text("ORTHO", "OUI")
            .concept(ctx, "MATRICE", &mats.rigi)?
            .run(ctx, Some(&out), "DYNA_LINE/ENRI_STAT", &[])?;
        current = out;
    }
    if statics.is_empty() {
        return Ok(Basis {
            name: current,
            storage: "DIAG",
        });
    }
    if !ortho {
        return Ok(Basis {
            name: current,
            storage: "PLEIN",
        });
    }
    reduced_modes(ctx, mats, &current, final_name)?;
    Ok(Basis {
        name: final_name.to_string(),
        storage: "DIAG",
    })
}

/// (F_min, F_max) of BANDE_ANALYSE: one value is F_max from 0.
pub fn band(args: &Args) -> Result<(f64, f64)> {
    let values = args.reals("BANDE_ANALYSE").ok_or_else(|| {
        Error::validation("BASE_CALCUL='GENE' needs the band of the modes of the basis")
            .keyword("DYNA_LINE/BANDE_ANALYSE")
            .hint("give BANDE_ANALYSE=F_max or (F_min, F_max) in Hz (Code_Aster's cutoff from the spectrum of the excitation is not computed)")
    })?;
    let (lo, hi) = match values.as_slice() {
        [hi] => (0.0, *hi),
        [lo, hi] => (*lo, *hi),
        _ => {
            return Err(Error::validation("expected one or two frequencies")
                .keyword("DYNA_LINE/BANDE_ANALYSE"))
        }
    };
    if hi <= lo {
        return Err(Error::validation(format!(
            "the band ({lo}, {hi}) Hz is empty: F_max must exceed F_min"
        ))
        .keyword("DYNA_LINE/BANDE_ANALYSE"));
    }
    Ok((lo, hi))
}

/// The error of a band without a mode, with the structure's lowest frequency to help.
fn empty_band(ctx: &mut OpContext<'_>, mats: &Assembled, prefix: &str, band: (f64, f64)) -> Error {
    let lowest_name = format!("{prefix}.LOWEST");
    let lowest = Call::new("CALC_MODES")
        .concept(ctx, "MATR_RIGI", &mats.rigi)
        .and_then(|c| c.concept(ctx, "MATR_MASS", &mats.mass))
        .and_then(|c| {
            c.text("OPTION", "PLUS_PETITE")
                .fact(
                    "CALC_FREQ",
                    vec![occurrence(
                        "CALC_MODES",
                        "CALC_FREQ",
                        vec![("NMAX_FREQ", Value::Int(1))],
                    )],
                )
                .run(ctx, Some(&lowest_name), "DYNA_LINE/BANDE_ANALYSE", &[])
        })
        .and_then(|()| mode_store::load_modes(ctx.store, &lowest_name))
        .ok()
        .and_then(|m| m.modes.first().map(|m| m.freq));
    let e = Error::input(format!(
        "BANDE_ANALYSE ({}, {}) Hz holds no mode of the structure: the basis would be empty",
        band.0, band.1
    ))
    .keyword("DYNA_LINE/BANDE_ANALYSE");
    match lowest {
        Some(f) => e.hint(format!(
            "the lowest frequency of the structure is {f:.6e} Hz: widen the band to hold the modes that matter"
        )),
        None => e.hint("widen the band"),
    }
}

/// A set of static modes of ENRI_STAT, in Code_Aster's order.
enum StaticSet {
    /// Pseudo-modes along the TYPE_APPUI='MONO' directions.
    Pseudo(Vec<Vec<f64>>),
    /// The static responses to the loads of EXCIT (their assembled fields).
    Loads(Vec<String>),
    /// FORCE_NODALE occurrences at the shocks' nodes.
    Shocks(Vec<Args>),
}

fn static_sets(args: &Args, load_fields: &[String]) -> Vec<StaticSet> {
    if args.text("ENRI_STAT") != Some("OUI") {
        return Vec::new();
    }
    let mut sets = Vec::new();
    let directions: Vec<Vec<f64>> = args
        .facts_or_empty("EXCIT")
        .iter()
        .filter(|o| o.text("TYPE_APPUI") == Some("MONO"))
        .filter_map(|o| o.reals("DIRECTION"))
        .collect();
    if !directions.is_empty() {
        sets.push(StaticSet::Pseudo(directions));
    }
    if !load_fields.is_empty() {
        sets.push(StaticSet::Loads(load_fields.to_vec()));
    }
    let shocks = shock_nodes(args);
    if !shocks.is_empty() {
        sets.push(StaticSet::Shocks(shocks));
    }
    sets
}

/// FORCE_NODALE occurrences for the nodes of the shocks (node 1 and 2, by name or group),
/// each once: on NOM_CMP when the shock names it, else on the translations the structure
/// leaves free (the rotations excluded, blocked components skipped by MODE_STATIQUE), the
/// DOFs Code_Aster finds a unit force there moves.
fn shock_nodes(args: &Args) -> Vec<Args> {
    let mut nodes: Vec<String> = Vec::new();
    let mut groups: Vec<String> = Vec::new();
    for occ in args.facts_or_empty("COMPORTEMENT") {
        for key in ["NOEUD_1", "NOEUD_2", "GROUP_NO_1", "GROUP_NO_2"] {
            let list = if key.starts_with("NOEUD") {
                &mut nodes
            } else {
                &mut groups
            };
            for n in occ.texts(key).unwrap_or_default() {
                if !list.contains(&n) {
                    list.push(n);
                }
            }
        }
    }
    let without_rotations = || {
        Value::Seq(
            ["DRX", "DRY", "DRZ"]
                .iter()
                .map(|c| Value::Str((*c).to_string()))
                .collect(),
        )
    };
    let mut out = Vec::new();
    for (key, list) in [("NOEUD", nodes), ("GROUP_NO", groups)] {
        if list.is_empty() {
            continue;
        }
        out.push(occurrence(
            "MODE_STATIQUE",
            "FORCE_NODALE",
            vec![
                (key, Value::Seq(list.into_iter().map(Value::Str).collect())),
                ("SANS_CMP", without_rotations()),
            ],
        ));
    }
    out
}

fn reals(v: &[f64]) -> Value {
    Value::Seq(v.iter().map(|x| Value::Real(*x)).collect())
}

/// ORTHO='OUI': the modes of the structure reduced on the basis `from`, saved as the
/// mode_meca `name` (mass-normalised, FREQ from their ω²), named with the stiffness and
/// mass they were computed with.
fn reduced_modes(ctx: &mut OpContext<'_>, mats: &Assembled, from: &str, name: &str) -> Result<()> {
    let basis = mode_store::load_modes(ctx.store, from)?;
    let k = matrix::load_matrix(ctx.store, &mats.rigi)?;
    let m = matrix::load_matrix(ctx.store, &mats.mass)?;
    let km = Metric::new(k.size(), &k.triplets)?;
    let mm = Metric::new(m.size(), &m.triplets)?;
    let shapes: Vec<Vec<f64>> = basis.modes.iter().map(|m| m.shape.clone()).collect();
    let reduced =
        ritz::rayleigh_ritz(&km, &mm, &shapes).map_err(|e| e.keyword("DYNA_LINE/ORTHO"))?;
    let modes = reduced
        .omega2
        .iter()
        .zip(reduced.shapes)
        .enumerate()
        .map(|(i, (&w2, shape))| {
            let (omega2, freq) = ritz::rayleigh_frequency(w2, 1.0);
            Mode {
                nume_ordre: i + 1,
                freq,
                omega2,
                mass_gene: 1.0,
                rigi_gene: w2,
                shape,
                label: "DEPL".to_string(),
            }
        })
        .collect();
    let result = ModeMeca {
        numbering: basis.numbering,
        numbering_name: basis.numbering_name,
        modes,
    };
    ctx.create(name, "mode_meca")?;
    mode_store::save_modes(ctx.store, name, &result)?;
    mode_store::save_matrices(
        ctx.store,
        name,
        &mode_store::ModeMatrices {
            rigi: mats.rigi.clone(),
            mass: mats.mass.clone(),
        },
    )?;
    ctx.store.record_dependency(name, from)?;
    Ok(())
}
