//! Functions of one parameter given by points (`fonction_sdaster`), evaluated as Code_Aster.
//!
//! - INTERPOL gives the interpolation of the abscissa and of the ordinate: `LIN` linear,
//!   `LOG` linear in the logarithm of that axis, `NON` no interpolation (the function is
//!   only defined at its abscissas). One value applies to both axes (`'LOG'` is log-log).
//! - PROL_GAUCHE / PROL_DROITE: `EXCLU` refuses to evaluate outside `[x1, xn]`,
//!   `CONSTANT` holds the end value, `LINEAIRE` extends the end segment (in the space of the
//!   interpolation, so a LOG/LOG function extends its power law).
//! - Abscissas must be strictly increasing: Code_Aster refuses other functions.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

pub mod calc;
pub mod formula;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Interp {
    Lin,
    Log,
    Non,
}

impl Interp {
    pub fn parse(s: &str) -> Option<Interp> {
        match s {
            "LIN" => Some(Interp::Lin),
            "LOG" => Some(Interp::Log),
            "NON" => Some(Interp::Non),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Interp::Lin => "LIN",
            Interp::Log => "LOG",
            Interp::Non => "NON",
        }
    }
    fn to_space(self, v: f64) -> f64 {
        match self {
            Interp::Log => v.ln(),
            _ => v,
        }
    }
    fn back_from_space(self, v: f64) -> f64 {
        match self {
            Interp::Log => v.exp(),
            _ => v,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Prol {
    Constant,
    Lineaire,
    Exclu,
}

impl Prol {
    pub fn parse(s: &str) -> Option<Prol> {
        match s {
            "CONSTANT" => Some(Prol::Constant),
            "LINEAIRE" => Some(Prol::Lineaire),
            "EXCLU" => Some(Prol::Exclu),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Prol::Constant => "CONSTANT",
            Prol::Lineaire => "LINEAIRE",
            Prol::Exclu => "EXCLU",
        }
    }
}

/// How points given in any order were put in increasing order of abscissa.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reorder {
    /// Already strictly increasing.
    None,
    /// Strictly decreasing: reversed.
    Reversed,
    /// Neither: sorted (stable, so equal abscissas keep their order).
    Sorted,
}

/// What [`order_points`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ordering {
    pub reorder: Reorder,
    /// Points dropped because their abscissa was already present (the first in the given
    /// order is kept).
    pub dropped: usize,
    /// Largest |y| difference between a dropped point and the point kept at its abscissa
    /// (0 when the dropped points were exact copies).
    pub max_dropped_dy: f64,
}

/// Put points given in any order (the rows of a table) in strictly increasing order of
/// abscissa, as Code_Aster's RECU_FONCTION does with a table whose abscissa is not
/// monotone (a branch that turns back, a table extended by a restart). Points whose
/// abscissa equals one already kept are dropped: a function has one value per abscissa.
pub fn order_points(x: &mut Vec<f64>, y: &mut Vec<f64>) -> Ordering {
    let n = x.len().min(y.len());
    x.truncate(n);
    y.truncate(n);
    let increasing = x.windows(2).all(|w| w[0] < w[1]);
    let reorder = if increasing {
        Reorder::None
    } else if x.windows(2).all(|w| w[0] > w[1]) {
        x.reverse();
        y.reverse();
        Reorder::Reversed
    } else {
        let mut idx: Vec<usize> = (0..n).collect();
        idx.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
        *x = idx.iter().map(|&i| x[i]).collect();
        *y = idx.iter().map(|&i| y[i]).collect();
        Reorder::Sorted
    };
    let mut dropped = 0;
    let mut max_dropped_dy: f64 = 0.0;
    let (mut kx, mut ky): (Vec<f64>, Vec<f64>) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for (&a, &b) in x.iter().zip(y.iter()) {
        match (kx.last(), ky.last()) {
            (Some(&la), Some(&lb)) if la == a => {
                dropped += 1;
                max_dropped_dy = max_dropped_dy.max((b - lb).abs());
            }
            _ => {
                kx.push(a);
                ky.push(b);
            }
        }
    }
    *x = kx;
    *y = ky;
    Ordering {
        reorder,
        dropped,
        max_dropped_dy,
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Function {
    /// Concept name, for messages (set when built or loaded).
    pub name: String,
    pub nom_para: String,
    pub nom_resu: String,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// Interpolation of (x, y).
    pub interpol: (Interp, Interp),
    pub prol_gauche: Prol,
    pub prol_droite: Prol,
}

impl Function {
    /// A function with Code_Aster's defaults (LIN/LIN, EXCLU on both sides), checked.
    pub fn new(
        name: &str,
        nom_para: &str,
        nom_resu: &str,
        x: Vec<f64>,
        y: Vec<f64>,
    ) -> Result<Function> {
        let f = Function {
            name: name.to_string(),
            nom_para: nom_para.to_string(),
            nom_resu: nom_resu.to_string(),
            x,
            y,
            interpol: (Interp::Lin, Interp::Lin),
            prol_gauche: Prol::Exclu,
            prol_droite: Prol::Exclu,
        };
        f.check()?;
        Ok(f)
    }

    /// Check the points against the interpolation and prolongations.
    pub fn check(&self) -> Result<()> {
        let name = &self.name;
        if self.x.len() != self.y.len() {
            return Err(Error::input(format!(
                "function {name}: {} abscissas for {} ordinates",
                self.x.len(),
                self.y.len()
            ))
            .keyword("VALE"));
        }
        if self.x.is_empty() {
            return Err(Error::input(format!("function {name} has no point")).keyword("VALE"));
        }
        if self.x.iter().chain(&self.y).any(|v| !v.is_finite()) {
            return Err(
                Error::input(format!("function {name} has a non-finite value")).keyword("VALE"),
            );
        }
        for (i, w) in self.x.windows(2).enumerate() {
            if let [a, b] = w {
                if b <= a {
                    return Err(Error::input(format!(
                        "function {name}: abscissas must be strictly increasing, but point {} ({b}) does not exceed point {} ({a})",
                        i + 2,
                        i + 1
                    ))
                    .keyword("VALE")
                    .hint("give the points in increasing order of the parameter"));
                }
            }
        }
        let (ix, iy) = self.interpol;
        if ix == Interp::Log && self.x.iter().any(|&v| v <= 0.0) {
            return Err(Error::input(format!(
                "function {name}: LOG interpolation of the abscissa needs positive abscissas"
            ))
            .keyword("INTERPOL"));
        }
        if iy == Interp::Log && self.y.iter().any(|&v| v <= 0.0) {
            return Err(Error::input(format!(
                "function {name}: LOG interpolation of the ordinate needs positive ordinates"
            ))
            .keyword("INTERPOL"));
        }
        for (side, p) in [
            ("PROL_GAUCHE", self.prol_gauche),
            ("PROL_DROITE", self.prol_droite),
        ] {
            if p == Prol::Lineaire && (self.x.len() < 2 || ix == Interp::Non || iy == Interp::Non) {
                return Err(Error::input(format!(
                    "function {name}: {side}='LINEAIRE' needs at least two points and an interpolation other than 'NON'"
                ))
                .keyword(side));
            }
        }
        Ok(())
    }

    fn mismatch(&self) -> Error {
        Error::input(format!(
            "function {}: {} abscissas for {} ordinates",
            self.name,
            self.x.len(),
            self.y.len()
        ))
    }

    fn range_text(&self) -> String {
        match (self.x.first(), self.x.last()) {
            (Some(a), Some(b)) => format!("[{a}, {b}]"),
            _ => "[]".into(),
        }
    }

    /// Value of the function at `x`.
    pub fn eval(&self, x: f64) -> Result<f64> {
        let (first, last) = match (self.x.first(), self.x.last()) {
            (Some(a), Some(b)) => (*a, *b),
            _ => return Err(Error::input(format!("function {} has no point", self.name))),
        };
        if x.is_nan() {
            return Err(Error::input(format!(
                "function {}: cannot evaluate at NaN",
                self.name
            )));
        }
        let n = self.x.len();
        if x < first || x > last {
            let (prol, side, i) = if x < first {
                (self.prol_gauche, "PROL_GAUCHE", 0)
            } else {
                (self.prol_droite, "PROL_DROITE", n.saturating_sub(2))
            };
            return match prol {
                Prol::Exclu => Err(Error::input(format!(
                    "function {}: {}={x} is outside its definition range {} and {side}='EXCLU'",
                    self.name,
                    self.nom_para,
                    self.range_text()
                ))
                .hint(format!(
                    "give {side}='CONSTANT' or 'LINEAIRE' to extend the function"
                ))),
                Prol::Constant => {
                    let end = if x < first {
                        self.y.first()
                    } else {
                        self.y.get(n - 1)
                    };
                    end.copied().ok_or_else(|| self.mismatch())
                }
                Prol::Lineaire => self.segment(i, x),
            };
        }
        // Index of the first abscissa >= x: x lies in [x(i-1), x(i)].
        let i = self.x.partition_point(|&v| v < x);
        if self.x.get(i) == Some(&x) {
            return self.y.get(i).copied().ok_or_else(|| self.mismatch());
        }
        if self.interpol.0 == Interp::Non || self.interpol.1 == Interp::Non {
            return Err(Error::input(format!(
                "function {}: INTERPOL='NON' defines it only at its abscissas, not at {}={x}",
                self.name, self.nom_para
            )));
        }
        self.segment(i.saturating_sub(1), x)
    }

    /// Interpolation (or extrapolation) on the segment [x(i), x(i+1)].
    fn segment(&self, i: usize, x: f64) -> Result<f64> {
        let (ix, iy) = self.interpol;
        let (x0, x1, y0, y1) = match (
            self.x.get(i),
            self.x.get(i + 1),
            self.y.get(i),
            self.y.get(i + 1),
        ) {
            (Some(a), Some(b), Some(c), Some(d)) => (*a, *b, *c, *d),
            _ => return Err(self.mismatch()),
        };
        if ix == Interp::Log && x <= 0.0 {
            return Err(Error::input(format!(
                "function {}: LOG interpolation cannot reach {}={x} (not positive)",
                self.name, self.nom_para
            )));
        }
        let (u, u0, u1) = (ix.to_space(x), ix.to_space(x0), ix.to_space(x1));
        let (v0, v1) = (iy.to_space(y0), iy.to_space(y1));
        let t = (u - u0) / (u1 - u0);
        Ok(iy.back_from_space(v0 + t * (v1 - v0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_in_any_order_are_sorted_and_duplicates_dropped() {
        // A branch that turns back: 1, 3, 2 (and a repeat of 3 with another value).
        let (mut x, mut y) = (vec![1.0, 3.0, 2.0, 3.0, 0.5], vec![10., 30., 20., 31., 5.]);
        let o = order_points(&mut x, &mut y);
        assert_eq!(o.reorder, Reorder::Sorted);
        assert_eq!(x, vec![0.5, 1.0, 2.0, 3.0]);
        assert_eq!(
            y,
            vec![5., 10., 20., 30.],
            "the first row of an abscissa is kept"
        );
        assert_eq!(o.dropped, 1);
        assert_eq!(o.max_dropped_dy, 1.0);

        let (mut x, mut y) = (vec![3.0, 2.0, 1.0], vec![1., 2., 3.]);
        let o = order_points(&mut x, &mut y);
        assert_eq!((o.reorder, o.dropped), (Reorder::Reversed, 0));
        assert_eq!((x, y), (vec![1.0, 2.0, 3.0], vec![3., 2., 1.]));

        let (mut x, mut y) = (vec![1.0, 2.0], vec![1., 2.]);
        assert_eq!(order_points(&mut x, &mut y).reorder, Reorder::None);

        // Increasing with an exact copy of a point (a restart that stores its start row):
        // sorted, one copy kept, nothing lost.
        let (mut x, mut y) = (vec![1.0, 2.0, 2.0, 3.0], vec![1., 4., 4., 9.]);
        let o = order_points(&mut x, &mut y);
        assert_eq!(
            (o.reorder, o.dropped, o.max_dropped_dy),
            (Reorder::Sorted, 1, 0.0)
        );
        assert_eq!(x, vec![1.0, 2.0, 3.0]);
    }

    /// y = x² sampled at 1, 2, 4.
    fn square(interpol: (Interp, Interp)) -> Function {
        let mut f =
            Function::new("F", "X", "Y", vec![1.0, 2.0, 4.0], vec![1.0, 4.0, 16.0]).unwrap();
        f.interpol = interpol;
        f.check().unwrap();
        f
    }

    // Tolerances: 1e-12 relative covers the rounding of ln/exp in f64; every expected value
    // below is a closed form of the sampled points.
    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn lin_lin_is_the_chord() {
        let f = square((Interp::Lin, Interp::Lin));
        // On [2, 4]: 4 + (3-2)/(4-2) * (16-4) = 10.
        assert!(close(f.eval(3.0).unwrap(), 10.0));
        assert_eq!(f.eval(2.0).unwrap(), 4.0);
        assert_eq!(f.eval(1.0).unwrap(), 1.0);
        assert_eq!(f.eval(4.0).unwrap(), 16.0);
    }

    #[test]
    fn log_log_is_exact_for_power_laws() {
        let f = square((Interp::Log, Interp::Log));
        for x in [1.3, 2.5, 3.0, 3.9] {
            assert!(close(f.eval(x).unwrap(), x * x), "x={x}");
        }
    }

    #[test]
    fn mixed_log_axes() {
        // x LIN, y LOG on [2, 4] at 3: exp(ln 4 + 0.5 (ln 16 - ln 4)) = 8.
        let f = square((Interp::Lin, Interp::Log));
        assert!(close(f.eval(3.0).unwrap(), 8.0));
        // x LOG, y LIN: t = ln(3/2)/ln 2, y = 4 + 12 t.
        let f = square((Interp::Log, Interp::Lin));
        let t = (1.5f64).ln() / 2f64.ln();
        assert!(close(f.eval(3.0).unwrap(), 4.0 + 12.0 * t));
    }

    #[test]
    fn prolongations() {
        let mut f = square((Interp::Lin, Interp::Lin));
        let err = f.eval(5.0).unwrap_err();
        assert!(err.message.contains("function F"), "{err}");
        assert!(err.message.contains("[1, 4]"), "{err}");
        assert!(err.message.contains("PROL_DROITE='EXCLU'"), "{err}");
        f.prol_gauche = Prol::Constant;
        f.prol_droite = Prol::Lineaire;
        assert_eq!(f.eval(0.0).unwrap(), 1.0);
        // End segment slope (16-4)/2 = 6: at 5, 16 + 6 = 22.
        assert!(close(f.eval(5.0).unwrap(), 22.0));
        // LOG/LOG LINEAIRE extends the power law: 8² = 64, and left 0.5² = 0.25.
        let mut g = square((Interp::Log, Interp::Log));
        g.prol_gauche = Prol::Lineaire;
        g.prol_droite = Prol::Lineaire;
        assert!(close(g.eval(8.0).unwrap(), 64.0));
        assert!(close(g.eval(0.5).unwrap(), 0.25));
        assert!(g.eval(-1.0).is_err());
    }

    use proptest::prelude::*;

    proptest! {
        /// LOG/LOG interpolation reproduces any power law y = c x^p between and (with
        /// LINEAIRE) beyond its points. 1e-10 relative: ln/exp round-trips in f64 lose
        /// ~1e-14 on these magnitudes (y within 1e-7..1e7).
        #[test]
        fn log_log_reproduces_power_laws(
            c in 0.1f64..10.0,
            p in -3.0f64..3.0,
            xs in prop::collection::btree_set(1u32..1000, 2..8),
            t in 0.0f64..1.0,
        ) {
            let xs: Vec<f64> = xs.into_iter().map(|v| f64::from(v) * 0.1).collect();
            let ys: Vec<f64> = xs.iter().map(|x| c * x.powf(p)).collect();
            let mut f = Function::new("P", "X", "Y", xs.clone(), ys).unwrap();
            f.interpol = (Interp::Log, Interp::Log);
            f.prol_gauche = Prol::Lineaire;
            f.prol_droite = Prol::Lineaire;
            let (lo, hi) = (xs[0] * 0.5, xs[xs.len() - 1] * 2.0);
            let x = lo + t * (hi - lo);
            let want = c * x.powf(p);
            let got = f.eval(x).unwrap();
            prop_assert!((got - want).abs() <= 1e-10 * want, "x={} got={} want={}", x, got, want);
        }
    }

    #[test]
    fn non_interpolation_only_at_nodes() {
        let f = square((Interp::Non, Interp::Non));
        assert_eq!(f.eval(2.0).unwrap(), 4.0);
        assert!(f.eval(3.0).unwrap_err().message.contains("INTERPOL='NON'"));
    }

    #[test]
    fn bad_definitions_are_refused() {
        let err = Function::new("G", "X", "Y", vec![0.0, 2.0, 1.0], vec![0.0; 3]).unwrap_err();
        assert!(err.message.contains("strictly increasing"), "{err}");
        assert!(Function::new("G", "X", "Y", vec![0.0, 0.0], vec![0.0; 2]).is_err());
        assert!(Function::new("G", "X", "Y", vec![0.0, 1.0], vec![0.0]).is_err());
        let mut f = Function::new("G", "X", "Y", vec![0.0, 1.0], vec![1.0, 2.0]).unwrap();
        f.interpol = (Interp::Log, Interp::Lin);
        assert!(f
            .check()
            .unwrap_err()
            .message
            .contains("positive abscissas"));
        let mut f = Function::new("G", "X", "Y", vec![1.0], vec![1.0]).unwrap();
        f.prol_droite = Prol::Lineaire;
        assert!(f.check().is_err());
    }
}
