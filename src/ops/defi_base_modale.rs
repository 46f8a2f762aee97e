//! DEFI_BASE_MODALE: a Ritz basis as a `mode_meca`. RITZ puts the first vectors of several
//! bases end to end (normal modes, then static modes), optionally orthonormalised with
//! respect to a matrix (ORTHO='OUI'); ORTHO_BASE orthonormalises an existing basis. The
//! numerics are `linalg::ritz`; the result is saved as CALC_MODES saves its modes, so that
//! NUME_DDL_GENE, PROJ_*_BASE, DYNA_VIBRA and REST_GENE_PHYS take it as they take those.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::linalg::ritz::{self, Metric, DEPENDENCE_RATIO};
use crate::model::modes::{Mode, ModeMeca};
use crate::model::{AssembledMatrix, DofNumbering, MatrixKind};
use crate::store::{matrix, modes as mode_store};
use crate::table::print::format_e;

const OP: &str = "DEFI_BASE_MODALE";

/// One basis the result takes vectors from, as the call names it.
struct Source {
    name: String,
    /// The keyword that names it, for errors (`DEFI_BASE_MODALE/RITZ[2]/MODE_INTF`).
    keyword: String,
    modes: ModeMeca,
    /// NMAX_MODE: how many of its first vectors to keep (None: all).
    count: Option<usize>,
    /// The NMAX_MODE keyword of its occurrence, for the alarm of a count too large.
    count_keyword: String,
}

/// The basis to save, before it is saved.
struct Basis {
    numbering: DofNumbering,
    numbering_name: String,
    modes: Vec<Mode>,
    matrices: Option<mode_store::ModeMatrices>,
    /// What the summary line says of where the vectors come from.
    summary: String,
    /// Each vector's origin, for INFO=2.
    origins: Vec<String>,
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    refuse_unsupported(args)?;
    let name = match (ctx.reuse, ctx.result) {
        (Some(r), _) | (None, Some(r)) => r.to_string(),
        (None, None) => ctx.result_name()?.to_string(),
    };
    // Every input is read before the result is created: with reuse= the result replaces
    // the basis it extends.
    let basis = if args.has("RITZ") {
        ritz_basis(ctx, args)?
    } else {
        ortho_base(ctx, args)?
    };
    ctx.say(&format!(
        "{OP} {name}: {} vector(s): {}",
        basis.modes.len(),
        basis.summary
    ))?;
    if ctx.info >= 2 {
        ctx.say("  NUME_ORDRE  FREQUENCE (HZ)   MASS_GENE       RIGI_GENE       ORIGIN")?;
        for (m, origin) in basis.modes.iter().zip(&basis.origins) {
            ctx.say(&format!(
                "  {:>10}  {:>14}   {:>14}  {:>14}  {origin}",
                m.nume_ordre,
                format_e(m.freq, 6),
                format_e(m.mass_gene, 6),
                format_e(m.rigi_gene, 6)
            ))?;
        }
    }
    let result = ModeMeca {
        numbering: basis.numbering,
        numbering_name: basis.numbering_name,
        modes: basis.modes,
    };
    ctx.create(&name, "mode_meca")?;
    mode_store::save_modes(ctx.store, &name, &result)?;
    if let Some(m) = &basis.matrices {
        mode_store::save_matrices(ctx.store, &name, m)?;
    }
    Ok(())
}

/// CLASSIQUE, DIAG_MASS and INTERF_DYNA, refused by name; ORTHO_BASE with RITZ's own
/// keywords.
fn refuse_unsupported(args: &Args) -> Result<()> {
    if args.has("CLASSIQUE") {
        return Err(Error::validation(
            "CLASSIQUE (a Craig-Bampton basis on the interfaces of DEFI_INTERF_DYNA) is not supported",
        )
        .keyword(format!("{OP}/CLASSIQUE"))
        .hint(
            "build a Ritz basis of normal and static modes: RITZ=(_F(MODE_MECA=<CALC_MODES result>), \
             _F(MODE_INTF=<MODE_STATIQUE result>))",
        ));
    }
    if args.has("DIAG_MASS") {
        return Err(Error::validation(
            "DIAG_MASS (normal and static modes made orthogonal by diagonalising the mass) is not supported",
        )
        .keyword(format!("{OP}/DIAG_MASS"))
        .hint(
            "give the modes and static modes to RITZ with ORTHO='OUI' and MATRICE=<the mass>: \
             the basis comes out mass-orthonormal",
        ));
    }
    if args.has("INTERF_DYNA") {
        return Err(Error::validation(
            "INTERF_DYNA: interfaces (DEFI_INTERF_DYNA) are not supported",
        )
        .keyword(format!("{OP}/INTERF_DYNA"))
        .hint("drop INTERF_DYNA: the Ritz basis is the vectors of RITZ, end to end"));
    }
    if args.has("ORTHO_BASE") {
        let ortho = args.text("ORTHO") == Some("OUI");
        for (given, key) in [
            (ortho, "ORTHO"),
            (args.has("MATRICE"), "MATRICE"),
            (args.has("NUME_REF"), "NUME_REF"),
        ] {
            if given {
                return Err(Error::validation(format!(
                    "{key} belongs to RITZ; ORTHO_BASE orthonormalises with its own MATRICE"
                ))
                .keyword(format!("{OP}/{key}"))
                .hint("give the matrix inside ORTHO_BASE=_F(BASE=..., MATRICE=...)"));
            }
        }
    }
    Ok(())
}

/// RITZ: the vectors of its occurrences end to end, orthonormalised with ORTHO='OUI'.
fn ritz_basis(ctx: &mut OpContext<'_>, args: &Args) -> Result<Basis> {
    let mut sources: Vec<Source> = Vec::new();
    let occurrences = args.facts_or_empty("RITZ");
    let several = occurrences.len() > 1;
    for (i, occ) in occurrences.iter().enumerate() {
        let at = if several {
            format!("{OP}/RITZ[{}]", i + 1)
        } else {
            format!("{OP}/RITZ")
        };
        let Some(key) = ["MODE_MECA", "BASE_MODALE", "MODE_INTF"]
            .into_iter()
            .find(|k| occ.has(k))
        else {
            return Err(
                Error::validation("RITZ needs one of MODE_MECA, BASE_MODALE, MODE_INTF")
                    .keyword(at),
            );
        };
        let concepts = occ.concepts(key).unwrap_or_default();
        let counts = counts(occ, concepts.len(), &format!("{at}/NMAX_MODE"), key)?;
        for (c, count) in concepts.iter().zip(counts) {
            sources.push(Source {
                name: c.name.clone(),
                keyword: format!("{at}/{key}"),
                modes: mode_store::load_modes(ctx.store, &c.name)?,
                count,
                count_keyword: format!("{at}/NMAX_MODE"),
            });
        }
    }
    let Some(first) = sources.first() else {
        return Err(Error::validation("RITZ names no basis").keyword(format!("{OP}/RITZ")));
    };
    let (numbering, numbering_name) = match args.concept("NUME_REF") {
        Some(c) => (matrix::load_numbering(ctx.store, &c.name)?, c.name.clone()),
        None => (
            first.modes.numbering.clone(),
            first.modes.numbering_name.clone(),
        ),
    };
    let reference = match args.concept("NUME_REF") {
        Some(c) => format!("NUME_REF={}", c.name),
        None => format!("{} (the first basis)", first.name),
    };
    for s in &sources {
        check_numbering(
            &s.modes.numbering,
            &numbering,
            &s.name,
            &reference,
            &s.keyword,
        )?;
    }
    let parts: Vec<(&[Mode], Option<usize>)> = sources
        .iter()
        .map(|s| (s.modes.modes.as_slice(), s.count))
        .collect();
    let joined = ritz::concatenate(&parts);
    for &(p, asked, has) in &joined.short {
        let s = &sources[p];
        ctx.alarm(
            "DEFI_BASE_MODALE_2",
            &format!(
                "{}: NMAX_MODE={asked} for {}, which holds {has} vector(s): all {has} are kept",
                s.count_keyword, s.name
            ),
        )?;
    }
    if joined.items.is_empty() {
        return Err(Error::validation(
            "the basis would hold no vector: every NMAX_MODE is 0 or every basis is empty",
        )
        .keyword(format!("{OP}/RITZ"))
        .hint("keep at least one vector"));
    }
    let origins: Vec<String> = joined
        .origin
        .iter()
        .zip(&joined.items)
        .map(|(&(p, _), m)| format!("NUME_ORDRE {} of {}", m.nume_ordre, sources[p].name))
        .collect();
    let matrices = known_matrices(ctx, &sources, &numbering)?;
    let (modes, origins, summary) = if args.text("ORTHO") == Some("OUI") {
        let a = args.req_concept("MATRICE")?.name.clone();
        let modes = orthonormal_modes(
            ctx,
            &joined.items,
            &origins,
            &a,
            &format!("{OP}/MATRICE"),
            &numbering,
            matrices.as_ref(),
        )?;
        // `orthonormal_modes` leaves each vector's NUME_ORDRE at its input position.
        let kept: Vec<(usize, usize)> = modes
            .iter()
            .filter_map(|m| joined.origin.get(m.nume_ordre.wrapping_sub(1)).copied())
            .collect();
        let dropped = joined.items.len() - modes.len();
        let mut summary = per_source(&sources, &kept);
        if dropped > 0 {
            summary.push_str(&format!(" ({dropped} dependent vector(s) left out)"));
        }
        summary.push_str(&format!(", orthonormalised with respect to {a}"));
        let origins = ortho_origins(&modes, &origins);
        (modes, origins, summary)
    } else {
        let summary = per_source(&sources, &joined.origin);
        (joined.items, origins, summary)
    };
    Ok(Basis {
        numbering,
        numbering_name,
        modes: renumbered(modes),
        matrices,
        summary,
        origins,
    })
}

/// ORTHO_BASE: an existing basis orthonormalised.
fn ortho_base(ctx: &mut OpContext<'_>, args: &Args) -> Result<Basis> {
    let occ = args.req_fact("ORTHO_BASE")?;
    let base = occ.req_concept("BASE")?.name.clone();
    let modes = mode_store::load_modes(ctx.store, &base)?;
    let key = format!("{OP}/ORTHO_BASE/BASE");
    if modes.modes.is_empty() {
        return Err(Error::input(format!("{base} holds no vector")).keyword(key));
    }
    let source = Source {
        name: base.clone(),
        keyword: key,
        count: None,
        count_keyword: String::new(),
        modes,
    };
    let numbering = source.modes.numbering.clone();
    let sources = [source];
    let matrices = known_matrices(ctx, &sources, &numbering)?;
    let (a, a_key) = match (occ.concept("MATRICE"), &matrices) {
        (Some(c), _) => (c.name.clone(), format!("{OP}/ORTHO_BASE/MATRICE")),
        (None, Some(m)) => (m.mass.clone(), format!("{OP}/ORTHO_BASE/BASE")),
        (None, None) => {
            return Err(Error::input(format!(
                "{base} does not name the mass matrix it was computed with (or that matrix is no longer on its numbering)"
            ))
            .keyword(format!("{OP}/ORTHO_BASE/MATRICE"))
            .hint("give the matrix: ORTHO_BASE=_F(BASE=..., MATRICE=<the mass>)"));
        }
    };
    let [source] = sources;
    let origins: Vec<String> = source
        .modes
        .modes
        .iter()
        .map(|m| format!("NUME_ORDRE {} of {base}", m.nume_ordre))
        .collect();
    let modes = orthonormal_modes(
        ctx,
        &source.modes.modes,
        &origins,
        &a,
        &a_key,
        &numbering,
        matrices.as_ref(),
    )?;
    let dropped = source.modes.modes.len() - modes.len();
    let left_out = if dropped > 0 {
        format!(" ({dropped} dependent vector(s) left out)")
    } else {
        String::new()
    };
    Ok(Basis {
        numbering,
        numbering_name: source.modes.numbering_name,
        summary: format!("{base}{left_out}, orthonormalised with respect to {a}"),
        origins: ortho_origins(&modes, &origins),
        modes: renumbered(modes),
        matrices,
    })
}

/// The NMAX_MODE counts of an occurrence naming `n` concepts: one per concept, or none.
fn counts(occ: &Args, n: usize, keyword: &str, key: &str) -> Result<Vec<Option<usize>>> {
    let Some(given) = occ.ints("NMAX_MODE") else {
        return Ok(vec![None; n]);
    };
    if given.len() != n {
        return Err(Error::validation(format!(
            "NMAX_MODE gives {} count(s) for the {n} concept(s) of {key}",
            given.len()
        ))
        .keyword(keyword)
        .hint(format!(
            "give one count per concept of {key}, in their order, or none to keep every vector"
        )));
    }
    given
        .into_iter()
        .map(|c| {
            usize::try_from(c).map(Some).map_err(|_| {
                Error::validation(format!("NMAX_MODE={c}: a count is 0 or more")).keyword(keyword)
            })
        })
        .collect()
}

/// `of` on the numbering of the result: same mesh and DOFs.
fn check_numbering(
    of: &DofNumbering,
    reference: &DofNumbering,
    name: &str,
    reference_name: &str,
    keyword: &str,
) -> Result<()> {
    if of.mesh == reference.mesh && of.dofs == reference.dofs {
        return Ok(());
    }
    let what = if of.mesh != reference.mesh {
        format!("on the mesh {}, not {}", of.mesh, reference.mesh)
    } else {
        format!(
            "on {} DOFs that are not the {} DOFs",
            of.len(),
            reference.len()
        )
    };
    Err(Error::input(format!(
        "{name} is {what} of {reference_name}: the vectors of a basis share one DOF numbering"
    ))
    .keyword(keyword)
    .hint("compute every basis from matrices assembled on the same NUME_DDL (and mesh)"))
}

/// "3 of MODES, 1 of MSTAT".
fn per_source(sources: &[Source], origin: &[(usize, usize)]) -> String {
    let parts: Vec<String> = sources
        .iter()
        .enumerate()
        .map(|(p, s)| {
            let n = origin.iter().filter(|(q, _)| *q == p).count();
            format!("{n} of {}", s.name)
        })
        .collect();
    parts.join(", ")
}

/// The stiffness and mass the result refers to (PROJ_VECT_BASE's metric of coordinates,
/// DYNA_VIBRA's check of the shocks' flexibility): those of the first source that names
/// matrices still assembled on the numbering.
fn known_matrices(
    ctx: &OpContext<'_>,
    sources: &[Source],
    numbering: &DofNumbering,
) -> Result<Option<mode_store::ModeMatrices>> {
    for s in sources {
        let Some(m) = mode_store::load_matrices(ctx.store, &s.name)? else {
            continue;
        };
        let on_numbering = |a: &str| {
            matrix::load_matrix(ctx.store, a).is_ok_and(|a| a.numbering.dofs == numbering.dofs)
        };
        if on_numbering(&m.rigi) && on_numbering(&m.mass) {
            return Ok(Some(m));
        }
    }
    Ok(None)
}

/// The vectors of `modes` orthonormalised with respect to the matrix `a_name`, each with
/// its generalized mass and stiffness (1 for the matrix `a_name`, the other from
/// `matrices` when known, else 0) and its Rayleigh frequency. Dependent vectors are dropped
/// with alarm DEFI_BASE_MODALE_1.
fn orthonormal_modes(
    ctx: &mut OpContext<'_>,
    modes: &[Mode],
    origins: &[String],
    a_name: &str,
    a_key: &str,
    numbering: &DofNumbering,
    matrices: Option<&mode_store::ModeMatrices>,
) -> Result<Vec<Mode>> {
    let a = matrix::load_matrix(ctx.store, a_name)?;
    if a.numbering.dofs != numbering.dofs {
        return Err(Error::input(format!(
            "{a_name} is not assembled on the DOF numbering of the vectors ({} DOFs, the vectors {})",
            a.size(),
            numbering.len()
        ))
        .keyword(a_key)
        .hint("assemble the matrix on the NUME_DDL the bases were computed on"));
    }
    if a.kind == MatrixKind::AmorMeca {
        return Err(Error::input(format!(
            "{a_name} is a damping matrix (AMOR_MECA): the basis is orthonormalised with respect to a mass or a stiffness"
        ))
        .keyword(a_key)
        .hint("give the MASS_MECA (or RIGI_MECA) assembled matrix"));
    }
    let metric = Metric::new(a.size(), &a.triplets)?;
    let shapes: Vec<Vec<f64>> = modes.iter().map(|m| m.shape.clone()).collect();
    let ortho =
        ritz::orthonormalize(&metric, &shapes, DEPENDENCE_RATIO).map_err(|e| e.keyword(a_key))?;
    if !ortho.dropped.is_empty() {
        let names: Vec<String> = ortho
            .dropped
            .iter()
            .map(|d| {
                let origin = origins.get(d.index).map_or("", String::as_str);
                format!(
                    "vector {} ({origin}; what is left of it is {:.1e} of its norm)",
                    d.index + 1,
                    d.ratio
                )
            })
            .collect();
        ctx.alarm(
            "DEFI_BASE_MODALE_1",
            &format!(
                "{} vector(s) left out of the basis, dependent on the vectors before them in \
                 the metric of {a_name}: {}",
                names.len(),
                names.join(", ")
            ),
        )?;
    }
    if ortho.vectors.is_empty() {
        return Err(Error::input(format!(
            "no vector is left: {a_name} sees none of them (zero on every vector)"
        ))
        .keyword(a_key));
    }
    // The other matrix of the pair, for the other generalized quantity.
    let other_name = matrices.map(|m| match a.kind {
        MatrixKind::MassMeca => m.rigi.clone(),
        // (AMOR_MECA is refused above.)
        MatrixKind::RigiMeca | MatrixKind::AmorMeca => m.mass.clone(),
    });
    let other: Option<AssembledMatrix> = match other_name {
        Some(n) => Some(matrix::load_matrix(ctx.store, &n)?),
        None => None,
    };
    let other_metric = match &other {
        Some(o) => Some(Metric::new(o.size(), &o.triplets)?),
        None => None,
    };
    let mut out = Vec::with_capacity(ortho.vectors.len());
    for (q, &k) in ortho.vectors.into_iter().zip(&ortho.kept) {
        let other_gene = match &other_metric {
            Some(o) => o.form(&q, &q)?,
            None => 0.0,
        };
        let (mass_gene, rigi_gene) = match a.kind {
            MatrixKind::MassMeca => (1.0, other_gene),
            MatrixKind::RigiMeca | MatrixKind::AmorMeca => (other_gene, 1.0),
        };
        let (omega2, freq) = ritz::rayleigh_frequency(rigi_gene, mass_gene);
        out.push(Mode {
            nume_ordre: k + 1,
            freq,
            omega2,
            mass_gene,
            rigi_gene,
            shape: q,
            label: "DEPL".to_string(),
        });
    }
    Ok(out)
}

/// Where each orthonormalised vector comes from: its input vector (whose NUME_ORDRE
/// `orthonormal_modes` leaves as the input's position) minus its components on the vectors
/// before it.
fn ortho_origins(modes: &[Mode], origins: &[String]) -> Vec<String> {
    modes
        .iter()
        .map(|m| {
            let of = origins.get(m.nume_ordre.wrapping_sub(1));
            format!(
                "vector {} ({}) orthonormalised",
                m.nume_ordre,
                of.map_or("", String::as_str)
            )
        })
        .collect()
}

/// NUME_ORDRE 1..n in order.
fn renumbered(mut modes: Vec<Mode>) -> Vec<Mode> {
    for (i, m) in modes.iter_mut().enumerate() {
        m.nume_ordre = i + 1;
    }
    modes
}
