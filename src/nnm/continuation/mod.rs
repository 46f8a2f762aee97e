//! Continuation: the EHMAN stages of one branch (the start, the ANM series and its Padé
//! approximants, the Newton correction of the branch end, the bifurcation test, the report)
//! and the driver that chains branches, with the guards that stop a branch that is no
//! longer a motion (step control, frequency floor, folds, roots of the law). Uses the model
//! and the solvers.

pub(in crate::nnm) mod anm;
pub(in crate::nnm) mod bifurcation;
pub(in crate::nnm) mod correction;
pub(in crate::nnm) mod driver;
pub(in crate::nnm) mod end_check;
pub(in crate::nnm) mod fold_guard;
pub(in crate::nnm) mod forced_start;
pub(in crate::nnm) mod frequency_floor;
pub(in crate::nnm) mod newton;
pub(in crate::nnm) mod pade;
pub(in crate::nnm) mod quadrature;
pub(in crate::nnm) mod report;
pub(in crate::nnm) mod series_step;
pub(in crate::nnm) mod start;
pub(in crate::nnm) mod step_control;
