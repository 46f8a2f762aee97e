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
    pub fn req_concept(&self, key: &str) -> Result<&ConceptRef> {
        self.concept(key)
            .ok_or_else(|| self.missing(key, "a concept"))
    }
    pub fn req_fact(&self, key: &str) -> Result<&Args> {
        self.fact(key)
            .ok_or_else(|| self.missing(key, "a factor keyword _F(...)"))
    }
}
