//! Diagnostics: byte offsets to line/column, rendering an error with its source line and
//! a caret, and "did you mean" suggestions.

use super::Source;
use crate::error::Error;
use crate::value::Span;
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

/// Renders an error as
/// ```text
/// error: unknown operator 'FOO'
///   --> study.comm:3:5
///    |
///  3 | X = FOO(A=1)
///    |     ^^^
///    = hint: did you mean 'FOX'?
/// ```
/// The source line is shown when `src` is the file the error points into.
pub fn render_styled(error: &Error, src: Option<&Source>, color: bool) -> String {
    let paint = |code: &str, s: &str| {
        if color {
            format!("\x1b[{code}m{s}\x1b[0m")
        } else {
            s.to_string()
        }
    };
    let mut out = String::new();
    let head = match &error.keyword {
        Some(kw) => format!("{kw}: {}", error.message),
        None => error.message.clone(),
    };
    out.push_str(&format!("{}: {head}\n", paint("1;31", "error")));
    if let Some(loc) = &error.location {
        let sp = loc.span;
        out.push_str(&format!("  --> {}:{}:{}\n", loc.file, sp.line, sp.col));
        let line_text = src
            .filter(|s| s.name == loc.file && sp.line > 0)
            .and_then(|s| s.text.split('\n').nth(sp.line - 1));
        if let Some(text) = line_text {
            let text = text.trim_end_matches('\r');
            let num = sp.line.to_string();
            let pad = " ".repeat(num.len());
            // Tabs are shown as 4 spaces; the caret column follows.
            let shown: String = text
                .chars()
                .map(|c| {
                    if c == '\t' {
                        "    ".to_string()
                    } else {
                        c.to_string()
                    }
                })
                .collect();
            let before: usize = text
                .chars()
                .take(sp.col.saturating_sub(1))
                .map(|c| if c == '\t' { 4 } else { 1 })
                .sum();
            let line_chars = text.chars().count();
            let span_chars = src
                .and_then(|s| s.text.get(sp.start..sp.end))
                .map_or(1, |t| t.split('\n').next().unwrap_or("").chars().count());
            let width = span_chars
                .min(line_chars.saturating_sub(sp.col.saturating_sub(1)))
                .max(1);
            out.push_str(&format!(" {pad} {}\n", paint("34", "|")));
            out.push_str(&format!(
                " {} {} {shown}\n",
                paint("34", &num),
                paint("34", "|")
            ));
            out.push_str(&format!(
                " {pad} {} {}{}\n",
                paint("34", "|"),
                " ".repeat(before),
                paint("1;31", &"^".repeat(width))
            ));
        }
    }
    if let Some(h) = &error.hint {
        out.push_str(&format!("  = {}: {h}\n", paint("1", "hint")));
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
        assert_eq!(lines[0], "error: unknown operator 'FOO'");
        assert_eq!(lines[1], "  --> f.comm:2:5");
        assert_eq!(lines[3], " 2 | X = FOO(A=1)");
        assert_eq!(lines[4], "   |     ^^^");
        assert_eq!(lines[5], "  = hint: did you mean 'FOX'?");
        assert!(!r.contains('\x1b'));
        assert!(render_styled(&e, Some(&src), true).contains("\x1b[1;31m^^^"));
    }

    #[test]
    fn caret_after_tabs_and_without_source() {
        let src = Source {
            name: "f.comm".into(),
            text: "\tX = y\n".into(),
        };
        let span = LineIndex::new(&src.text).span(5, 6);
        let e = Error::input("name 'y' is not defined").at("f.comm", span);
        let r = render_plain(&e, Some(&src));
        assert!(r.contains("     X = y\n"), "{r}");
        assert!(r.contains("   |         ^\n"), "{r}");
        // Another file: location only.
        let other = Source {
            name: "g.comm".into(),
            text: String::new(),
        };
        assert_eq!(render_plain(&e, Some(&other)).lines().count(), 2);
        assert_eq!(render_plain(&e, None).lines().count(), 2);
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
