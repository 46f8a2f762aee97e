//! The engine's front door: follow a family from its start, with the checks of every branch
//! end the caller's `StepControl` asks for. It wires the continuation (which only asks) to
//! the analysis room (which answers with the contact laws checked in time), so that neither
//! room reaches into the other.

use crate::nnm::continuation::driver::{continue_checked, Outcome};
use crate::nnm::continuation::end_check::EndCheck;
use crate::nnm::error::Result;
use crate::nnm::{BranchReport, Point, PostProcessor, Problem, Settings, StartState, StepControl};

/// Continue `settings.n_branches` branches from `start`; `on_branch` is called after each.
pub fn continue_branches(
    problem: &Problem,
    settings: &Settings,
    start: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]),
) -> Outcome {
    continue_while(problem, settings, start, &mut |r, p| {
        on_branch(r, p);
        true
    })
}

/// As [`continue_branches`], but stops after the first branch for which `on_branch` returns
/// false (e.g. once the energy has passed a bound); at most `settings.n_branches` branches.
pub fn continue_while(
    problem: &Problem,
    settings: &Settings,
    start: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]) -> bool,
) -> Outcome {
    continue_controlled(problem, settings, StepControl::none(), start, on_branch)
}

/// As [`continue_while`], with `control` deciding what happens to a branch that fails.
pub fn continue_controlled(
    problem: &Problem,
    settings: &Settings,
    control: StepControl,
    start: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]) -> bool,
) -> Outcome {
    match end_check(problem, settings, &control) {
        Ok(check) => {
            let check = check.as_ref().map(|c| c as &dyn EndCheck);
            continue_checked(problem, settings, control, check, start, on_branch)
        }
        Err(error) => Outcome {
            points: Vec::new(),
            error: Some(error),
            limit: None,
        },
    }
}

/// The contact laws checked in time at every branch end, when `control` asks for it and
/// there is a law to check.
fn end_check(
    problem: &Problem,
    settings: &Settings,
    control: &StepControl,
) -> Result<Option<PostProcessor>> {
    let checked = control.law_defect_max.is_some() || control.work_min.is_some();
    match checked && !problem.shocks.is_empty() {
        true => PostProcessor::new(problem, settings).map(Some),
        false => Ok(None),
    }
}
