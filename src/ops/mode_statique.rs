//! MODE_STATIQUE: static deformations (MODE_STAT, FORCE_NODALE, PSEUDO_MODE) stored as a
//! `mode_meca` whose vectors carry their NOEUD_CMP. Glue only: the keywords become
//! `StaticRequest`s, `model::static_shapes` computes them.

use super::common::resources::check_memory;
use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::linalg::static_modes::StaticError;
use crate::mesh::select::select_nodes;
use crate::mesh::Mesh;
use crate::model::modes::{Mode, ModeMeca, StaticKind, StaticTag};
use crate::model::static_shapes::{
    form_full, load_responses, static_shapes, StaticRequest, StaticShapeError,
};
use crate::model::{AssembledMatrix, Cmp};
use crate::store::{matrix, model, modes as mode_store};

const OP: &str = "MODE_STATIQUE";

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let k_name = args.req_concept("MATR_RIGI")?.name.clone();
    let m_name = args.concept("MATR_MASS").map(|c| c.name.clone());
    let k = matrix::load_matrix(ctx.store, &k_name)?;
    let m = match &m_name {
        Some(n) => Some(matrix::load_matrix(ctx.store, n)?),
        None => None,
    };
    k.refuse_damping(&k_name, &format!("{OP}/MATR_RIGI"))?;
    if let (Some(m), Some(mn)) = (&m, &m_name) {
        m.refuse_damping(mn, &format!("{OP}/MATR_MASS"))?;
        if !k.same_dofs(m) {
            return Err(Error::input(format!(
                "{k_name} and {mn} are not assembled on the same DOF numbering and boundary conditions"
            ))
            .keyword(format!("{OP}/MATR_MASS"))
            .hint("assemble both matrices with the same NUME_DDL and CHAR_CINE"));
        }
    }
    if args.has("MODE_INTERF") {
        return Err(Error::validation("interface modes are not computed")
            .keyword(format!("{OP}/MODE_INTERF"))
            .hint("MODE_STAT (constraint modes) or FORCE_NODALE (attachment modes) give the static part of a Ritz basis (DEFI_BASE_MODALE)"));
    }
    let mesh = model::load_mesh(ctx.store, &k.numbering.mesh)?;
    let (requests, tags) = requests(args, &k, &mesh)?;
    if requests.is_empty() {
        return Err(Error::validation(
            "the nodes and components given select no DOF of the right kind",
        )
        .keyword(OP)
        .hint("MODE_STAT takes blocked DOFs (DDL_IMPO, AFFE_CHAR_CINE); FORCE_NODALE free ones"));
    }
    // One right-hand side and one shape of the full numbering per request (TOUT='OUI' with
    // TOUT_CMP on a large model asks for many): checked before allocating.
    check_memory(
        OP,
        "the static deformations",
        2.0 * 8.0 * requests.len() as f64 * k.size() as f64,
    )?;
    let shapes = static_shapes(&k, m.as_ref(), &requests).map_err(|e| shape_error(e, &k))?;
    let mut modes = Vec::with_capacity(shapes.len());
    ctx.say(&format!(
        "{OP} {name}: {} static deformation(s)\n  NUME_ORDRE  NOEUD_CMP",
        shapes.len()
    ))?;
    for (shape, tag) in shapes.into_iter().zip(&tags) {
        ctx.say(&format!("  {:>10}  {}", tag.nume_ordre, tag.noeud_cmp()))?;
        modes.push(Mode {
            nume_ordre: tag.nume_ordre,
            freq: 0.0,
            omega2: 0.0,
            mass_gene: m.as_ref().map_or(0.0, |m| form_full(m, &shape, &shape)),
            rigi_gene: form_full(&k, &shape, &shape),
            shape,
            label: "DEPL".to_string(),
        });
    }
    let result = ModeMeca {
        numbering: k.numbering.clone(),
        numbering_name: matrix::matrix_numbering_name(ctx.store, &k_name)?,
        modes,
    };
    ctx.create(&name, "mode_meca")?;
    mode_store::save_modes(ctx.store, &name, &result)?;
    mode_store::save_static_tags(ctx.store, &name, &tags)?;
    if let Some(mn) = m_name {
        mode_store::save_matrices(
            ctx.store,
            &name,
            &mode_store::ModeMatrices {
                rigi: k_name,
                mass: mn,
            },
        )?;
    }
    Ok(())
}

/// The static responses K⁻¹f to the assembled load fields `fields` (DYNA_LINE's
/// enrichment by the loads of its EXCIT), saved as the mode_meca `name` as MODE_STATIQUE
/// saves its deformations (FREQ 0, generalized mass and stiffness, the matrices named),
/// without NOEUD_CMP: a response to a load is no DOF's.
pub(crate) fn save_load_responses(
    ctx: &mut OpContext<'_>,
    name: &str,
    (k_name, m_name): (&str, &str),
    fields: &[String],
) -> Result<()> {
    let k = matrix::load_matrix(ctx.store, k_name)?;
    let m = matrix::load_matrix(ctx.store, m_name)?;
    let mut loads = Vec::with_capacity(fields.len());
    for f in fields {
        let field = crate::store::gene::load_field(ctx.store, f)?;
        loads.push(super::proj_vect_base::field_on_numbering(
            &field,
            &k.numbering,
            f,
        )?);
    }
    let shapes = load_responses(&k, &loads).map_err(|e| shape_error(e, &k))?;
    ctx.say(&format!(
        "{OP} {name}: {} static response(s) to the loads",
        shapes.len()
    ))?;
    let modes = shapes
        .into_iter()
        .enumerate()
        .map(|(i, shape)| Mode {
            nume_ordre: i + 1,
            freq: 0.0,
            omega2: 0.0,
            mass_gene: form_full(&m, &shape, &shape),
            rigi_gene: form_full(&k, &shape, &shape),
            shape,
            label: "DEPL".to_string(),
        })
        .collect();
    let result = ModeMeca {
        numbering: k.numbering.clone(),
        numbering_name: matrix::matrix_numbering_name(ctx.store, k_name)?,
        modes,
    };
    ctx.create(name, "mode_meca")?;
    mode_store::save_modes(ctx.store, name, &result)?;
    mode_store::save_matrices(
        ctx.store,
        name,
        &mode_store::ModeMatrices {
            rigi: k_name.to_string(),
            mass: m_name.to_string(),
        },
    )
}

/// Every request of the call with its tag, numbered in order: MODE_STAT, FORCE_NODALE
/// and PSEUDO_MODE occurrences as written (one of them only, by the catalog's rule).
fn requests(
    args: &Args,
    k: &AssembledMatrix,
    mesh: &Mesh,
) -> Result<(Vec<StaticRequest>, Vec<StaticTag>)> {
    let mut reqs = Vec::new();
    let mut tags: Vec<StaticTag> = Vec::new();
    let mut push = |r: StaticRequest, kind: StaticKind, node: String, cmp: String| {
        reqs.push(r);
        let nume_ordre = tags.len() + 1;
        tags.push(StaticTag {
            nume_ordre,
            kind,
            node,
            cmp,
        });
    };
    for (key, kind) in [
        ("MODE_STAT", StaticKind::Imposed),
        ("FORCE_NODALE", StaticKind::Force),
    ] {
        for occ in args.facts_or_empty(key) {
            for i in dofs_of(occ, k, mesh, kind)? {
                let d = &k.numbering.dofs[i];
                let r = match kind {
                    StaticKind::Imposed => StaticRequest::Imposed(i),
                    _ => StaticRequest::Force(i),
                };
                push(r, kind, d.node.clone(), d.cmp.name().to_string());
            }
        }
    }
    for occ in args.facts_or_empty("PSEUDO_MODE") {
        for key in ["TOUT", "GROUP_NO"] {
            if occ.has(key) {
                return Err(
                    Error::validation("the pseudo-modes of each support are not computed")
                        .keyword(occ.key_path(key))
                        .hint("give AXE or DIRECTION (a unit acceleration of the whole structure)"),
                );
            }
        }
        for axis in occ.texts("AXE").unwrap_or_default() {
            let dir = match axis.as_str() {
                "X" => [1.0, 0.0, 0.0],
                "Y" => [0.0, 1.0, 0.0],
                _ => [0.0, 0.0, 1.0],
            };
            push(
                StaticRequest::Acceleration(dir),
                StaticKind::Acceleration,
                "ACCE".to_string(),
                axis,
            );
        }
        if let Some(d) = occ.reals("DIRECTION") {
            let dir = [
                d.first().copied().unwrap_or(0.0),
                d.get(1).copied().unwrap_or(0.0),
                d.get(2).copied().unwrap_or(0.0),
            ];
            let nom = occ.text("NOM_DIR").ok_or_else(|| {
                Error::validation("DIRECTION needs NOM_DIR, the name of the direction")
                    .keyword(occ.key_path("NOM_DIR"))
            })?;
            push(
                StaticRequest::Acceleration(dir),
                StaticKind::Acceleration,
                "ACCE".to_string(),
                nom.to_string(),
            );
        }
    }
    Ok((reqs, tags))
}

/// The DOFs (full indices, numbering order) an occurrence of MODE_STAT or FORCE_NODALE
/// selects: blocked ones for MODE_STAT, free ones for FORCE_NODALE. A DOF named
/// explicitly (NOEUD/GROUP_NO with AVEC_CMP) of the other status is an error; with TOUT
/// or TOUT_CMP/SANS_CMP the others are skipped, as Code_Aster does.
fn dofs_of(occ: &Args, k: &AssembledMatrix, mesh: &Mesh, kind: StaticKind) -> Result<Vec<usize>> {
    let nodes = select_nodes(mesh, &selection(occ))?;
    let names: std::collections::HashSet<&str> = nodes
        .iter()
        .filter_map(|&i| mesh.nodes.get(i).map(|n| n.name.as_str()))
        .collect();
    let cmps = components(occ)?;
    let explicit = !occ.has("TOUT") && occ.has("AVEC_CMP");
    let want_blocked = kind == StaticKind::Imposed;
    let mut out = Vec::new();
    for (i, d) in k.numbering.dofs.iter().enumerate() {
        if !names.contains(d.node.as_str()) || !cmps.contains(&d.cmp) {
            continue;
        }
        let blocked = k.eliminated.get(i).copied().unwrap_or(false);
        let usable = if want_blocked {
            blocked
        } else {
            k.reduced_index(i).is_some()
        };
        if usable {
            out.push(i);
        } else if explicit {
            let (what, fix) = if want_blocked {
                (
                    "is not blocked",
                    "MODE_STAT displaces blocked DOFs (AFFE_CHAR_MECA DDL_IMPO or AFFE_CHAR_CINE on the matrices); FORCE_NODALE loads free ones",
                )
            } else {
                (
                    "is blocked or expressed by a relation",
                    "FORCE_NODALE loads free DOFs; MODE_STAT displaces blocked ones",
                )
            };
            return Err(
                Error::validation(format!("DOF {} {} {what}", d.node, d.cmp.name()))
                    .keyword(occ.key_path("AVEC_CMP"))
                    .hint(fix),
            );
        }
    }
    Ok(out)
}

/// TOUT_CMP, AVEC_CMP or SANS_CMP as a set of components.
fn components(occ: &Args) -> Result<Vec<Cmp>> {
    let parse = |key: &str| -> Result<Vec<Cmp>> {
        occ.texts(key)
            .unwrap_or_default()
            .iter()
            .map(|c| {
                Cmp::parse(c.trim()).ok_or_else(|| {
                    Error::validation(format!("unknown component '{c}'"))
                        .keyword(occ.key_path(key))
                        .hint("the components are DX, DY, DZ, DRX, DRY, DRZ")
                })
            })
            .collect()
    };
    if occ.has("AVEC_CMP") {
        return parse("AVEC_CMP");
    }
    let without = parse("SANS_CMP")?;
    Ok(Cmp::ALL
        .into_iter()
        .filter(|c| !without.contains(c))
        .collect())
}

fn shape_error(e: StaticShapeError, k: &AssembledMatrix) -> Error {
    let dof = |i: usize| {
        k.numbering
            .dofs
            .get(i)
            .map(|d| format!("{} {}", d.node, d.cmp.name()))
            .unwrap_or_else(|| format!("DOF {i}"))
    };
    match e {
        StaticShapeError::Solver(StaticError::NotHeld) => Error::input(
            "the stiffness of the free DOFs is singular or not positive: the supports do not hold the structure, so it has no static deformation",
        )
        .keyword(format!("{OP}/MATR_RIGI"))
        .hint("block the rigid-body motions (AFFE_CHAR_MECA DDL_IMPO) in the matrices given"),
        StaticShapeError::WrongStatus { dof: i, blocked } => Error::validation(format!(
            "DOF {} is {}",
            dof(i),
            if blocked { "not free" } else { "not blocked" }
        ))
        .keyword(OP),
        StaticShapeError::NoMass => Error::validation("PSEUDO_MODE needs the mass")
            .keyword(format!("{OP}/MATR_MASS")),
        other => Error::internal(format!("{OP}: {other:?}")),
    }
}
