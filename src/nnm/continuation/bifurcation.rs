//! EHMAN stage 4, the bifurcation test along the continuation (TEST_BIFURCATION): the
//! series test flags rows inside a branch (anm.rs); with 'SERIE_DETERMINANT' the sign of
//! the bordered tangent's determinant at each branch start is also compared with the sign
//! at its end, and a change is located among the branch's points by factorising the
//! tangent at each of them. Why a determinant test beside the series one, and how the
//! sign is obtained without a dense matrix: condensed_det.rs and linear_solver.rs.

use crate::nnm::continuation::anm::Series;
use crate::nnm::error::Result;
use crate::nnm::model::system::System;
use crate::nnm::solve::linear_solver::TangentSolver;
use crate::nnm::Point;

/// The determinant test along the continuation (TEST_BIFURCATION = 'SERIE_DETERMINANT'):
/// the sign at the start of each branch against the sign at its end; where they differ, the
/// branch's points are probed for the first one past the change, which is flagged.
pub(in crate::nnm) struct DeterminantWatch {
    enabled: bool,
    /// The sign at the start of the current branch (None: off, or undecided).
    sign: Option<f64>,
    /// A second factorisation for the points inside a branch where the sign change is looked
    /// for (the main one holds the next branch's tangent then); made when first needed.
    probe: Option<Box<dyn TangentSolver>>,
}

impl DeterminantWatch {
    /// `solver` holds the factorised tangent at the start point.
    pub(in crate::nnm) fn new(enabled: bool, sys: &System, solver: &mut dyn TangentSolver) -> Self {
        let mut watch = DeterminantWatch {
            enabled,
            sign: None,
            probe: None,
        };
        watch.sign = watch.sign(sys, solver);
        watch
    }

    /// The sign of the tangent `solver` holds, when the test is on and can decide.
    pub(in crate::nnm) fn sign(&self, sys: &System, solver: &mut dyn TangentSolver) -> Option<f64> {
        if self.enabled {
            solver.det_sign(sys).ok()
        } else {
            None
        }
    }

    /// The start was factorised with a border the branch leaves against: the start's sign
    /// flips with it (det [R_X; bᵀ] = (b·t)·det [R_X; tᵀ]).
    pub(in crate::nnm) fn border_reversed(&mut self) {
        self.sign = self.sign.map(|s| -s);
    }

    /// The unknowns were re-expressed in other units (rescale.rs): the probe, factorised in
    /// the old ones, is made again when next needed. The sign itself is unchanged.
    pub(in crate::nnm) fn units_changed(&mut self) {
        self.probe = None;
    }

    /// The branch from `x_start` along `series` has ended with sign `end_sign`: flag its first
    /// point past a sign change, if there is one; the end sign becomes the next start's.
    #[allow(clippy::too_many_arguments)]
    pub(in crate::nnm) fn branch_ended(
        &mut self,
        sys: &System,
        end_sign: Option<f64>,
        series: &Series,
        x_start: &[f64],
        np: usize,
        points: &mut [Point],
        make_probe: impl FnOnce() -> Result<Box<dyn TangentSolver>>,
    ) -> Result<()> {
        if let (Some(s0), Some(s1)) = (self.sign, end_sign) {
            if s0 != s1 {
                let probe = match &mut self.probe {
                    Some(p) => p,
                    None => self.probe.insert(make_probe()?),
                };
                let row = first_row_past_sign_change(sys, probe.as_mut(), series, x_start, np, s1);
                if let Some(p) = points.get_mut(row - 1) {
                    p.bifurcation = true;
                }
            }
        }
        self.sign = end_sign;
        Ok(())
    }
}

/// The first point of a branch (1-based, among its `np` points) where the bordered tangent's
/// determinant already has the sign `end_sign` of the branch end: the first row past the
/// bifurcation. Points whose test cannot decide count as not yet past it.
fn first_row_past_sign_change(
    sys: &System,
    probe: &mut dyn TangentSolver,
    series: &Series,
    x_start: &[f64],
    np: usize,
    end_sign: f64,
) -> usize {
    for i in 1..np {
        let a = series.a_max * i as f64 / np as f64;
        let x = series.eval(x_start, a);
        let t = series.unit_tangent(a);
        let sign = probe.factor(sys, &x, &t).and_then(|_| probe.det_sign(sys));
        if sign.ok() == Some(end_sign) {
            return i;
        }
    }
    np
}
