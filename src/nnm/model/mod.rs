//! The model of the problem: what is solved (the structure, its shocks and the settings),
//! the layout and scaling of the unknowns, the regularised contact laws, the
//! harmonic-balance system with its tangent, the Fourier machinery it is written in, and
//! what a point is (its energy, its physical units). Nothing here knows how a branch is
//! followed or how the tangent is solved.

pub(in crate::nnm) mod contact_samples;
pub(in crate::nnm) mod cosine_sampler;
pub(in crate::nnm) mod energy;
pub mod exact;
pub(in crate::nnm) mod fourier;
pub(in crate::nnm) mod law;
pub(in crate::nnm) mod linear_modes;
pub(in crate::nnm) mod low_synth;
pub(in crate::nnm) mod point;
pub(in crate::nnm) mod point_law;
pub(in crate::nnm) mod problem;
pub(in crate::nnm) mod reduced;
pub(in crate::nnm) mod rescale;
pub(in crate::nnm) mod root_defect;
pub(in crate::nnm) mod system;
pub(in crate::nnm) mod unknowns;
pub(in crate::nnm) mod vector;
pub(in crate::nnm) mod workspace;
