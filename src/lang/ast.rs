//! Syntax tree of a `.comm` file, produced by the parser and walked by the evaluator.

use crate::value::Span;

/// A parsed command file.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    pub stmts: Vec<Stmt>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    pub kind: StmtKind,
    /// The whole statement (for a `for` loop: its header line).
    pub span: Span,
}

/// A name with the place it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Name {
    pub text: String,
    pub span: Span,
}

/// What an assignment or a `for` loop binds.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    Name(Name),
    /// `a, b` (also `a,`): the value is unpacked.
    Tuple(Vec<Name>, Span),
}

#[derive(Clone, Debug, PartialEq)]
pub enum StmtKind {
    /// `NAME = expr` or `A, B = expr`.
    Assign { target: Target, value: Expr },
    /// `NAME += expr` (also `-=`, `*=`, `/=`).
    AugAssign {
        target: Name,
        op: BinOp,
        value: Expr,
    },
    /// A call used as a statement: `DEBUT()`, `TEST_TABLE(...)`.
    Call(Expr),
    /// `for NAME in iter:` + indented body.
    For {
        var: Target,
        iter: Expr,
        body: Vec<Stmt>,
    },
    /// `from MODULE import *` (`names == None`) or `from MODULE import a, b as c`.
    ImportFrom {
        module: Name,
        /// (imported name, name bound in the file)
        names: Option<Vec<(Name, Name)>>,
    },
    /// `import MODULE [as ALIAS]`.
    Import { module: Name, alias: Name },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    FloorDiv,
    Mod,
    Pow,
}

impl BinOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::FloorDiv => "//",
            BinOp::Mod => "%",
            BinOp::Pow => "**",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Plus,
}

/// One argument of a call: `KEY=value` or a positional value.
#[derive(Clone, Debug, PartialEq)]
pub struct Arg {
    pub name: Option<Name>,
    pub value: Expr,
    /// The whole `KEY=value`.
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
    /// Height of the tree below this node (a leaf is 1). The parser refuses to build trees
    /// higher than [`MAX_EXPR_DEPTH`] so that evaluating and dropping them cannot overflow
    /// the stack.
    pub depth: u32,
}

/// Deepest expression tree the parser builds (Python's own parser stops near 200).
pub const MAX_EXPR_DEPTH: u32 = 200;

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Int(i64),
    Real(f64),
    Str(String),
    Bool(bool),
    None,
    Name(String),
    Tuple(Vec<Expr>),
    List(Vec<Expr>),
    Unary(UnOp, Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    Call { func: Box<Expr>, args: Vec<Arg> },
    Index(Box<Expr>, Box<Expr>),
    Attr(Box<Expr>, Name),
}
