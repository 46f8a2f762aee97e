//! IMPR_TABLE and IMPR_FONCTION with FORMAT='PNG' | 'SVG', run through `lookup` on an
//! in-memory store; the pictures go to a temporary directory holding the "command file".

use crate::args::Args;
use crate::ops::common::harness::*;
use crate::plot::tests::{has_texts, png_size, svg_texts};
use crate::value::Value;
use std::path::PathBuf;

fn liste(para: &str, kind: &str, v: Vec<Value>) -> Args {
    fact("CREA_TABLE/LISTE", vec![("PARA", k(para)), (kind, seq(v))])
}

fn crea(h: &mut Harness, name: &str, titre: &str, lists: Vec<Args>) {
    let a = args(
        "CREA_TABLE",
        vec![("TITRE", k(titre))],
        vec![("LISTE", lists)],
    );
    h.run("CREA_TABLE", Some(name), None, &a).unwrap();
}

/// A harness whose command file sits in a fresh temporary directory.
fn harness() -> (Harness, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let mut h = Harness::new();
    h.units.comm_file = Some(dir.path().join("case.comm"));
    (h, dir)
}

/// MNL: four rows of a MODE_NON_LINE table, the first at zero energy (the linear mode).
fn mnl(h: &mut Harness) {
    crea(
        h,
        "MNL",
        "",
        vec![
            liste("NUME_ORDRE", "LISTE_I", vec![i(1), i(2), i(3), i(4)]),
            liste(
                "ENERGIE",
                "LISTE_R",
                vec![r(0.0), r(1e-3), r(1e-2), r(1e-1)],
            ),
            liste(
                "FREQUENCE",
                "LISTE_R",
                vec![r(0.503), r(0.51), r(0.55), r(0.62)],
            ),
            liste(
                "STABILITE",
                "LISTE_K",
                vec![k("STABLE"), k("STABLE"), k("INSTABLE"), k("NON_EVALUE")],
            ),
            liste(
                "BIFURCATION",
                "LISTE_K",
                vec![k("NON"), k("NON"), k("OUI"), k("NON")],
            ),
        ],
    );
}

#[test]
fn impr_table_draws_the_frequency_energy_plot_of_a_mode_non_line_table() {
    let (mut h, dir) = harness();
    mnl(&mut h);
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("MNL")),
            ("FORMAT", k("SVG")),
            ("FICHIER", k("fe.svg")),
            ("TITRE", k("sdnd122")),
        ],
        vec![],
    );
    h.run("IMPR_TABLE", None, None, &a).unwrap();
    let path = dir.path().join("fe.svg");
    let out = h.output();
    assert!(
        out.contains(&format!(
            "IMPR_TABLE: picture written to {}",
            path.display()
        )),
        "{out}"
    );
    // The zero-energy row cannot sit on the log axis: drawn 3 of 4, with an alarm.
    assert!(out.contains("(3 points)"), "{out}");
    assert!(out.contains("<A> <PLOT_1>"), "{out}");
    has_texts(
        &svg_texts(&path),
        &[
            "sdnd122",
            "ENERGIE (J)",
            "FREQUENCE (Hz)",
            "stable",
            "unstable",
            "stability not evaluated",
            "bifurcation",
        ],
    );
    // ECHELLE_X='LIN' keeps every row (the zero energy included).
    h.out.clear();
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("MNL")),
            ("FORMAT", k("PNG")),
            ("UNITE", i(30)),
            ("ECHELLE_X", k("LIN")),
        ],
        vec![],
    );
    h.run("IMPR_TABLE", None, None, &a).unwrap();
    assert!(h.output().contains("(4 points)"), "{}", h.output());
    assert!(!h.output().contains("PLOT_1"));
    assert_eq!(png_size(&dir.path().join("fort.30.png")), (1024, 768));
}

/// TH: orders 1 and 2 at INST 0, 1 for node N2, components DX and DY.
fn time_history(h: &mut Harness) {
    let mut cols: [Vec<Value>; 6] = Default::default();
    for o in [1, 2] {
        for t in [0.0, 1.0] {
            for (c, s) in [("DX", 1.0), ("DY", -1.0)] {
                cols[0].push(i(o));
                cols[1].push(r(t));
                cols[2].push(k("N2"));
                cols[3].push(k(c));
                cols[4].push(r(s * (t + o as f64)));
                cols[5].push(r(s * t));
            }
        }
    }
    let [o, t, n, c, d, v] = cols;
    crea(
        h,
        "TH",
        "",
        vec![
            liste("NUME_ORDRE", "LISTE_I", o),
            liste("INST", "LISTE_R", t),
            liste("NOEUD", "LISTE_K", n),
            liste("NOM_CMP", "LISTE_K", c),
            liste("DEPL", "LISTE_R", d),
            liste("VITE", "LISTE_R", v),
        ],
    );
}

#[test]
fn impr_table_draws_time_histories_and_phase_portraits() {
    let (mut h, dir) = harness();
    time_history(&mut h);
    // Two components and none chosen: an error that lists them.
    let a = args(
        "IMPR_TABLE",
        vec![("TABLE", table("TH")), ("FORMAT", k("PNG"))],
        vec![],
    );
    let err = h.run("IMPR_TABLE", None, None, &a).unwrap_err();
    assert_eq!(err.keyword.as_deref(), Some("IMPR_TABLE/NOEUD"));
    assert!(
        err.hint.as_deref().unwrap_or("").contains("N2 DX, N2 DY"),
        "{err}"
    );
    // FILTRE chooses the component, as for text output.
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("TH")),
            ("FORMAT", k("PNG")),
            ("FICHIER", k("th.png")),
        ],
        vec![(
            "FILTRE",
            vec![fact(
                "IMPR_TABLE/FILTRE",
                vec![("NOM_PARA", k("NOM_CMP")), ("VALE_K", k("DX"))],
            )],
        )],
    );
    h.run("IMPR_TABLE", None, None, &a).unwrap();
    // Two panels × two orders × two instants.
    assert!(h.output().contains("(8 points)"), "{}", h.output());
    assert_eq!(png_size(&dir.path().join("th.png")), (1024, 1024));
    // The phase portrait of N2 DY chosen by keywords.
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("TH")),
            ("FORMAT", k("SVG")),
            ("FICHIER", k("ph.svg")),
            ("COURBE", k("PHASE")),
            ("NOEUD", k("N2")),
            ("NOM_CMP", k("DY")),
        ],
        vec![],
    );
    h.run("IMPR_TABLE", None, None, &a).unwrap();
    has_texts(
        &svg_texts(&dir.path().join("ph.svg")),
        &[
            "DEPL N2 DY (m)",
            "VITE N2 DY (m/s)",
            "NUME_ORDRE 1",
            "NUME_ORDRE 2",
            "TH",
        ],
    );
    // The frequency-energy picture of a table that is not a MODE_NON_LINE one.
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("TH")),
            ("FORMAT", k("SVG")),
            ("COURBE", k("FREQ_ENER")),
        ],
        vec![],
    );
    let err = h.run("IMPR_TABLE", None, None, &a).unwrap_err();
    assert!(
        err.message.contains("TH is not a MODE_NON_LINE table"),
        "{err}"
    );
}

#[test]
fn impr_table_draws_columns_given_by_nom_para() {
    let (mut h, dir) = harness();
    crea(
        &mut h,
        "TAB",
        "three modes",
        vec![
            liste("NUME_ORDRE", "LISTE_I", vec![i(1), i(2), i(3)]),
            liste("FREQ", "LISTE_R", vec![r(1.5), r(2.5), r(3.5)]),
            liste("AMOR", "LISTE_R", vec![r(0.01), r(0.02), r(0.5)]),
        ],
    );
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("FORMAT", k("SVG")),
            ("FICHIER", k("cols.svg")),
            ("NOM_PARA", seq(vec![k("NUME_ORDRE"), k("FREQ"), k("AMOR")])),
            ("LEGENDE_Y", k("value")),
        ],
        vec![],
    );
    h.run("IMPR_TABLE", None, None, &a).unwrap();
    has_texts(
        &svg_texts(&dir.path().join("cols.svg")),
        &["three modes", "NUME_ORDRE", "value", "FREQ", "AMOR"],
    );
    // A plain table without NOM_PARA: which columns?
    let a = args(
        "IMPR_TABLE",
        vec![("TABLE", table("TAB")), ("FORMAT", k("PNG"))],
        vec![],
    );
    let err = h.run("IMPR_TABLE", None, None, &a).unwrap_err();
    assert_eq!(err.keyword.as_deref(), Some("IMPR_TABLE/NOM_PARA"));
}

#[test]
fn impr_fonction_draws_functions_and_point_lists() {
    let (mut h, dir) = harness();
    let a = args(
        "DEFI_FONCTION",
        vec![
            ("NOM_PARA", k("FREQ")),
            ("NOM_RESU", k("ACCE")),
            (
                "VALE",
                seq(vec![r(1.0), r(1.0), r(2.0), r(4.0), r(4.0), r(16.0)]),
            ),
        ],
        vec![],
    );
    h.run("DEFI_FONCTION", Some("F"), None, &a).unwrap();
    let out: PathBuf = dir.path().join("mapped.svg");
    h.units.map.insert(29, out.clone());
    let courbes = vec![
        fact(
            "IMPR_FONCTION/COURBE",
            vec![("FONCTION", concept("F", "fonction_sdaster"))],
        ),
        fact(
            "IMPR_FONCTION/COURBE",
            vec![
                ("ABSCISSE", seq(vec![r(-1.0), r(1.0), r(3.0)])),
                ("ORDONNEE", seq(vec![r(2.0), r(2.0), r(9.0)])),
                ("LEGENDE", k("measured")),
                ("STYLE", i(0)),
                ("MARQUEUR", i(1)),
                ("COULEUR", i(2)),
            ],
        ),
    ];
    let a = args(
        "IMPR_FONCTION",
        vec![
            ("FORMAT", k("SVG")),
            ("UNITE", i(29)),
            ("ECHELLE_X", k("LOG")),
            ("TITRE", k("spectrum")),
        ],
        vec![("COURBE", courbes.clone())],
    );
    h.run("IMPR_FONCTION", None, None, &a).unwrap();
    let o = h.output();
    // 3 points of F + 2 of the list; the abscissa -1 is not drawn on the log axis.
    assert!(
        o.contains(&format!("picture written to {} (5 points)", out.display())),
        "{o}"
    );
    assert!(
        o.contains("1 point(s) with a non-positive value on a log axis"),
        "{o}"
    );
    // Axis names from the function; legend: F's name and the given LEGENDE.
    has_texts(
        &svg_texts(&out),
        // Axis names with their units (before: "FREQ", "ACCE").
        &["spectrum", "FREQ (Hz)", "ACCE (m/s²)", "F", "measured"],
    );
    // PNG beside the command file.
    let a = args(
        "IMPR_FONCTION",
        vec![("FORMAT", k("PNG")), ("FICHIER", k("f.png"))],
        vec![("COURBE", courbes)],
    );
    h.run("IMPR_FONCTION", None, None, &a).unwrap();
    assert_eq!(png_size(&dir.path().join("f.png")), (1024, 768));
    // Nothing drawable (all ordinates non-positive on a log axis): an error, no file.
    let a = args(
        "IMPR_FONCTION",
        vec![
            ("FORMAT", k("PNG")),
            ("FICHIER", k("none.png")),
            ("ECHELLE_Y", k("LOG")),
        ],
        vec![(
            "COURBE",
            vec![fact(
                "IMPR_FONCTION/COURBE",
                vec![
                    ("ABSCISSE", seq(vec![r(1.0), r(2.0)])),
                    ("ORDONNEE", seq(vec![r(0.0), r(-1.0)])),
                ],
            )],
        )],
    );
    let err = h.run("IMPR_FONCTION", None, None, &a).unwrap_err();
    assert!(err.message.contains("nothing to draw"), "{err}");
    assert_eq!(err.keyword.as_deref(), Some("IMPR_FONCTION/COURBE"));
    assert!(!dir.path().join("none.png").exists());
    // Text output of a point list still works.
    h.out.clear();
    let a = args(
        "IMPR_FONCTION",
        vec![],
        vec![(
            "COURBE",
            vec![fact(
                "IMPR_FONCTION/COURBE",
                vec![
                    ("ABSCISSE", seq(vec![r(1.0)])),
                    ("ORDONNEE", seq(vec![r(2.0)])),
                ],
            )],
        )],
    );
    h.run("IMPR_FONCTION", None, None, &a).unwrap();
    assert!(
        h.output().contains("#COURBE 1\nABSCISSE     ORDONNEE\n"),
        "{}",
        h.output()
    );
}
