//! The `.comm` command language: the Python subset of Code_Aster command files.
//!
//! [`parse`] turns a [`Source`] into a [`Program`] (syntax errors carry file, line and
//! column); [`execute`] runs it, keeping Python variables in an [`Env`] and handing every
//! operator call to a [`Host`] as a [`CommandCall`]; [`render`] shows an error with its
//! source line and a caret.
//!
//! Supported subset: `NAME = OP(...)` and bare `OP(...)` statements, `;` separators,
//! `#` comments, continuation inside brackets and after `\\`; keyword arguments,
//! `reuse=`, `_F(...)`, `CO('N')`; ints, reals and strings in every Python form, tuples and
//! lists, `True`/`False`/`None`; `+ - * / // % **` with Python precedence and Python 3
//! semantics; variables, `+= -= *= /=`, tuple unpacking, indexing `L[i]` (negative too);
//! `for` loops with indented or inline bodies; `import math [as m]`,
//! `from math import *|names`; builtins abs float int round min max len range list tuple
//! sum str print enumerate zip; lone strings (docstrings). Anything else (def, class,
//! while, if, lambda, comparisons, methods, dictionaries, other modules) is an error
//! naming file, line and column. Evaluation is bounded ([`Limits`]) and never panics.
//!
//! Layout: `scan` (logical lines, indentation, lexical errors) -> `parser` (pest grammar
//! `grammar/comm.pest` -> `ast`) -> `blocks` (`for` bodies by indentation) -> `eval`
//! (with `arith` and `builtins`); `diag` renders errors.

mod arith;
pub mod ast;
mod blocks;
mod builtins;
pub mod diag;
pub mod encoding;
mod eval;
pub mod extent;
pub mod formula;
mod parser;
mod scan;

pub use ast::Program;
pub use diag::{render, render_plain, render_styled};

use crate::error::Result;
use crate::value::{CommandCall, ConceptRef, Value};
use std::collections::HashMap;

/// A command file: `name` is the path shown in messages.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Source {
    pub name: String,
    pub text: String,
}

impl Source {
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> Self {
        Source {
            name: name.into(),
            text: text.into(),
        }
    }

    /// The command file at `path`, decoded as [`encoding`] says (UTF-8, or Latin-1 when the
    /// file declares it or is not UTF-8), with the note to print when the encoding was
    /// guessed.
    pub fn read(path: &std::path::Path) -> Result<(Source, Option<String>)> {
        let name = path.display().to_string();
        // A regular file of bounded size, both checked before a byte is read (text_file.rs).
        let bytes = crate::text_file::read_bytes(path, "the command file")?;
        let decoded = encoding::decode(&bytes, &name)?;
        Ok((Source::new(name, decoded.text), decoded.note))
    }
}

/// Parses a command file (no evaluation).
pub fn parse(src: &Source) -> Result<Program> {
    parser::parse(src)
}

/// Runs a parsed file. Stops at the first error, which names the file, line and column.
pub fn execute(program: &Program, src: &Source, env: &mut Env, host: &mut dyn Host) -> Result<()> {
    eval::execute(program, src, env, host)
}

/// Parses and runs a command file.
pub fn run(src: &Source, env: &mut Env, host: &mut dyn Host) -> Result<()> {
    let program = parse(src)?;
    execute(&program, src, env, host)
}

/// Bounds on one execution, so that a runaway file stops with an error instead of hanging.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Most statements run (loop bodies count once per iteration).
    pub max_steps: u64,
    /// Most list items and text characters built by literals, `+`, `*` and builtins, over
    /// the whole run.
    pub max_work: u64,
    /// Most items one value may hold, counted at every level of nesting
    /// ([`extent::Extent`]): checked as the value is built, before it is kept.
    pub max_value_items: u64,
    /// Deepest nesting of lists (and `_F`) in one value.
    pub max_depth: usize,
    /// Most operator calls one run makes (each is a transaction, milliseconds at least).
    pub max_operator_calls: u64,
    /// A `for` loop whose iterations times the operator calls of its body exceed this is
    /// announced before it starts.
    pub warn_operator_calls: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_steps: 10_000_000,
            max_work: 50_000_000,
            max_value_items: 2_000_000,
            max_depth: 100,
            max_operator_calls: 100_000,
            warn_operator_calls: 10_000,
        }
    }
}

/// The Python names of a running file.
#[derive(Clone, Debug)]
pub struct Env {
    /// Execution bounds (defaults suit real studies).
    pub limits: Limits,
    /// Variables (numbers, texts, tuples, concepts...).
    pub(crate) vars: HashMap<String, Value>,
    /// Imported math functions: bound name -> math function name.
    pub(crate) funcs: HashMap<String, String>,
    /// Names bound to a module of scalar functions (`import math [as m]`,
    /// `import numpy as np`): bound name -> which module.
    pub(crate) modules: HashMap<String, ScalarModule>,
}

/// The modules a command file may import: Python's `math`, and `numpy` for the scalar
/// functions and constants Code_Aster's files take from it (`np.sqrt(2.)`, `np.pi`); its
/// arrays are not supported.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScalarModule {
    Math,
    Numpy,
}

impl ScalarModule {
    /// The module of an `import` statement, None for the modules whose import is accepted
    /// and ignored (`code_aster`).
    pub fn named(name: &str) -> Option<ScalarModule> {
        match name {
            "math" => Some(ScalarModule::Math),
            "numpy" => Some(ScalarModule::Numpy),
            _ => None,
        }
    }

    /// The module's name as written in an import.
    pub fn name(self) -> &'static str {
        match self {
            ScalarModule::Math => "math",
            ScalarModule::Numpy => "numpy",
        }
    }

    /// The math function that computes the module's function `name` on a number.
    pub fn function(self, name: &str) -> Option<&'static str> {
        match self {
            ScalarModule::Math => builtins::MATH_FUNCS.iter().copied().find(|f| *f == name),
            ScalarModule::Numpy => builtins::numpy_function(name),
        }
    }

    /// The module's constant `name`.
    pub fn constant(self, name: &str) -> Option<f64> {
        match self {
            ScalarModule::Math => builtins::math_const(name),
            ScalarModule::Numpy => builtins::numpy_const(name),
        }
    }
}

/// The math names a Code_Aster command file sees without importing them: its supervisor
/// evaluates command files where `sin, cos, tan, asin, acos, atan2, atan, sinh, cosh, tanh`
/// and `pi, exp, log, log10, sqrt` are already imported (its validation files, e.g.
/// sdnd100a, write `cos(pi / 4.)` with no import). Other math names need
/// `from math import ...`, as in Code_Aster.
pub const CODE_ASTER_MATH: &[&str] = &[
    "sin", "cos", "tan", "asin", "acos", "atan2", "atan", "sinh", "cosh", "tanh", "exp", "log",
    "log10", "sqrt",
];

impl Default for Env {
    /// A file's names at its start: Code_Aster's preloaded math names ([`CODE_ASTER_MATH`]
    /// and `pi`).
    fn default() -> Self {
        let mut env = Env {
            limits: Limits::default(),
            vars: HashMap::new(),
            funcs: HashMap::new(),
            modules: HashMap::new(),
        };
        for f in CODE_ASTER_MATH {
            env.import_fn(f, f);
        }
        env.vars
            .insert("pi".into(), Value::Real(std::f64::consts::PI));
        env
    }
}

impl Env {
    pub fn new() -> Self {
        Self::default()
    }

    /// Binds a variable (a later assignment of the same name replaces it, and hides an
    /// imported function or module of that name, as in Python).
    pub fn bind(&mut self, name: &str, value: Value) {
        self.funcs.remove(name);
        self.modules.remove(name);
        self.vars.insert(name.to_string(), value);
    }

    pub fn get(&self, name: &str) -> Option<&Value> {
        self.vars.get(name)
    }

    /// Variable names, sorted.
    pub fn names(&self) -> Vec<String> {
        let mut v: Vec<String> = self.vars.keys().cloned().collect();
        v.sort();
        v
    }

    pub(crate) fn import_fn(&mut self, bound: &str, math_name: &str) {
        self.vars.remove(bound);
        self.modules.remove(bound);
        self.funcs.insert(bound.to_string(), math_name.to_string());
    }
}

/// What the language needs from the interpreter.
pub trait Host {
    /// Is `name` an operator (from the catalogs)? Calls to non-operators that are not
    /// builtins are errors.
    fn is_operator(&self, name: &str) -> bool;

    /// Runs (or just validates) one operator call; returns the value to bind to the
    /// result name (usually `Value::Concept`). An `Err` stops execution and [`execute`]
    /// returns it (located at the call when it has no location yet).
    fn call(&mut self, call: CommandCall) -> Result<Value>;

    /// All operator names, for "did you mean" hints.
    fn operator_names(&self) -> Vec<String> {
        Vec::new()
    }

    /// For a Code_Aster operator the host does not implement: what to do instead.
    fn unsupported_operator(&self, _name: &str) -> Option<String> {
        None
    }

    /// The concept named `name` if it exists: after a call, every `CO('NAME')` of its
    /// keywords that the host reports here becomes a Python name, and a name no statement
    /// bound is looked up here (concepts of an earlier run continued by POURSUITE).
    fn lookup_concept(&self, _name: &str) -> Option<ConceptRef> {
        None
    }

    /// The contents of the table concept `table` (`T.EXTR_TABLE()`, `T['PARA', i]`):
    /// `Value::Table`, or `Value::Unknown` when nothing runs (`aster-nl check`).
    fn table_contents(&mut self, table: &ConceptRef) -> Result<Value> {
        Err(crate::error::Error::input(format!(
            "the contents of table {} are not available here",
            table.name
        )))
    }

    /// An error met while evaluating the file: `true` when the host has recorded it and
    /// evaluation goes on with what failed taken as unknown ([`crate::value::Value::Unknown`]:
    /// an undefined name, the result of an unsupported operator, the targets of a failed
    /// statement), so that `aster-nl check` reports every error of a file in one pass;
    /// `false` (a run) stops execution with it.
    fn recover(&mut self, _error: &crate::error::Error) -> bool {
        false
    }

    /// An alarm of the language itself (`id`, e.g. `RESSOURCES_2`: a loop of many operator
    /// calls), before the statement it is about runs.
    fn warn(&mut self, id: &str, text: &str) {
        eprintln!("<A> <{id}> {text}");
    }

    /// Output of `print(...)` in the command file.
    fn print(&mut self, text: &str) {
        println!("{text}");
    }

    /// The value at `x` of the function concept `function` (`F(x)` in the command file):
    /// `Value::Real`, or `Value::Unknown` when nothing runs (`aster-nl check`).
    fn function_value(&mut self, function: &ConceptRef, _x: f64) -> Result<Value> {
        Err(crate::error::Error::input(format!(
            "the values of function {} are not available here",
            function.name
        )))
    }

    /// A file a command names by its path (`MA.readAsterMeshFile("x.mail")` of Code_Aster's
    /// Python API): the logical unit the host has mapped it to, for the operator that
    /// reads it.
    fn map_file(&mut self, path: &str) -> Result<i64> {
        Err(crate::error::Error::input(format!(
            "reading the file '{path}' by its name is not available here"
        )))
    }

    /// A method of Code_Aster's Python API on the DYNA_VIBRA result `result`
    /// (`R.VARI_INTERNE(1)`): its value (a list, a list of rows), or `Value::Unknown` when
    /// nothing runs (`aster-nl check`).
    fn result_method(
        &mut self,
        result: &ConceptRef,
        _method: crate::value::ResultMethod,
    ) -> Result<Value> {
        Err(crate::error::Error::input(format!(
            "the contents of {} are not available here",
            result.name
        )))
    }

    /// Writes `text` to the file `path` a command file names (`np.savetxt("x.csv", ...)`),
    /// replacing it, as numpy does; nothing when nothing runs (`aster-nl check`).
    fn save_text(&mut self, path: &str, _text: &str) -> Result<()> {
        Err(crate::error::Error::input(format!(
            "writing the file '{path}' is not available here"
        )))
    }

    /// One assertion of a `code_aster.TestCase()` (`test.assertTrue(...)`): a test, OK or
    /// NOOK, with its printed line.
    fn record_test(&mut self, ok: bool, line: &str) {
        println!("{line}");
        let _ = ok;
    }
}

#[cfg(test)]
mod tests;
