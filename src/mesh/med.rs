//! Reader of MED meshes (HDF5, MED 3.x/4.x layout), with a pure-Rust HDF5 decoder
//! (`hdf5-pure`): nothing to install, every build reads MED.
//!
//! Layout used: `ENS_MAA/<mesh>/<time step>/NOE/COO` (coordinates, all x then all y...),
//! `NOE/FAM` (family of each node), `MAI/<type>/NOD` (1-based connectivity, first nodes
//! of all cells, then second nodes...), `MAI/<type>/FAM`, and `FAS/<mesh>/{NOEUD,ELEME}/
//! <family>` with attribute `NUM` and `GRO/NOM` (80-character group names). Groups are
//! made of every node/cell whose family lists them. Integers are read whatever their
//! stored width (MED writes 32- or 64-bit `med_int`).
//!
//! Names: the optional `NOM` datasets (16 characters), else `N<k>` for the k-th node and
//! `M<k>` for the k-th cell, cells numbered type after type in Code_Aster's type order.

use super::{Cell, CellKind, Group, Mesh, Node};
use crate::error::{Error, Result};
use hdf5_pure as h5;
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

/// Errors of one file, each naming the file and what was being read.
struct Reader {
    file: String,
}

impl Reader {
    fn bad(&self, what: impl std::fmt::Display) -> Error {
        Error::input(format!("{}: {what}", self.file)).hint(
            "the file should be a MED mesh file (written by SALOME, Code_Aster, gmsh or meshio)",
        )
    }

    /// Maps an HDF5 error to ours, naming what was being read.
    fn h5(&self, what: &str) -> impl Fn(h5::Error) -> Error + '_ {
        let what = what.to_string();
        move |e| Error::input(format!("{}: cannot read {what}: {e}", self.file))
    }

    fn group(&self, g: &h5::Group, name: &str, what: &str) -> Result<h5::Group> {
        g.group(name).map_err(self.h5(what))
    }

    fn subgroups(&self, g: &h5::Group, what: &str) -> Result<Vec<String>> {
        let mut v = g.groups().map_err(self.h5(what))?;
        v.sort();
        Ok(v)
    }

    fn has_group(&self, g: &h5::Group, name: &str, what: &str) -> Result<bool> {
        Ok(g.groups().map_err(self.h5(what))?.iter().any(|n| n == name))
    }

    fn has_dataset(&self, g: &h5::Group, name: &str, what: &str) -> Result<bool> {
        Ok(g.datasets()
            .map_err(self.h5(what))?
            .iter()
            .any(|n| n == name))
    }

    /// An integer attribute, whatever its stored width.
    fn int_attr(&self, g: &h5::Group, name: &str, what: &str) -> Result<i64> {
        use h5::AttrValue as A;
        let attrs = g.attrs().map_err(self.h5(what))?;
        match attrs.get(name) {
            Some(A::I64(v)) => Ok(*v),
            Some(A::I32(v)) => Ok(i64::from(*v)),
            Some(A::I16(v)) => Ok(i64::from(*v)),
            Some(A::I8(v)) => Ok(i64::from(*v)),
            Some(A::U32(v)) => Ok(i64::from(*v)),
            Some(A::U16(v)) => Ok(i64::from(*v)),
            Some(A::U8(v)) => Ok(i64::from(*v)),
            Some(other) => Err(self.bad(format!(
                "{what}: attribute {name} is {other:?}, not an integer"
            ))),
            None => Err(self.bad(format!("{what}: attribute {name} is missing"))),
        }
    }

    /// Family numbers of `count` entities (0, no family, when the dataset is absent).
    fn fam(&self, g: &h5::Group, count: usize, what: &str) -> Result<Vec<i64>> {
        if !self.has_dataset(g, "FAM", what)? {
            return Ok(vec![0; count]);
        }
        let v = g
            .dataset("FAM")
            .and_then(|d| d.read_i64())
            .map_err(self.h5(&format!("{what}/FAM")))?;
        if v.len() != count {
            return Err(self.bad(format!(
                "{what}/FAM has {} family numbers for {count} entities",
                v.len()
            )));
        }
        Ok(v)
    }

    /// Fixed-width names (`NOM` dataset), if present: `count` names of `width` characters.
    fn names(
        &self,
        g: &h5::Group,
        width: usize,
        count: usize,
        what: &str,
    ) -> Result<Option<Vec<String>>> {
        if !self.has_dataset(g, "NOM", what)? {
            return Ok(None);
        }
        let chars = self.chars(g, "NOM", &format!("{what}/NOM"))?;
        if chars.len() != width * count {
            return Err(self.bad(format!(
                "{what}/NOM has {} characters for {count} names of {width}",
                chars.len()
            )));
        }
        Ok(Some(chars.chunks(width).map(text).collect()))
    }

    /// The bytes of a character dataset, stored as arrays of 80 (or 16) bytes or as a
    /// plain table of bytes: the raw record bytes are the characters in both cases.
    fn chars(&self, g: &h5::Group, name: &str, what: &str) -> Result<Vec<u8>> {
        g.dataset(name)
            .and_then(|d| d.read_raw())
            .map_err(self.h5(what))
    }

    /// `family number -> group names` of one FAS branch (NOEUD or ELEME).
    fn families(&self, g: &h5::Group, what: &str) -> Result<BTreeMap<i64, Vec<String>>> {
        let mut out = BTreeMap::new();
        for fam in self.subgroups(g, what)? {
            let fw = format!("{what}/{fam}");
            let fg = self.group(g, &fam, &fw)?;
            let num = self.int_attr(&fg, "NUM", &fw)?;
            let names = if self.has_group(&fg, "GRO", &fw)? {
                let gro = self.group(&fg, "GRO", &fw)?;
                self.chars(&gro, "NOM", &format!("{fw}/GRO/NOM"))?
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
}

/// Read mesh `name` (or the first mesh) of the MED file at `path`.
pub fn read_file(path: &Path, name: Option<&str>) -> Result<Mesh> {
    let r = Reader {
        file: path.display().to_string(),
    };
    let f = h5::File::open(path).map_err(r.h5("the file as HDF5"))?;
    let ens = f
        .group("ENS_MAA")
        .map_err(r.h5("ENS_MAA (the list of meshes)"))?;
    let meshes = r.subgroups(&ens, "ENS_MAA")?;
    let mesh_name = match name {
        Some(n) => meshes
            .iter()
            .find(|m| m.trim_end() == n)
            .cloned()
            .ok_or_else(|| {
                Error::input(format!("{}: no mesh named '{n}' (NOM_MED)", r.file))
                    .keyword("LIRE_MAILLAGE/NOM_MED")
                    .hint(format!("the file holds: {}", meshes.join(", ")))
            })?,
        None => meshes
            .first()
            .cloned()
            .ok_or_else(|| r.bad("the file holds no mesh"))?,
    };
    let mesh_group = r.group(&ens, &mesh_name, &mesh_name)?;
    let space_dim = r.int_attr(&mesh_group, "ESP", "the space dimension (ESP)")?;
    let dim = usize::try_from(space_dim)
        .ok()
        .filter(|d| (1..=3).contains(d))
        .ok_or_else(|| r.bad(format!("space dimension {space_dim} is not 1, 2 or 3")))?;
    // MED 3 stores the mesh under a time-step group; older files have NOE directly.
    let step = if r.has_group(&mesh_group, "NOE", &mesh_name)? {
        mesh_group
    } else {
        let steps = r.subgroups(&mesh_group, &mesh_name)?;
        let s = steps
            .first()
            .ok_or_else(|| r.bad(format!("mesh {mesh_name} has no nodes")))?;
        r.group(&mesh_group, s, s)?
    };

    // Nodes
    let noe = r.group(&step, "NOE", "NOE (nodes)")?;
    let coo = noe
        .dataset("COO")
        .and_then(|d| d.read_f64())
        .map_err(r.h5("NOE/COO (coordinates)"))?;
    if !coo.len().is_multiple_of(dim) {
        return Err(r.bad(format!(
            "{} coordinates is not a multiple of the dimension {dim}",
            coo.len()
        )));
    }
    let n_nodes = coo.len() / dim;
    if let Some(i) = coo.iter().position(|c| !c.is_finite()) {
        return Err(r.bad(format!(
            "node {} has the coordinate {}: coordinates must be finite numbers",
            i % n_nodes.max(1) + 1,
            coo[i]
        )));
    }
    let node_names = r.names(&noe, 16, n_nodes, "NOE")?;
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
    let node_fam = r.fam(&noe, n_nodes, "NOE")?;

    // Cells
    let mai = r.group(&step, "MAI", "MAI (cells)")?;
    let present = r.subgroups(&mai, "MAI")?;
    if let Some(t) = present.iter().find(|t| !TYPES.iter().any(|(m, _)| m == t)) {
        return Err(r
            .bad(format!("MED cell type {t} is not supported"))
            .hint("supported: PO1 SE2 SE3 TR3 TR6 QU4 QU8 TE4 HE8 PE6 PY5"));
    }
    let mut cells = Vec::new();
    let mut cell_fam = Vec::new();
    for (med, kind) in TYPES {
        if !present.iter().any(|t| t == med) {
            continue;
        }
        let what = format!("MAI/{med}");
        let g = r.group(&mai, med, &what)?;
        let nod = g
            .dataset("NOD")
            .and_then(|d| d.read_i64())
            .map_err(r.h5(&format!("{what}/NOD")))?;
        let nn = kind.node_count();
        if !nod.len().is_multiple_of(nn) {
            return Err(r.bad(format!(
                "{what}/NOD has {} entries, not a multiple of {nn}",
                nod.len()
            )));
        }
        let count = nod.len() / nn;
        let names = r.names(&g, 16, count, &what)?;
        cell_fam.extend(r.fam(&g, count, &what)?);
        for i in 0..count {
            let nodes = (0..nn)
                .map(|k| {
                    let n = nod[k * count + i];
                    usize::try_from(n - 1)
                        .ok()
                        .filter(|&j| j < n_nodes)
                        .ok_or_else(|| {
                            r.bad(format!("a {med} cell uses node {n}, outside 1..{n_nodes}"))
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
    let fas_path = format!("FAS/{mesh_name}");
    let fas = f.group(&fas_path).ok();
    let families = |kind: &str| -> Result<BTreeMap<i64, Vec<String>>> {
        let what = format!("{fas_path}/{kind}");
        match &fas {
            Some(g) if r.has_group(g, kind, &fas_path)? => {
                r.families(&r.group(g, kind, &what)?, &what)
            }
            _ => Ok(BTreeMap::new()),
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

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes)
        .trim_end_matches(['\0', ' '])
        .trim()
        .to_string()
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
