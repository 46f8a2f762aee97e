//! The reference's own mechanical model of a generated case: dense stiffness and mass
//! matrices over the free DOFs, assembled here from the case's parameters (springs and
//! lumped masses; Euler–Bernoulli Hermite beam elements with consistent mass and no rotary
//! inertia, the POU_D_E convention), not read from the program under test.

use super::sample::{BeamEnds, Case, ChainEnds, Law, Structure, E_STEEL, RHO_STEEL};

pub struct Model {
    pub n: usize,
    pub k: Vec<f64>,
    pub m: Vec<f64>,
    /// (node, component) of each DOF, as the program's tables name them.
    pub dofs: Vec<(String, &'static str)>,
    /// The shock's DOFs: x (PLAN, BI_PLAN: the one component) and, for CERCLE, y.
    pub shock_dofs: (usize, Option<usize>),
}

impl Model {
    pub fn of(case: &Case) -> Model {
        let planar2 = matches!(case.law, Law::Cercle { .. });
        let mut dofs: Vec<(String, &'static str)> = Vec::new();
        let mut pairs: Vec<(Option<usize>, Option<usize>, f64)> = Vec::new(); // springs
        let mut masses: Vec<(usize, f64)> = Vec::new();
        let mut k_extra: Vec<(usize, usize, f64)> = Vec::new();
        let mut m_extra: Vec<(usize, usize, f64)> = Vec::new();
        match &case.structure {
            Structure::Chain {
                ends,
                masses: ms,
                springs,
                ground,
                ky_ratio,
            } => {
                let n = ms.len();
                let comps: &[&'static str] = if planar2 { &["DX", "DY"] } else { &["DX"] };
                for i in 1..=n {
                    for c in comps {
                        dofs.push((format!("N{i}"), c));
                    }
                }
                let nc = comps.len();
                let dof = |node: usize, c: usize| -> Option<usize> {
                    (1..=n).contains(&node).then(|| (node - 1) * nc + c)
                };
                let ky = |k: f64, c: usize| if c == 0 { k } else { k * ky_ratio };
                // Spring j joins nodes (a, b): the fixed chains start at the wall N0.
                for (j, &kj) in springs.iter().enumerate() {
                    let (a, b) = match ends {
                        ChainEnds::Grounded => (j + 1, j + 2),
                        _ => (j, j + 1),
                    };
                    for c in 0..nc {
                        pairs.push((dof(a, c), dof(b, c), ky(kj, c)));
                    }
                }
                for (i, &kg) in ground.iter().enumerate() {
                    for c in 0..nc {
                        if kg > 0.0 {
                            pairs.push((dof(i + 1, c), None, ky(kg, c)));
                        }
                    }
                }
                for (i, &mi) in ms.iter().enumerate() {
                    for c in 0..nc {
                        masses.push((i * nc + c, mi));
                    }
                }
            }
            Structure::Beam {
                ends,
                elements,
                length,
                radius,
            } => {
                let ne = *elements;
                let h = length / ne as f64;
                let area = std::f64::consts::PI * radius * radius;
                let inertia = std::f64::consts::PI * radius.powi(4) / 4.0;
                // Free (DY, DRZ) of each node; None where clamped or pinned.
                let mut idx: Vec<[Option<usize>; 2]> = Vec::new();
                for node in 0..=ne {
                    let fixed_v = node == 0 || (node == ne && *ends != BeamEnds::Cantilever);
                    let fixed_r = node == 0 || (node == ne && *ends == BeamEnds::ClampedClamped);
                    let mut e = [None, None];
                    if !fixed_v {
                        e[0] = Some(dofs.len());
                        dofs.push((format!("N{node}"), "DY"));
                    }
                    if !fixed_r {
                        e[1] = Some(dofs.len());
                        dofs.push((format!("N{node}"), "DRZ"));
                    }
                    idx.push(e);
                }
                let ei = E_STEEL * inertia;
                let ks = [
                    [12.0, 6.0 * h, -12.0, 6.0 * h],
                    [6.0 * h, 4.0 * h * h, -6.0 * h, 2.0 * h * h],
                    [-12.0, -6.0 * h, 12.0, -6.0 * h],
                    [6.0 * h, 2.0 * h * h, -6.0 * h, 4.0 * h * h],
                ];
                let ms = [
                    [156.0, 22.0 * h, 54.0, -13.0 * h],
                    [22.0 * h, 4.0 * h * h, 13.0 * h, -3.0 * h * h],
                    [54.0, 13.0 * h, 156.0, -22.0 * h],
                    [-13.0 * h, -3.0 * h * h, -22.0 * h, 4.0 * h * h],
                ];
                let (kf, mf) = (ei / h.powi(3), RHO_STEEL * area * h / 420.0);
                for e in 0..ne {
                    let loc = [idx[e][0], idx[e][1], idx[e + 1][0], idx[e + 1][1]];
                    for a in 0..4 {
                        for b in 0..4 {
                            if let (Some(p), Some(q)) = (loc[a], loc[b]) {
                                k_extra.push((p, q, kf * ks[a][b]));
                                m_extra.push((p, q, mf * ms[a][b]));
                            }
                        }
                    }
                }
            }
        }
        let n = dofs.len();
        let mut k = vec![0.0; n * n];
        let mut m = vec![0.0; n * n];
        for (a, b, s) in pairs {
            for (p, q, sign) in [(a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)] {
                if let (Some(p), Some(q)) = (p, q) {
                    k[p * n + q] += sign * s;
                }
            }
        }
        for (p, q, s) in k_extra {
            k[p * n + q] += s;
        }
        for (p, q, s) in m_extra {
            m[p * n + q] += s;
        }
        for (p, s) in masses {
            m[p * n + p] += s;
        }
        let find = |c: &str| dofs.iter().position(|d| d.0 == case.shock_node && d.1 == c);
        let shock_dofs = match case.law {
            Law::Cercle { .. } => (find("DX").unwrap_or(0), find("DY")),
            _ => match case.structure {
                Structure::Beam { .. } => (find("DY").unwrap_or(0), None),
                Structure::Chain { .. } => (find("DX").unwrap_or(0), None),
            },
        };
        Model {
            n,
            k,
            m,
            dofs,
            shock_dofs,
        }
    }
}
