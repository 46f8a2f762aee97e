//! Our mesh readers against meshio: every mesh in testcases/meshes/ is read by aster-nl and
//! compared with `<stem>.expected.json`, written by `testcases/meshes/meshio_expected.py`
//! (meshio 5.3) for Gmsh files and by hand for Code_Aster native files, which meshio does
//! not read.

use aster_nl::mesh::{self, CellKind, Mesh, MeshFormat};
use serde_json::Value as Json;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/meshes")
}

fn meshio_type(k: CellKind) -> &'static str {
    match k {
        CellKind::Poi1 => "vertex",
        CellKind::Seg2 => "line",
        CellKind::Seg3 => "line3",
        CellKind::Tria3 => "triangle",
        CellKind::Tria6 => "triangle6",
        CellKind::Quad4 => "quad",
        CellKind::Quad8 => "quad8",
        CellKind::Tetra4 => "tetra",
        CellKind::Hexa8 => "hexahedron",
        CellKind::Penta6 => "wedge",
        CellKind::Pyram5 => "pyramid",
    }
}

/// Groups meshio cannot see (see meshio_expected.py): an unnamed second physical group of
/// a Gmsh 4.1 entity.
const HIDDEN_FROM_MESHIO: &[(&str, &str)] = &[("mixed41.msh", "GM12"), ("mixed41.msh", "GN12")];

fn compare(file: &str, format: MeshFormat) -> usize {
    let path = dir().join(file);
    let m: Mesh = mesh::read_file(&path, format, None).unwrap_or_else(|e| panic!("{e}"));
    let stem = file.rsplit_once('.').map_or(file, |(s, _)| s);
    let text = std::fs::read_to_string(dir().join(format!("{stem}.expected.json"))).unwrap();
    let exp: Json = serde_json::from_str(&text).unwrap();

    // Points, exactly as written: 1e-12 only absorbs decimal/binary round-trips.
    let pts = exp["points"].as_array().unwrap();
    assert_eq!(m.nodes.len(), pts.len(), "{file}: node count");
    for (n, p) in m.nodes.iter().zip(pts) {
        for (a, b) in n.coords.iter().zip(p.as_array().unwrap()) {
            let b = b.as_f64().unwrap();
            assert!((a - b).abs() <= 1e-12, "{file}: node {} {a} != {b}", n.name);
        }
    }
    if let Some(names) = exp.get("node_names") {
        let ours: Vec<&str> = m.nodes.iter().map(|n| n.name.as_str()).collect();
        let theirs: Vec<&str> = names
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap())
            .collect();
        assert_eq!(ours, theirs, "{file}: node names");
    }
    if let Some(names) = exp.get("cell_names") {
        let ours: Vec<&str> = m.cells.iter().map(|c| c.name.as_str()).collect();
        let theirs: Vec<&str> = names
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap())
            .collect();
        assert_eq!(ours, theirs, "{file}: cell names");
    }
    if let Some(d) = exp.get("dim") {
        assert_eq!(m.dim as u64, d.as_u64().unwrap(), "{file}: dim");
    }

    // Cells by type in file order, and each cell's (type, index within type).
    let mut by_type: BTreeMap<&str, Vec<Vec<u64>>> = BTreeMap::new();
    let mut id: Vec<(String, u64)> = Vec::new();
    for c in &m.cells {
        let t = meshio_type(c.kind);
        let v = by_type.entry(t).or_default();
        id.push((t.to_string(), v.len() as u64));
        v.push(c.nodes.iter().map(|&i| i as u64).collect());
    }
    let exp_cells: BTreeMap<&str, Vec<Vec<u64>>> = exp["cells"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| (k.as_str(), serde_json::from_value(v.clone()).unwrap()))
        .collect();
    assert_eq!(by_type, exp_cells, "{file}: cells by type");

    let hidden = |name: &str| HIDDEN_FROM_MESHIO.contains(&(file, name));
    let exp_cg = exp["cell_groups"].as_object().unwrap();
    let ours: Vec<&str> = m
        .cell_groups
        .iter()
        .map(|g| g.name.as_str())
        .filter(|n| !hidden(n))
        .collect();
    let mut theirs: Vec<&str> = exp_cg.keys().map(String::as_str).collect();
    let mut ours_sorted = ours.clone();
    ours_sorted.sort_unstable();
    theirs.sort_unstable();
    assert_eq!(ours_sorted, theirs, "{file}: GROUP_MA names");
    // MED lists cells type by type, so its groups are compared as sets.
    let unordered = exp.get("group_order").and_then(Json::as_str) == Some("unordered");
    for g in m.cell_groups.iter().filter(|g| !hidden(&g.name)) {
        let mut members: Vec<(String, u64)> = g.members.iter().map(|&i| id[i].clone()).collect();
        let mut expected: Vec<(String, u64)> =
            serde_json::from_value(exp_cg[&g.name].clone()).unwrap();
        if unordered {
            members.sort();
            expected.sort();
        }
        assert_eq!(members, expected, "{file}: GROUP_MA {}", g.name);
    }
    let exp_ng = exp["node_groups"].as_object().unwrap();
    let mut ours: Vec<&str> = m
        .node_groups
        .iter()
        .map(|g| g.name.as_str())
        .filter(|n| !hidden(n))
        .collect();
    let mut theirs: Vec<&str> = exp_ng.keys().map(String::as_str).collect();
    ours.sort_unstable();
    theirs.sort_unstable();
    assert_eq!(ours, theirs, "{file}: GROUP_NO names");
    for g in m.node_groups.iter().filter(|g| !hidden(&g.name)) {
        let mut members: Vec<u64> = g.members.iter().map(|&i| i as u64).collect();
        members.sort_unstable();
        let expected: Vec<u64> = serde_json::from_value(exp_ng[&g.name].clone()).unwrap();
        assert_eq!(members, expected, "{file}: GROUP_NO {}", g.name);
    }
    m.cells.len()
}

#[test]
fn gmsh_22_matches_meshio() {
    assert_eq!(compare("square22.msh", MeshFormat::Gmsh), 10);
}

#[test]
fn gmsh_41_matches_meshio() {
    assert_eq!(compare("square41.msh", MeshFormat::Gmsh), 8);
}

#[test]
fn gmsh_41_quadratic_and_multi_physical_matches_meshio() {
    assert_eq!(compare("mixed41.msh", MeshFormat::Gmsh), 5);
}

#[test]
fn aster_sdnd122a_matches_hand_expectation() {
    assert_eq!(compare("sdnd122a.mail", MeshFormat::Aster), 2);
}

#[test]
fn aster_plate2d_matches_hand_expectation() {
    assert_eq!(compare("plate2d.mail", MeshFormat::Aster), 6);
}

#[test]
fn aster_solid3d_matches_hand_expectation() {
    assert_eq!(compare("solid3d.mail", MeshFormat::Aster), 5);
}

#[test]
fn med_2d_with_families_matches_meshio() {
    assert_eq!(compare("plate_med.med", MeshFormat::Med), 6);
}

#[test]
fn med_3d_matches_meshio() {
    assert_eq!(compare("solid_med.med", MeshFormat::Med), 3);
}

/// The layout of the MED library (SALOME, Code_Aster): version 2 superblock, groups that
/// track creation order, 32-bit integers (see make_med.py).
#[test]
fn med_written_like_the_med_library_matches_meshio() {
    assert_eq!(compare("plate_med4.med", MeshFormat::Med), 6);
}

/// More families than a compact group holds: the links are in dense storage (fractal heap
/// and B-tree) in the MED-library layout.
#[test]
fn med_with_many_families_matches_meshio() {
    assert_eq!(compare("line_med.med", MeshFormat::Med), 14);
    assert_eq!(compare("line_med4.med", MeshFormat::Med), 14);
    let m = mesh::read_file(&dir().join("line_med4.med"), MeshFormat::Med, None).unwrap();
    assert_eq!((m.cell_groups.len(), m.node_groups.len()), (16, 13));
}

/// Every mesh file in the directory has an expected file and is covered above.
#[test]
fn every_mesh_file_is_compared() {
    let mut n = 0;
    for e in std::fs::read_dir(dir()).unwrap() {
        let p = e.unwrap().path();
        let ext = p.extension().and_then(|s| s.to_str()).unwrap_or("");
        if ["mail", "msh", "med"].contains(&ext) {
            let stem = p.file_stem().unwrap().to_str().unwrap();
            assert!(
                dir().join(format!("{stem}.expected.json")).exists(),
                "{stem}"
            );
            n += 1;
        }
    }
    assert!(n >= 8, "expected at least 8 meshes, found {n}");
}
