//! Plain-text help: `aster-nl catalog` (summary) and `aster-nl catalog OP` (describe).

use super::def::{FactDef, OperatorDef, Reuse, Rule, SimpDef, Statut};
use super::validate::{bound_text, bounds_text, when_text};
use std::fmt::Write;

/// Types of a simple keyword as written in the catalog: `R`, `table_sdaster | table_container`.
pub(crate) fn type_label(s: &SimpDef) -> String {
    let t = s.types.join(" | ");
    if s.is_list() {
        format!("list of {t} ({})", bounds_text(s.min, s.max))
    } else {
        t
    }
}

pub(crate) fn into_label(s: &SimpDef) -> Option<String> {
    s.into.as_ref().map(|v| {
        v.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    })
}

pub(crate) fn range_label(s: &SimpDef) -> Option<String> {
    let t = |x: f64| bound_text(x, &s.types);
    let ge = if s.val_min_excluded { ">" } else { ">=" };
    let le = if s.val_max_excluded { "<" } else { "<=" };
    match (s.val_min, s.val_max) {
        (None, None) => None,
        (Some(a), None) => Some(format!("{ge} {}", t(a))),
        (None, Some(b)) => Some(format!("{le} {}", t(b))),
        (Some(a), Some(b)) if !s.val_min_excluded && !s.val_max_excluded => {
            Some(format!("{} to {}", t(a), t(b)))
        }
        (Some(a), Some(b)) => Some(format!("{ge} {} and {le} {}", t(a), t(b))),
    }
}

/// "or a plain value" note of a factor keyword that also accepts one.
pub(crate) fn or_value_label(alt: &SimpDef) -> String {
    match into_label(alt) {
        Some(i) => format!("or a plain value {} ({i})", alt.types.join(" | ")),
        None => format!("or a plain value {}", alt.types.join(" | ")),
    }
}

pub(crate) fn rule_label(r: &Rule) -> String {
    let cond = r
        .when
        .as_ref()
        .map(|w| format!(" {}", when_text(w)))
        .unwrap_or_default();
    format!("{}({}){cond}", r.kind.name(), r.keywords.join(", "))
}

pub(crate) fn result_label(op: &OperatorDef) -> String {
    let mut s = match (&op.result, &op.result_from) {
        (Some(r), None) => r.clone(),
        (r, Some(rf)) => {
            let mut m: Vec<String> = rf
                .map
                .iter()
                .map(|(k, v)| format!("{}='{k}' -> {v}", rf.keyword))
                .collect();
            if let Some(r) = r {
                m.push(format!("otherwise {r}"));
            }
            m.join("; ")
        }
        (None, None) => "nothing".into(),
    };
    if let Some(k) = &op.result_type_of {
        s = format!("the type of {k} ({s} when unknown)");
    }
    let of = op
        .reuse_of
        .as_ref()
        .map(|k| format!(": the concept of {k}"))
        .unwrap_or_default();
    match op.reuse {
        Reuse::No => {}
        Reuse::Optional => s.push_str(&format!(" (reuse= allowed{of})")),
        Reuse::Required => s.push_str(&format!(" (reuse= required{of})")),
    }
    s
}

fn simp_text(out: &mut String, s: &SimpDef, indent: &str) {
    let mut line = format!(
        "{indent}{:<22} {}  [{}]",
        s.name,
        type_label(s),
        s.statut.label()
    );
    if let Some(d) = &s.default {
        let _ = write!(line, "  default {d}");
    }
    let _ = writeln!(out, "{line}");
    let sub = format!("{indent}    ");
    if let Some(i) = into_label(s) {
        let _ = writeln!(out, "{sub}values: {i}");
    }
    if let Some(r) = range_label(s) {
        let _ = writeln!(out, "{sub}range: {r}");
    }
    if let Some(w) = &s.when {
        let _ = writeln!(out, "{sub}only {}", when_text(w));
    }
    wrapped(out, &s.doc, &sub);
}

fn fact_text(out: &mut String, f: &FactDef, indent: &str) {
    let occ = bounds_text(f.min, f.max);
    let _ = writeln!(
        out,
        "{indent}{} = _F(...)  [{}{}]  occurrences: {occ}",
        f.name,
        f.statut.label(),
        if f.statut == Statut::Defaulted {
            ", created with its defaults"
        } else {
            ""
        }
    );
    let sub = format!("{indent}    ");
    if let Some(w) = &f.when {
        let _ = writeln!(out, "{sub}only {}", when_text(w));
    }
    if let Some(alt) = f.or_value_def() {
        let _ = writeln!(out, "{sub}{}", or_value_label(&alt));
    }
    wrapped(out, &f.doc, &sub);
    for r in &f.rules {
        let _ = writeln!(out, "{sub}rule {}", rule_label(r));
    }
    for s in &f.simp {
        simp_text(out, s, &sub);
    }
    for g in &f.fact {
        fact_text(out, g, &sub);
    }
}

/// Full description of one operator, or `None` if it is unknown.
pub fn describe(op: &str) -> Option<String> {
    let def = super::get(op)?;
    let mut out = String::new();
    let _ = writeln!(out, "{} -> {}", def.name, result_label(def));
    wrapped(&mut out, &def.doc, "    ");
    for r in &def.rules {
        let _ = writeln!(out, "    rule {}", rule_label(r));
    }
    let _ = writeln!(out);
    for s in &def.simp {
        simp_text(&mut out, s, "  ");
    }
    for f in &def.fact {
        fact_text(&mut out, f, "  ");
    }
    Some(out)
}

/// First sentence of a doc string, for one-line listings.
pub(crate) fn first_line(doc: &str) -> &str {
    let line = doc.lines().next().unwrap_or("");
    // The first ". " that is not the end of an abbreviation.
    let end = line
        .match_indices(". ")
        .map(|(i, _)| i)
        .find(|&i| !(line[..i].ends_with("e.g") || line[..i].ends_with("i.e")));
    match end {
        Some(i) => &line[..=i],
        None => line,
    }
}

/// Writes `text` word-wrapped to about `WIDTH` columns, each line starting with `indent`.
fn wrapped(out: &mut String, text: &str, indent: &str) {
    const WIDTH: usize = 96;
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && indent.len() + line.len() + 1 + word.len() > WIDTH {
            let _ = writeln!(out, "{indent}{line}");
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        let _ = writeln!(out, "{indent}{line}");
    }
}

/// One line per operator: name and first line of its doc.
pub fn summary() -> String {
    let mut out = String::new();
    for op in &super::catalog().ops {
        let _ = writeln!(out, "{:<18} {}", op.name, first_line(&op.doc));
    }
    out
}
