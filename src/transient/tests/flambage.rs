//! The FLAMBAGE law in the integrators (flambage.rs, dis_choc.rs) against the exact motion
//! of a mass thrown on a buckling stop, written here from the law's definition (not from
//! its code): elastic until the stop's force reaches FNOR_CRIT, a constant force
//! FNOR_POST_FL while the mass crushes the stop, elastic unloading from the crushed
//! position with the post-buckling stiffness, release there. Every scheme must see the law:
//! DIFF_CENTRE, NEWMARK, ADAPT_ORDRE2, DEVOGE, RUNGE_KUTTA_54. And a run split in two
//! (integrate_from, the restart of ETAT_INIT=_F(RESULTAT=...)) is the run in one.
//!
//! The error the schemes make is first order in the step near buckling, whatever their
//! order: the element is marked buckled at the end of the step in which its force reaches
//! FNOR_CRIT (it is a state, advanced at accepted steps only), so the force stays at
//! FNOR_CRIT instead of FNOR_POST_FL for a part of that step. The lost impulse is at most
//! h_b (FNOR_CRIT − FNOR_POST_FL), h_b the step that buckled, and it shortens the crush by
//! at most v_b h_b (FNOR_CRIT − FNOR_POST_FL)/FNOR_POST_FL (v_b the velocity at buckling:
//! the plateau turns kinetic energy m v²/2 into crush against FNOR_POST_FL); the instant of
//! buckling is found at that step's end, within h_b after the exact one.

use super::*;
use crate::transient::flambage::{Buckling, BucklingSpec};
use crate::transient::{AdaptOptions, AdaptOrder};

/// A mass `m` on a spring `k` (to ground, at rest at 0) thrown at `v0` on a buckling stop
/// at 0 (its stiffness `kn`), and the exact phases of its motion.
#[derive(Clone, Copy, Debug)]
struct Throw {
    m: f64,
    k: f64,
    kn: f64,
    f_crit: f64,
    f_post: f64,
    v0: f64,
}

/// The exact motion up to the release (module doc).
#[derive(Debug)]
struct Exact {
    /// Buckling: instant and velocity.
    t_b: f64,
    v_b: f64,
    /// The largest penetration and when it is reached.
    p_max: f64,
    t_max: f64,
    /// The post-buckling stiffness and the crush.
    k_post: f64,
    crush: f64,
    /// Release (the mass leaves the crushed stop): instant and velocity.
    t_r: f64,
    v_r: f64,
}

impl Throw {
    fn exact(&self) -> Exact {
        let Throw {
            m,
            k,
            kn,
            f_crit,
            f_post,
            v0,
        } = *self;
        // Elastic phase: m p'' = −(k + kn) p from p = 0, p' = v0.
        let w1 = ((k + kn) / m).sqrt();
        let p_b = f_crit / kn;
        let t_b = (p_b * w1 / v0).asin() / w1;
        let v_b = v0 * (w1 * t_b).cos();
        // Plateau: m p'' = −k p − f_post until p' = 0.
        let (p_max, t_plateau) = if k == 0.0 {
            (p_b + m * v_b * v_b / (2.0 * f_post), m * v_b / f_post)
        } else {
            let w0 = (k / m).sqrt();
            let pe = -f_post / k;
            let (a, b) = (p_b - pe, v_b / w0);
            (pe + a.hypot(b), b.atan2(a) / w0)
        };
        // The post-buckling line of the default law: through the crush 0 at p = 0 and
        // through (f_crit/kn, f_post).
        let k_post = f_post * kn / f_crit;
        let crush = p_max - f_post / k_post;
        // Unloading: m p'' = −k p − k_post (p − crush) from p_max at rest, until p = crush.
        let w2 = ((k + k_post) / m).sqrt();
        let pe = k_post * crush / (k + k_post);
        let s = ((crush - pe) / (p_max - pe)).acos();
        Exact {
            t_b,
            v_b,
            p_max,
            t_max: t_b + t_plateau,
            k_post,
            crush,
            t_r: t_b + t_plateau + s / w2,
            v_r: -w2 * (p_max - pe) * s.sin(),
        }
    }

    fn law(&self) -> Buckling {
        Buckling::new(&BucklingSpec {
            rigi_nor: self.kn,
            fnor_crit: self.f_crit,
            fnor_post_fl: self.f_post,
            enfo_fl: 1e-20,
            damping_in_criterion: true,
            ..BucklingSpec::default()
        })
        .unwrap()
    }

    /// The integrated motion over [0, t_end], every step archived.
    fn run(&self, scheme: Scheme, dt: f64, t_end: f64) -> Trajectory {
        let s = DenseStructure::diagonal(vec![self.m], vec![self.k], None).unwrap();
        let mut shocks = vec![stop_shock(0.0, self.kn, 0.0).with_buckling(self.law())];
        let grid = TimeGrid { t0: 0.0, t_end, dt };
        run(
            &s,
            &mut shocks,
            (&[0.0], &[self.v0]),
            scheme,
            grid,
            &Archive::Every(1),
        )
        .unwrap()
    }
}

/// What a run says of the buckling: the first archived instant with a positive crush
/// (POST_DYNA_MODA_T's INST_FLAMB), the step that ended there, the final crush
/// (ECRAS_RESI) and the largest penetration.
struct Measured {
    t_b: f64,
    h_b: f64,
    crush: f64,
    p_max: f64,
}

fn measure(tr: &Trajectory) -> Measured {
    let s = &tr.shocks[0];
    let k = s
        .iter()
        .position(|x| x.state.buckling.crush > 0.0)
        .expect("the stop buckles");
    let last = s.last().expect("samples").state.buckling;
    Measured {
        t_b: tr.t[k],
        h_b: tr.t[k] - tr.t[k - 1],
        crush: last.crush,
        p_max: last.max_penetration,
    }
}

/// The instant q crosses `level` going down after `after`, linearly interpolated between
/// archived instants (exact in a free flight).
fn down_crossing(tr: &Trajectory, level: f64, after: f64) -> f64 {
    for i in 1..tr.t.len() {
        let (a, b) = (tr.q_at(i - 1)[0], tr.q_at(i)[0]);
        if tr.t[i - 1] >= after && a >= level && b < level {
            return tr.t[i - 1] + (a - level) / (a - b) * (tr.t[i] - tr.t[i - 1]);
        }
    }
    panic!("q does not cross {level} after {after}");
}

/// A free mass (no spring): m = 2, RIGI_NOR = 50, FNOR_CRIT = 4, FNOR_POST_FL = 1.5,
/// thrown at 1.2: ω = 5, t_b = asin(1/3)/5, crush = m v_b²/(2 FNOR_POST_FL) = 0.853, the
/// release speed FNOR_POST_FL/√(k_post m), and the return through 0 at
/// t_r + crush/|v_r|.
const FREE: Throw = Throw {
    m: 2.0,
    k: 0.0,
    kn: 50.0,
    f_crit: 4.0,
    f_post: 1.5,
    v0: 1.2,
};

/// The bound of the module doc on the crush's error, for the step that buckled, plus the
/// second-order share of the elastic force's rise over that step (its impulse error is at
/// most RIGI_NOR·v_b·h_b², turned into crush the same way).
fn crush_bound(th: &Throw, ex: &Exact, h_b: f64) -> f64 {
    let to_crush = ex.v_b / th.f_post;
    to_crush * (h_b * (th.f_crit - th.f_post) + th.kn * ex.v_b * h_b * h_b)
}

/// The reference itself: the phases join (the stop's force is FNOR_CRIT at buckling, the
/// energy balance of the plateau holds, the release speed is the post-buckling spring's).
#[test]
fn the_exact_motion_is_consistent() {
    let ex = FREE.exact();
    assert!((FREE.kn * (FREE.v0 / 5.0) * (5.0 * ex.t_b).sin() - FREE.f_crit).abs() < 1e-12);
    let energy = 0.5 * FREE.m * ex.v_b * ex.v_b;
    assert!((FREE.f_post * (ex.p_max - FREE.f_crit / FREE.kn) - energy).abs() < 1e-12);
    assert!((ex.crush - energy / FREE.f_post).abs() < 1e-12);
    let release = FREE.f_post / (ex.k_post * FREE.m).sqrt();
    assert!((ex.v_r + release).abs() < 1e-12, "{ex:?}");
    assert!(ex.t_max < ex.t_r);
}

/// DIFF_CENTRE on the free mass: the buckling instant within one step after the exact one
/// (3.3e-5 after it at both steps), the crush within the first-order bound, and its error
/// halves with the step (first order: 1.0e-3 and 5.3e-4 at h = 1e-3 and 5e-4, against
/// bounds 1.9e-3 and 9.6e-4). The mass comes back through 0 at constant speed after the
/// release: that instant is off by the crush's error over the release speed (plus a step
/// or two of the same first-order shifts): 5.0e-3 and 2.6e-3.
#[test]
fn diff_centre_buckles_and_crushes_as_the_exact_motion() {
    let ex = FREE.exact();
    let mut errs = Vec::new();
    for h in [1e-3, 5e-4] {
        let tr = FREE.run(Scheme::DiffCentre, h, 6.0);
        let m = measure(&tr);
        assert!(
            m.t_b >= ex.t_b && m.t_b - ex.t_b <= h * (1.0 + 1e-9),
            "{} {}",
            m.t_b,
            ex.t_b
        );
        let err = (m.crush - ex.crush).abs();
        eprintln!(
            "DIFF_CENTRE h = {h:e}: t_b {:e} after, crush error {err:e} (bound {:e})",
            m.t_b - ex.t_b,
            crush_bound(&FREE, &ex, m.h_b)
        );
        assert!(err <= crush_bound(&FREE, &ex, m.h_b), "h = {h}: {err:e}");
        errs.push(err);
        // The return through 0 at constant speed after the release: the crush's error
        // over the release speed, plus the same first-order shift of the instants.
        let t0 = ex.t_r + ex.crush / ex.v_r.abs();
        let t_back = down_crossing(&tr, 0.0, ex.t_max);
        eprintln!("  return through 0: {:e} off", t_back - t0);
        let allowed = crush_bound(&FREE, &ex, m.h_b) / ex.v_r.abs() + 2.0 * h;
        assert!((t_back - t0).abs() < allowed, "{t_back} {t0}");
    }
    let ratio = errs[0] / errs[1];
    assert!((1.6..2.5).contains(&ratio), "{errs:?}");
}

/// NEWMARK (its Newton iterations see the law's slopes) on the free mass at h = 5e-4:
/// buckling 3.3e-5 after the exact instant, the crush and the largest penetration 5.3e-4
/// short (bound 9.6e-4).
#[test]
fn newmark_buckles_and_crushes_as_the_exact_motion() {
    let ex = FREE.exact();
    let h = 5e-4;
    let tr = FREE.run(Scheme::from_name("NEWMARK").unwrap(), h, 4.0);
    let m = measure(&tr);
    eprintln!(
        "NEWMARK h = {h:e}: t_b {:e} after, crush error {:e}, p_max error {:e} (bound {:e})",
        m.t_b - ex.t_b,
        m.crush - ex.crush,
        m.p_max - ex.p_max,
        crush_bound(&FREE, &ex, m.h_b)
    );
    assert!(m.t_b >= ex.t_b && m.t_b - ex.t_b <= h * (1.0 + 1e-9));
    assert!((m.crush - ex.crush).abs() <= crush_bound(&FREE, &ex, m.h_b));
    assert!((m.p_max - ex.p_max).abs() <= crush_bound(&FREE, &ex, m.h_b));
}

/// ADAPT_ORDRE2, DEVOGE and RUNGE_KUTTA_54 on the free mass: the same bound with the step
/// each took at buckling (PAS_MAXI 1e-3 for all; measured: ADAPT_ORDRE2 a step of 1e-3,
/// crush error 1.8e-3 against 1.9e-3, the buckling detected nearly a whole step late;
/// DEVOGE at TOLERANCE 1e-7 a step of 1e-3, 5.2e-4; RUNGE_KUTTA_54 at TOLERANCE 1e-8 a step
/// of 4.2e-4, 1.9e-4 against 8.0e-4).
#[test]
fn adaptive_schemes_buckle_and_crush_as_the_exact_motion() {
    let ex = FREE.exact();
    let mut adapt = AdaptOptions::new(AdaptOrder::Two);
    adapt.pas_maxi = Some(1e-3);
    let mut devoge = DevogeOptions {
        tolerance: 1e-7,
        ..DevogeOptions::default()
    };
    devoge.pas_maxi = Some(1e-3);
    let mut rk = AdaptiveOptions::new(RkPair::DormandPrince54);
    rk.tolerance = 1e-8;
    rk.pas_maxi = Some(1e-3);
    for (name, scheme) in [
        ("ADAPT_ORDRE2", Scheme::Adapt(adapt)),
        ("DEVOGE", Scheme::Devoge(devoge)),
        ("RUNGE_KUTTA_54", Scheme::Adaptive(rk)),
    ] {
        let tr = FREE.run(scheme, 1e-4, 4.0);
        let m = measure(&tr);
        assert!(
            m.t_b >= ex.t_b - 1e-12 && m.t_b - ex.t_b <= m.h_b * (1.0 + 1e-9),
            "{name}: {} {} (step {})",
            m.t_b,
            ex.t_b,
            m.h_b
        );
        let err = (m.crush - ex.crush).abs();
        eprintln!(
            "{name}: t_b {:e} after, step {:e}, crush error {err:e} (bound {:e}), {} steps",
            m.t_b - ex.t_b,
            m.h_b,
            crush_bound(&FREE, &ex, m.h_b),
            tr.t.len()
        );
        assert!(
            err <= crush_bound(&FREE, &ex, m.h_b),
            "{name}: crush {:e} vs {:e} (step {:e})",
            m.crush,
            ex.crush,
            m.h_b
        );
    }
}

/// A mass on a spring: m = 1, k = 4, RIGI_NOR = 60, FNOR_CRIT = 3, FNOR_POST_FL = 1,
/// thrown at 1.5. The plateau is a half-oscillation about −FNOR_POST_FL/k, the unloading
/// one about the crushed stop's equilibrium, and the mass leaves the stop at its crushed
/// position with the speed of that oscillation. DIFF_CENTRE at h = 2e-4: buckling within
/// a step (5.3e-5 after), the crush within the first-order bound (1.4e-4 against 5.8e-4),
/// the largest penetration within 5 steps (5.7e-5), the release instant (the first
/// archived instant after it with FN = 0) within 3 steps (3.2e-5), and its velocity within
/// 2e-3 relative (3.0e-4: the crush's error carried over).
#[test]
fn a_mass_on_a_spring_buckles_crushes_and_leaves_the_crushed_stop() {
    let th = Throw {
        m: 1.0,
        k: 4.0,
        kn: 60.0,
        f_crit: 3.0,
        f_post: 1.0,
        v0: 1.5,
    };
    let ex = th.exact();
    let h = 2e-4;
    let tr = th.run(Scheme::DiffCentre, h, ex.t_r + 0.2);
    let m = measure(&tr);
    assert!(m.t_b >= ex.t_b && m.t_b - ex.t_b <= h * (1.0 + 1e-9));
    assert!(
        (m.crush - ex.crush).abs() <= crush_bound(&th, &ex, m.h_b),
        "{} {}",
        m.crush,
        ex.crush
    );
    let s = &tr.shocks[0];
    let k_max = (0..tr.t.len())
        .max_by(|&a, &b| tr.q_at(a)[0].total_cmp(&tr.q_at(b)[0]))
        .unwrap();
    assert!((tr.t[k_max] - ex.t_max).abs() < 5.0 * h);
    let k_r = (k_max..tr.t.len()).find(|&i| s[i].f_n == 0.0).unwrap();
    assert!(
        (tr.t[k_r] - ex.t_r).abs() < 3.0 * h,
        "{} {}",
        tr.t[k_r],
        ex.t_r
    );
    // The velocity just after the release (DIFF_CENTRE's is the half step's).
    let v_r = tr.v_at(k_r)[0];
    eprintln!(
        "spring: t_b {:e} after, crush error {:e} (bound {:e}), t_max {:e}, t_r {:e}, v_r {:e} relative",
        m.t_b - ex.t_b,
        m.crush - ex.crush,
        crush_bound(&th, &ex, m.h_b),
        tr.t[k_max] - ex.t_max,
        tr.t[k_r] - ex.t_r,
        (v_r - ex.v_r) / ex.v_r.abs()
    );
    assert!(
        (v_r - ex.v_r).abs() < 2e-3 * ex.v_r.abs(),
        "{v_r} {}",
        ex.v_r
    );
    assert!((ex.crush - (ex.p_max - th.f_post / ex.k_post)).abs() < 1e-15);
}

/// A run split at T/2 and continued from its stored state (integrate_from with the
/// acceleration and the shocks' states of that instant) is the run in one call, to the
/// last bit for DIFF_CENTRE (the same operations on the same numbers; the steps land on
/// the same instants, t0 + k·h with t0 = T/2 a multiple of h): split during the plateau,
/// the second half must carry the buckled state, or it would see an elastic stop again.
#[test]
fn a_split_run_is_the_run_in_one() {
    let (h, t_end) = (1e-3, 2.0);
    let whole = FREE.run(Scheme::DiffCentre, h, t_end);
    let half = FREE.run(Scheme::DiffCentre, h, t_end / 2.0);
    let k = half.t.len() - 1;
    assert!(half.shocks[0][k].state.buckling.crush > 0.0 && half.shocks[0][k].f_n > 0.0);
    let s = DenseStructure::diagonal(vec![FREE.m], vec![FREE.k], None).unwrap();
    let mut shocks = vec![stop_shock(0.0, FREE.kn, 0.0).with_buckling(FREE.law())];
    shocks[0].state = half.shocks[0][k].state;
    let rest = crate::transient::integrate_from(
        &s,
        &mut shocks,
        &[],
        (half.q_at(k), half.v_at(k)),
        Some(half.a_at(k)),
        Scheme::DiffCentre,
        TimeGrid {
            t0: half.t[k],
            t_end,
            dt: h,
        },
        &Archive::Every(1),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(rest.t.len(), whole.t.len() - k);
    for i in 0..rest.t.len() {
        let j = k + i;
        assert_eq!(rest.q_at(i), whole.q_at(j), "instant {}", whole.t[j]);
        assert_eq!(rest.v_at(i), whole.v_at(j));
        assert_eq!(rest.a_at(i), whole.a_at(j));
        if i > 0 {
            assert_eq!(rest.shocks[0][i], whole.shocks[0][j]);
        }
    }
    // Without the state the continued run sees an unbuckled stop: it differs.
    let mut fresh = vec![stop_shock(0.0, FREE.kn, 0.0).with_buckling(FREE.law())];
    let forgetful = crate::transient::integrate_from(
        &s,
        &mut fresh,
        &[],
        (half.q_at(k), half.v_at(k)),
        Some(half.a_at(k)),
        Scheme::DiffCentre,
        TimeGrid {
            t0: half.t[k],
            t_end,
            dt: h,
        },
        &Archive::Every(1),
        &mut |_| {},
    )
    .unwrap();
    let last = forgetful.t.len() - 1;
    assert!((forgetful.q_at(last)[0] - whole.q_at(whole.t.len() - 1)[0]).abs() > 1e-3);
}
