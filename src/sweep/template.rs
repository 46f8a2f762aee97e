//! The `.comm` template: its top-level assignments `NAME = value` are the parameters. A
//! point's file is the template with the right-hand side of each parameter's assignment
//! replaced by the point's value, and nothing else changed: the lines keep their numbers,
//! so an error in a point names the same line as in the template.

use super::study::Study;
use super::value::ParamValue;
use crate::error::Result;
use crate::lang::ast::{StmtKind, Target};
use crate::lang::{self, Source};
use std::ops::Range;

/// A parsed template and where each parameter's value sits in its text.
#[derive(Clone, Debug)]
pub struct Template {
    pub source: Source,
    /// For each parameter of the study (same order): the byte range of the value assigned
    /// at top level.
    slots: Vec<Range<usize>>,
}

impl Template {
    /// Read the study's template and find its parameters. Every parameter must be assigned
    /// exactly once at top level (not inside a `for` loop), so that the replacement is the
    /// value the whole file sees.
    pub fn load(study: &Study) -> Result<Template> {
        let text = crate::text_file::read(&study.template, "the template")?;
        let source = Source {
            name: study.template.display().to_string(),
            text,
        };
        let program = lang::parse(&source)?;
        let mut slots = Vec::with_capacity(study.params.len());
        for (i, name) in study.params.iter().enumerate() {
            let found: Vec<(usize, Range<usize>)> = program
                .stmts
                .iter()
                .filter_map(|s| match &s.kind {
                    StmtKind::Assign {
                        target: Target::Name(n),
                        value,
                    } if n.text == *name => Some((n.span.line, value.span.start..value.span.end)),
                    _ => None,
                })
                .collect();
            match found.as_slice() {
                [(_, r)] => slots.push(r.clone()),
                [] => {
                    return Err(study
                        .param_error(
                            i,
                            format!(
                                "{name} is not assigned at the top level of the template {}",
                                study.template.display()
                            ),
                        )
                        .hint(format!(
                        "a parameter is a variable of the template: write a line `{name} = ...` \
                             near its top and use {name} where the value goes"
                    )))
                }
                many => {
                    let lines: Vec<String> = many.iter().map(|(l, _)| l.to_string()).collect();
                    return Err(study
                        .param_error(
                            i,
                            format!(
                                "{name} is assigned {} times at the top level of {} (lines {}): \
                                 the sweep would not know which value to replace",
                                many.len(),
                                study.template.display(),
                                lines.join(", ")
                            ),
                        )
                        .hint("assign a parameter once; derive other variables from it"));
                }
            }
        }
        Ok(Template { source, slots })
    }

    /// The text of one point: each slot replaced by its value. A value that spanned several
    /// lines is followed by as many newlines, so later lines keep their numbers.
    pub fn render(&self, values: &[ParamValue]) -> String {
        let text = &self.source.text;
        let mut order: Vec<usize> = (0..self.slots.len()).collect();
        order.sort_by_key(|&i| self.slots[i].start);
        let mut out = String::with_capacity(text.len() + 64);
        let mut at = 0;
        for i in order {
            let r = &self.slots[i];
            out.push_str(&text[at..r.start]);
            out.push_str(&values[i].python());
            let lines = text[r.clone()].matches('\n').count();
            out.extend(std::iter::repeat_n('\n', lines));
            at = r.end;
        }
        out.push_str(&text[at..]);
        out
    }
}
