//! What several operators share (the operators themselves are the other files of
//! `src/ops/`, one each).

// Test support: operators run on an in-memory store with hand-built `Args`.
#[cfg(test)]
pub mod harness;
// How a MODE_NON_LINE run that ended before NB_BRANCHE is reported (alarm or error).
pub mod mnl_end;
// MODE_NON_LINE's live view: the rows of each branch in a side file while it runs.
pub mod live;
// MODE_NON_LINE's RESOLUTION/CORR_LOI_EXACTE: rows corrected on the exact law.
pub mod mnl_exact_law;
// MODE_NON_LINE restarts: the stored direction of travel.
pub mod mnl_restart;
// MODE_NON_LINE's start from linear modes (ETAT_INIT).
pub mod mnl_start;
// Stored shocks and matrices back to the engine's problem (MODE_NON_LINE, REST_MODE_NONL,
// CALC_STABILITE).
pub mod mnl_problem;
// One component of a dyna_trans by NOM_CHAM, NOEUD | GROUP_NO, NOM_CMP (TEST_RESU,
// RECU_FONCTION).
pub mod dyna_trans;
// The stored results IMPR_RESU writes to MED, as nodal fields on their mesh.
pub mod med_fields;
// The node of NOEUD= or of a one-node GROUP_NO= (TEST_RESU, MODE_NON_LINE's CHOC).
pub mod nodes;
// Writing to logical units (UNITE); the files a run never writes over.
pub mod output;
// The picture keywords of IMPR_FONCTION and IMPR_TABLE.
pub mod plot_args;
// Progress bars (on a terminal only).
pub mod progress;
// Whether a call fits the machine (memory, long work).
pub mod resources;
// The section keywords (SECTION, CARA, VALE) of AFFE_CARA_ELEM's POUTRE and BARRE.
pub mod section;
// The location keywords (TOUT, GROUP_MA, MAILLE, GROUP_NO, NOEUD) as a mesh selection.
pub mod selection;
// The table keywords (FILTRE, TRI, TABLE) shared by the table operators.
pub mod table_args;
// The comparison behind every TEST_* operator.
pub mod testing;
