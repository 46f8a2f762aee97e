//! Operators: one thin file each, connecting the catalog (`Args`), the store and the
//! numerics. An operator never does numerics inline and never writes SQL itself beyond
//! calling the typed `store` API.
//!
//! The interpreter calls [`run`] inside one store transaction per call.
//!
//! Every file of this folder beside `mod.rs` is one operator, named after it; what several
//! operators share is in [`common`], the tests of the operators in `tests/`.

pub mod common;
#[cfg(test)]
mod tests;

pub mod affe_cara_elem;
pub mod affe_char_cine;
pub mod affe_char_meca;
pub mod affe_materiau;
pub mod affe_modele;
pub mod asse_matrice;
pub mod asse_vecteur;
pub mod assemblage;
pub mod calc_char_seisme;
pub mod calc_fonc_interp;
pub mod calc_fonction;
pub mod calc_matr_elem;
pub mod calc_modes;
pub mod calc_stabilite;
pub mod calc_table;
pub mod calc_vect_elem;
pub mod crea_champ;
pub mod crea_maillage;
pub mod crea_table;
pub mod defi_base_modale;
pub mod defi_fonction;
pub mod defi_group;
pub mod defi_list_reel;
pub mod defi_materiau;
pub mod defi_obstacle;
pub mod detruire;
pub mod dyna_line;
pub mod dyna_tran_modal;
pub mod dyna_vibra;
pub mod extr_table;
pub mod formule;
pub mod impr_fonction;
pub mod impr_resu;
pub mod impr_table;
pub mod lire_maillage;
pub mod mode_iter_simult;
pub mod mode_non_line;
pub mod mode_statique;
pub mod modi_maillage;
pub mod norm_mode;
pub mod nume_ddl;
pub mod nume_ddl_gene;
pub mod post_dyna_moda_t;
pub mod proj_base;
pub mod proj_matr_base;
pub mod proj_vect_base;
pub mod recu_fonction;
pub mod reponse_forcee_nl;
pub mod rest_gene_phys;
pub mod rest_mode_nonl;
pub mod test_fonction;
pub mod test_resu;
pub mod test_table;

use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::Store;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::PathBuf;

/// Outcome of one TEST_* check.
#[derive(Clone, Debug, PartialEq)]
pub struct TestOutcome {
    pub ok: bool,
    /// The printed OK/NOOK line.
    pub line: String,
}

/// Logical units (`UNITE=20`) mapped to files, Code_Aster style.
#[derive(Clone, Debug, Default)]
pub struct Units {
    pub map: BTreeMap<i64, PathBuf>,
    /// The command file: used to find `<stem>.mail`/`.msh`/`.med` beside it when a unit is
    /// not mapped.
    pub comm_file: Option<PathBuf>,
    /// Files of the run that no operator may write to (the database and its journals, the
    /// command and export files), with what each is, for the message.
    pub protected: Vec<(PathBuf, String)>,
    /// Input files operators have read during the run (meshes): protected as well.
    pub read: std::cell::RefCell<Vec<PathBuf>>,
}

/// First logical unit given to files a command file names by their path (above Code_Aster's
/// units 1..99, so that no `--unit` or `.export` mapping is taken).
const NAMED_FILE_UNITS: i64 = 1000;

impl Units {
    /// A file the command file names by its path (`MA.readAsterMeshFile("x.mail")` of
    /// Code_Aster's Python API): the file beside the command file, else the path as given
    /// (relative to the working directory), mapped to a fresh logical unit for the operator
    /// that reads it.
    pub fn map_named_file(&mut self, name: &str) -> Result<i64> {
        let given = PathBuf::from(name);
        let beside = self
            .comm_file
            .as_ref()
            .and_then(|c| c.parent())
            .filter(|_| given.is_relative())
            .map(|d| d.join(&given));
        let path = match (&beside, given.is_file()) {
            (Some(b), _) if b.is_file() => b.clone(),
            (_, true) => given,
            _ => {
                let looked = match &beside {
                    Some(b) => format!("{} nor {}", b.display(), given.display()),
                    None => given.display().to_string(),
                };
                return Err(Error::input(format!(
                    "the file '{name}' does not exist (neither {looked})"
                ))
                .hint("put the file beside the command file"));
            }
        };
        let unit = self
            .map
            .range(NAMED_FILE_UNITS..)
            .next_back()
            .map_or(NAMED_FILE_UNITS, |(u, _)| u + 1);
        self.map.insert(unit, path);
        Ok(unit)
    }
}

/// Everything an operator may use besides its arguments.
pub struct OpContext<'a> {
    pub store: &'a Store,
    /// Operator name, e.g. `MODE_NON_LINE`.
    pub op: &'a str,
    /// Name the result is bound to (`MNL = ...`), if any.
    pub result: Option<&'a str>,
    /// `reuse=` concept, if any.
    pub reuse: Option<&'a str>,
    /// Source file and line of the call (recorded in the `concepts` table).
    pub file: &'a str,
    pub line: usize,
    /// INFO level of the call (1 when the operator has no INFO keyword).
    pub info: i64,
    /// Where the operator prints (stdout for a run, a buffer in tests).
    pub out: &'a mut dyn Write,
    pub units: &'a Units,
    /// Alarms the user silenced in DEBUT(IGNORE_ALARM=...).
    pub ignored_alarms: &'a [String],
    /// DEBUT(ERREUR=_F(ALARME='EXCEPTION')): an alarm that is not silenced stops the
    /// operator as an error, as in Code_Aster.
    pub alarms_are_errors: bool,
    /// `aster-nl run --tole-machine X`: every real non-regression tolerance (VALE_CALC)
    /// is at least X.
    pub tole_machine: Option<f64>,
    /// Tests run by TEST_* operators, in order.
    pub tests: &'a mut Vec<TestOutcome>,
    /// Concepts created by this call: (name, type). Filled by [`OpContext::create`].
    pub created: Vec<(String, String)>,
    /// Whether progress bars may be drawn (a terminal, not a test).
    pub progress: bool,
    /// Set by operators whose result is a plain Python value (EXTR_TABLE with
    /// TYPE_RESU='R', ...) rather than a concept.
    pub value: Option<crate::value::Value>,
    /// An error to report after this operator's work is committed: MODE_NON_LINE keeps
    /// the branches computed before a failed correction, then the run stops.
    pub deferred_error: Option<Error>,
}

impl<'a> OpContext<'a> {
    /// A context with no result name, no reuse, INFO=1, no silenced alarms and no
    /// progress bars; callers set the other fields they need.
    pub fn new(
        store: &'a Store,
        op: &'a str,
        out: &'a mut dyn Write,
        units: &'a Units,
        tests: &'a mut Vec<TestOutcome>,
    ) -> Self {
        OpContext {
            store,
            op,
            result: None,
            reuse: None,
            file: "",
            line: 0,
            info: 1,
            out,
            units,
            ignored_alarms: &[],
            alarms_are_errors: false,
            tole_machine: None,
            tests,
            created: Vec::new(),
            progress: false,
            value: None,
            deferred_error: None,
        }
    }

    /// The name of the result, or an error if the call was not assigned.
    pub fn result_name(&self) -> Result<&str> {
        self.result.ok_or_else(|| {
            Error::validation(format!(
                "{} produces a concept: assign it, e.g. X = {}(...)",
                self.op, self.op
            ))
        })
    }

    /// Register a new concept of type `ty` named `name` in the store.
    pub fn create(&mut self, name: &str, ty: &str) -> Result<()> {
        self.store
            .register_concept(name, ty, self.op, self.file, self.line)?;
        self.created.push((name.to_string(), ty.to_string()));
        Ok(())
    }

    /// Print an alarm (warning) unless the user silenced its id in DEBUT(IGNORE_ALARM=...);
    /// with DEBUT(ERREUR=_F(ALARME='EXCEPTION')) an alarm Code_Aster raises in the same
    /// situation ([`CODE_ASTER_ALARMS`]) is an error instead. aster-nl's own alarms stay
    /// alarms there: a file written for Code_Aster asks for Code_Aster's alarms to stop
    /// it, and must not be stopped by a diagnostic Code_Aster does not make.
    pub fn alarm(&mut self, id: &str, message: &str) -> Result<()> {
        if self.ignored_alarms.iter().any(|a| a == id) {
            return Ok(());
        }
        if self.alarms_are_errors && !CODE_ASTER_ALARMS.contains(&id) {
            writeln!(
                self.out,
                "<A> <{id}> {message} (aster-nl's own alarm: ERREUR/ALARME='EXCEPTION' applies to Code_Aster's alarms only)"
            )?;
            return Ok(());
        }
        if self.alarms_are_errors {
            return Err(
                Error::input(format!("alarm <{id}> raised as an error: {message}")).hint(format!(
                    "DEBUT(ERREUR=_F(ALARME='EXCEPTION')) turns alarms into errors; \
                     silence this one with IGNORE_ALARM='{id}', or drop ALARME='EXCEPTION'"
                )),
            );
        }
        writeln!(self.out, "<A> <{id}> {message}")?;
        Ok(())
    }

    pub fn say(&mut self, text: &str) -> Result<()> {
        writeln!(self.out, "{text}")?;
        Ok(())
    }
}

/// Alarms Code_Aster raises in the same situation: RECU_FONCTION reordering the abscissas
/// (FONCT0_62, the id Code_Aster's files silence) and LIRE_MAILLAGE's checks of the mesh
/// (orphan, coincident nodes, degenerate cells: Code_Aster's VERI_MAIL, on by default),
/// IMPR_TABLE's TABLEAU_CROISE of a table without three parameters (TABLE0_36) and XMGRACE
/// of one without two (TABLE0_21), DYNA_VIBRA's ADAPT_ORDRE1/2 keeping a step after
/// NMAX_ITER_PAS tries (DYNAMIQUE_18). Only these become errors under
/// DEBUT(ERREUR=_F(ALARME='EXCEPTION')).
pub const CODE_ASTER_ALARMS: &[&str] = &[
    "FONCT0_62",
    "MAILLAGE_ORPHAN_NODES",
    "MAILLAGE_COINCIDENT_NODES",
    "MAILLAGE_DEGENERATE_CELLS",
    "TABLE0_36",
    "TABLE0_21",
    "DYNAMIQUE_18",
];

/// Signature of every operator.
pub type OpFn = fn(&mut OpContext<'_>, &Args) -> Result<()>;

/// Run operator `f` in one store transaction: committed when it succeeds, rolled back
/// (the database left as it was) when it or the commit fails. The interpreter, the test
/// harness and the integration tests all run operators through this.
pub fn run_in_transaction(f: OpFn, ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    run_checked_in_transaction(f, ctx, args, &[])
}

/// [`run_in_transaction`], refusing first, in the same transaction, a concept of `used`
/// that something it was computed from no longer matches ([`Store::check_dependencies`]).
/// Inside the transaction the checks read under the lock the operator takes anyway; each
/// one outside would lock and unlock the file (and look for a journal) on its own.
pub fn run_checked_in_transaction(
    f: OpFn,
    ctx: &mut OpContext<'_>,
    args: &Args,
    used: &[String],
) -> Result<()> {
    ctx.store.begin_op()?;
    let outcome = used
        .iter()
        .try_for_each(|c| ctx.store.check_dependencies(c))
        .and_then(|()| f(ctx, args))
        .and_then(|()| ctx.store.commit_op());
    if outcome.is_err() {
        ctx.store.rollback_op();
    }
    outcome
}

/// Commands the interpreter runs itself (they open, continue and close the study): in the
/// catalog, not in [`OPERATORS`].
pub const INTERPRETER_COMMANDS: &[&str] = &["DEBUT", "POURSUITE", "FIN"];

/// Every operator with a `run`, one line each: `("NAME", module::run)`. A test checks that
/// these names and [`INTERPRETER_COMMANDS`] are exactly the catalog's operators.
pub const OPERATORS: &[(&str, OpFn)] = &[
    ("CALC_TABLE", calc_table::run),
    ("CREA_TABLE", crea_table::run),
    ("DEFI_FONCTION", defi_fonction::run),
    ("FORMULE", formule::run),
    ("CALC_FONC_INTERP", calc_fonc_interp::run),
    ("CALC_FONCTION", calc_fonction::run),
    ("DETRUIRE", detruire::run),
    ("EXTR_TABLE", extr_table::run),
    ("IMPR_FONCTION", impr_fonction::run),
    ("IMPR_TABLE", impr_table::run),
    ("IMPR_RESU", impr_resu::run),
    ("RECU_FONCTION", recu_fonction::run),
    ("TEST_FONCTION", test_fonction::run),
    ("TEST_TABLE", test_table::run),
    ("AFFE_MODELE", affe_modele::run),
    ("DEFI_MATERIAU", defi_materiau::run),
    ("AFFE_MATERIAU", affe_materiau::run),
    ("AFFE_CARA_ELEM", affe_cara_elem::run),
    ("AFFE_CHAR_CINE", affe_char_cine::run),
    ("AFFE_CHAR_MECA", affe_char_meca::run),
    ("CALC_MATR_ELEM", calc_matr_elem::run),
    ("NUME_DDL", nume_ddl::run),
    ("CALC_MODES", calc_modes::run),
    ("MODE_ITER_SIMULT", mode_iter_simult::run),
    ("CALC_STABILITE", calc_stabilite::run),
    ("MODE_NON_LINE", mode_non_line::run),
    ("REPONSE_FORCEE_NL", reponse_forcee_nl::run),
    ("REST_MODE_NONL", rest_mode_nonl::run),
    ("TEST_RESU", test_resu::run),
    ("ASSE_MATRICE", asse_matrice::run),
    ("ASSEMBLAGE", assemblage::run),
    ("LIRE_MAILLAGE", lire_maillage::run),
    ("CREA_MAILLAGE", crea_maillage::run),
    ("DEFI_GROUP", defi_group::run),
    ("MODI_MAILLAGE", modi_maillage::run),
    ("CREA_CHAMP", crea_champ::run),
    ("DEFI_OBSTACLE", defi_obstacle::run),
    ("NUME_DDL_GENE", nume_ddl_gene::run),
    ("PROJ_BASE", proj_base::run),
    ("PROJ_MATR_BASE", proj_matr_base::run),
    ("PROJ_VECT_BASE", proj_vect_base::run),
    ("DEFI_BASE_MODALE", defi_base_modale::run),
    ("NORM_MODE", norm_mode::run),
    ("DYNA_VIBRA", dyna_vibra::run),
    ("POST_DYNA_MODA_T", post_dyna_moda_t::run),
    ("REST_GENE_PHYS", rest_gene_phys::run),
    ("DEFI_LIST_REEL", defi_list_reel::run),
    ("DYNA_TRAN_MODAL", dyna_tran_modal::run),
    ("DYNA_LINE", dyna_line::run),
    ("CALC_VECT_ELEM", calc_vect_elem::run),
    ("ASSE_VECTEUR", asse_vecteur::run),
    ("MODE_STATIQUE", mode_statique::run),
    ("CALC_CHAR_SEISME", calc_char_seisme::run),
];

/// The operator that implements `name`, if we have one. Operators handled by the
/// interpreter itself ([`INTERPRETER_COMMANDS`]) are not listed here.
pub fn lookup(name: &str) -> Option<OpFn> {
    OPERATORS.iter().find(|(n, _)| *n == name).map(|(_, f)| *f)
}
