//! A generated case as a user writes it: the command file (`.comm`) and its mesh (`.mail`,
//! Code_Aster's ASTER format, one group per cell and per node as Code_Aster 16+ meshes have).

use super::sample::{BeamEnds, Case, ChainEnds, Law, Structure, E_STEEL, RHO_STEEL};
use std::fmt::Write;

/// A real as Python reads it back to the same double.
fn real(x: f64) -> String {
    format!("{x:e}")
}

fn group(out: &mut String, kind: &str, name: &str, members: &[String]) {
    let _ = writeln!(out, "{kind}\n {name}");
    for m in members {
        let _ = writeln!(out, " {m}");
    }
    out.push_str("FINSF\n");
}

/// The mesh of the case.
pub fn mesh(case: &Case) -> String {
    let mut out = format!(
        "TITRE\n generated case {} (aster-nl issue 34)\nFINSF\nCOOR_3D\n",
        case.name()
    );
    let mut seg: Vec<(String, usize, usize)> = Vec::new();
    let mut poi: Vec<(String, usize)> = Vec::new();
    let mut walls: Vec<usize> = Vec::new();
    let nodes: Vec<usize> = match &case.structure {
        Structure::Chain {
            ends,
            masses,
            springs,
            ..
        } => {
            let n = masses.len();
            for j in 0..springs.len() {
                let (a, b) = match ends {
                    ChainEnds::Grounded => (j + 1, j + 2),
                    _ => (j, j + 1),
                };
                seg.push((format!("S{}", j + 1), a, b));
            }
            for i in 1..=n {
                poi.push((format!("P{i}"), i));
            }
            match ends {
                ChainEnds::FixedFree => walls.push(0),
                ChainEnds::FixedFixed => walls.extend([0, n + 1]),
                ChainEnds::Grounded => {}
            }
            let first = if *ends == ChainEnds::Grounded { 1 } else { 0 };
            let last = if *ends == ChainEnds::FixedFixed {
                n + 1
            } else {
                n
            };
            (first..=last).collect()
        }
        Structure::Beam { elements, .. } => {
            for e in 0..*elements {
                seg.push((format!("E{}", e + 1), e, e + 1));
            }
            (0..=*elements).collect()
        }
    };
    let dx = match &case.structure {
        Structure::Beam {
            length, elements, ..
        } => length / *elements as f64,
        Structure::Chain { .. } => 1.0,
    };
    for &i in &nodes {
        let _ = writeln!(out, " N{i}  {}  0.0  0.0", real(i as f64 * dx));
    }
    out.push_str("FINSF\n");
    if !seg.is_empty() {
        out.push_str("SEG2\n");
        for (name, a, b) in &seg {
            let _ = writeln!(out, " {name}  N{a}  N{b}");
        }
        out.push_str("FINSF\n");
    }
    if !poi.is_empty() {
        out.push_str("POI1\n");
        for (name, a) in &poi {
            let _ = writeln!(out, " {name}  N{a}");
        }
        out.push_str("FINSF\n");
    }
    for (name, ..) in &seg {
        group(&mut out, "GROUP_MA", name, std::slice::from_ref(name));
    }
    for (name, _) in &poi {
        group(&mut out, "GROUP_MA", name, std::slice::from_ref(name));
    }
    let names: Vec<String> = nodes.iter().map(|i| format!("N{i}")).collect();
    for n in &names {
        group(&mut out, "GROUP_NO", n, std::slice::from_ref(n));
    }
    group(&mut out, "GROUP_NO", "TOUS", &names);
    if !walls.is_empty() {
        let w: Vec<String> = walls.iter().map(|i| format!("N{i}")).collect();
        group(&mut out, "GROUP_NO", "WALL", &w);
    }
    out.push_str("FIN\n");
    out
}

/// The command file of the case.
pub fn comm(case: &Case) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "# Generated case {} (aster-nl issue 34, tests/gencases): {} {} shock, RIGI_NOR/k_ref = {:.3e},\n\
         # first contact at ENERGIE {:.6e} J; the user wants to reach {:.6e} J.",
        case.name(),
        case.family(),
        case.law.name(),
        case.ratio,
        case.e_contact,
        case.e_target
    );
    o.push_str("DEBUT(CODE=_F(NIV_PUB_WEB='INTERNET'), IGNORE_ALARM=('FONCT0_62',))\n\n");
    o.push_str("MAIL = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\n");
    let ring = matches!(case.law, Law::Cercle { .. });
    match &case.structure {
        Structure::Chain {
            ends,
            masses,
            springs,
            ground,
            ky_ratio,
        } => {
            o.push_str(
                "MODELE = AFFE_MODELE(MAILLAGE=MAIL,\n                     AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))\n",
            );
            let ky = |k: f64| if ring { k * ky_ratio } else { 0.0 };
            let mut d = Vec::new();
            for (j, &k) in springs.iter().enumerate() {
                d.push(format!(
                    "_F(GROUP_MA='S{}', CARA='K_T_D_L', VALE=({}, {}, 0.), REPERE='GLOBAL')",
                    j + 1,
                    real(k),
                    real(ky(k))
                ));
            }
            for (i, &m) in masses.iter().enumerate() {
                d.push(format!(
                    "_F(GROUP_MA='P{}', CARA='M_T_D_N', VALE={})",
                    i + 1,
                    real(m)
                ));
                if ground[i] > 0.0 {
                    d.push(format!(
                        "_F(GROUP_MA='P{}', CARA='K_T_D_N', VALE=({}, {}, 0.))",
                        i + 1,
                        real(ground[i]),
                        real(ky(ground[i]))
                    ));
                }
            }
            let _ = writeln!(
                o,
                "CARA = AFFE_CARA_ELEM(MODELE=MODELE,\n                      DISCRET=({},))",
                d.join(",\n                               ")
            );
            let mut bc = Vec::new();
            if *ends != ChainEnds::Grounded {
                bc.push("_F(GROUP_NO='WALL', DX=0., DY=0., DZ=0.)".to_string());
            }
            bc.push(if ring {
                "_F(GROUP_NO='TOUS', DZ=0.)".to_string()
            } else {
                "_F(GROUP_NO='TOUS', DY=0., DZ=0.)".to_string()
            });
            let _ = writeln!(
                o,
                "CL = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=({},))",
                bc.join(", ")
            );
            o.push_str(
                "ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUMEDDL'),\n           MATR_ASSE=(_F(MATRICE=CO('RIGIDITE'), OPTION='RIGI_MECA'),\n                      _F(MATRICE=CO('MASSE'), OPTION='MASS_MECA'),),)\n",
            );
        }
        Structure::Beam {
            ends,
            elements,
            radius,
            ..
        } => {
            let groups: Vec<String> = (1..=*elements).map(|e| format!("'E{e}'")).collect();
            let _ = writeln!(
                o,
                "MODELE = AFFE_MODELE(MAILLAGE=MAIL,\n                     AFFE=_F(GROUP_MA=({},), PHENOMENE='MECANIQUE', MODELISATION='POU_D_E'))",
                groups.join(", ")
            );
            let _ = writeln!(
                o,
                "ACIER = DEFI_MATERIAU(ELAS=_F(E={}, NU=0.3, RHO={}))",
                real(E_STEEL),
                real(RHO_STEEL)
            );
            o.push_str("CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', MATER=ACIER))\n");
            let _ = writeln!(
                o,
                "CARA = AFFE_CARA_ELEM(MODELE=MODELE,\n                      POUTRE=_F(GROUP_MA=({},), SECTION='CERCLE', CARA='R', VALE={}))",
                groups.join(", "),
                real(*radius)
            );
            let last = format!("N{elements}");
            let mut bc =
                vec!["_F(GROUP_NO='N0', DX=0., DY=0., DZ=0., DRX=0., DRY=0., DRZ=0.)".to_string()];
            match ends {
                BeamEnds::Cantilever => {}
                BeamEnds::ClampedClamped => bc.push(format!(
                    "_F(GROUP_NO='{last}', DX=0., DY=0., DZ=0., DRX=0., DRY=0., DRZ=0.)"
                )),
                BeamEnds::ClampedPinned => bc.push(format!(
                    "_F(GROUP_NO='{last}', DX=0., DY=0., DZ=0., DRX=0., DRY=0.)"
                )),
            }
            bc.push("_F(GROUP_NO='TOUS', DX=0., DZ=0., DRX=0., DRY=0.)".to_string());
            let _ = writeln!(
                o,
                "BLOC = AFFE_CHAR_CINE(MODELE=MODELE,\n                      MECA_IMPO=({},))",
                bc.join(",\n                                 ")
            );
            o.push_str(
                "ASSEMBLAGE(MODELE=MODELE, CHAM_MATER=CHMAT, CARA_ELEM=CARA, CHAR_CINE=BLOC,\n           NUME_DDL=CO('NUMEDDL'),\n           MATR_ASSE=(_F(MATRICE=CO('RIGIDITE'), OPTION='RIGI_MECA'),\n                      _F(MATRICE=CO('MASSE'), OPTION='MASS_MECA'),),)\n",
            );
        }
    }
    let n_modes = (case.mode + 1).min(case.dofs());
    let _ = writeln!(
        o,
        "MODES = CALC_MODES(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, OPTION='PLUS_PETITE',\n                   CALC_FREQ=_F(NMAX_FREQ={n_modes}))\n"
    );
    let choc = match case.law {
        Law::Plan | Law::BiPlan => {
            let cmp = match case.structure {
                Structure::Beam { .. } => "DY",
                Structure::Chain { .. } => "DX",
            };
            format!(
                "OBSTACLE='{}', GROUP_NO='{}', NOM_CMP='{cmp}',\n                            JEU={}, RIGI_NOR={}, PARA_REGUL={}",
                case.law.name(),
                case.shock_node,
                real(case.gap),
                real(case.rigi_nor),
                real(case.para_regul)
            )
        }
        Law::Cercle { centre } => {
            let mut s = format!(
                "OBSTACLE='CERCLE', GROUP_NO='{}', NOM_CMP=('DX', 'DY'),\n                            JEU={}, RIGI_NOR={}, PARA_REGUL={}",
                case.shock_node,
                real(case.gap),
                real(case.rigi_nor),
                real(case.para_regul)
            );
            if centre != [0.0, 0.0] {
                let _ = write!(
                    s,
                    ",\n                            ORIG_OBST=({}, {}, 0.)",
                    real(centre[0]),
                    real(centre[1])
                );
            }
            s
        }
    };
    let _ = writeln!(
        o,
        "MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,\n                    ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE={}, DIR_EVOLUTION={}, COEF_AMPL={}),\n                    CHOC=_F({choc}),\n                    RESOLUTION=_F(METHODE='EHMAN', NB_HARM_LINE={}, NB_HARM_NONL={},\n                                  NB_BRANCHE={}, NB_PAS_MAN={}),\n                    INFO=1)\n",
        case.mode,
        case.dir_evolution,
        real(case.coef_ampl),
        case.h_lin,
        case.h_nonl,
        case.nb_branche,
        case.nb_pas_man
    );
    let _ = writeln!(
        o,
        "# What the user reads next: the backbone curve, and the frequency at the energy wanted.\nFREQ = RECU_FONCTION(TABLE=MNL, PARA_X='ENERGIE', PARA_Y='FREQUENCE')\nIMPR_FONCTION(COURBE=_F(FONCTION=FREQ), UNITE=8)\n\nFIN()"
    );
    o
}
