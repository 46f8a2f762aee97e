//! Linear algebra glue over faer: sparse matrices (`sparse`) and, written separately,
//! the generalized eigen solvers (`eigen*`, integration: add their `pub mod` lines here).

pub mod sparse;
