//! The exact solution of a one-DOF oscillator (m = 1, stiffness k) against a stop of
//! stiffness k_n at x = g, written independently of the integrator: between contact
//! changes the motion is harmonic about the phase's equilibrium (0 free, k_n g/(k + k_n)
//! in contact), and each change is the first instant the closed form reaches x = g.

/// Phase data: start time, start state, equilibrium, pulsation.
#[derive(Clone, Copy, Debug)]
struct Phase {
    t: f64,
    x: f64,
    v: f64,
    xe: f64,
    w: f64,
}

impl Phase {
    fn at(&self, t: f64) -> (f64, f64) {
        let s = t - self.t;
        let (c, sn) = ((self.w * s).cos(), (self.w * s).sin());
        let d = self.x - self.xe;
        (
            self.xe + d * c + self.v / self.w * sn,
            -d * self.w * sn + self.v * c,
        )
    }

    /// First τ > 0 (beyond a tiny margin) with x(τ) = level, by the closed form
    /// R cos(wτ − φ) = level − xe.
    fn next_crossing(&self, level: f64) -> Option<f64> {
        let d = self.x - self.xe;
        let b = self.v / self.w;
        let r = d.hypot(b);
        let c = (level - self.xe) / r;
        if c.is_nan() || c.abs() > 1.0 {
            return None;
        }
        let phi = b.atan2(d);
        let ac = c.acos();
        let two_pi = 2.0 * std::f64::consts::PI;
        let mut best = f64::INFINITY;
        for s in [ac, -ac] {
            let mut th = (phi + s).rem_euclid(two_pi);
            if th <= 1e-12 {
                th += two_pi;
            }
            best = best.min(th / self.w);
        }
        Some(best)
    }
}

/// The exact trajectory and its contact-change instants up to `t_end`.
pub(super) struct Exact {
    phases: Vec<Phase>,
    pub events: Vec<f64>,
}

impl Exact {
    pub fn new(k: f64, kn: f64, g: f64, x0: f64, v0: f64, t_end: f64) -> Exact {
        assert!(x0 < g);
        let (wf, wc) = (k.sqrt(), (k + kn).sqrt());
        let xc = kn * g / (k + kn);
        let mut phases = vec![Phase {
            t: 0.0,
            x: x0,
            v: v0,
            xe: 0.0,
            w: wf,
        }];
        let mut events = Vec::new();
        loop {
            let p = *phases.last().unwrap();
            let Some(tau) = p.next_crossing(g) else { break };
            let te = p.t + tau;
            if te > t_end {
                break;
            }
            let (x, v) = p.at(te);
            let contact = p.xe == 0.0;
            events.push(te);
            phases.push(Phase {
                t: te,
                x,
                v,
                xe: if contact { xc } else { 0.0 },
                w: if contact { wc } else { wf },
            });
        }
        Exact { phases, events }
    }

    pub fn x(&self, t: f64) -> f64 {
        let p = self
            .phases
            .iter()
            .rev()
            .find(|p| p.t <= t)
            .unwrap_or(&self.phases[0]);
        p.at(t).0
    }
}

#[test]
fn reference_is_continuous_at_events_and_conserves_energy() {
    let (k, kn, g) = (1.0, 100.0, 0.5);
    let ex = Exact::new(k, kn, g, 0.0, 1.0, 40.0);
    assert!(ex.events.len() >= 10, "{} events", ex.events.len());
    for &te in &ex.events {
        // Both phases give x = g at the event (to rounding).
        assert!((ex.x(te) - g).abs() < 1e-12);
        assert!((ex.x(te - 1e-9) - g).abs() < 1e-8);
    }
    // Energy ½v² + ½k x² + ½k_n (x − g)₊² stays ½ (v0 = 1): exact to 1e-12.
    for p in &ex.phases {
        let e = 0.5 * p.v * p.v + 0.5 * k * p.x * p.x;
        assert!((e - 0.5).abs() < 1e-12);
    }
}
