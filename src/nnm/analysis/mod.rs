//! Analysis of computed points: what each row reports besides the point (post-processing,
//! the contact laws checked in time, the work of the contact forces), a point as a motion
//! (orbit), the accuracy advice (error sources, resolution, the exact law), the alarms on
//! rows clear of every obstacle, the measured cost of the contact routes, and Floquet
//! stability. Uses every other room; none uses it.

pub(in crate::nnm) mod amplitude;
pub(in crate::nnm) mod band;
pub(in crate::nnm) mod below_contact;
pub(in crate::nnm) mod contact_work;
pub mod error_sources;
pub mod exact_law;
pub(in crate::nnm) mod law_check;
pub(in crate::nnm) mod orbit;
pub(in crate::nnm) mod post;
pub(in crate::nnm) mod resolution;
pub(in crate::nnm) mod resonance;
pub(in crate::nnm) mod route_timing;
pub mod stability;
