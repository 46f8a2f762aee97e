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
///
/// Built once per text; each lookup costs a binary search plus counting the characters of
/// at most [`CHECKPOINT_BYTES`] bytes, so locating every token of a megabyte line stays
/// linear in the text instead of quadratic.
pub struct LineIndex<'a> {
    text: &'a str,
    /// Byte offset of the start of each line.
    starts: Vec<usize>,
    /// Every [`CHECKPOINT_BYTES`] bytes (at a char boundary): (byte offset, characters
    /// before it in the text).
    checkpoints: Vec<(usize, usize)>,
}

/// Distance between two checkpoints of [`LineIndex`].
const CHECKPOINT_BYTES: usize = 1024;

impl<'a> LineIndex<'a> {
    pub fn new(text: &'a str) -> Self {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        let mut checkpoints = vec![(0, 0)];
        let mut chars = 0;
        let mut at = 0;
        while at < text.len() {
            let next = floor_char(text, (at + CHECKPOINT_BYTES).min(text.len()));
            let next = if next <= at {
                // A char longer than the step (cannot happen for 1024, kept for safety).
                at + text[at..].chars().next().map_or(1, char::len_utf8)
            } else {
                next
            };
            chars += text[at..next].chars().count();
            checkpoints.push((next, chars));
            at = next;
        }
        LineIndex {
            text,
            starts,
            checkpoints,
        }
    }

    /// Characters of the text before byte `at` (a char boundary).
    fn chars_before(&self, at: usize) -> usize {
        let k = self.checkpoints.partition_point(|&(b, _)| b <= at).max(1) - 1;
        let (b, n) = self.checkpoints[k];
        n + self.text.get(b..at).map_or(0, |s| s.chars().count())
    }

    /// The span of bytes `start..end` (clamped to the text).
    pub fn span(&self, start: usize, end: usize) -> Span {
        let start = floor_char(self.text, start.min(self.text.len()));
        let end = floor_char(self.text, end.clamp(start, self.text.len()));
        let line = self.starts.partition_point(|&s| s <= start).max(1);
        let line_start = self.starts.get(line - 1).copied().unwrap_or(0);
        // Near the line start (every span of an ordinary file) counting the few characters
        // before it is cheaper than two checkpoint lookups, each counting up to
        // CHECKPOINT_BYTES; far along a long line the checkpoints bound the work.
        let col = if start - line_start <= CHECKPOINT_BYTES {
            self.text
                .get(line_start..start)
                .map_or(0, |s| s.chars().count())
                + 1
        } else {
            self.chars_before(start) - self.chars_before(line_start) + 1
        };
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
            let excerpt = Excerpt::around(&s.text, sp);
            let label = LabeledSpan::underline(SourceSpan::new(
                excerpt.label_start.into(),
                excerpt.label_len,
            ));
            let report = Report::new(diag.with_label(label))
                .with_source_code(NamedSource::new(s.name.clone(), excerpt));
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

/// At most this many characters of a source line are shown around an error: the renderer
/// pads with the column (it cannot pad past 65,535) and a megabyte line helps nobody.
const EXCERPT_CHARS: usize = 160;
/// Characters shown before the start of the underlined span on a cut line.
const EXCERPT_BEFORE: usize = 60;

/// What the renderer is given instead of the whole file: the line of the error and one line
/// of context on each side, each cut to [`EXCERPT_CHARS`] around the error, reporting the
/// real line numbers and the real column of the error.
struct Excerpt {
    text: String,
    /// 0-based line number of the first excerpt line in the file.
    first_line: usize,
    /// 0-based column (in characters) of the error in its line, as the caller computed it.
    error_col: usize,
    /// The underlined span, in bytes of `text`.
    label_start: usize,
    label_len: usize,
}

impl Excerpt {
    fn around(text: &str, sp: Span) -> Excerpt {
        let start = floor_char(text, sp.start.min(text.len()));
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        let end = floor_char(text, sp.end.clamp(start, line_end));
        let mut out = String::new();
        let mut first_line = sp.line.saturating_sub(1);
        if line_start > 0 {
            let prev_start = text[..line_start - 1].rfind('\n').map_or(0, |i| i + 1);
            out.push_str(&cut_head(&text[prev_start..line_start - 1]));
            out.push('\n');
            first_line = first_line.saturating_sub(1);
        }
        // The error's line: keep EXCERPT_BEFORE characters before the span.
        let before = &text[line_start..start];
        let skip = before.chars().count().saturating_sub(EXCERPT_BEFORE);
        let kept_from = before
            .char_indices()
            .nth(skip)
            .map_or(start, |(i, _)| line_start + i);
        if skip > 0 {
            out.push_str("...");
        }
        out.push_str(&text[kept_from..start]);
        let label_start = out.len();
        let kept_before = before.chars().count() - skip;
        let room = EXCERPT_CHARS.saturating_sub(kept_before);
        let after = &text[start..line_end];
        let shown_after: String = after.chars().take(room.max(1)).collect();
        let span_in_shown = (end - start).min(shown_after.len());
        out.push_str(&shown_after);
        if shown_after.len() < after.len() {
            out.push_str("...");
        }
        let label_len = if span_in_shown > 0 {
            span_in_shown
        } else {
            shown_after.chars().next().map_or(0, char::len_utf8)
        };
        if line_end < text.len() {
            let next_end = text[line_end + 1..]
                .find('\n')
                .map_or(text.len(), |i| line_end + 1 + i);
            out.push('\n');
            out.push_str(&cut_head(&text[line_end + 1..next_end]));
        }
        Excerpt {
            text: out,
            first_line,
            error_col: sp.col.saturating_sub(1),
            label_start,
            label_len,
        }
    }
}

/// The first [`EXCERPT_CHARS`] characters of a context line.
fn cut_head(line: &str) -> String {
    let mut s: String = line.chars().take(EXCERPT_CHARS).collect();
    if s.len() < line.len() {
        s.push_str("...");
    }
    s
}

impl miette::SourceCode for Excerpt {
    fn read_span<'a>(
        &'a self,
        span: &SourceSpan,
        before: usize,
        after: usize,
    ) -> std::result::Result<Box<dyn miette::SpanContents<'a> + 'a>, miette::MietteError> {
        let inner =
            <[u8] as miette::SourceCode>::read_span(self.text.as_bytes(), span, before, after)?;
        // The renderer reads the header's line:column from the label's own span, read
        // without context: that is where the real column goes.
        let column = if before == 0 && after == 0 && span.offset() == self.label_start {
            self.error_col
        } else {
            inner.column()
        };
        Ok(Box::new(miette::MietteSpanContents::new(
            inner.data(),
            *inner.span(),
            self.first_line + inner.line(),
            column,
            inner.line_count(),
        )))
    }
}

/// Up to three names close to `name`, closest first (the rule of `crate::suggest`).
pub fn suggestions(name: &str, candidates: &[String]) -> Vec<String> {
    crate::suggest::closest(name, candidates.iter().map(String::as_str))
        .into_iter()
        .map(str::to_string)
        .collect()
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
    fn line_index_agrees_with_counting_from_the_line_start() {
        // Multi-byte characters across checkpoint boundaries, long and short lines.
        let mut text = String::new();
        for i in 0..3000 {
            text.push_str(if i % 7 == 0 { "é€" } else { "ab" });
            if i % 500 == 499 {
                text.push('\n');
            }
        }
        let idx = LineIndex::new(&text);
        for (start, _) in text.char_indices().step_by(37) {
            let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
            let line = text[..start].matches('\n').count() + 1;
            let col = text[line_start..start].chars().count() + 1;
            let s = idx.span(start, start);
            assert_eq!((s.line, s.col), (line, col), "at byte {start}");
        }
    }

    #[test]
    fn an_error_far_along_a_long_line_renders_with_its_real_column() {
        // The renderer panicked past column 65,535 (it pads with the column).
        let mut text = String::from("A = 1\nF = (");
        for i in 0..20_000 {
            text.push_str(&format!("{i}.0, "));
        }
        let at = text.len();
        text.push_str("BAD)\nFIN()\n");
        let src = Source {
            name: "f.comm".into(),
            text,
        };
        let span = LineIndex::new(&src.text).span(at, at + 3);
        assert!(span.col > 65_535);
        let e = Error::input("name 'BAD' is not defined").at("f.comm", span);
        let r = render_plain(&e, Some(&src));
        assert!(r.contains(&format!("[f.comm:2:{}]", span.col)), "{r}");
        assert!(r.contains("..."), "the line is cut: {r}");
        assert!(r.lines().all(|l| l.chars().count() < 300), "{r}");
        let caret_line = r
            .lines()
            .find(|l| l.contains('─') && l.contains('·'))
            .unwrap();
        let code_line = r.lines().find(|l| l.contains("BAD)")).unwrap();
        assert_eq!(
            caret_line.chars().position(|c| c == '─'),
            code_line
                .find("BAD")
                .map(|b| code_line[..b].chars().count()),
            "{r}"
        );
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
    }
}
