//! What is derived from each computed point besides the point itself (MODE_NON_LINE's rows,
//! CALC_STABILITE's orbits): the Fourier coefficients of the displacements, velocities and
//! contact unknowns, and the time-domain check of the contact laws (`law_check`).
//!
//! Everything that depends only on the problem is built once: the layout of the unknowns
//! (`Unknowns`, cheap: no scaling, matrices or FFT plan, unlike a `System`) and, for the law
//! check, the physical laws (η needs factorisations of K and M) and the FFT plan of the
//! sampling (`PostProcessor`). A row then costs copies and a few FFTs.

use crate::nnm::analysis::contact_work::ContactWork;
use crate::nnm::analysis::law_check::LawCheck;
use crate::nnm::continuation::end_check::EndCheck;
use crate::nnm::error::Result;
use crate::nnm::model::unknowns::Unknowns;
use crate::nnm::{Harmonics, Problem};

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
    pub fn new(problem: &Problem, harmonics: impl Into<Harmonics>) -> Result<PostProcessor> {
        let unknowns = Unknowns::new(problem, harmonics)?;
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
    /// [`LAW_DEFECT_ALARM`](crate::nnm::LAW_DEFECT_ALARM) relative (the defect taken from `known`
    /// when the run computed it already, `Point::law_defect`) and its contact forces pass
    /// the work test at `work_min` ([`PostProcessor::not_a_motion`]). What decides the rows a
    /// wrong branch keeps (the operator's `end::rows_kept`, ops/mode_non_line/end.rs).
    pub fn is_motion(&self, x: &[f64], known: Option<(f64, f64)>, work_min: f64) -> Result<bool> {
        self.unknowns.check(x)?;
        let displacement = self.unknowns.displacement_unchecked(x);
        let contact = self.unknowns.contact_unchecked(x);
        let relative = match known {
            Some((_, rel)) => rel,
            None => self.check.defects(&displacement, &contact)?.1,
        };
        Ok(relative <= crate::nnm::LAW_DEFECT_ALARM
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
pub fn contact_law_defect(
    problem: &Problem,
    harmonics: impl Into<Harmonics>,
    x: &[f64],
) -> Result<f64> {
    if problem.shocks.is_empty() {
        return Ok(0.0);
    }
    PostProcessor::new(problem, harmonics)?.law_defect(x)
}

/// The driver's checks of a branch end (continuation/end_check.rs) are the row's.
impl EndCheck for PostProcessor {
    fn law_defects(&self, x: &[f64]) -> Result<(f64, f64)> {
        PostProcessor::law_defects(self, x)
    }
    fn not_a_motion(&self, x: &[f64], work_min: f64) -> Result<Option<f64>> {
        PostProcessor::not_a_motion(self, x, work_min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::tests::{one_dof, settings};
    use crate::nnm::ShockLaw;

    /// Every output of a row reads the point through `Unknowns::check`: a point one value
    /// short, or not finite, is refused as bad input (not a panic on a slice).
    #[test]
    fn a_row_of_another_problem_is_refused() {
        let s = settings(3, 7, 1, 1);
        let p = one_dof(ShockLaw::Plan, 1e-4);
        let post = PostProcessor::new(&p, &s).unwrap();
        let n = Unknowns::new(&p, &s).unwrap().layout().n_unk;
        let e = post.row(&vec![0.0; n - 1]).unwrap_err();
        assert_eq!(e.kind, crate::nnm::error::ErrorKind::Input);
        let mut x = vec![0.0; n];
        x[3] = f64::NAN;
        assert!(post.row(&x).is_err());
        assert!(post.displacement(&x).is_err());
        assert!(post.law_defects(&x).is_err());
    }
}
