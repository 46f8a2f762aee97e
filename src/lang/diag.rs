//! Diagnostics: byte offsets to line/column, rendering an error with its source line
//! (miette's graphical report), and "did you mean" suggestions.

use super::Source;
use crate::error::Error;
use crate::value::Span;
use miette::{
    GraphicalReportHandler, GraphicalTheme, LabeledSpan, MietteDiagnostic, NamedSource, Report,
    SourceSpan,
};
use std::io::IsTerminal;

/// Maps byte offsets of one text to 1-based lines and columns (columns count characters).
pub struct LineIndex<'a> {
    text: &'a str,
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    pub fn new(text: &'a str) -> Self {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex { text, starts }
    }

    /// The span of bytes `start..end` (clamped to the text).
    pub fn span(&self, start: usize, end: usize) -> Span {
        let start = floor_char(self.text, start.min(self.text.len()));
        let end = floor_char(self.text, end.clamp(start, self.text.len()));
        let line = self.starts.partition_point(|&s| s <= start).max(1);
        let line_start = self.starts.get(line - 1).copied().unwrap_or(0);
        let col = self
            .text
            .get(line_start..start)
            .map_or(0, |s| s.chars().count())
            + 1;
        Span {
            start,
            end,
            line,
            col,
        }
    }
}

/// The largest char boundary not after `i`.
fn floor_char(text: &str, mut i: usize) -> usize {
    while i > 0 && !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Renders an error for a terminal: ANSI colours only when stderr is a terminal and
/// `NO_COLOR` is not set.
pub fn render(error: &Error, src: Option<&Source>) -> String {
    let color = std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    render_styled(error, src, color)
}

/// Renders an error without any escape sequence (logs, files, tests).
pub fn render_plain(error: &Error, src: Option<&Source>) -> String {
    render_styled(error, src, false)
}

/// Renders an error with miette's graphical report: the message (with the keyword it is
/// about), then, when `src` is the file the error points into, the offending line with the
/// span underlined and its `file:line:col`; otherwise a `--> file:line:col` line. The hint
/// comes last.
pub fn render_styled(error: &Error, src: Option<&Source>, color: bool) -> String {
    let head = match &error.keyword {
        Some(kw) => format!("{kw}: {}", error.message),
        None => error.message.clone(),
    };
    let mut diag = MietteDiagnostic::new(head);
    if let Some(h) = &error.hint {
        diag = diag.with_help(h.clone());
    }
    let theme = if color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let handler = GraphicalReportHandler::new_themed(theme)
        .with_context_lines(1)
        // No wrapping: messages stay on one line, whole in logs and searchable.
        .with_width(100_000);
    let mut out = String::new();
    let in_source = error.location.as_ref().and_then(|loc| {
        src.filter(|s| s.name == loc.file && loc.span.line > 0)
            .map(|s| (loc.span, s))
    });
    let rendered = match (in_source, &error.location) {
        (Some((sp, s)), _) => {
            // Underline the first line of the span (at least one character).
            let start = floor_char(&s.text, sp.start.min(s.text.len()));
            let line_end = s.text[start..]
                .find('\n')
                .map_or(s.text.len(), |i| start + i);
            let end = sp.end.clamp(start, line_end);
            let len = if end > start {
                end - start
            } else {
                s.text[start..line_end]
                    .chars()
                    .next()
                    .map_or(0, char::len_utf8)
            };
            let diag = diag.with_label(LabeledSpan::underline(SourceSpan::new(start.into(), len)));
            let report = Report::new(diag)
                .with_source_code(NamedSource::new(s.name.clone(), s.text.clone()));
            handler.render_report(&mut out, &*report)
        }
        (None, Some(loc)) => {
            let r = handler.render_report(&mut out, &diag);
            out.push_str(&format!(
                "  --> {}:{}:{}\n",
                loc.file, loc.span.line, loc.span.col
            ));
            r
        }
        (None, None) => handler.render_report(&mut out, &diag),
    };
    if rendered.is_err() {
        // Formatting into a String cannot fail; keep the plain message if it ever does.
        return format!("error: {error}\n");
    }
    out
}

/// Levenshtein distance (in characters).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != *cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// Up to three names close to `name`, closest first.
pub fn suggestions(name: &str, candidates: &[String]) -> Vec<String> {
    let limit = (name.chars().count() / 3).max(1);
    let mut scored: Vec<(usize, &String)> = candidates
        .iter()
        .map(|c| (edit_distance(name, c), c))
        .filter(|(d, _)| *d <= limit)
        .collect();
    scored.sort();
    scored.into_iter().take(3).map(|(_, c)| c.clone()).collect()
}

/// "did you mean 'A' or 'B'?" for a list of suggestions.
pub fn did_you_mean(names: &[String]) -> Option<String> {
    let quoted: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
    match quoted.len() {
        0 => None,
        _ => Some(format!("did you mean {}?", quoted.join(" or "))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_index_counts_lines_and_characters() {
        let idx = LineIndex::new("ab\nçd e\n");
        let s = idx.span(7, 8); // 'e': 'ç' is 2 bytes
        assert_eq!((s.line, s.col), (2, 4));
        assert_eq!(idx.span(0, 1).line, 1);
        let s = idx.span(100, 200);
        assert_eq!((s.start, s.end, s.line), (9, 9, 3));
    }

    #[test]
    fn caret_is_under_the_span() {
        let src = Source {
            name: "f.comm".into(),
            text: "A = 1\nX = FOO(A=1)\n".into(),
        };
        let span = LineIndex::new(&src.text).span(10, 13);
        let e = Error::input("unknown operator 'FOO'")
            .at("f.comm", span)
            .hint("did you mean 'FOX'?");
        let r = render_plain(&e, Some(&src));
        let lines: Vec<&str> = r.lines().collect();
        assert_eq!(lines[0], "  × unknown operator 'FOO'", "{r}");
        assert_eq!(lines[1], "   ╭─[f.comm:2:5]", "{r}");
        assert_eq!(lines[3], " 2 │ X = FOO(A=1)", "{r}");
        assert_eq!(lines[4], "   ·     ───", "{r}");
        assert!(r.contains("help: did you mean 'FOX'?"), "{r}");
        assert!(!r.contains('\x1b'));
        assert!(render_styled(&e, Some(&src), true).contains('\x1b'));
    }

    #[test]
    fn without_the_source_the_location_is_still_given() {
        let span = LineIndex::new("\tX = y\n").span(5, 6);
        let e = Error::input("name 'y' is not defined").at("f.comm", span);
        // Another file than the one the error points into: location only.
        let other = Source {
            name: "g.comm".into(),
            text: String::new(),
        };
        for r in [render_plain(&e, Some(&other)), render_plain(&e, None)] {
            assert!(r.contains("name 'y' is not defined"), "{r}");
            assert!(r.contains("--> f.comm:1:6"), "{r}");
        }
    }

    #[test]
    fn suggests_close_names() {
        let names: Vec<String> = ["AFFE_MODELE", "AFFE_MATERIAU", "LIRE_MAILLAGE"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        assert_eq!(
            suggestions("AFFE_MODEL", &names),
            vec!["AFFE_MODELE".to_string()]
        );
        assert!(suggestions("XYZ", &names).is_empty());
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }
}
