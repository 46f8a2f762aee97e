//! Groups parsed logical lines into `for` blocks by indentation, as Python does: a body
//! is the run of following lines indented deeper than its header, and a dedent must
//! return to an enclosing level.

use super::ast::{Expr, Stmt, StmtKind, Target};
use super::diag::LineIndex;
use crate::error::{Error, Result};
use crate::value::Span;

/// Deepest nesting of `for` blocks.
const MAX_BLOCK_DEPTH: usize = 20;

/// A parsed logical line before blocks are built.
pub(super) enum Line {
    Simple(Vec<Stmt>),
    For {
        var: Target,
        iter: Expr,
        /// The body written on the header line (`for i in x: a = i`).
        inline: Option<Vec<Stmt>>,
        span: Span,
    },
}

pub(super) struct Parsed {
    pub indent: usize,
    /// Byte offset of the line's first character.
    pub start: usize,
    pub line: Line,
}

/// The statements of a whole file.
pub(super) fn build(lines: &[Parsed], file: &str, idx: &LineIndex) -> Result<Vec<Stmt>> {
    let b = Blocks { file, idx };
    let mut pos = 0;
    b.block(lines, &mut pos, 0, 0)
}

struct Blocks<'a> {
    file: &'a str,
    idx: &'a LineIndex<'a>,
}

impl Blocks<'_> {
    fn err(&self, msg: impl Into<String>, span: Span) -> Error {
        Error::syntax(msg).at(self.file, span)
    }

    /// Statements of the block whose lines are indented by `indent`, from `pos`.
    fn block(
        &self,
        lines: &[Parsed],
        pos: &mut usize,
        indent: usize,
        depth: usize,
    ) -> Result<Vec<Stmt>> {
        let mut out = Vec::new();
        while let Some(l) = lines.get(*pos) {
            if l.indent < indent {
                break;
            }
            if l.indent > indent {
                return Err(self.err("unexpected indent", self.idx.span(l.start, l.start + 1)));
            }
            *pos += 1;
            match &l.line {
                Line::Simple(stmts) => out.extend(stmts.iter().cloned()),
                Line::For {
                    var,
                    iter,
                    inline,
                    span,
                } => {
                    let body = match inline {
                        Some(b) => b.clone(),
                        None => {
                            let next = lines.get(*pos).filter(|n| n.indent > indent);
                            let Some(next) = next else {
                                return Err(self
                                    .err("expected an indented block after 'for'", *span)
                                    .hint("indent the loop body, e.g. by 4 spaces"));
                            };
                            if depth >= MAX_BLOCK_DEPTH {
                                return Err(self.err(
                                    format!(
                                        "loops are nested too deeply (more than {MAX_BLOCK_DEPTH})"
                                    ),
                                    *span,
                                ));
                            }
                            let body = self.block(lines, pos, next.indent, depth + 1)?;
                            if let Some(after) = lines.get(*pos) {
                                if after.indent > indent {
                                    return Err(self.err(
                                        "unindent does not match any outer indentation level",
                                        self.idx.span(after.start, after.start + 1),
                                    ));
                                }
                            }
                            body
                        }
                    };
                    out.push(Stmt {
                        kind: StmtKind::For {
                            var: var.clone(),
                            iter: iter.clone(),
                            body,
                        },
                        span: *span,
                    });
                }
            }
        }
        Ok(out)
    }
}
