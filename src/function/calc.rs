//! CALC_FONCTION's operations on tabulated functions: linear combination (COMB), product
//! (MULT), absolute value (ABS), derivative (DERIVE), primitive by trapezes (INTEGRE).
//!
//! COMB and MULT work on a common support, Code_Aster's rule for two functions applied in
//! turn: on the left, the later start wins unless that function extends to the left
//! (PROL_GAUCHE other than EXCLU), then the earlier start wins; on the right alike. The
//! abscissas are those of every function inside the support, and every function is
//! evaluated (interpolated, or extended by its prolongation) at each of them.

use super::{Function, Prol};
use crate::error::{Error, Result};

/// One end of the support being built: where it is and whether the function that set it
/// extends beyond it.
#[derive(Clone, Copy)]
struct End {
    at: f64,
    extends: bool,
}

/// The abscissas every function of `fs` is evaluated at: the union of their abscissas in
/// the common support, sorted, each once.
pub fn support(fs: &[&Function]) -> Result<Vec<f64>> {
    let ends = |f: &Function| -> Option<(End, End)> {
        Some((
            End {
                at: *f.x.first()?,
                extends: f.prol_gauche != Prol::Exclu,
            },
            End {
                at: *f.x.last()?,
                extends: f.prol_droite != Prol::Exclu,
            },
        ))
    };
    let mut it = fs.iter();
    let (Some(first), true) = (it.next(), fs.iter().all(|f| !f.x.is_empty())) else {
        return Err(Error::input("no function, or a function without points"));
    };
    let (mut lo, mut hi) = ends(first).ok_or_else(|| Error::input("a function has no point"))?;
    for f in it {
        let (l, h) = ends(f).ok_or_else(|| Error::input("a function has no point"))?;
        // Left: the later start, unless the later-starting one extends to the left.
        lo = if l.at > lo.at {
            if l.extends {
                lo
            } else {
                l
            }
        } else if lo.extends {
            l
        } else {
            lo
        };
        // Right: the earlier end, unless the earlier-ending one extends to the right.
        hi = if h.at < hi.at {
            if h.extends {
                hi
            } else {
                h
            }
        } else if hi.extends {
            h
        } else {
            hi
        };
    }
    if lo.at > hi.at {
        let ranges: Vec<String> = fs
            .iter()
            .map(|f| format!("{} on [{}, {}]", f.name, f.x[0], f.x[f.x.len() - 1]))
            .collect();
        return Err(Error::input(format!(
            "the functions have no abscissa in common: {} (PROL_GAUCHE/PROL_DROITE='EXCLU')",
            ranges.join(", ")
        ))
        .hint("give PROL_GAUCHE or PROL_DROITE='CONSTANT' or 'LINEAIRE' to the functions"));
    }
    let mut xs: Vec<f64> = fs
        .iter()
        .flat_map(|f| f.x.iter().copied())
        .filter(|&x| x >= lo.at && x <= hi.at)
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    Ok(xs)
}

/// Σ cᵢ fᵢ on the common support: (abscissas, values).
pub fn combine(terms: &[(&Function, f64)]) -> Result<(Vec<f64>, Vec<f64>)> {
    let fs: Vec<&Function> = terms.iter().map(|(f, _)| *f).collect();
    let xs = support(&fs)?;
    let mut ys = vec![0.0; xs.len()];
    for (f, c) in terms {
        for (y, &x) in ys.iter_mut().zip(&xs) {
            *y += c * f.eval(x)?;
        }
    }
    Ok((xs, ys))
}

/// Π fᵢ on the common support: (abscissas, values).
pub fn multiply(fs: &[&Function]) -> Result<(Vec<f64>, Vec<f64>)> {
    let xs = support(fs)?;
    let mut ys = vec![1.0; xs.len()];
    for f in fs {
        for (y, &x) in ys.iter_mut().zip(&xs) {
            *y *= f.eval(x)?;
        }
    }
    Ok((xs, ys))
}

/// |f|: a LINEAIRE prolongation becomes EXCLU (a straight line's absolute value is not
/// one), as in Code_Aster.
pub fn abs(f: &Function) -> Function {
    let mut g = f.clone();
    g.y.iter_mut().for_each(|y| *y = y.abs());
    for p in [&mut g.prol_gauche, &mut g.prol_droite] {
        if *p == Prol::Lineaire {
            *p = Prol::Exclu;
        }
    }
    g
}

/// The result name after differentiating (DEPL -> VITE -> ACCE) or integrating (the other
/// way), as Code_Aster renames it; any other name is kept.
fn renamed(nom_resu: &str, pairs: &[(&str, &str)]) -> String {
    for (from, to) in pairs {
        if nom_resu.starts_with(from) {
            return (*to).to_string();
        }
    }
    nom_resu.to_string()
}

/// The derivative at each abscissa by centred differences (METHODE='DIFF_CENTREE', as
/// Code_Aster): inside, the chord (y(i+1) - y(i-1)) / (x(i+1) - x(i-1)), exact for a
/// parabola on an even grid; at the ends, the end segments' slopes. EXCLU on both sides.
pub fn derive(f: &Function) -> Result<Function> {
    let n = f.x.len();
    if n < 2 || f.y.len() != n {
        return Err(Error::input(format!(
            "function {} needs at least two points to be differentiated",
            f.name
        )));
    }
    let slope = |i: usize, j: usize| (f.y[j] - f.y[i]) / (f.x[j] - f.x[i]);
    let mut d = Vec::with_capacity(n);
    d.push(slope(0, 1));
    for i in 1..n - 1 {
        d.push(slope(i - 1, i + 1));
    }
    d.push(slope(n - 2, n - 1));
    let mut g = f.clone();
    g.y = d;
    g.prol_gauche = Prol::Exclu;
    g.prol_droite = Prol::Exclu;
    g.nom_resu = renamed(&f.nom_resu, &[("DEPL", "VITE"), ("VITE", "ACCE")]);
    Ok(g)
}

/// The primitive by the trapezoidal rule, equal to `c0` at the first abscissa. EXCLU on
/// both sides.
pub fn integrate_trapeze(f: &Function, c0: f64) -> Function {
    let mut acc = c0;
    let mut y = Vec::with_capacity(f.x.len());
    y.push(c0);
    for (w, v) in f.x.windows(2).zip(f.y.windows(2)) {
        acc += 0.5 * (v[0] + v[1]) * (w[1] - w[0]);
        y.push(acc);
    }
    y.truncate(f.x.len());
    let mut g = f.clone();
    g.y = y;
    g.prol_gauche = Prol::Exclu;
    g.prol_droite = Prol::Exclu;
    g.nom_resu = renamed(&f.nom_resu, &[("VITE", "DEPL"), ("ACCE", "VITE")]);
    g
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::function::Interp;

    fn f(name: &str, x: &[f64], y: &[f64], pg: Prol, pd: Prol) -> Function {
        let mut f = Function::new(name, "INST", "ACCE", x.to_vec(), y.to_vec()).unwrap();
        f.prol_gauche = pg;
        f.prol_droite = pd;
        f
    }

    #[test]
    fn comb_of_linear_functions_is_exact_on_the_union() {
        // a(x) = 2x on 0, 1, 2; b(x) = 1 - x on 0.5, 1.5, 3 (EXCLU both): support [0.5, 2],
        // abscissas 0.5 1 1.5 2. 3a - 2b = 8x - 2, exactly (linear interpolation of lines).
        let a = f("A", &[0., 1., 2.], &[0., 2., 4.], Prol::Exclu, Prol::Exclu);
        let b = f(
            "B",
            &[0.5, 1.5, 3.],
            &[0.5, -0.5, -2.],
            Prol::Exclu,
            Prol::Exclu,
        );
        let (x, y) = combine(&[(&a, 3.0), (&b, -2.0)]).unwrap();
        assert_eq!(x, vec![0.5, 1.0, 1.5, 2.0]);
        for (x, y) in x.iter().zip(&y) {
            assert!((y - (8.0 * x - 2.0)).abs() <= 1e-15 * 16.0, "{x} {y}");
        }
        // B extends to the left (CONSTANT at 0.5): the support starts at A's 0.
        let b2 = f(
            "B",
            &[0.5, 1.5, 3.],
            &[0.5, -0.5, -2.],
            Prol::Constant,
            Prol::Exclu,
        );
        let (x, y) = combine(&[(&a, 1.0), (&b2, 1.0)]).unwrap();
        assert_eq!(x, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
        assert_eq!(y[0], 0.0 + 0.5);
        // A extends to the right (LINEAIRE): the support ends at B's 3, A(3) = 6.
        let a2 = f(
            "A",
            &[0., 1., 2.],
            &[0., 2., 4.],
            Prol::Exclu,
            Prol::Lineaire,
        );
        let (x, y) = combine(&[(&a2, 1.0), (&b, 1.0)]).unwrap();
        assert_eq!(*x.last().unwrap(), 3.0);
        assert_eq!(*y.last().unwrap(), 6.0 - 2.0);
        // Disjoint and EXCLU: no common abscissa.
        let c = f("C", &[5., 6.], &[0., 0.], Prol::Exclu, Prol::Exclu);
        let err = combine(&[(&a, 1.0), (&c, 1.0)]).unwrap_err();
        assert!(err.message.contains("no abscissa in common"), "{err}");
    }

    #[test]
    fn mult_abs() {
        let a = f(
            "A",
            &[0., 1., 2.],
            &[1., -2., 3.],
            Prol::Lineaire,
            Prol::Exclu,
        );
        let b = f("B", &[0., 2.], &[2., 2.], Prol::Exclu, Prol::Exclu);
        let (x, y) = multiply(&[&a, &b]).unwrap();
        assert_eq!((x, y), (vec![0., 1., 2.], vec![2., -4., 6.]));
        let g = abs(&a);
        assert_eq!(g.y, vec![1., 2., 3.]);
        assert_eq!(g.prol_gauche, Prol::Exclu);
    }

    #[test]
    fn derive_is_exact_for_a_parabola_inside_and_integrate_for_a_line() {
        // y = x² on an even grid (step 0.5, exact in binary): the centred chord is 2x at
        // the inner points; the ends get the end segments' slopes (x0 + x1 and x3 + x4).
        let x = vec![0.0, 0.5, 1.0, 1.5, 2.0];
        let y: Vec<f64> = x.iter().map(|v| v * v).collect();
        let mut p = Function::new("P", "INST", "DEPL", x.clone(), y).unwrap();
        p.interpol = (Interp::Lin, Interp::Lin);
        let d = derive(&p).unwrap();
        assert_eq!(d.nom_resu, "VITE");
        assert_eq!(d.y, vec![0.5, 1.0, 2.0, 3.0, 3.5]);
        // Uneven grid: the chord over both neighbours, (x(i+1)² - x(i-1)²)/(x(i+1) - x(i-1))
        // = x(i-1) + x(i+1).
        let u = vec![0.0, 0.5, 1.25, 2.0, 4.0];
        let q = Function::new(
            "Q",
            "INST",
            "X",
            u.clone(),
            u.iter().map(|v| v * v).collect(),
        )
        .unwrap();
        let d = derive(&q).unwrap();
        for i in 1..u.len() - 1 {
            assert!(
                (d.y[i] - (u[i - 1] + u[i + 1])).abs() <= 1e-15 * 8.0,
                "{}",
                d.y[i]
            );
        }
        assert_eq!(d.nom_resu, "X");
        // The trapezoidal rule integrates y = 3x + 1 exactly: 1.5x² + x + c0.
        let l = Function::new(
            "L",
            "INST",
            "ACCE",
            x.clone(),
            x.iter().map(|v| 3.0 * v + 1.0).collect(),
        )
        .unwrap();
        let i = integrate_trapeze(&l, 2.0);
        assert_eq!(i.nom_resu, "VITE");
        for (xv, yv) in x.iter().zip(&i.y) {
            assert!(
                (yv - (1.5 * xv * xv + xv + 2.0)).abs() <= 1e-14,
                "{xv} {yv}"
            );
        }
    }
}
