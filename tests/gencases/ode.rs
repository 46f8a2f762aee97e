//! Adaptive Runge–Kutta (Dormand–Prince 5(4), FSAL) for the references' equations of motion,
//! with exact stops at given instants. The error norm is mixed: component i is scaled by
//! rtol·(|y_i| + scale_i), so that a state component crossing zero is held to the size of
//! the motion, not to zero.

pub struct Stats {
    pub steps: usize,
    pub rejected: usize,
}

const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// 5th-order weights (= the last row of A) minus the 4th-order ones.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// Integrates ẏ = f(y) from t = 0, returning y at each of `stops` (increasing, > 0).
/// Err if the step collapses or more than `max_steps` steps are needed.
pub fn integrate(
    f: &dyn Fn(&[f64], &mut [f64]),
    y0: &[f64],
    stops: &[f64],
    rtol: f64,
    scale: &[f64],
    max_steps: usize,
) -> Result<(Vec<Vec<f64>>, Stats), String> {
    let n = y0.len();
    let mut y = y0.to_vec();
    let mut k: Vec<Vec<f64>> = vec![vec![0.0; n]; 7];
    f(&y, &mut k[0]);
    let mut t = 0.0;
    let t_end = *stops.last().ok_or("no stop")?;
    let mut h = t_end * 1e-3;
    let mut out = Vec::with_capacity(stops.len());
    let mut next = 0;
    let mut stats = Stats {
        steps: 0,
        rejected: 0,
    };
    let mut ytmp = vec![0.0; n];
    let mut ynew = vec![0.0; n];
    while next < stops.len() {
        if stats.steps + stats.rejected > max_steps {
            return Err(format!("more than {max_steps} steps"));
        }
        let target = stops[next];
        let hit = t + h >= target * (1.0 - 1e-15);
        let hs = if hit { target - t } else { h };
        for s in 1..7 {
            for i in 0..n {
                let mut acc = y[i];
                for (j, kj) in k.iter().enumerate().take(s) {
                    acc += hs * A[s][j] * kj[i];
                }
                ytmp[i] = acc;
            }
            f(&ytmp, &mut k[s]);
            if s == 6 {
                ynew.copy_from_slice(&ytmp);
            }
        }
        // k[6] = f(ynew) (FSAL); error estimate.
        let mut err: f64 = 0.0;
        for i in 0..n {
            let mut e = 0.0;
            for (j, kj) in k.iter().enumerate() {
                e += E[j] * kj[i];
            }
            let sc = rtol * (y[i].abs().max(ynew[i].abs()) + scale[i]);
            err = err.max((hs * e).abs() / sc);
        }
        if !err.is_finite() {
            return Err("non-finite state".into());
        }
        if err <= 1.0 {
            t = if hit { target } else { t + hs };
            y.copy_from_slice(&ynew);
            k.swap(0, 6);
            stats.steps += 1;
            if hit {
                out.push(y.clone());
                next += 1;
            }
            let grow = if err == 0.0 {
                5.0
            } else {
                (0.9 * err.powf(-0.2)).min(5.0)
            };
            // A step shortened to land on a stop does not set the next one.
            h = if hit { h.max(hs * grow) } else { hs * grow };
        } else {
            stats.rejected += 1;
            h = hs * (0.9 * err.powf(-0.2)).max(0.1);
        }
        if h < t_end * 1e-15 {
            return Err(format!("step collapsed at t = {t:e}"));
        }
    }
    Ok((out, stats))
}
