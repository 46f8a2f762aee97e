//! AFFE_CHAR_MECA: imposed DOFs (DDL_IMPO), linear relations (LIAISON_DDL) and nodal
//! forces (FORCE_NODALE). Code_Aster dualises imposed DOFs and relations with Lagrange
//! multipliers; we eliminate them through the numbering (model::relations), which gives
//! the same modes. The forces are assembled by ASSE_VECTEUR.

use super::common::selection::{names, selection};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::select::{select_nodes, Names, Selection};
use crate::mesh::Mesh;
use crate::model::loads::{Condition, ImposedComponent, NodalRelation, RelationTerm};
use crate::model::{Cmp, KinematicLoad, LoadKind, Model};
use crate::store::model::{load_model_and_mesh, save_load};

/// FORCE_NODALE's keywords and the DOF each works on.
const FORCE_COMPONENTS: [(&str, Cmp); 6] = [
    ("FX", Cmp::Dx),
    ("FY", Cmp::Dy),
    ("FZ", Cmp::Dz),
    ("MX", Cmp::Drx),
    ("MY", Cmp::Dry),
    ("MZ", Cmp::Drz),
];

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    if !args.has("FORCE_NODALE") && !args.has("LIAISON_DDL") {
        return super::affe_char_cine::build(ctx, args, LoadKind::Meca, "DDL_IMPO", "char_meca");
    }
    let name = ctx.result_name()?.to_string();
    let model_name = args.req_concept("MODELE")?.name.clone();
    let (model, mesh) = load_model_and_mesh(ctx.store, &model_name)?;
    let mut load = super::affe_char_cine::kinematic_load(
        LoadKind::Meca,
        &model_name,
        &model,
        &mesh,
        args.facts_or_empty("DDL_IMPO"),
    )?;
    let occurrences = args
        .facts_or_empty("FORCE_NODALE")
        .iter()
        .map(force_condition)
        .collect::<Result<Vec<_>>>()?;
    load.forces = KinematicLoad::nodal_forces(&model, &mesh, &occurrences)?;
    load.relations = args
        .facts_or_empty("LIAISON_DDL")
        .iter()
        .map(|occ| relation(&model, &mesh, occ))
        .collect::<Result<Vec<_>>>()?;
    super::affe_char_cine::warn_nonzero(ctx, &load)?;
    if let Some(r) = load.relations.iter().find(|r| r.rhs != 0.0) {
        ctx.alarm(
            "MODEL_NONZERO_IMPO",
            &format!(
                "a LIAISON_DDL relation has COEF_IMPO = {}: modal analysis only uses the homogeneous relation (right-hand side 0), the value is stored but ignored",
                r.rhs
            ),
        )?;
    }
    ctx.create(&name, "char_meca")?;
    save_load(ctx.store, &name, &load)
}

/// One LIAISON_DDL occurrence: its nodes (GROUP_NO's members in order, or NOEUD), one
/// per DDL and COEF_MULT, each carrying its component in the model.
fn relation(model: &Model, mesh: &Mesh, occ: &Args) -> Result<NodalRelation> {
    let mut nodes: Vec<usize> = Vec::new();
    let groups = names(occ, "GROUP_NO");
    for g in &groups.names {
        // One group at a time: a group's members, in order; the same node may come back
        // in a later group (a relation between two components of one node).
        let one = Selection {
            node_groups: Names {
                names: vec![g.clone()],
                keyword: groups.keyword.clone(),
            },
            ..Selection::default()
        };
        nodes.extend(select_nodes(mesh, &one)?);
    }
    let listed = names(occ, "NOEUD");
    for n in &listed.names {
        let one = Selection {
            nodes: Names {
                names: vec![n.clone()],
                keyword: listed.keyword.clone(),
            },
            ..Selection::default()
        };
        nodes.extend(select_nodes(mesh, &one)?);
    }
    let ddl = occ.req_texts("DDL")?;
    let coefs = occ.req_reals("COEF_MULT")?;
    if ddl.len() != nodes.len() || coefs.len() != nodes.len() {
        return Err(Error::input(format!(
            "{} node(s), {} DDL and {} COEF_MULT: a relation needs one of each per term",
            nodes.len(),
            ddl.len(),
            coefs.len()
        ))
        .keyword(occ.key_path("DDL"))
        .hint("list a node (GROUP_NO of one node each, or NOEUD) for every DDL and COEF_MULT, repeating a node for two of its components"));
    }
    if coefs.iter().all(|&c| c == 0.0) {
        return Err(
            Error::input("every COEF_MULT is zero: the relation says nothing")
                .keyword(occ.key_path("COEF_MULT")),
        );
    }
    let carried = model.node_components(mesh);
    let mut terms = Vec::with_capacity(nodes.len());
    for ((&n, d), &coef) in nodes.iter().zip(&ddl).zip(&coefs) {
        let node = mesh.nodes.get(n).map_or("?", |x| x.name.as_str());
        let cmp = Cmp::parse(d).ok_or_else(|| {
            Error::validation(format!("unknown component {d}")).keyword(occ.key_path("DDL"))
        })?;
        if !carried.get(&n).is_some_and(|c| c.contains(&cmp)) {
            return Err(Error::input(format!(
                "component {cmp} does not exist on node {node} in the model"
            ))
            .keyword(occ.key_path("DDL"))
            .hint("each term's node must carry its component in the model (AFFE_MODELE)"));
        }
        terms.push(RelationTerm {
            node: node.to_string(),
            cmp,
            coef,
        });
    }
    Ok(NodalRelation {
        terms,
        rhs: occ.req_real("COEF_IMPO")?,
    })
}

fn force_condition(occ: &Args) -> Result<Condition> {
    let components: Vec<ImposedComponent> = FORCE_COMPONENTS
        .iter()
        .filter_map(|&(key, cmp)| {
            occ.real(key).map(|value| ImposedComponent {
                cmp,
                value,
                keyword: occ.key_path(key),
            })
        })
        .collect();
    if components.is_empty() {
        return Err(Error::input("no component given")
            .keyword(occ.path.clone())
            .hint("give at least one of FX FY FZ MX MY MZ"));
    }
    Ok(Condition {
        on: selection(occ),
        components,
        clamp: false,
        keyword: occ.path.clone(),
    })
}
