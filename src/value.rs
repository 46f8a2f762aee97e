//! Values of the command language after evaluation.
//!
//! These types are the contract between the language (`lang`), the catalogs
//! (`catalog`) and the operators (`ops`): the evaluator turns source text into
//! [`CommandCall`]s made of [`Value`]s, the validator checks them against a
//! catalog and hands the operator an [`crate::args::Args`].

use std::fmt;

/// A position in a source file. `start`/`end` are byte offsets, `line`/`col` are 1-based.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Span {
    pub start: usize,
    pub end: usize,
    pub line: usize,
    pub col: usize,
}

/// A concept (a named result of an operator: mesh, model, matrix, table...).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConceptRef {
    pub name: String,
    /// Code_Aster type name, e.g. `maillage_sdaster`, `matr_asse_depl_r`, `table_sdaster`.
    pub ty: String,
}

/// One `KEY=value` of a call or of a factor keyword `_F(...)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Keyword {
    pub name: String,
    pub value: Value,
    /// Span of the whole `KEY=value`.
    pub span: Span,
}

/// An evaluated value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    None,
    Bool(bool),
    Int(i64),
    Real(f64),
    Str(String),
    /// A tuple or a list (Code_Aster does not distinguish them).
    Seq(Vec<Value>),
    /// A factor keyword occurrence `_F(K=v, ...)`.
    Fact(Vec<Keyword>),
    /// A concept bound to a Python name.
    Concept(ConceptRef),
    /// `CO('NAME')`: a concept a macro command creates as an extra output.
    Co(String),
    /// A value only a run can compute (`aster-nl check` runs no operator: what EXTR_TABLE
    /// and the like return there). Arithmetic on it gives `Unknown`; the catalog accepts
    /// it wherever a simple value is expected.
    Unknown,
    /// The contents of a table concept, as `T.EXTR_TABLE()` returns them: `tab.PARA` is
    /// the column (a list, `None` in an empty cell), `len(tab)` the number of rows.
    Table(std::sync::Arc<TableValue>),
    /// An object of Code_Aster's Python API that its newer test files create
    /// (docs/mode_non_line.md, "Files written with Code_Aster's Python API").
    Api(ApiObject),
}

/// The objects of Code_Aster's Python API that aster-nl understands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ApiObject {
    /// `test = code_aster.TestCase()`: its assert methods count as tests (OK/NOOK).
    TestCase,
    /// `MA = code_aster.Mesh()`: an empty mesh until `MA.readAsterMeshFile(...)` or
    /// `MA.readMedFile(...)` reads one (LIRE_MAILLAGE).
    Mesh,
}

/// A method of Code_Aster's Python API on a DYNA_VIBRA result (`tran_gene`) that a command
/// file calls (docs/mode_non_line.md, "Files written with Code_Aster's Python API").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResultMethod {
    /// `R.LIST_ARCH()`: the archived instants.
    ListArch,
    /// `R.FORCE_NORMALE(i)`: the normal force of nonlinearity `i` (1-based; `None`: the
    /// first, with Code_Aster's note) at the archived instants.
    NormalForce(Option<i64>),
    /// `R.VARI_INTERNE(i, describe=...)`: every internal variable of nonlinearity `i`, one
    /// row per archived instant; `describe` prints their names first.
    InternalVariables { index: Option<i64>, describe: bool },
}

/// A table's contents in the command language (`T.EXTR_TABLE()`).
#[derive(Clone, Debug, PartialEq)]
pub struct TableValue {
    /// The concept it was extracted from (for messages).
    pub name: String,
    pub columns: Vec<String>,
    /// One value per column in each row; `Value::None` for an empty cell.
    pub rows: Vec<Vec<Value>>,
}

impl TableValue {
    /// The values of column `name` in row order, `None` if the table has no such column.
    pub fn column(&self, name: &str) -> Option<Vec<Value>> {
        let j = self.columns.iter().position(|c| c == name)?;
        Some(
            self.rows
                .iter()
                .map(|r| r.get(j).cloned().unwrap_or(Value::None))
                .collect(),
        )
    }
}

impl Value {
    /// Short description of the kind of value, for error messages ("a real", "a text"...).
    pub fn kind_name(&self) -> &'static str {
        match self {
            Value::None => "None",
            Value::Bool(_) => "a boolean",
            Value::Int(_) => "an integer",
            Value::Real(_) => "a real",
            Value::Str(_) => "a text",
            Value::Seq(_) => "a list",
            Value::Fact(_) => "a factor keyword _F(...)",
            Value::Concept(_) => "a concept",
            Value::Co(_) => "CO(...)",
            Value::Unknown => "a value known only when the file runs",
            Value::Table(_) => "a table (EXTR_TABLE())",
            Value::Api(ApiObject::TestCase) => "a code_aster.TestCase()",
            Value::Api(ApiObject::Mesh) => "a code_aster.Mesh() not read yet",
        }
    }

    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Int(i) => Some(*i as f64),
            Value::Real(r) => Some(*r),
            _ => None,
        }
    }
}

impl Value {
    /// The value as the file would write it, cut after about 100 characters ("…"): what a
    /// message shows, however long the list is (formatting stops there, it is not built
    /// whole and then cut).
    pub fn brief(&self) -> String {
        use fmt::Write;
        const MAX: usize = 100;
        struct Bounded(String);
        impl fmt::Write for Bounded {
            fn write_str(&mut self, s: &str) -> fmt::Result {
                for c in s.chars() {
                    if self.0.len() >= MAX {
                        return Err(fmt::Error);
                    }
                    self.0.push(c);
                }
                Ok(())
            }
        }
        let mut out = Bounded(String::new());
        match write!(out, "{self}") {
            Ok(()) => out.0,
            Err(_) => format!("{}…", out.0),
        }
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::None => write!(f, "None"),
            Value::Bool(b) => write!(f, "{}", if *b { "True" } else { "False" }),
            Value::Int(i) => write!(f, "{i}"),
            Value::Real(r) => write!(f, "{r:?}"),
            Value::Str(s) => write!(f, "'{s}'"),
            Value::Seq(items) => {
                write!(f, "(")?;
                for (i, v) in items.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{v}")?;
                }
                if items.len() == 1 {
                    write!(f, ",")?;
                }
                write!(f, ")")
            }
            Value::Fact(kws) => {
                write!(f, "_F(")?;
                for (i, k) in kws.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{}={}", k.name, k.value)?;
                }
                write!(f, ")")
            }
            Value::Concept(c) => write!(f, "{}", c.name),
            Value::Co(n) => write!(f, "CO('{n}')"),
            Value::Unknown => write!(f, "<known when run>"),
            Value::Table(t) => write!(
                f,
                "<table {} of {} row(s): {}>",
                t.name,
                t.rows.len(),
                t.columns.join(", ")
            ),
            Value::Api(ApiObject::TestCase) => write!(f, "<code_aster.TestCase>"),
            Value::Api(ApiObject::Mesh) => write!(f, "<code_aster.Mesh>"),
        }
    }
}

/// One operator call, evaluated: `RESULT = OP(args)` or a bare `OP(args)`.
#[derive(Clone, Debug, PartialEq)]
pub struct CommandCall {
    /// Operator name, e.g. `MODE_NON_LINE`.
    pub op: String,
    /// Name the result is bound to (`MNL = ...`), if any.
    pub result: Option<String>,
    /// `reuse=NAME`: the concept the operator enriches (removed from `args`).
    pub reuse: Option<ConceptRef>,
    /// Keyword arguments in source order (without `reuse`).
    pub args: Vec<Keyword>,
    /// Span of the whole statement.
    pub span: Span,
    /// Span of the operator name.
    pub op_span: Span,
}
