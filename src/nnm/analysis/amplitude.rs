//! The amplitude of a periodic displacement given by its Fourier coefficients: the largest
//! |u(t)| over one period, found on a grid and refined by Newton on u'(t) = 0 (REPONSE_FORCEE_NL's
//! AMPL_ columns).

use crate::nnm::model::fourier;

/// Grid instants per harmonic before the refinement: enough for the grid's best instant to
/// lie in the basin of the true maximum (a sum of H harmonics has at most 2H extrema).
const SAMPLES_PER_HARMONIC: usize = 16;

/// u, u' and u'' at phase θ of the series `c` = (0, C1..CH, S1..SH).
fn eval(c: &[f64], h: usize, theta: f64) -> (f64, f64, f64) {
    let (mut u, mut du, mut d2u) = (c[0], 0.0, 0.0);
    for k in 1..=h {
        let (ck, sk, kf) = (c[fourier::ic(k)], c[fourier::is(h, k)], k as f64);
        let (s, co) = (kf * theta).sin_cos();
        u += ck * co + sk * s;
        du += kf * (sk * co - ck * s);
        d2u -= kf * kf * (ck * co + sk * s);
    }
    (u, du, d2u)
}

/// The largest |u(θ)| over θ ∈ [0, 2π) of the series `c` (0, C1..CH, S1..SH): the grid's
/// best instant refined by Newton on u' = 0 (kept only where it raises |u|), to round-off.
pub fn peak_amplitude(c: &[f64], h: usize) -> f64 {
    let n = SAMPLES_PER_HARMONIC * h.max(1) + 2;
    let step = 2.0 * std::f64::consts::PI / n as f64;
    let (mut best, mut at) = (0.0f64, 0.0);
    for j in 0..n {
        let theta = step * j as f64;
        let u = eval(c, h, theta).0.abs();
        if u > best {
            best = u;
            at = theta;
        }
    }
    let mut theta = at;
    for _ in 0..20 {
        let (_, du, d2u) = eval(c, h, theta);
        if d2u == 0.0 {
            break;
        }
        let next = theta - du / d2u;
        // Newton stays within the grid cell of the best instant, or it is not refining it.
        if (next - at).abs() > step {
            break;
        }
        let u = eval(c, h, next).0.abs();
        if u < best {
            break;
        }
        best = u;
        let moved = (next - theta).abs();
        theta = next;
        if moved < 1e-15 {
            break;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One harmonic: the amplitude is √(C1² + S1²) + |mean| when the mean has the sign of
    /// the largest excursion; closed forms.
    #[test]
    fn one_harmonic_and_a_mean() {
        let c = [0.0, 3.0, 4.0];
        assert!((peak_amplitude(&c, 1) - 5.0).abs() < 1e-14);
        let c = [0.5, 3.0, 4.0];
        assert!((peak_amplitude(&c, 1) - 5.5).abs() < 1e-14);
        let c = [-0.5, 3.0, 4.0];
        assert!((peak_amplitude(&c, 1) - 5.5).abs() < 1e-14);
    }

    /// cos θ + 0.3 cos 3θ: the maximum 1.3 at θ = 0 (all harmonics in phase); and
    /// sin θ + ½ sin 2θ, whose maximum is at cos θ = ½ (u' = cos θ + cos 2θ =
    /// 2cos²θ + cos θ − 1 = 0), u = 3√3/4 in closed form.
    #[test]
    fn several_harmonics_against_closed_forms() {
        let h = 3;
        let mut c = vec![0.0; 2 * h + 1];
        c[fourier::ic(1)] = 1.0;
        c[fourier::ic(3)] = 0.3;
        assert!((peak_amplitude(&c, h) - 1.3).abs() < 1e-14);
        let mut c = vec![0.0; 2 * h + 1];
        c[fourier::is(h, 1)] = 1.0;
        c[fourier::is(h, 2)] = 0.5;
        let exact = 3.0 * 3f64.sqrt() / 4.0;
        assert!((peak_amplitude(&c, h) - exact).abs() < 1e-14);
    }
}
