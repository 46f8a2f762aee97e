//! What is derived from each computed point besides the point itself (MODE_NON_LINE's rows,
//! CALC_STABILITE's orbits): the Fourier coefficients of the displacements, velocities and
//! contact unknowns, and the time-domain check of the contact laws (`law_check`).
//!
//! Everything that depends only on the problem is built once: the layout of the unknowns
//! (`Unknowns`, cheap: no scaling, matrices or FFT plan, unlike a `System`) and, for the law
//! check, the physical laws (η needs factorisations of K and M) and the FFT plan of the
//! sampling (`PostProcessor`). A row then costs copies and a few FFTs.

use super::contact_work::ContactWork;
use super::law_check::LawCheck;
use super::point::finite;
use super::system::{self, Layout};
use super::{Problem, Settings};
use crate::error::{Error, Result};

/// Where each series of a stored point (a physical `Point::x`) sits.
#[derive(Clone, Debug)]
pub(crate) struct Unknowns {
    lay: Layout,
    /// Per shock: the offset of its contact unknowns and their number.
    shocks: Vec<(usize, usize)>,
}

impl Unknowns {
    pub fn new(problem: &Problem, settings: &Settings) -> Result<Unknowns> {
        system::validate(problem, settings)?;
        let (lay, offsets) = Layout::of(problem, settings);
        let shocks = offsets
            .into_iter()
            .zip(&problem.shocks)
            .map(|(o, s)| (o, system::own_count(s.law)))
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

    fn displacement_unchecked(&self, x: &[f64]) -> Vec<Vec<f64>> {
        let lay = &self.lay;
        (0..lay.n)
            .map(|i| x[lay.u(i)..lay.u(i) + lay.n_coef_lin].to_vec())
            .collect()
    }

    fn contact_unchecked(&self, x: &[f64]) -> Vec<Vec<Vec<f64>>> {
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

/// The outputs of one point (physical units).
#[derive(Clone, Debug)]
pub struct RowOutputs {
    /// Per DOF: 0, C1..CH_l, S1..SH_l.
    pub displacement: Vec<Vec<f64>>,
    /// Per shock, per contact unknown (PLAN: f; BI_PLAN: f, z; CERCLE: fx, fy, r, φ or, with
    /// LOI_CERCLE='SECANTE', fx, fy, λ, z):
    /// 0, C1..CH_nl, S1..SH_nl.
    pub contact: Vec<Vec<Vec<f64>>>,
    /// Largest |f_series(t) − f_law(u(t))| / (RIGI_NOR·JEU) over the shocks and over
    /// 2(2H_nl+1) instants of one period; 0 without shocks (ECART_LOI_CHOC).
    pub law_defect: f64,
    /// `law_defect` relative to the force the law carries (`LawCheck::defects`): what the
    /// run's guard and alarm compare, so that a row far into a stop, whose force is many
    /// RIGI_NOR·JEU, is judged by its relative accuracy.
    pub law_defect_relative: f64,
}

/// Post-processing of the points of one problem, built once per operator call.
pub struct PostProcessor {
    unknowns: Unknowns,
    check: LawCheck,
    work: ContactWork,
}

impl PostProcessor {
    pub fn new(problem: &Problem, settings: &Settings) -> Result<PostProcessor> {
        let unknowns = Unknowns::new(problem, settings)?;
        let check = LawCheck::new(problem, unknowns.layout())?;
        let work = ContactWork::new(problem, unknowns.layout())?;
        Ok(PostProcessor {
            unknowns,
            check,
            work,
        })
    }

    /// Everything stored with the point `x` (a `Point::x` of this problem and settings).
    pub fn row(&self, x: &[f64]) -> Result<RowOutputs> {
        self.row_with_defect(x, None)
    }

    /// `row`, with the law defect taken from `known` when the run has computed it already
    /// (`Point::law_defect`, from `law_defects` on the same `x`).
    pub fn row_with_defect(&self, x: &[f64], known: Option<(f64, f64)>) -> Result<RowOutputs> {
        self.unknowns.check(x)?;
        let displacement = self.unknowns.displacement_unchecked(x);
        let contact = self.unknowns.contact_unchecked(x);
        let (law_defect, law_defect_relative) = match known {
            Some(d) => d,
            None => self.check.defects(&displacement, &contact)?,
        };
        Ok(RowOutputs {
            displacement,
            contact,
            law_defect,
            law_defect_relative,
        })
    }

    /// See [`RowOutputs::displacement`].
    pub fn displacement(&self, x: &[f64]) -> Result<Vec<Vec<f64>>> {
        self.unknowns.displacement(x)
    }

    /// Fourier coefficients of the velocity of each DOF.
    pub fn velocity(&self, x: &[f64]) -> Result<Vec<Vec<f64>>> {
        self.unknowns.velocity(x)
    }

    /// See [`RowOutputs::contact`].
    pub fn contact(&self, x: &[f64]) -> Result<Vec<Vec<Vec<f64>>>> {
        self.unknowns.contact(x)
    }

    /// See [`RowOutputs::law_defect`].
    pub fn law_defect(&self, x: &[f64]) -> Result<f64> {
        Ok(self.row(x)?.law_defect)
    }

    /// The law defect relative to the force the law carries (`LawCheck::defects`): what
    /// the run's guard (StepControl::law_defect_max) compares.
    pub fn relative_law_defect(&self, x: &[f64]) -> Result<f64> {
        Ok(self.law_defects(x)?.1)
    }

    /// Whether the point `x` may be a motion of the system: its contact law holds within
    /// [`LAW_DEFECT_ALARM`](super::LAW_DEFECT_ALARM) relative (the defect taken from `known`
    /// when the run computed it already, `Point::law_defect`) and its contact forces pass
    /// the work test at `work_min` ([`PostProcessor::not_a_motion`]). What decides the rows a
    /// wrong branch keeps (the operator's `mnl_end::rows_kept`).
    pub fn is_motion(&self, x: &[f64], known: Option<(f64, f64)>, work_min: f64) -> Result<bool> {
        self.unknowns.check(x)?;
        let displacement = self.unknowns.displacement_unchecked(x);
        let contact = self.unknowns.contact_unchecked(x);
        let relative = match known {
            Some((_, rel)) => rel,
            None => self.check.defects(&displacement, &contact)?.1,
        };
        Ok(relative <= super::LAW_DEFECT_ALARM
            && self
                .work
                .not_a_motion(&displacement, &contact, work_min)
                .is_none())
    }

    /// The work ratio of a point that is not a motion by the work test (contact_work.rs:
    /// the work of its contact forces on the displacement over the period, relative to
    /// the elastic virial, below `work_min`; StepControl::work_min), None for one that may
    /// be.
    pub fn not_a_motion(&self, x: &[f64], work_min: f64) -> Result<Option<f64>> {
        self.unknowns.check(x)?;
        let displacement = self.unknowns.displacement_unchecked(x);
        let contact = self.unknowns.contact_unchecked(x);
        Ok(self.work.not_a_motion(&displacement, &contact, work_min))
    }

    /// The largest penetration of the nonsmooth law along the orbit of `x`, in units of
    /// JEU (`LawCheck::largest_penetration`): negative when the orbit reaches no obstacle;
    /// None without shocks.
    pub fn largest_penetration(&self, x: &[f64]) -> Result<Option<f64>> {
        self.unknowns.check(x)?;
        let displacement = self.unknowns.displacement_unchecked(x);
        self.check.largest_penetration(&displacement)
    }

    /// The law defect of `row` and the relative one of `relative_law_defect`, from one
    /// sampling of the law.
    pub fn law_defects(&self, x: &[f64]) -> Result<(f64, f64)> {
        self.unknowns.check(x)?;
        let displacement = self.unknowns.displacement_unchecked(x);
        let contact = self.unknowns.contact_unchecked(x);
        self.check.defects(&displacement, &contact)
    }
}

/// Largest |f_series(t) − f_law(u(t))| / (α·JEU) over the shocks and over 2(2H_nl+1)
/// instants of one period; 0 without shocks. For many points of one problem, build a
/// [`PostProcessor`] once instead.
pub fn contact_law_defect(problem: &Problem, settings: &Settings, x: &[f64]) -> Result<f64> {
    if problem.shocks.is_empty() {
        return Ok(0.0);
    }
    PostProcessor::new(problem, settings)?.law_defect(x)
}

#[cfg(test)]
mod tests {
    use super::super::system::{Scaling, System};
    use super::super::tests::{settings, sparse};
    use super::super::{CercleForm, Shock, ShockLaw};
    use super::*;

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
                .map(|(&o, sh)| (o, system::own_count(sh.law)))
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
        let post = PostProcessor::new(&p, &s).unwrap();
        let n = Layout::of(&p, &s).0.n_unk;
        let e = post.row(&vec![0.0; n - 1]).unwrap_err();
        // The engine does not know which keyword chose the point: the operator names it.
        assert_eq!(e.kind, crate::error::ErrorKind::Input);
        assert_eq!(e.keyword, None);
        let mut x = vec![0.0; n];
        x[3] = f64::NAN;
        assert!(post.row(&x).is_err());
        assert!(post.displacement(&x).is_err());
    }
}
