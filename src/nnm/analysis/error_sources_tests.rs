//! Tests of error_sources.rs: the advice against exact periods of piecewise-linear systems
//! (exact.rs, closed forms written independently of the engine), on one-DOF walls and on
//! two-DOF chains whose anti-phase mode is a one-DOF BI_PLAN oscillator.

use super::*;
use crate::nnm::model::exact::Oscillator;
use crate::nnm::tests::{settings, sparse};
use crate::nnm::{continue_while, resolution_warnings, start_from_mode, Shock, ShockLaw};

/// One grid case: the system, its stop and the settings.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Two masses (m = 1) on ground springs k = 10, coupled by kc = 5, a BI_PLAN stop on
    /// each, anti-phase mode; else one mass m = 1, k = 10, PLAN.
    pub chain: bool,
    /// RIGI_NOR / k.
    pub ratio: f64,
    pub regul: f64,
    pub h_lin: usize,
    pub h_nonl: usize,
}

const GAP: f64 = 0.01;
const K: f64 = 10.0;
const KC: f64 = 5.0;

impl Case {
    fn problem(&self, regul: f64) -> Problem {
        let alpha = self.ratio * K;
        let shock = |dof: usize, law: ShockLaw| Shock {
            law,
            dofs: vec![dof],
            gap: GAP,
            stiffness: alpha,
            regul,
        };
        if self.chain {
            Problem {
                forcing: None,
                k: sparse(
                    2,
                    &[(0, 0, K + KC), (0, 1, -KC), (1, 0, -KC), (1, 1, K + KC)],
                ),
                m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
                shocks: vec![shock(0, ShockLaw::BiPlan), shock(1, ShockLaw::BiPlan)],
            }
        } else {
            Problem {
                forcing: None,
                k: sparse(1, &[(0, 0, K)]),
                m: sparse(1, &[(0, 0, 1.0)]),
                shocks: vec![shock(0, ShockLaw::Plan)],
            }
        }
    }

    /// The one-DOF oscillator the orbit reduces to: in anti-phase each mass feels
    /// k + 2kc and its own stop, and carries half the ENERGIE.
    fn oscillator(&self) -> Oscillator {
        Oscillator {
            m: 1.0,
            k: if self.chain { K + 2.0 * KC } else { K },
            g: GAP,
            alpha: self.ratio * K,
        }
    }

    /// Exact frequency (Hz) of the nonsmooth system at ENERGIE `e`.
    pub fn exact(&self, e: f64) -> f64 {
        let o = self.oscillator();
        if self.chain {
            o.frequency_biplan(0.5 * e)
        } else {
            o.frequency_plan(e)
        }
    }

    /// ENERGIE of first contact.
    pub fn contact_energy(&self) -> f64 {
        let e = self.oscillator().contact_energy();
        if self.chain {
            2.0 * e
        } else {
            e
        }
    }

    /// The branch from the linear mode up to `top` times the contact energy (at most 150
    /// branches of one row each).
    fn run(&self, regul: f64, h_lin: usize, h_nonl: usize, top: f64) -> Vec<Point> {
        let p = self.problem(regul);
        let s = settings(h_lin, h_nonl, 150, 1);
        let (mode, w): (Vec<f64>, f64) = if self.chain {
            (vec![1.0, -1.0], (K + 2.0 * KC).sqrt())
        } else {
            (vec![1.0], K.sqrt())
        };
        let Ok(st) = start_from_mode(&p, &s, &mode, 1.0, w) else {
            return Vec::new();
        };
        let e_stop = top * self.contact_energy();
        continue_while(&p, &s, st, &mut |_, pts| {
            pts.last().is_none_or(|q| q.energy < e_stop)
        })
        .points
    }
}

/// What the advice did on one case.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub case: Case,
    /// The tail alarm fired.
    pub alarm: bool,
    pub sources: Option<Sources>,
    /// The run's error: the largest |relative frequency error| over its rows between first
    /// contact and `top`·E_c, each against the exact frequency at its own ENERGIE (no
    /// interpolation), before and after following the advice.
    pub before: f64,
    pub after: Option<f64>,
}

/// The row lies on the anti-phase family the chain's reference describes (|U1 + U2| at
/// most 1e-6 of |U1|, harmonic by harmonic); a one-DOF row always does.
fn on_family(case: &Case, p: &Point, h_lin: usize) -> bool {
    if !case.chain {
        return true;
    }
    let l = fourier::len(h_lin);
    let big = p.x[..l].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    (0..l).all(|i| (p.x[i] + p.x[l + i]).abs() <= 1e-6 * big)
}

/// The run reaches `top`·E_c, on the reference's family all the way (a chain whose branch
/// leaves the anti-phase orbits, at a symmetry-breaking bifurcation, has no closed-form
/// reference).
fn reaches(case: &Case, pts: &[Point], top: f64, h_lin: usize) -> bool {
    let e_top = top * case.contact_energy();
    pts.last().is_some_and(|q| q.energy >= e_top)
        && pts
            .iter()
            .filter(|p| p.energy <= e_top)
            .all(|p| on_family(case, p, h_lin))
}

/// The largest |f_row/f_exact(ENERGIE) − 1| over the rows of `pts` (computed with `h_lin`
/// harmonics) in (E_c, top·E_c] that lie on the reference's family.
pub fn run_error(case: &Case, pts: &[Point], top: f64, h_lin: usize) -> f64 {
    let ec = case.contact_energy();
    pts.iter()
        .filter(|p| p.energy > ec && p.energy <= top * ec && on_family(case, p, h_lin))
        .map(|p| (p.frequency / case.exact(p.energy) - 1.0).abs())
        .fold(0.0, f64::max)
}

/// Runs `case` up to `top`·E_c, estimates the error sources, follows the advice (doubling
/// the named harmonic count, NB_HARM_NONL raised to NB_HARM_LINE if below; halving
/// PARA_REGUL) and measures the run's error again.
pub fn follow(case: Case, top: f64) -> Option<Outcome> {
    let pts = case.run(case.regul, case.h_lin, case.h_nonl, top);
    if !reaches(&case, &pts, top, case.h_lin) {
        return None;
    }
    let p = case.problem(case.regul);
    let s = settings(case.h_lin, case.h_nonl, 150, 1);
    let alarm = !resolution_warnings(&p, &s, &pts, 1, false).is_empty();
    let sources = worst_row(&p, &s, &pts);
    let before = run_error(&case, &pts, top, case.h_lin);
    let after = sources.and_then(|src| src.advised()).map(|knob| {
        let (mut regul, mut hl, mut hn) = (case.regul, case.h_lin, case.h_nonl);
        match knob {
            Source::HarmLine => {
                hl *= 2;
                hn = hn.max(hl);
            }
            Source::HarmNonl => hn *= 2,
            Source::Regul => regul *= 0.5,
        }
        let refined = case.run(regul, hl, hn, top);
        if !reaches(&case, &refined, top, hl) {
            return f64::INFINITY;
        }
        run_error(&case, &refined, top, hl)
    });
    Some(Outcome {
        case,
        alarm,
        sources,
        before,
        after,
    })
}

/// One line of the grid's table.
pub fn line(o: &Outcome) -> String {
    let c = &o.case;
    let src = o.sources.map_or("-".to_string(), |s| {
        format!(
            "tot {:+.2e} d1 {:+.2e} nl {:+.2e} reg {:+.2e} E {:.3e} {:?}",
            s.total(),
            s.line_doubling,
            s.harm_nonl,
            s.regul,
            s.energy,
            s.advised()
        )
    });
    format!(
        "{} {:.0e} {:.0e} {} {} alarm={} before={:.3e} after={} | {src}",
        if c.chain { "chain2" } else { "wall" },
        c.ratio,
        c.regul,
        c.h_lin,
        c.h_nonl,
        o.alarm,
        o.before,
        o.after.map_or("-".to_string(), |a| format!("{a:.3e}"))
    )
}

#[test]
fn padding_keeps_every_harmonic_in_place() {
    // Two series of 2 harmonics [0, C1, C2, S1, S2] padded to 3: [0, C1, C2, 0, S1, S2, 0].
    let u = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0];
    let p = padded(&u, 2, 2, 3);
    assert_eq!(
        p,
        vec![1.0, 2.0, 3.0, 0.0, 4.0, 5.0, 0.0, 6.0, 7.0, 8.0, 0.0, 9.0, 10.0, 0.0]
    );
}

#[test]
fn the_advice_weighs_signed_parts() {
    // Issue 34's stiff wall, in round numbers: the displacement's part dominates.
    let s = Sources {
        row: 0,
        energy: 1.0,
        line_doubling: -3e-3,
        harm_nonl: 1e-5,
        regul: 2e-6,
    };
    assert_eq!(s.dominant(), Source::HarmLine);
    assert_eq!(s.advised(), Some(Source::HarmLine));
    // Worst case R = 0: before −2.988e-3, after +1.2e-5.
    assert!((s.worst_ratio(Source::HarmLine) - 0.5).abs() < 1e-2);
    assert!(s
        .text(&settings(20, 1000, 1, 1).harmonics, 1)
        .contains("raise NB_HARM_LINE (doubled: 40)"));
    // The parts cancel: the regularisation's +4.1e-3 against the displacement's −2e-3 to
    // −4e-3. Doubling NB_HARM_LINE overshoots where R is small, halving PARA_REGUL where it
    // is large: nothing is named.
    let c = Sources {
        line_doubling: -2e-3,
        regul: 4.1e-3,
        harm_nonl: 0.0,
        ..s
    };
    assert_eq!(c.advised(), None);
    assert!(c
        .text(&settings(20, 1000, 1, 1).harmonics, 1)
        .contains("the parts cancel"));
    // Below NEGLIGIBLE for every remainder: nothing is named.
    let t = Sources {
        line_doubling: -2.5e-6,
        harm_nonl: 1e-6,
        regul: 0.0,
        ..s
    };
    assert_eq!(t.advised(), None);
    assert!(t
        .text(&settings(20, 1000, 1, 1).harmonics, 1)
        .contains("do not limit"));
    // The contact unknowns' part dominates and the others are small: NB_HARM_NONL.
    let u = Sources {
        line_doubling: 1e-6,
        harm_nonl: -4e-3,
        regul: 1e-6,
        ..s
    };
    assert_eq!(u.advised(), Some(Source::HarmNonl));
}

/// Counts of a grid's outcomes: (alarms, named, lowered, raised, refined run short).
pub fn tally(outcomes: &[Outcome]) -> (usize, usize, usize, usize, usize) {
    let alarms: Vec<&Outcome> = outcomes.iter().filter(|o| o.alarm).collect();
    let named: Vec<&&Outcome> = alarms.iter().filter(|o| o.after.is_some()).collect();
    let short = named
        .iter()
        .filter(|o| o.after == Some(f64::INFINITY))
        .count();
    let lowered = named
        .iter()
        .filter(|o| o.after.is_some_and(|a| a < o.before))
        .count();
    (
        alarms.len(),
        named.len(),
        lowered,
        named.len() - lowered - short,
        short,
    )
}

/// Issue 34, point 4, on a small grid (one-DOF walls RIGI_NOR/k 1e2..1e8, PARA_REGUL 1e-3
/// and 1e-8, NB_HARM_LINE/NB_HARM_NONL 10/200 and 40/200; two-DOF chains at 5/50): wherever
/// the tail alarm fires and names a setting, following the advice (doubling it, or
/// halving PARA_REGUL) lowers the run's error against the exact period. A refined run that
/// does not reach 10 E_c (the engine's limit, not the advice's) is counted, not judged;
/// the test requires most named cases to be judged, and every source to be named at least
/// once on a grid that has cases of each.
#[test]
fn following_the_advice_lowers_the_error_on_a_grid() {
    let mut cases = Vec::new();
    for ratio in [1e2, 1e4, 1e6, 1e8] {
        for regul in [1e-3, 1e-8] {
            for (hl, hn) in [(10, 200), (40, 200)] {
                cases.push(Case {
                    chain: false,
                    ratio,
                    regul,
                    h_lin: hl,
                    h_nonl: hn,
                });
            }
        }
    }
    for ratio in [1e2, 1e4] {
        cases.push(Case {
            chain: true,
            ratio,
            regul: 1e-5,
            h_lin: 5,
            h_nonl: 50,
        });
    }
    let outcomes: Vec<Outcome> = cases.into_iter().filter_map(|c| follow(c, 10.0)).collect();
    let report: String = outcomes.iter().map(|o| line(o) + "\n").collect();
    let (alarms, named, lowered, raised, short) = tally(&outcomes);
    assert_eq!(
        raised, 0,
        "following the advice raised the error:\n{report}"
    );
    assert!(
        alarms >= 10 && lowered + 2 >= named && lowered >= 8,
        "{alarms} alarms, {named} named, {lowered} lowered, {short} refined runs short:\n{report}"
    );
    for s in [Source::HarmLine, Source::HarmNonl, Source::Regul] {
        assert!(
            outcomes
                .iter()
                .any(|o| o.alarm && o.sources.and_then(|x| x.advised()) == Some(s)),
            "{s:?} never named:\n{report}"
        );
    }
}

/// The full grid of docs/mode_non_line.md ("Which setting limits the frequency"): prints
/// one line per case and the tally (`cargo test --release advice_grid_table -- --ignored
/// --nocapture`; about 15 minutes; ADVICE_GRID=walls or chains runs half of it).
#[test]
#[ignore]
fn advice_grid_table() {
    let mut all = Vec::new();
    let which = std::env::var("ADVICE_GRID").unwrap_or_default();
    for chain in [false, true] {
        if (which == "walls" && chain) || (which == "chains" && !chain) {
            continue;
        }
        let pairs: &[(usize, usize)] = if chain {
            &[(5, 50), (10, 200), (20, 400), (40, 200)]
        } else {
            &[(5, 50), (10, 200), (20, 1000), (40, 200)]
        };
        for ratio in [1e2, 1e4, 1e6, 1e8] {
            for regul in [1e-3, 1e-5, 1e-8] {
                for &(hl, hn) in pairs {
                    let c = Case {
                        chain,
                        ratio,
                        regul,
                        h_lin: hl,
                        h_nonl: hn,
                    };
                    let t = std::time::Instant::now();
                    match follow(c, 10.0) {
                        Some(o) => {
                            println!("{} [{:.1}s]", line(&o), t.elapsed().as_secs_f64());
                            all.push(o);
                        }
                        None => println!("{c:?}: the run does not reach 10 E_c on the family"),
                    }
                }
            }
        }
    }
    let (alarms, named, lowered, raised, short) = tally(&all);
    println!(
        "{} cases run; {alarms} alarms; {named} name a setting; lowered {lowered}, raised \
         {raised}, refined run short of 10 E_c {short}",
        all.len()
    );
}

/// Calibration: per-row estimates against the actual error (`ROWS_CASE=ratio,regul,hl,hn`).
#[test]
#[ignore]
fn calibration_rows() {
    let v: Vec<f64> = std::env::var("ROWS_CASE")
        .unwrap_or("1e8,1e-3,20,1000".into())
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let c = Case {
        chain: std::env::var("ROWS_CHAIN").is_ok(),
        ratio: v[0],
        regul: v[1],
        h_lin: v[2] as usize,
        h_nonl: v[3] as usize,
    };
    let pts = c.run(c.regul, c.h_lin, c.h_nonl, 10.0);
    let p = c.problem(c.regul);
    let s = settings(c.h_lin, c.h_nonl, 150, 1);
    for (i, q) in pts.iter().enumerate() {
        let err = q.frequency / c.exact(q.energy) - 1.0;
        match estimate(&p, &s, q, i) {
            Ok(src) => println!(
                "{i} E/Ec {:.4} err {err:+.3e} est {:+.3e}..{:+.3e} d1 {:+.2e} nl {:+.2e} reg {:+.2e} {:?}",
                q.energy / c.contact_energy(),
                src.total() - 0.5 * src.line_doubling,
                src.total() + 0.5 * src.line_doubling,
                src.line_doubling,
                src.harm_nonl,
                src.regul,
                src.advised()
            ),
            Err(e) => println!("{i} E/Ec {:.4} err {err:+.3e} estimate failed: {e}", q.energy / c.contact_energy()),
        }
    }
}
