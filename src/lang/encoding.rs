//! The bytes of a command file as text. Older French studies are in Latin-1: Python 2, which
//! Code_Aster used until its version 14, read them when their first or second line declared
//! it (`# -*- coding: latin-1 -*-`, PEP 263). Rules, in order:
//!
//! - a coding line naming UTF-8, Latin-1 (ISO-8859-1), ISO-8859-15 or Windows-1252 (cp1252)
//!   decodes the file so; a UTF-8 file that is not valid UTF-8 is an error at the first bad
//!   byte (file, line, column); another encoding is an error naming the ones we read;
//! - without a coding line, valid UTF-8 is UTF-8 (the case of every current file); anything
//!   else is decoded as Windows-1252 (Latin-1 with the letters French text uses in
//!   0x80–0x9F, such as œ and €) with a note saying where the first non-UTF-8 byte is and
//!   how to declare the encoding. Windows-1252's five unassigned bytes read as Latin-1.
//!
//! Columns count characters.

use crate::error::{Error, ErrorKind, Result};
use crate::value::Span;

/// A decoded command file, and the note to print when its encoding was guessed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Decoded {
    pub text: String,
    pub note: Option<String>,
}

/// The encodings a coding line may name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Utf8,
    Latin1,
    Latin9,
    Cp1252,
}

/// Decode the bytes of the file `file` (its name in messages).
pub fn decode(bytes: &[u8], file: &str) -> Result<Decoded> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let encoding = declared(bytes, file)?;
    match encoding {
        Some(Encoding::Utf8) | None => match std::str::from_utf8(bytes) {
            Ok(text) => Ok(Decoded {
                text: text.to_string(),
                note: None,
            }),
            Err(e) => {
                let at = e.valid_up_to();
                let (line, col) = line_col(bytes, at);
                let byte = bytes.get(at).copied().unwrap_or(0);
                if encoding.is_some() {
                    return Err(Error::new(
                        ErrorKind::Syntax,
                        format!(
                            "byte 0x{byte:02X} is not UTF-8, though the file declares \
                             coding: utf-8"
                        ),
                    )
                    .at(file, span(at, line, col))
                    .hint(
                        "save the file as UTF-8 (e.g. `iconv -f latin1 -t utf-8`), or, if it \
                         is a Latin-1 file, make its coding line say latin-1",
                    ));
                }
                Ok(Decoded {
                    text: bytes.iter().map(|&b| cp1252(b)).collect(),
                    note: Some(format!(
                        "{file}:{line}:{col}: byte 0x{byte:02X} is not UTF-8 and the file \
                         declares no encoding: read as Latin-1 (Windows-1252), as an older \
                         French study usually is; put `# -*- coding: latin-1 -*-` on its \
                         first line to say so, or save it as UTF-8"
                    )),
                })
            }
        },
        Some(Encoding::Latin1) => Ok(Decoded {
            text: bytes.iter().map(|&b| char::from(b)).collect(),
            note: None,
        }),
        Some(Encoding::Latin9) => Ok(Decoded {
            text: bytes.iter().map(|&b| latin9(b)).collect(),
            note: None,
        }),
        Some(Encoding::Cp1252) => Ok(Decoded {
            text: bytes.iter().map(|&b| cp1252(b)).collect(),
            note: None,
        }),
    }
}

/// The encoding a coding line of the first two lines declares (PEP 263:
/// `coding[:=]\s*([-\w.]+)` on a comment line), `None` without one.
fn declared(bytes: &[u8], file: &str) -> Result<Option<Encoding>> {
    let mut offset = 0;
    for (i, line) in bytes.split(|&b| b == b'\n').take(2).enumerate() {
        let here = offset;
        offset += line.len() + 1;
        // The line is ASCII up to the name in any file that declares an encoding; the rest
        // may be anything, so it is read lossily.
        let text = String::from_utf8_lossy(line);
        let Some(comment) = text.trim_start().strip_prefix('#') else {
            continue;
        };
        let Some(pos) = comment.find("coding") else {
            continue;
        };
        let rest = &comment[pos + "coding".len()..];
        let Some(rest) = rest.strip_prefix([':', '=']) else {
            continue;
        };
        let name: String = rest
            .trim_start()
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
            .collect();
        let norm = name.to_ascii_lowercase().replace('_', "-");
        let enc = match norm.as_str() {
            "utf-8" | "utf8" | "utf-8-sig" => Encoding::Utf8,
            "latin-1" | "latin1" | "iso-8859-1" | "iso8859-1" | "l1" | "iso-latin-1" => {
                Encoding::Latin1
            }
            "latin-9" | "latin9" | "iso-8859-15" | "iso8859-15" | "l9" => Encoding::Latin9,
            "cp1252" | "windows-1252" => Encoding::Cp1252,
            _ => {
                let col = text
                    .find(name.as_str())
                    .map_or(1, |c| text[..c].chars().count() + 1);
                return Err(Error::new(
                    ErrorKind::Syntax,
                    format!("the file declares coding: {name}, which aster-nl does not read"),
                )
                .at(file, span(here, i + 1, col))
                .hint("aster-nl reads utf-8, latin-1 (iso-8859-1), iso-8859-15 and cp1252"));
            }
        };
        return Ok(Some(enc));
    }
    Ok(None)
}

/// 1-based line and character column of byte `at` (characters read as UTF-8 up to it,
/// which they are: `at` is where valid UTF-8 ends).
fn line_col(bytes: &[u8], at: usize) -> (usize, usize) {
    let before = &bytes[..at];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    let col = String::from_utf8_lossy(&before[start..]).chars().count() + 1;
    (line, col)
}

fn span(start: usize, line: usize, col: usize) -> Span {
    Span {
        start,
        end: start + 1,
        line,
        col,
    }
}

/// Windows-1252: Latin-1 but for 0x80–0x9F (the unassigned 0x81, 0x8D, 0x8F, 0x90 and 0x9D
/// read as Latin-1's control characters, as the WHATWG decoder does).
fn cp1252(b: u8) -> char {
    const HIGH: [char; 32] = [
        '€', '\u{81}', '‚', 'ƒ', '„', '…', '†', '‡', 'ˆ', '‰', 'Š', '‹', 'Œ', '\u{8D}', 'Ž',
        '\u{8F}', '\u{90}', '‘', '’', '“', '”', '•', '–', '—', '˜', '™', 'š', '›', 'œ', '\u{9D}',
        'ž', 'Ÿ',
    ];
    match b {
        0x80..=0x9F => HIGH[usize::from(b - 0x80)],
        _ => char::from(b),
    }
}

/// ISO-8859-15: Latin-1 but for eight letters and the euro sign.
fn latin9(b: u8) -> char {
    match b {
        0xA4 => '€',
        0xA6 => 'Š',
        0xA8 => 'š',
        0xB4 => 'Ž',
        0xB8 => 'ž',
        0xBC => 'Œ',
        0xBD => 'œ',
        0xBE => 'Ÿ',
        _ => char::from(b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf8_is_read_as_is() {
        let d = decode("# é\nA = 1\n".as_bytes(), "f.comm").unwrap();
        assert_eq!(d.text, "# é\nA = 1\n");
        assert_eq!(d.note, None);
        // A byte-order mark is dropped.
        let d = decode(b"\xEF\xBB\xBFA = 1\n", "f.comm").unwrap();
        assert_eq!(d.text, "A = 1\n");
    }

    #[test]
    fn a_coding_line_decodes_latin1_and_its_relatives() {
        // "é" is 0xE9 in all three; 0x9C is "œ" in cp1252 only, 0xBD is "œ" in Latin-9.
        let body = b"# \xE9tude c\x9Cur \xBD\nA = 1\n";
        for (line, want) in [
            (&b"# -*- coding: latin-1 -*-\n"[..], "étude c\u{9C}ur ½"),
            (b"# -*- coding: iso-8859-1 -*-\n", "étude c\u{9C}ur ½"),
            (b"# vim: set fileencoding=cp1252 :\n", "étude cœur ½"),
            (
                b"#!/usr/bin/env python\n# coding=ISO-8859-15\n",
                "étude c\u{9C}ur œ",
            ),
        ] {
            let bytes = [line, &body[..]].concat();
            let d = decode(&bytes, "f.comm").unwrap();
            assert!(d.text.contains(want), "{line:?}: {}", d.text);
            assert_eq!(d.note, None);
        }
    }

    #[test]
    fn undeclared_latin1_is_read_with_a_note_naming_the_first_bad_byte() {
        let d = decode(b"DEBUT()\n# r\xE9sultat c\x9Cur\nFIN()\n", "old.comm").unwrap();
        assert_eq!(d.text, "DEBUT()\n# résultat cœur\nFIN()\n");
        let note = d.note.unwrap();
        assert!(
            note.starts_with("old.comm:2:4: byte 0xE9 is not UTF-8"),
            "{note}"
        );
        assert!(note.contains("# -*- coding: latin-1 -*-"), "{note}");
    }

    #[test]
    fn a_utf8_file_with_a_bad_byte_is_an_error_at_that_byte() {
        let e = decode(b"# coding: utf-8\nA = 1 # \xC3\xA9t\xE9\n", "u.comm").unwrap_err();
        let loc = e.location.unwrap();
        assert_eq!(
            (loc.file.as_str(), loc.span.line, loc.span.col),
            ("u.comm", 2, 11)
        );
        assert!(
            e.message.contains("byte 0xE9 is not UTF-8"),
            "{}",
            e.message
        );
        assert!(e.hint.unwrap().contains("latin-1"));
    }

    #[test]
    fn an_unknown_coding_is_an_error_naming_what_is_read() {
        let e = decode(b"# -*- coding: koi8-r -*-\nA = 1\n", "k.comm").unwrap_err();
        assert!(e.message.contains("coding: koi8-r"), "{}", e.message);
        let loc = e.location.unwrap();
        assert_eq!((loc.span.line, loc.span.col), (1, 15));
        assert!(e.hint.unwrap().contains("latin-1"));
        // A coding line after the second line is only a comment (PEP 263).
        let d = decode(b"A = 1\nB = 2\n# coding: koi8-r\n", "k.comm").unwrap();
        assert_eq!(d.note, None);
    }
}
