//! Reader of MED meshes (HDF5, MED 3.x/4.x layout), behind the cargo feature `med`.
//!
//! Layout used: `ENS_MAA/<mesh>/<time step>/NOE/COO` (coordinates, all x then all y...),
//! `NOE/FAM` (family of each node), `MAI/<type>/NOD` (1-based connectivity, first nodes
//! of all cells, then second nodes...), `MAI/<type>/FAM`, and `FAS/<mesh>/{NOEUD,ELEME}/
//! <family>` with attribute `NUM` and `GRO/NOM` (80-character group names). Groups are
//! made of every node/cell whose family lists them.
//!
//! Names: the optional `NOM` datasets (16 characters), else `N<k>` for the k-th node and
//! `M<k>` for the k-th cell, cells numbered type after type in Code_Aster's type order.

use super::{Cell, CellKind, Group, Mesh, Node};
use crate::error::{Error, Result};
use hdf5_metno as h5;
use std::collections::BTreeMap;
use std::path::Path;

/// MED type names, in the order cells are numbered.
const TYPES: [(&str, CellKind); 11] = [
    ("PO1", CellKind::Poi1),
    ("SE2", CellKind::Seg2),
    ("SE3", CellKind::Seg3),
    ("TR3", CellKind::Tria3),
    ("TR6", CellKind::Tria6),
    ("QU4", CellKind::Quad4),
    ("QU8", CellKind::Quad8),
    ("TE4", CellKind::Tetra4),
    ("HE8", CellKind::Hexa8),
    ("PE6", CellKind::Penta6),
    ("PY5", CellKind::Pyram5),
];

/// Read mesh `name` (or the first mesh) of the MED file at `path`.
pub fn read_file(path: &Path, name: Option<&str>) -> Result<Mesh> {
    let file = path.display().to_string();
    let bad = |what: String| {
        Error::input(format!("{file}: {what}")).hint(
            "the file should be a MED mesh file (written by SALOME, Code_Aster, gmsh or meshio)",
        )
    };
    let h5e = |ctx: &str| {
        let file = file.clone();
        let ctx = ctx.to_string();
        move |e: h5::Error| Error::input(format!("{file}: cannot read {ctx}: {e}"))
    };
    let f = h5::File::open(path).map_err(h5e("the file as HDF5"))?;
    let ens = f
        .group("ENS_MAA")
        .map_err(h5e("ENS_MAA (the list of meshes)"))?;
    let mut meshes = ens.member_names().map_err(h5e("ENS_MAA"))?;
    meshes.sort();
    let mesh_name = match name {
        Some(n) => meshes
            .iter()
            .find(|m| m.trim_end() == n)
            .cloned()
            .ok_or_else(|| {
                Error::input(format!("{file}: no mesh named '{n}' (NOM_MED)"))
                    .keyword("LIRE_MAILLAGE/NOM_MED")
                    .hint(format!("the file holds: {}", meshes.join(", ")))
            })?,
        None => meshes
            .first()
            .cloned()
            .ok_or_else(|| bad("the file holds no mesh".into()))?,
    };
    let mesh_group = ens.group(&mesh_name).map_err(h5e(&mesh_name))?;
    let space_dim: i64 = mesh_group
        .attr("ESP")
        .and_then(|a| a.read_scalar())
        .map_err(h5e("the space dimension (ESP)"))?;
    let dim = usize::try_from(space_dim)
        .ok()
        .filter(|d| (1..=3).contains(d))
        .ok_or_else(|| bad(format!("space dimension {space_dim} is not 1, 2 or 3")))?;
    // MED 3 stores the mesh under a time-step group; older files have NOE directly.
    let step = if mesh_group.link_exists("NOE") {
        mesh_group
    } else {
        let mut steps = mesh_group.member_names().map_err(h5e(&mesh_name))?;
        steps.sort();
        let s = steps
            .first()
            .ok_or_else(|| bad(format!("mesh {mesh_name} has no nodes")))?;
        mesh_group.group(s).map_err(h5e(s))?
    };

    // Nodes
    let noe = step.group("NOE").map_err(h5e("NOE (nodes)"))?;
    let coo: Vec<f64> = noe
        .dataset("COO")
        .and_then(|d| d.read_raw())
        .map_err(h5e("NOE/COO (coordinates)"))?;
    if !coo.len().is_multiple_of(dim) {
        return Err(bad(format!(
            "{} coordinates is not a multiple of the dimension {dim}",
            coo.len()
        )));
    }
    let n_nodes = coo.len() / dim;
    if let Some(i) = coo.iter().position(|c| !c.is_finite()) {
        return Err(bad(format!(
            "node {} has the coordinate {}: coordinates must be finite numbers",
            i % n_nodes.max(1) + 1,
            coo[i]
        )));
    }
    let node_names = read_names(&noe, 16, n_nodes).map_err(h5e("NOE/NOM (node names)"))?;
    let nodes: Vec<Node> = (0..n_nodes)
        .map(|i| {
            let mut c = [0.0; 3];
            for (k, ck) in c.iter_mut().enumerate().take(dim) {
                *ck = coo[k * n_nodes + i];
            }
            Node {
                name: node_names
                    .as_ref()
                    .and_then(|n| n.get(i).cloned())
                    .unwrap_or_else(|| format!("N{}", i + 1)),
                coords: c,
            }
        })
        .collect();
    let node_fam = read_fam(&noe, n_nodes).map_err(h5e("NOE/FAM (node families)"))?;

    // Cells
    let mai = step.group("MAI").map_err(h5e("MAI (cells)"))?;
    let present = mai.member_names().map_err(h5e("MAI"))?;
    if let Some(t) = present.iter().find(|t| !TYPES.iter().any(|(m, _)| m == t)) {
        return Err(bad(format!("MED cell type {t} is not supported"))
            .hint("supported: PO1 SE2 SE3 TR3 TR6 QU4 QU8 TE4 HE8 PE6 PY5"));
    }
    let mut cells = Vec::new();
    let mut cell_fam = Vec::new();
    for (med, kind) in TYPES {
        if !present.iter().any(|t| t == med) {
            continue;
        }
        let g = mai.group(med).map_err(h5e(med))?;
        let nod: Vec<i64> = g
            .dataset("NOD")
            .and_then(|d| d.read_raw())
            .map_err(h5e(&format!("MAI/{med}/NOD")))?;
        let nn = kind.node_count();
        if !nod.len().is_multiple_of(nn) {
            return Err(bad(format!(
                "MAI/{med}/NOD has {} entries, not a multiple of {nn}",
                nod.len()
            )));
        }
        let count = nod.len() / nn;
        let names = read_names(&g, 16, count).map_err(h5e(&format!("MAI/{med}/NOM")))?;
        cell_fam.extend(read_fam(&g, count).map_err(h5e(&format!("MAI/{med}/FAM")))?);
        for i in 0..count {
            let nodes = (0..nn)
                .map(|k| {
                    let n = nod[k * count + i];
                    usize::try_from(n - 1)
                        .ok()
                        .filter(|&j| j < n_nodes)
                        .ok_or_else(|| {
                            bad(format!("a {med} cell uses node {n}, outside 1..{n_nodes}"))
                        })
                })
                .collect::<Result<Vec<_>>>()?;
            let k = cells.len() + 1;
            cells.push(Cell {
                name: names
                    .as_ref()
                    .and_then(|n| n.get(i).cloned())
                    .unwrap_or_else(|| format!("M{k}")),
                kind,
                nodes,
            });
        }
    }

    // Families -> groups
    let fas = f.group("FAS").and_then(|g| g.group(&mesh_name)).ok();
    let families = |kind: &str| -> Result<BTreeMap<i64, Vec<String>>> {
        match fas.as_ref().filter(|g| g.link_exists(kind)) {
            Some(g) => read_families(&g.group(kind).map_err(h5e(kind))?)
                .map_err(h5e(&format!("FAS/{mesh_name}/{kind}"))),
            None => Ok(BTreeMap::new()),
        }
    };
    let node_groups = groups_of(&node_fam, &families("NOEUD")?);
    let cell_groups = groups_of(&cell_fam, &families("ELEME")?);
    Ok(Mesh {
        dim,
        nodes,
        cells,
        node_groups,
        cell_groups,
    })
}

/// Family numbers of `count` entities (0, no family, when the dataset is absent).
fn read_fam(g: &h5::Group, count: usize) -> h5::Result<Vec<i64>> {
    if !g.link_exists("FAM") {
        return Ok(vec![0; count]);
    }
    let v: Vec<i64> = g.dataset("FAM")?.read_raw()?;
    if v.len() != count {
        return Err(h5::Error::from(format!(
            "{} family numbers for {count} entities",
            v.len()
        )));
    }
    Ok(v)
}

/// Fixed-width names (`NOM` dataset), if present: `count` names of `width` characters.
fn read_names(g: &h5::Group, width: usize, count: usize) -> h5::Result<Option<Vec<String>>> {
    if !g.link_exists("NOM") {
        return Ok(None);
    }
    let chars = read_chars(&g.dataset("NOM")?)?;
    if chars.len() != width * count {
        return Err(h5::Error::from(format!(
            "{} characters for {count} names of {width}",
            chars.len()
        )));
    }
    Ok(Some(chars.chunks(width).map(text).collect()))
}

/// The bytes of a character dataset, whether stored as arrays of 80 (or 16) bytes or as a
/// 2D byte table.
fn read_chars(d: &h5::Dataset) -> h5::Result<Vec<u8>> {
    if let Ok(v) = d.read_raw::<[u8; 80]>() {
        return Ok(v.concat());
    }
    if let Ok(v) = d.read_raw::<[u8; 16]>() {
        return Ok(v.concat());
    }
    d.read_raw::<u8>()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes)
        .trim_end_matches(['\0', ' '])
        .trim()
        .to_string()
}

/// `family number -> group names` of one FAS branch (NOEUD or ELEME).
fn read_families(g: &h5::Group) -> h5::Result<BTreeMap<i64, Vec<String>>> {
    let mut out = BTreeMap::new();
    for fam in g.member_names()? {
        let fg = g.group(&fam)?;
        let num: i64 = fg.attr("NUM")?.read_scalar()?;
        let names = if fg.link_exists("GRO") {
            let chars = read_chars(&fg.group("GRO")?.dataset("NOM")?)?;
            chars
                .chunks(80)
                .map(text)
                .filter(|s| !s.is_empty())
                .collect()
        } else {
            Vec::new()
        };
        out.insert(num, names);
    }
    Ok(out)
}

/// Groups from family numbers: each group in order of first appearance over the
/// families (by number), members in index order.
fn groups_of(fam: &[i64], families: &BTreeMap<i64, Vec<String>>) -> Vec<Group> {
    let mut groups: Vec<Group> = Vec::new();
    for names in families.values() {
        for n in names {
            if !groups.iter().any(|g| &g.name == n) {
                groups.push(Group {
                    name: n.clone(),
                    members: Vec::new(),
                });
            }
        }
    }
    for (i, f) in fam.iter().enumerate() {
        if let Some(names) = families.get(f) {
            for n in names {
                if let Some(g) = groups.iter_mut().find(|g| &g.name == n) {
                    g.members.push(i);
                }
            }
        }
    }
    groups
}
