//! Where each series of a stored point sits: the layout of a physical `Point::x` for one
//! problem and its harmonic counts, checked against a point read back from the store. Cheap
//! to build (no scaling, matrices or FFT plan, unlike a `System`).

use crate::nnm::error::{Error, Result};
use crate::nnm::model::point::finite;
use crate::nnm::model::problem::Harmonics;
use crate::nnm::model::system::{self, Layout};
use crate::nnm::Problem;

/// Where each series of a stored point (a physical `Point::x`) sits.
#[derive(Clone, Debug)]
pub(crate) struct Unknowns {
    lay: Layout,
    /// Per shock: the offset of its contact unknowns and their number.
    shocks: Vec<(usize, usize)>,
}

impl Unknowns {
    pub fn new(problem: &Problem, harmonics: impl Into<Harmonics>) -> Result<Unknowns> {
        let harmonics = harmonics.into();
        system::validate_problem(problem, harmonics)?;
        let (lay, offsets) = Layout::of(problem, harmonics);
        let shocks = offsets
            .into_iter()
            .zip(&problem.shocks)
            .map(|(o, s)| (o, s.law.n_own()))
            .collect();
        Ok(Unknowns { lay, shocks })
    }

    pub fn layout(&self) -> &Layout {
        &self.lay
    }

    /// `x` has the size of a point of this problem and is finite.
    pub fn check(&self, x: &[f64]) -> Result<()> {
        if x.len() != self.lay.n_unk || !finite(x) {
            return Err(Error::input(format!(
                "the stored point has {} values ({} finite expected for these NB_HARM_LINE/NB_HARM_NONL and shocks)",
                x.len(),
                self.lay.n_unk
            ))
            .hint("the point was stored by a run with other NB_HARM_LINE/NB_HARM_NONL or shocks: use the settings of that run"));
        }
        Ok(())
    }

    /// Fourier coefficients (0, C1..CH_l, S1..SH_l) of the displacement of each DOF.
    pub fn displacement(&self, x: &[f64]) -> Result<Vec<Vec<f64>>> {
        self.check(x)?;
        Ok(self.displacement_unchecked(x))
    }

    /// Fourier coefficients of the velocity of each DOF.
    pub fn velocity(&self, x: &[f64]) -> Result<Vec<Vec<f64>>> {
        self.check(x)?;
        let lay = &self.lay;
        Ok((0..lay.n)
            .map(|i| x[lay.v(i)..lay.v(i) + lay.n_coef_lin].to_vec())
            .collect())
    }

    /// Fourier coefficients (0, C1..CH_nl, S1..SH_nl) of each contact unknown of each shock.
    pub fn contact(&self, x: &[f64]) -> Result<Vec<Vec<Vec<f64>>>> {
        self.check(x)?;
        Ok(self.contact_unchecked(x))
    }

    pub(in crate::nnm) fn displacement_unchecked(&self, x: &[f64]) -> Vec<Vec<f64>> {
        let lay = &self.lay;
        (0..lay.n)
            .map(|i| x[lay.u(i)..lay.u(i) + lay.n_coef_lin].to_vec())
            .collect()
    }

    pub(in crate::nnm) fn contact_unchecked(&self, x: &[f64]) -> Vec<Vec<Vec<f64>>> {
        let nn = self.lay.n_coef_nonl;
        self.shocks
            .iter()
            .map(|&(offset, n_own)| {
                (0..n_own)
                    .map(|v| x[offset + v * nn..offset + (v + 1) * nn].to_vec())
                    .collect()
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::model::system::{Scaling, System};
    use crate::nnm::tests::{settings, sparse};
    use crate::nnm::{CercleForm, Shock, ShockLaw};

    fn shock(law: ShockLaw, dofs: Vec<usize>) -> Shock {
        Shock {
            law,
            dofs,
            gap: 0.01,
            stiffness: 50.0,
            regul: 5e-5,
        }
    }

    /// Three DOFs carrying one shock of each law (the laws' equations fix how many
    /// contact unknowns each has), and the same structure without shocks.
    fn problems() -> Vec<Problem> {
        let diag = |v: f64| sparse(3, &[(0, 0, v), (1, 1, v), (2, 2, v)]);
        let with = |shocks: Vec<Shock>| Problem {
            forcing: None,
            k: diag(10.0),
            m: diag(1.0),
            shocks,
        };
        vec![
            with(vec![
                shock(ShockLaw::Plan, vec![0]),
                shock(ShockLaw::BiPlan, vec![1]),
                shock(
                    ShockLaw::Cercle {
                        origin: [0.0, 0.0],
                        form: CercleForm::Secant,
                    },
                    vec![1, 2],
                ),
            ]),
            with(vec![]),
        ]
    }

    /// The layout read without a system is the one `System::new` builds: the engine's
    /// placement of the contact unknowns is the reference.
    #[test]
    fn layout_without_a_system_is_the_systems() {
        let s = settings(3, 7, 1, 1);
        for p in problems() {
            let sys = System::new(&p, &s, Scaling::new(&p, 1.0, 0).unwrap(), 0).unwrap();
            let (of_problem, offsets) = Layout::of(&p, &s);
            let lay = sys.lay;
            assert_eq!(
                (
                    of_problem.n,
                    of_problem.h_lin,
                    of_problem.h_nonl,
                    of_problem.n_coef_lin,
                    of_problem.n_coef_nonl,
                    of_problem.n_unk
                ),
                (
                    lay.n,
                    lay.h_lin,
                    lay.h_nonl,
                    lay.n_coef_lin,
                    lay.n_coef_nonl,
                    lay.n_unk
                )
            );
            let engine: Vec<(usize, usize)> = sys
                .shocks
                .iter()
                .map(|sh| (sh.offset, sh.eqs.n_own))
                .collect();
            let ours: Vec<(usize, usize)> = offsets
                .iter()
                .zip(&p.shocks)
                .map(|(&o, sh)| (o, sh.law.n_own()))
                .collect();
            assert_eq!(ours, engine);

            // Every series is read from where the engine puts it: number each unknown by
            // its position and check the first coefficient of each series.
            let x: Vec<f64> = (0..lay.n_unk).map(|i| i as f64).collect();
            let unk = Unknowns::new(&p, &s).unwrap();
            let u = unk.displacement(&x).unwrap();
            let v = unk.velocity(&x).unwrap();
            for i in 0..lay.n {
                assert_eq!(u[i][0], lay.u(i) as f64);
                assert_eq!(v[i][0], lay.v(i) as f64);
                assert_eq!((u[i].len(), v[i].len()), (lay.n_coef_lin, lay.n_coef_lin));
            }
            let c = unk.contact(&x).unwrap();
            assert_eq!(c.len(), sys.shocks.len());
            for (sh, series) in sys.shocks.iter().zip(&c) {
                assert_eq!(series.len(), sh.eqs.n_own);
                for (k, f) in series.iter().enumerate() {
                    assert_eq!(f[0], (sh.offset + k * lay.n_coef_nonl) as f64);
                    assert_eq!(f.len(), lay.n_coef_nonl);
                }
            }
        }
    }

    /// A point of another problem (one value short) or not finite is refused, naming
    /// ETAT_INIT as the engine's restart does.
    #[test]
    fn a_point_of_the_wrong_size_or_not_finite_is_refused() {
        let s = settings(3, 7, 1, 1);
        let p = problems().remove(0);
        let unknowns = Unknowns::new(&p, &s).unwrap();
        let n = Layout::of(&p, &s).0.n_unk;
        let e = unknowns.check(&vec![0.0; n - 1]).unwrap_err();
        // The engine does not know which keyword chose the point: the operator names it.
        assert_eq!(e.kind, crate::nnm::error::ErrorKind::Input);
        assert_eq!(e.setting, None);
        let mut x = vec![0.0; n];
        x[3] = f64::NAN;
        assert!(unknowns.check(&x).is_err());
        assert!(unknowns.displacement(&x).is_err());
        assert!(unknowns.velocity(&x).is_err());
        assert!(unknowns.contact(&x).is_err());
    }

    /// Reading a stored point needs its harmonic counts alone: continuation settings that a
    /// run refuses (NB_ORDRE_MAN below 2) do not stop restitution, and a run still refuses
    /// them.
    #[test]
    fn restitution_needs_the_harmonic_counts_alone() {
        let p = problems().remove(0);
        let mut s = settings(3, 7, 1, 1);
        s.continuation.order = 0;
        let h = Harmonics::from(&s);
        assert_eq!((h.h_lin, h.h_nonl), (3, 7));
        let n = Unknowns::new(&p, h).unwrap().layout().n_unk;
        assert_eq!(n, Layout::of(&p, &s).0.n_unk);
        let e = system::validate(&p, &s).unwrap_err();
        assert_eq!(e.setting, Some(crate::nnm::error::Setting::SeriesOrder));
        system::validate_problem(&p, h).unwrap();
        // Harmonics of their own are still checked.
        let bad = Harmonics {
            h_lin: 0,
            h_nonl: 7,
        };
        assert!(Unknowns::new(&p, bad).is_err());
    }
}
