//! What several operators share (the operators themselves are the other files of
//! `src/ops/`, one each).

// Test support: operators run on an in-memory store with hand-built `Args`.
#[cfg(test)]
pub mod harness;
// MODE_NON_LINE's live view: the rows of each branch in a side file while it runs.
pub mod live;
// The engine's errors in the user's words (the keyword of each setting).
pub mod engine_errors;
// One component of a dyna_trans by NOM_CHAM, NOEUD | GROUP_NO, NOM_CMP (TEST_RESU,
// RECU_FONCTION).
pub mod dyna_trans;
// The basis of a generalized numbering (PROJ_MATR_BASE, PROJ_VECT_BASE, DYNA_VIBRA).
pub mod gene;
// The archived instants INST, NUME_ORDRE, INTERPOL ask for (REST_GENE_PHYS, RECU_FONCTION).
pub mod instants;
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
// The methods of Code_Aster's Python API on a DYNA_VIBRA result (LIST_ARCH, VARI_INTERNE).
pub mod result_api;
// A shock's internal variables VINTi in Code_Aster's order (RECU_FONCTION, VARI_INTERNE).
pub mod shock_vint;
// The section keywords (SECTION, CARA, VALE) of AFFE_CARA_ELEM's POUTRE and BARRE.
pub mod section;
// The location keywords (TOUT, GROUP_MA, MAILLE, GROUP_NO, NOEUD) as a mesh selection.
pub mod selection;
// The moving supports of a seismic excitation and their constraint modes (CALC_CHAR_SEISME,
// DYNA_VIBRA MULT_APPUI, REST_GENE_PHYS, RECU_FONCTION).
pub mod supports;
// Time histories of a DYNA_VIBRA result (RECU_FONCTION's RESU_GENE).
pub mod tran_gene;
// The table keywords (FILTRE, TRI, TABLE) shared by the table operators.
pub mod table_args;
// The comparison behind every TEST_* operator.
pub mod testing;
