//! Source text -> [`Program`]: logical lines from [`super::scan`], each parsed by the pest
//! grammar `grammar/comm.pest`, then grouped into `for` blocks by indentation.

use super::ast::*;
use super::blocks::{self, Line, Parsed};
use super::diag::LineIndex;
use super::scan::{scan, LogicalLine};
use super::{ScalarModule, Source};
use crate::error::{Error, Result};
use crate::value::Span;
use pest::iterators::Pair;
use pest::Parser as _;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/comm.pest"]
struct CommParser;

const SUPPORTED: &str = "a .comm file may contain assignments, operator calls, `for` loops \
over lists or ranges and `from math import ...`";

/// Parses a whole command file.
pub fn parse(src: &Source) -> Result<Program> {
    let idx = LineIndex::new(&src.text);
    let p = LineParser { src, idx: &idx };
    let (lines, scan_error) = scan(&src.text);
    let mut parsed = Vec::with_capacity(lines.len());
    for l in &lines {
        parsed.push(p.line(l)?);
    }
    if let Some(e) = scan_error {
        return Err(p.scan_error(e));
    }
    let stmts = blocks::build(&parsed, &src.name, &idx)?;
    Ok(Program { stmts })
}

/// Parses a text that must be one expression (FORMULE's VALE): the same scanner and grammar
/// as a command file, so the same subset and the same messages; spans are in `src.text`.
pub fn parse_expression(src: &Source) -> Result<Expr> {
    let idx = LineIndex::new(&src.text);
    let p = LineParser { src, idx: &idx };
    let (lines, scan_error) = scan(&src.text);
    if let Some(e) = scan_error {
        return Err(p.scan_error(e));
    }
    match lines.as_slice() {
        [l] => p.expression(l),
        [] => Err(p.err("the expression is empty", idx.span(0, 0))),
        [_, second, ..] => Err(p.err(
            "one expression is expected, not several lines",
            idx.span(second.start, second.end),
        )),
    }
}

/// The Python string prefix (f, r, b, fr, rb, ...: letters only, any case) that `before`
/// ends with, when it is a word of its own: what a quote right after it means in Python.
fn string_prefix(before: &str) -> Option<&str> {
    let word_start = before
        .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .map_or(0, |i| i + 1);
    let word = &before[word_start..];
    let is_prefix = !word.is_empty()
        && word.len() <= 2
        && word
            .chars()
            .all(|c| matches!(c.to_ascii_lowercase(), 'f' | 'r' | 'b' | 'u'));
    is_prefix.then_some(word)
}

struct LineParser<'a> {
    src: &'a Source,
    idx: &'a LineIndex<'a>,
}

impl LineParser<'_> {
    fn err(&self, msg: impl Into<String>, span: Span) -> Error {
        Error::syntax(msg).at(&self.src.name, span)
    }

    fn scan_error(&self, e: super::scan::ScanError) -> Error {
        let mut err = Error::syntax(e.message).at(&self.src.name, self.idx.span(e.start, e.end));
        if let Some(open) = e.open_at {
            let at = self.idx.span(open, open + 1);
            err = err.hint(format!(
                "it was opened at line {}, column {}",
                at.line, at.col
            ));
        } else if let Some(h) = e.hint {
            err = err.hint(h);
        }
        err
    }

    /// The error for a keyword of Python outside the subset, if the line has one.
    fn unsupported(&self, l: &LogicalLine) -> Option<Error> {
        let (s, e, kw) = l.unsupported?;
        let msg = match kw {
            "{" => "dictionaries ({...}) are not supported".to_string(),
            "and" | "or" | "not" | "is" => format!("the operator '{kw}' is not supported"),
            _ => format!("'{kw}' is not supported in .comm files"),
        };
        Some(self.err(msg, self.idx.span(s, e)).hint(SUPPORTED))
    }

    /// A logical line that must be one expression (no statement, no `;`).
    fn expression(&self, l: &LogicalLine) -> Result<Expr> {
        if let Some(e) = self.unsupported(l) {
            return Err(e);
        }
        let text = self.src.text.get(l.start..l.end).unwrap_or("");
        let span = self.idx.span(l.start, l.end);
        let mut pairs =
            CommParser::parse(Rule::line, text).map_err(|e| self.pest_error(e, l.start, text))?;
        let not_one = || self.err("one expression is expected, not a statement", span);
        let stmts = match pairs.next().and_then(|p| p.into_inner().next()) {
            Some(p) if p.as_rule() == Rule::simple_stmts => p,
            _ => return Err(not_one()),
        };
        let mut it = stmts.into_inner();
        match (it.next(), it.next()) {
            (Some(s), None) if s.as_rule() == Rule::expr_stmt => match s.into_inner().next() {
                Some(e) => self.expr(e, l.start),
                None => Err(not_one()),
            },
            _ => Err(not_one()),
        }
    }

    fn line(&self, l: &LogicalLine) -> Result<Parsed> {
        if let Some(e) = self.unsupported(l) {
            return Err(e);
        }
        let text = self.src.text.get(l.start..l.end).unwrap_or("");
        let mut pairs =
            CommParser::parse(Rule::line, text).map_err(|e| self.pest_error(e, l.start, text))?;
        let line = pairs.next().and_then(|p| p.into_inner().next());
        let line = match line {
            Some(p) if p.as_rule() == Rule::for_stmt => self.for_header(p, l.start)?,
            Some(p) => Line::Simple(self.simple_stmts(p, l.start)?),
            None => return Err(self.err("empty statement", self.idx.span(l.start, l.end))),
        };
        Ok(Parsed {
            indent: l.indent,
            start: l.start,
            line,
        })
    }

    fn pest_error(&self, e: pest::error::Error<Rule>, off: usize, text: &str) -> Error {
        let pos = match e.location {
            pest::error::InputLocation::Pos(p) => p,
            pest::error::InputLocation::Span((s, _)) => s,
        };
        let at = off + pos;
        let width = text
            .get(pos..)
            .and_then(|t| t.chars().next())
            .map_or(0, char::len_utf8);
        let span = self.idx.span(at, at + width);
        let found = match text.get(pos..).and_then(|t| t.chars().next()) {
            None => "the end of the statement".to_string(),
            Some(c) if c == '\n' || c == '\r' => "the end of the line".to_string(),
            Some(c) => format!("'{c}'"),
        };
        let expected = match &e.variant {
            pest::error::ErrorVariant::ParsingError { positives, .. } => expected_text(positives),
            pest::error::ErrorVariant::CustomError { message } => message.clone(),
        };
        let mut err = self.err(
            format!("invalid syntax: expected {expected}, found {found}"),
            span,
        );
        let next = text.get(pos..).unwrap_or("");
        let before = text.get(..pos).unwrap_or("");
        if next.starts_with(['\'', '"']) && string_prefix(before).is_some() {
            let p = string_prefix(before).unwrap_or_default();
            return self
                .err(
                    format!("string prefixes such as {p}'...' (f-strings, raw or byte strings) are not supported"),
                    self.idx.span(at - p.len(), at + width),
                )
                .hint("build the text with + and str(), e.g. 'JEU = ' + str(jeu)");
        }
        if next.starts_with("==") {
            err = err.hint("comparisons are not supported; a keyword is written KEY=value");
        } else if expected.contains("','")
            && (expected.contains("')'") || expected.contains("']'"))
            && next.starts_with(|c: char| c.is_alphanumeric() || c == '_' || c == '\'' || c == '"')
        {
            err = err.hint("a ',' may be missing");
        }
        err
    }

    fn span(&self, p: &Pair<Rule>, off: usize) -> Span {
        let s = p.as_span();
        self.idx.span(off + s.start(), off + s.end())
    }

    fn name(&self, p: &Pair<Rule>, off: usize) -> Name {
        Name {
            text: p.as_str().to_string(),
            span: self.span(p, off),
        }
    }

    fn for_header(&self, p: Pair<Rule>, off: usize) -> Result<Line> {
        let span = self.span(&p, off);
        let mut var = None;
        let mut iter = None;
        let mut inline = None;
        for q in p.into_inner() {
            match q.as_rule() {
                Rule::targets => var = Some(self.targets(q, off)),
                Rule::expr_list => iter = Some(self.expr_list(q, off)?),
                Rule::simple_stmts => inline = Some(self.simple_stmts(q, off)?),
                _ => {}
            }
        }
        match (var, iter) {
            (Some(var), Some(iter)) => Ok(Line::For {
                var,
                iter,
                inline,
                span,
            }),
            _ => Err(Error::internal("malformed for statement").at(&self.src.name, span)),
        }
    }

    fn targets(&self, p: Pair<Rule>, off: usize) -> Target {
        let span = self.span(&p, off);
        let mut names = Vec::new();
        let mut comma = false;
        for q in p.into_inner() {
            match q.as_rule() {
                Rule::comma => comma = true,
                _ => names.push(self.name(&q, off)),
            }
        }
        match names.pop() {
            Some(n) if names.is_empty() && !comma => Target::Name(n),
            Some(n) => {
                names.push(n);
                Target::Tuple(names, span)
            }
            None => Target::Tuple(names, span),
        }
    }

    fn simple_stmts(&self, p: Pair<Rule>, off: usize) -> Result<Vec<Stmt>> {
        let mut out = Vec::new();
        for q in p.into_inner() {
            if let Some(s) = self.stmt(q, off)? {
                out.push(s);
            }
        }
        Ok(out)
    }

    /// One statement; `None` for a lone string literal (a docstring, as in Python).
    fn stmt(&self, p: Pair<Rule>, off: usize) -> Result<Option<Stmt>> {
        let span = self.span(&p, off);
        let rule = p.as_rule();
        let mut inner: Vec<Pair<Rule>> = p.into_inner().collect();
        let kind = match rule {
            Rule::assign if inner.len() == 2 => {
                let value = self.expr_list(inner.remove(1), off)?;
                StmtKind::Assign {
                    target: self.targets(inner.remove(0), off),
                    value,
                }
            }
            Rule::aug_assign if inner.len() == 3 => {
                let op = match inner.get(1).map(|p| p.as_str()) {
                    Some("+=") => BinOp::Add,
                    Some("-=") => BinOp::Sub,
                    Some("*=") => BinOp::Mul,
                    _ => BinOp::Div,
                };
                let value = self.expr(inner.remove(2), off)?;
                let target = inner.remove(0);
                StmtKind::AugAssign {
                    target: self.name(&target, off),
                    op,
                    value,
                }
            }
            Rule::expr_stmt if inner.len() == 1 => {
                let e = self.expr(inner.remove(0), off)?;
                if matches!(e.kind, ExprKind::Str(_)) {
                    return Ok(None);
                }
                if !matches!(e.kind, ExprKind::Call { .. }) {
                    return Err(self
                        .err(
                            "this statement does nothing: only calls may stand alone",
                            e.span,
                        )
                        .hint("assign the value to a name (x = ...) or call an operator"));
                }
                StmtKind::Call(e)
            }
            Rule::import_from => self.import_from(inner, off)?,
            Rule::import_stmt => self.import(inner, off, span)?,
            _ => return Err(Error::internal("unexpected statement").at(&self.src.name, span)),
        };
        Ok(Some(Stmt { kind, span }))
    }

    fn import_from(&self, inner: Vec<Pair<Rule>>, off: usize) -> Result<StmtKind> {
        let mut module = None;
        let mut names = None;
        for q in inner {
            match q.as_rule() {
                Rule::dotted => module = Some(self.name(&q, off)),
                Rule::import_names => {
                    let mut list = Vec::new();
                    for n in q.into_inner() {
                        let parts: Vec<Name> = n
                            .into_inner()
                            .filter(|x| x.as_rule() == Rule::name)
                            .map(|x| self.name(&x, off))
                            .collect();
                        if let Some(first) = parts.first() {
                            let bound = parts.get(1).unwrap_or(first).clone();
                            list.push((first.clone(), bound));
                        }
                    }
                    names = Some(list);
                }
                _ => {}
            }
        }
        let module = module.ok_or_else(|| Error::internal("import without module"))?;
        self.check_module(&module)?;
        Ok(StmtKind::ImportFrom { module, names })
    }

    fn import(&self, inner: Vec<Pair<Rule>>, off: usize, span: Span) -> Result<StmtKind> {
        let items: Vec<Pair<Rule>> = inner
            .into_iter()
            .filter(|q| q.as_rule() == Rule::import_as)
            .collect();
        if items.len() != 1 {
            return Err(self.err("import one module per statement", span));
        }
        let mut module = None;
        let mut alias = None;
        for q in items.into_iter().flat_map(|i| i.into_inner()) {
            match q.as_rule() {
                Rule::dotted => module = Some(self.name(&q, off)),
                Rule::name => alias = Some(self.name(&q, off)),
                _ => {}
            }
        }
        let module = module.ok_or_else(|| Error::internal("import without module"))?;
        self.check_module(&module)?;
        let alias = alias.unwrap_or_else(|| module.clone());
        Ok(StmtKind::Import { module, alias })
    }

    /// `math` and the scalar part of `numpy` are importable; `code_aster` imports of
    /// new-style files are accepted (and ignored) because every operator is available
    /// anyway.
    fn check_module(&self, m: &Name) -> Result<()> {
        let t = m.text.as_str();
        if ScalarModule::named(t).is_some() || t == "code_aster" || t.starts_with("code_aster.") {
            return Ok(());
        }
        Err(self
            .err(format!("importing module '{t}' is not supported"), m.span)
            .hint(
                "only `math` and numpy's scalar functions can be imported (from math import *, \
                 import numpy as np)",
            ))
    }

    // ---- expressions -------------------------------------------------------------

    fn mk(&self, kind: ExprKind, span: Span, children: &[&Expr]) -> Result<Expr> {
        let depth = 1 + children.iter().map(|c| c.depth).max().unwrap_or(0);
        if depth > MAX_EXPR_DEPTH {
            return Err(self.err(
                format!("expression is too complex (nested more than {MAX_EXPR_DEPTH} levels)"),
                span,
            ));
        }
        Ok(Expr { kind, span, depth })
    }

    fn join(&self, a: Span, b: Span) -> Span {
        Span {
            end: b.end.max(a.end),
            ..a
        }
    }

    /// `e1, e2, ...`: a tuple when there is a comma, else the expression itself.
    fn expr_list(&self, p: Pair<Rule>, off: usize) -> Result<Expr> {
        let span = self.span(&p, off);
        let mut items = Vec::new();
        let mut comma = false;
        for q in p.into_inner() {
            match q.as_rule() {
                Rule::comma => comma = true,
                _ => items.push(self.expr(q, off)?),
            }
        }
        if !comma && items.len() == 1 {
            return items
                .pop()
                .ok_or_else(|| Error::internal("empty expression list"));
        }
        let refs: Vec<&Expr> = items.iter().collect();
        let depth_probe = self.mk(ExprKind::None, span, &refs)?;
        Ok(Expr {
            kind: ExprKind::Tuple(items),
            ..depth_probe
        })
    }

    fn expr(&self, p: Pair<Rule>, off: usize) -> Result<Expr> {
        let span = self.span(&p, off);
        match p.as_rule() {
            Rule::expr | Rule::product => {
                let mut it = p.into_inner();
                let first = it
                    .next()
                    .ok_or_else(|| self.err("empty expression", span))?;
                let mut acc = self.expr(first, off)?;
                while let (Some(op), Some(rhs)) = (it.next(), it.next()) {
                    let op = match op.as_str() {
                        "+" => BinOp::Add,
                        "-" => BinOp::Sub,
                        "*" => BinOp::Mul,
                        "/" => BinOp::Div,
                        "//" => BinOp::FloorDiv,
                        _ => BinOp::Mod,
                    };
                    let rhs = self.expr(rhs, off)?;
                    let sp = self.join(acc.span, rhs.span);
                    let e = self.mk(ExprKind::None, sp, &[&acc, &rhs])?;
                    acc = Expr {
                        kind: ExprKind::Binary(op, Box::new(acc), Box::new(rhs)),
                        ..e
                    };
                }
                Ok(acc)
            }
            Rule::unary => {
                let mut signs = Vec::new();
                let mut operand = None;
                for q in p.into_inner() {
                    match q.as_rule() {
                        Rule::sign => signs.push(self.span(&q, off)),
                        _ => operand = Some(self.expr(q, off)?),
                    }
                }
                let operand = operand.ok_or_else(|| self.err("missing operand", span))?;
                self.apply_signs(&signs, operand, off)
            }
            Rule::power => self.power(p, off),
            Rule::postfix => self.postfix(p, off),
            _ => self.primary(p, off),
        }
    }

    /// Applies unary signs (written at `signs`, outermost first) to `e`.
    fn apply_signs(&self, signs: &[Span], mut e: Expr, _off: usize) -> Result<Expr> {
        for s in signs.iter().rev() {
            let op = if self.src.text.get(s.start..s.end) == Some("-") {
                UnOp::Neg
            } else {
                UnOp::Plus
            };
            let sp = self.join(*s, e.span);
            let probe = self.mk(ExprKind::None, sp, &[&e])?;
            e = Expr {
                kind: ExprKind::Unary(op, Box::new(e)),
                ..probe
            };
        }
        Ok(e)
    }

    /// `b ** s1 p1 ** s2 p2 ...` folded to the right: b ** (s1 (p1 ** (s2 p2 ...))).
    fn power(&self, p: Pair<Rule>, off: usize) -> Result<Expr> {
        let span = self.span(&p, off);
        // operands[k] = (signs before it, expression)
        let mut operands: Vec<(Vec<Span>, Expr)> = Vec::new();
        let mut signs = Vec::new();
        for q in p.into_inner() {
            match q.as_rule() {
                Rule::pow_op => {}
                Rule::sign => signs.push(self.span(&q, off)),
                _ => operands.push((std::mem::take(&mut signs), self.expr(q, off)?)),
            }
        }
        let (last_signs, last) = operands
            .pop()
            .ok_or_else(|| self.err("missing operand", span))?;
        let mut acc = last;
        let mut acc_signs = last_signs;
        while let Some((s, base)) = operands.pop() {
            let exponent = self.apply_signs(&acc_signs, acc, off)?;
            let sp = self.join(base.span, exponent.span);
            let probe = self.mk(ExprKind::None, sp, &[&base, &exponent])?;
            acc = Expr {
                kind: ExprKind::Binary(BinOp::Pow, Box::new(base), Box::new(exponent)),
                ..probe
            };
            acc_signs = s;
        }
        // The first operand of `power` never carries signs (they belong to `unary`).
        self.apply_signs(&acc_signs, acc, off)
    }

    fn postfix(&self, p: Pair<Rule>, off: usize) -> Result<Expr> {
        let span = self.span(&p, off);
        let mut it = p.into_inner();
        let first = it
            .next()
            .ok_or_else(|| self.err("missing expression", span))?;
        let mut acc = self.expr(first, off)?;
        for t in it {
            let tspan = self.span(&t, off);
            let sp = self.join(acc.span, tspan);
            match t.as_rule() {
                Rule::call => {
                    let mut args = Vec::new();
                    for a in t.into_inner() {
                        if !matches!(a.as_rule(), Rule::comma | Rule::rpar) {
                            args.push(self.arg(a, off)?);
                        }
                    }
                    let refs: Vec<&Expr> = std::iter::once(&acc)
                        .chain(args.iter().map(|a| &a.value))
                        .collect();
                    let probe = self.mk(ExprKind::None, sp, &refs)?;
                    acc = Expr {
                        kind: ExprKind::Call {
                            func: Box::new(acc),
                            args,
                        },
                        ..probe
                    };
                }
                Rule::index => {
                    let mut items = Vec::new();
                    let mut comma = false;
                    for q in t.into_inner() {
                        match q.as_rule() {
                            Rule::comma => comma = true,
                            Rule::rbrack => {}
                            _ => items.push(self.expr(q, off)?),
                        }
                    }
                    let i = if items.len() == 1 && !comma {
                        items
                            .pop()
                            .ok_or_else(|| self.err("missing index", tspan))?
                    } else {
                        let refs: Vec<&Expr> = items.iter().collect();
                        let probe = self.mk(ExprKind::None, tspan, &refs)?;
                        Expr {
                            kind: ExprKind::Tuple(items),
                            ..probe
                        }
                    };
                    let probe = self.mk(ExprKind::None, sp, &[&acc, &i])?;
                    acc = Expr {
                        kind: ExprKind::Index(Box::new(acc), Box::new(i)),
                        ..probe
                    };
                }
                _ => {
                    let n = t
                        .into_inner()
                        .next()
                        .ok_or_else(|| self.err("missing attribute", tspan))?;
                    let n = self.name(&n, off);
                    let probe = self.mk(ExprKind::None, sp, &[&acc])?;
                    acc = Expr {
                        kind: ExprKind::Attr(Box::new(acc), n),
                        ..probe
                    };
                }
            }
        }
        Ok(acc)
    }

    fn arg(&self, a: Pair<Rule>, off: usize) -> Result<Arg> {
        let span = self.span(&a, off);
        if a.as_rule() == Rule::kwarg {
            let mut it = a.into_inner();
            let (Some(n), Some(v)) = (it.next(), it.next()) else {
                return Err(Error::internal("malformed keyword").at(&self.src.name, span));
            };
            Ok(Arg {
                name: Some(self.name(&n, off)),
                value: self.expr(v, off)?,
                span,
            })
        } else {
            Ok(Arg {
                name: None,
                value: self.expr(a, off)?,
                span,
            })
        }
    }

    fn primary(&self, p: Pair<Rule>, off: usize) -> Result<Expr> {
        let span = self.span(&p, off);
        let leaf = |kind| {
            Ok(Expr {
                kind,
                span,
                depth: 1,
            })
        };
        match p.as_rule() {
            Rule::int => match p.as_str().parse::<i64>() {
                Ok(i) => leaf(ExprKind::Int(i)),
                Err(_) => Err(self
                    .err("integer literal is too large", span)
                    .hint("write it as a real (e.g. 1.e20)")),
            },
            Rule::real => match p.as_str().parse::<f64>() {
                Ok(r) if r.is_finite() => leaf(ExprKind::Real(r)),
                _ => Err(self.err("real literal is out of range", span)),
            },
            Rule::strings => {
                let mut s = String::new();
                for q in p.into_inner() {
                    s.push_str(&unquote(q.as_str()));
                }
                leaf(ExprKind::Str(s))
            }
            Rule::constant => leaf(match p.as_str() {
                "True" => ExprKind::Bool(true),
                "False" => ExprKind::Bool(false),
                _ => ExprKind::None,
            }),
            Rule::name => leaf(ExprKind::Name(p.as_str().to_string())),
            Rule::paren => {
                let mut items = Vec::new();
                let mut comma = false;
                for q in p.into_inner() {
                    match q.as_rule() {
                        Rule::comma => comma = true,
                        Rule::rpar => {}
                        _ => items.push(self.expr(q, off)?),
                    }
                }
                if items.len() == 1 && !comma {
                    // Keep the parentheses in the span: errors point at what was written.
                    let inner = items.pop().ok_or_else(|| self.err("empty", span))?;
                    let probe = self.mk(ExprKind::None, span, &[&inner])?;
                    return Ok(Expr {
                        span,
                        depth: probe.depth,
                        ..inner
                    });
                }
                let refs: Vec<&Expr> = items.iter().collect();
                let probe = self.mk(ExprKind::None, span, &refs)?;
                Ok(Expr {
                    kind: ExprKind::Tuple(items),
                    ..probe
                })
            }
            Rule::list => {
                let items = p
                    .into_inner()
                    .filter(|q| !matches!(q.as_rule(), Rule::comma | Rule::rbrack))
                    .map(|q| self.expr(q, off))
                    .collect::<Result<Vec<_>>>()?;
                let refs: Vec<&Expr> = items.iter().collect();
                let probe = self.mk(ExprKind::None, span, &refs)?;
                Ok(Expr {
                    kind: ExprKind::List(items),
                    ..probe
                })
            }
            _ => self.expr(p, off),
        }
    }
}

/// Human names of what the parser expected.
fn expected_text(positives: &[Rule]) -> String {
    let mut names: Vec<&str> = Vec::new();
    for r in positives {
        let n = match r {
            Rule::expr
            | Rule::product
            | Rule::unary
            | Rule::power
            | Rule::postfix
            | Rule::real
            | Rule::int
            | Rule::strings
            | Rule::string
            | Rule::constant
            | Rule::paren
            | Rule::list
            | Rule::expr_list
            | Rule::sign => "an expression",
            Rule::name | Rule::kwarg | Rule::targets => "a name",
            Rule::EOI => "the end of the statement (or ';')",
            Rule::add_op | Rule::mul_op | Rule::pow_op => "an operator",
            Rule::call | Rule::index | Rule::attr => "'(' '[' or '.'",
            Rule::comma => "','",
            Rule::colon => "':'",
            Rule::rpar => "')'",
            Rule::rbrack => "']'",
            Rule::aug_op => "'='",
            Rule::star => "'*'",
            Rule::dotted => "a module name",
            Rule::kw_in => "'in'",
            Rule::kw_import => "'import'",
            Rule::kw_as => "'as'",
            Rule::for_stmt
            | Rule::simple_stmts
            | Rule::assign
            | Rule::aug_assign
            | Rule::expr_stmt
            | Rule::import_from
            | Rule::import_stmt
            | Rule::kw_for
            | Rule::kw_from => "a statement",
            _ => "something else",
        };
        if !names.contains(&n) {
            names.push(n);
        }
    }
    // "an operator" and trailers are possible almost everywhere: name them only when
    // nothing else was expected.
    let weak = ["an operator", "'(' '[' or '.'"];
    if names.iter().any(|n| !weak.contains(n)) {
        names.retain(|n| !weak.contains(n));
    }
    if names.contains(&"a statement") {
        names.retain(|n| !["an expression", "a name", "'import'"].contains(n));
    }
    if names.contains(&"an expression") {
        names.retain(|n| *n != "a name");
    }
    if names.is_empty() {
        return "something else".into();
    }
    names.join(" or ")
}

/// The value of a string literal (with its optional `r` prefix and quotes).
fn unquote(lit: &str) -> String {
    let raw = lit.starts_with(['r', 'R']);
    let body = if raw { lit.get(1..).unwrap_or("") } else { lit };
    let q = if body.starts_with("\"\"\"") || body.starts_with("'''") {
        3
    } else {
        1
    };
    let inner = body.get(q..body.len().saturating_sub(q)).unwrap_or("");
    if raw {
        return inner.to_string();
    }
    let mut out = String::with_capacity(inner.len());
    let mut chars = inner.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('t') => out.push('\t'),
            Some('r') => out.push('\r'),
            Some('0') => out.push('\0'),
            Some('\\') => out.push('\\'),
            Some('\'') => out.push('\''),
            Some('"') => out.push('"'),
            Some('\n') => {}
            Some(other) => {
                out.push('\\');
                out.push(other);
            }
            None => out.push('\\'),
        }
    }
    out
}
