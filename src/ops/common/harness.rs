//! Test support: run operators on an in-memory store with hand-built `Args`. Every call
//! goes through the catalog's validation first ([`validated`]), as a user's call does, so
//! the operators see the defaults the catalog fills, never an `Args` without them.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::ops::{lookup, run_in_transaction, OpContext, TestOutcome, Units};
use crate::store::Store;
use crate::value::{ConceptRef, Span, Value};

pub struct Harness {
    pub store: Store,
    pub out: Vec<u8>,
    pub units: Units,
    pub tests: Vec<TestOutcome>,
}

impl Default for Harness {
    fn default() -> Self {
        Harness::new()
    }
}

impl Harness {
    pub fn new() -> Harness {
        Harness {
            store: Store::in_memory().expect("in-memory store"),
            out: Vec::new(),
            units: Units::default(),
            tests: Vec::new(),
        }
    }

    /// Run `op` inside a transaction as the interpreter does; returns the plain value the
    /// operator handed back, if any.
    pub fn run(
        &mut self,
        op: &str,
        result: Option<&str>,
        reuse: Option<&str>,
        args: &Args,
    ) -> Result<Option<Value>> {
        let f = lookup(op).ok_or_else(|| Error::internal(format!("no operator {op}")))?;
        let args = &validated(op, args, reuse)?;
        let mut ctx = OpContext::new(&self.store, op, &mut self.out, &self.units, &mut self.tests);
        ctx.result = result;
        ctx.reuse = reuse;
        ctx.file = "test.comm";
        ctx.line = 1;
        run_in_transaction(f, &mut ctx, args)?;
        Ok(ctx.value.take())
    }

    pub fn output(&self) -> String {
        String::from_utf8_lossy(&self.out).into_owned()
    }
}

/// The call `args` of `op` validated against the embedded catalog, as a user's call is
/// (see [`crate::catalog::validate_args`]).
pub fn validated(op: &str, args: &Args, reuse: Option<&str>) -> Result<Args> {
    crate::catalog::validate_args(op, args, reuse, "test.comm")
}

/// Build `Args` by hand: simple keywords and factor keywords.
pub fn args(path: &str, simple: Vec<(&str, Value)>, factor: Vec<(&str, Vec<Args>)>) -> Args {
    Args {
        path: path.to_string(),
        simple: simple
            .into_iter()
            .map(|(k, v)| (k.to_string(), v, Span::default()))
            .collect(),
        factor: factor
            .into_iter()
            .map(|(k, v)| (k.to_string(), v, Span::default()))
            .collect(),
    }
}

pub fn fact(path: &str, simple: Vec<(&str, Value)>) -> Args {
    args(path, simple, vec![])
}

pub fn k(s: &str) -> Value {
    Value::Str(s.to_string())
}
pub fn r(x: f64) -> Value {
    Value::Real(x)
}
pub fn i(x: i64) -> Value {
    Value::Int(x)
}
pub fn seq(v: Vec<Value>) -> Value {
    Value::Seq(v)
}
pub fn concept(name: &str, ty: &str) -> Value {
    Value::Concept(ConceptRef {
        name: name.to_string(),
        ty: ty.to_string(),
    })
}
pub fn table(name: &str) -> Value {
    concept(name, "table_sdaster")
}
