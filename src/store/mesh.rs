//! Persistence of meshes (`maillage_sdaster`) in plain SQL tables, so users can query them:
//!
//! - `meshes(mesh, dim)`: one row per mesh.
//! - `mesh_nodes(mesh, idx, name, x, y, z)`
//! - `mesh_cells(mesh, idx, name, type, nodes)`: `type` is the Code_Aster name (`SEG2`),
//!   `nodes` the node names separated by spaces.
//! - `mesh_group_defs(mesh, kind, gidx, name)`: the groups in order (`kind` is `NO` or
//!   `MA`), so that empty groups survive a round trip.
//! - `mesh_groups(mesh, kind, name, pos, member_idx, member)`: one row per member, `pos`
//!   its place in the group, `member_idx` the node/cell index and `member` its name.
//!
//! [`load_mesh`] rebuilds exactly the [`Mesh`] that [`save_mesh`] wrote.

use super::{Schema, Store};
use crate::error::{Error, Result};
use crate::mesh::{Cell, CellKind, Group, Mesh, Node};
use rusqlite::params;
use std::collections::HashMap;

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS meshes (
    mesh TEXT PRIMARY KEY REFERENCES concepts(name) ON DELETE CASCADE,
    dim INTEGER NOT NULL
);
CREATE TABLE IF NOT EXISTS mesh_nodes (
    mesh TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    idx INTEGER NOT NULL,
    name TEXT NOT NULL,
    x REAL NOT NULL, y REAL NOT NULL, z REAL NOT NULL,
    PRIMARY KEY (mesh, idx)
);
CREATE TABLE IF NOT EXISTS mesh_cells (
    mesh TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    idx INTEGER NOT NULL,
    name TEXT NOT NULL,
    type TEXT NOT NULL,
    nodes TEXT NOT NULL,
    PRIMARY KEY (mesh, idx)
);
CREATE TABLE IF NOT EXISTS mesh_group_defs (
    mesh TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    kind TEXT NOT NULL CHECK (kind IN ('NO', 'MA')),
    gidx INTEGER NOT NULL,
    name TEXT NOT NULL,
    PRIMARY KEY (mesh, kind, gidx)
);
CREATE TABLE IF NOT EXISTS mesh_groups (
    mesh TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    kind TEXT NOT NULL CHECK (kind IN ('NO', 'MA')),
    name TEXT NOT NULL,
    pos INTEGER NOT NULL,
    member_idx INTEGER NOT NULL,
    member TEXT NOT NULL,
    PRIMARY KEY (mesh, kind, name, pos)
);
";

/// Create the mesh tables if they are not there yet.
pub fn ensure_schema(store: &Store) -> Result<()> {
    store.ensure_schema(Schema::Mesh, SCHEMA)
}

/// Delete every row of mesh `name` (nothing happens if the tables do not exist yet).
pub fn delete_mesh(store: &Store, name: &str) -> Result<()> {
    let exists: Option<i64> = store.row(
        "SELECT count(*) FROM sqlite_master WHERE type='table' AND name='meshes'",
        [],
        |r| r.get(0),
    )?;
    if exists.unwrap_or(0) == 0 {
        return Ok(());
    }
    for sql in [
        "DELETE FROM mesh_groups WHERE mesh = ?1",
        "DELETE FROM mesh_group_defs WHERE mesh = ?1",
        "DELETE FROM mesh_cells WHERE mesh = ?1",
        "DELETE FROM mesh_nodes WHERE mesh = ?1",
        "DELETE FROM meshes WHERE mesh = ?1",
    ] {
        store.exec(sql, params![name])?;
    }
    Ok(())
}

/// Save `mesh` as concept `name` (registered beforehand), replacing any previous rows.
/// The name the study's meshes give node `number` (1-based, in file order), when they all
/// agree on it (a mesh and the meshes CREA_MAILLAGE derived from it keep their nodes);
/// `None` when no mesh has that node or they disagree.
pub fn node_name_by_number(store: &Store, number: usize) -> Result<Option<String>> {
    ensure_schema(store)?;
    let Some(idx) = number.checked_sub(1).and_then(|i| i64::try_from(i).ok()) else {
        return Ok(None);
    };
    let conn = store.conn();
    let mut stmt =
        conn.prepare_cached("SELECT DISTINCT name FROM mesh_nodes WHERE idx = ?1 LIMIT 2")?;
    let names = stmt
        .query_map(params![idx], |r| r.get::<_, String>(0))?
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok(match names.as_slice() {
        [one] => Some(one.clone()),
        _ => None,
    })
}

pub fn save_mesh(store: &Store, name: &str, mesh: &Mesh) -> Result<()> {
    ensure_schema(store)?;
    delete_mesh(store, name)?;
    store.exec(
        "INSERT INTO meshes(mesh, dim) VALUES (?1, ?2)",
        params![name, mesh.dim as i64],
    )?;
    let conn = store.conn();
    let mut stmt = conn.prepare_cached(
        "INSERT INTO mesh_nodes(mesh, idx, name, x, y, z) VALUES (?1,?2,?3,?4,?5,?6)",
    )?;
    for (i, n) in mesh.nodes.iter().enumerate() {
        let [x, y, z] = n.coords;
        stmt.execute(params![name, i as i64, n.name, x, y, z])?;
    }
    let node_name = |i: usize| {
        mesh.nodes.get(i).map(|n| n.name.as_str()).ok_or_else(|| {
            Error::internal(format!(
                "mesh {name}: a cell uses node index {i}, out of range"
            ))
        })
    };
    let mut stmt = conn.prepare_cached(
        "INSERT INTO mesh_cells(mesh, idx, name, type, nodes) VALUES (?1,?2,?3,?4,?5)",
    )?;
    for (i, c) in mesh.cells.iter().enumerate() {
        let nodes = c
            .nodes
            .iter()
            .map(|&k| node_name(k))
            .collect::<Result<Vec<_>>>()?
            .join(" ");
        stmt.execute(params![name, i as i64, c.name, c.kind.aster_name(), nodes])?;
    }
    let cell_name = |i: usize| {
        mesh.cells.get(i).map(|c| c.name.as_str()).ok_or_else(|| {
            Error::internal(format!(
                "mesh {name}: a group uses cell index {i}, out of range"
            ))
        })
    };
    save_groups(conn, name, "NO", &mesh.node_groups, node_name)?;
    save_groups(conn, name, "MA", &mesh.cell_groups, cell_name)?;
    Ok(())
}

fn save_groups<'m>(
    conn: &rusqlite::Connection,
    mesh: &str,
    kind: &str,
    groups: &'m [Group],
    member_name: impl Fn(usize) -> Result<&'m str>,
) -> Result<()> {
    let mut def = conn.prepare_cached(
        "INSERT INTO mesh_group_defs(mesh, kind, gidx, name) VALUES (?1,?2,?3,?4)",
    )?;
    let mut mem = conn.prepare_cached(
        "INSERT INTO mesh_groups(mesh, kind, name, pos, member_idx, member) VALUES (?1,?2,?3,?4,?5,?6)",
    )?;
    for (gi, g) in groups.iter().enumerate() {
        def.execute(params![mesh, kind, gi as i64, g.name])?;
        for (pos, &m) in g.members.iter().enumerate() {
            mem.execute(params![
                mesh,
                kind,
                g.name,
                pos as i64,
                m as i64,
                member_name(m)?
            ])?;
        }
    }
    Ok(())
}

fn corrupt(name: &str, what: String) -> Error {
    Error::store(format!("stored mesh {name} is inconsistent: {what}"))
        .hint("the database was changed by hand or by another program; rerun the study")
}

fn to_index(name: &str, v: i64, what: &str) -> Result<usize> {
    usize::try_from(v).map_err(|_| corrupt(name, format!("negative {what} {v}")))
}

/// Rebuild mesh `name` from its rows.
pub fn load_mesh(store: &Store, name: &str) -> Result<Mesh> {
    ensure_schema(store)?;
    let conn = store.conn();
    let dim: Option<i64> = store.row(
        "SELECT dim FROM meshes WHERE mesh = ?1",
        params![name],
        |r| r.get(0),
    )?;
    let dim = dim.ok_or_else(|| Error::store(format!("no mesh named {name} in the store")))?;
    let mut mesh = Mesh {
        dim: to_index(name, dim, "dimension")?,
        ..Mesh::default()
    };

    let mut stmt =
        conn.prepare_cached("SELECT name, x, y, z FROM mesh_nodes WHERE mesh = ?1 ORDER BY idx")?;
    let rows = stmt.query_map(params![name], |r| {
        Ok(Node {
            name: r.get(0)?,
            coords: [r.get(1)?, r.get(2)?, r.get(3)?],
        })
    })?;
    mesh.nodes = rows.collect::<rusqlite::Result<Vec<_>>>()?;
    let node_idx: HashMap<&str, usize> = mesh
        .nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.name.as_str(), i))
        .collect();

    let mut stmt = conn
        .prepare_cached("SELECT name, type, nodes FROM mesh_cells WHERE mesh = ?1 ORDER BY idx")?;
    let rows = stmt.query_map(params![name], |r| {
        Ok((
            r.get::<_, String>(0)?,
            r.get::<_, String>(1)?,
            r.get::<_, String>(2)?,
        ))
    })?;
    let mut cells = Vec::new();
    for row in rows {
        let (cname, ty, nodes) = row?;
        let kind = CellKind::from_aster_name(&ty)
            .ok_or_else(|| corrupt(name, format!("cell {cname} has unknown type {ty}")))?;
        let nodes = nodes
            .split_whitespace()
            .map(|n| {
                node_idx
                    .get(n)
                    .copied()
                    .ok_or_else(|| corrupt(name, format!("cell {cname} uses unknown node {n}")))
            })
            .collect::<Result<Vec<_>>>()?;
        if nodes.len() != kind.node_count() {
            return Err(corrupt(
                name,
                format!("cell {cname} ({ty}) has {} nodes", nodes.len()),
            ));
        }
        cells.push(Cell {
            name: cname,
            kind,
            nodes,
        });
    }
    mesh.cells = cells;
    mesh.node_groups = load_groups(conn, name, "NO", mesh.nodes.len())?;
    mesh.cell_groups = load_groups(conn, name, "MA", mesh.cells.len())?;
    Ok(mesh)
}

fn load_groups(
    conn: &rusqlite::Connection,
    mesh: &str,
    kind: &str,
    count: usize,
) -> Result<Vec<Group>> {
    let mut stmt = conn.prepare_cached(
        "SELECT name FROM mesh_group_defs WHERE mesh = ?1 AND kind = ?2 ORDER BY gidx",
    )?;
    let names = stmt
        .query_map(params![mesh, kind], |r| r.get::<_, String>(0))?
        .collect::<rusqlite::Result<Vec<_>>>()?;
    let mut stmt = conn.prepare_cached(
        "SELECT member_idx FROM mesh_groups WHERE mesh = ?1 AND kind = ?2 AND name = ?3 ORDER BY pos",
    )?;
    let mut out = Vec::with_capacity(names.len());
    for g in names {
        let members = stmt
            .query_map(params![mesh, kind, g], |r| r.get::<_, i64>(0))?
            .collect::<rusqlite::Result<Vec<_>>>()?
            .into_iter()
            .map(|m| {
                let i = to_index(mesh, m, "group member")?;
                if i >= count {
                    return Err(corrupt(
                        mesh,
                        format!("group {g} member {i} is out of range"),
                    ));
                }
                Ok(i)
            })
            .collect::<Result<Vec<_>>>()?;
        out.push(Group { name: g, members });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::aster;

    fn sample() -> Mesh {
        let p =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/meshes/plate2d.mail");
        let mut m = aster::read_file(&p).unwrap();
        // An empty group must survive too.
        m.cell_groups.push(Group {
            name: "EMPTY".into(),
            members: vec![],
        });
        // Coordinates that are not short decimals.
        m.nodes[6].coords = [1.0 / 3.0, -2.0_f64.sqrt(), 1e-300];
        m
    }

    #[test]
    fn round_trip_is_exact() {
        let s = Store::in_memory().unwrap();
        s.register_concept("MAIL", "maillage_sdaster", "LIRE_MAILLAGE", "t.comm", 1)
            .unwrap();
        let m = sample();
        save_mesh(&s, "MAIL", &m).unwrap();
        assert_eq!(load_mesh(&s, "MAIL").unwrap(), m);
        // Saving again replaces, it does not add.
        save_mesh(&s, "MAIL", &m).unwrap();
        assert_eq!(load_mesh(&s, "MAIL").unwrap(), m);
    }

    #[test]
    fn tables_are_queryable() {
        let s = Store::in_memory().unwrap();
        s.register_concept("MAIL", "maillage_sdaster", "LIRE_MAILLAGE", "t.comm", 1)
            .unwrap();
        save_mesh(&s, "MAIL", &sample()).unwrap();
        let nodes: String = s
            .conn()
            .query_row(
                "SELECT nodes FROM mesh_cells WHERE mesh='MAIL' AND name='Q2'",
                [],
                |r| r.get(0),
            )
            .unwrap();
        assert_eq!(nodes, "A2 A3 A6 A5");
        let members: Vec<String> = s
            .conn()
            .prepare("SELECT member FROM mesh_groups WHERE mesh='MAIL' AND kind='MA' AND name='PLATE' ORDER BY pos")
            .unwrap()
            .query_map([], |r| r.get(0))
            .unwrap()
            .collect::<rusqlite::Result<_>>()
            .unwrap();
        assert_eq!(members, vec!["Q1", "Q2", "T1"]);
    }

    #[test]
    fn deleting_the_concept_removes_its_rows() {
        let s = Store::in_memory().unwrap();
        s.register_concept("MAIL", "maillage_sdaster", "LIRE_MAILLAGE", "t.comm", 1)
            .unwrap();
        save_mesh(&s, "MAIL", &sample()).unwrap();
        s.delete_concept("MAIL").unwrap();
        for t in [
            "meshes",
            "mesh_nodes",
            "mesh_cells",
            "mesh_group_defs",
            "mesh_groups",
        ] {
            let n: i64 = s
                .conn()
                .query_row(&format!("SELECT count(*) FROM {t}"), [], |r| r.get(0))
                .unwrap();
            assert_eq!(n, 0, "{t}");
        }
        let e = load_mesh(&s, "MAIL").unwrap_err();
        assert!(e.message.contains("no mesh named MAIL"), "{e}");
    }

    #[test]
    fn corrupted_rows_are_reported_not_panicked() {
        let s = Store::in_memory().unwrap();
        s.register_concept("MAIL", "maillage_sdaster", "LIRE_MAILLAGE", "t.comm", 1)
            .unwrap();
        save_mesh(&s, "MAIL", &sample()).unwrap();
        s.conn()
            .execute("UPDATE mesh_cells SET nodes='A1 ZZ' WHERE name='S1'", [])
            .unwrap();
        let e = load_mesh(&s, "MAIL").unwrap_err();
        assert!(e.message.contains("cell S1 uses unknown node ZZ"), "{e}");
    }
}
