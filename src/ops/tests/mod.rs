//! Tests of the operators, run on an in-memory store (`common::harness`).

// The model operators end to end on the sdnd122 system, and the catalogs against the
// registered operators.
mod model_ops;
// Table, function and TEST_* operators.
mod operators;
// The pictures of IMPR_FONCTION and IMPR_TABLE.
mod plots;
