//! Exact periods of the nonsmooth one-DOF systems of docs/ehman.md §5 (η → 0, H_nl → ∞): the
//! references of the engine tests and of the accuracy study (`crate::accuracy`).
//! m, k: the oscillator; g: the gap; alpha: the stop stiffness.

use std::f64::consts::PI;

#[derive(Clone, Copy, Debug)]
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
    pub g: f64,
    pub alpha: f64,
}

impl Oscillator {
    fn w0(&self) -> f64 {
        (self.k / self.m).sqrt()
    }
    fn w1(&self) -> f64 {
        ((self.k + self.alpha) / self.m).sqrt()
    }
    fn uc(&self) -> f64 {
        self.alpha * self.g / (self.k + self.alpha)
    }
    /// Largest excursion A into the stop of an orbit of total energy e (> ½kg²):
    /// ½kA² + ½α(A − g)² = e.
    pub fn amplitude(&self, e: f64) -> f64 {
        let (k, a, g) = (self.k, self.alpha, self.g);
        let disc = a * a * g * g - (k + a) * (a * g * g - 2.0 * e);
        (a * g + disc.sqrt()) / (k + a)
    }
    /// Free amplitude B: ½kB² = e.
    fn free_amplitude(&self, e: f64) -> f64 {
        (2.0 * e / self.k).sqrt()
    }
    /// Contact time of one impact: from g to A and back.
    fn contact_time(&self, e: f64) -> f64 {
        let a = self.amplitude(e);
        2.0 * ((self.g - self.uc()) / (a - self.uc())).acos() / self.w1()
    }
    /// Unilateral stop (PLAN) on the + side: T = 2(π − arccos(g/B))/ω0 + contact time.
    pub fn period_plan(&self, e: f64) -> f64 {
        let b = self.free_amplitude(e);
        if b <= self.g {
            return 2.0 * PI / self.w0();
        }
        2.0 * (PI - (self.g / b).acos()) / self.w0() + self.contact_time(e)
    }
    /// Symmetric stops at ±g (BI_PLAN): four free quarter-arcs from 0 to g, two impacts.
    pub fn period_biplan(&self, e: f64) -> f64 {
        let b = self.free_amplitude(e);
        if b <= self.g {
            return 2.0 * PI / self.w0();
        }
        4.0 * (self.g / b).asin() / self.w0() + 2.0 * self.contact_time(e)
    }
    /// Energy of first contact, ½kg² (below it the frequency is the linear one).
    pub fn contact_energy(&self) -> f64 {
        0.5 * self.k * self.g * self.g
    }
    /// Exact frequency (Hz) of the PLAN orbit of energy e: 1/T.
    pub fn frequency_plan(&self, e: f64) -> f64 {
        1.0 / self.period_plan(e)
    }
    /// Exact frequency (Hz) of the BI_PLAN orbit of energy e: 1/T.
    pub fn frequency_biplan(&self, e: f64) -> f64 {
        1.0 / self.period_biplan(e)
    }
}

/// Radial force of the regularised CERCLE law at radial distance r ≥ 0 (ring radius g,
/// stiffness α, regularisation ε = PARA_REGUL·k_ref): the root φ of
/// φ (1 − ((φ − α r)/(α g))²) = ε r in (max(0, α(r − g)), α r), where the left side minus
/// the right goes from negative to positive (BI_PLAN's law at the radial distance). On a
/// circular orbit of radius r the force is constant, so ω² = (k + φ(r)/r)/m is the exact
/// pulsation of the regularised system. By bisection to round-off.
pub fn regularised_ring_force(r: f64, g: f64, alpha: f64, eps: f64) -> f64 {
    if r <= 0.0 {
        return 0.0;
    }
    let psi = |f: f64| f * (1.0 - ((f - alpha * r) / (alpha * g)).powi(2)) - eps * r;
    let (mut lo, mut hi) = ((alpha * (r - g)).max(0.0), alpha * r);
    for _ in 0..2000 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break; // adjacent doubles
        }
        if psi(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_are_right() {
        let o = Oscillator {
            m: 1.0,
            k: 10.0,
            g: 0.01,
            alpha: 50.0,
        };
        let t0 = 2.0 * PI / 10f64.sqrt();
        // At grazing energy both periods are the linear one.
        let e0 = 0.5 * 10.0 * 0.01 * 0.01;
        assert!((o.period_plan(e0 * (1.0 + 1e-12)) - t0).abs() < 1e-5);
        assert!((o.period_biplan(e0 * (1.0 + 1e-12)) - t0).abs() < 1e-5);
        // Zero gap: half periods of both springs.
        let z = Oscillator { g: 0.0, ..o };
        let t = PI / 10f64.sqrt() + PI / 60f64.sqrt();
        assert!((z.period_plan(1.0) - t).abs() < 1e-12);
        assert!((z.period_biplan(1.0) - 2.0 * PI / 60f64.sqrt()).abs() < 1e-12);
    }
}
