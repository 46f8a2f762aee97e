//! Executes a [`Program`]: Python variables, arithmetic, `math`, `for` loops; every
//! operator call becomes a [`CommandCall`] handed to the [`Host`].

use super::arith;
use super::ast::*;
use super::builtins::{self, BUILTINS, MATH_FUNCS};
use super::diag::{did_you_mean, suggestions};
use super::extent::{extent, Extent};
use super::{Env, Host, ScalarModule, Source};
use crate::error::{Error, Result};
use crate::value::{CommandCall, ConceptRef, Keyword, Span, Value};

mod python_api;
mod result_api;
mod savetxt;

const IMPORT_HINT: &str = "add `from math import *` at the top of the file";

pub fn execute(program: &Program, src: &Source, env: &mut Env, host: &mut dyn Host) -> Result<()> {
    let mut ev = Evaluator {
        file: &src.name,
        env,
        host,
        steps: 0,
        work: 0,
        stopped: false,
        operator_calls: 0,
    };
    ev.block(&program.stmts)
}

/// What a formula's evaluation may call on: nothing (no operator, no concept).
struct NoHost;

impl Host for NoHost {
    fn is_operator(&self, _name: &str) -> bool {
        false
    }
    fn call(&mut self, call: CommandCall) -> Result<Value> {
        Err(Error::internal(format!(
            "operator {} called while evaluating a formula",
            call.op
        )))
    }
    fn print(&mut self, _text: &str) {}
    fn warn(&mut self, _id: &str, _text: &str) {}
}

/// Evaluates one expression with the names of `env` alone (a formula's scope: its
/// parameters, its constants and the math functions), as a command file would: same
/// arithmetic, same math, same errors; no operator can be called.
pub(super) fn evaluate(expr: &Expr, env: &mut Env) -> Result<Value> {
    let mut host = NoHost;
    let mut ev = Evaluator {
        file: "",
        env,
        host: &mut host,
        steps: 0,
        work: 0,
        stopped: false,
        operator_calls: 0,
    };
    ev.eval(expr)
}

struct Evaluator<'a> {
    file: &'a str,
    env: &'a mut Env,
    host: &'a mut dyn Host,
    steps: u64,
    work: u64,
    /// A limit on statements or work was passed: no error is recovered any more, or a
    /// runaway loop would report one error per statement.
    stopped: bool,
    operator_calls: u64,
}

/// Positional values (with their spans) and keywords of a call.
type EvaluatedArgs = (Vec<(Value, Span)>, Vec<Keyword>);

/// Where a call stands: operators may only be called by a statement.
#[derive(Clone, Copy)]
enum Site<'n> {
    /// Inside an expression.
    Nested,
    /// A call statement (its span).
    Statement(Span),
    /// The whole right-hand side of `NAME = ...` (target, statement span).
    Assign(&'n Name, Span),
}

/// Concept types whose contents `EXTR_TABLE()` and `T['PARA', i]` read.
/// `?` is a concept `aster-nl check` could not type (its contents are unknown anyway).
fn is_table_type(ty: &str) -> bool {
    ty.starts_with("table") || ty == crate::catalog::UNKNOWN_CONCEPT_TYPE
}

/// Concept types a command file may call like a Python function: `F(x)`.
fn is_function_type(ty: &str) -> bool {
    ty.starts_with("fonction") || ty == "formule"
}

fn is_upper_name(n: &str) -> bool {
    n.chars().next().is_some_and(|c| c.is_ascii_uppercase())
        && n.chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
}

impl Evaluator<'_> {
    fn syntax(&self, msg: impl Into<String>, span: Span) -> Error {
        Error::syntax(msg).at(self.file, span)
    }
    fn input(&self, msg: impl Into<String>, span: Span) -> Error {
        Error::input(msg).at(self.file, span)
    }

    /// Refuses a value that would exceed the bounds on one value ([`super::Limits`]):
    /// called with the extent of what is about to be built, before building it.
    fn check_extent(&self, e: Extent, span: Span) -> Result<()> {
        let limits = &self.env.limits;
        if e.depth > limits.max_depth {
            return Err(self
                .input(
                    format!(
                        "this value would be nested {} levels deep, more than the {} a value may have",
                        e.depth, limits.max_depth
                    ),
                    span,
                )
                .hint("a loop probably puts a list inside itself (a = [a])"));
        }
        if e.items > limits.max_value_items {
            return Err(self
                .input(
                    format!(
                        "this value would have {} items (counting those of nested lists and \
                         the characters of texts), more than the {} a value may have",
                        e.items, limits.max_value_items
                    ),
                    span,
                )
                .hint("a loop probably doubles a list (x = (x, x)) or repeats a long one"));
        }
        Ok(())
    }

    /// Checks a value just built against the bounds on one value and counts its items
    /// against `Limits::max_work`, the items built over the whole run.
    fn charge(&mut self, v: Value, span: Span) -> Result<Value> {
        let e = extent(&v);
        self.check_extent(e, span)?;
        self.add_work(e.items, span)?;
        Ok(v)
    }

    /// Counts `items` built or copied; errors past `Limits::max_work`.
    fn add_work(&mut self, items: u64, span: Span) -> Result<()> {
        self.work = self.work.saturating_add(items);
        let max_work = self.env.limits.max_work;
        if self.work > max_work {
            self.stopped = true;
            return Err(self
                .input(
                    format!("more than {max_work} list items or characters built or copied"),
                    span,
                )
                .hint("a loop probably builds very long lists, or reads a long one many times"));
        }
        Ok(())
    }

    /// `x op y`, refused before it is computed when its result would be too big.
    fn binary(&mut self, op: BinOp, x: &Value, y: &Value, span: Span) -> Result<Value> {
        let count = |v: &Value| match v {
            Value::Int(n) => Some(u64::try_from(*n).unwrap_or(0)),
            Value::Bool(b) => Some(u64::from(*b)),
            _ => None,
        };
        let sized = |v: &Value| matches!(v, Value::Seq(_) | Value::Str(_));
        let result = match op {
            BinOp::Add if sized(x) && sized(y) => Some(extent(x).joined(extent(y))),
            BinOp::Mul if sized(x) => count(y).map(|n| extent(x).repeated(n)),
            BinOp::Mul if sized(y) => count(x).map(|n| extent(y).repeated(n)),
            _ => None,
        };
        if let Some(e) = result {
            self.check_extent(e, span)?;
        }
        let v = arith::binary(op, x, y).map_err(|m| self.input(m, span))?;
        self.charge(v, span)
    }

    fn block(&mut self, stmts: &[Stmt]) -> Result<()> {
        for s in stmts {
            if let Err(e) = self.stmt(s) {
                let e = e.at(self.file, s.span);
                if self.stopped || !self.host.recover(&e) {
                    return Err(e);
                }
                // Recorded by the host (`check`): what the statement would have bound is
                // unknown, and the next statement is checked.
                self.unknown_targets(s);
            }
        }
        Ok(())
    }

    /// `Ok(Value::Unknown)` when the host records `e` and goes on (`check`), else `Err(e)`.
    fn recovered(&mut self, e: Error) -> Result<Value> {
        if self.stopped || !self.host.recover(&e) {
            return Err(e);
        }
        Ok(Value::Unknown)
    }

    /// A call that cannot be made (an unsupported or unknown operator, an undefined
    /// function): when the host goes on, its arguments are still evaluated for their own
    /// errors and its result is unknown.
    fn unknown_call(&mut self, e: Error, args: &[Arg]) -> Result<Value> {
        let v = self.recovered(e)?;
        self.args(args)?;
        Ok(v)
    }

    /// Binds the names a failed statement would have bound to `Value::Unknown`.
    fn unknown_targets(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Assign { target, .. } | StmtKind::For { var: target, .. } => {
                let _ = self.bind_target(target, Value::Unknown, s.span);
            }
            StmtKind::AugAssign { target, .. } => self.env.bind(&target.text, Value::Unknown),
            _ => {}
        }
    }

    fn stmt(&mut self, s: &Stmt) -> Result<()> {
        self.steps += 1;
        let max_steps = self.env.limits.max_steps;
        if self.steps > max_steps {
            self.stopped = true;
            return Err(self
                .input(format!("more than {max_steps} statements executed"), s.span)
                .hint("a loop is probably far too long"));
        }
        match &s.kind {
            StmtKind::Assign { target, value } => {
                let v = match (&value.kind, target) {
                    (ExprKind::Call { func, args }, Target::Name(t)) => {
                        self.call(func, args, value.span, Site::Assign(t, s.span))?
                    }
                    _ => self.eval(value)?,
                };
                self.bind_target(target, v, value.span)?;
            }
            StmtKind::AugAssign { target, op, value } => {
                let cur = self.name_value(&target.text, target.span)?;
                let rhs = self.eval(value)?;
                let v = self.binary(*op, &cur, &rhs, s.span)?;
                self.env.bind(&target.text, v);
            }
            StmtKind::Call(e) => {
                if let ExprKind::Call { func, args } = &e.kind {
                    self.call(func, args, e.span, Site::Statement(s.span))?;
                }
            }
            StmtKind::For { var, iter, body } => {
                let items = match self.eval(iter)? {
                    Value::Seq(items) => items,
                    Value::Str(t) => t.chars().map(|c| Value::Str(c.to_string())).collect(),
                    // Known only when the file runs (`check`): check the body once.
                    Value::Unknown => vec![Value::Unknown],
                    v => {
                        return Err(self.input(
                            format!(
                                "'for' needs a list, a tuple or a range, got {}",
                                v.kind_name()
                            ),
                            iter.span,
                        ))
                    }
                };
                self.announce_loop(items.len(), body, s.span)?;
                for item in items {
                    self.bind_target(var, item, iter.span)?;
                    self.block(body)?;
                }
            }
            StmtKind::ImportFrom { module, names } => self.import_from(module, names.as_deref())?,
            StmtKind::Import { module, alias } => {
                if let Some(m) = ScalarModule::named(&module.text) {
                    self.env.vars.remove(&alias.text);
                    self.env.funcs.remove(&alias.text);
                    self.env.modules.insert(alias.text.clone(), m);
                }
            }
        }
        Ok(())
    }

    /// Before a `for` loop of `iterations` starts: the operator calls its body makes at the
    /// least (a nested loop's body counted once) times its iterations are refused when
    /// they exceed what the run may still make (`Limits::max_operator_calls`), and
    /// announced when they exceed `Limits::warn_operator_calls`: each call is a
    /// transaction, so such a loop runs for minutes or hours.
    fn announce_loop(&mut self, iterations: usize, body: &[Stmt], span: Span) -> Result<()> {
        let per_iteration = self.operator_calls_in(body);
        if per_iteration == 0 {
            return Ok(());
        }
        let calls = (iterations as u64).saturating_mul(per_iteration);
        let limits = self.env.limits;
        let left = limits
            .max_operator_calls
            .saturating_sub(self.operator_calls);
        if calls > left {
            return Err(self
                .input(
                    format!(
                        "this loop would make at least {calls} operator calls ({iterations} \
                         iterations of {per_iteration}), more than the {} a run may make",
                        limits.max_operator_calls
                    ),
                    span,
                )
                .hint("each operator call is a transaction of the study: loop over fewer values"));
        }
        if calls > limits.warn_operator_calls {
            self.host.warn(
                "RESSOURCES_2",
                &format!(
                    "{}:{}: this loop makes at least {calls} operator calls ({iterations} \
                     iterations of {per_iteration}): expect a long run",
                    self.file, span.line
                ),
            );
        }
        Ok(())
    }

    /// Operator calls written in `body` (a nested loop's body counted once: a lower bound).
    fn operator_calls_in(&self, body: &[Stmt]) -> u64 {
        body.iter()
            .map(|s| match &s.kind {
                StmtKind::Call(e) | StmtKind::Assign { value: e, .. } => match &e.kind {
                    ExprKind::Call { func, .. } => match &func.kind {
                        ExprKind::Name(n) if self.host.is_operator(n) => 1,
                        _ => 0,
                    },
                    _ => 0,
                },
                StmtKind::For { body, .. } => self.operator_calls_in(body),
                _ => 0,
            })
            .sum()
    }

    /// Binds a name, or unpacks `value` (built at `span`) into a tuple of names.
    fn bind_target(&mut self, target: &Target, value: Value, span: Span) -> Result<()> {
        match target {
            Target::Name(n) => self.env.bind(&n.text, value),
            Target::Tuple(names, tspan) => {
                let items = match value {
                    Value::Seq(items) if items.len() == names.len() => items,
                    Value::Unknown => vec![Value::Unknown; names.len()],
                    Value::Seq(items) => {
                        return Err(self.input(
                            format!(
                                "cannot unpack {} values into {} names",
                                items.len(),
                                names.len()
                            ),
                            span,
                        ))
                    }
                    v => {
                        let msg =
                            format!("cannot unpack {} into {} names", v.kind_name(), names.len());
                        return Err(self.input(msg, *tspan));
                    }
                };
                for (n, v) in names.iter().zip(items) {
                    self.env.bind(&n.text, v);
                }
            }
        }
        Ok(())
    }

    fn import_from(&mut self, module: &Name, names: Option<&[(Name, Name)]>) -> Result<()> {
        let Some(m) = ScalarModule::named(&module.text) else {
            return Ok(()); // code_aster imports: every operator is already available
        };
        match names {
            None => {
                // `from numpy import *` binds the names numpy shares with math (sqrt,
                // sin, ...), not numpy's own aliases (arcsin, power): give those by name.
                for f in MATH_FUNCS {
                    self.env.import_fn(f, f);
                }
                for c in ["pi", "e", "tau"] {
                    if let Some(x) = m.constant(c).or_else(|| builtins::math_const(c)) {
                        self.env.bind(c, Value::Real(x));
                    }
                }
            }
            Some(list) => {
                for (n, bound) in list {
                    if let Some(x) = m.constant(&n.text) {
                        self.env.bind(&bound.text, Value::Real(x));
                    } else if let Some(f) = m.function(&n.text) {
                        self.env.import_fn(&bound.text, f);
                    } else {
                        return Err(self.input(
                            format!("cannot import '{}' from '{}'", n.text, m.name()),
                            n.span,
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    /// The value of a bare name. Each use copies the value: a list's copy counts against
    /// `Limits::max_work` like a list built, so that a long loop reading a long list ends.
    fn name_value(&mut self, n: &str, span: Span) -> Result<Value> {
        if let Some(v) = self.env.vars.get(n) {
            let v = v.clone();
            if matches!(v, Value::Seq(_) | Value::Fact(_) | Value::Table(_)) {
                self.add_work(extent(&v).items, span)?;
            }
            return Ok(v);
        }
        if self.env.funcs.contains_key(n) || BUILTINS.contains(&n) {
            return Err(self.syntax(format!("'{n}' is a function: call it, e.g. {n}(...)"), span));
        }
        if self.env.modules.contains_key(n) {
            return Err(self.syntax(format!("module '{n}' cannot be used as a value"), span));
        }
        // A concept of the study that no statement of this file bound: one created by an
        // earlier run (POURSUITE).
        if let Some(c) = self.host.lookup_concept(n) {
            return Ok(Value::Concept(c));
        }
        let mut err = self.input(format!("name '{n}' is not defined"), span);
        if builtins::math_const(n).is_some() {
            err = err.hint(IMPORT_HINT);
        } else if self.host.is_operator(n) {
            err = err.hint(format!("'{n}' is an operator: call it, e.g. X = {n}(...)"));
        } else {
            let vars: Vec<String> = self.env.vars.keys().cloned().collect();
            if let Some(h) = did_you_mean(&suggestions(n, &vars)) {
                err = err.hint(h);
            }
        }
        self.recovered(err)
    }

    fn eval(&mut self, e: &Expr) -> Result<Value> {
        match &e.kind {
            ExprKind::Int(i) => Ok(Value::Int(*i)),
            ExprKind::Real(r) => Ok(Value::Real(*r)),
            ExprKind::Str(s) => Ok(Value::Str(s.clone())),
            ExprKind::Bool(b) => Ok(Value::Bool(*b)),
            ExprKind::None => Ok(Value::None),
            ExprKind::Name(n) => self.name_value(n, e.span),
            ExprKind::Tuple(items) | ExprKind::List(items) => {
                // Bounded item by item: `(x, x)` stops before the second copy is made.
                let mut out = Vec::with_capacity(items.len());
                let mut size = Extent::list_of([]);
                for i in items {
                    let v = self.eval(i)?;
                    size.push(extent(&v));
                    self.check_extent(size, e.span)?;
                    out.push(v);
                }
                self.charge(Value::Seq(out), e.span)
            }
            ExprKind::Unary(op, x) => {
                let v = self.eval(x)?;
                arith::unary(*op, &v).map_err(|m| self.input(m, e.span))
            }
            ExprKind::Binary(op, a, b) => {
                let x = self.eval(a)?;
                let y = self.eval(b)?;
                self.binary(*op, &x, &y, e.span)
            }
            ExprKind::Call { func, args } => self.call(func, args, e.span, Site::Nested),
            ExprKind::Index(base, idx) => {
                let b = self.eval(base)?;
                let i = self.eval(idx)?;
                if let Value::Concept(c) = &b {
                    if is_table_type(&c.ty) {
                        return self.table_cell(c, &i, e.span);
                    }
                }
                index(&b, &i).map_err(|m| self.input(m, e.span))
            }
            ExprKind::Attr(base, attr) => {
                let module = match &base.kind {
                    ExprKind::Name(m) => self.module_named(m).map(|module| (m, module)),
                    _ => None,
                };
                if let Some((m, module)) = module {
                    return match module.constant(&attr.text) {
                        Some(x) => Ok(Value::Real(x)),
                        None if module.function(&attr.text).is_some() => Err(self.syntax(
                            format!("'{m}.{}' is a function: call it", attr.text),
                            e.span,
                        )),
                        None => Err(self.unsupported_attribute(module, attr, "attribute")),
                    };
                }
                match self.eval(base)? {
                    Value::Table(t) => t.column(&attr.text).map(Value::Seq).ok_or_else(|| {
                        self.input(
                            format!("table {} has no column '{}'", t.name, attr.text),
                            attr.span,
                        )
                        .hint(format!("its columns: {}", t.columns.join(", ")))
                    }),
                    Value::Unknown => Ok(Value::Unknown),
                    _ => Err(self.syntax("attributes (x.name) are not supported", attr.span)),
                }
            }
        }
    }

    /// The module a name is bound to, unless a variable of that name hides it.
    fn module_named(&self, name: &str) -> Option<ScalarModule> {
        if self.env.vars.contains_key(name) {
            return None;
        }
        self.env.modules.get(name).copied()
    }

    /// `m.attr` where the module has no such function or constant (`what`: "function"
    /// when it is called, else "attribute").
    fn unsupported_attribute(&self, module: ScalarModule, attr: &Name, what: &str) -> Error {
        match module {
            ScalarModule::Math => self.input(
                format!("module 'math' has no {what} '{}'", attr.text),
                attr.span,
            ),
            ScalarModule::Numpy => self
                .input(
                    format!(
                        "numpy.{} is not supported: aster-nl offers numpy's scalar functions \
                         and constants (sqrt, sin, arctan2, power, pi, ...) and savetxt, not \
                         its arrays",
                        attr.text
                    ),
                    attr.span,
                )
                .hint("compute with numbers, lists and the operators' tables instead"),
        }
    }

    /// Evaluates call arguments: positional values and keywords (duplicates refused).
    fn args(&mut self, args: &[Arg]) -> Result<EvaluatedArgs> {
        let mut pos = Vec::new();
        let mut kws: Vec<Keyword> = Vec::new();
        for a in args {
            // Errors inside a keyword's value name it, with the path through factor
            // keywords as Code_Aster writes it: CHOC/JEU.
            let v = self.eval(&a.value).map_err(|mut e| {
                if let Some(n) = &a.name {
                    e.keyword = Some(match e.keyword.take() {
                        Some(inner) => format!("{}/{inner}", n.text),
                        None => n.text.clone(),
                    });
                }
                e
            })?;
            match &a.name {
                None => pos.push((v, a.span)),
                Some(n) => {
                    if kws.iter().any(|k| k.name == n.text) {
                        return Err(self
                            .input(format!("keyword '{}' is given twice", n.text), a.span)
                            .keyword(n.text.clone()));
                    }
                    kws.push(Keyword {
                        name: n.text.clone(),
                        value: v,
                        span: a.span,
                    });
                }
            }
        }
        Ok((pos, kws))
    }

    /// A call; `span` is the span of the call expression, `site` where it stands.
    fn call(&mut self, func: &Expr, args: &[Arg], span: Span, site: Site) -> Result<Value> {
        let name = match &func.kind {
            ExprKind::Name(n) => n.as_str(),
            ExprKind::Attr(base, attr) => return self.method_call(base, attr, args, span),
            _ => return Err(self.syntax("only functions and operators can be called", func.span)),
        };
        match name {
            "_F" => {
                let (pos, kws) = self.args(args)?;
                if let Some((_, s)) = pos.first() {
                    return Err(self.syntax("_F(...) takes only keywords KEY=value", *s));
                }
                return self.charge(Value::Fact(kws), span);
            }
            "CO" => {
                let (pos, kws) = self.args(args)?;
                return match (pos.as_slice(), kws.is_empty()) {
                    ([(Value::Str(s), _)], true) => Ok(Value::Co(s.clone())),
                    _ => Err(self.input("CO() takes one text: CO('NAME')", span)),
                };
            }
            _ => {}
        }
        if let Some(v) = self.env.vars.get(name) {
            // F(x) on a function concept (fonction_sdaster) or a formula (formule), as
            // Code_Aster's Python allows.
            if let Value::Concept(c) = v {
                if is_function_type(&c.ty) {
                    let c = c.clone();
                    return self.function_call(&c, args, span);
                }
            }
            return Err(self.input(
                format!("'{name}' is {}, not a function", v.kind_name()),
                func.span,
            ));
        }
        if let Some(target) = self.env.funcs.get(name).cloned() {
            let vals = self.positional(name, args)?;
            return builtins::call_math(&target, &vals).map_err(|m| self.input(m, span));
        }
        if name == "print" {
            let vals = self.positional(name, args)?;
            let text: Vec<String> = vals.iter().map(builtins::to_text).collect();
            self.host.print(&text.join(" "));
            return Ok(Value::None);
        }
        if BUILTINS.contains(&name) {
            let vals = self.positional(name, args)?;
            let v = builtins::call_builtin(name, &vals).map_err(|m| self.input(m, span))?;
            return self.charge(v, span);
        }
        if MATH_FUNCS.contains(&name) {
            return Err(self
                .input(format!("name '{name}' is not defined"), func.span)
                .hint(IMPORT_HINT));
        }
        if self.host.is_operator(name) {
            return self.operator(name, func.span, args, site);
        }
        if let Some(instead) = self.host.unsupported_operator(name) {
            let err = self
                .input(
                    format!("{name} is a Code_Aster operator that aster-nl does not support"),
                    func.span,
                )
                .hint(instead);
            return self.unknown_call(err, args);
        }
        // A function of the study that no statement of this file bound (POURSUITE).
        if let Some(c) = self.host.lookup_concept(name) {
            if is_function_type(&c.ty) {
                return self.function_call(&c, args, span);
            }
        }
        if is_upper_name(name) {
            let mut err = self.input(format!("unknown operator '{name}'"), func.span);
            if let Some(h) = did_you_mean(&suggestions(name, &self.host.operator_names())) {
                err = err.hint(h);
            }
            return self.unknown_call(err, args);
        }
        let err = self
            .input(format!("name '{name}' is not defined"), func.span)
            .hint(
                "functions available: the operators, math functions after `from math import *`, \
             and abs float int min max len range list tuple sum str round print",
            );
        self.unknown_call(err, args)
    }

    /// `F(x)` on the function or formula concept `c`: its value at the number x.
    fn function_call(&mut self, c: &ConceptRef, args: &[Arg], span: Span) -> Result<Value> {
        let vals = self.positional(&c.name, args)?;
        match vals.as_slice() {
            [Value::Unknown] => Ok(Value::Unknown),
            [x] if x.as_f64().is_some() => self
                .host
                .function_value(c, x.as_f64().unwrap_or_default())
                .map_err(|e| e.at(self.file, span)),
            _ => Err(self.input(
                format!("{}(x) takes one number, the abscissa", c.name),
                span,
            )),
        }
    }

    /// Evaluates the arguments of a Python function: positional only.
    fn positional(&mut self, f: &str, args: &[Arg]) -> Result<Vec<Value>> {
        let (pos, kws) = self.args(args)?;
        if let Some(k) = kws.first() {
            return Err(self.syntax(format!("{f}() does not take keyword arguments"), k.span));
        }
        Ok(pos.into_iter().map(|(v, _)| v).collect())
    }

    /// `math.sqrt(x)`; any other `x.method(...)` is outside the subset.
    fn method_call(&mut self, base: &Expr, attr: &Name, args: &[Arg], span: Span) -> Result<Value> {
        if let ExprKind::Name(m) = &base.kind {
            if let Some(module) = self.module_named(m) {
                if module == ScalarModule::Numpy && attr.text == "savetxt" {
                    return self.numpy_savetxt(args, span);
                }
                let Some(f) = module.function(&attr.text) else {
                    return Err(self.unsupported_attribute(module, attr, "function"));
                };
                let vals = self.positional(&attr.text, args)?;
                return builtins::call_math(f, &vals).map_err(|m| self.input(m, span));
            }
            if let Some(Value::Api(obj)) = self.env.vars.get(m).cloned() {
                return self.api_method(m, obj, attr, args, span);
            }
            if !self.env.vars.contains_key(m) && self.host.lookup_concept(m).is_none() {
                if m == "code_aster" {
                    if let Some(v) = self.code_aster_call(attr, args, span)? {
                        return Ok(v);
                    }
                    return Err(self
                        .input(
                            format!(
                                "code_aster.{}(): this part of the Python API of Code_Aster is not \
                                 supported (only code_aster.init(), code_aster.close(), \
                                 code_aster.Mesh() with its read...File methods and \
                                 code_aster.TestCase() with its assertions)",
                                attr.text
                            ),
                            span,
                        )
                        .hint(
                            "write that part as commands: DEBUT(), LIRE_MAILLAGE(...), TEST_*(...), \
                             FIN()",
                        ));
                }
                let mut err = self.input(format!("name '{m}' is not defined"), base.span);
                if m == "math" {
                    err = err.hint("add `import math` at the top of the file");
                }
                return self.unknown_call(err, args);
            }
        }
        if attr.text == "EXTR_TABLE" {
            let table = self.eval(base)?;
            if matches!(table, Value::Unknown) {
                // `check`: a table that only a run creates (or a name already reported).
                return Ok(Value::Unknown);
            }
            if let Value::Concept(c) = table {
                if is_table_type(&c.ty) {
                    let (pos, kws) = self.args(args)?;
                    if let Some(s) = pos.first().map(|p| p.1).or(kws.first().map(|k| k.span)) {
                        return Err(self.syntax("EXTR_TABLE() takes no argument", s));
                    }
                    return self
                        .host
                        .table_contents(&c)
                        .map_err(|e| e.at(self.file, span));
                }
                return Err(self.input(
                    format!(
                        "{} is a {}: EXTR_TABLE() is a method of tables",
                        c.name, c.ty
                    ),
                    base.span,
                ));
            }
        }
        if let Value::Concept(c) = self.eval(base)? {
            if result_api::has_result_methods(&c.ty) {
                if let Some(v) = self.result_method(&c, attr, args, span)? {
                    return Ok(v);
                }
                if c.ty == "tran_gene" {
                    return Err(self
                        .input(
                            format!(
                                "{}.{}(): this method of a DYNA_VIBRA result is not supported",
                                c.name, attr.text
                            ),
                            attr.span,
                        )
                        .hint(format!("supported: {}", result_api::METHODS)));
                }
            }
        }
        Err(self
            .syntax(
                format!("calling methods (.{}(...)) is not supported", attr.text),
                attr.span,
            )
            .hint(format!(
                "only operators, math functions, a few builtins, T.EXTR_TABLE() on a table \
                 and {} on a DYNA_VIBRA result can be called",
                result_api::METHODS
            )))
    }

    /// `T['PARA', i]` on a table concept: the cell of column PARA in row i, counted from 1
    /// as Code_Aster's tables do.
    fn table_cell(&mut self, table: &ConceptRef, key: &Value, span: Span) -> Result<Value> {
        let (para, row) = match key {
            Value::Seq(k) => match k.as_slice() {
                [Value::Str(p), Value::Int(i)] => (p.clone(), *i),
                _ => (String::new(), 0),
            },
            _ => (String::new(), 0),
        };
        if para.is_empty() {
            return Err(self
                .input(
                    format!(
                        "a table is indexed by ('PARA', row), got {}",
                        key.kind_name()
                    ),
                    span,
                )
                .hint(format!(
                    "write {}['FREQUENCE', 1] (rows count from 1)",
                    table.name
                )));
        }
        let t = match self
            .host
            .table_contents(table)
            .map_err(|e| e.at(self.file, span))?
        {
            Value::Table(t) => t,
            other => return Ok(other),
        };
        let col = t.column(&para).ok_or_else(|| {
            self.input(format!("table {} has no column '{para}'", t.name), span)
                .hint(format!("its columns: {}", t.columns.join(", ")))
        })?;
        usize::try_from(row)
            .ok()
            .and_then(|r| r.checked_sub(1))
            .and_then(|r| col.get(r).cloned())
            .ok_or_else(|| {
                self.input(
                    format!(
                        "table {} has no row {row}: rows count from 1 to {}",
                        t.name,
                        col.len()
                    ),
                    span,
                )
            })
    }

    fn operator(&mut self, op: &str, op_span: Span, args: &[Arg], site: Site) -> Result<Value> {
        let (target, stmt_span) = match site {
            Site::Assign(t, s) => (Some(t.text.clone()), s),
            Site::Statement(s) => (None, s),
            Site::Nested => {
                return Err(self
                    .syntax(
                        format!("operator '{op}' must be called in a statement of its own"),
                        op_span,
                    )
                    .hint(format!("write X = {op}(...) on its own line, then use X")))
            }
        };
        self.operator_calls += 1;
        let max_calls = self.env.limits.max_operator_calls;
        if self.operator_calls > max_calls {
            return Err(self
                .input(format!("more than {max_calls} operator calls"), op_span)
                .hint("a loop probably calls operators far too many times"));
        }
        let (pos, mut kws) = self.args(args)?;
        if let Some((_, s)) = pos.first() {
            return Err(self
                .syntax(format!("arguments of operator '{op}' must be keywords"), *s)
                .hint("write KEY=value"));
        }
        if op == "FORMULE" {
            // Its other keywords and the file's variables it uses become its CONTEXTE.
            kws = super::formula::formule_keywords(kws, self.env, self.file)?;
        }
        let mut reuse = None;
        if let Some(i) = kws.iter().position(|k| k.name == "reuse") {
            let k = kws.remove(i);
            match k.value {
                Value::Concept(c) => reuse = Some(c),
                // `check`: a concept already reported unknown; the call is still checked.
                Value::Unknown => {}
                v => {
                    return Err(self
                        .input(
                            format!("reuse= must name a concept, got {}", v.kind_name()),
                            k.span,
                        )
                        .keyword("reuse"))
                }
            }
        }
        let co_names = co_names(&kws);
        let call = CommandCall {
            op: op.to_string(),
            result: target,
            reuse,
            args: kws,
            span: stmt_span,
            op_span,
        };
        let value = self
            .host
            .call(call)
            .map_err(|e| e.at(self.file, stmt_span))?;
        // Macro commands create the CO('NAME') concepts: make them Python names too.
        for n in co_names {
            if let Some(c) = self.host.lookup_concept(&n) {
                self.env.bind(&n, Value::Concept(c));
            }
        }
        Ok(value)
    }
}

/// Names of the `CO('NAME')` values found anywhere in the keywords.
fn co_names(kws: &[Keyword]) -> Vec<String> {
    fn walk(v: &Value, out: &mut Vec<String>) {
        match v {
            Value::Co(n) => out.push(n.clone()),
            Value::Seq(items) => items.iter().for_each(|i| walk(i, out)),
            Value::Fact(k) => k.iter().for_each(|k| walk(&k.value, out)),
            _ => {}
        }
    }
    let mut out = Vec::new();
    kws.iter().for_each(|k| walk(&k.value, &mut out));
    out
}

/// `seq[i]` with Python's negative indices.
fn index(base: &Value, i: &Value) -> std::result::Result<Value, String> {
    if matches!(base, Value::Unknown) || matches!(i, Value::Unknown) {
        return Ok(Value::Unknown);
    }
    let i = match i {
        Value::Int(i) => *i,
        Value::Bool(b) => i64::from(*b),
        v => {
            return Err(format!(
                "an index must be an integer, got {}",
                v.kind_name()
            ))
        }
    };
    let get = |len: usize| -> std::result::Result<usize, String> {
        let l = i64::try_from(len).unwrap_or(i64::MAX);
        let k = if i < 0 { i.checked_add(l) } else { Some(i) };
        match k {
            Some(k) if (0..l).contains(&k) => usize::try_from(k).map_err(|_| String::new()),
            _ => Err(format!("index {i} is out of range (length {len})")),
        }
    };
    match base {
        Value::Seq(items) => {
            let k = get(items.len())?;
            items
                .get(k)
                .cloned()
                .ok_or_else(|| format!("index {i} is out of range"))
        }
        Value::Str(s) => {
            let chars: Vec<char> = s.chars().collect();
            let k = get(chars.len())?;
            chars
                .get(k)
                .map(|c| Value::Str(c.to_string()))
                .ok_or_else(|| format!("index {i} is out of range"))
        }
        v => Err(format!("{} cannot be indexed", v.kind_name())),
    }
}
