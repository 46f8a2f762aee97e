//! The space users work in, sampled from a seed: a structure (1- to 5-mass spring chain or a
//! short POU_D_E beam), one shock (PLAN, BI_PLAN, or CERCLE centred or off centre), its
//! stiffness ratio and regularisation, the harmonics, the continuation budget, the start
//! (linear mode, DIR_EVOLUTION, COEF_AMPL) and the energy the user wants to reach.

use super::eigen;
use super::model::Model;
use super::rng::Rng;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ChainEnds {
    /// A wall on the left, the last mass free.
    FixedFree,
    /// A wall at both ends.
    FixedFixed,
    /// No wall: every mass on its own spring to the ground (K_T_D_N), neighbours coupled.
    Grounded,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BeamEnds {
    Cantilever,
    ClampedClamped,
    ClampedPinned,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Structure {
    /// Masses m[i] on node N(i+1); springs in x (K_T_D_L), stiffness `springs[j]`, and, for
    /// CERCLE, `ky_ratio` times that in y; `ground[i]` the spring of mass i to the ground.
    Chain {
        ends: ChainEnds,
        masses: Vec<f64>,
        springs: Vec<f64>,
        ground: Vec<f64>,
        ky_ratio: f64,
    },
    /// A steel POU_D_E along x, full circular section, bending in the XY plane only.
    Beam {
        ends: BeamEnds,
        elements: usize,
        length: f64,
        radius: f64,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    Plan,
    BiPlan,
    /// Ring centre (metres, in the plane DX, DY of the shock node).
    Cercle {
        centre: [f64; 2],
    },
}

impl Law {
    pub fn name(&self) -> &'static str {
        match self {
            Law::Plan => "PLAN",
            Law::BiPlan => "BI_PLAN",
            Law::Cercle { centre } if centre == &[0.0, 0.0] => "CERCLE",
            Law::Cercle { .. } => "CERCLE_OFF",
        }
    }
}

pub const E_STEEL: f64 = 2.1e11;
pub const RHO_STEEL: f64 = 7800.0;

#[derive(Debug, Clone)]
pub struct Case {
    pub seed: u64,
    pub index: u64,
    pub structure: Structure,
    /// The shock's node (mesh name) and law.
    pub shock_node: String,
    pub law: Law,
    pub gap: f64,
    /// RIGI_NOR / k_ref.
    pub ratio: f64,
    pub rigi_nor: f64,
    pub para_regul: f64,
    pub h_lin: usize,
    pub h_nonl: usize,
    pub nb_branche: usize,
    pub nb_pas_man: usize,
    pub dir_evolution: i32,
    pub coef_ampl: f64,
    /// NUME_ORDRE of the starting linear mode.
    pub mode: usize,
    /// k_ref = 1/(K⁻¹)pp at the shock's last component (Code_Aster's reference stiffness).
    pub k_ref: f64,
    /// Energy of the linear mode when it first touches the obstacle.
    pub e_contact: f64,
    /// The energy the user wants to reach (a multiple of `e_contact`).
    pub e_target: f64,
    /// Frequency (Hz) of the starting linear mode, by the reference's own eigen-solver.
    pub f_linear: f64,
}

impl Case {
    pub fn name(&self) -> String {
        format!("s{}_c{:04}", self.seed, self.index)
    }

    pub fn family(&self) -> &'static str {
        match self.structure {
            Structure::Chain { .. } => "chain",
            Structure::Beam { .. } => "beam",
        }
    }

    pub fn dofs(&self) -> usize {
        Model::of(self).n
    }
}

/// Energy of a linear mode φ (any scaling) at its first contact with the obstacle, or None
/// if that mode does not move the shock's DOFs toward it.
pub fn contact_energy(model: &Model, law: Law, gap: f64, phi: &[f64]) -> Option<f64> {
    let e1 = eigen::half_quad(&model.k, phi);
    let (px, py) = model.shock_dofs;
    let scale = match law {
        Law::Plan | Law::BiPlan => {
            let a = phi[px].abs();
            (a > 0.0).then(|| gap / a)?
        }
        Law::Cercle { centre } => {
            // Smallest a > 0 with |a φ_xy − c| = gap (c inside the ring).
            let (fx, fy) = (phi[px], phi[py?]);
            let ff = fx * fx + fy * fy;
            if ff == 0.0 {
                return None;
            }
            let fc = fx * centre[0] + fy * centre[1];
            let cc = centre[0] * centre[0] + centre[1] * centre[1];
            let disc = fc * fc - ff * (cc - gap * gap);
            // A mode along ±φ: the nearer crossing on either side (the orbit swings both ways).
            let a1 = (fc + disc.sqrt()) / ff;
            let a2 = (-fc + disc.sqrt()) / ff;
            a1.min(a2)
        }
    };
    Some(e1 * scale * scale)
}

/// Samples case `index` of `seed`.
pub fn sample(seed: u64, index: u64) -> Case {
    let mut r = Rng::new(seed, index);
    loop {
        if let Some(c) = try_sample(&mut r, seed, index) {
            return c;
        }
    }
}

fn try_sample(r: &mut Rng, seed: u64, index: u64) -> Option<Case> {
    let is_beam = r.unit() < 0.25;
    let law_pick = r.unit();
    let law = if is_beam {
        if law_pick < 0.5 {
            Law::Plan
        } else {
            Law::BiPlan
        }
    } else if law_pick < 0.35 {
        Law::Plan
    } else if law_pick < 0.65 {
        Law::BiPlan
    } else {
        Law::Cercle { centre: [0.0, 0.0] }
    };
    let (structure, shock_node, gap) = if is_beam {
        let ends = *r.pick(&[
            BeamEnds::Cantilever,
            BeamEnds::ClampedClamped,
            BeamEnds::ClampedPinned,
        ]);
        let elements = r.int(2, 5);
        let length = r.log_uniform(0.5, 2.0);
        let radius = r.log_uniform(5e-3, 2e-2);
        let node = match ends {
            BeamEnds::Cantilever => elements,
            _ => elements.div_ceil(2),
        };
        let gap = length * r.log_uniform(1e-4, 1e-2);
        (
            Structure::Beam {
                ends,
                elements,
                length,
                radius,
            },
            format!("N{node}"),
            gap,
        )
    } else {
        let n = r.int(1, 5);
        let ends = *r.pick(&[
            ChainEnds::FixedFree,
            ChainEnds::FixedFixed,
            ChainEnds::Grounded,
        ]);
        let masses: Vec<f64> = (0..n).map(|_| r.log_uniform(0.5, 2.0)).collect();
        let n_springs = match ends {
            ChainEnds::FixedFree => n,
            ChainEnds::FixedFixed => n + 1,
            ChainEnds::Grounded => n - 1,
        };
        let springs = (0..n_springs).map(|_| r.log_uniform(5.0, 50.0)).collect();
        let ground = match ends {
            ChainEnds::Grounded => (0..n).map(|_| r.log_uniform(2.0, 20.0)).collect(),
            _ => vec![0.0; n],
        };
        let ky_ratio = r.uniform(1.3, 3.0);
        let node = r.int(1, n);
        (
            Structure::Chain {
                ends,
                masses,
                springs,
                ground,
                ky_ratio,
            },
            format!("N{node}"),
            r.log_uniform(1e-3, 1e-1),
        )
    };
    // CERCLE off centre in half the ring cases: up to 0.5 JEU, in a random direction.
    let law = match law {
        Law::Cercle { .. } if r.unit() < 0.5 => {
            let (rad, ang) = (
                gap * r.uniform(0.05, 0.5),
                r.uniform(0.0, std::f64::consts::TAU),
            );
            Law::Cercle {
                centre: [rad * ang.cos(), rad * ang.sin()],
            }
        }
        l => l,
    };
    let mut case = Case {
        seed,
        index,
        structure,
        shock_node,
        law,
        gap,
        ratio: r.log_uniform(1.0, 1e8),
        rigi_nor: 0.0,
        para_regul: r.log_uniform(1e-8, 1e-3),
        h_lin: r.log_int(3, 40),
        h_nonl: 0,
        nb_branche: r.log_int(10, 1000),
        nb_pas_man: *r.pick(&[1, 1, 2, 5, 10]),
        dir_evolution: *r.pick(&[-1, -1, -1, 1]),
        coef_ampl: r.log_uniform(0.1, 1.0),
        mode: 1,
        k_ref: 0.0,
        e_contact: 0.0,
        e_target: 0.0,
        f_linear: 0.0,
    };
    case.h_nonl = r.log_int(case.h_lin.max(20), 1000);
    let model = Model::of(&case);
    let p = model.shock_dofs.1.unwrap_or(model.shock_dofs.0);
    let mut unit = vec![0.0; model.n];
    unit[p] = 1.0;
    case.k_ref = 1.0 / eigen::solve(&model.k, &unit)?[p];
    case.rigi_nor = case.ratio * case.k_ref;
    let (w2, shapes) = eigen::modes(&model.k, &model.m, model.n)?;
    // The starting mode: 1 mostly, 2 or 3 sometimes; it must move the shock's DOFs.
    let wanted = *r.pick(&[1, 1, 1, 2, 3]);
    case.mode = wanted.min(model.n);
    let phi = &shapes[case.mode - 1];
    let largest = phi.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let (px, py) = model.shock_dofs;
    let moved = phi[px].abs().max(py.map_or(0.0, |q| phi[q].abs()));
    if moved < 0.2 * largest {
        return None;
    }
    // Distinct frequencies around the start (CALC_MODES' order must be ours).
    let w = w2[case.mode - 1];
    if w2
        .iter()
        .enumerate()
        .any(|(i, &o)| i != case.mode - 1 && (o / w - 1.0).abs() < 1e-3)
    {
        return None;
    }
    case.f_linear = w.sqrt() / std::f64::consts::TAU;
    case.e_contact = contact_energy(&model, case.law, case.gap, phi)?;
    case.e_target = case.e_contact * r.log_uniform(1.5, 100.0);
    Some(case)
}
