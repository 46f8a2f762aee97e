//! DEVOGE (devoge.rs) against exact solutions: the order of its fixed step without and
//! with damping, its error as TOLERANCE falls, the landing on listed instants with the cut
//! part as the next step, and its refusals.

use super::*;

fn devoge(tol: f64, pas_mini: Option<f64>, pas_maxi: Option<f64>) -> Scheme {
    Scheme::Devoge(DevogeOptions {
        tolerance: tol,
        pas_mini,
        pas_maxi,
        ..DevogeOptions::default()
    })
}

/// PAS_MINI = PAS_MAXI = h: Code_Aster's DEVOGE without step control.
fn fixed(h: f64) -> Scheme {
    devoge(1e-5, Some(h), Some(h))
}

/// The largest error of q over the instants 0.1, 0.2, ..., 2 against `exact`.
fn max_error(s: &dyn Structure, scheme: Scheme, exact: &dyn Fn(f64) -> f64) -> f64 {
    let ts: Vec<f64> = (1..=20).map(|i| f64::from(i) * 0.1).collect();
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 2.0,
        dt: match scheme {
            Scheme::Devoge(o) => o.pas_mini.unwrap_or(0.01),
            _ => 0.01,
        },
    };
    let tr = run(
        s,
        &mut [],
        (&[1.0], &[0.0]),
        scheme,
        grid,
        &Archive::Instants(ts.clone()),
    )
    .unwrap();
    assert_eq!(tr.t, ts);
    ts.iter()
        .enumerate()
        .map(|(i, &t)| (tr.q_at(i)[0] - exact(t)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn without_damping_the_fixed_step_is_fourth_order() {
    // m = k = 1 from x = 1 at rest: x = cos t. Measured ratios 16.0 per halving.
    let s = one_dof(1.0);
    let errors: Vec<f64> = [0.1, 0.05, 0.025, 0.0125]
        .iter()
        .map(|&h| max_error(&s, fixed(h), &f64::cos))
        .collect();
    assert!(errors[0] < 1e-6, "{errors:?}");
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!((14.0..18.0).contains(&ratio), "{errors:?}");
    }
}

#[test]
fn with_damping_the_fixed_step_is_third_order() {
    // ξ = 0.05 on m = k = 1. The mid-point velocity is a trapezoid (error h³) that the
    // end velocity's Simpson rule weighs through C: third order (measured ratios 6.1, 7.2,
    // 7.6 per halving, tending to 8).
    let xi = 0.05f64;
    let s = DenseStructure::diagonal(vec![1.0], vec![1.0], Some(vec![2.0 * xi])).unwrap();
    let wd = (1.0 - xi * xi).sqrt();
    let exact = |t: f64| (-xi * t).exp() * ((wd * t).cos() + xi / wd * (wd * t).sin());
    let errors: Vec<f64> = [0.025, 0.0125, 0.00625, 0.003125]
        .iter()
        .map(|&h| max_error(&s, fixed(h), &exact))
        .collect();
    assert!(errors[0] < 1e-8, "{errors:?}");
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!((5.5..10.0).contains(&ratio), "{errors:?}");
    }
}

#[test]
fn the_adaptive_error_follows_tolerance() {
    // x = cos t over 10 s from PAS = 0.01. Measured errors at 10 s: 2.7e-4, 7.9e-6, 2.8e-6,
    // 9.0e-8, 1.0e-7, 8.8e-9 for TOLERANCE 1e-4 ... 1e-9: within 3 to 10 times TOLERANCE
    // (Code_Aster's estimate is per half step and its controller saw-tooths on a smooth
    // motion), and down by 3e4 over the five decades.
    let s = one_dof(1.0);
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 10.0,
        dt: 0.01,
    };
    let mut last_steps = 0;
    let mut errors = Vec::new();
    for tol in [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9] {
        let tr = run(
            &s,
            &mut [],
            (&[1.0], &[0.0]),
            devoge(tol, None, None),
            grid,
            &Archive::Instants(vec![10.0]),
        )
        .unwrap();
        let err = (tr.q_at(0)[0] - 10.0f64.cos()).abs();
        assert!(err < 20.0 * tol, "TOLERANCE {tol:e}: error {err:e}");
        assert!(tr.steps_taken > last_steps, "TOLERANCE {tol:e}");
        last_steps = tr.steps_taken;
        errors.push(err);
    }
    assert!(errors[5] < 1e-4 * errors[0], "{errors:?}");
}

#[test]
fn listed_instants_are_landed_on_and_the_cut_part_is_the_next_step() {
    // Fixed step 0.1 with 0.25 and 0.6 listed and every step archived: the step that would
    // pass 0.25 is cut to it, the next one is the part cut off (0.05), then PAS again; 0.6
    // is a step's end. Code_Aster's driver (dtmcalc).
    let s = one_dof(1.0);
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 1.0,
        dt: 0.1,
    };
    let listed = vec![0.25, 0.6];
    let tr = run(
        &s,
        &mut [],
        (&[1.0], &[0.0]),
        fixed(0.1),
        grid,
        &Archive::EveryAnd(1, listed.clone()),
    )
    .unwrap();
    let expected = [0.0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0];
    assert_eq!(tr.t.len(), expected.len(), "{:?}", tr.t);
    for (i, (&t, &e)) in tr.t.iter().zip(&expected).enumerate() {
        assert!((t - e).abs() < 1e-12, "{:?}", tr.t);
        assert!((tr.q_at(i)[0] - t.cos()).abs() < 2e-6, "at {t}");
    }
    // Adaptive: the listed instants are archived at their exact values.
    let tr = run(
        &s,
        &mut [],
        (&[1.0], &[0.0]),
        devoge(1e-8, None, None),
        grid,
        &Archive::EveryAnd(1, listed.clone()),
    )
    .unwrap();
    for ti in &listed {
        let i = tr.t.iter().position(|t| t == ti).unwrap();
        assert!((tr.q_at(i)[0] - ti.cos()).abs() < 1e-7, "at {ti}");
    }
    assert!(tr.t.windows(2).all(|w| w[1] > w[0]));
}

#[test]
fn devoge_is_its_own_scheme_with_code_aster_defaults() {
    let Some(Scheme::Devoge(o)) = Scheme::from_name("DEVOGE") else {
        panic!("DEVOGE is not mapped to its own scheme")
    };
    assert_eq!(o.tolerance, 1e-5);
    assert_eq!(o.alpha, 0.0);
    assert_eq!((o.pas_mini, o.pas_maxi), (None, None));
}

#[test]
fn pas_maxi_below_pas_and_a_step_held_at_pas_mini_are_refused() {
    let s = one_dof(1.0);
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 1.0,
        dt: 0.1,
    };
    let e = run(
        &s,
        &mut [],
        (&[1.0], &[0.0]),
        devoge(1e-5, None, Some(0.05)),
        grid,
        &Archive::Every(1),
    )
    .unwrap_err();
    assert!(
        matches!(&e, TransientError::Invalid { keyword, .. } if keyword == "SCHEMA_TEMPS/PAS_MAXI"),
        "{e:?}"
    );
    // TOLERANCE 1e-14 cannot be met at 0.1 and PAS_MINI = 0.1 forbids shortening.
    let e = run(
        &s,
        &mut [],
        (&[1.0], &[0.0]),
        devoge(1e-14, Some(0.1), Some(1.0)),
        grid,
        &Archive::Every(1),
    )
    .unwrap_err();
    assert!(
        matches!(e, TransientError::StepTooSmall { pas_mini, .. } if pas_mini == 0.1),
        "{e:?}"
    );
}
