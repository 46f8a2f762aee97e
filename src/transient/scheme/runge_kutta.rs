//! The embedded explicit Runge–Kutta pairs of RUNGE_KUTTA_54 (Dormand–Prince 5(4)) and
//! RUNGE_KUTTA_32 (Bogacki–Shampine 3(2)): their Butcher tableaux, both FSAL (the last
//! stage is the derivative at the new state), the solution propagated with the higher
//! order and the difference of the two orders as the error estimate; and Code_Aster's
//! error weights and step-rule exponent of each ([`aster_control`], for `rk_loop.rs`).

use super::RkPair;

/// A Butcher tableau with an embedded error estimate.
pub(crate) struct Tableau {
    pub stages: usize,
    pub c: &'static [f64],
    /// Row i: a[i][0..i].
    pub a: &'static [&'static [f64]],
    /// b − b̂ (the error weights).
    pub e: &'static [f64],
    /// Order of the error estimate (the lower order): the step control exponent is
    /// 1/(order + 1).
    pub low_order: u32,
}

const DP_C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
const DP_A: [&[f64]; 7] = [
    &[],
    &[0.2],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ],
    &[
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ],
    &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Weights of the propagated solution (the last row of `a`, FSAL).
#[cfg(test)]
const DP_B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
const DP_E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

const BS_C: [f64; 4] = [0.0, 0.5, 0.75, 1.0];
const BS_A: [&[f64]; 4] = [
    &[],
    &[0.5],
    &[0.0, 0.75],
    &[2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0],
];
#[cfg(test)]
const BS_B: [f64; 4] = [2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0, 0.0];
const BS_E: [f64; 4] = [
    2.0 / 9.0 - 7.0 / 24.0,
    1.0 / 3.0 - 0.25,
    4.0 / 9.0 - 1.0 / 3.0,
    -0.125,
];

static DORMAND_PRINCE: Tableau = Tableau {
    stages: 7,
    c: &DP_C,
    a: &DP_A,
    e: &DP_E,
    low_order: 4,
};

static BOGACKI_SHAMPINE: Tableau = Tableau {
    stages: 4,
    c: &BS_C,
    a: &BS_A,
    e: &BS_E,
    low_order: 2,
};

pub(crate) fn tableau(pair: RkPair) -> &'static Tableau {
    match pair {
        RkPair::DormandPrince54 => &DORMAND_PRINCE,
        RkPair::BogackiShampine32 => &BOGACKI_SHAMPINE,
    }
}

/// Code_Aster's error weights of Bogacki–Shampine, b̂ − b as its `intruku32` writes them
/// (the opposite of [`BS_E`], each fraction rounded once).
const BS_ASTER_E: [f64; 4] = [5.0 / 72.0, -1.0 / 12.0, -1.0 / 9.0, 1.0 / 8.0];

/// Code_Aster's step control of a pair (`rk_loop.rs`): its error weights (one per stage,
/// the last one weighting the derivative at the new state) and the exponent p of its rule
/// (thresholds (0.9/5)^p and (0.9/0.2)^p, factor 0.9·err^(−1/p)): 4 for RUNGE_KUTTA_32,
/// 6 for RUNGE_KUTTA_54, as Code_Aster has them.
pub(crate) fn aster_control(pair: RkPair) -> (&'static [f64], f64) {
    match pair {
        RkPair::DormandPrince54 => (&DP_E, 6.0),
        RkPair::BogackiShampine32 => (&BS_ASTER_E, 4.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Row sums equal c, weights sum to 1, error weights to 0 (consistency, exact to
    /// rounding of the rational coefficients: 1e-14).
    #[test]
    fn tableaux_are_consistent() {
        for (t, b) in [(&DORMAND_PRINCE, &DP_B[..]), (&BOGACKI_SHAMPINE, &BS_B[..])] {
            for i in 0..t.stages {
                let s: f64 = t.a[i].iter().sum();
                assert!((s - t.c[i]).abs() < 1e-14, "row {i}");
            }
            assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!(t.e.iter().sum::<f64>().abs() < 1e-14);
            // FSAL: the last row is b.
            for (x, y) in t.a[t.stages - 1].iter().zip(b) {
                assert_eq!(x, y);
            }
        }
        // Code_Aster's weights are the pairs' differences (up to sign), to rounding.
        for (pair, t) in [
            (RkPair::DormandPrince54, &DORMAND_PRINCE),
            (RkPair::BogackiShampine32, &BOGACKI_SHAMPINE),
        ] {
            let (w, _) = aster_control(pair);
            assert_eq!(w.len(), t.stages);
            for (x, y) in w.iter().zip(t.e) {
                assert!((x.abs() - y.abs()).abs() < 1e-16, "{pair:?}: {x} vs {y}");
            }
        }
    }
}
