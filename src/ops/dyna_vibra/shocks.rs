//! DYNA_VIBRA's shocks: each occurrence of COMPORTEMENT (RELATION='DIS_CHOC') or CHOC read
//! into the integrator's [`Shock`], with the names the result gives it.

use super::space::Space;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::ops::common::nodes::{one_node_of_group, OneNode};
use crate::ops::OpContext;
use crate::store::gene;
use crate::transient::{Friction, ObstacleKind, Shock, ShockSpec};

/// What the result says of a shock.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ShockName {
    /// INTITULE, by default "node1" or "node1 node2".
    pub intitule: String,
    pub node1: String,
    pub node2: Option<String>,
    /// The obstacle's TYPE.
    pub obstacle: String,
}

/// The shocks of a call, in order, with their names.
pub struct CallShocks {
    pub shocks: Vec<Shock>,
    pub names: Vec<ShockName>,
    /// (INTITULE, node) of each NOEUD_2 given with a one-node obstacle, ignored.
    pub ignored: Vec<(String, String)>,
}

/// The shocks of the call.
pub fn read(ctx: &OpContext<'_>, args: &Args, space: &Space, mesh: &Mesh) -> Result<CallShocks> {
    let occurrences = if args.has("COMPORTEMENT") {
        args.facts_or_empty("COMPORTEMENT")
    } else {
        args.facts_or_empty("CHOC")
    };
    let mut shocks = Vec::with_capacity(occurrences.len());
    let mut names = Vec::with_capacity(occurrences.len());
    let mut ignored = Vec::new();
    for occ in occurrences {
        let (shock, name, dropped) = one(ctx, occ, space, mesh)?;
        if let Some(n2) = dropped {
            ignored.push((name.intitule.clone(), n2));
        }
        if names
            .iter()
            .any(|n: &ShockName| n.intitule == name.intitule)
        {
            return Err(Error::validation(format!(
                "two shocks are named '{}': RECU_FONCTION could not tell them apart",
                name.intitule
            ))
            .keyword(occ.key_path("INTITULE"))
            .hint("give each shock its own INTITULE"));
        }
        shocks.push(shock);
        names.push(name);
    }
    Ok(CallShocks {
        shocks,
        names,
        ignored,
    })
}

/// One occurrence: the shock, its name, and the second node it ignores (NOEUD_2 given with
/// a one-node obstacle: Code_Aster's shock law takes a second node for the BI_ obstacles
/// only, and applies no force to it otherwise).
fn one(
    ctx: &OpContext<'_>,
    occ: &Args,
    space: &Space,
    mesh: &Mesh,
) -> Result<(Shock, ShockName, Option<String>)> {
    let obstacle_name = occ.req_concept("OBSTACLE")?.name.clone();
    let def = gene::load_obstacle(ctx.store, &obstacle_name)?;
    let obstacle = ObstacleKind::from_name(&def.kind).ok_or_else(|| {
        Error::input(format!(
            "obstacle {obstacle_name} has TYPE '{}', which DYNA_VIBRA does not know",
            def.kind
        ))
        .keyword(occ.key_path("OBSTACLE"))
    })?;
    let node1 = node(ctx, occ, space, "1")?.ok_or_else(|| {
        Error::validation("give NOEUD_1 or GROUP_NO_1").keyword(occ.key_path("NOEUD_1"))
    })?;
    let mut node2 = node(ctx, occ, space, "2")?;
    let dropped = if obstacle.two_nodes() {
        None
    } else {
        node2.take()
    };
    if obstacle.two_nodes() && node2.is_none() {
        return Err(Error::validation(format!(
            "OBSTACLE {obstacle_name} is a {}, a shock between two nodes: give NOEUD_2 or GROUP_NO_2",
            def.kind
        ))
        .keyword(occ.key_path("NOEUD_2")));
    }
    let rows = |name: &str, kw: &str| {
        space.node_rows(name).ok_or_else(|| {
            Error::input(format!(
                "node {name} has no DX, DY or DZ in the DOFs of the matrices"
            ))
            .keyword(occ.key_path(kw))
            .hint("a shock acts on the translations of a node of the model")
        })
    };
    let coords = |name: &str, kw: &str| {
        mesh.node_index(name)
            .map(|i| mesh.nodes[i].coords)
            .ok_or_else(|| {
                Error::input(format!("mesh {} has no node {name}", space.mesh()))
                    .keyword(occ.key_path(kw))
            })
    };
    let rows1 = rows(&node1, "NOEUD_1")?;
    let rows2 = match &node2 {
        Some(n) => Some(rows(n, "NOEUD_2")?),
        None => None,
    };
    let friction = match occ.req_text("FROTTEMENT")? {
        "COULOMB" => Friction::Coulomb {
            mu: occ.req_real("COULOMB")?,
        },
        "COULOMB_STAT_DYNA" => Friction::CoulombStatDyna {
            stat: occ.req_real("COULOMB_STAT")?,
            dyna: occ.req_real("COULOMB_DYNA")?,
        },
        _ => Friction::None,
    };
    let vec3 = |key: &str| -> Result<[f64; 3]> {
        let v = occ.req_reals(key)?;
        <[f64; 3]>::try_from(v.as_slice())
            .map_err(|_| Error::validation("expected three reals").keyword(occ.key_path(key)))
    };
    let spec = ShockSpec {
        obstacle,
        orig_obst: vec3("ORIG_OBST")?,
        norm_obst: vec3("NORM_OBST")?,
        angl_vril: occ.real("ANGL_VRIL"),
        node1: coords(&node1, "NOEUD_1")?,
        node2: match &node2 {
            Some(n) => Some(coords(n, "NOEUD_2")?),
            None => None,
        },
        jeu: occ.req_real("JEU")?,
        dist1: occ.req_real("DIST_1")?,
        dist2: occ.req_real("DIST_2")?,
        rigi_nor: occ.req_real("RIGI_NOR")?,
        amor_nor: occ.req_real("AMOR_NOR")?,
        rigi_tan: occ.req_real("RIGI_TAN")?,
        amor_tan: occ.real("AMOR_TAN").unwrap_or(0.0),
        friction,
    };
    let shock = Shock::new(spec, rows1, rows2).map_err(|e| in_occurrence(e.into(), occ))?;
    let intitule = occ
        .text("INTITULE")
        .map(str::to_string)
        .unwrap_or_else(|| match &node2 {
            Some(n2) => format!("{node1} {n2}"),
            None => node1.clone(),
        });
    Ok((
        shock,
        ShockName {
            intitule,
            node1,
            node2,
            obstacle: def.kind,
        },
        dropped,
    ))
}

/// The node of NOEUD_<which> or of a one-node GROUP_NO_<which>, if given.
fn node(ctx: &OpContext<'_>, occ: &Args, space: &Space, which: &str) -> Result<Option<String>> {
    if let Some(n) = occ.text(&format!("NOEUD_{which}")) {
        return Ok(Some(n.to_string()));
    }
    let Some(group) = occ.text(&format!("GROUP_NO_{which}")) else {
        return Ok(None);
    };
    one_node_of_group(
        ctx.store,
        space.mesh(),
        group,
        OneNode {
            reason: "a shock acts on exactly one node on each side",
            hint: Some("give the node with NOEUD_1=/NOEUD_2=, or a GROUP_NO of one node"),
        },
        occ.key_path(&format!("GROUP_NO_{which}")),
    )
    .map(Some)
}

/// An error of the integrator about a shock keyword ("CHOC/JEU") named by its path in this
/// occurrence ("DYNA_VIBRA/COMPORTEMENT[2]/JEU").
pub fn in_occurrence(mut e: Error, occ: &Args) -> Error {
    let key = e
        .keyword
        .as_deref()
        .and_then(|k| k.strip_prefix("CHOC/"))
        .map(|k| occ.key_path(k));
    if let Some(k) = key {
        e.keyword = Some(k);
    }
    e.keyword(occ.key_path("OBSTACLE"))
}
