//! DYNA_VIBRA's shocks: each occurrence of COMPORTEMENT (RELATION='DIS_CHOC' or
//! 'FLAMBAGE'), or of CHOC and FLAMBAGE (Code_Aster 13.x), read into the integrator's
//! [`Shock`], with the names the result gives it.

use super::space::Space;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::ops::common::nodes::{one_node_of_group, OneNode};
use crate::ops::OpContext;
use crate::store::gene;
use crate::transient::{Buckling, BucklingSpec, Friction, ObstacleKind, Shock, ShockSpec};

/// Code_Aster's ENFO_FL when a file cannot give it (the FLAMBAGE factor of 13.x): the
/// sudden drop from FNOR_CRIT to FNOR_POST_FL.
const SUDDEN_DROP: f64 = 1e-20;

/// The relation of a shock: RELATION of COMPORTEMENT, or the factor of 13.x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Relation {
    DisChoc,
    Flambage,
}

impl Relation {
    /// Code_Aster's RELATION name.
    pub fn name(self) -> &'static str {
        match self {
            Relation::DisChoc => "DIS_CHOC",
            Relation::Flambage => "FLAMBAGE",
        }
    }
}

/// What the result says of a shock.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ShockName {
    /// INTITULE, by default "node1" or "node1 node2".
    pub intitule: String,
    pub node1: String,
    pub node2: Option<String>,
    /// The obstacle's TYPE.
    pub obstacle: String,
    /// RELATION: 'DIS_CHOC' or 'FLAMBAGE'.
    pub relation: String,
    /// Whether it has friction (its stick/slip memory is stored).
    #[serde(default)]
    pub friction: bool,
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
    let occurrences = occurrences(args)?;
    let mut shocks = Vec::with_capacity(occurrences.len());
    let mut names = Vec::with_capacity(occurrences.len());
    let mut ignored = Vec::new();
    for (occ, relation) in occurrences {
        let (shock, name, dropped) = one(ctx, occ, relation, space, mesh)?;
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

/// The occurrences of the call's shocks with their relation, in the result's order:
/// COMPORTEMENT's as written, or (13.x) the CHOC ones then the FLAMBAGE ones, as
/// Code_Aster orders them.
pub fn occurrences(args: &Args) -> Result<Vec<(&Args, Relation)>> {
    if args.has("COMPORTEMENT") {
        return args
            .facts_or_empty("COMPORTEMENT")
            .iter()
            .map(|occ| {
                Ok(match occ.req_text("RELATION")? {
                    "FLAMBAGE" => (occ, Relation::Flambage),
                    _ => (occ, Relation::DisChoc),
                })
            })
            .collect();
    }
    let chocs = args.facts_or_empty("CHOC").iter();
    let flambages = args.facts_or_empty("FLAMBAGE").iter();
    Ok(chocs
        .map(|o| (o, Relation::DisChoc))
        .chain(flambages.map(|o| (o, Relation::Flambage)))
        .collect())
}

/// The buckling law of a FLAMBAGE occurrence (COMPORTEMENT with RELATION='FLAMBAGE', or the
/// FLAMBAGE factor of 13.x, which has no damping, plateau or post-buckling lists).
fn buckling_law(occ: &Args) -> Result<Buckling> {
    let list = |key: &str| occ.reals(key).unwrap_or_default();
    let spec = BucklingSpec {
        rigi_nor: occ.req_real("RIGI_NOR")?,
        amor_nor: occ.real("AMOR_NOR").unwrap_or(0.0),
        fnor_crit: occ.req_real("FNOR_CRIT")?,
        fnor_post_fl: occ.req_real("FNOR_POST_FL")?,
        enfo_fl: occ.real("ENFO_FL").unwrap_or(SUDDEN_DROP),
        larg_plat: occ.real("LARG_PLAT").unwrap_or(0.0),
        amor_fl: occ.real("AMOR_FL"),
        depl_post_fl: list("DEPL_POST_FL"),
        rigi_post_fl: list("RIGI_POST_FL"),
        amor_post_fl: list("AMOR_POST_FL"),
        rigi_nor_post_fl: occ.real("RIGI_NOR_POST_FL"),
        damping_in_criterion: occ.text("CRIT_AMOR") != Some("EXCLUS"),
    };
    Buckling::new(&spec).map_err(|e| in_occurrence(e.into(), occ))
}

/// One occurrence: the shock, its name, and the second node it ignores (NOEUD_2 given with
/// a one-node obstacle: Code_Aster's shock law takes a second node for the BI_ obstacles
/// only, and applies no force to it otherwise).
fn one(
    ctx: &OpContext<'_>,
    occ: &Args,
    relation: Relation,
    space: &Space,
    mesh: &Mesh,
) -> Result<(Shock, ShockName, Option<String>)> {
    let buckling = match relation {
        Relation::Flambage => Some(buckling_law(occ)?),
        Relation::DisChoc => None,
    };
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
    let friction = match occ.text("FROTTEMENT").unwrap_or("NON") {
        _ if buckling.is_some() => Friction::None,
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
        amor_nor: match &buckling {
            Some(law) => law.amor_nor,
            None => occ.req_real("AMOR_NOR")?,
        },
        rigi_tan: match &buckling {
            Some(_) => 0.0,
            None => occ.req_real("RIGI_TAN")?,
        },
        amor_tan: occ.real("AMOR_TAN").unwrap_or(0.0),
        friction,
        friction_along_x_only: friction.active() && occ.text("UNIDIRECTIONNEL") == Some("OUI"),
    };
    let mut shock = Shock::new(spec, rows1, rows2).map_err(|e| in_occurrence(e.into(), occ))?;
    if let Some(law) = buckling {
        shock = shock.with_buckling(law);
    }
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
            relation: relation.name().to_string(),
            friction: friction.active(),
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
        .and_then(|k| {
            k.strip_prefix("CHOC/")
                .or_else(|| k.strip_prefix("FLAMBAGE/"))
        })
        .map(|k| occ.key_path(k));
    if let Some(k) = key {
        e.keyword = Some(k);
    }
    e.keyword(occ.key_path("OBSTACLE"))
}
