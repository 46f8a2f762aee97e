//! IMPR_RESU(FORMAT='MED') read back by meshio (Python): mode shapes of a beam and the
//! orbit of a nonlinear mode, compared with the mesh and the values of the database. CI
//! installs meshio and h5py (`.ci/run`, which sets ASTER_NL_TEST_MESHIO=1 so that a
//! missing meshio fails there); elsewhere the test says it skipped.

use serde_json::Value as Json;
use std::path::{Path, PathBuf};
use std::process::Command;

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("testcases")
        .join(name)
}

fn run(comm: &Path, db: &Path, units: &[&str]) -> String {
    let mut c = Command::new(env!("CARGO_BIN_EXE_aster-nl"));
    c.arg("run").arg(comm).arg("--db").arg(db);
    for u in units {
        c.arg("--unit").arg(u);
    }
    let o = c.output().unwrap();
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(o.status.code(), Some(0), "{out}");
    out
}

/// What meshio reads from `med`: points, cell blocks (type, count), point data (name →
/// rows), and the point/cell tags' group names; `None` when meshio is not installed and
/// CI did not ask for it.
fn meshio_read(med: &Path) -> Option<Json> {
    const SCRIPT: &str = r#"
import json, sys, meshio
m = meshio.read(sys.argv[1], file_format="med")
print(json.dumps({
    "points": m.points.tolist(),
    "cells": [[b.type, len(b.data)] for b in m.cells],
    "point_data": {k: v.tolist() for k, v in m.point_data.items() if k != "point_tags"},
    "point_tags": {str(k): v for k, v in getattr(m, "point_tags", {}).items()},
}))
"#;
    let probe = Command::new("python3")
        .args(["-c", "import meshio, h5py"])
        .output();
    if !probe.is_ok_and(|o| o.status.success()) {
        assert!(
            std::env::var_os("ASTER_NL_TEST_MESHIO").is_none(),
            "ASTER_NL_TEST_MESHIO is set but python3 cannot import meshio and h5py"
        );
        eprintln!(
            "skipped: python3 with meshio and h5py is not available (pip install meshio h5py)"
        );
        return None;
    }
    let o = Command::new("python3")
        .args(["-c", SCRIPT])
        .arg(med)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "meshio could not read {}: {}",
        med.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    Some(serde_json::from_slice(&o.stdout).unwrap())
}

fn rows(v: &Json) -> Vec<Vec<f64>> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| match r {
            Json::Array(a) => a.iter().map(|x| x.as_f64().unwrap()).collect(),
            x => vec![x.as_f64().unwrap()],
        })
        .collect()
}

/// The 20-element clamped-clamped tube of beam_med.comm (6 DOFs per node): modes 1 and 3
/// written to MED. meshio must see the 21 nodes where the mesh has them, the 20 SEG2
/// cells, the groups BaseL and BaseR, and each mode's DX..DRZ at every node equal to the
/// database's mode_shapes (blocked DOFs 0). Values are copied as binary doubles: equal.
#[test]
fn mode_shapes_of_a_beam_read_back_by_meshio() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("beam_med.comm")).unwrap();
    let comm = dir.path().join("beam.comm");
    std::fs::write(
        &comm,
        src.replace(
            "FIN()",
            "IMPR_RESU(FORMAT='MED', UNITE=81, RESU=_F(RESULTAT=MODES, NUME_ORDRE=(1, 3)))\nFIN()",
        ),
    )
    .unwrap();
    std::fs::copy(case("beam_med.med"), dir.path().join("beam.med")).unwrap();
    let med = dir.path().join("modes.med");
    let db = dir.path().join("beam.db");
    let unit = format!("81={}", med.display());
    let out = run(&comm, &db, &[&unit]);
    assert!(out.contains("MODES___DEPL"), "{out}");
    // Our own reader reads the file back with its groups.
    let mesh = aster_nl::mesh::read_file(&med, aster_nl::mesh::MeshFormat::Med, None).unwrap();
    assert_eq!(mesh.nodes.len(), 21);
    let groups: Vec<&str> = mesh.node_groups.iter().map(|g| g.name.as_str()).collect();
    assert!(
        groups.contains(&"BaseL") && groups.contains(&"BaseR"),
        "{groups:?}"
    );
    let Some(m) = meshio_read(&med) else { return };
    let points = rows(&m["points"]);
    assert_eq!(points.len(), 21);
    for (i, p) in points.iter().enumerate() {
        assert_eq!(p, &vec![i as f64 / 20.0, 0.0, 0.0], "node {i}");
    }
    assert_eq!(m["cells"], serde_json::json!([["line", 20]]));
    let tags: Vec<String> = m["point_tags"]
        .as_object()
        .unwrap()
        .values()
        .flat_map(|v| {
            v.as_array()
                .unwrap()
                .iter()
                .map(|s| s.as_str().unwrap().to_string())
        })
        .collect();
    assert!(
        tags.contains(&"BaseL".to_string()) && tags.contains(&"BaseR".to_string()),
        "{tags:?}"
    );
    let data = m["point_data"].as_object().unwrap();
    // Two steps: meshio names them FIELD[i] - time (the frequency).
    let mut names: Vec<&String> = data.keys().collect();
    names.sort();
    assert_eq!(names.len(), 2, "{names:?}");
    let conn = rusqlite::Connection::open(&db).unwrap();
    for (name, mode) in names.iter().zip([1, 3]) {
        assert!(
            name.starts_with(&format!("MODES___DEPL[{}]", (mode - 1) / 2)),
            "{name}"
        );
        let values = rows(&data[name.as_str()]);
        assert_eq!(values.len(), 21);
        let mut st = conn
            .prepare(
                "SELECT NOEUD, NOM_CMP, value FROM mode_shapes WHERE concept='MODES' AND NUME_ORDRE=?1",
            )
            .unwrap();
        let stored: Vec<(String, String, f64)> = st
            .query_map([mode], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
            .unwrap()
            .map(Result::unwrap)
            .collect();
        assert_eq!(stored.len(), 21 * 6);
        let cmps = ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"];
        let mut largest: f64 = 0.0;
        for (node, cmp, v) in stored {
            let i = mesh.node_index(&node).unwrap();
            let c = cmps.iter().position(|x| *x == cmp).unwrap();
            assert_eq!(values[i][c], v, "mode {mode} {node} {cmp}");
            largest = largest.max(v.abs());
        }
        assert!(largest > 0.0, "mode {mode} is all zero");
    }
}

/// The orbit of a nonlinear mode (REST_MODE_NONL of a short sdnd122a run, 16 instants):
/// DEPL and VITE as two fields of 16 steps each; N2 DX equal to the dyna_trans table and
/// N1 (clamped) zero.
#[test]
fn nnm_orbit_read_back_by_meshio() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("sdnd122a.comm")).unwrap();
    let head = &src[..src.find("FREQ = RECU_FONCTION").unwrap()];
    let short = head
        .replace("NB_HARM_NONL=200", "NB_HARM_NONL=40")
        .replace("NB_BRANCHE=105", "NB_BRANCHE=3");
    let comm = dir.path().join("orbit.comm");
    std::fs::write(
        &comm,
        format!(
            "{short}\nHIST = REST_MODE_NONL(MODE_NON_LINE=MNL, NUME_ORDRE=3, NB_INST=16)\n\
             IMPR_RESU(FORMAT='MED', RESU=_F(RESULTAT=HIST, NOM_CHAM=('DEPL', 'VITE')))\nFIN()\n"
        ),
    )
    .unwrap();
    std::fs::copy(case("sdnd122a.mail"), dir.path().join("orbit.mail")).unwrap();
    let db = dir.path().join("orbit.db");
    run(&comm, &db, &[]);
    // UNITE defaults to 80: fort.80 beside the command file.
    let med = dir.path().join("fort.80");
    let Some(m) = meshio_read(&med) else { return };
    assert_eq!(
        rows(&m["points"]),
        vec![vec![0.0, 0.0, 0.0], vec![1.0, 0.0, 0.0]]
    );
    let conn = rusqlite::Connection::open(&db).unwrap();
    let data = m["point_data"].as_object().unwrap();
    for field in ["DEPL", "VITE"] {
        let mut st = conn
            .prepare(&format!(
                "SELECT {field} FROM HIST WHERE NOEUD='N2' AND NOM_CMP='DX' ORDER BY NUME_ORDRE"
            ))
            .unwrap();
        let stored: Vec<f64> = st
            .query_map([], |r| r.get(0))
            .unwrap()
            .map(Result::unwrap)
            .collect();
        assert_eq!(stored.len(), 16);
        let prefix = format!("HIST____{field}[");
        let mut steps: Vec<(usize, &String)> = data
            .keys()
            .filter(|k| k.starts_with(&prefix))
            .map(|k| (k[prefix.len()..k.find(']').unwrap()].parse().unwrap(), k))
            .collect();
        steps.sort();
        assert_eq!(steps.len(), 16, "{:?}", data.keys().collect::<Vec<_>>());
        for ((i, name), want) in steps.iter().zip(&stored) {
            let v = rows(&data[name.as_str()]);
            // Components DX only (the model's one free DOF and its blocked DY, DZ: DX DY DZ).
            assert_eq!(v[1][0], *want, "{field} step {i}");
            assert!(v[0].iter().all(|x| *x == 0.0), "{field} step {i}: N1 moves");
        }
    }
}

/// IMPR_RESU with MAILLAGE and RESULTAT in one RESU occurrence, as Code_Aster accepts it:
/// written when MAILLAGE is the result's mesh, refused naming MAILLAGE otherwise.
#[test]
fn resu_with_its_mesh_and_result_together() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("beam_med.comm")).unwrap();
    std::fs::copy(case("beam_med.med"), dir.path().join("beam.med")).unwrap();
    let comm = dir.path().join("beam.comm");
    std::fs::write(
        &comm,
        src.replace(
            "FIN()",
            "IMPR_RESU(FORMAT='MED', UNITE=81, RESU=_F(MAILLAGE=maill, RESULTAT=MODES))\nFIN()",
        ),
    )
    .unwrap();
    let med = dir.path().join("modes.med");
    let unit = format!("81={}", med.display());
    let out = run(&comm, &dir.path().join("beam.db"), &[&unit]);
    assert!(out.contains("MODES___DEPL"), "{out}");
    assert!(med.exists());
    // Another mesh than the result's.
    std::fs::write(
        &comm,
        src.replace(
            "FIN()",
            "other = LIRE_MAILLAGE(UNITE=20, FORMAT='MED')\n\
             IMPR_RESU(FORMAT='MED', UNITE=81, RESU=_F(MAILLAGE=other, RESULTAT=MODES))\nFIN()",
        ),
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
        .arg("run")
        .arg(&comm)
        .arg("--db")
        .arg(dir.path().join("beam2.db"))
        .arg("--unit")
        .arg(&unit)
        .output()
        .unwrap();
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("IMPR_RESU/RESU/MAILLAGE"), "{out}");
    assert!(out.contains("not on MAILLAGE=other"), "{out}");
}
