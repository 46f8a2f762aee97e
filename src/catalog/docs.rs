//! The command reference `docs/commands.md`, generated from the catalogs.

use super::def::{FactDef, OperatorDef, SimpDef};
use super::print::{
    first_line, into_label, or_value_label, range_label, result_label, rule_label, type_label,
};
use super::validate::{bounds_text, when_text};
use std::fmt::Write;

fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

fn simp_row(out: &mut String, path: &str, s: &SimpDef) {
    let mut notes: Vec<String> = Vec::new();
    if let Some(i) = into_label(s) {
        notes.push(format!("values: {i}"));
    }
    if let Some(r) = range_label(s) {
        notes.push(format!("range: {r}"));
    }
    if let Some(w) = &s.when {
        notes.push(format!("only {}", when_text(w)));
    }
    if !s.doc.is_empty() {
        notes.push(s.doc.clone());
    }
    let default = s
        .default
        .as_ref()
        .map(|d| format!("`{d}`"))
        .unwrap_or_default();
    let _ = writeln!(
        out,
        "| `{path}{}` | {} | {} | {} | {} |",
        s.name,
        cell(&type_label(s)),
        s.statut.label(),
        cell(&default),
        cell(&notes.join("; "))
    );
}

fn fact_rows(out: &mut String, path: &str, f: &FactDef) {
    let mut notes = vec![format!("occurrences: {}", bounds_text(f.min, f.max))];
    if let Some(w) = &f.when {
        notes.push(format!("only {}", when_text(w)));
    }
    if let Some(alt) = f.or_value_def() {
        notes.push(or_value_label(&alt));
    }
    for r in &f.rules {
        notes.push(format!("rule {}", rule_label(r)));
    }
    if !f.doc.is_empty() {
        notes.push(f.doc.clone());
    }
    let _ = writeln!(
        out,
        "| `{path}{}` | _F(...) | {} |  | {} |",
        f.name,
        f.statut.label(),
        cell(&notes.join("; "))
    );
    let sub = format!("{path}{}/", f.name);
    for s in &f.simp {
        simp_row(out, &sub, s);
    }
    for g in &f.fact {
        fact_rows(out, &sub, g);
    }
}

fn op_section(out: &mut String, op: &OperatorDef) {
    let _ = writeln!(out, "## {}\n", op.name);
    if !op.doc.is_empty() {
        let _ = writeln!(out, "{}\n", op.doc);
    }
    let _ = writeln!(out, "Result: {}\n", result_label(op));
    if !op.rules.is_empty() {
        let rules: Vec<String> = op
            .rules
            .iter()
            .map(|r| format!("`{}`", rule_label(r)))
            .collect();
        let _ = writeln!(out, "Rules: {}\n", rules.join(", "));
    }
    let _ = writeln!(out, "| keyword | type | statut | default | notes |");
    let _ = writeln!(out, "|---|---|---|---|---|");
    for s in &op.simp {
        simp_row(out, "", s);
    }
    for f in &op.fact {
        fact_rows(out, "", f);
    }
    let _ = writeln!(out);
}

/// The whole command reference, in Markdown.
pub fn markdown_reference() -> String {
    let mut out = String::new();
    out.push_str("# Command reference\n\n");
    out.push_str(
        "Generated from `commands/*.toml` by `aster_nl::catalog::markdown_reference`; \
         do not edit by hand (regenerate with `UPDATE_DOCS=1 cargo test catalog`).\n\n",
    );
    out.push_str(
        "Keyword paths are written `FACT/KEY` for keywords of a factor keyword `FACT=_F(...)`. \
         Rules apply to the keywords given by the user, not to defaults.\n\n",
    );
    for op in &super::catalog().ops {
        let anchor = op.name.to_lowercase();
        let _ = writeln!(out, "- [{}](#{anchor}): {}", op.name, first_line(&op.doc));
    }
    out.push('\n');
    for op in &super::catalog().ops {
        op_section(&mut out, op);
    }
    out
}
