//! RUNGE_KUTTA_32 and RUNGE_KUTTA_54 as Code_Aster computes them (rk_loop.rs): the loop
//! against an independent flat transcription of Code_Aster's step, step control and
//! driver; the order of each pair at a fixed step (PAS_MINI = PAS_MAXI) against the exact
//! free vibration; the fixed step's cut at a listed instant; the stop below PAS_MINI
//! (Code_Aster's ALGORITH5_23). The event-located pairs (LOCALISATION_CHOC='OUI') are
//! tested in impact.rs and from_rest.rs.

use super::*;
use crate::error::Error;

fn rk(pair: RkPair) -> AdaptiveOptions {
    AdaptiveOptions::new(pair)
}

/// Code_Aster's coefficients, written out again from its routines (not taken from
/// scheme/runge_kutta.rs): the nodes c, the rows of a, its error weights, and the
/// exponent of its step rule.
struct Coefficients {
    c: Vec<f64>,
    a: Vec<Vec<f64>>,
    e: Vec<f64>,
    p: f64,
}

fn coefficients(pair: RkPair) -> Coefficients {
    match pair {
        RkPair::BogackiShampine32 => Coefficients {
            c: vec![0.0, 0.5, 0.75, 1.0],
            a: vec![
                vec![],
                vec![0.5],
                vec![0.0, 0.75],
                vec![2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0],
            ],
            e: vec![5.0 / 72.0, -1.0 / 12.0, -1.0 / 9.0, 1.0 / 8.0],
            p: 4.0,
        },
        RkPair::DormandPrince54 => Coefficients {
            c: vec![0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0],
            a: vec![
                vec![],
                vec![0.2],
                vec![3.0 / 40.0, 9.0 / 40.0],
                vec![44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
                vec![
                    19372.0 / 6561.0,
                    -25360.0 / 2187.0,
                    64448.0 / 6561.0,
                    -212.0 / 729.0,
                ],
                vec![
                    9017.0 / 3168.0,
                    -355.0 / 33.0,
                    46732.0 / 5247.0,
                    49.0 / 176.0,
                    -5103.0 / 18656.0,
                ],
                vec![
                    35.0 / 384.0,
                    0.0,
                    500.0 / 1113.0,
                    125.0 / 192.0,
                    -2187.0 / 6784.0,
                    11.0 / 84.0,
                ],
            ],
            e: vec![
                71.0 / 57600.0,
                0.0,
                -71.0 / 16695.0,
                71.0 / 1920.0,
                -17253.0 / 339200.0,
                22.0 / 525.0,
                -1.0 / 40.0,
            ],
            p: 6.0,
        },
    }
}

/// What the transcription did besides its archive.
#[derive(Debug, Default)]
struct Counts {
    retries: usize,
    /// Retries accepted because their error did not fall (err taken as 0.99).
    stalled: usize,
}

/// The settings of a transcribed run.
struct Case {
    pair: RkPair,
    tol: f64,
    alpha: f64,
    pas: f64,
    pas_maxi: f64,
    t_end: f64,
    inst: Vec<f64>,
    pas_arch: usize,
}

/// Code_Aster's driver and RUNGE_KUTTA step written out again, flat and scalar, in the
/// order of its Fortran (`dtmcalc`, `intruku32` / `intruku54`), for one unknown with
/// x'' = acc(t, x, v) from rest: the instants, displacements and velocities it archives.
/// The one departure is aster-nl's: a landed instant is the listed one exactly (Code_Aster
/// keeps t₁ + h, an ulp away).
fn transcription(
    case: &Case,
    acc: &dyn Fn(f64, f64, f64) -> f64,
) -> (Vec<(f64, f64, f64)>, Counts) {
    let co = coefficients(case.pair);
    let s = co.c.len();
    let eps = f64::EPSILON;
    let (eps_drv, epsi) = (10.0 * eps, 100.0 * eps);
    let mut archlst = case.inst.clone();
    archlst.push(case.t_end);
    // dtmprep: the driver's own test of a free step.
    let adapt = (case.pas_maxi / (1e-6 * case.pas) - 1.0).abs() > eps;
    let mut counts = Counts::default();
    let (mut d1, mut v1) = (0.0, 0.0);
    let mut a1 = acc(0.0, d1, v1);
    let mut step = case.pas;
    let mut params: Option<(f64, f64, f64)> = None;
    let (mut time, mut i, mut iarch, mut force_arch, mut nbarf) = (0.0, 1usize, 0usize, 0, 0);
    let mut newdt = 0.0;
    let mut out = vec![(0.0, d1, v1)];
    while case.t_end - time > i as f64 * eps_drv {
        let tol_i = i as f64 * eps_drv;
        let dt = step;
        if time + dt - archlst[iarch] > tol_i {
            newdt = archlst[iarch] - time;
            step = newdt;
            force_arch = 1;
        } else if (time + dt - archlst[iarch]).abs() < tol_i {
            newdt = dt;
            force_arch = 1;
        }
        // intruku: the parameters at the first call, from the step it is handed.
        let mut h = step;
        let (dtmin, dtmax, deltadt) = *params.get_or_insert_with(|| {
            let (dtmin, dtmax) = (1e-10 * h, case.pas_maxi);
            (dtmin, dtmax, (dtmax / dtmin - 1.0).abs())
        });
        let mut errt0 = f64::MAX;
        let (d2, v2, a2, dt2) = loop {
            let (mut kde, mut kvi) = (Vec::new(), Vec::new());
            let (mut d2, mut v2, mut a2) = (d1, v1, a1);
            for ee in 1..s {
                kde.push(v2);
                kvi.push(a2);
                d2 = d1;
                v2 = v1;
                for ss in 0..ee {
                    d2 += h * co.a[ee][ss] * kde[ss];
                    v2 += h * co.a[ee][ss] * kvi[ss];
                }
                a2 = acc(time + h * co.c[ee], d2, v2);
            }
            let mut dt2 = h;
            if deltadt >= epsi {
                let (mut errde, mut errvi) = (0.0, 0.0);
                for ee in 0..s - 1 {
                    errde += co.e[ee] * kde[ee];
                    errvi += co.e[ee] * kvi[ee];
                }
                errde += co.e[s - 1] * v2;
                errvi += co.e[s - 1] * a2;
                let (ddep, dvit) = ((d2 - d1).abs(), (v2 - v1).abs());
                let skd = (case.tol * (d1 + case.alpha).abs())
                    .max(case.tol * (ddep + case.alpha))
                    .max(epsi);
                let skv = (case.tol * (v1 + case.alpha).abs())
                    .max(case.tol * (dvit + case.alpha))
                    .max(epsi);
                let errd = (errde / skd) * (errde / skd);
                let errv = (errvi / skv) * (errvi / skv);
                let mut errt = (h * ((errd + errv) / 2.0).sqrt()).max(epsi);
                if errt * 1.01 > errt0 {
                    errt = 0.99;
                    counts.stalled += 1;
                }
                let coeff = if errt < (0.9f64 / 5.0).powf(co.p) {
                    5.0
                } else if errt > (0.9f64 / 0.2).powf(co.p) {
                    0.2
                } else {
                    0.9 * errt.powf(-1.0 / co.p)
                };
                dt2 = dtmax.min(h * coeff);
                if errt >= 1.0 && dt2 >= dtmin {
                    h = dt2;
                    errt0 = errt;
                    counts.retries += 1;
                    continue;
                }
                assert!(dt2 >= dtmin, "ALGORITH5_23 in the transcription");
            }
            break (d2, v2, a2, dt2);
        };
        d1 = d2;
        v1 = v2;
        a1 = a2;
        step = dt2;
        time += h;
        // dtmcalc's bookkeeping.
        if force_arch == 2 {
            force_arch = 0;
            if !adapt {
                step = case.pas;
            }
        }
        if force_arch == 1 {
            if (time - archlst[iarch]).abs() <= tol_i {
                time = archlst[iarch];
                out.push((time, d1, v1));
                iarch += 1;
                force_arch = 0;
                if (dt - newdt).abs() > tol_i {
                    nbarf += 1;
                    step = dt - newdt;
                    force_arch = 2;
                } else if !adapt {
                    step = case.pas;
                }
            }
        } else if (i - nbarf) % case.pas_arch == 0 {
            out.push((time, d1, v1));
        }
        i += 1;
    }
    (out, counts)
}

/// The force of the transcribed case: 3 + 0.5 cos 7t from td on, nothing before.
fn multiplier(td: f64, t: f64) -> f64 {
    if t >= td {
        3.0 + 0.5 * (7.0 * t).cos()
    } else {
        0.0
    }
}

/// x'' = −4x + H(t − td)(3 + 0.5 cos 7t) from rest: nothing moves until the force
/// switches on at td (the step grows by 5 up to PAS_MAXI), the step across td is retried,
/// and a retry whose error grows (the scale |Δv| shrinks with the step) is accepted by
/// Code_Aster's stall rule; then a forced oscillation under the step control. Written as
/// the model sums it, −(k x) + f(t), so that both compute the same operations.
fn forced(td: f64) -> impl Fn(f64, f64, f64) -> f64 {
    move |t: f64, x: f64, _v: f64| -(4.0 * x) + multiplier(td, t)
}

fn run_case(case: &Case, td: f64) -> Trajectory {
    let s = one_dof(4.0);
    let forcing = Forcing {
        generalized_force: vec![1.0],
        multiplier: Box::new(move |t| multiplier(td, t)),
    };
    let mut o = rk(case.pair);
    o.tolerance = case.tol;
    o.alpha = case.alpha;
    o.pas_maxi = Some(case.pas_maxi);
    integrate(
        &s,
        &mut [],
        &[forcing],
        (&[0.0], &[0.0]),
        Scheme::Adaptive(o),
        TimeGrid {
            t0: 0.0,
            t_end: case.t_end,
            dt: case.pas,
        },
        &Archive::EveryAnd(case.pas_arch, case.inst.clone()),
        &mut |_| {},
    )
    .unwrap()
}

/// The loop against the transcription, both pairs (RUNGE_KUTTA_54 with ALPHA), every other
/// step archived and two listed instants cut: the same instants, positions and velocities
/// to round-off (1e-12 of the motion: both compute the same operations in the same order,
/// the force as the loop's model sums it). The case must exercise the retries and the stall
/// rule: changing the retry or acceptance rule, the thresholds or the driver changes the
/// steps, and the instants differ.
#[test]
fn the_loop_is_code_asters_driver_and_step() {
    for (pair, tol, alpha, td) in [
        (RkPair::BogackiShampine32, 1e-6, 0.0, 0.285),
        (RkPair::DormandPrince54, 1e-8, 1e-3, 0.2835),
    ] {
        let case = Case {
            pair,
            tol,
            alpha,
            pas: 1e-3,
            pas_maxi: 0.05,
            t_end: 3.0,
            inst: vec![0.7345, 2.1],
            pas_arch: 2,
        };
        let (reference, counts) = transcription(&case, &forced(td));
        let traj = run_case(&case, td);
        eprintln!(
            "{pair:?}: {} archived, {} steps, {} retried; transcription {counts:?}",
            traj.t.len(),
            traj.steps_taken,
            traj.steps_rejected
        );
        assert!(counts.retries > counts.stalled, "{pair:?}: {counts:?}");
        assert!(
            counts.stalled > 0,
            "{pair:?}: the stall rule must be exercised"
        );
        assert_eq!(traj.steps_rejected, counts.retries, "{pair:?}");
        assert_eq!(traj.t.len(), reference.len(), "{pair:?}");
        let scale = reference.iter().fold(0.0f64, |m, r| m.max(r.1.abs()));
        for (i, &(t, x, v)) in reference.iter().enumerate() {
            assert!(
                (traj.t[i] - t).abs() <= 1e-12 * case.t_end,
                "{pair:?} instant {i}: {} vs {t}",
                traj.t[i]
            );
            assert!(
                (traj.q_at(i)[0] - x).abs() <= 1e-12 * scale,
                "{pair:?} q at {t}: {} vs {x}",
                traj.q_at(i)[0]
            );
            assert!(
                (traj.v_at(i)[0] - v).abs() <= 1e-12 * scale * 10.0,
                "{pair:?} v at {t}"
            );
        }
        for ti in case.inst {
            assert!(traj.t.contains(&ti), "{pair:?}: {ti} landed on exactly");
        }
    }
}

/// Largest |x − cos t| over 10 s for x'' = −x from (1, 0) at the fixed step h
/// (PAS_MINI = PAS_MAXI = PAS = h: Code_Aster does not judge the step), every step
/// archived.
fn fixed_step_error(pair: RkPair, h: f64) -> f64 {
    let mut o = rk(pair);
    o.pas_mini = Some(h);
    o.pas_maxi = Some(h);
    let traj = run(
        &one_dof(1.0),
        &mut [],
        (&[1.0], &[0.0]),
        Scheme::Adaptive(o),
        TimeGrid {
            t0: 0.0,
            t_end: 10.0,
            dt: h,
        },
        &Archive::Every(1),
    )
    .unwrap();
    assert_eq!(traj.steps_rejected, 0);
    assert_eq!(traj.steps_taken, (10.0 / h).round() as usize);
    traj.t
        .iter()
        .enumerate()
        .map(|(i, &t)| (traj.q_at(i)[0] - t.cos()).abs())
        .fold(0.0, f64::max)
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

/// At a fixed step the pairs keep their orders: 3 for RUNGE_KUTTA_32, 5 for
/// RUNGE_KUTTA_54 (the propagated solution is the higher order's), against the exact free
/// vibration, h = 0.2·2^(−k), k = 0..3 (RUNGE_KUTTA_54's smallest error stays far above
/// round-off). Asserted within ±0.25 of the order.
#[test]
fn fixed_step_orders_are_three_and_five() {
    let steps: Vec<f64> = (0..4).map(|k| 0.2 / f64::from(1 << k)).collect();
    for (pair, order) in [
        (RkPair::BogackiShampine32, 3.0),
        (RkPair::DormandPrince54, 5.0),
    ] {
        let errs: Vec<f64> = steps.iter().map(|&h| fixed_step_error(pair, h)).collect();
        let p = slope(&steps, &errs);
        eprintln!("{pair:?} at fixed steps {steps:?}: errors {errs:?}, order {p}");
        assert!((p - order).abs() < 0.25, "{pair:?}: observed order {p}");
    }
}

/// PAS_MINI = PAS_MAXI: every step is PAS, cut at the listed instant 0.025 and followed by
/// the remainder of the cut step, then PAS again (Code_Aster's driver).
#[test]
fn a_fixed_step_is_cut_at_a_listed_instant_and_resumes() {
    let mut o = rk(RkPair::BogackiShampine32);
    o.pas_mini = Some(0.01);
    o.pas_maxi = Some(0.01);
    let traj = run(
        &one_dof(1.0),
        &mut [],
        (&[1.0], &[0.0]),
        Scheme::Adaptive(o),
        TimeGrid {
            t0: 0.0,
            t_end: 0.06,
            dt: 0.01,
        },
        &Archive::EveryAnd(1, vec![0.025]),
    )
    .unwrap();
    let expect = [0.0, 0.01, 0.02, 0.025, 0.03, 0.04, 0.05, 0.06];
    assert_eq!(traj.t.len(), expect.len(), "{:?}", traj.t);
    for (t, e) in traj.t.iter().zip(expect) {
        assert!((t - e).abs() < 1e-15, "{:?}", traj.t);
    }
}

/// A step whose next length falls below PAS_MINI stops the run (Code_Aster's
/// ALGORITH5_23): a TransientError naming the instant, the step and PAS_MINI, which
/// becomes an error on SCHEMA_TEMPS/PAS_MINI. Here TOLERANCE 1e-12 asks for steps of about
/// 1e-3 on x'' = −x while PAS_MINI is 0.04.
#[test]
fn a_step_below_pas_mini_stops_the_run() {
    for pair in [RkPair::BogackiShampine32, RkPair::DormandPrince54] {
        let mut o = rk(pair);
        o.tolerance = 1e-12;
        o.pas_mini = Some(0.04);
        let err = run(
            &one_dof(1.0),
            &mut [],
            (&[1.0], &[0.0]),
            Scheme::Adaptive(o),
            TimeGrid {
                t0: 0.0,
                t_end: 1.0,
                dt: 0.05,
            },
            &Archive::Every(1),
        )
        .unwrap_err();
        let TransientError::StepTooSmall { t, dt, pas_mini } = err.clone() else {
            panic!("{pair:?}: {err:?}")
        };
        assert_eq!(pas_mini, 0.04);
        assert!(dt < pas_mini && t < 1.0, "{pair:?}: {err:?}");
        let e = Error::from(err);
        assert_eq!(e.keyword.as_deref(), Some("SCHEMA_TEMPS/PAS_MINI"));
        assert!(e.message.contains("PAS_MINI"), "{}", e.message);
    }
}

/// PAS_MAXI below PAS is refused, as Code_Aster does.
#[test]
fn pas_maxi_below_pas_is_refused() {
    let mut o = rk(RkPair::DormandPrince54);
    o.pas_maxi = Some(1e-3);
    let err = run(
        &one_dof(1.0),
        &mut [],
        (&[1.0], &[0.0]),
        Scheme::Adaptive(o),
        TimeGrid {
            t0: 0.0,
            t_end: 1.0,
            dt: 1e-2,
        },
        &Archive::Every(1),
    )
    .unwrap_err();
    assert!(
        matches!(&err, TransientError::Invalid { keyword, .. } if keyword == "SCHEMA_TEMPS/PAS_MAXI"),
        "{err:?}"
    );
}
