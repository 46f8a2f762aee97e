//! The value a sweep gives one parameter at one point: what the study file wrote, how it is
//! written into the `.comm` (a Python literal), how it is shown and how it is stored in SQL.

use serde::{Deserialize, Serialize};

/// One parameter value. `Int` and `Real` stay apart so that `NB_BRANCHE = 10` is written as
/// an integer (an `I` keyword refuses `10.0`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ParamValue {
    Int(i64),
    Real(f64),
    Bool(bool),
    Text(String),
    /// A TOML array inside a value: a Python tuple, e.g. `FREQ = (0.01, 10.)`.
    Tuple(Vec<ParamValue>),
}

impl ParamValue {
    /// The value of a TOML item, or why it cannot be one.
    pub fn from_toml(v: &toml::Value) -> Result<ParamValue, String> {
        match v {
            toml::Value::Integer(i) => Ok(ParamValue::Int(*i)),
            toml::Value::Float(x) if x.is_finite() => Ok(ParamValue::Real(*x)),
            toml::Value::Float(x) => Err(format!(
                "{x} has no Python literal in a .comm file (finite numbers only)"
            )),
            toml::Value::Boolean(b) => Ok(ParamValue::Bool(*b)),
            toml::Value::String(s) => Ok(ParamValue::Text(s.clone())),
            toml::Value::Array(items) => items
                .iter()
                .map(ParamValue::from_toml)
                .collect::<Result<Vec<_>, _>>()
                .map(ParamValue::Tuple),
            toml::Value::Table(_) => Err("a table is not a parameter value".into()),
            toml::Value::Datetime(_) => Err("a date is not a parameter value".into()),
        }
    }

    /// The Python literal written into the point's `.comm`. Reals use Rust's shortest
    /// round-trip form (`0.01`, `50.0`, `1e-5`), which Python reads back to the same double.
    pub fn python(&self) -> String {
        match self {
            ParamValue::Int(i) => i.to_string(),
            ParamValue::Real(x) => format!("{x:?}"),
            ParamValue::Bool(true) => "True".into(),
            ParamValue::Bool(false) => "False".into(),
            ParamValue::Text(s) => {
                let mut out = String::with_capacity(s.len() + 2);
                out.push('\'');
                for c in s.chars() {
                    match c {
                        '\\' => out.push_str("\\\\"),
                        '\'' => out.push_str("\\'"),
                        '\n' => out.push_str("\\n"),
                        '\t' => out.push_str("\\t"),
                        c => out.push(c),
                    }
                }
                out.push('\'');
                out
            }
            ParamValue::Tuple(items) => {
                let inner: Vec<String> = items.iter().map(ParamValue::python).collect();
                match inner.len() {
                    1 => format!("({},)", inner[0]),
                    _ => format!("({})", inner.join(", ")),
                }
            }
        }
    }

    /// For people: the literal, strings without their quotes.
    pub fn display(&self) -> String {
        match self {
            ParamValue::Text(s) => s.clone(),
            other => other.python(),
        }
    }

    /// The SQL cell: numbers as numbers (so `GROUP BY JEU` and comparisons work), a tuple
    /// as its literal text.
    pub fn sql(&self) -> rusqlite::types::Value {
        use rusqlite::types::Value;
        match self {
            ParamValue::Int(i) => Value::Integer(*i),
            ParamValue::Real(x) => Value::Real(*x),
            ParamValue::Bool(b) => Value::Integer(i64::from(*b)),
            ParamValue::Text(s) => Value::Text(s.clone()),
            ParamValue::Tuple(_) => Value::Text(self.python()),
        }
    }

    /// A number for colour scales, if the value is one.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            ParamValue::Int(i) => Some(*i as f64),
            ParamValue::Real(x) => Some(*x),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn python_literals_read_back_as_written() {
        assert_eq!(ParamValue::Real(0.01).python(), "0.01");
        assert_eq!(ParamValue::Real(50.0).python(), "50.0");
        assert_eq!(ParamValue::Real(1e-5).python(), "1e-5");
        assert_eq!(ParamValue::Real(-2.5e10).python(), "-25000000000.0");
        assert_eq!(ParamValue::Int(-3).python(), "-3");
        assert_eq!(ParamValue::Bool(true).python(), "True");
        assert_eq!(ParamValue::Text("it's".into()).python(), r"'it\'s'");
        assert_eq!(
            ParamValue::Tuple(vec![ParamValue::Real(0.01), ParamValue::Int(10)]).python(),
            "(0.01, 10)"
        );
        assert_eq!(ParamValue::Tuple(vec![ParamValue::Int(1)]).python(), "(1,)");
        // Shortest round trip: the literal parses back to the same double.
        for x in [0.1 + 0.2, 1.0 / 3.0, 6.02214076e23, 5e-324] {
            let back: f64 = ParamValue::Real(x).python().parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits());
        }
    }

    #[test]
    fn non_finite_and_tables_are_refused() {
        assert!(ParamValue::from_toml(&toml::Value::Float(f64::NAN)).is_err());
        assert!(ParamValue::from_toml(&toml::Value::Table(Default::default())).is_err());
    }

    #[test]
    fn json_keeps_integers_and_reals_apart() {
        let vals = vec![
            ParamValue::Int(50),
            ParamValue::Real(50.0),
            ParamValue::Text("PLAN".into()),
            ParamValue::Tuple(vec![ParamValue::Real(1.5), ParamValue::Bool(false)]),
        ];
        let text = serde_json::to_string(&vals).unwrap();
        let back: Vec<ParamValue> = serde_json::from_str(&text).unwrap();
        assert_eq!(back, vals);
    }
}
