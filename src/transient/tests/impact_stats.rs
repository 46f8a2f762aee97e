//! POST_DYNA_MODA_T's statistics (impact_stats.rs) on histories whose statistics are known
//! in closed form: trains of sampled half-sine pulses, a harmonic slide under a constant
//! normal force, and the impact oscillator integrated by RUNGE_KUTTA_54 (the stop at the
//! spring's rest position, so that every contact is half a period of the contact
//! pulsation).
//!
//! A half-sine pulse F sin(π j/N) sampled at t = j h, j = 0..N, has its samples in contact
//! at j = 1..N−1; the references follow from Σ_{j=1}^{N−1} sin(π j/N) = cot(π/(2N)).
//! Tolerances: sums of a few hundred terms of size 1 agree to a few ulps; 1e-12 relative.

use super::*;
use crate::transient::impact_stats::{detect, histogram, mean_and_deviation, wear, Series};
use std::f64::consts::PI;

const TOL: f64 = 1e-12;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

/// `pulses` half-sine pulses of N = `n` intervals and peak `f`, separated by `rest`
/// samples at zero, starting after `lead` zeros; step `h`. Returns (t, FN, VN) with VN the
/// pulse's derivative (so V_IMPACT is known).
fn pulse_train(
    pulses: usize,
    n: usize,
    rest: usize,
    lead: usize,
    f: f64,
    h: f64,
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut fs = vec![0.0; lead];
    let mut vs = vec![0.0; lead];
    for p in 0..pulses {
        fs.push(0.0);
        vs.push(0.0);
        for j in 1..n {
            let a = PI * j as f64 / n as f64;
            fs.push(f * a.sin());
            vs.push(-f * a.cos());
        }
        fs.push(0.0);
        vs.push(0.0);
        if p + 1 < pulses {
            fs.extend(std::iter::repeat_n(0.0, rest));
            vs.extend(std::iter::repeat_n(0.0, rest));
        }
    }
    fs.extend([0.0, 0.0]);
    vs.extend([0.0, 0.0]);
    let t = (0..fs.len()).map(|k| k as f64 * h).collect();
    (t, fs, vs)
}

#[test]
fn a_train_of_pulses_gives_their_closed_form_statistics() {
    let (n, h, f) = (40, 1e-3, 250.0);
    let (t, fs, vs) = pulse_train(5, n, 60, 7, f, h);
    let d = detect(&t, &fs, &vs, 0.0, 0.0);
    assert_eq!(d.impacts.len(), 5);
    assert!(d.open.is_none());
    assert_eq!(d.contacts.len(), 5);
    let impulse = h * f / (PI / (2.0 * n as f64)).tan();
    for (p, imp) in d.impacts.iter().enumerate() {
        let start = 7 + p * (n + 1 + 60);
        assert_eq!(imp.first, start + 1);
        assert_eq!(imp.end, Some(start + n));
        assert_eq!(imp.contacts, 1);
        // The peak sample j = N/2: sin(π/2) is 1 exactly.
        assert_eq!(imp.f_max, f);
        assert!(close(imp.t_peak, (start + n / 2) as f64 * h, TOL));
        assert!(close(imp.duration, (n - 1) as f64 * h, TOL));
        assert!(
            close(imp.impulse, impulse, TOL),
            "{} {impulse}",
            imp.impulse
        );
        assert!(close(imp.v_impact, -f * (PI / n as f64).cos(), TOL));
    }
    assert_eq!(d.f_max_abs, f);
    // The continuous impulse of the pulse, 2 F N h/π, is approached as 1 − π²/(12 N²).
    let continuous = 2.0 * f * n as f64 * h / PI;
    let rel = (impulse - continuous) / continuous;
    assert!(
        close(rel, -PI * PI / (12.0 * (n * n) as f64), 2e-3),
        "{rel}"
    );
}

#[test]
fn short_rests_merge_contacts_into_one_impact() {
    // Two pulses with 4 zeros between the ending sample of the first and the start of the
    // second.
    let (n, h, f) = (10, 0.5, 3.0);
    let (t, fs, vs) = pulse_train(2, n, 4, 2, f, h);
    // Rest of the first pulse: from its ending sample (zero) to the next sample in
    // contact, 6 samples (4 zeros and the second pulse's j = 0) = 3 s later.
    let apart = detect(&t, &fs, &vs, 0.0, 2.99);
    assert_eq!(apart.impacts.len(), 2);
    for dr in [3.0, 3.5] {
        let merged = detect(&t, &fs, &vs, 0.0, dr);
        assert_eq!(merged.impacts.len(), 1, "DUREE_REPOS {dr}");
        let imp = merged.impacts[0];
        assert_eq!(imp.contacts, 2);
        // From the first pulse's first sample to the second pulse's ending sample.
        let first = 2 + 1;
        let end = 2 + (n + 1) + 4 + n;
        assert_eq!((imp.first, imp.end), (first, Some(end)));
        assert!(close(imp.duration, (end - first) as f64 * h, TOL));
        let one = h * f / (PI / (2.0 * n as f64)).tan();
        assert!(close(imp.impulse, 2.0 * one, TOL));
        assert_eq!(merged.contacts.len(), 2);
    }
}

#[test]
fn threshold_and_open_impacts() {
    let (n, h, f) = (8, 1.0, 10.0);
    let (t, mut fs, mut vs) = pulse_train(2, n, 3, 0, f, h);
    // Cut the history inside the second pulse: it stays open.
    let cut = (n + 1) + 3 + n / 2 + 1;
    fs.truncate(cut);
    vs.truncate(cut);
    let d = detect(&t[..cut], &fs, &vs, 0.0, 0.0);
    assert_eq!(d.impacts.len(), 1);
    let open = d.open.expect("the second pulse is open");
    assert_eq!(open.end, None);
    assert_eq!(open.f_max, f);
    assert_eq!(d.f_max_abs, f);
    // A threshold of F sin(2π/8) keeps the samples j = 3, 4, 5 of a pulse of 8 intervals
    // (sin(3π/8) > sin(π/4)): duration 3 steps.
    let s = f * (PI / 4.0).sin();
    let (t, fs, vs) = pulse_train(1, n, 0, 1, f, h);
    let d = detect(&t, &fs, &vs, s * (1.0 + 1e-12), 0.0);
    assert_eq!(d.impacts.len(), 1);
    assert_eq!(d.impacts[0].first, 1 + 3);
    assert!(close(d.impacts[0].duration, 3.0 * h, TOL));
    // Nothing above the threshold: no impact, F_MAX_ABS 0.
    let none = detect(&t, &fs, &vs, 2.0 * f, 0.0);
    assert!(none.impacts.is_empty() && none.open.is_none());
    assert_eq!(none.f_max_abs, 0.0);
}

#[test]
fn histogram_classes_and_shares() {
    let h = histogram(&[1.0, 2.0, 3.0, 4.0], 2);
    assert_eq!(h.len(), 2);
    assert_eq!((h[0].lower, h[0].upper, h[0].proba), (1.0, 2.5, 0.5));
    assert_eq!((h[1].lower, h[1].upper, h[1].proba), (2.5, 4.0, 0.5));
    // The largest value belongs to the last class; a class may be empty.
    let h = histogram(&[0.0, 0.1, 0.2, 10.0], 4);
    let p: Vec<f64> = h.iter().map(|c| c.proba).collect();
    assert_eq!(p, vec![0.75, 0.0, 0.0, 0.25]);
    // Equal values: all in the first class, of zero width.
    let h = histogram(&[5.0; 3], 3);
    assert_eq!(h[0].proba, 1.0);
    assert!(h.iter().all(|c| c.lower == 5.0 && c.upper == 5.0));
    // No value: zero classes.
    assert!(histogram(&[], 4)
        .iter()
        .all(|c| c.proba == 0.0 && c.upper == 0.0));
    let (m, s) = mean_and_deviation(&[99.0 + 1e-13; 7]);
    assert_eq!(s, 0.0);
    assert!(close(m, 99.0, TOL));
    let (m, s) = mean_and_deviation(&[1.0, 3.0]);
    assert_eq!((m, s), (2.0, 1.0));
}

/// A slide x = U cos(ω t) under a constant normal force, sampled with N steps per half
/// period: FN·|v| averages FN U ω cot(π/(2N))/N over whole half periods (the trapezoidal
/// rule of |sin| hits its zeros), → FN U ω 2/π as N grows.
#[test]
fn wear_power_of_a_harmonic_slide() {
    let (fnorm, u, w, n) = (20.0, 1e-3, 100.0, 50usize);
    let half = PI / w;
    let h = half / n as f64;
    let halves = 8;
    let samples = halves * n + 1;
    let t: Vec<f64> = (0..samples).map(|k| k as f64 * h).collect();
    let x: Vec<f64> = t.iter().map(|&s| u * (w * s).cos()).collect();
    let v: Vec<f64> = t.iter().map(|&s| -u * w * (w * s).sin()).collect();
    let f_n = vec![fnorm; samples];
    let zero = vec![0.0; samples];
    let yl = vec![0.3; samples];
    let series = Series {
        t: &t,
        f_n: &f_n,
        f_t: [&zero, &zero],
        v_n: &zero,
        v_t: [&zero, &v],
        loc: [&x, &yl, &zero],
        sticking: None,
    };
    let exact = fnorm * u * w / (PI / (2.0 * n as f64)).tan() / n as f64;
    let one = wear(&series, 0.0, 0.0, 1).unwrap();
    assert!(
        close(one.wear_power, exact, TOL),
        "{} {exact}",
        one.wear_power
    );
    let continuous = fnorm * u * w * 2.0 / PI;
    assert!((one.wear_power / continuous - 1.0).abs() < 4e-4);
    // Always in contact: one impact still open, none counted; FN statistics are FN.
    assert_eq!(one.counts.per_second, 0);
    assert_eq!(one.normal.max, fnorm);
    assert!(close(one.normal.mean_total, fnorm, TOL) && close(one.normal.rms_contact, fnorm, TOL));
    // DXLOC = U cos over m = 8N + 1 samples: the first 8N cover four periods (Σ cos = 0,
    // Σ cos² = 4N), the last one adds U: mean U/m, RMS U √((4N + 1)/m).
    let d = one.displacement[0];
    let m = samples as f64;
    assert!(close(d.mean, u / m, 1e-9), "{}", d.mean);
    assert!(close(
        d.rms,
        u * ((m - 1.0) / 2.0 + 1.0).sqrt() / m.sqrt(),
        TOL
    ));
    assert_eq!((d.max, d.min), (u, -u));
    // DYLOC = 0.3, DZLOC = 0: radial 0.3, angle 0; FT1 = FT2 = 0.
    assert!(
        close(one.radial.mean, 0.3, TOL) && one.radial.deviation < 1e-15,
        "{:?}",
        one.radial
    );
    assert_eq!(one.angle.max, 0.0);
    assert_eq!(one.tangential[1].rms, 0.0);
    // Four blocks of 2N samples (the last sample left out). A block spans 2N − 1 steps:
    // two half periods but their last step, where the trapezoid holds h p/2, p = FN U ω
    // sin(π/N); every block alike.
    let four = wear(&series, 0.0, 0.0, 4).unwrap();
    let nf = n as f64;
    let block =
        fnorm * u * w * (2.0 / (PI / (2.0 * nf)).tan() - 0.5 * (PI / nf).sin()) / (2.0 * nf - 1.0);
    assert!(
        close(four.wear_power, block, TOL),
        "{} {block}",
        four.wear_power
    );
    // Too many blocks.
    assert!(wear(&series, 0.0, 0.0, samples).is_err());
    // Code_Aster's `pusure` leaves out the intervals whose first sample sticks (VINT13):
    // flagging every other half period as a stick halves the wear power exactly (the
    // half periods carry the same integral), and flagging all of them gives 0. The
    // flag of the last sample starts no interval.
    let every_other: Vec<f64> = (0..samples)
        .map(|k| if (k / n) % 2 == 1 { 1.0 } else { 0.0 })
        .collect();
    let half_stuck = wear(
        &Series {
            sticking: Some(&every_other),
            ..series
        },
        0.0,
        0.0,
        1,
    )
    .unwrap();
    assert!(
        close(half_stuck.wear_power, exact / 2.0, TOL),
        "{} {}",
        half_stuck.wear_power,
        exact / 2.0
    );
    let all: Vec<f64> = (0..samples)
        .map(|k| if k + 1 < samples { 1.0 } else { 0.0 })
        .collect();
    let stuck = wear(
        &Series {
            sticking: Some(&all),
            ..series
        },
        0.0,
        0.0,
        1,
    )
    .unwrap();
    assert_eq!(stuck.wear_power, 0.0);
    // A flag column of another length is refused.
    assert!(wear(
        &Series {
            sticking: Some(&all[1..]),
            ..series
        },
        0.0,
        0.0,
        1
    )
    .is_err());
}

#[test]
fn polar_displacement_and_impact_counts() {
    // DYLOC, DZLOC on a circle of radius R at angles 10°, 20°, ...: radial R, angle known.
    let r = 2.0;
    let k = 9;
    let ang: Vec<f64> = (1..=k).map(|i| 10.0 * i as f64).collect();
    let y: Vec<f64> = ang.iter().map(|a| r * a.to_radians().cos()).collect();
    let z: Vec<f64> = ang.iter().map(|a| r * a.to_radians().sin()).collect();
    let t: Vec<f64> = (0..k).map(|i| i as f64).collect();
    let zero = vec![0.0; k];
    let s = Series {
        t: &t,
        f_n: &zero,
        f_t: [&zero, &zero],
        v_n: &zero,
        v_t: [&zero, &zero],
        loc: [&zero, &y, &z],
        sticking: None,
    };
    let st = wear(&s, 0.0, 0.0, 1).unwrap();
    assert!(close(st.radial.mean, r, TOL) && st.radial.deviation < 1e-15);
    assert!(close(st.angle.mean, 50.0, TOL));
    assert!(close(st.angle.max, 90.0, TOL) && close(st.angle.min, 10.0, TOL));
    // Population deviation of 10, 20, ..., 90: 10 √(20/3).
    assert!(close(
        st.angle.deviation,
        10.0 * (20.0f64 / 3.0).sqrt(),
        TOL
    ));
    // Five pulses of 40 steps of 1 ms, 60 zeros apart, 7 zeros first: 5 impacts of 39 ms,
    // one contact each, over (samples) ms.
    let (t, fs, vs) = pulse_train(5, 40, 60, 7, 250.0, 1e-3);
    let m = t.len();
    let zero = vec![0.0; m];
    let s = Series {
        t: &t,
        f_n: &fs,
        f_t: [&zero, &zero],
        v_n: &vs,
        v_t: [&zero, &zero],
        loc: [&zero, &zero, &zero],
        sticking: None,
    };
    let c = wear(&s, 0.0, 0.0, 1).unwrap().counts;
    let acquired = m as f64 * 1e-3;
    assert_eq!(c.per_second, (5.0 / acquired).floor() as i64);
    assert_eq!(c.contacts_per_impact, 1);
    assert!(close(c.duration_mean, 39e-3, TOL) && close(c.duration_min, 39e-3, TOL));
    assert!(close(c.contact_mean, 39e-3, TOL));
    assert_eq!(
        c.percent_in_impact,
        (100.0 * 5.0 * 39e-3 / acquired).floor() as i64
    );
}

/// The impact oscillator with the stop at the spring's rest position: m = 1, k = 1e4
/// (ω = 100), k_n = 9.9e5 (contact pulsation ω_c = 1000), started at x = 0 with velocity
/// −v0 (away from the stop). Contacts begin at t_i = π/ω + i (π/ω + π/ω_c) and last π/ω_c;
/// in contact FN = k_n (v0/ω_c) sin(ω_c (t − t_i)). Archived at t = j h, h = π/(50 ω_c),
/// the instants fall on the onsets, releases and peaks, so the sampled statistics are the
/// closed forms of the pulse train: F_MAX = k_n v0/ω_c, T_CHOC = 49 h,
/// IMPULSION = h F_MAX cot(π/100). Integrated by RUNGE_KUTTA_54 at TOLERANCE 1e-10, whose
/// solution is within ~1e-8 relative of the exact one (impact.rs): 1e-7 here.
#[test]
fn the_impact_oscillator_integrated() {
    let (k, kn, v0) = (1e4, 9.9e5, 0.1);
    let (w, wc) = (100.0f64, 1000.0f64);
    let h = PI / (50.0 * wc);
    let t_end = 0.2;
    let count = (t_end / h).floor() as usize;
    let inst: Vec<f64> = (0..=count).map(|j| j as f64 * h).collect();
    let s = one_dof(k);
    let mut shocks = vec![stop_shock(0.0, kn, 0.0)];
    let grid = TimeGrid {
        t0: 0.0,
        t_end,
        dt: 1e-4,
    };
    let Some(Scheme::Adaptive(mut o)) = Scheme::from_name("RUNGE_KUTTA_54") else {
        panic!("RUNGE_KUTTA_54 is adaptive")
    };
    o.tolerance = 1e-10;
    o.locate_contacts = true;
    let scheme = Scheme::Adaptive(o);
    let traj = run(
        &s,
        &mut shocks,
        (&[0.0], &[-v0]),
        scheme,
        grid,
        &Archive::Instants(inst),
    )
    .unwrap();
    let fs: Vec<f64> = traj.shocks[0].iter().map(|x| x.f_n).collect();
    let vs: Vec<f64> = traj.shocks[0].iter().map(|x| x.v_n).collect();
    // A threshold of 1 N (F_MAX = 99 N; the first sample in a contact carries 6.2 N)
    // keeps the samples on the onsets and releases, where FN is 0 up to the solver's
    // error, out of contact.
    let d = detect(&traj.t, &fs, &vs, 1.0, 0.0);
    let period = PI / w + PI / wc;
    let full = ((t_end - PI / w) / period).floor() as usize + 1;
    assert_eq!(d.impacts.len(), full);
    let fmax = kn * v0 / wc;
    let impulse = h * fmax / (PI / 100.0).tan();
    for (i, imp) in d.impacts.iter().enumerate() {
        let onset = PI / w + i as f64 * period;
        assert!(close(imp.f_max, fmax, 1e-7), "{} {fmax}", imp.f_max);
        assert!(close(imp.t_peak, onset + PI / (2.0 * wc), 1e-9));
        assert!(close(imp.duration, 49.0 * h, 1e-9));
        assert!(close(imp.impulse, impulse, 1e-7));
        assert_eq!(imp.contacts, 1);
    }
}
