//! Validation of a [`CommandCall`] against its catalog, producing [`Args`].
//!
//! Every problem of a call is collected (not only the first one) so the user can fix a
//! command in one go. Rules (`UN_PARMI`...) apply to the keywords the user gave; defaults
//! are filled in afterwards and never trigger a rule.

use super::def::{FactDef, OperatorDef, Reuse, Rule, RuleKind, SimpDef, Statut, When};
use super::suggest;
use crate::args::Args;
use crate::error::Error;
use crate::value::{CommandCall, Keyword, Span, Value};

/// The keywords of one level: the operator itself or one factor keyword.
pub(crate) struct Level<'a> {
    pub path: String,
    pub simp: &'a [SimpDef],
    pub fact: &'a [FactDef],
    pub rules: &'a [Rule],
}

impl<'a> Level<'a> {
    pub fn of_op(op: &'a OperatorDef) -> Self {
        Level {
            path: op.name.clone(),
            simp: &op.simp,
            fact: &op.fact,
            rules: &op.rules,
        }
    }
    pub fn of_fact(parent: &str, f: &'a FactDef) -> Self {
        Level {
            path: format!("{parent}/{}", f.name),
            simp: &f.simp,
            fact: &f.fact,
            rules: &f.rules,
        }
    }
    /// Names of the keywords of this level, each once, in catalog order.
    pub fn names(&self) -> Vec<&'a str> {
        let mut out: Vec<&str> = Vec::new();
        let all = self.simp.iter().map(|s| s.name.as_str());
        for n in all.chain(self.fact.iter().map(|f| f.name.as_str())) {
            if !out.contains(&n) {
                out.push(n);
            }
        }
        out
    }
    fn key(&self, name: &str) -> String {
        format!("{}/{name}", self.path)
    }
}

/// Validates one call. `file` names the command file in error locations.
pub fn validate(call: &CommandCall, file: &str) -> Result<Args, Vec<Error>> {
    let Some(op) = super::get(&call.op) else {
        let names = super::operator_names();
        let e = Error::validation(format!("unknown operator {}", call.op))
            .at(file, call.op_span)
            .keyword(call.op.clone())
            .hint(suggest::hint(&call.op, &names));
        return Err(vec![e]);
    };
    validate_with(op, call, file)
}

/// Validates a call against a given catalog (the embedded one is used by [`validate`]).
pub fn validate_with(op: &OperatorDef, call: &CommandCall, file: &str) -> Result<Args, Vec<Error>> {
    let mut errors = Vec::new();
    let level = Level::of_op(op);
    let args = validate_level(&level, &call.args, call.span, file, &mut errors);
    check_reuse(op, call, &args, file, &mut errors);
    if errors.is_empty() {
        Ok(args)
    } else {
        Err(errors)
    }
}

fn check_reuse(
    op: &OperatorDef,
    call: &CommandCall,
    args: &Args,
    file: &str,
    errors: &mut Vec<Error>,
) {
    let key = format!("{}/reuse", op.name);
    match (op.reuse, &call.reuse) {
        (Reuse::No, Some(_)) => errors.push(
            Error::validation(format!("{} does not accept reuse=", op.name))
                .at(file, call.span)
                .keyword(key)
                .hint("assign the result to a new name instead"),
        ),
        (Reuse::Required, None) => errors.push(
            Error::validation(format!(
                "{} enriches an existing concept: expected reuse=<concept>",
                op.name
            ))
            .at(file, call.span)
            .keyword(key),
        ),
        (Reuse::Optional | Reuse::Required, Some(c)) => {
            if let Some(ty) = super::result_type_with(op, args) {
                if ty != c.ty && is_concept_type(&ty) && c.ty != super::UNKNOWN_CONCEPT_TYPE {
                    errors.push(
                        Error::validation(format!(
                            "expected reuse= a concept of type {ty}, got {} of type {}",
                            c.name, c.ty
                        ))
                        .at(file, call.span)
                        .keyword(key),
                    );
                    return;
                }
            }
            let Some(path) = &op.reuse_of else {
                return;
            };
            let given = match path.split_once('/') {
                Some((f, k)) => args.fact(f).and_then(|occ| occ.concept(k)),
                None => args.concept(path),
            };
            match given {
                Some(g) if g.name == c.name => {}
                Some(g) => errors.push(
                    Error::validation(format!(
                        "reuse={} but {path}={}: a reused concept is the one the call extends",
                        c.name, g.name
                    ))
                    .at(file, call.span)
                    .keyword(key)
                    .hint(format!(
                        "give {path}={} to extend {}, or drop reuse= and assign a new name",
                        c.name, c.name
                    )),
                ),
                None => errors.push(
                    Error::validation(format!(
                        "reuse={} needs {path}={}: {} extends the concept it starts from",
                        c.name, c.name, op.name
                    ))
                    .at(file, call.span)
                    .keyword(key)
                    .hint("drop reuse= and assign the result to a new name"),
                ),
            }
        }
        _ => {}
    }
}

/// Scalar types that are not concepts.
const PLAIN_TYPES: [&str; 5] = ["R", "I", "TXM", "C", "CO"];

pub(crate) fn is_concept_type(t: &str) -> bool {
    !PLAIN_TYPES.contains(&t)
}

/// How deep `when` conditions may chain (a conditional keyword controlling another one).
const MAX_WHEN_DEPTH: usize = 4;

/// The value of a keyword at a level for `when` conditions: given, else its default, from
/// the definition of that name that is active (a keyword given where it is not allowed
/// does not count).
fn current_value<'v>(
    level: &'v Level,
    given: &[&'v Keyword],
    name: &str,
    depth: usize,
) -> Option<&'v Value> {
    let def = level
        .simp
        .iter()
        .filter(|s| s.name == name)
        .find(|s| when_active_at(s.when.as_ref(), level, given, depth + 1))?;
    match given.iter().find(|k| k.name == name) {
        Some(k) => Some(&k.value),
        None => def.default.as_ref(),
    }
}

pub(crate) fn when_active(when: Option<&When>, level: &Level, given: &[&Keyword]) -> bool {
    when_active_at(when, level, given, 0)
}

fn when_active_at(when: Option<&When>, level: &Level, given: &[&Keyword], depth: usize) -> bool {
    let Some(w) = when else { return true };
    if depth > MAX_WHEN_DEPTH {
        return false;
    }
    let Some(v) = current_value(level, given, &w.keyword, depth) else {
        return false;
    };
    match &w.equals {
        None => true,
        Some(allowed) => {
            let v = match v {
                Value::Seq(items) if items.len() == 1 => &items[0],
                v => v,
            };
            allowed.iter().any(|a| value_eq(a, v))
        }
    }
}

/// Equality of catalog values and given values; numbers compare as reals (1 == 1.0).
pub(crate) fn value_eq(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Str(x), Value::Str(y)) => x == y,
        (Value::Int(x), Value::Int(y)) => x == y,
        _ => match (a.as_f64(), b.as_f64()) {
            (Some(x), Some(y)) => x == y,
            _ => false,
        },
    }
}

pub(crate) fn when_text(w: &When) -> String {
    match &w.equals {
        None => format!("when {} is given", w.keyword),
        Some(v) => format!(
            "when {} is {}",
            w.keyword,
            v.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(" or ")
        ),
    }
}

pub(crate) fn validate_level(
    level: &Level,
    kws: &[Keyword],
    span: Span,
    file: &str,
    errors: &mut Vec<Error>,
) -> Args {
    let mut args = Args::new(level.path.clone());
    // `KEY=None` means "not given", as in Code_Aster.
    let mut given: Vec<&Keyword> = Vec::new();
    for k in kws.iter().filter(|k| k.value != Value::None) {
        if given.iter().any(|g| g.name == k.name) {
            errors.push(
                Error::validation(format!("keyword {} is given twice", k.name))
                    .at(file, k.span)
                    .keyword(level.key(&k.name)),
            );
        } else {
            given.push(k);
        }
    }

    let names = level.names();
    for k in &given {
        if !names.contains(&k.name.as_str()) {
            errors.push(
                Error::validation(format!("unknown keyword {} for {}", k.name, level.path))
                    .at(file, k.span)
                    .keyword(level.key(&k.name))
                    .hint(suggest::hint(&k.name, &names)),
            );
        }
    }

    // Conditional keywords given while their condition does not hold.
    for k in &given {
        let simps = level.simp.iter().filter(|s| s.name == k.name);
        let whens: Vec<Option<&When>> = simps
            .map(|s| s.when.as_ref())
            .chain(
                level
                    .fact
                    .iter()
                    .filter(|f| f.name == k.name)
                    .map(|f| f.when.as_ref()),
            )
            .collect();
        // When a controlling keyword has a wrong value, that error is enough: the keywords
        // depending on it are not reported too.
        let cascade = whens
            .iter()
            .flatten()
            .any(|w| controller_invalid(w, level, &given));
        if !whens.is_empty() && !cascade && !whens.iter().any(|w| when_active(*w, level, &given)) {
            let conds: Vec<String> = whens.iter().flatten().map(|w| when_text(w)).collect();
            errors.push(
                Error::validation(format!(
                    "keyword {} is only allowed {}",
                    k.name,
                    conds.join(", or ")
                ))
                .at(file, k.span)
                .keyword(level.key(&k.name)),
            );
        }
    }

    for def in level.simp {
        if !when_active(def.when.as_ref(), level, &given) {
            continue;
        }
        match given.iter().find(|k| k.name == def.name) {
            Some(k) => match check_simple(def, &k.value) {
                Ok(v) => args.simple.push((def.name.clone(), v, k.span)),
                Err(msgs) => {
                    let form = form_hint(level, def);
                    errors.extend(msgs.into_iter().map(|(m, h)| {
                        let e = Error::validation(m)
                            .at(file, k.span)
                            .keyword(level.key(&def.name));
                        let h = match (h, &form) {
                            (Some(h), Some(f)) => Some(format!("{h}; {f}")),
                            (h, f) => h.or_else(|| f.clone()),
                        };
                        match h {
                            Some(h) => e.hint(h),
                            None => e,
                        }
                    }))
                }
            },
            None => match def.statut {
                Statut::Mandatory => {
                    errors.push(missing(level, &def.name, def.when.as_ref(), span, file))
                }
                Statut::Defaulted => {
                    if let Some(d) = &def.default {
                        // Normalized like a given value (a scalar default of a list keyword
                        // becomes a one-element list).
                        let v = check_simple(def, d).unwrap_or_else(|_| d.clone());
                        args.simple.push((def.name.clone(), v, span));
                    }
                }
                Statut::Optional => {}
            },
        }
    }

    for def in level.fact {
        if !when_active(def.when.as_ref(), level, &given) {
            continue;
        }
        let child = Level::of_fact(&level.path, def);
        match given.iter().find(|k| k.name == def.name) {
            Some(k) => {
                let occs: Vec<&[Keyword]> = match &k.value {
                    Value::Fact(f) => vec![f.as_slice()],
                    Value::Seq(items) if items.iter().all(|i| matches!(i, Value::Fact(_))) => items
                        .iter()
                        .filter_map(|i| match i {
                            Value::Fact(f) => Some(f.as_slice()),
                            _ => None,
                        })
                        .collect(),
                    other => {
                        if let Some(alt) = def.or_value_def() {
                            match check_simple(&alt, other) {
                                Ok(v) => args.simple.push((def.name.clone(), v, k.span)),
                                Err(msgs) => errors.extend(msgs.into_iter().map(|(m, _)| {
                                    Error::validation(format!(
                                        "expected a factor keyword _F(...) or {}: {m}",
                                        types_text(&alt.types)
                                    ))
                                    .at(file, k.span)
                                    .keyword(level.key(&def.name))
                                })),
                            }
                            continue;
                        }
                        errors.push(
                            Error::validation(format!(
                                "expected a factor keyword _F(...) or a tuple of them, got {} {}",
                                other.kind_name(),
                                other.brief()
                            ))
                            .at(file, k.span)
                            .keyword(level.key(&def.name)),
                        );
                        continue;
                    }
                };
                let n = occs.len();
                if n < def.min || def.max.is_some_and(|m| n > m) {
                    errors.push(
                        Error::validation(format!(
                            "expected {} occurrence(s) of _F(...), got {n}",
                            bounds_text(def.min, def.max)
                        ))
                        .at(file, k.span)
                        .keyword(level.key(&def.name)),
                    );
                }
                let occ_args = occs
                    .into_iter()
                    .map(|o| validate_level(&child, o, k.span, file, errors))
                    .collect();
                args.factor.push((def.name.clone(), occ_args, k.span));
            }
            None => match def.statut {
                Statut::Mandatory => {
                    errors.push(missing(level, &def.name, def.when.as_ref(), span, file))
                }
                Statut::Defaulted => {
                    let occ = validate_level(&child, &[], span, file, errors);
                    args.factor.push((def.name.clone(), vec![occ], span));
                }
                Statut::Optional => {}
            },
        }
    }

    let present: Vec<(&str, Span)> = given
        .iter()
        .filter(|k| names.contains(&k.name.as_str()))
        .map(|k| (k.name.as_str(), k.span))
        .collect();
    for rule in level
        .rules
        .iter()
        .filter(|r| when_active(r.when.as_ref(), level, &given))
    {
        check_rule(rule, level, &present, span, file, errors);
    }
    args
}

/// For a keyword defined several times at one level (its form follows another keyword,
/// e.g. `CHOC/NOM_CMP` by OBSTACLE), says which form was applied: "expected 2 value(s)"
/// alone would not tell the user why.
fn form_hint(level: &Level, def: &SimpDef) -> Option<String> {
    let w = def.when.as_ref()?;
    if level.simp.iter().filter(|s| s.name == def.name).count() < 2 {
        return None;
    }
    Some(format!("{} takes this form {}", def.name, when_text(w)))
}

/// Whether the keyword a `when` depends on was given with a value no definition accepts.
fn controller_invalid(w: &When, level: &Level, given: &[&Keyword]) -> bool {
    let Some(k) = given.iter().find(|k| k.name == w.keyword) else {
        return false;
    };
    let mut defs = level.simp.iter().filter(|s| s.name == w.keyword).peekable();
    defs.peek().is_some() && defs.all(|d| check_simple(d, &k.value).is_err())
}

fn missing(level: &Level, name: &str, when: Option<&When>, span: Span, file: &str) -> Error {
    let cond = when
        .map(|w| format!(" {}", when_text(w)))
        .unwrap_or_default();
    Error::validation(format!("missing mandatory keyword {name}{cond}"))
        .at(file, span)
        .keyword(level.key(name))
}

pub(crate) fn bounds_text(min: usize, max: Option<usize>) -> String {
    match max {
        Some(m) if m == min => format!("{min}"),
        Some(m) => format!("{min} to {m}"),
        None => format!("at least {min}"),
    }
}

/// A numeric bound as the user would write it: `1` for an integer keyword, `1.0` for a real.
pub(crate) fn bound_text(x: f64, types: &[String]) -> String {
    if types.iter().all(|t| t == "I") && x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x:?}")
    }
}

/// Describes accepted types for messages: "a real", "a concept of type a or b".
pub(crate) fn types_text(types: &[String]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut concepts: Vec<&str> = Vec::new();
    for t in types {
        match t.as_str() {
            "R" => parts.push("a real".into()),
            "I" => parts.push("an integer".into()),
            "TXM" => parts.push("a text".into()),
            "C" => parts.push("a complex (a real or ('RI', re, im) or ('MP', mod, phase))".into()),
            "CO" => parts.push("CO('NAME')".into()),
            "assd" => parts.push("a concept".into()),
            c => concepts.push(c),
        }
    }
    if !concepts.is_empty() {
        parts.push(format!("a concept of type {}", concepts.join(" or ")));
    }
    parts.join(" or ")
}

/// A complex written Code_Aster style: ('RI', re, im) or ('MP', modulus, phase).
fn is_complex_tuple(v: &Value) -> bool {
    match v {
        Value::Seq(items) => {
            items.len() == 3
                && matches!(&items[0], Value::Str(s) if s == "RI" || s == "MP")
                && items[1].as_f64().is_some()
                && items[2].as_f64().is_some()
        }
        _ => false,
    }
}

fn type_ok(types: &[String], v: &Value) -> bool {
    types.iter().any(|t| match (t.as_str(), v) {
        ("R", Value::Int(_) | Value::Real(_)) => true,
        ("I", Value::Int(_)) => true,
        ("TXM", Value::Str(_)) => true,
        ("C", v) => v.as_f64().is_some() || is_complex_tuple(v),
        ("CO", Value::Co(_)) => true,
        ("assd", Value::Concept(_)) => true,
        (t, Value::Concept(c)) => {
            is_concept_type(t) && (c.ty == t || c.ty == super::UNKNOWN_CONCEPT_TYPE)
        }
        _ => false,
    })
}

type Msg = (String, Option<String>);

/// Checks one item of a simple keyword's value: type, `into`, bounds.
fn check_item(def: &SimpDef, v: &Value) -> Option<Msg> {
    // `check` runs no operator: what EXTR_TABLE and the like return is only known at run
    // time, and the run validates it then.
    if matches!(v, Value::Unknown) {
        return None;
    }
    if !type_ok(&def.types, v) {
        let expected = types_text(&def.types);
        return Some(match v {
            Value::Concept(c) => (
                format!("expected {expected}, got {} of type {}", c.name, c.ty),
                None,
            ),
            Value::Str(s) if def.types.iter().any(|t| is_concept_type(t) && t != "C") => (
                format!("expected {expected}, got a text {}", v.brief()),
                Some(format!("a concept is named without quotes: {s}")),
            ),
            _ => (
                format!("expected {expected}, got {} {}", v.kind_name(), v.brief()),
                None,
            ),
        });
    }
    if let Some(into) = &def.into {
        if !into.iter().any(|a| value_eq(a, v)) {
            let allowed: Vec<String> = into.iter().map(|a| a.to_string()).collect();
            return Some((
                format!("expected one of {}, got {}", allowed.join(", "), v.brief()),
                Some(format!("allowed values: {}", allowed.join(", "))),
            ));
        }
    }
    if let Some(x) = v.as_f64() {
        // No keyword takes an infinite or undefined number (1e400, float('nan')).
        if !x.is_finite() {
            return Some((format!("expected a finite number, got {v}"), None));
        }
        if let Some(lo) = def.val_min {
            let (refused, op) = if def.val_min_excluded {
                (x <= lo, ">")
            } else {
                (x < lo, ">=")
            };
            if refused {
                return Some((
                    format!(
                        "expected a value {op} {}, got {v}",
                        bound_text(lo, &def.types)
                    ),
                    None,
                ));
            }
        }
        if let Some(hi) = def.val_max {
            let (refused, op) = if def.val_max_excluded {
                (x >= hi, "<")
            } else {
                (x > hi, "<=")
            };
            if refused {
                return Some((
                    format!(
                        "expected a value {op} {}, got {v}",
                        bound_text(hi, &def.types)
                    ),
                    None,
                ));
            }
        }
    }
    None
}

/// Checks a simple keyword's value and normalizes it: a scalar for `max = 1`, a `Seq`
/// for lists (a scalar given to a list keyword becomes a one-element list).
pub(crate) fn check_simple(def: &SimpDef, v: &Value) -> Result<Value, Vec<Msg>> {
    let complex_scalar = def.types.iter().any(|t| t == "C") && is_complex_tuple(v);
    let (items, given_list): (Vec<&Value>, bool) = match v {
        Value::Seq(items) if !complex_scalar => (items.iter().collect(), true),
        v => (vec![v], false),
    };
    let what = types_text(&def.types);
    if !def.is_list() && items.len() != 1 {
        return Err(vec![(
            format!(
                "expected a single value ({what}), got a list of {} values",
                items.len()
            ),
            None,
        )]);
    }
    if def.is_list() && (items.len() < def.min || def.max.is_some_and(|m| items.len() > m)) {
        return Err(vec![(
            format!(
                "expected {} value(s) ({what}), got {}",
                bounds_text(def.min, def.max),
                items.len()
            ),
            None,
        )]);
    }
    // One message per keyword, however many of its items are wrong: the first, and how
    // many more (a list of a million wrong items is one line, not a million).
    let mut wrong = items.iter().filter_map(|i| check_item(def, i));
    if let Some((first, hint)) = wrong.next() {
        let more = wrong.count();
        let message = if more > 0 {
            format!("{first} (and {more} more wrong item(s) in this keyword)")
        } else {
            first
        };
        return Err(vec![(message, hint)]);
    }
    Ok(if def.is_list() {
        Value::Seq(items.into_iter().cloned().collect())
    } else if given_list {
        items.first().map(|v| (*v).clone()).unwrap_or(Value::None)
    } else {
        v.clone()
    })
}

fn check_rule(
    rule: &Rule,
    level: &Level,
    present: &[(&str, Span)],
    span: Span,
    file: &str,
    errors: &mut Vec<Error>,
) {
    let here: Vec<(&str, Span)> = rule
        .keywords
        .iter()
        .filter_map(|k| present.iter().find(|(n, _)| n == k).copied())
        .collect();
    let list = rule.keywords.join(", ");
    let cond = rule
        .when
        .as_ref()
        .map(|w| format!(" {}", when_text(w)))
        .unwrap_or_default();
    let first = rule.keywords.first().map(String::as_str).unwrap_or("");
    let names_of = |v: &[(&str, Span)]| v.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(" and ");
    let err = |msg: String, kw: &str, at: Span| {
        Error::validation(format!("{msg} (rule {}({list}){cond})", rule.kind.name()))
            .at(file, at)
            .keyword(level.key(kw))
    };
    match rule.kind {
        RuleKind::UnParmi | RuleKind::AuMoinsUn if here.is_empty() => {
            let what = if rule.kind == RuleKind::UnParmi {
                "exactly one"
            } else {
                "at least one"
            };
            errors.push(err(
                format!("expected {what} of {list}, none given"),
                first,
                span,
            ));
        }
        RuleKind::UnParmi | RuleKind::AuPlusUn | RuleKind::Exclus if here.len() > 1 => {
            let what = if rule.kind == RuleKind::UnParmi {
                "exactly one"
            } else {
                "at most one"
            };
            let (n, s) = here[1];
            errors.push(err(
                format!("expected {what} of {list}, got {}", names_of(&here)),
                n,
                s,
            ));
        }
        RuleKind::Ensemble if !here.is_empty() && here.len() < rule.keywords.len() => {
            for k in rule
                .keywords
                .iter()
                .filter(|k| !here.iter().any(|(n, _)| n == k))
            {
                errors.push(err(
                    format!(
                        "expected {k} too: {list} go together, got only {}",
                        names_of(&here)
                    ),
                    k,
                    span,
                ));
            }
        }
        RuleKind::PresentPresent if here.first().is_some_and(|(n, _)| *n == first) => {
            for k in rule
                .keywords
                .iter()
                .skip(1)
                .filter(|k| !here.iter().any(|(n, _)| n == k))
            {
                errors.push(err(format!("expected {k} since {first} is given"), k, span));
            }
        }
        RuleKind::PresentAbsent if here.first().is_some_and(|(n, _)| *n == first) => {
            for (n, s) in here.iter().skip(1) {
                errors.push(err(
                    format!("{n} is not allowed together with {first}"),
                    n,
                    *s,
                ));
            }
        }
        _ => {}
    }
}
