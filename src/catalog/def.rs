//! The catalog data model: what one `commands/<OPERATOR>.toml` file says (see
//! `docs/catalog-format.md`). Deserialized with serde; TOML values become [`Value`]s.

use crate::value::Value;
use serde::{Deserialize, Deserializer};
use std::collections::BTreeMap;

/// `statut` of a keyword.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub enum Statut {
    /// "o": mandatory.
    #[serde(rename = "o")]
    Mandatory,
    /// "f": optional.
    #[serde(rename = "f")]
    Optional,
    /// "d": optional, with a default value (a factor keyword: created with its defaults).
    #[serde(rename = "d")]
    Defaulted,
}

impl Statut {
    pub fn label(self) -> &'static str {
        match self {
            Statut::Mandatory => "mandatory",
            Statut::Optional => "optional",
            Statut::Defaulted => "optional with default",
        }
    }
}

/// Whether an operator accepts `reuse=`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Reuse {
    #[default]
    No,
    Optional,
    Required,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub enum RuleKind {
    #[serde(rename = "UN_PARMI")]
    UnParmi,
    #[serde(rename = "AU_MOINS_UN")]
    AuMoinsUn,
    #[serde(rename = "AU_PLUS_UN")]
    AuPlusUn,
    #[serde(rename = "EXCLUS")]
    Exclus,
    #[serde(rename = "ENSEMBLE")]
    Ensemble,
    #[serde(rename = "PRESENT_PRESENT")]
    PresentPresent,
    #[serde(rename = "PRESENT_ABSENT")]
    PresentAbsent,
}

impl RuleKind {
    pub fn name(self) -> &'static str {
        match self {
            RuleKind::UnParmi => "UN_PARMI",
            RuleKind::AuMoinsUn => "AU_MOINS_UN",
            RuleKind::AuPlusUn => "AU_PLUS_UN",
            RuleKind::Exclus => "EXCLUS",
            RuleKind::Ensemble => "ENSEMBLE",
            RuleKind::PresentPresent => "PRESENT_PRESENT",
            RuleKind::PresentAbsent => "PRESENT_ABSENT",
        }
    }
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rule {
    pub kind: RuleKind,
    pub keywords: Vec<String>,
    /// The rule applies only under this condition (Code_Aster: a rule inside a BLOC).
    #[serde(default)]
    pub when: Option<When>,
}

/// Condition of a conditional keyword (Code_Aster `BLOC(condition=...)`): the keyword
/// `keyword` of the same level is given (or defaulted) and, with `equals`, has one of
/// those values.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct When {
    pub keyword: String,
    #[serde(default, deserialize_with = "de_opt_values")]
    pub equals: Option<Vec<Value>>,
}

/// A simple keyword (`SIMP`).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimpDef {
    pub name: String,
    /// Accepted types: "R", "I", "TXM", "C", "CO", a concept type, or "assd" (any concept).
    #[serde(rename = "type", deserialize_with = "de_one_or_many")]
    pub types: Vec<String>,
    pub statut: Statut,
    #[serde(default, deserialize_with = "de_opt_value")]
    pub default: Option<Value>,
    #[serde(default = "one")]
    pub min: usize,
    /// `None`: unbounded ("**"). `Some(1)` (the default): a scalar.
    #[serde(default = "some_one", deserialize_with = "de_max")]
    pub max: Option<usize>,
    #[serde(default, deserialize_with = "de_opt_values")]
    pub into: Option<Vec<Value>>,
    #[serde(default)]
    pub val_min: Option<f64>,
    #[serde(default)]
    pub val_max: Option<f64>,
    /// `val_min` itself is refused (a strict bound: `> val_min`).
    #[serde(default)]
    pub val_min_excluded: bool,
    /// `val_max` itself is refused (a strict bound: `< val_max`).
    #[serde(default)]
    pub val_max_excluded: bool,
    #[serde(default)]
    pub doc: String,
    #[serde(default)]
    pub when: Option<When>,
    /// The type of the concept a `CO('NAME')` given to this keyword creates (keywords whose
    /// `type` includes "CO"): what `check` knows of it without running the operator.
    #[serde(default)]
    pub co_type: Option<String>,
}

impl SimpDef {
    /// Whether the keyword takes a list (more than one value allowed).
    pub fn is_list(&self) -> bool {
        self.max != Some(1)
    }
}

/// A factor keyword (`FACT`): `KEY=_F(...)` or a tuple of `_F(...)`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FactDef {
    pub name: String,
    pub statut: Statut,
    /// Occurrence bounds, checked when the keyword is given.
    #[serde(default = "one")]
    pub min: usize,
    #[serde(default = "some_one", deserialize_with = "de_max")]
    pub max: Option<usize>,
    #[serde(default)]
    pub doc: String,
    #[serde(default)]
    pub rules: Vec<Rule>,
    #[serde(default)]
    pub simp: Vec<SimpDef>,
    #[serde(default)]
    pub fact: Vec<FactDef>,
    #[serde(default)]
    pub when: Option<When>,
    /// A plain value also accepted instead of `_F(...)` (Code_Aster changed some keywords
    /// from factor to simple, e.g. `DEBUT(CODE='OUI')` next to `CODE=_F(NIV_PUB_WEB=...)`).
    /// It lands in `Args::simple` under the keyword's name.
    #[serde(default)]
    pub or_value: Option<OrValue>,
}

/// Type and allowed values of [`FactDef::or_value`].
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrValue {
    #[serde(rename = "type", deserialize_with = "de_one_or_many")]
    pub types: Vec<String>,
    #[serde(default, deserialize_with = "de_opt_values")]
    pub into: Option<Vec<Value>>,
}

impl FactDef {
    /// The plain-value alternative as a simple keyword definition.
    pub fn or_value_def(&self) -> Option<SimpDef> {
        self.or_value.as_ref().map(|o| SimpDef {
            name: self.name.clone(),
            types: o.types.clone(),
            statut: Statut::Optional,
            default: None,
            min: 1,
            max: Some(1),
            into: o.into.clone(),
            val_min: None,
            val_max: None,
            val_min_excluded: false,
            val_max_excluded: false,
            doc: String::new(),
            when: None,
            co_type: None,
        })
    }
}

/// Maps the value of a text keyword to the produced concept type, e.g.
/// `EXTR_TABLE(TYPE_RESU='TABLE_SDASTER')` → `table_sdaster`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResultFrom {
    pub keyword: String,
    pub map: BTreeMap<String, String>,
}

/// One operator catalog.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OperatorDef {
    pub name: String,
    /// Concept type produced (absent: the operator returns nothing).
    #[serde(default)]
    pub result: Option<String>,
    #[serde(default)]
    pub result_from: Option<ResultFrom>,
    /// The produced concept has the type of the concept given to this keyword (Code_Aster's
    /// `sd_prod` returning `AsType(TABLE)`): CALC_TABLE of a `table_container` is one.
    /// `result` is the type when the keyword's concept is not known.
    #[serde(default)]
    pub result_type_of: Option<String>,
    #[serde(default)]
    pub reuse: Reuse,
    /// With `reuse=`, the keyword (path `FACT/SIMP` or `SIMP`) that must name the same
    /// concept (Code_Aster's `reentrant='f:KEYWORD'`): `MODE_NON_LINE(reuse=MNL,
    /// ETAT_INIT=_F(MODE_NON_LINE=MNL, ...))` extends the table it restarts from.
    #[serde(default)]
    pub reuse_of: Option<String>,
    #[serde(default)]
    pub doc: String,
    #[serde(default)]
    pub rules: Vec<Rule>,
    #[serde(default)]
    pub simp: Vec<SimpDef>,
    #[serde(default)]
    pub fact: Vec<FactDef>,
}

fn one() -> usize {
    1
}
fn some_one() -> Option<usize> {
    Some(1)
}

/// Converts a TOML value into a command-language value (tables have no counterpart).
pub fn toml_to_value(v: toml::Value) -> Result<Value, String> {
    Ok(match v {
        toml::Value::String(s) => Value::Str(s),
        toml::Value::Integer(i) => Value::Int(i),
        toml::Value::Float(f) => Value::Real(f),
        toml::Value::Boolean(b) => Value::Bool(b),
        toml::Value::Array(a) => Value::Seq(
            a.into_iter()
                .map(toml_to_value)
                .collect::<Result<Vec<_>, _>>()?,
        ),
        other => return Err(format!("unsupported value in a catalog: {other}")),
    })
}

fn de_opt_value<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Value>, D::Error> {
    let v = toml::Value::deserialize(d)?;
    toml_to_value(v).map(Some).map_err(serde::de::Error::custom)
}

fn de_opt_values<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Vec<Value>>, D::Error> {
    let v = Vec::<toml::Value>::deserialize(d)?;
    v.into_iter()
        .map(toml_to_value)
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
        .map_err(serde::de::Error::custom)
}

#[derive(Deserialize)]
#[serde(untagged)]
enum OneOrMany {
    One(String),
    Many(Vec<String>),
}

fn de_one_or_many<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
    Ok(match OneOrMany::deserialize(d)? {
        OneOrMany::One(s) => vec![s],
        OneOrMany::Many(v) => v,
    })
}

#[derive(Deserialize)]
#[serde(untagged)]
enum Bound {
    N(usize),
    Text(String),
}

fn de_max<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
    match Bound::deserialize(d)? {
        Bound::N(n) => Ok(Some(n)),
        Bound::Text(s) if s == "**" => Ok(None),
        Bound::Text(s) => Err(serde::de::Error::custom(format!(
            "max must be an integer or \"**\", got {s:?}"
        ))),
    }
}
