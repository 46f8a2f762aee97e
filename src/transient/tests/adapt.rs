//! Code_Aster's ADAPT_ORDRE1 / ADAPT_ORDRE2 (scheme/adapt.rs, adapt_loop.rs): their order
//! against the exact free vibration, their convergence on the impact oscillator's exact
//! event-driven solution (reference.rs), the archive cuts with Code_Aster's remainder
//! rule, and the ends of the step control (a step kept after NMAX_ITER_PAS tries, a step
//! below PAS_MINI).

use super::impact::error as impact_error;
use super::*;
use crate::transient::{AdaptOptions, AdaptOrder};

fn adapt(order: AdaptOrder, points: f64) -> Scheme {
    let mut o = AdaptOptions::new(order);
    o.points_per_period = points;
    Scheme::Adapt(o)
}

/// Largest |x − cos t| over the archived instants for x'' = −x from (1, 0).
fn free_vibration_error(scheme: Scheme, dt: f64, archive: &Archive) -> (f64, Trajectory) {
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 10.0,
        dt,
    };
    let traj = run(
        &one_dof(1.0),
        &mut [],
        (&[1.0], &[0.0]),
        scheme,
        grid,
        archive,
    )
    .unwrap();
    assert!(traj.steps_forced.is_empty());
    let err = traj
        .t
        .iter()
        .enumerate()
        .map(|(i, &t)| (traj.q_at(i)[0] - t.cos()).abs())
        .fold(0.0, f64::max);
    (err, traj)
}

/// The least-squares slope of log(error) against log(step).
fn slope(steps: &[f64], errs: &[f64]) -> f64 {
    let xs: Vec<f64> = steps.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
    let n = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// The observed order of a scheme run at a constant step (PAS_MINI = PAS_MAXI = h, every
/// step archived), h = 0.02·2^(−k), k = 0..4.
fn constant_step_order(order: AdaptOrder) -> f64 {
    let steps: Vec<f64> = (0..5).map(|k| 0.02 / f64::from(1 << k)).collect();
    let errs: Vec<f64> = steps
        .iter()
        .map(|&h| {
            let mut o = AdaptOptions::new(order);
            o.pas_mini = Some(h);
            o.pas_maxi = Some(h);
            free_vibration_error(Scheme::Adapt(o), h, &Archive::Every(1)).0
        })
        .collect();
    eprintln!("{order:?} at constant steps {steps:?}: errors {errs:?}");
    slope(&steps, &errs)
}

/// ADAPT_ORDRE2's step at a constant length is the central difference: second order in
/// the positions (asserted within ±0.2 of 2).
#[test]
fn adapt_ordre2_is_second_order_at_a_constant_step() {
    let p = constant_step_order(AdaptOrder::Two);
    assert!((p - 2.0).abs() < 0.2, "observed order {p}");
}

/// ADAPT_ORDRE1 starts with a whole kick (q1 = q0 + h v0 + h² a0, h²/2 too much), a phase
/// error of order h that stays: first order (asserted within ±0.2 of 1).
#[test]
fn adapt_ordre1_is_first_order_at_a_constant_step() {
    let p = constant_step_order(AdaptOrder::One);
    assert!((p - 1.0).abs() < 0.2, "observed order {p}");
}

/// With its step free, ADAPT_ORDRE2 kicks the half-step velocity by the new step h, not by
/// the mean of the old and new steps (Code_Aster's form), so each change of length (a
/// growth by COEF_MULT_PAS, a cut at an archive instant) adds an error of first order:
/// the error still falls as NB_POIN_PERIODE grows, but not like its square. Measured on
/// the free vibration (cuts at t = 1..10): 1.39e-2 with 50 points per period, 2.39e-3 with
/// 800; asserted: 16 times more points divide the error by more than 3.
#[test]
fn adapt_ordre2_converges_as_the_points_per_period_grow() {
    let instants: Vec<f64> = (1..=10).map(f64::from).collect();
    let archive = Archive::Instants(instants.clone());
    let run_at = |points: f64| {
        let (err, traj) = free_vibration_error(adapt(AdaptOrder::Two, points), 1e-3, &archive);
        assert_eq!(traj.t, instants, "the listed instants are reached exactly");
        err
    };
    let (coarse, fine) = (run_at(50.0), run_at(800.0));
    eprintln!("free vibration: NB_POIN_PERIODE 50: {coarse:e}, 800: {fine:e}");
    assert!(fine < coarse / 3.0, "{coarse:e} -> {fine:e}");
}

/// On the impact oscillator (6 impacts against a stop 100 times stiffer) the error falls
/// as NB_POIN_PERIODE grows: the apparent frequency sees the contact's stiffness, so the
/// steps shorten inside contacts by themselves. Measured: 1.28e-1 with 50 points per
/// period (1301 steps), 1.27e-2 with 3200 (41 004 steps); asserted: 64 times more points
/// divide the error by more than 5.
#[test]
fn adapt_ordre2_converges_on_the_impact_oscillator() {
    let (coarse, tc) = impact_error(adapt(AdaptOrder::Two, 50.0), 0.01);
    let (fine, tf) = impact_error(adapt(AdaptOrder::Two, 3200.0), 0.01);
    eprintln!(
        "impact: NB_POIN_PERIODE 50: {coarse:e} ({} steps), 3200: {fine:e} ({} steps)",
        tc.steps_taken, tf.steps_taken
    );
    assert!(fine < coarse / 5.0, "{coarse:e} -> {fine:e}");
}

/// PAS_MINI = PAS_MAXI: a constant step, cut at the listed instant 0.025 and followed by
/// the remainder of the cut step (Code_Aster's driver), then back to the constant step.
#[test]
fn archive_cut_is_followed_by_the_remainder() {
    let mut o = AdaptOptions::new(AdaptOrder::Two);
    o.pas_mini = Some(0.01);
    o.pas_maxi = Some(0.01);
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 0.06,
        dt: 0.01,
    };
    let traj = run(
        &one_dof(1.0),
        &mut [],
        (&[1.0], &[0.0]),
        Scheme::Adapt(o),
        grid,
        &Archive::EveryAnd(1, vec![0.025]),
    )
    .unwrap();
    let expect = [0.0, 0.01, 0.02, 0.025, 0.03, 0.04, 0.05, 0.06];
    assert_eq!(traj.t.len(), expect.len(), "{:?}", traj.t);
    for (t, e) in traj.t.iter().zip(expect) {
        assert!((t - e).abs() < 1e-15, "{:?}", traj.t);
    }
}

/// x'' = −x from (1, 0) over 0.5 s, first step 0.05, every step archived.
fn half_second(o: AdaptOptions) -> Result<Trajectory, TransientError> {
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 0.5,
        dt: 0.05,
    };
    run(
        &one_dof(1.0),
        &mut [],
        (&[1.0], &[0.0]),
        Scheme::Adapt(o),
        grid,
        &Archive::Every(1),
    )
}

/// COEF_DIVI_PAS = 1 with a step too long for NB_POIN_PERIODE: every step is tried
/// NMAX_ITER_PAS times and kept (Code_Aster's alarm), and each is reported.
#[test]
fn a_step_still_too_long_after_its_tries_is_kept_and_reported() {
    let mut o = AdaptOptions::new(AdaptOrder::Two);
    o.coef_divi = 1.0;
    o.points_per_period = 1000.0;
    o.nmax_iter_pas = 3;
    let traj = half_second(o).unwrap();
    assert_eq!(traj.steps_taken, 10);
    assert_eq!(traj.steps_forced.len(), 10);
    assert_eq!(traj.steps_rejected, 20);
}

/// A step that would fall below PAS_MINI stops the run with that error.
#[test]
fn a_step_below_pas_mini_is_an_error() {
    let mut o = AdaptOptions::new(AdaptOrder::Two);
    o.points_per_period = 1000.0;
    o.pas_mini = Some(0.04);
    let err = half_second(o).unwrap_err();
    assert!(
        matches!(err, TransientError::StepTooSmall { pas_mini, .. } if pas_mini == 0.04),
        "{err:?}"
    );
}

/// Code_Aster's driver and ADAPT_ORDRE2 step written out again, flat, in the order of its
/// Fortran (the step with its retries, then the driver's archive bookkeeping), for
/// x'' = −k x + f cos(Ωt) with m = 1: an independent transcription to hold the loop of
/// adapt_loop.rs (controller, retries, cuts, remainders, vmin) to.
fn transcription(
    k: f64,
    f: f64,
    big: f64,
    x0: f64,
    pas: f64,
    t_end: f64,
    inst: &[f64],
) -> Vec<(f64, f64, f64)> {
    let acc = |t: f64, x: f64| -k * x + f * (big * t).cos();
    let (npper, nrmax, cmult, cdivi) = (50.0, 16, 1.1, 1.333_333_4);
    let (dtmax, dtmin) = (1e6 * pas, 1e-6 * pas);
    let eps_drv = 10.0 * f64::EPSILON;
    let mut archlst = inst.to_vec();
    archlst.push(t_end);
    let (mut d1, mut v1, mut a1) = (x0, 0.0, acc(0.0, x0));
    let mut vmin = 1e-15;
    let mut stab = 1.0;
    let mut step = pas;
    let mut initial = true;
    let (mut time, mut i, mut iarch, mut force_arch) = (0.0, 1usize, 0usize, 0);
    let mut newdt = 0.0;
    let mut out = vec![(0.0, d1, v1)];
    while t_end - time > i as f64 * eps_drv {
        let tol = i as f64 * eps_drv;
        let dt = step;
        if time + dt - archlst[iarch] > tol {
            newdt = archlst[iarch] - time;
            step = newdt;
            force_arch = 1;
        } else if (time + dt - archlst[iarch]).abs() < tol {
            newdt = dt;
            force_arch = 1;
        }
        // intadapt2
        let dtc = if initial { 0.0 } else { step };
        initial = false;
        let mut dt1 = step;
        let mut nr = 1;
        let (d2, vel, v2, a2, dt2) = loop {
            let pas1 = 0.5 * (dtc + dt1);
            let velint = v1 + a1 * pas1;
            let d2 = d1 + velint * dt1;
            let v2 = velint + 0.5 * dt1 * a1;
            let a2 = acc(time + dt1, d2);
            let b = (vmin * dt1).max((d2 - d1).abs());
            let b = if b <= f64::MIN_POSITIVE {
                f64::EPSILON
            } else {
                b
            };
            let freq =
                f64::EPSILON.max(((a2 - a1) / b).abs()).sqrt() / (2.0 * std::f64::consts::PI);
            let err = (npper * freq * dt1).max(100.0 * f64::EPSILON);
            let mut coeff = 1.0;
            if err >= 1.0 {
                coeff = 1.0 / cdivi;
            } else if stab > 4.5 {
                if err < 0.75 {
                    coeff = cmult;
                    stab = 1.0;
                }
            } else {
                stab += 1.0;
            }
            let dt2 = dtmax.min(dt1 * coeff);
            if err >= 1.0 && dt2 >= dtmin && nr < nrmax {
                nr += 1;
                dt1 = dt2;
                continue;
            }
            vmin = velint.abs() * 0.01;
            break (d2, velint, v2, a2, dt2);
        };
        d1 = d2;
        v1 = vel;
        a1 = a2;
        step = dt2;
        time += dt1;
        // dtmcalc
        if force_arch == 2 {
            force_arch = 0;
        }
        if force_arch == 1 {
            if (time - archlst[iarch]).abs() <= tol {
                out.push((archlst[iarch], d2, v2));
                time = archlst[iarch];
                iarch += 1;
                force_arch = 0;
                if (dt - newdt).abs() > tol {
                    step = dt - newdt;
                    force_arch = 2;
                }
            }
        } else {
            // PAS_ARCH = 1: (i − nbarf) mod 1 is always 0.
            out.push((time, d2, v2));
        }
        i += 1;
    }
    out
}

/// The loop against the transcription on a forced oscillator whose apparent frequency
/// changes (the force at 3 times the natural one), every step archived and two listed
/// instants cut: the same instants, positions and velocities to round-off (1e-12 of the
/// motion; both compute the same operations, in the same order for each step).
#[test]
fn the_loop_is_code_asters_driver_and_step() {
    let (k, f, big, x0, pas, t_end) = (4.0, 30.0, 6.0, 0.2, 1e-3, 3.0);
    let inst = [0.7345, 2.1];
    let reference = transcription(k, f, big, x0, pas, t_end, &inst);
    let s = one_dof(k);
    let forcing = Forcing {
        generalized_force: vec![f],
        multiplier: Box::new(move |t| (big * t).cos()),
    };
    let traj = integrate(
        &s,
        &mut [],
        &[forcing],
        (&[x0], &[0.0]),
        adapt(AdaptOrder::Two, 50.0),
        TimeGrid {
            t0: 0.0,
            t_end,
            dt: pas,
        },
        &Archive::EveryAnd(1, inst.to_vec()),
        &mut |_| {},
    )
    .unwrap();
    assert!(
        traj.steps_rejected > 0,
        "the case must exercise the retries"
    );
    assert_eq!(traj.t.len(), reference.len());
    let scale = reference.iter().fold(0.0f64, |m, r| m.max(r.1.abs()));
    for (i, &(t, x, v)) in reference.iter().enumerate() {
        assert!(
            (traj.t[i] - t).abs() <= 1e-12 * t_end,
            "instant {i}: {} vs {t}",
            traj.t[i]
        );
        assert!((traj.q_at(i)[0] - x).abs() <= 1e-12 * scale, "q at {t}");
        assert!(
            (traj.v_at(i)[0] - v).abs() <= 1e-12 * scale * 10.0,
            "v at {t}"
        );
    }
}
