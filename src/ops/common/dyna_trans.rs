//! One component of one field of a `dyna_trans` as the keywords NOM_CHAM, NOEUD | GROUP_NO
//! and NOM_CMP designate it (TEST_RESU's RESU, RECU_FONCTION): resolved here only, with
//! errors naming the keyword and what was expected.

use super::nodes::{one_node_of_group, OneNode};
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::dyna_trans::{self as store, Layout, Samples};
use crate::store::{mesh as mesh_store, Store};

/// The samples over the stored instants of one component, and what they are.
#[derive(Clone, Debug)]
pub struct Component {
    pub field: &'static str,
    pub node: String,
    pub cmp: String,
    pub samples: Samples,
}

/// The component of `result` given by `a`'s NOM_CHAM, NOEUD or GROUP_NO, and NOM_CMP;
/// `kw` gives the full keyword path of a keyword, `why` ends the message refusing a group
/// of several nodes ("TEST_RESU tests one value").
pub fn component(
    st: &Store,
    a: &Args,
    result: &str,
    kw: &dyn Fn(&str) -> String,
    why: &str,
) -> Result<Component> {
    let field = field(st, a, result, kw)?;
    let layout = store::load_layout(st, result)?;
    let node = node(st, a, result, layout.as_ref(), kw, why)?;
    let cmp = a.req_text("NOM_CMP")?.to_string();
    let samples = store::samples(st, result, field, &node, &cmp)?;
    if samples.values.is_empty() {
        return Err(missing_component(
            st,
            result,
            layout.as_ref(),
            &node,
            &cmp,
            kw,
        ));
    }
    Ok(Component {
        field,
        node,
        cmp,
        samples,
    })
}

fn field(st: &Store, a: &Args, result: &str, kw: &dyn Fn(&str) -> String) -> Result<&'static str> {
    // NOM_CHAM has no default (Code_Aster's neither).
    let asked = a.req_text("NOM_CHAM")?;
    let stored = store::stored_fields(st, result)?;
    if let Some(f) = stored.iter().find(|f| **f == asked) {
        return Ok(f);
    }
    let e = Error::validation(format!(
        "NOM_CHAM='{asked}' is not stored in {result}, which holds {}",
        stored.join(", ")
    ))
    .keyword(kw("NOM_CHAM"));
    Err(if store::FIELDS.contains(&asked) {
        e.hint(format!(
            "{result} was written before REST_MODE_NONL stored {asked}: run REST_MODE_NONL \
             again, or use {}",
            stored.join(" or ")
        ))
    } else {
        e.hint(format!("use {}", stored.join(" or ")))
    })
}

fn node(
    st: &Store,
    a: &Args,
    result: &str,
    layout: Option<&Layout>,
    kw: &dyn Fn(&str) -> String,
    why: &str,
) -> Result<String> {
    if let Some(n) = a.text("NOEUD") {
        if let Some(l) = layout {
            let mesh = mesh_store::load_mesh(st, &l.mesh)?;
            if mesh.node_index(n).is_none() {
                return Err(Error::validation(format!(
                    "mesh {} of {result} has no node '{n}'",
                    l.mesh
                ))
                .keyword(kw("NOEUD"))
                .hint("give a node of the mesh, or a GROUP_NO of one node"));
            }
        }
        return Ok(n.to_string());
    }
    let group = a
        .text("GROUP_NO")
        .ok_or_else(|| Error::validation("expected NOEUD or GROUP_NO").keyword(kw("NOEUD")))?;
    let l = layout.ok_or_else(|| {
        Error::validation(format!(
            "{result} does not record its mesh (written by an older aster-nl): GROUP_NO \
             cannot be resolved"
        ))
        .keyword(kw("GROUP_NO"))
        .hint("give the node by NOEUD, or run REST_MODE_NONL again")
    })?;
    one_node_of_group(
        st,
        &l.mesh,
        group,
        OneNode {
            reason: why,
            hint: Some("give one node by NOEUD, or a GROUP_NO of one node (DEFI_GROUP)"),
        },
        kw("GROUP_NO"),
    )
}

/// Why `result` has no row of `node` `cmp`: a blocked DOF, a component not in the model,
/// or (without a layout) a node without rows at all.
fn missing_component(
    st: &Store,
    result: &str,
    layout: Option<&Layout>,
    node: &str,
    cmp: &str,
    kw: &dyn Fn(&str) -> String,
) -> Error {
    let stored = store::components_at(st, result, node).unwrap_or_default();
    let at = if stored.is_empty() {
        format!("{result} holds no component of {node}")
    } else {
        format!("{result} holds {} at {node}", stored.join(", "))
    };
    let blocked = layout.is_some_and(|l| l.blocked.iter().any(|(n, c)| n == node && c == cmp));
    let message = if blocked {
        format!(
            "component {cmp} of node {node} is blocked (eliminated by a boundary condition): \
             {at}, the free DOFs only"
        )
    } else if layout.is_some() {
        format!("node {node} has no component {cmp} in the model of {result}: {at}")
    } else {
        format!("{result} has no {cmp} of node {node} (blocked, or not in the model): {at}")
    };
    let e = Error::validation(message).keyword(kw("NOM_CMP"));
    if stored.is_empty() {
        e.hint("every DOF of this node is blocked or absent: choose another node")
    } else {
        e.hint(format!("use NOM_CMP={}", quoted(&stored)))
    }
}

fn quoted(cmps: &[String]) -> String {
    cmps.iter()
        .map(|c| format!("'{c}'"))
        .collect::<Vec<_>>()
        .join(" or ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::common::harness::{fact, k};
    use crate::table::{Cell, ColKind, Table};

    /// A time history as REST_MODE_NONL wrote it before accelerations and the layout were
    /// stored: DEPL and VITE of N2 DX at two instants, no `dyna_trans` payload.
    fn older_result() -> Store {
        let st = Store::in_memory().unwrap();
        st.register_concept("H", "dyna_trans", "REST_MODE_NONL", "t.comm", 1)
            .unwrap();
        let mut t = Table::new("old");
        for (c, kind) in [
            ("NUME_ORDRE", ColKind::I),
            ("INST", ColKind::R),
            ("NOEUD", ColKind::K),
            ("NOM_CMP", ColKind::K),
            ("DEPL", ColKind::R),
            ("VITE", ColKind::R),
        ] {
            t.add_column(c, kind).unwrap();
        }
        for (n, time, d, v) in [(1, 0.0, 0.01, 0.0), (2, 0.5, -0.01, 0.0)] {
            t.push_row(vec![
                Cell::I(n),
                Cell::R(time),
                Cell::K("N2".into()),
                Cell::K("DX".into()),
                Cell::R(d),
                Cell::R(v),
            ])
            .unwrap();
        }
        crate::store::table::save_table(&st, "H", &t).unwrap();
        st
    }

    fn get(st: &Store, keys: Vec<(&str, crate::value::Value)>) -> Result<Component> {
        let a = fact("RECU_FONCTION", keys);
        component(st, &a, "H", &|kw| a.key_path(kw), "one node")
    }

    #[test]
    fn an_older_result_reads_what_it_holds_and_says_what_it_lacks() {
        let st = older_result();
        let c = get(
            &st,
            vec![
                ("NOM_CHAM", k("DEPL")),
                ("NOEUD", k("N2")),
                ("NOM_CMP", k("DX")),
            ],
        )
        .unwrap();
        assert_eq!(
            (c.field, c.node.as_str(), c.cmp.as_str()),
            ("DEPL", "N2", "DX")
        );
        assert_eq!(c.samples.inst, vec![0.0, 0.5]);
        assert_eq!(c.samples.values, vec![0.01, -0.01]);
        assert_eq!(c.samples.nume_ordre, vec![1, 2]);

        let e = get(
            &st,
            vec![
                ("NOM_CHAM", k("ACCE")),
                ("NOEUD", k("N2")),
                ("NOM_CMP", k("DX")),
            ],
        )
        .unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("RECU_FONCTION/NOM_CHAM"));
        assert_eq!(
            e.message,
            "NOM_CHAM='ACCE' is not stored in H, which holds DEPL, VITE"
        );
        assert!(e.hint.unwrap().contains("run REST_MODE_NONL again"));

        let e = get(
            &st,
            vec![
                ("NOM_CHAM", k("DEPL")),
                ("GROUP_NO", k("G")),
                ("NOM_CMP", k("DX")),
            ],
        )
        .unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("RECU_FONCTION/GROUP_NO"));
        assert!(
            e.message.contains("does not record its mesh"),
            "{}",
            e.message
        );

        // Without a layout, a node or component without rows cannot be told apart.
        let e = get(
            &st,
            vec![
                ("NOM_CHAM", k("VITE")),
                ("NOEUD", k("N2")),
                ("NOM_CMP", k("DY")),
            ],
        )
        .unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("RECU_FONCTION/NOM_CMP"));
        assert_eq!(
            e.message,
            "H has no DY of node N2 (blocked, or not in the model): H holds DX at N2"
        );
        assert_eq!(e.hint.as_deref(), Some("use NOM_CMP='DX'"));
        let e = get(
            &st,
            vec![
                ("NOM_CHAM", k("VITE")),
                ("NOEUD", k("N7")),
                ("NOM_CMP", k("DX")),
            ],
        )
        .unwrap_err();
        assert!(
            e.message.ends_with("H holds no component of N7"),
            "{}",
            e.message
        );
    }
}
