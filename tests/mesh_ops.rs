// Large `Error` on purpose: the reason is given once, at the top of src/lib.rs.
#![allow(clippy::result_large_err)]
//! LIRE_MAILLAGE, CREA_MAILLAGE, DEFI_GROUP and the mesh-location helper, run on an
//! in-memory store with hand-built contexts and arguments.

use aster_nl::args::Args;
use aster_nl::error::Result;
use aster_nl::mesh::select::{select_cells, select_nodes, Names, Selection};
use aster_nl::mesh::CellKind;
use aster_nl::ops::{self, OpContext, TestOutcome, Units};
use aster_nl::store::mesh::load_mesh;
use aster_nl::store::Store;
use aster_nl::value::{ConceptRef, Span, Value};
use std::path::{Path, PathBuf};

fn meshes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/meshes")
}

fn s(v: &str) -> Value {
    Value::Str(v.into())
}
fn list(v: &[&str]) -> Value {
    Value::Seq(v.iter().map(|x| s(x)).collect())
}
fn mesh_ref(name: &str) -> Value {
    Value::Concept(ConceptRef {
        name: name.into(),
        ty: "maillage_sdaster".into(),
    })
}

fn args(path: &str, simple: &[(&str, Value)]) -> Args {
    let mut a = Args::new(path);
    for (k, v) in simple {
        a.simple.push((k.to_string(), v.clone(), Span::default()));
    }
    a
}

fn with_facts(mut a: Args, key: &str, occ: Vec<Args>) -> Args {
    a.factor.push((key.to_string(), occ, Span::default()));
    a
}

/// Run operator `op` and return what it printed.
fn run(
    store: &Store,
    op: &str,
    result: &str,
    reuse: Option<&str>,
    units: &Units,
    a: &Args,
) -> Result<String> {
    let mut out: Vec<u8> = Vec::new();
    let mut tests: Vec<TestOutcome> = Vec::new();
    let f = ops::lookup(op).expect("operator registered");
    // Through the catalog, as a user's call goes: the operators read its defaults.
    let a = &aster_nl::catalog::validate_args(op, a, reuse, "t.comm")?;
    let mut ctx = OpContext::new(store, op, &mut out, units, &mut tests);
    ctx.result = Some(result);
    ctx.reuse = reuse;
    ctx.file = "t.comm";
    ctx.line = 1;
    ctx.info = a.int("INFO").unwrap_or(1);
    ops::run_in_transaction(f, &mut ctx, a)?;
    Ok(String::from_utf8(out).unwrap())
}

fn units_with(unit: i64, file: &str) -> Units {
    let mut u = Units::default();
    u.map.insert(unit, meshes().join(file));
    u
}

fn lire(store: &Store, name: &str, units: &Units, format: &str) -> Result<String> {
    let a = args(
        "LIRE_MAILLAGE",
        &[
            ("FORMAT", s(format)),
            ("UNITE", Value::Int(20)),
            ("INFO", Value::Int(1)),
        ],
    );
    run(store, "LIRE_MAILLAGE", name, None, units, &a)
}

#[test]
fn lire_maillage_reads_the_mapped_unit_and_saves() {
    let st = Store::in_memory().unwrap();
    let out = lire(&st, "MAIL", &units_with(20, "sdnd122a.mail"), "ASTER").unwrap();
    assert!(
        out.contains("MAIL: 2 nodes, 2 cells (SEG2 1, POI1 1)"),
        "{out}"
    );
    let m = load_mesh(&st, "MAIL").unwrap();
    assert_eq!(m.nodes[1].coords, [1.0, 0.0, 0.0]);
    assert_eq!(m.cells[1].kind, CellKind::Poi1);
    assert_eq!(
        st.concept_type("MAIL").unwrap().as_deref(),
        Some("maillage_sdaster")
    );
}

#[test]
fn lire_maillage_finds_the_file_beside_the_command_file() {
    let st = Store::in_memory().unwrap();
    let units = Units {
        comm_file: Some(meshes().join("square41.comm")),
        ..Units::default()
    };
    let out = lire(&st, "MA", &units, "GMSH").unwrap();
    assert!(out.contains("unit 20 is not mapped; reading"), "{out}");
    assert!(out.contains("square41.msh"), "{out}");
    assert_eq!(load_mesh(&st, "MA").unwrap().cells.len(), 8);
}

#[test]
fn lire_maillage_missing_file_names_unit_and_paths() {
    let st = Store::in_memory().unwrap();
    let units = Units {
        comm_file: Some(meshes().join("nowhere.comm")),
        ..Units::default()
    };
    let e = lire(&st, "MA", &units, "ASTER").unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("unit 20") && msg.contains("nowhere.mail"),
        "{msg}"
    );
    assert_eq!(e.keyword.as_deref(), Some("LIRE_MAILLAGE/UNITE"));
    let e = lire(&st, "MA", &units_with(20, "absent.msh"), "GMSH").unwrap_err();
    assert!(
        e.to_string().contains("absent.msh, which does not exist"),
        "{e}"
    );
    // Nothing was created.
    assert!(st.concepts().unwrap().is_empty());
}

#[test]
fn lire_maillage_bad_file_leaves_no_concept() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bad.mail");
    std::fs::write(
        &p,
        "COOR_3D\n N1 0 0 0\nFINSF\nSEG2\n M1 N1 N9\nFINSF\nFIN\n",
    )
    .unwrap();
    let mut units = Units::default();
    units.map.insert(20, p);
    let st = Store::in_memory().unwrap();
    let e = lire(&st, "MA", &units, "ASTER").unwrap_err();
    assert_eq!(e.location.unwrap().span.line, 5);
    assert!(st.concepts().unwrap().is_empty());
}

#[test]
fn lire_maillage_veri_mail_raises_alarms() {
    let st = Store::in_memory().unwrap();
    let a = with_facts(
        args(
            "LIRE_MAILLAGE",
            &[("FORMAT", s("ASTER")), ("UNITE", Value::Int(20))],
        ),
        "VERI_MAIL",
        vec![args(
            "LIRE_MAILLAGE/VERI_MAIL",
            &[("VERIF", s("OUI")), ("APLAT", Value::Real(1e-3))],
        )],
    );
    // solid3d has orphan nodes N12 and N13.
    let out = run(
        &st,
        "LIRE_MAILLAGE",
        "M",
        None,
        &units_with(20, "solid3d.mail"),
        &a,
    )
    .unwrap();
    assert!(
        out.contains("<A> <MAILLAGE_ORPHAN_NODES> 2 node(s) belong to no cell: N12, N13"),
        "{out}"
    );
}

#[test]
fn select_helper_on_sdnd122() {
    let st = Store::in_memory().unwrap();
    lire(&st, "MAIL", &units_with(20, "sdnd122a.mail"), "ASTER").unwrap();
    let m = load_mesh(&st, "MAIL").unwrap();
    // One list of names, as an AFFE occurrence gives it (keyword paths AFFE/...).
    let sel = |key: &str, names: &[&str]| {
        let list = Names {
            names: names.iter().map(|n| n.to_string()).collect(),
            keyword: format!("AFFE/{key}"),
        };
        let mut sel = Selection::default();
        match key {
            "TOUT" => sel.all = true,
            "GROUP_MA" => sel.cell_groups = list,
            "MAILLE" => sel.cells = list,
            "GROUP_NO" => sel.node_groups = list,
            _ => sel.nodes = list,
        }
        sel
    };
    assert_eq!(select_cells(&m, &sel("TOUT", &[])).unwrap(), vec![0, 1]);
    assert_eq!(
        select_cells(&m, &sel("GROUP_MA", &["P2", "M1"])).unwrap(),
        vec![1, 0]
    );
    assert_eq!(select_cells(&m, &sel("MAILLE", &["M1"])).unwrap(), vec![0]);
    // Nodes of cells, each once.
    assert_eq!(
        select_nodes(&m, &sel("GROUP_MA", &["M1", "P2"])).unwrap(),
        vec![0, 1]
    );
    assert_eq!(
        select_nodes(&m, &sel("GROUP_NO", &["N2"])).unwrap(),
        vec![1]
    );
    assert_eq!(
        select_nodes(&m, &sel("NOEUD", &["N2", "N1", "N2"])).unwrap(),
        vec![1, 0]
    );
    let e = select_cells(&m, &sel("GROUP_MA", &["WALL"])).unwrap_err();
    assert_eq!(e.keyword.as_deref(), Some("AFFE/GROUP_MA"));
    let msg = e.to_string();
    assert!(
        msg.contains("GROUP_MA 'WALL' is not in the mesh") && msg.contains("M1, P2"),
        "{msg}"
    );
    let e = select_nodes(&m, &sel("NOEUD", &["N3"])).unwrap_err();
    assert!(
        e.to_string().contains("node 'N3' is not in the mesh") && e.to_string().contains("N1, N2"),
        "{e}"
    );
}

#[test]
fn crea_maillage_adds_poi1_cells_and_group() {
    let st = Store::in_memory().unwrap();
    lire(&st, "MAIL", &units_with(20, "plate2d.mail"), "ASTER").unwrap();
    let occ = args(
        "CREA_MAILLAGE/CREA_POI1",
        &[("NOM_GROUP_MA", s("MASSES")), ("GROUP_NO", s("LEFT"))],
    );
    let occ2 = args("CREA_MAILLAGE/CREA_POI1", &[("NOEUD", s("A7"))]);
    let a = with_facts(
        args("CREA_MAILLAGE", &[("MAILLAGE", mesh_ref("MAIL"))]),
        "CREA_POI1",
        vec![occ, occ2],
    );
    let out = run(&st, "CREA_MAILLAGE", "MAIL2", None, &Units::default(), &a).unwrap();
    assert!(
        out.contains("2 POI1 cell(s) created in GROUP_MA MASSES"),
        "{out}"
    );
    let m = load_mesh(&st, "MAIL2").unwrap();
    let before = load_mesh(&st, "MAIL").unwrap();
    assert_eq!(m.cells.len(), before.cells.len() + 3);
    let g = m.cell_group("MASSES").unwrap();
    let named: Vec<(&str, Vec<usize>)> = g
        .members
        .iter()
        .map(|&i| (m.cells[i].name.as_str(), m.cells[i].nodes.clone()))
        .collect();
    assert_eq!(named, vec![("A1", vec![0]), ("A4", vec![3])]);
    assert!(g.members.iter().all(|&i| m.cells[i].kind == CellKind::Poi1));
    assert_eq!(m.cells.last().unwrap().name, "A7");
    // The source mesh is untouched.
    assert_eq!(
        before,
        aster_nl::mesh::aster::read_file(&meshes().join("plate2d.mail")).unwrap()
    );
}

/// sdnd123a's pattern: a POI1 group of all the masses plus one group per node. Each node
/// gets one cell, which both groups hold (Code_Aster does the same), so a model on the
/// group of all and characteristics on a per-node group meet on the same cell.
#[test]
fn crea_poi1_shares_one_cell_per_node_between_occurrences() {
    let st = Store::in_memory().unwrap();
    lire(&st, "MAIL", &units_with(20, "plate2d.mail"), "ASTER").unwrap();
    let all = args(
        "CREA_MAILLAGE/CREA_POI1",
        &[("NOM_GROUP_MA", s("MASSES")), ("GROUP_NO", s("LEFT"))],
    );
    let one = args(
        "CREA_MAILLAGE/CREA_POI1",
        &[("NOM_GROUP_MA", s("A4")), ("NOEUD", s("A4"))],
    );
    // MAILLE (the 13.x spelling) gives the nodes of cell S1: A1 (shared) and A2 (new).
    let by_cell = args(
        "CREA_MAILLAGE/CREA_POI1",
        &[("NOM_GROUP_MA", s("S1P")), ("MAILLE", s("S1"))],
    );
    let a = with_facts(
        args("CREA_MAILLAGE", &[("MAILLAGE", mesh_ref("MAIL"))]),
        "CREA_POI1",
        vec![all, one, by_cell],
    );
    let out = run(&st, "CREA_MAILLAGE", "MAIL2", None, &Units::default(), &a).unwrap();
    assert!(
        out.contains("0 POI1 cell(s) created in GROUP_MA A4, 1 shared with an earlier occurrence"),
        "{out}"
    );
    let m = load_mesh(&st, "MAIL2").unwrap();
    let before = load_mesh(&st, "MAIL").unwrap();
    assert_eq!(m.cells.len(), before.cells.len() + 3, "one POI1 per node");
    let masses = &m.cell_group("MASSES").unwrap().members;
    let a4 = &m.cell_group("A4").unwrap().members;
    assert_eq!(a4.len(), 1);
    assert!(
        masses.contains(&a4[0]),
        "the per-node group holds the shared cell"
    );
    assert_eq!(m.cells[a4[0]].nodes, vec![3]);
    let s1p = &m.cell_group("S1P").unwrap().members;
    assert_eq!(s1p.len(), 2);
    assert_eq!(s1p[0], masses[0], "A1's cell is shared");
    assert_eq!(m.cells[s1p[1]].nodes, vec![1]);
}

#[test]
fn crea_maillage_existing_group_name_is_refused() {
    let st = Store::in_memory().unwrap();
    lire(&st, "MAIL", &units_with(20, "plate2d.mail"), "ASTER").unwrap();
    let occ = args(
        "CREA_MAILLAGE/CREA_POI1",
        &[("NOM_GROUP_MA", s("PLATE")), ("TOUT", s("OUI"))],
    );
    let a = with_facts(
        args("CREA_MAILLAGE", &[("MAILLAGE", mesh_ref("MAIL"))]),
        "CREA_POI1",
        vec![occ],
    );
    let e = run(&st, "CREA_MAILLAGE", "MAIL2", None, &Units::default(), &a).unwrap_err();
    assert_eq!(
        e.keyword.as_deref(),
        Some("CREA_MAILLAGE/CREA_POI1/NOM_GROUP_MA")
    );
    assert_eq!(st.concept_type("MAIL2").unwrap(), None);
}

#[test]
fn defi_group_creates_and_removes_groups_in_place() {
    let st = Store::in_memory().unwrap();
    lire(&st, "MAIL", &units_with(20, "plate2d.mail"), "ASTER").unwrap();
    let a = args("DEFI_GROUP", &[("MAILLAGE", mesh_ref("MAIL"))]);
    let a = with_facts(
        a,
        "DETR_GROUP_NO",
        vec![args("DEFI_GROUP/DETR_GROUP_NO", &[("NOM", s("TIP"))])],
    );
    let a = with_facts(
        a,
        "CREA_GROUP_MA",
        vec![
            args(
                "DEFI_GROUP/CREA_GROUP_MA",
                &[("NOM", s("ALL")), ("TOUT", s("OUI"))],
            ),
            args(
                "DEFI_GROUP/CREA_GROUP_MA",
                &[("NOM", s("SOME")), ("MAILLE", list(&["T1", "S1"]))],
            ),
        ],
    );
    let a = with_facts(
        a,
        "CREA_GROUP_NO",
        vec![
            args(
                "DEFI_GROUP/CREA_GROUP_NO",
                &[("GROUP_MA", list(&["BOTTOM"]))],
            ),
            args(
                "DEFI_GROUP/CREA_GROUP_NO",
                &[("GROUP_MA", s("SOME")), ("NOM", s("SOME_N"))],
            ),
            args(
                "DEFI_GROUP/CREA_GROUP_NO",
                &[("NOEUD", list(&["A7", "A1"])), ("NOM", s("TIP"))],
            ),
        ],
    );
    run(
        &st,
        "DEFI_GROUP",
        "MAIL",
        Some("MAIL"),
        &Units::default(),
        &a,
    )
    .unwrap();
    let m = load_mesh(&st, "MAIL").unwrap();
    assert_eq!(
        m.cell_group("ALL").unwrap().members,
        (0..6).collect::<Vec<_>>()
    );
    assert_eq!(m.cell_group("SOME").unwrap().members, vec![2, 3]);
    assert_eq!(m.node_group("BOTTOM").unwrap().members, vec![0, 1, 2]);
    // T1 = A3 A7 A6, S1 = A1 A2: nodes in order of first appearance.
    assert_eq!(m.node_group("SOME_N").unwrap().members, vec![2, 6, 5, 0, 1]);
    assert_eq!(m.node_group("TIP").unwrap().members, vec![6, 0]);
    // Still one concept, still produced by LIRE_MAILLAGE (enriched in place).
    let c = st.concepts().unwrap();
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].operator, "LIRE_MAILLAGE");
}

#[test]
fn defi_group_tout_group_ma_skips_existing_with_alarm() {
    let st = Store::in_memory().unwrap();
    lire(&st, "MAIL", &units_with(20, "square22.msh"), "GMSH").unwrap();
    let a = with_facts(
        args("DEFI_GROUP", &[("MAILLAGE", mesh_ref("MAIL"))]),
        "CREA_GROUP_NO",
        vec![args(
            "DEFI_GROUP/CREA_GROUP_NO",
            &[("TOUT_GROUP_MA", s("OUI"))],
        )],
    );
    let out = run(
        &st,
        "DEFI_GROUP",
        "MAIL",
        Some("MAIL"),
        &Units::default(),
        &a,
    )
    .unwrap();
    assert!(
        out.contains("<A> <DEFI_GROUP_EXISTS> TOUT_GROUP_MA: GROUP_NO corner already exists"),
        "{out}"
    );
    // GM3 (unnamed physical 3) gets GROUP_NO GM3 beside the reader's GN3.
    let m = load_mesh(&st, "MAIL").unwrap();
    assert_eq!(
        m.node_group("GM3").unwrap().members,
        m.node_group("GN3").unwrap().members
    );
}

#[test]
fn defi_group_errors_roll_back() {
    let st = Store::in_memory().unwrap();
    lire(&st, "MAIL", &units_with(20, "plate2d.mail"), "ASTER").unwrap();
    let before = load_mesh(&st, "MAIL").unwrap();
    let a = with_facts(
        args("DEFI_GROUP", &[("MAILLAGE", mesh_ref("MAIL"))]),
        "CREA_GROUP_MA",
        vec![
            args(
                "DEFI_GROUP/CREA_GROUP_MA",
                &[("NOM", s("OK")), ("TOUT", s("OUI"))],
            ),
            args(
                "DEFI_GROUP/CREA_GROUP_MA",
                &[("NOM", s("BAD")), ("GROUP_MA", s("NOPE"))],
            ),
        ],
    );
    let e = run(
        &st,
        "DEFI_GROUP",
        "MAIL",
        Some("MAIL"),
        &Units::default(),
        &a,
    )
    .unwrap_err();
    assert_eq!(
        e.keyword.as_deref(),
        Some("DEFI_GROUP/CREA_GROUP_MA/GROUP_MA")
    );
    assert!(e.to_string().contains("BOTTOM, PLATE"), "{e}");
    assert_eq!(load_mesh(&st, "MAIL").unwrap(), before);
}

#[test]
fn lire_maillage_med_and_nom_med() {
    let st = Store::in_memory().unwrap();
    let out = lire(&st, "MA", &units_with(20, "plate_med.med"), "MED").unwrap();
    assert!(
        out.contains("MA: 7 nodes, 6 cells (POI1 1, SEG2 2, TRIA3 2, QUAD4 1)"),
        "{out}"
    );
    let m = load_mesh(&st, "MA").unwrap();
    // Unnamed MED entities get Code_Aster names: cells numbered type after type.
    assert_eq!(m.cells[0].name, "M1");
    assert_eq!(m.cells[0].kind, CellKind::Poi1);
    assert_eq!(m.dim, 2);
    let a = args(
        "LIRE_MAILLAGE",
        &[
            ("FORMAT", s("MED")),
            ("UNITE", Value::Int(20)),
            ("NOM_MED", s("other")),
        ],
    );
    let e = run(
        &st,
        "LIRE_MAILLAGE",
        "MB",
        None,
        &units_with(20, "plate_med.med"),
        &a,
    )
    .unwrap_err();
    assert!(
        e.to_string().contains("no mesh named 'other'") && e.to_string().contains("mesh"),
        "{e}"
    );
}
