//! Consistency of the catalogs themselves (run by the tests): defaults match their type,
//! bounds and `into`; rules and `when` name existing keywords; no duplicate names.

use super::def::{OperatorDef, Rule, RuleKind, Statut, When};
use super::validate::{check_simple, is_concept_type, value_eq, Level};

/// Concept types the catalogs may name. A new kind of concept is added here on purpose,
/// so a misspelt type in a catalog is caught.
pub const CONCEPT_TYPES: &[&str] = &[
    "assd",
    "maillage_sdaster",
    "modele_sdaster",
    "mater_sdaster",
    "cham_mater",
    "cara_elem",
    "char_meca",
    "char_cine_meca",
    "matr_elem_depl_r",
    "nume_ddl_sdaster",
    "matr_asse_depl_r",
    "mode_meca",
    "table_sdaster",
    "table_container",
    "fonction_sdaster",
    "formule",
    "dyna_trans",
    "nume_ddl_gene",
    "matr_asse_gene_r",
    "vect_asse_gene",
    "cham_no_sdaster",
    "table_fonction",
    "tran_gene",
    "vect_elem_depl_r",
];

/// Every problem found in the embedded catalogs (parse errors included); empty when fine.
pub fn check_consistency() -> Vec<String> {
    let cat = super::catalog();
    let mut out = cat.errors.clone();
    for (file, text) in super::files() {
        if let Ok(op) = super::parse(file, text) {
            if format!("{}.toml", op.name) != *file {
                out.push(format!(
                    "commands/{file}: operator {} in a file not named after it",
                    op.name
                ));
            }
        }
    }
    for op in &cat.ops {
        check_op(op, &mut out);
        if super::unsupported(&op.name).is_some() {
            out.push(format!(
                "{}: both implemented and listed as unsupported",
                op.name
            ));
        }
    }
    out
}

pub(crate) fn check_op(op: &OperatorDef, out: &mut Vec<String>) {
    if let Some(t) = &op.result {
        check_type(&op.name, t, out);
    }
    if let Some(rf) = &op.result_from {
        if !op.simp.iter().any(|s| s.name == rf.keyword) {
            out.push(format!(
                "{}: result_from names unknown keyword {}",
                op.name, rf.keyword
            ));
        }
        for t in rf.map.values() {
            if !["R", "I", "TXM"].contains(&t.as_str()) {
                check_type(&op.name, t, out);
            }
        }
    }
    if let Some(path) = &op.reuse_of {
        if op.reuse == super::def::Reuse::No {
            out.push(format!("{}: reuse_of without reuse", op.name));
        }
        let found = match path.split_once('/') {
            Some((f, k)) => op
                .fact
                .iter()
                .any(|d| d.name == f && d.simp.iter().any(|s| s.name == k)),
            None => op.simp.iter().any(|s| s.name == *path),
        };
        if !found {
            out.push(format!(
                "{}: reuse_of names unknown keyword {path}",
                op.name
            ));
        }
    }
    check_level(&Level::of_op(op), out);
}

fn check_type(path: &str, t: &str, out: &mut Vec<String>) {
    if is_concept_type(t) && !CONCEPT_TYPES.contains(&t) {
        out.push(format!("{path}: unknown type {t}"));
    }
}

fn check_when(level: &Level, name: &str, w: &When, out: &mut Vec<String>) {
    let Some(ctl) = level.simp.iter().find(|s| s.name == w.keyword) else {
        out.push(format!(
            "{}/{name}: `when` names unknown keyword {}",
            level.path, w.keyword
        ));
        return;
    };
    if let (Some(eq), Some(into)) = (&w.equals, &ctl.into) {
        for v in eq.iter().filter(|v| !into.iter().any(|a| value_eq(a, v))) {
            out.push(format!(
                "{}/{name}: `when` value {v} not allowed for {}",
                level.path, w.keyword
            ));
        }
    }
}

/// Two definitions of one name are allowed only as alternatives under disjoint `when`
/// conditions (Code_Aster BLOCs defining a keyword differently): different values of the
/// same keyword, or the presence of two keywords that an unconditional rule of the level
/// (UN_PARMI, AU_PLUS_UN, EXCLUS) forbids together.
fn disjoint(a: Option<&When>, b: Option<&When>, rules: &[Rule]) -> bool {
    match (a, b) {
        (Some(a), Some(b)) if a.keyword == b.keyword => match (&a.equals, &b.equals) {
            (Some(x), Some(y)) => !x.iter().any(|v| y.iter().any(|w| value_eq(v, w))),
            _ => false,
        },
        (Some(a), Some(b)) if a.equals.is_none() && b.equals.is_none() => rules.iter().any(|r| {
            r.when.is_none()
                && matches!(
                    r.kind,
                    RuleKind::UnParmi | RuleKind::AuPlusUn | RuleKind::Exclus
                )
                && r.keywords.contains(&a.keyword)
                && r.keywords.contains(&b.keyword)
        }),
        _ => false,
    }
}

fn check_level(level: &Level, out: &mut Vec<String>) {
    let p = &level.path;
    let entries: Vec<(&str, Option<&When>)> = level
        .simp
        .iter()
        .map(|s| (s.name.as_str(), s.when.as_ref()))
        .chain(
            level
                .fact
                .iter()
                .map(|f| (f.name.as_str(), f.when.as_ref())),
        )
        .collect();
    for (i, (n, w)) in entries.iter().enumerate() {
        for (m, v) in entries.iter().skip(i + 1) {
            if n == m && !disjoint(*w, *v, level.rules) {
                out.push(format!(
                    "{p}: keyword {n} defined twice (without disjoint `when`)"
                ));
            }
        }
    }
    let names = level.names();
    for r in level.rules {
        if r.keywords.len() < 2 {
            out.push(format!(
                "{p}: rule {} needs at least two keywords",
                r.kind.name()
            ));
        }
        for k in r.keywords.iter().filter(|k| !names.contains(&k.as_str())) {
            out.push(format!(
                "{p}: rule {} names unknown keyword {k}",
                r.kind.name()
            ));
        }
        if let Some(w) = &r.when {
            check_when(level, r.kind.name(), w, out);
        }
    }
    for s in level.simp {
        let sp = format!("{p}/{}", s.name);
        if s.types.is_empty() {
            out.push(format!("{sp}: no type"));
        }
        for t in &s.types {
            check_type(&sp, t, out);
        }
        if let Some(w) = &s.when {
            check_when(level, &s.name, w, out);
        }
        match (&s.co_type, s.types.iter().any(|t| t == "CO")) {
            (Some(t), true) => check_type(&sp, t, out),
            (Some(_), false) => out.push(format!("{sp}: co_type without type \"CO\"")),
            (None, true) => out.push(format!("{sp}: type \"CO\" needs co_type")),
            (None, false) => {}
        }
        if s.max.is_some_and(|m| m < s.min.max(1)) {
            out.push(format!("{sp}: max below min"));
        }
        match (&s.default, s.statut) {
            (None, Statut::Defaulted) => out.push(format!("{sp}: statut \"d\" without default")),
            (Some(_), Statut::Mandatory | Statut::Optional) => {
                out.push(format!("{sp}: a default needs statut \"d\""))
            }
            (Some(d), Statut::Defaulted) => {
                if let Err(msgs) = check_simple(s, d) {
                    for (m, _) in msgs {
                        out.push(format!("{sp}: default {d}: {m}"));
                    }
                }
            }
            (None, _) => {}
        }
        if let Some(into) = &s.into {
            for v in into {
                let single = super::def::SimpDef {
                    max: Some(1),
                    into: None,
                    ..s.clone()
                };
                if let Err(msgs) = check_simple(&single, v) {
                    for (m, _) in msgs {
                        out.push(format!("{sp}: into value {v}: {m}"));
                    }
                }
            }
        }
    }
    for f in level.fact {
        if let Some(w) = &f.when {
            check_when(level, &f.name, w, out);
        }
        if let Some(alt) = f.or_value_def() {
            for t in &alt.types {
                check_type(&format!("{p}/{}", f.name), t, out);
            }
        }
        if f.max.is_some_and(|m| m < f.min) {
            out.push(format!("{p}/{}: max below min", f.name));
        }
        check_level(&Level::of_fact(p, f), out);
    }
}
