//! NORM_MODE: scales every mode of a `mode_meca` by one criterion (NORME, a node's
//! component, AVEC_CMP/SANS_CMP), then imposes a sign (MODE_SIGNE). Frequencies are
//! unchanged; MASS_GENE and RIGI_GENE scale with the square of the factor.
//!
//! Reentrant as in Code_Aster: `MODES = NORM_MODE(reuse=MODES, MODE=MODES, ...)` rewrites
//! the modes of MODES in place (its numbering and the 'matrices' it was computed from are
//! kept; the interpreter gives it a new generation, so that what was computed from the
//! old shapes, a NUME_DDL_GENE or a projection, is refused until recomputed). Assigned to
//! another name, the result is a new `mode_meca` with the same numbering, matrices and
//! dependencies as MODE, which is left as it was.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::linalg::eigen::norm::{
    euclidean_norm, generalized_scale, largest_component, quadratic_form, stiffness_is_round_off,
    ModeNorm,
};
use crate::model::dof::Cmp;
use crate::model::modes::ModeMeca;
use crate::model::AssembledMatrix;
use crate::ops::common::nodes::{one_node_of_group, OneNode};
use crate::ops::OpContext;
use crate::store::{matrix, modes as mode_store};
use crate::table::print::format_e;

const OP: &str = "NORM_MODE";

/// The criterion of the call, as the numerics take it, with the keyword that chose it and
/// how messages name it.
struct Criterion {
    norm: ModeNorm,
    keyword: String,
    what: String,
    /// NOEUD/NOM_CMP: the DOF made 1.
    point: Option<usize>,
}

/// MODE_SIGNE: the DOF whose sign is imposed, and that sign.
struct Sign {
    dof: usize,
    positive: bool,
    what: String,
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let src = args.req_concept("MODE")?.name.clone();
    let name = match (ctx.result, ctx.reuse) {
        (Some(r), _) | (None, Some(r)) => r.to_string(),
        (None, None) => ctx.result_name()?.to_string(),
    };
    // reuse_of = "MODE" in the catalog: a reuse= is MODE itself.
    let in_place = ctx.reuse == Some(name.as_str()) && name == src;
    if ctx.store.concept_operator(&src)?.as_deref() == Some("MODE_STATIQUE") {
        return Err(Error::validation(format!(
            "{src} is a MODE_STATIQUE result: its vectors are responses to unit \
             displacements, forces or accelerations, and scaling them would lose that meaning"
        ))
        .keyword(format!("{OP}/MODE"))
        .hint("normalise the vibration modes of CALC_MODES"));
    }
    // A redefinition without reuse= (`MODES = NORM_MODE(MODE=MODES)`) drops MODES's
    // dependencies with it: they are checked here and recorded again on the result.
    ctx.store.check_dependencies(&src)?;
    let dependencies = ctx.store.dependencies(&src)?;
    let mut modes = mode_store::load_modes(ctx.store, &src)?;
    let own = mode_store::load_matrices(ctx.store, &src)?;
    let criterion = criterion(ctx, args, &modes, &src)?;
    let sign = match args.fact("MODE_SIGNE") {
        Some(occ) => Some(mode_signe(ctx, occ, &modes, &src)?),
        None => None,
    };
    let masse = given_matrix(ctx, args, "MASSE", &modes, &src)?;
    let raide = given_matrix(ctx, args, "RAIDE", &modes, &src)?;
    // RIGI_GENE: the scale of K that tells a rigid-body mode's round-off φᵀKφ from a
    // stiffness (RAIDE, else the MATR_RIGI the modes were computed from when it is still
    // there on their numbering; without either, only a zero or negative value is refused).
    let k_scale = match (&criterion.norm, &raide) {
        (ModeNorm::RigiGene, Some(k)) => Some(diagonal_scale(k)),
        (ModeNorm::RigiGene, None) => own_stiffness_scale(ctx, own.as_ref(), &modes)?,
        _ => None,
    };

    // NOEUD/NOM_CMP on a DOF that is 0 in every mode (a blocked one): said in the error.
    let point_dead = criterion.point.is_some_and(|dof| {
        modes
            .modes
            .iter()
            .all(|m| m.shape.get(dof).copied().unwrap_or(0.0) == 0.0)
    });
    let mut rows: Vec<(usize, f64, f64, f64, f64)> = Vec::with_capacity(modes.modes.len());
    let mut unsigned: Vec<String> = Vec::new();
    for mode in &mut modes.modes {
        let n = mode.nume_ordre;
        let freq = mode.freq;
        // φᵀMφ and φᵀKφ before scaling: recomputed with MASSE, RAIDE when given, over the
        // full vector. The stored shape is u = T·q (zero on blocked DOFs, the dependent DOFs
        // of LIAISON_DDL relations completed from theirs), so uᵀAu over the full triplets is
        // qᵀ(TᵀAT)q, the form CALC_MODES computed on the free DOFs. Unlike reduced()/
        // restrict(), it does not depend on the matrix's own blocked DOFs and relations:
        // were they not the modes', the reduced form would drop or misplace components the
        // mode has, while the full form stays φᵀAφ of the vector as stored.
        let gm = match &masse {
            Some(m) => quadratic_form(&m.triplets, &mode.shape)?,
            None => mode.mass_gene,
        };
        let gk = match &raide {
            Some(k) => quadratic_form(&k.triplets, &mode.shape)?,
            None => mode.rigi_gene,
        };
        let mut scale = match &criterion.norm {
            ModeNorm::MassGene => generalized_scale(gm).ok_or_else(|| {
                let e = Error::numerical(format!(
                    "mode {n} ({freq:.6e} Hz) has the generalized mass {gm:e}: \
                     NORME='MASS_GENE' cannot make it 1"
                ))
                .keyword(criterion.keyword.clone());
                if masse.is_none() && own.is_none() {
                    e.hint(format!(
                        "{src} stores no generalized mass of its own (it was not computed \
                         by CALC_MODES): give the mass matrix, MASSE=..."
                    ))
                } else {
                    e.hint("a mode with no mass has no mass normalisation: choose another NORME")
                }
            })?,
            ModeNorm::RigiGene => {
                let pp: f64 = mode.shape.iter().map(|x| x * x).sum();
                let round_off = match k_scale {
                    Some(ks) => stiffness_is_round_off(gk, ks, pp),
                    None => generalized_scale(gk).is_none(),
                };
                match generalized_scale(gk).filter(|_| !round_off) {
                    Some(s) => s,
                    None => {
                        return Err(Error::numerical(format!(
                            "mode {n} ({freq:.6e} Hz) has the generalized stiffness {gk:e}, \
                             zero to round-off (a rigid-body mode?): NORME='RIGI_GENE' \
                             cannot make it 1"
                        ))
                        .keyword(criterion.keyword.clone())
                        .hint("use NORME='MASS_GENE' for a structure with rigid-body modes"))
                    }
                }
            }
            ModeNorm::LargestComponent { mask } => {
                let v = largest_component(&mode.shape, mask)?;
                zero_checked(1.0 / v, v, n, freq, &criterion, point_dead)?
            }
            ModeNorm::Euclidean { mask } => {
                let v = euclidean_norm(&mode.shape, mask)?;
                zero_checked(1.0 / v, v, n, freq, &criterion, point_dead)?
            }
        };
        if let Some(sign) = &sign {
            let v = mode.shape.get(sign.dof).copied().unwrap_or(0.0) * scale;
            if v == 0.0 {
                unsigned.push(n.to_string());
            } else if (v > 0.0) != sign.positive {
                scale = -scale;
            }
        }
        mode.shape.iter_mut().for_each(|x| *x *= scale);
        mode.mass_gene = gm * scale * scale;
        mode.rigi_gene = gk * scale * scale;
        rows.push((n, freq, scale, mode.mass_gene, mode.rigi_gene));
    }
    if let (Some(sign), false) = (&sign, unsigned.is_empty()) {
        ctx.alarm(
            "NORM_MODE_1",
            &format!(
                "{} is 0 in mode(s) {}: MODE_SIGNE cannot give it a sign, so they keep theirs",
                sign.what,
                unsigned.join(", ")
            ),
        )?;
    }
    report(ctx, &name, &criterion, &rows)?;

    if in_place {
        // The concept stays; its rows are replaced (numbering and matrices unchanged).
        return mode_store::save_modes(ctx.store, &name, &modes);
    }
    // A new concept (or MODE redefined under its own name: `create` drops the old one,
    // whose data were read above).
    ctx.create(&name, "mode_meca")?;
    mode_store::save_modes(ctx.store, &name, &modes)?;
    if let Some(m) = &own {
        mode_store::save_matrices(ctx.store, &name, m)?;
    }
    for (on, _) in &dependencies {
        // Checked above at the generation recorded: the same generation is recorded here.
        ctx.store.record_dependency(&name, on)?;
    }
    Ok(())
}

/// 1/v for a criterion whose value v (largest component, norm) may be zero: an error
/// naming the mode and the keyword then.
fn zero_checked(
    scale: f64,
    v: f64,
    n: usize,
    freq: f64,
    criterion: &Criterion,
    point_dead: bool,
) -> Result<f64> {
    if v != 0.0 && v.is_finite() && scale.is_finite() {
        return Ok(scale);
    }
    let e = Error::numerical(format!(
        "mode {n} ({freq:.6e} Hz) is 0 on {}: it cannot be normalised by it",
        criterion.what
    ))
    .keyword(criterion.keyword.clone());
    Err(match criterion.point {
        Some(_) if point_dead => {
            e.hint("that DOF is 0 in every mode (a blocked DOF is): choose a DOF the modes move")
        }
        Some(_) => e.hint("choose a DOF this mode moves, or NORME='TRAN_ROTA'"),
        None => e.hint("choose components this mode moves, or NORME='TRAN_ROTA'"),
    })
}

/// The criterion of the call: NORME, NOEUD|GROUP_NO with NOM_CMP, AVEC_CMP or SANS_CMP
/// (exactly one: the catalog's UN_PARMI).
fn criterion(ctx: &OpContext<'_>, args: &Args, modes: &ModeMeca, src: &str) -> Result<Criterion> {
    let dofs = &modes.numbering.dofs;
    let mask =
        |keep: &dyn Fn(Cmp) -> bool| -> Vec<bool> { dofs.iter().map(|d| keep(d.cmp)).collect() };
    let translation = |c: Cmp| matches!(c, Cmp::Dx | Cmp::Dy | Cmp::Dz);
    if !args.has("NOEUD") && !args.has("GROUP_NO") && args.has("NOM_CMP") {
        return Err(Error::validation(
            "NOM_CMP names the component of NOEUD or GROUP_NO, given alone",
        )
        .keyword(args.key_path("NOM_CMP"))
        .hint("add NOEUD= (or GROUP_NO=), or drop NOM_CMP"));
    }
    if let Some(norme) = args.text("NORME") {
        let norm = match norme {
            "MASS_GENE" => ModeNorm::MassGene,
            "RIGI_GENE" => ModeNorm::RigiGene,
            "EUCL" => ModeNorm::Euclidean {
                mask: mask(&|_| true),
            },
            "EUCL_TRAN" => ModeNorm::Euclidean {
                mask: mask(&translation),
            },
            "TRAN" => ModeNorm::LargestComponent {
                mask: mask(&translation),
            },
            "TRAN_ROTA" => ModeNorm::LargestComponent {
                mask: mask(&|_| true),
            },
            other => {
                return Err(
                    Error::validation(format!("NORME='{other}' is not supported"))
                        .keyword(args.key_path("NORME")),
                )
            }
        };
        return Ok(Criterion {
            norm,
            keyword: args.key_path("NORME"),
            what: match norme {
                "EUCL_TRAN" | "TRAN" => format!("its translations (NORME='{norme}')"),
                _ => format!("every component (NORME='{norme}')"),
            },
            point: None,
        });
    }
    if args.has("NOEUD") || args.has("GROUP_NO") {
        let (dof, what, keyword) = named_dof(ctx, args, modes, src)?;
        let mut one = vec![false; dofs.len()];
        if let Some(m) = one.get_mut(dof) {
            *m = true;
        }
        return Ok(Criterion {
            norm: ModeNorm::LargestComponent { mask: one },
            keyword,
            what,
            point: Some(dof),
        });
    }
    for (kw, keep_listed) in [("AVEC_CMP", true), ("SANS_CMP", false)] {
        let Some(names) = args.texts(kw) else {
            continue;
        };
        let listed = components(&names, &args.key_path(kw))?;
        let m = mask(&|c| listed.contains(&c) == keep_listed);
        if !m.iter().any(|&k| k) {
            return Err(Error::validation(format!(
                "{kw}={} leaves no DOF of {src}'s numbering to normalise on (its components: {})",
                names.join(", "),
                present_components(modes)
            ))
            .keyword(args.key_path(kw)));
        }
        return Ok(Criterion {
            norm: ModeNorm::LargestComponent { mask: m },
            keyword: args.key_path(kw),
            what: format!("the components {kw}={} selects", names.join(", ")),
            point: None,
        });
    }
    Err(Error::validation(
        "give one of NORME, NOEUD (or GROUP_NO) with NOM_CMP, AVEC_CMP, SANS_CMP",
    )
    .keyword(args.key_path("NORME")))
}

/// The components AVEC_CMP or SANS_CMP names. LAGR (Code_Aster's Lagrange multipliers,
/// which aster-nl does not have) names none.
fn components(names: &[String], keyword: &str) -> Result<Vec<Cmp>> {
    let mut out = Vec::new();
    for n in names {
        if n == "LAGR" {
            continue;
        }
        out.push(parse_cmp(n, keyword)?);
    }
    Ok(out)
}

fn parse_cmp(name: &str, keyword: &str) -> Result<Cmp> {
    Cmp::parse(name).ok_or_else(|| {
        let known = Cmp::ALL.map(Cmp::name);
        let mean = crate::suggest::did_you_mean(name, known);
        Error::validation(format!("unknown component '{name}'"))
            .keyword(keyword.to_string())
            .hint(format!("{mean}the components are {}", known.join(", ")))
    })
}

/// The components the numbering of the modes has, for messages.
fn present_components(modes: &ModeMeca) -> String {
    Cmp::ALL
        .into_iter()
        .filter(|c| modes.numbering.dofs.iter().any(|d| d.cmp == *c))
        .map(Cmp::name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The DOF named by NOEUD or GROUP_NO (one node) and NOM_CMP in `occ` (the call, or
/// MODE_SIGNE): its index in the numbering, how messages name it, and the keyword an
/// error about its value names.
fn named_dof(
    ctx: &OpContext<'_>,
    occ: &Args,
    modes: &ModeMeca,
    src: &str,
) -> Result<(usize, String, String)> {
    let dofs = &modes.numbering.dofs;
    let (node, node_kw) = match occ.text("NOEUD") {
        Some(n) => (n.to_string(), occ.key_path("NOEUD")),
        None => {
            let group = occ.req_text("GROUP_NO")?;
            let kw = occ.key_path("GROUP_NO");
            let node = one_node_of_group(
                ctx.store,
                &modes.numbering.mesh,
                group,
                OneNode {
                    reason: "NORM_MODE needs exactly one node",
                    hint: Some("use NOEUD=, or a GROUP_NO of one node"),
                },
                kw.clone(),
            )?;
            (node, kw)
        }
    };
    if !dofs.iter().any(|d| d.node == node) {
        let mut seen = std::collections::HashSet::new();
        let nodes: Vec<&str> = dofs
            .iter()
            .map(|d| d.node.as_str())
            .filter(|n| seen.insert(*n))
            .collect();
        let mean = crate::suggest::did_you_mean(&node, nodes.iter().copied());
        let shown: Vec<&str> = nodes.iter().take(20).copied().collect();
        return Err(Error::validation(format!(
            "{src} has no DOF on node '{node}' (its numbering {} does not have that node)",
            modes.numbering_name
        ))
        .keyword(node_kw)
        .hint(format!(
            "{mean}the numbering has DOFs on {} node(s): {}{}",
            nodes.len(),
            shown.join(", "),
            if nodes.len() > shown.len() {
                ", ..."
            } else {
                ""
            }
        )));
    }
    let cmp_kw = occ.key_path("NOM_CMP");
    let cmp = parse_cmp(occ.req_text("NOM_CMP")?, &cmp_kw)?;
    let dof = modes.numbering.index_of(&node, cmp).ok_or_else(|| {
        let has: Vec<&str> = dofs
            .iter()
            .filter(|d| d.node == node)
            .map(|d| d.cmp.name())
            .collect();
        Error::validation(format!(
            "node {node} has no DOF {cmp} in the numbering of {src} (its DOFs: {})",
            has.join(", ")
        ))
        .keyword(cmp_kw)
    })?;
    Ok((dof, format!("{cmp} of node {node}"), node_kw))
}

fn mode_signe(ctx: &OpContext<'_>, occ: &Args, modes: &ModeMeca, src: &str) -> Result<Sign> {
    let (dof, what, _) = named_dof(ctx, occ, modes, src)?;
    Ok(Sign {
        dof,
        positive: occ.req_text("SIGNE")? != "NEGATIF",
        what,
    })
}

/// MASSE or RAIDE, if given: it must be assembled on the modes' DOFs, and be of its kind.
fn given_matrix(
    ctx: &OpContext<'_>,
    args: &Args,
    kw: &str,
    modes: &ModeMeca,
    src: &str,
) -> Result<Option<AssembledMatrix>> {
    let Some(c) = args.concept(kw) else {
        return Ok(None);
    };
    let m = matrix::load_matrix(ctx.store, &c.name)?;
    if m.numbering.dofs != modes.numbering.dofs {
        return Err(Error::input(format!(
            "{} is assembled on other DOFs ({}) than the modes of {src} ({})",
            c.name,
            m.numbering.dofs.len(),
            modes.numbering.dofs.len()
        ))
        .keyword(args.key_path(kw))
        .hint(format!(
            "give a matrix assembled with the numbering of the modes, {}",
            modes.numbering_name
        )));
    }
    let want = match kw {
        "MASSE" => crate::model::elem::MatrixKind::MassMeca,
        _ => crate::model::elem::MatrixKind::RigiMeca,
    };
    if m.kind != want {
        return Err(Error::input(format!(
            "{} is a {} matrix, {kw} takes a {} matrix",
            c.name,
            m.kind.aster_name(),
            want.aster_name()
        ))
        .keyword(args.key_path(kw)));
    }
    Ok(Some(m))
}

/// The largest |A_ii| of a matrix.
fn diagonal_scale(a: &AssembledMatrix) -> f64 {
    a.triplets
        .iter()
        .filter(|(i, j, _)| i == j)
        .fold(0.0f64, |s, (_, _, v)| s.max(v.abs()))
}

/// [`diagonal_scale`] of the MATR_RIGI the modes were computed from, if that matrix is
/// still a matrix on their DOFs.
fn own_stiffness_scale(
    ctx: &OpContext<'_>,
    own: Option<&mode_store::ModeMatrices>,
    modes: &ModeMeca,
) -> Result<Option<f64>> {
    let Some(own) = own else {
        return Ok(None);
    };
    if ctx.store.concept_type(&own.rigi)?.as_deref() != Some("matr_asse_depl_r") {
        return Ok(None);
    }
    let k = matrix::load_matrix(ctx.store, &own.rigi)?;
    Ok((k.numbering.dofs == modes.numbering.dofs).then(|| diagonal_scale(&k)))
}

fn report(
    ctx: &mut OpContext<'_>,
    name: &str,
    criterion: &Criterion,
    rows: &[(usize, f64, f64, f64, f64)],
) -> Result<()> {
    let how = match criterion.norm {
        ModeNorm::MassGene => "MASS_GENE = 1".to_string(),
        ModeNorm::RigiGene => "RIGI_GENE = 1".to_string(),
        ModeNorm::Euclidean { .. } => format!("Euclidean norm of {} = 1", criterion.what),
        ModeNorm::LargestComponent { .. } => match criterion.point {
            Some(_) => format!("{} = 1", criterion.what),
            None => format!("largest |component| of {} = 1", criterion.what),
        },
    };
    ctx.say(&format!("{OP} {name}: {} mode(s), {how}", rows.len()))?;
    if ctx.info >= 2 {
        ctx.say("  NUME_ORDRE  FREQUENCE (HZ)        FACTEUR      MASS_GENE      RIGI_GENE")?;
        for &(n, freq, scale, gm, gk) in rows {
            ctx.say(&format!(
                "  {n:>10}  {:>14}  {:>13}  {:>13}  {:>13}",
                format_e(freq, 6),
                format_e(scale, 6),
                format_e(gm, 6),
                format_e(gk, 6)
            ))?;
        }
    }
    Ok(())
}
