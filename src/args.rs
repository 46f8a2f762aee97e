//! Validated keyword arguments of one operator call (or of one factor keyword occurrence).
//!
//! The validator (`catalog::validate`) builds an [`Args`] only after the call matched its
//! catalog: keywords are known, types are right, defaults are filled in. Operators read it
//! with the typed getters below; the `req_*` getters still return an error rather than
//! panic, naming the keyword, for the rare case an operator asks for something the catalog
//! does not make mandatory.

use crate::error::{Error, Result};
use crate::value::{ConceptRef, Span, Value};

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Args {
    /// Path of the keyword for messages: `MODE_NON_LINE` or `MODE_NON_LINE/CHOC`.
    pub path: String,
    /// Simple keywords, in catalog order; defaults included (with a default span).
    pub simple: Vec<(String, Value, Span)>,
    /// Factor keywords: each occurrence is an `Args` of its own.
    pub factor: Vec<(String, Vec<Args>, Span)>,
}

impl Args {
    pub fn new(path: impl Into<String>) -> Self {
        Args {
            path: path.into(),
            ..Args::default()
        }
    }

    pub fn value(&self, key: &str) -> Option<&Value> {
        self.simple
            .iter()
            .find(|(k, _, _)| k == key)
            .map(|(_, v, _)| v)
    }

    pub fn has(&self, key: &str) -> bool {
        self.value(key).is_some_and(|v| *v != Value::None) || self.facts(key).is_some()
    }

    pub fn span(&self, key: &str) -> Option<Span> {
        self.simple
            .iter()
            .find(|(k, _, _)| k == key)
            .map(|(_, _, s)| *s)
            .or_else(|| {
                self.factor
                    .iter()
                    .find(|(k, _, _)| k == key)
                    .map(|(_, _, s)| *s)
            })
    }

    /// Full keyword path for messages, e.g. `MODE_NON_LINE/CHOC/JEU`.
    pub fn key_path(&self, key: &str) -> String {
        format!("{}/{}", self.path, key)
    }

    fn scalar(&self, key: &str) -> Option<&Value> {
        match self.value(key)? {
            Value::Seq(items) if items.len() == 1 => Some(&items[0]),
            Value::None => None,
            v => Some(v),
        }
    }

    pub fn real(&self, key: &str) -> Option<f64> {
        self.scalar(key)?.as_f64()
    }
    pub fn int(&self, key: &str) -> Option<i64> {
        match self.scalar(key)? {
            Value::Int(i) => Some(*i),
            _ => None,
        }
    }
    pub fn text(&self, key: &str) -> Option<&str> {
        match self.scalar(key)? {
            Value::Str(s) => Some(s),
            _ => None,
        }
    }
    pub fn concept(&self, key: &str) -> Option<&ConceptRef> {
        match self.scalar(key)? {
            Value::Concept(c) => Some(c),
            _ => None,
        }
    }
    /// `CO('NAME')` given to a keyword.
    pub fn co(&self, key: &str) -> Option<&str> {
        match self.scalar(key)? {
            Value::Co(n) => Some(n),
            _ => None,
        }
    }

    fn items(&self, key: &str) -> Option<Vec<&Value>> {
        match self.value(key)? {
            Value::None => None,
            Value::Seq(items) => Some(items.iter().collect()),
            v => Some(vec![v]),
        }
    }
    /// A scalar or a list of reals (integers are accepted as reals).
    pub fn reals(&self, key: &str) -> Option<Vec<f64>> {
        self.items(key)?.into_iter().map(Value::as_f64).collect()
    }
    pub fn ints(&self, key: &str) -> Option<Vec<i64>> {
        self.items(key)?
            .into_iter()
            .map(|v| match v {
                Value::Int(i) => Some(*i),
                _ => None,
            })
            .collect()
    }
    pub fn texts(&self, key: &str) -> Option<Vec<String>> {
        self.items(key)?
            .into_iter()
            .map(|v| match v {
                Value::Str(s) => Some(s.clone()),
                _ => None,
            })
            .collect()
    }
    pub fn concepts(&self, key: &str) -> Option<Vec<ConceptRef>> {
        self.items(key)?
            .into_iter()
            .map(|v| match v {
                Value::Concept(c) => Some(c.clone()),
                _ => None,
            })
            .collect()
    }

    /// Occurrences of a factor keyword, if given (or created by default).
    pub fn facts(&self, key: &str) -> Option<&[Args]> {
        self.factor
            .iter()
            .find(|(k, _, _)| k == key)
            .map(|(_, v, _)| v.as_slice())
    }
    /// Occurrences of a factor keyword, empty when absent.
    pub fn facts_or_empty(&self, key: &str) -> &[Args] {
        self.facts(key).unwrap_or(&[])
    }
    /// The single occurrence of a factor keyword.
    pub fn fact(&self, key: &str) -> Option<&Args> {
        self.facts(key).and_then(|f| f.first())
    }

    fn missing(&self, key: &str, what: &str) -> Error {
        Error::validation(format!("expected {what}"))
            .keyword(self.key_path(key))
            .hint("this keyword is required here")
    }
    pub fn req_real(&self, key: &str) -> Result<f64> {
        self.real(key).ok_or_else(|| self.missing(key, "a real"))
    }
    pub fn req_int(&self, key: &str) -> Result<i64> {
        self.int(key).ok_or_else(|| self.missing(key, "an integer"))
    }
    /// A count (a size, a number of steps): an integer the catalog bounds below (`val_min`),
    /// so that a negative value never reaches an operator; the conversion still fails
    /// cleanly if a catalog lacks the bound.
    pub fn count(&self, key: &str) -> Result<Option<usize>> {
        self.int(key)
            .map(|v| {
                usize::try_from(v).map_err(|_| {
                    Error::internal(format!(
                        "{key}={v} reached the operator: its catalog needs val_min >= 0"
                    ))
                    .keyword(self.key_path(key))
                })
            })
            .transpose()
    }
    pub fn req_count(&self, key: &str) -> Result<usize> {
        self.count(key)?
            .ok_or_else(|| self.missing(key, "an integer"))
    }
    pub fn req_text(&self, key: &str) -> Result<&str> {
        self.text(key).ok_or_else(|| self.missing(key, "a text"))
    }
    /// A list of reals (a scalar is a one-element list) the catalog makes mandatory or
    /// defaults; its length is the catalog's `min`..`max`.
    pub fn req_reals(&self, key: &str) -> Result<Vec<f64>> {
        self.reals(key)
            .ok_or_else(|| self.missing(key, "a list of reals"))
    }
    /// A list of texts (a scalar is a one-element list) the catalog makes mandatory or
    /// defaults; its length is the catalog's `min`..`max`.
    pub fn req_texts(&self, key: &str) -> Result<Vec<String>> {
        self.texts(key)
            .ok_or_else(|| self.missing(key, "a list of texts"))
    }
    pub fn req_concept(&self, key: &str) -> Result<&ConceptRef> {
        self.concept(key)
            .ok_or_else(|| self.missing(key, "a concept"))
    }
    /// The keyword an error names, found in this call: its path in one style,
    /// `OP/FACT/KEY` (`OP/FACT[i]/KEY`, 1-based, when the factor has several occurrences),
    /// and the span of what the user wrote there (for a defaulted keyword, the factor or
    /// call it was filled into). `path` may name the operator or not, and name an
    /// occurrence or not (`CHOC/JEU`, `MODE_NON_LINE/CHOC[2]/JEU`, `JEU` all resolve when
    /// unambiguous). What does not resolve keeps its text, under the operator's name, and
    /// the deepest span found.
    pub fn locate(&self, path: &str) -> (String, Option<Span>) {
        let op = self.path.as_str();
        if path != op && path.starts_with(op) && !path[op.len()..].starts_with('/') {
            // Not a keyword path ("CALC_STABILITE (row NUME_ORDRE=3)"): leave it.
            return (path.to_string(), None);
        }
        let rest = path
            .strip_prefix(op)
            .map_or(path, |r| r.trim_start_matches('/'));
        let mut canon = op.to_string();
        let mut span = None;
        let mut level = self;
        let mut segs = rest.split('/').filter(|s| !s.is_empty()).peekable();
        while let Some(seg) = segs.next() {
            let (name, occurrence) = split_occurrence(seg);
            if let Some((_, occs, fspan)) = level.factor.iter().find(|(k, _, _)| k == name) {
                span = Some(*fspan);
                let index = match occurrence {
                    Some(i) if (1..=occs.len()).contains(&i) => Some(i - 1),
                    None if occs.len() == 1 => Some(0),
                    _ => None,
                };
                match (index, occurrence) {
                    (Some(i), _) if occs.len() > 1 => {
                        canon.push_str(&format!("/{name}[{}]", i + 1))
                    }
                    (None, Some(i)) => canon.push_str(&format!("/{name}[{i}]")),
                    _ => canon.push_str(&format!("/{name}")),
                }
                let Some(i) = index else {
                    // Several occurrences and none named: the factor is all we can point at.
                    segs.for_each(|s| canon.push_str(&format!("/{s}")));
                    break;
                };
                level = &occs[i];
                if segs.peek().is_none() {
                    span = level.first_given_span(*fspan).or(span);
                }
            } else if let Some((_, _, s)) = level.simple.iter().find(|(k, _, _)| k == name) {
                span = Some(*s);
                canon.push_str(&format!("/{seg}"));
                segs.for_each(|s| canon.push_str(&format!("/{s}")));
                break;
            } else {
                canon.push_str(&format!("/{seg}"));
                segs.for_each(|s| canon.push_str(&format!("/{s}")));
                break;
            }
        }
        (canon, span)
    }

    /// The earliest span of a keyword written in this occurrence (not a default, which
    /// carries the span of the factor it was filled into).
    fn first_given_span(&self, factor_span: Span) -> Option<Span> {
        self.simple
            .iter()
            .map(|(_, _, s)| *s)
            .chain(self.factor.iter().map(|(_, _, s)| *s))
            .filter(|s| *s != factor_span)
            .min_by_key(|s| s.start)
    }

    pub fn req_fact(&self, key: &str) -> Result<&Args> {
        self.fact(key)
            .ok_or_else(|| self.missing(key, "a factor keyword _F(...)"))
    }
}

/// `CHOC[2]` → (`CHOC`, Some(2)); `CHOC` → (`CHOC`, None).
fn split_occurrence(seg: &str) -> (&str, Option<usize>) {
    match seg.strip_suffix(']').and_then(|s| s.split_once('[')) {
        Some((name, i)) => match i.parse() {
            Ok(i) => (name, Some(i)),
            Err(_) => (seg, None),
        },
        None => (seg, None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn span(start: usize, line: usize) -> Span {
        Span {
            start,
            end: start + 1,
            line,
            col: 1,
        }
    }

    /// MODE_NON_LINE(CHOC=(_F(JEU=...), _F(JEU=...)), RESOLUTION=_F(NB_HARM_NONL=...)),
    /// with ITER_NEWTON_MAXI defaulted into RESOLUTION.
    fn call() -> Args {
        let occ = |line| {
            let mut a = Args::new("MODE_NON_LINE/CHOC");
            a.simple
                .push(("JEU".into(), Value::Real(0.1), span(10 * line, line)));
            a
        };
        let mut res = Args::new("MODE_NON_LINE/RESOLUTION");
        res.simple
            .push(("NB_HARM_NONL".into(), Value::Int(20), span(50, 5)));
        res.simple
            .push(("ITER_NEWTON_MAXI".into(), Value::Int(15), span(40, 4)));
        let mut a = Args::new("MODE_NON_LINE");
        a.factor
            .push(("CHOC".into(), vec![occ(2), occ(3)], span(15, 1)));
        a.factor.push(("RESOLUTION".into(), vec![res], span(40, 4)));
        a
    }

    #[test]
    fn every_style_of_path_resolves_to_one_style_and_the_written_span() {
        let a = call();
        let (k, s) = a.locate("CHOC[2]/JEU");
        assert_eq!(k, "MODE_NON_LINE/CHOC[2]/JEU");
        assert_eq!(s.map(|s| s.line), Some(3));
        let (k, s) = a.locate("MODE_NON_LINE/RESOLUTION/NB_HARM_NONL");
        assert_eq!(k, "MODE_NON_LINE/RESOLUTION/NB_HARM_NONL");
        assert_eq!(s.map(|s| s.line), Some(5));
        let (k, s) = a.locate("RESOLUTION/NB_HARM_NONL");
        assert_eq!(k, "MODE_NON_LINE/RESOLUTION/NB_HARM_NONL");
        assert_eq!(s.map(|s| s.line), Some(5));
    }

    #[test]
    fn a_defaulted_keyword_points_at_its_factor_and_an_occurrence_at_its_first_keyword() {
        let a = call();
        let (k, s) = a.locate("RESOLUTION/ITER_NEWTON_MAXI");
        assert_eq!(k, "MODE_NON_LINE/RESOLUTION/ITER_NEWTON_MAXI");
        assert_eq!(s.map(|s| s.line), Some(4));
        let (k, s) = a.locate("MODE_NON_LINE/CHOC[1]");
        assert_eq!(k, "MODE_NON_LINE/CHOC[1]");
        assert_eq!(s.map(|s| s.line), Some(2));
    }

    #[test]
    fn an_ambiguous_or_unknown_path_keeps_its_text_and_the_deepest_span() {
        let a = call();
        // Two CHOC occurrences, none named: the factor keyword.
        let (k, s) = a.locate("CHOC/JEU");
        assert_eq!(k, "MODE_NON_LINE/CHOC/JEU");
        assert_eq!(s.map(|s| s.line), Some(1));
        let (k, s) = a.locate("ETAT_INIT/NUME_ORDRE");
        assert_eq!(k, "MODE_NON_LINE/ETAT_INIT/NUME_ORDRE");
        assert_eq!(s, None);
        let (k, s) = a.locate("MODE_NON_LINE (row 3)");
        assert_eq!(k, "MODE_NON_LINE (row 3)");
        assert_eq!(s, None);
        let (k, _) = a.locate("CHOC[7]/JEU");
        assert_eq!(k, "MODE_NON_LINE/CHOC[7]/JEU");
    }
}
