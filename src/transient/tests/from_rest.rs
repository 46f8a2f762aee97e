//! An adaptive scheme started from rest under a force that starts from zero (EXCIT with a
//! sine FONC_MULT), the situation of Code_Aster's sliding-pad case (run with ADAPT_ORDRE2,
//! which is now Code_Aster's own scheme: adapt.rs).
//! Against the exact response of the undamped oscillator, m x'' + k x = F sin(Ωt), x(0) =
//! x'(0) = 0: x(t) = F/(k(1 − r²)) (sin Ωt − r sin ωt), r = Ω/ω.

use super::*;

/// m = 156, k = 2e6 (ω = 113.2 rad/s), F = 3e3 at 5 Hz, over 0.5 s, no shock.
pub(super) fn from_rest(scheme: Scheme) -> f64 {
    let (m, k, f, big_omega) = (156.0, 2.0e6, 3.0e3, 2.0 * std::f64::consts::PI * 5.0);
    let s = DenseStructure::diagonal(vec![m], vec![k], None).unwrap();
    let forcing = Forcing {
        generalized_force: vec![f],
        multiplier: Box::new(move |t| (big_omega * t).sin()),
    };
    let instants: Vec<f64> = (1..=10).map(|i| 0.05 * i as f64).collect();
    let traj = integrate(
        &s,
        &mut [],
        &[forcing],
        (&[0.0], &[0.0]),
        scheme,
        TimeGrid {
            t0: 0.0,
            t_end: 0.5,
            dt: 4.0e-6,
        },
        &Archive::Instants(instants.clone()),
        &mut |_| {},
    )
    .expect("the adaptive scheme starts from rest");
    let omega = (k / m).sqrt();
    let r = big_omega / omega;
    let amp = f / (k * (1.0 - r * r));
    let exact = |t: f64| amp * ((big_omega * t).sin() - r * (omega * t).sin());
    traj.t
        .iter()
        .enumerate()
        .map(|(i, &t)| (traj.q_at(i)[0] - exact(t)).abs() / amp.abs())
        .fold(0.0, f64::max)
}

/// Both event-located pairs (LOCALISATION_CHOC='OUI', whose error scale this is) at
/// TOLERANCE 1e-8 reach the end, within 1e-5 of the amplitude (the same
/// bound as the impact oscillator's, impact.rs: the global error is a few hundred times
/// the local tolerance). Before the error scale was floored near rest, every step at t = 0
/// was rejected until the step fell below PAS_MINI.
#[test]
fn adaptive_schemes_start_from_rest_under_a_sine_force() {
    for name in ["RUNGE_KUTTA_54", "RUNGE_KUTTA_32"] {
        let Some(Scheme::Adaptive(mut o)) = Scheme::from_name(name) else {
            panic!("{name} is adaptive")
        };
        o.tolerance = 1e-8;
        o.locate_contacts = true;
        let err = from_rest(Scheme::Adaptive(o));
        eprintln!("{name}: largest relative error {err:e}");
        assert!(err < 1e-5, "{name}: {err:e}");
    }
}
