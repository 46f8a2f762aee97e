//! The one node an operator keyword designates by `NOEUD=` or by a `GROUP_NO=` holding
//! exactly one node (TEST_RESU's RESU, MODE_NON_LINE's CHOC): resolved here only.

use crate::error::{Error, Result};
use crate::store::{mesh as mesh_store, Store};

/// Why a group of several nodes is refused, as the operator says it.
pub struct OneNode<'a> {
    /// End of the message after "GROUP_NO 'G' holds n nodes; ".
    pub reason: &'a str,
    /// Hint given with that message, if any.
    pub hint: Option<&'a str>,
}

/// The name of the only node of group `group` of mesh `mesh`; errors name the keyword
/// `kw_group` (the full keyword path of GROUP_NO).
pub fn one_node_of_group(
    store: &Store,
    mesh: &str,
    group: &str,
    why: OneNode<'_>,
    kw_group: String,
) -> Result<String> {
    let m = mesh_store::load_mesh(store, mesh)?;
    let g = m.node_group(group).ok_or_else(|| {
        Error::validation(format!("mesh {mesh} has no GROUP_NO '{group}'"))
            .keyword(kw_group.clone())
            .hint(crate::mesh::select::not_found_hint(
                group,
                "GROUP_NO",
                m.node_groups.iter().map(|g| g.name.as_str()),
            ))
    })?;
    match g.members.as_slice() {
        [one] => m
            .nodes
            .get(*one)
            .map(|n| n.name.clone())
            .ok_or_else(|| Error::internal(format!("GROUP_NO {group} names a missing node"))),
        members => {
            let e = Error::validation(format!(
                "GROUP_NO '{group}' holds {} nodes; {}",
                members.len(),
                why.reason
            ))
            .keyword(kw_group);
            Err(match why.hint {
                Some(h) => e.hint(h),
                None => e,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Group, Mesh, Node};

    fn store_with_groups() -> Store {
        let store = Store::in_memory().unwrap();
        let node = |name: &str, x: f64| Node {
            name: name.into(),
            coords: [x, 0.0, 0.0],
        };
        let mesh = Mesh {
            dim: 3,
            nodes: vec![node("N1", 0.0), node("N2", 1.0)],
            cells: vec![],
            node_groups: vec![
                Group {
                    name: "TIP".into(),
                    members: vec![1],
                },
                Group {
                    name: "BOTH".into(),
                    members: vec![0, 1],
                },
            ],
            cell_groups: vec![],
        };
        store
            .register_concept("MA", "maillage_sdaster", "LIRE_MAILLAGE", "t.comm", 1)
            .unwrap();
        crate::store::mesh::save_mesh(&store, "MA", &mesh).unwrap();
        store
    }

    fn why() -> OneNode<'static> {
        OneNode {
            reason: "one is needed",
            hint: Some("use NOEUD="),
        }
    }

    #[test]
    fn a_one_node_group_gives_its_node_and_others_are_refused_by_keyword() {
        let store = store_with_groups();
        let kw = || "CHOC/GROUP_NO".to_string();
        assert_eq!(
            one_node_of_group(&store, "MA", "TIP", why(), kw()).unwrap(),
            "N2"
        );
        let e = one_node_of_group(&store, "MA", "BOTH", why(), kw()).unwrap_err();
        assert_eq!(e.message, "GROUP_NO 'BOTH' holds 2 nodes; one is needed");
        assert_eq!(e.keyword.as_deref(), Some("CHOC/GROUP_NO"));
        assert_eq!(e.hint.as_deref(), Some("use NOEUD="));
        let e = one_node_of_group(&store, "MA", "NONE", why(), kw()).unwrap_err();
        assert_eq!(e.message, "mesh MA has no GROUP_NO 'NONE'");
        assert_eq!(e.keyword.as_deref(), Some("CHOC/GROUP_NO"));
        assert_eq!(
            e.hint.as_deref(),
            Some("the mesh has 2 GROUP_NO(s): TIP, BOTH")
        );
        let e = one_node_of_group(&store, "MA", "TPI", why(), kw()).unwrap_err();
        assert_eq!(
            e.hint.as_deref(),
            Some("did you mean 'TIP'? the mesh has 2 GROUP_NO(s): TIP, BOTH")
        );
    }
}
