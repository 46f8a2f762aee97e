//! Moving supports (support.rs), on cases drawn by a generator: a mass on a spring whose
//! support moves by d(t) = −(A/Ω²) sin Ωt, against a stop fixed in the absolute frame. Two
//! formulations of the same motion, integrated separately:
//! - relative (what MULT_APPUI runs): q = x − d, q̈ + ω²q = −d̈(t), the shock on q + d(t)
//!   through the support's share (ψ = 1 at the node, DEPL, VITE);
//! - absolute: ẍ + ω²x = ω² d(t), the shock on x, no support motion,
//!   x(0) = d(0) = 0, ẋ(0) = ḋ(0).
//!
//! They are the same ODE, so x = q + d at every instant to the integration error:
//! RUNGE_KUTTA_54 at TOLERANCE 1e-10 on both, asserted within 1e-6 of the largest |x|
//! (the event-located runs of testcases/dyna_vibra_seisme.comm agree with the exact
//! solution to 1.3e-8; the margin covers grazing contacts the generator may draw). A
//! shock that saw q instead of q + d is off by up to A/Ω², a large fraction of |x|.

use super::*;
use crate::transient::{SupportMotion, SupportTerm};
use proptest::prelude::*;
use std::rc::Rc;

fn rk54() -> Scheme {
    let mut o = AdaptiveOptions::new(RkPair::DormandPrince54);
    o.tolerance = 1e-10;
    o.locate_contacts = true;
    Scheme::Adaptive(o)
}

/// x(t) at the listed instants, relative formulation with the support's share added back.
fn relative(k: f64, a: f64, w: f64, g: f64, kn: f64, t: &[f64], t_end: f64) -> Vec<f64> {
    let s = one_dof(k);
    let mut shock = stop_shock(g, kn, 0.0);
    shock.set_support(SupportMotion::new(vec![SupportTerm {
        psi: [[0.0, 1.0, 0.0], [0.0; 3]],
        depl: Rc::new(move |t| -(a / (w * w)) * (w * t).sin()),
        vite: Rc::new(move |t| -(a / w) * (w * t).cos()),
    }]));
    let forcing = [Forcing {
        generalized_force: vec![1.0],
        multiplier: Box::new(move |t| -a * (w * t).sin()),
    }];
    let traj = integrate(
        &s,
        &mut [shock],
        &forcing,
        (&[0.0], &[0.0]),
        rk54(),
        TimeGrid {
            t0: 0.0,
            t_end,
            dt: 1e-4,
        },
        &Archive::Instants(t.to_vec()),
        &mut |_| {},
    )
    .unwrap();
    traj.t
        .iter()
        .enumerate()
        .map(|(i, &ti)| traj.q_at(i)[0] - (a / (w * w)) * (w * ti).sin())
        .collect()
}

/// x(t) at the listed instants, absolute formulation.
fn absolute(k: f64, a: f64, w: f64, g: f64, kn: f64, t: &[f64], t_end: f64) -> Vec<f64> {
    let s = one_dof(k);
    let forcing = [Forcing {
        generalized_force: vec![k],
        multiplier: Box::new(move |t| -(a / (w * w)) * (w * t).sin()),
    }];
    let traj = integrate(
        &s,
        &mut [stop_shock(g, kn, 0.0)],
        &forcing,
        (&[0.0], &[-a / w]),
        rk54(),
        TimeGrid {
            t0: 0.0,
            t_end,
            dt: 1e-4,
        },
        &Archive::Instants(t.to_vec()),
        &mut |_| {},
    )
    .unwrap();
    (0..traj.t.len()).map(|i| traj.q_at(i)[0]).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn a_moving_support_is_the_absolute_motion(
        k in 1.0e3f64..1.0e5,
        ratio in prop_oneof![0.3f64..0.85, 1.2f64..2.5],
        a in 0.1f64..10.0,
        gap in 0.2f64..2.0,
        stiff in 10.0f64..1000.0,
    ) {
        let omega = k.sqrt();
        let w = ratio * omega;
        let g = gap * a / (w * w);
        let kn = stiff * k;
        let t_end = 10.0 * 2.0 * std::f64::consts::PI / omega;
        let instants: Vec<f64> = (1..=10).map(|i| t_end * i as f64 / 10.0).collect();
        let x_rel = relative(k, a, w, g, kn, &instants, t_end);
        let x_abs = absolute(k, a, w, g, kn, &instants, t_end);
        let scale = x_abs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (r, b) in x_rel.iter().zip(&x_abs) {
            prop_assert!((r - b).abs() <= 1e-6 * scale, "{r} vs {b} (scale {scale})");
        }
    }
}
