//! Splits a `.comm` file into logical lines, as Python's tokenizer does: a newline ends a
//! statement only outside brackets and when not escaped by a backslash. It also measures
//! each line's indentation (for `for` bodies) and catches the lexical errors that a PEG
//! parser would report badly: unclosed or mismatched brackets, unterminated strings,
//! Python keywords outside the supported subset, too deep nesting.

/// Deepest bracket nesting accepted (keeps the recursive-descent parser's stack small).
pub const MAX_BRACKET_DEPTH: usize = 64;

/// One logical line: `text[start..end]` (it may span several physical lines).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LogicalLine {
    pub start: usize,
    pub end: usize,
    /// Width of the leading blanks of its first physical line (a tab goes to the next
    /// multiple of 8, as in Python).
    pub indent: usize,
    /// The first Python keyword outside the supported subset: (start, end, keyword).
    pub unsupported: Option<(usize, usize, &'static str)>,
}

/// A lexical error: message and the byte range it is about.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScanError {
    pub message: String,
    pub hint: Option<String>,
    /// For a mismatched closing bracket: where the opening one is.
    pub open_at: Option<usize>,
    pub start: usize,
    pub end: usize,
}

/// Python keywords (and constructs) the `.comm` subset does not support.
const UNSUPPORTED: &[&str] = &[
    "def", "class", "while", "if", "elif", "else", "try", "except", "finally", "with", "return",
    "yield", "lambda", "global", "nonlocal", "del", "pass", "break", "continue", "raise", "assert",
    "async", "await", "and", "or", "not", "is",
];

/// The logical lines before the first lexical error, and that error if any. Lines are
/// returned even when an error follows so that earlier syntax errors are reported first.
pub fn scan(text: &str) -> (Vec<LogicalLine>, Option<ScanError>) {
    let b = text.as_bytes();
    let n = b.len();
    let mut lines = Vec::new();
    let mut i = 0;
    while i < n {
        // Indentation of a new physical line.
        let mut indent = 0;
        while i < n && matches!(b[i], b' ' | b'\t' | b'\x0C') {
            indent = if b[i] == b'\t' {
                (indent / 8 + 1) * 8
            } else {
                indent + 1
            };
            i += 1;
        }
        if i >= n {
            break;
        }
        match b[i] {
            b'\n' | b'\r' => {
                i += 1;
                continue;
            }
            b'#' => {
                while i < n && b[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            _ => {}
        }
        let start = i;
        let mut stack: Vec<(u8, usize)> = Vec::new();
        let mut unsupported = None;
        let mut end = n;
        while i < n {
            let c = b[i];
            match c {
                b'#' => {
                    while i < n && b[i] != b'\n' {
                        i += 1;
                    }
                }
                b'\'' | b'"' => match skip_string(b, i) {
                    Ok(next) => i = next,
                    Err(e) => {
                        return (lines, Some(e));
                    }
                },
                b'(' | b'[' | b'{' => {
                    if c == b'{' && unsupported.is_none() {
                        unsupported = Some((i, i + 1, "{"));
                    }
                    stack.push((c, i));
                    if stack.len() > MAX_BRACKET_DEPTH {
                        let e = ScanError {
                open_at: None,
                            message: format!(
                                "brackets are nested too deeply (more than {MAX_BRACKET_DEPTH} levels)"
                            ),
                            hint: None,
                            start: i,
                            end: i + 1,
                        };
                        return (lines, Some(e));
                    }
                    i += 1;
                }
                b')' | b']' | b'}' => {
                    let open = match c {
                        b')' => b'(',
                        b']' => b'[',
                        _ => b'{',
                    };
                    match stack.pop() {
                        Some((o, _)) if o == open => {}
                        Some((o, at)) => {
                            let e = ScanError {
                                open_at: Some(at),
                                message: format!(
                                    "closing '{}' does not match '{}'",
                                    c as char, o as char
                                ),
                                hint: None,
                                start: i,
                                end: i + 1,
                            };
                            return (lines, Some(e));
                        }
                        None => {
                            let e = ScanError {
                                open_at: None,
                                message: format!("unmatched '{}'", c as char),
                                hint: None,
                                start: i,
                                end: i + 1,
                            };
                            return (lines, Some(e));
                        }
                    }
                    i += 1;
                }
                b'\\' if b.get(i + 1) == Some(&b'\n') => i += 2,
                b'\\' if b.get(i + 1) == Some(&b'\r') && b.get(i + 2) == Some(&b'\n') => i += 3,
                b'\n' if stack.is_empty() => {
                    end = i;
                    i += 1;
                    break;
                }
                c if c.is_ascii_alphabetic() || c == b'_' => {
                    let s = i;
                    while i < n && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                        i += 1;
                    }
                    // A name right after a digit or a dot is part of a number or an
                    // attribute (`1.e4`, `math.pi`), never a keyword.
                    let after_dot = s > 0 && (b[s - 1] == b'.' || b[s - 1].is_ascii_digit());
                    if unsupported.is_none() && !after_dot && b.get(i) != Some(&b'=') {
                        if let Some(k) = UNSUPPORTED.iter().find(|k| k.as_bytes() == &b[s..i]) {
                            unsupported = Some((s, i, *k));
                        }
                    }
                }
                c if c.is_ascii_digit() => {
                    while i < n && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                        i += 1;
                    }
                }
                _ => i += 1,
            }
        }
        if let Some(&(o, at)) = stack.last() {
            let e = ScanError {
                open_at: None,
                message: format!("'{}' was never closed", o as char),
                hint: Some("add the closing bracket".into()),
                start: at,
                end: at + 1,
            };
            return (lines, Some(e));
        }
        lines.push(LogicalLine {
            start,
            end,
            indent,
            unsupported,
        });
    }
    (lines, None)
}

/// Skips the string literal starting at `i` (a quote); returns the index after it.
fn skip_string(b: &[u8], i: usize) -> Result<usize, ScanError> {
    let q = b[i];
    let triple = b.get(i + 1) == Some(&q) && b.get(i + 2) == Some(&q);
    let mut j = if triple { i + 3 } else { i + 1 };
    while j < b.len() {
        let c = b[j];
        if c == b'\\' {
            j += 2;
            continue;
        }
        if triple {
            if c == q && b.get(j + 1) == Some(&q) && b.get(j + 2) == Some(&q) {
                return Ok(j + 3);
            }
        } else if c == q {
            return Ok(j + 1);
        } else if c == b'\n' {
            break;
        }
        j += 1;
    }
    Err(ScanError {
        open_at: None,
        message: "unterminated string".into(),
        hint: Some(format!("close it with {}", q as char)),
        start: i,
        end: i + if triple { 3 } else { 1 },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(src: &str) -> Vec<(String, usize)> {
        let (lines, err) = scan(src);
        assert!(err.is_none(), "{err:?}");
        lines
            .iter()
            .map(|l| (src[l.start..l.end].to_string(), l.indent))
            .collect()
    }

    #[test]
    fn splits_on_newlines_outside_brackets_only() {
        let got = texts("A=F(X=1,\n  Y=2)\n\n# c\n  B = 1 \\\n + 2\nC=3");
        assert_eq!(
            got,
            vec![
                ("A=F(X=1,\n  Y=2)".to_string(), 0),
                ("B = 1 \\\n + 2".to_string(), 2),
                ("C=3".to_string(), 0)
            ]
        );
    }

    #[test]
    fn tabs_indent_to_multiples_of_eight() {
        assert_eq!(texts("\tA=1\n  \tB=1")[1].1, 8);
        assert_eq!(texts("\tA=1")[0].1, 8);
    }

    #[test]
    fn strings_hide_brackets_and_comments() {
        let got = texts("A='(#'\nB=\"\"\"x\n)\"\"\"\n");
        assert_eq!(got.len(), 2);
    }

    #[test]
    fn lexical_errors() {
        let (_, e) = scan("A=F(1,\nB=2");
        let e = e.unwrap();
        assert_eq!((e.message.as_str(), e.start), ("'(' was never closed", 3));
        let (_, e) = scan("A=(1]");
        assert_eq!(e.unwrap().message, "closing ']' does not match '('");
        let (_, e) = scan("A=1)");
        assert_eq!(e.unwrap().start, 3);
        let (lines, e) = scan("A=1\nB='abc\n");
        assert_eq!(lines.len(), 1);
        assert_eq!(e.unwrap().start, 6);
    }

    #[test]
    fn finds_unsupported_keywords_but_not_keyword_arguments() {
        let (lines, _) = scan("while x: pass\nF(if=1)\nx = math.if_\n");
        assert_eq!(lines[0].unsupported, Some((0, 5, "while")));
        assert_eq!(lines[1].unsupported, None);
        assert_eq!(lines[2].unsupported, None);
    }
}
