//! The expressions of FORMULE (`FORMULE(VALE='sin(W*INST)', W=W, NOM_PARA='INST')`), in
//! the language of the command file itself:
//!
//! - [`Expression::parse`]: the text (stripped, its lines joined, as Code_Aster does) read
//!   by the command file's own scanner and grammar: one expression, the same subset;
//! - [`Expression::names`]: the names it reads and the functions it calls;
//! - [`Scope`] and [`Expression::eval`]: evaluated by the command file's own evaluator, in a
//!   scope of numbers (the formula's parameters and constants) and math functions;
//! - [`formule_keywords`]: when a file calls FORMULE, Code_Aster evaluates the expression
//!   in a context made of FORMULE's other keywords and the names of the command file; here
//!   that context is captured when FORMULE is called (the values at definition) and handed
//!   to the operator as the keyword CONTEXTE (`commands/FORMULE.toml`).

use super::ast::{Expr, ExprKind};
use super::builtins::MATH_FUNCS;
use super::{Env, Source};
use crate::error::{Error, Result};
use crate::suggest::closest;
use crate::value::{Keyword, Span, Value};
use std::collections::BTreeSet;

/// FORMULE's own keywords; every other keyword of the call is a constant of its context.
const OWN_KEYWORDS: &[&str] = &["VALE", "VALE_C", "NOM_PARA", "reuse"];

/// The builtins a formula may call besides the math functions.
const FORMULA_BUILTINS: &[&str] = &["abs", "min", "max", "float", "int", "round"];

/// An expression parsed once, evaluated many times.
#[derive(Clone, Debug, PartialEq)]
pub struct Expression {
    /// The text parsed: stripped, its lines joined.
    text: String,
    expr: Expr,
}

/// The names an expression uses.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Names {
    /// Names read as values (`W`, `INST`, `pi`).
    pub values: BTreeSet<String>,
    /// Names called as functions (`sin`, `abs`).
    pub calls: BTreeSet<String>,
    /// Names whose attribute is read (`math` in `math.sin(x)`).
    pub modules: BTreeSet<String>,
}

impl Expression {
    /// Parses `text` as one expression. A syntax error names the column in the text it
    /// read (stripped, its lines joined), without a file location: the caller says which
    /// keyword holds the text.
    pub fn parse(text: &str) -> Result<Expression> {
        let joined: String = text.trim().lines().collect::<Vec<_>>().join("");
        let src = Source::new("", joined.clone());
        let expr = super::parser::parse_expression(&src).map_err(|e| {
            let col = e.location.as_ref().map_or(1, |l| l.span.col);
            let mut err = Error::syntax(format!("{} (column {col} of '{joined}')", e.message));
            if let Some(h) = e.hint {
                err = err.hint(h);
            }
            err
        })?;
        Ok(Expression { text: joined, expr })
    }

    pub fn text(&self) -> &str {
        &self.text
    }

    /// The names the expression reads, calls, and the modules it uses.
    pub fn names(&self) -> Names {
        let mut n = Names::default();
        walk(&self.expr, &mut n);
        n
    }

    /// The value of the expression with the names of `scope`. An error says what failed
    /// (a math domain error, an undefined name...), without location.
    pub fn eval(&self, scope: &mut Scope) -> Result<Value> {
        super::eval::evaluate(&self.expr, &mut scope.env).map_err(|mut e| {
            e.location = None;
            e
        })
    }
}

fn walk(e: &Expr, n: &mut Names) {
    match &e.kind {
        ExprKind::Name(s) => {
            n.values.insert(s.clone());
        }
        ExprKind::Tuple(items) | ExprKind::List(items) => items.iter().for_each(|i| walk(i, n)),
        ExprKind::Unary(_, x) => walk(x, n),
        ExprKind::Binary(_, a, b) | ExprKind::Index(a, b) => {
            walk(a, n);
            walk(b, n);
        }
        ExprKind::Call { func, args } => {
            match &func.kind {
                ExprKind::Name(s) => {
                    n.calls.insert(s.clone());
                }
                _ => walk(func, n),
            }
            args.iter().for_each(|a| walk(&a.value, n));
        }
        ExprKind::Attr(base, _) => match &base.kind {
            ExprKind::Name(s) => {
                n.modules.insert(s.clone());
            }
            _ => walk(base, n),
        },
        ExprKind::Int(_) | ExprKind::Real(_) | ExprKind::Str(_) | ExprKind::Bool(_) => {}
        ExprKind::None => {}
    }
}

/// The names a formula sees: Code_Aster's preloaded math names ([`super::CODE_ASTER_MATH`]
/// and `pi`), every other function of `math` (`fabs`, `floor`, ...), the module `math`
/// itself, `abs min max float int round`, and the numbers bound with [`Scope::bind`].
#[derive(Clone, Debug)]
pub struct Scope {
    env: Env,
}

impl Default for Scope {
    fn default() -> Self {
        let mut env = Env::default();
        for f in MATH_FUNCS {
            env.import_fn(f, f);
        }
        env.modules
            .insert("math".to_string(), super::ScalarModule::Math);
        Scope { env }
    }
}

impl Scope {
    pub fn new() -> Self {
        Self::default()
    }

    /// Binds `name` to the number `x` (a parameter or a constant).
    pub fn bind(&mut self, name: &str, x: f64) {
        // A parameter is bound again at each evaluation: updated in place.
        match self.env.vars.get_mut(name) {
            Some(v) => *v = Value::Real(x),
            None => self.env.bind(name, Value::Real(x)),
        }
    }

    /// Whether `name` may be read as a value here (a bound number, `pi`).
    pub fn has_value(&self, name: &str) -> bool {
        self.env.vars.contains_key(name)
    }

    /// Whether `name` may be called here.
    pub fn has_function(&self, name: &str) -> bool {
        self.env.funcs.contains_key(name) || FORMULA_BUILTINS.contains(&name)
    }

    /// Whether `name` is a module here (`math`).
    pub fn has_module(&self, name: &str) -> bool {
        self.env.modules.contains_key(name)
    }

    /// The functions a formula may call, sorted (for messages).
    pub fn function_names(&self) -> Vec<String> {
        let mut v: Vec<String> = self.env.funcs.keys().cloned().collect();
        v.extend(FORMULA_BUILTINS.iter().map(|s| s.to_string()));
        v.sort();
        v
    }
}

/// Checks that every name `expr` reads is a parameter of `params`, a constant of
/// `constants` or `pi`, that every function it calls is one a formula may call, and that it
/// reads attributes of `math` only. The errors name VALE and suggest the closest name.
pub fn check_names(expr: &Expression, params: &[String], constants: &[String]) -> Result<()> {
    let scope = Scope::new();
    let names = expr.names();
    for n in &names.values {
        if params.contains(n) || constants.contains(n) || scope.has_value(n) {
            continue;
        }
        let mut err = Error::input(format!(
            "name '{n}' is not defined: a formula reads its parameters ({}), FORMULE's other \
             keywords and the numbers of the command file",
            params.join(", ")
        ))
        .keyword("VALE");
        let known = params.iter().chain(constants).map(String::as_str);
        if scope.has_function(n) {
            err = err.hint(format!("'{n}' is a function: call it, e.g. {n}(INST)"));
        } else if let Some(c) = closest(n, known).first() {
            err = err.hint(format!("did you mean '{c}'?"));
        } else {
            err = err.hint(format!(
                "define {n} before FORMULE, or give {n}=... to FORMULE"
            ));
        }
        return Err(err);
    }
    for f in &names.calls {
        if !scope.has_function(f) {
            let all = scope.function_names();
            let mut err = Error::input(format!(
                "'{f}' is not a function a formula may call (those of math, abs, min, max, \
                 float, int, round; not a function or a formula of the study)"
            ))
            .keyword("VALE");
            if let Some(c) = closest(f, all.iter().map(String::as_str)).first() {
                err = err.hint(format!("did you mean '{c}'?"));
            }
            return Err(err);
        }
    }
    if let Some(m) = names.modules.iter().find(|m| !scope.has_module(m)) {
        return Err(Error::input(format!(
            "the expression reads an attribute of '{m}': only math.<name> is available"
        ))
        .keyword("VALE"));
    }
    Ok(())
}

fn is_number(v: &Value) -> bool {
    matches!(
        v,
        Value::Int(_) | Value::Real(_) | Value::Bool(_) | Value::Unknown
    )
}

/// FORMULE's keywords as its catalog takes them. VALE, VALE_C and NOM_PARA stay; every
/// other keyword is a constant of the formula's context (Code_Aster's own rule), and so is
/// every name of VALE that the command file binds (its value now, at definition), unless
/// it is a parameter or a keyword: both go into `CONTEXTE=(_F(NOM=..., VALE=...), ...)`.
/// A constant that is not a number is refused here, at its keyword (a formula computes
/// with numbers; functions inside formulas are not supported); a VALE that does not parse,
/// or reads a name nothing binds, at VALE ([`check_names`]): so that `aster-nl check`
/// finds them too. FORMULE checks them again (`function::formula`).
pub(super) fn formule_keywords(kws: Vec<Keyword>, env: &Env, file: &str) -> Result<Vec<Keyword>> {
    let mut own: Vec<Keyword> = Vec::new();
    let mut context: Vec<(String, Value, Span)> = Vec::new();
    for k in kws {
        if OWN_KEYWORDS.contains(&k.name.as_str()) {
            own.push(k);
            continue;
        }
        if !is_number(&k.value) {
            return Err(Error::input(format!(
                "{}= binds a name of the formula's expression to {}: a formula computes with \
                 numbers only",
                k.name,
                k.value.kind_name()
            ))
            .at(file, k.span)
            .keyword(k.name.clone())
            .hint(
                "give numbers (W=2*pi*f); a formula cannot call a function or a formula: \
                 sample it with CALC_FONC_INTERP and combine with CALC_FONCTION",
            ));
        }
        context.push((k.name, k.value, k.span));
    }
    let params: Vec<String> = match own.iter().find(|k| k.name == "NOM_PARA").map(|k| &k.value) {
        Some(Value::Str(s)) => vec![s.clone()],
        Some(Value::Seq(items)) => items
            .iter()
            .filter_map(|v| match v {
                Value::Str(s) => Some(s.clone()),
                _ => None,
            })
            .collect(),
        _ => Vec::new(),
    };
    let vale = own
        .iter()
        .find(|k| k.name == "VALE")
        .and_then(|k| match &k.value {
            Value::Str(s) => Some((s.clone(), k.span)),
            _ => None,
        });
    if let Some((text, span)) = vale {
        let e = Expression::parse(&text).map_err(|e| e.at(file, span).keyword("VALE"))?;
        for n in e.names().values {
            if params.contains(&n) || context.iter().any(|(c, _, _)| *c == n) {
                continue;
            }
            match env.get(&n) {
                Some(v) if is_number(v) => context.push((n, v.clone(), span)),
                Some(v) => {
                    return Err(Error::input(format!(
                        "VALE uses '{n}', which is {} in the command file: a formula \
                         computes with numbers only",
                        v.kind_name()
                    ))
                    .at(file, span)
                    .keyword("VALE"))
                }
                None => {}
            }
        }
        let constants: Vec<String> = context.iter().map(|(c, _, _)| c.clone()).collect();
        check_names(&e, &params, &constants).map_err(|e| e.at(file, span))?;
    }
    if let Some(&(_, _, first)) = context.first() {
        let facts = context
            .into_iter()
            .map(|(name, value, span)| {
                Value::Fact(vec![
                    Keyword {
                        name: "NOM".into(),
                        value: Value::Str(name),
                        span,
                    },
                    Keyword {
                        name: "VALE".into(),
                        value,
                        span,
                    },
                ])
            })
            .collect();
        own.push(Keyword {
            name: "CONTEXTE".into(),
            value: Value::Seq(facts),
            span: first,
        });
    }
    Ok(own)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(text: &str, bind: &[(&str, f64)]) -> Result<Value> {
        let e = Expression::parse(text)?;
        let mut s = Scope::new();
        for (n, x) in bind {
            s.bind(n, *x);
        }
        e.eval(&mut s)
    }

    fn real(text: &str, bind: &[(&str, f64)]) -> f64 {
        match value(text, bind) {
            Ok(Value::Real(x)) => x,
            other => panic!("{text}: {other:?}"),
        }
    }

    #[test]
    fn the_command_files_arithmetic_and_math() {
        // Each reference is the same expression written in Rust: the evaluator computes it
        // with the same f64 operations, so they agree to the last bit.
        let w = 2.0 * std::f64::consts::PI * 10.0;
        let t = 0.0123;
        assert_eq!(
            real("sin(W*INST) ", &[("W", w), ("INST", t)]),
            (w * t).sin()
        );
        assert_eq!(
            real("-sin(W*INST)/(W**2)", &[("W", w), ("INST", t)]),
            -(w * t).sin() / w.powf(2.0)
        );
        assert_eq!(
            real("15.*sin (W *INST)", &[("W", w), ("INST", t)]),
            15.0 * (w * t).sin()
        );
        assert_eq!(
            real(
                "max(abs(X), 2)**0.5 + atan2(Y, X) + math.fabs(-Y) + pi",
                &[("X", -3.0), ("Y", 4.0)]
            ),
            3.0f64.powf(0.5) + 4.0f64.atan2(-3.0) + 4.0 + std::f64::consts::PI
        );
        // Lines joined, as Code_Aster does with a triple-quoted VALE.
        assert_eq!(real("\n  2*X\n  + 1\n", &[("X", 3.0)]), 7.0);
    }

    #[test]
    fn names_read_called_and_modules() {
        let e = Expression::parse("a*sin(W*INST) + math.cos(b) + min(c, 1)").unwrap();
        let n = e.names();
        let v: Vec<&str> = n.values.iter().map(String::as_str).collect();
        assert_eq!(v, ["INST", "W", "a", "b", "c"]);
        let c: Vec<&str> = n.calls.iter().map(String::as_str).collect();
        assert_eq!(c, ["min", "sin"]);
        assert!(n.modules.contains("math"));
    }

    #[test]
    fn errors_say_what_and_where_in_the_text() {
        let e = Expression::parse("sin(W*INST))").unwrap_err();
        assert!(e.message.contains("column 12"), "{e}");
        assert!(e.location.is_none());
        for bad in ["x = 1", "1; 2", "", "INST if INST else 0", "(1,\n 2"] {
            assert!(Expression::parse(bad).is_err(), "{bad}");
        }
        let err = value("log(INST)", &[("INST", -1.0)]).unwrap_err();
        assert!(err.message.contains("math domain error"), "{err}");
        let err = value("2*X", &[]).unwrap_err();
        assert!(err.message.contains("name 'X' is not defined"), "{err}");
        // No operator can be called from a formula.
        assert!(value("DEBUT()", &[]).is_err());
    }

    #[test]
    fn formule_keywords_capture_the_context() {
        let sp = Span::default();
        let kw = |n: &str, v: Value| Keyword {
            name: n.into(),
            value: v,
            span: sp,
        };
        let mut env = Env::new();
        env.bind("f", Value::Int(5));
        env.bind("W", Value::Real(99.0));
        env.bind("L", Value::Seq(vec![]));
        let out = formule_keywords(
            vec![
                kw("VALE", Value::Str("Fa*sin(2*pi*f*INST) + W".into())),
                kw("Fa", Value::Real(3.0e3)),
                kw("W", Value::Real(1.0)),
                kw("NOM_PARA", Value::Str("INST".into())),
            ],
            &env,
            "t.comm",
        )
        .unwrap();
        let names: Vec<&str> = out.iter().map(|k| k.name.as_str()).collect();
        assert_eq!(names, ["VALE", "NOM_PARA", "CONTEXTE"]);
        let Value::Seq(ctx) = &out[2].value else {
            panic!("{out:?}")
        };
        let pairs: Vec<(String, Value)> = ctx
            .iter()
            .map(|f| match f {
                Value::Fact(k) => (k[0].value.to_string(), k[1].value.clone()),
                _ => panic!(),
            })
            .collect();
        // The keyword W wins over the file's W; INST is the parameter; pi and f come from
        // the file (the names of VALE in sorted order after the keywords).
        assert_eq!(
            pairs,
            [
                ("'Fa'".to_string(), Value::Real(3.0e3)),
                ("'W'".to_string(), Value::Real(1.0)),
                ("'f'".to_string(), Value::Int(5)),
                ("'pi'".to_string(), Value::Real(std::f64::consts::PI)),
            ]
        );
        let err = formule_keywords(
            vec![
                kw("VALE", Value::Str("L*INST".into())),
                kw("NOM_PARA", Value::Str("INST".into())),
            ],
            &env,
            "t.comm",
        )
        .unwrap_err();
        assert!(err.message.contains("'L', which is a list"), "{err}");
        assert_eq!(err.keyword.as_deref(), Some("VALE"));
        let err = formule_keywords(
            vec![
                kw("VALE", Value::Str("F*2".into())),
                kw("F", Value::Str("x".into())),
            ],
            &env,
            "t.comm",
        )
        .unwrap_err();
        assert_eq!(err.keyword.as_deref(), Some("F"));
        // A syntax error and a name nothing binds are found here, at VALE (so by `check`).
        for (vale, what) in [
            ("sin(W*INST", "was never closed"),
            ("sin(W*INST))", "unmatched ')' (column 12"),
            ("2*INST 3", "invalid syntax"),
            ("sin(OMEGA*INST)", "name 'OMEGA' is not defined"),
            ("sine(INST)", "'sine' is not a function"),
        ] {
            let err = formule_keywords(
                vec![
                    kw("VALE", Value::Str(vale.into())),
                    kw("NOM_PARA", Value::Str("INST".into())),
                ],
                &env,
                "t.comm",
            )
            .unwrap_err();
            assert!(err.message.contains(what), "{vale}: {err}");
            assert_eq!(err.keyword.as_deref(), Some("VALE"), "{vale}");
            assert!(err.location.is_some(), "{vale}");
        }
    }
}
