//! Writer of MED files (HDF5, the MED 3.0 layout that ParaVis, SALOME and meshio read): one
//! mesh with its groups and nodal fields over several steps (mode shapes, the instants of
//! an orbit), through `hdf5-pure`'s writer: nothing to install.
//!
//! Layout written (what `med.rs` reads back, and the names the MED library uses):
//!
//! - `INFOS_GENERALES` with the MED version (`MAJ`, `MIN`, `REL` = 3, 0, 0: newer version
//!   numbers are refused by older SALOME releases);
//! - `ENS_MAA/<mesh>/-0000000000000000001-0000000000000000001/` (the mesh's one "no time"
//!   step) holding `NOE/COO` (all x, then all y...), `NOE/NOM` (16-character node names),
//!   `NOE/FAM`, and `MAI/<type>/NOD` (1-based connectivity, first nodes of all cells, then
//!   second nodes...), `MAI/<type>/NOM`, `MAI/<type>/FAM`;
//! - `FAS/<mesh>/{FAMILLE_ZERO, NOEUD, ELEME}`: a family per distinct set of groups, node
//!   families numbered 1, 2..., cell families -1, -2..., each listing its groups in
//!   `GRO/NOM` (80 characters per name);
//! - `CHA/<field>/<step>/NOE/MED_NO_PROFILE_INTERNAL/CO`: the values of every node, all
//!   first components then all second components..., one `<step>` group per step named by
//!   its number and iteration (20 digits each) with its time (`PDT`).
//!
//! Texts are fixed-width ASCII, as the MED library writes them (meshio decodes them as
//! bytes). The file is written whole; the caller decides whether a file may be replaced.

use super::{CellKind, Group, Mesh};
use crate::error::{Error, Result};
use hdf5_pure::{AttrValue, FileBuilder, GroupBuilder};
use std::collections::BTreeMap;
use std::path::Path;

/// A field known at every node of the mesh, over one or more steps.
#[derive(Clone, Debug, PartialEq)]
pub struct NodalField {
    /// The MED field name (at most 64 characters), e.g. `MODES___DEPL`.
    pub name: String,
    /// Component names (at most 16 characters each), e.g. DX, DY, DZ.
    pub components: Vec<String>,
    /// Unit of every component (at most 16 characters), e.g. `m`.
    pub unit: String,
    pub steps: Vec<Step>,
}

/// The values of a field at one step.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// Step number (NUME_ORDRE).
    pub number: i64,
    /// Time of the step (INST; a frequency for mode shapes).
    pub time: f64,
    /// `values[node * components + c]`, every node of the mesh.
    pub values: Vec<f64>,
}

/// MED type names of our cell kinds.
fn med_type(kind: CellKind) -> &'static str {
    match kind {
        CellKind::Poi1 => "PO1",
        CellKind::Seg2 => "SE2",
        CellKind::Seg3 => "SE3",
        CellKind::Tria3 => "TR3",
        CellKind::Tria6 => "TR6",
        CellKind::Quad4 => "QU4",
        CellKind::Quad8 => "QU8",
        CellKind::Tetra4 => "TE4",
        CellKind::Hexa8 => "HE8",
        CellKind::Penta6 => "PE6",
        CellKind::Pyram5 => "PY5",
    }
}

/// The MED library's "no profile" name: the values cover every node.
const NO_PROFILE: &str = "MED_NO_PROFILE_INTERNAL";
/// The name of the mesh's single step (no time step, no iteration).
const MESH_STEP: &str = "-0000000000000000001-0000000000000000001";

fn text(s: &str) -> AttrValue {
    AttrValue::AsciiString(s.to_string())
}

/// `names` padded with NULs to `width` bytes each, cut to `width`.
fn fixed(names: &[&str], width: usize) -> Vec<i8> {
    let mut out = Vec::with_capacity(names.len() * width);
    for n in names {
        let mut b: Vec<i8> = n.bytes().take(width).map(|b| b as i8).collect();
        b.resize(width, 0);
        out.extend(b);
    }
    out
}

/// `names` padded with spaces to `width` each and concatenated (MED's component names).
fn padded(names: &[String], width: usize) -> String {
    names
        .iter()
        .map(|n| format!("{:<width$}", n.chars().take(width).collect::<String>()))
        .collect()
}

/// Family of every entity: entities in the same groups share one, numbered from `sign`
/// (1 for nodes, -1 for cells) outward; 0 for entities in no group. Returns the family of
/// each entity and the groups of each family.
fn families(count: usize, groups: &[Group], sign: i64) -> (Vec<i64>, BTreeMap<i64, Vec<String>>) {
    let mut of: Vec<Vec<&str>> = vec![Vec::new(); count];
    for g in groups {
        for &m in &g.members {
            if let Some(v) = of.get_mut(m) {
                if !v.contains(&g.name.as_str()) {
                    v.push(&g.name);
                }
            }
        }
    }
    let mut ids: BTreeMap<Vec<&str>, i64> = BTreeMap::new();
    let mut fam = Vec::with_capacity(count);
    for set in &of {
        if set.is_empty() {
            fam.push(0);
            continue;
        }
        let next = sign * (ids.len() as i64 + 1);
        fam.push(*ids.entry(set.clone()).or_insert(next));
    }
    let names = ids
        .into_iter()
        .map(|(set, id)| (id, set.into_iter().map(str::to_string).collect()))
        .collect();
    (fam, names)
}

fn int_dataset(g: &mut GroupBuilder, name: &str, values: &[i64], count: usize) {
    let v32: Vec<i32> = values.iter().map(|&v| v as i32).collect();
    g.create_dataset(name)
        .with_i32_data(&v32)
        .set_attr("CGT", AttrValue::I32(1))
        .set_attr("NBR", AttrValue::I32(count as i32));
}

fn names_dataset(g: &mut GroupBuilder, names: &[&str], width: usize) {
    g.create_dataset("NOM")
        .with_i8_data(&fixed(names, width))
        .set_attr("CGT", AttrValue::I32(1))
        .set_attr("NBR", AttrValue::I32(names.len() as i32));
}

/// `FAS/<mesh>/<branch>`: one group per family with its number and group names.
fn family_branch(
    parent: &mut GroupBuilder,
    name: &str,
    fams: &BTreeMap<i64, Vec<String>>,
) -> GroupBuilder {
    let mut branch = parent.create_group(name);
    for (id, groups) in fams {
        let mut f = branch.create_group(&format!("FAM_{id}"));
        f.set_attr("NUM", AttrValue::I32(*id as i32));
        let mut gro = f.create_group("GRO");
        gro.set_attr("NBR", AttrValue::I32(groups.len() as i32));
        let refs: Vec<&str> = groups.iter().map(String::as_str).collect();
        gro.create_dataset("NOM")
            .with_i8_data(&fixed(&refs, 80))
            .with_shape(&[groups.len() as u64, 80]);
        f.add_group(gro.finish());
        branch.add_group(f.finish());
    }
    branch
}

/// Write `mesh` (named `mesh_name` in the file) and `fields` to the MED file `path`,
/// replacing it.
pub fn write_file(path: &Path, mesh_name: &str, mesh: &Mesh, fields: &[NodalField]) -> Result<()> {
    let bytes = build(mesh_name, mesh, fields)?;
    std::fs::write(path, bytes).map_err(|e| {
        Error::new(
            crate::error::ErrorKind::Io,
            format!("cannot write the MED file {}: {e}", path.display()),
        )
    })
}

/// The bytes of the MED file of [`write_file`].
pub fn build(mesh_name: &str, mesh: &Mesh, fields: &[NodalField]) -> Result<Vec<u8>> {
    let n = mesh.nodes.len();
    let dim = mesh.dim.clamp(1, 3);
    for f in fields {
        let width = f.components.len();
        if let Some(s) = f.steps.iter().find(|s| s.values.len() != n * width) {
            return Err(Error::internal(format!(
                "MED field {} step {}: {} values for {n} nodes of {width} components",
                f.name,
                s.number,
                s.values.len()
            )));
        }
    }
    let mut fb = FileBuilder::new();

    let mut info = fb.create_group("INFOS_GENERALES");
    info.set_attr("MAJ", AttrValue::I32(3));
    info.set_attr("MIN", AttrValue::I32(0));
    info.set_attr("REL", AttrValue::I32(0));
    fb.add_group(info.finish());

    // The mesh.
    let axes: Vec<String> = ["X", "Y", "Z"][..dim]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let mut ens = fb.create_group("ENS_MAA");
    let mut m = ens.create_group(mesh_name);
    for (k, v) in [("DIM", dim), ("ESP", dim)] {
        m.set_attr(k, AttrValue::I32(v as i32));
    }
    m.set_attr("REP", AttrValue::I32(0));
    m.set_attr("TYP", AttrValue::I32(0));
    m.set_attr("SRT", AttrValue::I32(1));
    m.set_attr("NXT", AttrValue::I32(1));
    m.set_attr("NXI", AttrValue::I32(-1));
    m.set_attr("NOM", text(&padded(&axes, 16)));
    m.set_attr("UNI", text(&padded(&vec!["m".to_string(); dim], 16)));
    m.set_attr("UNT", text(""));
    m.set_attr("DES", text("written by aster-nl"));
    let mut step = m.create_group(MESH_STEP);
    step.set_attr("CGT", AttrValue::I32(1));
    step.set_attr("NDT", AttrValue::I32(-1));
    step.set_attr("NOR", AttrValue::I32(-1));
    step.set_attr("PDT", AttrValue::F64(-1.0));

    let mut noe = step.create_group("NOE");
    noe.set_attr("CGT", AttrValue::I32(1));
    noe.set_attr("CGS", AttrValue::I32(1));
    noe.set_attr("PFL", text(NO_PROFILE));
    let coo: Vec<f64> = (0..dim)
        .flat_map(|k| mesh.nodes.iter().map(move |node| node.coords[k]))
        .collect();
    noe.create_dataset("COO")
        .with_f64_data(&coo)
        .set_attr("CGT", AttrValue::I32(1))
        .set_attr("NBR", AttrValue::I32(n as i32));
    let node_names: Vec<&str> = mesh.nodes.iter().map(|x| x.name.as_str()).collect();
    names_dataset(&mut noe, &node_names, 16);
    let (node_fam, node_fams) = families(n, &mesh.node_groups, 1);
    int_dataset(&mut noe, "FAM", &node_fam, n);
    step.add_group(noe.finish());

    let (cell_fam, cell_fams) = families(mesh.cells.len(), &mesh.cell_groups, -1);
    let mut mai = step.create_group("MAI");
    mai.set_attr("CGT", AttrValue::I32(1));
    let mut by_type: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (i, c) in mesh.cells.iter().enumerate() {
        by_type.entry(med_type(c.kind)).or_default().push(i);
    }
    for (t, cells) in &by_type {
        let mut g = mai.create_group(t);
        g.set_attr("CGT", AttrValue::I32(1));
        g.set_attr("CGS", AttrValue::I32(1));
        g.set_attr("PFL", text(NO_PROFILE));
        let per = cells.first().map_or(0, |&c| mesh.cells[c].nodes.len());
        let nod: Vec<i64> = (0..per)
            .flat_map(|k| {
                cells
                    .iter()
                    .map(move |&c| (mesh.cells[c].nodes[k] + 1) as i64)
            })
            .collect();
        int_dataset(&mut g, "NOD", &nod, cells.len());
        let names: Vec<&str> = cells.iter().map(|&c| mesh.cells[c].name.as_str()).collect();
        names_dataset(&mut g, &names, 16);
        let fam: Vec<i64> = cells.iter().map(|&c| cell_fam[c]).collect();
        int_dataset(&mut g, "FAM", &fam, cells.len());
        mai.add_group(g.finish());
    }
    step.add_group(mai.finish());
    m.add_group(step.finish());
    ens.add_group(m.finish());
    fb.add_group(ens.finish());

    // The groups, as families.
    let mut fas = fb.create_group("FAS");
    let mut fas_mesh = fas.create_group(mesh_name);
    let mut zero = fas_mesh.create_group("FAMILLE_ZERO");
    zero.set_attr("NUM", AttrValue::I32(0));
    fas_mesh.add_group(zero.finish());
    if !node_fams.is_empty() {
        let branch = family_branch(&mut fas_mesh, "NOEUD", &node_fams);
        fas_mesh.add_group(branch.finish());
    }
    if !cell_fams.is_empty() {
        let branch = family_branch(&mut fas_mesh, "ELEME", &cell_fams);
        fas_mesh.add_group(branch.finish());
    }
    fas.add_group(fas_mesh.finish());
    fb.add_group(fas.finish());

    // The fields.
    let mut cha = fb.create_group("CHA");
    for f in fields {
        let width = f.components.len();
        let mut g = cha.create_group(&f.name);
        g.set_attr("MAI", text(mesh_name));
        g.set_attr("TYP", AttrValue::I32(6)); // MED_FLOAT64
        g.set_attr("NCO", AttrValue::I32(width as i32));
        g.set_attr("NOM", text(&padded(&f.components, 16)));
        g.set_attr("UNI", text(&padded(&vec![f.unit.clone(); width], 16)));
        g.set_attr("UNT", text(""));
        for s in &f.steps {
            let mut st = g.create_group(&format!("{:020}{:020}", s.number, s.number));
            st.set_attr("NDT", AttrValue::I32(s.number as i32));
            st.set_attr("NOR", AttrValue::I32(s.number as i32));
            st.set_attr("PDT", AttrValue::F64(s.time));
            st.set_attr("RDT", AttrValue::I32(-1));
            st.set_attr("ROR", AttrValue::I32(-1));
            let mut noe = st.create_group("NOE");
            noe.set_attr("GAU", text(""));
            noe.set_attr("PFL", text(NO_PROFILE));
            let mut pfl = noe.create_group(NO_PROFILE);
            pfl.set_attr("NBR", AttrValue::I32(n as i32));
            pfl.set_attr("NGA", AttrValue::I32(1));
            pfl.set_attr("GAU", text(""));
            let co: Vec<f64> = (0..width)
                .flat_map(|c| (0..n).map(move |i| s.values[i * width + c]))
                .collect();
            pfl.create_dataset("CO").with_f64_data(&co);
            noe.add_group(pfl.finish());
            st.add_group(noe.finish());
            g.add_group(st.finish());
        }
        cha.add_group(g.finish());
    }
    fb.add_group(cha.finish());
    fb.finish()
        .map_err(|e| Error::internal(format!("MED file of {mesh_name}: {e}")))
}
