//! The one-DOF wall of issue 12 through the engine API: `cargo run --release --example
//! wall_grid -- RATIO REGUL [H_l H_nl PREC_MAN COEF_AMPL NB_PAS_MAN NB_BRANCHE
//! PREC_NEWTON]`, RATIO =
//! RIGI_NOR/k. sdnd122's oscillator (m = 1, k = 10, JEU = 0.01, PLAN), started from the
//! linear mode, retries and the no-progress guard as the catalog defaults them, stopped once a
//! row passes 5x the first-contact energy. Prints one line per branch (VERBOSE=1) and a
//! summary: branches, retries, rows accepted at the round-off floor, the worst frequency error
//! against the exact nonsmooth (penalty) period over the rows past 1.5x the first-contact
//! energy, and the wall time. Environment: DIR (DIR_EVOLUTION, default -1), START_PN
//! (PREC_NEWTON of the start correction only), VERBOSE (also prints the start point), PADE
//! (RESOLUTION/APPROX_MAN = 'PADE').

use aster_nl::nnm::exact::Oscillator;
use aster_nl::nnm::{
    continue_controlled, start_from_mode, Approximation, Continuation, Harmonics, PostProcessor,
    Problem, Settings, Shock, ShockLaw, StepControl,
};
use faer::sparse::{SparseColMat, Triplet};
use std::time::Instant;

fn one(v: f64) -> SparseColMat<usize, f64> {
    SparseColMat::try_new_from_triplets(1, 1, &[Triplet::new(0, 0, v)]).unwrap()
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let f = |i: usize, d: f64| a.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let ratio = f(1, 1e6);
    let regul = f(2, 1e-7);
    let hl = f(3, 20.0) as usize;
    let hn = f(4, 200.0) as usize;
    let prec_man = f(5, 1e-9);
    let coef = f(6, 1.0);
    let np = f(7, 1.0) as usize;
    let nb = f(8, 400.0) as usize;
    let prec_newton = f(9, 1e-8);
    let verbose = std::env::var("VERBOSE").is_ok();
    let (k, g) = (10.0, 0.01);
    let problem = Problem {
        forcing: None,
        k: one(k),
        m: one(1.0),
        shocks: vec![Shock {
            law: ShockLaw::Plan,
            dofs: vec![0],
            gap: g,
            stiffness: ratio * k,
            regul,
        }],
    };
    let settings = Settings {
        harmonics: Harmonics {
            h_lin: hl,
            h_nonl: hn,
        },
        continuation: Continuation {
            n_branches: nb,
            n_points_per_branch: np,
            order: 20,
            prec_man,
            prec_newton,
            iter_newton_max: 15,
            bif_terms: 3,
            bif_tol: 1e-4,
            det_test: true,
            direction: std::env::var("DIR")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(-1),
        },
    };
    let osc = Oscillator {
        m: 1.0,
        k,
        g,
        alpha: ratio * k,
    };
    let e_c = osc.contact_energy();
    let t0 = Instant::now();
    let mut start_settings = settings.clone();
    if let Some(v) = std::env::var("START_PN").ok().and_then(|s| s.parse().ok()) {
        start_settings.continuation.prec_newton = v;
    }
    let start = match start_from_mode(&problem, &start_settings, &[1.0], coef, k.sqrt()) {
        Ok(s) => s,
        Err(e) => {
            println!("start failed: {}", e.message);
            return;
        }
    };
    if verbose {
        let p = &start.point;
        println!(
            "start E/Ec {:.6} f {:.6} newton {}",
            p.energy / e_c,
            p.frequency,
            start.newton_iterations
        );
    }
    let control = StepControl {
        retries_max: 4,
        stall_branches: 50,
        law_defect_max: Some(0.5),
        root_jump_max: None,
        correction_ratio_max: None,
        spread_max: None,
        work_min: None,
        gamma_max: None,
        frequency_floor: None,
        approximation: if std::env::var("PADE").is_ok() {
            Approximation::Pade
        } else {
            Approximation::Series
        },
    };
    let post = PostProcessor::new(&problem, &settings).unwrap();
    let mut branches = 0;
    let out = continue_controlled(&problem, &settings, control, start, &mut |r, pts| {
        branches = r.branch;
        if verbose {
            let p = pts.last().unwrap();
            println!(
                "b {:>4} E/Ec {:.6} f {:.6} a_max {:.3e} newton {} retries {} floor {} bif {} spread {:.2e} defect {:.2e}",
                r.branch,
                p.energy / e_c,
                p.frequency,
                r.a_max,
                r.newton_iterations,
                r.step_retries,
                r.at_floor,
                r.bifurcation,
                p.energy_spread,
                post.relative_law_defect(&p.x).unwrap()
            );
        }
        pts.iter().all(|p| p.energy < 5.0 * e_c)
    });
    let wall = t0.elapsed().as_secs_f64();
    let pts = &out.points;
    let retries: usize = pts.iter().map(|p| p.step_retries).sum();
    let floor = pts.iter().filter(|p| p.at_floor).count();
    let bif = pts.iter().filter(|p| p.bifurcation).count();
    let e_end = pts.last().map_or(0.0, |p| p.energy / e_c);
    let err = pts
        .iter()
        .filter(|p| p.energy > 1.5 * e_c)
        .map(|p| (p.frequency * osc.period_plan(p.energy) - 1.0).abs())
        .fold(0.0f64, f64::max);
    println!(
        "ratio {ratio:.0e} regul {regul:.0e} H {hl}/{hn} prec {prec_man:.0e} coef {coef}: branches {branches} \
         E_end/Ec {e_end:.4} retries {retries} floor {floor} bif_rows {bif} err {err:.3e} wall {wall:.2} s{}",
        match &out.error {
            Some(e) => format!("  ERROR {}", e.message),
            None => String::new(),
        }
    );
}
