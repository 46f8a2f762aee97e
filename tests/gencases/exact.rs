//! Exact periods of the one-DOF oscillator against a piecewise-linear stop (the nonsmooth
//! law, η = 0): mass m, spring k, gap g, stop stiffness α, total energy e.
//!
//! Out of contact the motion is u = B cos ω0 t with ½kB² = e, ω0 = √(k/m). In contact,
//! k u + α(u − g) = (k + α)(u − uc) with uc = αg/(k + α): the motion is uc + (A − uc) cos ω1 t,
//! ω1 = √((k + α)/m), up to the turning point A of ½kA² + ½α(A − g)² = e. The period adds
//! the phase spent on each piece:
//! - PLAN: the free arc is the part of B cos φ below g, 2(π − arccos(g/B))/ω0; one contact,
//!   the part of the stiff cosine above g, 2 arccos((g − uc)/(A − uc))/ω1;
//! - BI_PLAN: two free crossings of [−g, g], each 2 arcsin(g/B)/ω0, and two contacts.
//!   Without contact (e ≤ ½kg²) the period is 2π/ω0.

use std::f64::consts::PI;

#[derive(Debug, Clone, Copy)]
pub struct OneDof {
    pub m: f64,
    pub k: f64,
    pub g: f64,
    pub alpha: f64,
}

impl OneDof {
    fn pieces(&self, e: f64) -> Option<(f64, f64, f64, f64)> {
        let (m, k, g, a) = (self.m, self.k, self.g, self.alpha);
        if e <= 0.5 * k * g * g {
            return None;
        }
        let b = (2.0 * e / k).sqrt();
        let big_a = (a * g + (a * a * g * g - (k + a) * (a * g * g - 2.0 * e)).sqrt()) / (k + a);
        let uc = a * g / (k + a);
        let (w0, w1) = ((k / m).sqrt(), ((k + a) / m).sqrt());
        let contact = ((g - uc) / (big_a - uc)).clamp(-1.0, 1.0).acos() / w1;
        Some((b, w0, contact, (g / b).clamp(-1.0, 1.0)))
    }

    pub fn period_plan(&self, e: f64) -> f64 {
        let w0 = (self.k / self.m).sqrt();
        match self.pieces(e) {
            None => 2.0 * PI / w0,
            Some((_, w0, contact, ratio)) => 2.0 * (PI - ratio.acos()) / w0 + 2.0 * contact,
        }
    }

    pub fn period_biplan(&self, e: f64) -> f64 {
        let w0 = (self.k / self.m).sqrt();
        match self.pieces(e) {
            None => 2.0 * PI / w0,
            Some((_, w0, contact, ratio)) => 4.0 * ratio.asin() / w0 + 4.0 * contact,
        }
    }
}
