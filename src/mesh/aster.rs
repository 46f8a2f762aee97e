//! Reader of the Code_Aster native mesh format (`.mail`).
//!
//! A file is a sequence of blocks, each opened by a keyword line and closed by `FINSF`,
//! and the file ends with `FIN`:
//!
//! ```text
//! TITRE            free text                      FINSF
//! COOR_3D          N1 x y z  (one node per entry)  FINSF   (COOR_2D, COOR_1D likewise)
//! SEG2             M1 N1 N2  (one cell per entry)  FINSF   (any cell type of CellKind)
//! GROUP_NO NOM=G   members...                      FINSF   (or: GROUP_NO / G members...)
//! GROUP_MA         G members...                    FINSF
//! FIN
//! ```
//!
//! `%` starts a comment; keywords are case-insensitive, names are kept as written.
//! An entry (node or cell) starts on a new line and may continue over the next lines, but
//! ends at a line end: that is what lets us tell a cell with a missing node from a wrapped
//! one. Blocks may come in any order, so references (cell nodes, group members) are
//! resolved once the whole file has been read; nothing half-read is ever returned.

use super::{Cell, CellKind, Group, Mesh, Node};
use crate::error::{Error, Result};
use std::collections::{HashMap, HashSet};
use std::path::Path;

/// Read a `.mail` file.
pub fn read_file(path: &Path) -> Result<Mesh> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::input(format!("cannot read the mesh file {}: {e}", path.display())))?;
    parse(&text, &path.display().to_string())
}

/// A word of the file and the 1-based line it is on.
#[derive(Clone, Debug)]
struct Tok<'a> {
    text: &'a str,
    line: usize,
}

/// The words of each non-empty line, comments removed.
fn lines_of(text: &str) -> Vec<Vec<Tok<'_>>> {
    text.lines()
        .enumerate()
        .map(|(i, raw)| {
            let code = raw.split('%').next().unwrap_or("");
            code.split_whitespace()
                .map(|w| Tok {
                    text: w,
                    line: i + 1,
                })
                .collect::<Vec<_>>()
        })
        .filter(|l| !l.is_empty())
        .collect()
}

/// The cell kind a block keyword names, if any.
fn cell_kind(word: &str) -> Option<CellKind> {
    CellKind::from_aster_name(word)
}

fn coor_dim(kw: &str) -> Option<usize> {
    match kw {
        "COOR_1D" => Some(1),
        "COOR_2D" => Some(2),
        "COOR_3D" => Some(3),
        _ => None,
    }
}

fn is_block_keyword(word: &str) -> bool {
    let w = word.to_ascii_uppercase();
    matches!(
        w.as_str(),
        "FIN" | "FINSF" | "TITRE" | "COOR_1D" | "COOR_2D" | "COOR_3D" | "GROUP_NO" | "GROUP_MA"
    ) || cell_kind(word).is_some()
}

/// A cell as read, before its node names are resolved.
struct RawCell<'a> {
    name: Tok<'a>,
    kind: CellKind,
    nodes: Vec<Tok<'a>>,
}

/// A group as read, before its member names are resolved.
struct RawGroup<'a> {
    name: Tok<'a>,
    members: Vec<Tok<'a>>,
}

/// Everything read from the file, names unresolved.
#[derive(Default)]
struct Raw<'a> {
    dim: usize,
    nodes: Vec<Node>,
    node_lines: Vec<usize>,
    cells: Vec<RawCell<'a>>,
    node_groups: Vec<RawGroup<'a>>,
    cell_groups: Vec<RawGroup<'a>>,
}

/// Parse the text of a `.mail` file; `file` names it in error messages.
pub fn parse(text: &str, file: &str) -> Result<Mesh> {
    // A file saved by an editor with a UTF-8 byte order mark reads as without one.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let lines = lines_of(text);
    let err = |msg: String, line: usize| Error::input(msg).at_line(file, line);
    let mut raw = Raw::default();
    let mut i = 0;
    let mut saw_fin = false;
    while i < lines.len() {
        let head = &lines[i];
        let kw_tok = &head[0];
        let kw = kw_tok.text.to_ascii_uppercase();
        if kw == "FIN" {
            saw_fin = true;
            break;
        }
        let is_group = kw == "GROUP_NO" || kw == "GROUP_MA";
        let kind = cell_kind(&kw);
        let known = is_group || kind.is_some() || kw == "TITRE" || coor_dim(&kw).is_some();
        if !known {
            return Err(err(
                format!("unknown cell type or block keyword '{}'", kw_tok.text),
                kw_tok.line,
            )
            .hint(format!(
                "blocks are TITRE, COOR_1D/2D/3D, GROUP_NO, GROUP_MA and the cell types {}",
                CellKind::ALL.map(|k| k.aster_name()).join(", ")
            )));
        }
        // The block body: the lines up to the FINSF line (FINSF alone on its line or as
        // the last word of a line).
        let (mut body, next) = block_body(&lines, i, file)?;
        let (attrs, free) = header_attrs(&head[1..], file)?;
        if kw != "TITRE" && !free.is_empty() {
            if is_group {
                // `GROUP_NO G1 N1 N2`: the name (and members) may start on the header line.
                body.insert(0, free);
            } else {
                return Err(err(
                    format!(
                        "unexpected '{}' after {}: entries start on the next line",
                        free[0].text, kw
                    ),
                    free[0].line,
                ));
            }
        }
        if let Some(d) = coor_dim(&kw) {
            raw.dim = raw.dim.max(d);
            read_coords(&body, d, &kw, file, &mut raw)?;
        } else if is_group {
            let g = read_group(&body, &attrs, &kw, kw_tok.line, file)?;
            if kw == "GROUP_NO" {
                raw.node_groups.push(g);
            } else {
                raw.cell_groups.push(g);
            }
        } else if let Some(kind) = kind {
            read_cells(&body, kind, file, &mut raw)?;
        }
        i = next;
    }
    if !saw_fin {
        let last = lines.last().and_then(|l| l.last()).map_or(1, |t| t.line);
        return Err(err("the mesh file ends without FIN".into(), last)
            .hint("the file looks truncated: a Code_Aster mesh file ends with the line FIN"));
    }
    resolve(raw, file)
}

/// Lines of the block opened at `lines[start]` (header excluded, FINSF excluded) and the
/// index of the line after its FINSF.
fn block_body<'a>(
    lines: &[Vec<Tok<'a>>],
    start: usize,
    file: &str,
) -> Result<(Vec<Vec<Tok<'a>>>, usize)> {
    let head = &lines[start][0];
    let is_titre = head.text.eq_ignore_ascii_case("TITRE");
    // FINSF on the header line itself closes an empty block.
    if lines[start][1..]
        .iter()
        .any(|t| t.text.eq_ignore_ascii_case("FINSF"))
    {
        return Ok((Vec::new(), start + 1));
    }
    let mut body = Vec::new();
    for (j, line) in lines.iter().enumerate().skip(start + 1) {
        if let Some(pos) = line
            .iter()
            .position(|t| t.text.eq_ignore_ascii_case("FINSF"))
        {
            if pos > 0 {
                body.push(line[..pos].to_vec());
            }
            return Ok((body, j + 1));
        }
        // The file's own end closes an open block: Code_Aster reads up to FIN, and some
        // of its own meshes (sdnd100c's) end their last block so.
        if !is_titre && line.len() == 1 && line[0].text.eq_ignore_ascii_case("FIN") {
            return Ok((body, j));
        }
        // A block keyword at the start of a line inside a data block means the FINSF of
        // this block was forgotten (TITRE text is free, so it is exempt).
        if !is_titre && is_block_keyword(line[0].text) {
            return Err(Error::input(format!(
                "block {} opened at line {} has no FINSF before '{}'",
                head.text.to_ascii_uppercase(),
                head.line,
                line[0].text
            ))
            .at_line(file, line[0].line)
            .hint("close every block with a line FINSF"));
        }
        body.push(line.clone());
    }
    let last = lines
        .last()
        .and_then(|l| l.last())
        .map_or(head.line, |t| t.line);
    Err(Error::input(format!(
        "block {} opened at line {} has no FINSF: the file ends first",
        head.text.to_ascii_uppercase(),
        head.line
    ))
    .at_line(file, last)
    .hint("the file looks truncated: close every block with FINSF and end the file with FIN"))
}

/// `KEY=VALUE` attributes of a header line (`GROUP_NO NOM=G1`); `KEY = VALUE` is accepted.
type Attrs<'a> = (HashMap<String, Tok<'a>>, Vec<Tok<'a>>);

/// Also returns the free words (not `KEY=VALUE`) of the header line.
fn header_attrs<'a>(words: &[Tok<'a>], file: &str) -> Result<Attrs<'a>> {
    let joined: Vec<Tok<'a>> = words.to_vec();
    let mut attrs = HashMap::new();
    let mut free = Vec::new();
    let mut k = 0;
    while k < joined.len() {
        let w = &joined[k];
        if let Some((key, val)) = w.text.split_once('=') {
            let (val, step) = if val.is_empty() {
                (joined.get(k + 1).map(|t| t.text), 2)
            } else {
                (Some(val), 1)
            };
            let val = val.ok_or_else(|| {
                Error::input(format!("attribute {key}= has no value")).at_line(file, w.line)
            })?;
            attrs.insert(
                key.to_ascii_uppercase(),
                Tok {
                    text: val,
                    line: w.line,
                },
            );
            k += step;
        } else if joined.get(k + 1).is_some_and(|t| t.text.starts_with('=')) {
            // `KEY =VALUE` or `KEY = VALUE`
            let rest = &joined[k + 1].text[1..];
            let (val, step) = if rest.is_empty() {
                (joined.get(k + 2).map(|t| t.text), 3)
            } else {
                (Some(rest), 2)
            };
            let val = val.ok_or_else(|| {
                Error::input(format!("attribute {}= has no value", w.text)).at_line(file, w.line)
            })?;
            attrs.insert(
                w.text.to_ascii_uppercase(),
                Tok {
                    text: val,
                    line: w.line,
                },
            );
            k += step;
        } else if w.text.eq_ignore_ascii_case("FINSF") {
            break;
        } else {
            free.push(w.clone());
            k += 1;
        }
    }
    Ok((attrs, free))
}

/// Split a block body into entries of exactly `size` words. An entry starts on a new line
/// and takes whole lines until it has `size` words.
fn entries<'a>(
    body: &[Vec<Tok<'a>>],
    size: usize,
    what: &str,
    expected: &str,
    file: &str,
) -> Result<Vec<Vec<Tok<'a>>>> {
    let mut out = Vec::new();
    let mut cur: Vec<Tok<'a>> = Vec::new();
    for line in body {
        cur.extend(line.iter().cloned());
        if cur.len() >= size {
            if cur.len() > size {
                let first = &cur[0];
                return Err(Error::input(format!(
                    "{what} {}: expected {expected}, found {} words",
                    first.text,
                    cur.len() - 1
                ))
                .at_line(file, first.line)
                .hint(
                    "an entry starts on a new line and may continue on the next lines, \
                     but must end at a line end",
                ));
            }
            out.push(std::mem::take(&mut cur));
        }
    }
    if let Some(first) = cur.first() {
        return Err(Error::input(format!(
            "{what} {}: expected {expected}, found {} words before FINSF",
            first.text,
            cur.len() - 1
        ))
        .at_line(file, first.line));
    }
    Ok(out)
}

fn parse_real(tok: &Tok<'_>, file: &str) -> Result<f64> {
    // Fortran writes exponents with D (1.0D+00).
    let t = tok.text.replace(['D', 'd'], "E");
    match t.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(Error::input(format!("'{}' is not a number", tok.text)).at_line(file, tok.line)),
    }
}

fn read_coords(
    body: &[Vec<Tok<'_>>],
    d: usize,
    kw: &str,
    file: &str,
    raw: &mut Raw<'_>,
) -> Result<()> {
    let expected = format!("{d} coordinate(s) after the node name ({kw})");
    for e in entries(body, d + 1, "node", &expected, file)? {
        let mut coords = [0.0; 3];
        for (c, tok) in coords.iter_mut().zip(&e[1..]) {
            *c = parse_real(tok, file)?;
        }
        raw.nodes.push(Node {
            name: e[0].text.to_string(),
            coords,
        });
        raw.node_lines.push(e[0].line);
    }
    Ok(())
}

fn read_cells<'a>(
    body: &[Vec<Tok<'a>>],
    kind: CellKind,
    file: &str,
    raw: &mut Raw<'a>,
) -> Result<()> {
    let n = kind.node_count();
    let expected = format!("{n} node name(s) for a {}", kind.aster_name());
    for mut e in entries(
        body,
        n + 1,
        &format!("{} cell", kind.aster_name()),
        &expected,
        file,
    )? {
        let nodes = e.split_off(1);
        raw.cells.push(RawCell {
            name: e.remove(0),
            kind,
            nodes,
        });
    }
    Ok(())
}

fn read_group<'a>(
    body: &[Vec<Tok<'a>>],
    attrs: &HashMap<String, Tok<'a>>,
    kw: &str,
    line: usize,
    file: &str,
) -> Result<RawGroup<'a>> {
    let mut words = body.iter().flatten().cloned();
    let name = match attrs.get("NOM") {
        Some(t) => t.clone(),
        None => words.next().ok_or_else(|| {
            Error::input(format!("{kw} block without a group name"))
                .at_line(file, line)
                .hint(format!(
                    "write `{kw} NOM=NAME` or put the name first in the block"
                ))
        })?,
    };
    Ok(RawGroup {
        name,
        members: words.collect(),
    })
}

/// Check names, resolve references and build the mesh.
fn resolve(raw: Raw<'_>, file: &str) -> Result<Mesh> {
    let dup = |what: &str, name: &str, line: usize, first: usize| {
        Error::input(format!(
            "{what} {name} is defined twice (first at line {first})"
        ))
        .at_line(file, line)
    };
    let mut node_idx: HashMap<&str, usize> = HashMap::new();
    for (i, n) in raw.nodes.iter().enumerate() {
        if let Some(&first) = node_idx.get(n.name.as_str()) {
            return Err(dup(
                "node",
                &n.name,
                raw.node_lines[i],
                raw.node_lines[first],
            ));
        }
        node_idx.insert(&n.name, i);
    }
    let undefined_node = |t: &Tok<'_>, ctx: String| {
        Error::input(format!(
            "node {} ({ctx}) is not defined in a COOR block",
            t.text
        ))
        .at_line(file, t.line)
    };
    let mut cell_idx: HashMap<&str, usize> = HashMap::new();
    let mut cells = Vec::with_capacity(raw.cells.len());
    for (i, c) in raw.cells.iter().enumerate() {
        if let Some(&first) = cell_idx.get(c.name.text) {
            return Err(dup(
                "cell",
                c.name.text,
                c.name.line,
                raw.cells[first].name.line,
            ));
        }
        cell_idx.insert(c.name.text, i);
        let nodes = c
            .nodes
            .iter()
            .map(|t| {
                node_idx
                    .get(t.text)
                    .copied()
                    .ok_or_else(|| undefined_node(t, format!("of cell {}", c.name.text)))
            })
            .collect::<Result<Vec<_>>>()?;
        cells.push(Cell {
            name: c.name.text.to_string(),
            kind: c.kind,
            nodes,
        });
    }
    let node_groups = resolve_groups(&raw.node_groups, "GROUP_NO", file, |t, g| {
        node_idx
            .get(t.text)
            .copied()
            .ok_or_else(|| undefined_node(t, format!("member of GROUP_NO {g}")))
    })?;
    let cell_groups = resolve_groups(&raw.cell_groups, "GROUP_MA", file, |t, g| {
        cell_idx.get(t.text).copied().ok_or_else(|| {
            Error::input(format!(
                "cell {} (member of GROUP_MA {g}) is not defined in a cell block",
                t.text
            ))
            .at_line(file, t.line)
        })
    })?;
    Ok(Mesh {
        dim: raw.dim,
        nodes: raw.nodes,
        cells,
        node_groups,
        cell_groups,
    })
}

fn resolve_groups(
    raw: &[RawGroup<'_>],
    kw: &str,
    file: &str,
    find: impl Fn(&Tok<'_>, &str) -> Result<usize>,
) -> Result<Vec<Group>> {
    let mut seen: HashMap<&str, usize> = HashMap::new();
    let mut out = Vec::with_capacity(raw.len());
    for g in raw {
        if let Some(first) = seen.get(g.name.text) {
            return Err(Error::input(format!(
                "{kw} {} is defined twice (first at line {first})",
                g.name.text
            ))
            .at_line(file, g.name.line));
        }
        seen.insert(g.name.text, g.name.line);
        // A member listed twice is kept once, at its first place.
        let mut members = Vec::with_capacity(g.members.len());
        let mut in_group = HashSet::new();
        for t in &g.members {
            let m = find(t, g.name.text)?;
            if in_group.insert(m) {
                members.push(m);
            }
        }
        out.push(Group {
            name: g.name.text.to_string(),
            members,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str =
        "TITRE\n t\nFINSF\nCOOR_3D\n N1 0 0 0\n N2 1 0 0\nFINSF\nSEG2\n M1 N1 N2\nFINSF\nFIN\n";

    /// Parse `text`, expect an error and return (line, message).
    fn fails(text: &str) -> (usize, String) {
        let e = parse(text, "t.mail").expect_err("the file should be refused");
        assert_eq!(e.kind, crate::error::ErrorKind::Input);
        let loc = e.location.clone().expect("errors carry a location");
        assert_eq!(loc.file, "t.mail");
        (loc.span.line, e.to_string())
    }

    #[test]
    fn a_byte_order_mark_is_accepted_and_coordinates_must_be_finite() {
        let m = parse(&format!("\u{feff}{GOOD}"), "t.mail").unwrap();
        assert_eq!(m.nodes.len(), 2);
        let (line, msg) = fails(&GOOD.replace("N2 1 0 0", "N2 nan 0 0"));
        assert_eq!(line, 6, "{msg}");
    }

    #[test]
    fn good_file_reads() {
        let m = parse(GOOD, "t.mail").unwrap();
        assert_eq!(m.dim, 3);
        assert_eq!(m.nodes.len(), 2);
        assert_eq!(m.cells[0].nodes, vec![0, 1]);
        assert_eq!(m.cells[0].kind, CellKind::Seg2);
    }

    #[test]
    fn group_order_is_kept_and_repeats_dropped() {
        let t = "COOR_2D\n A 0 0\n B 1 0\n C 2 0\nFINSF\nGROUP_NO NOM=G\n C A\n C B\nFINSF\nFIN\n";
        let m = parse(t, "t.mail").unwrap();
        assert_eq!(m.node_group("G").unwrap().members, vec![2, 0, 1]);
        assert_eq!(m.dim, 2);
    }

    #[test]
    fn blocks_may_reference_later_blocks() {
        let t = "GROUP_MA\n G M1\nFINSF\nSEG2\n M1 N1 N2\nFINSF\nCOOR_3D\n N1 0 0 0\n N2 1 0 0\nFINSF\nFIN\n";
        let m = parse(t, "t.mail").unwrap();
        assert_eq!(m.cell_group("G").unwrap().members, vec![0]);
    }

    #[test]
    fn missing_fin_is_truncation() {
        let (line, msg) = fails(&GOOD.replace("FIN\n", ""));
        assert_eq!(line, 10);
        assert!(msg.contains("without FIN"), "{msg}");
    }

    #[test]
    fn missing_finsf_at_end_of_file() {
        let (line, msg) = fails("COOR_3D\n N1 0 0 0\n N2 1 0 0\n");
        assert_eq!(line, 3);
        assert!(
            msg.contains("COOR_3D opened at line 1 has no FINSF"),
            "{msg}"
        );
    }

    #[test]
    fn fin_closes_the_last_block() {
        let m = parse(
            "COOR_3D\n N1 0 0 0\n N2 1 0 0\nFINSF\nPOI1\n E1 N1\n E2 N2\nFIN\n",
            "t.mail",
        )
        .unwrap();
        assert_eq!(m.nodes.len(), 2);
        assert_eq!(m.cells.len(), 2);
    }

    #[test]
    fn missing_finsf_before_next_block() {
        let (line, msg) = fails("COOR_3D\n N1 0 0 0\nSEG2\n M1 N1 N1\nFINSF\nFIN\n");
        assert_eq!(line, 3);
        assert!(msg.contains("no FINSF before 'SEG2'"), "{msg}");
    }

    #[test]
    fn unknown_cell_type() {
        let (line, msg) = fails(&GOOD.replace("SEG2", "SEG7"));
        assert_eq!(line, 8);
        assert!(
            msg.contains("unknown cell type or block keyword 'SEG7'"),
            "{msg}"
        );
    }

    #[test]
    fn undefined_node_in_cell() {
        let (line, msg) = fails(&GOOD.replace("M1 N1 N2", "M1 N1\n N9"));
        assert_eq!(line, 10);
        assert!(msg.contains("node N9 (of cell M1) is not defined"), "{msg}");
    }

    #[test]
    fn undefined_node_in_group() {
        let (line, msg) = fails(&GOOD.replace("FIN\n", "GROUP_NO\n G\n N1 N7\nFINSF\nFIN\n"));
        assert_eq!(line, 13);
        assert!(msg.contains("node N7 (member of GROUP_NO G)"), "{msg}");
    }

    #[test]
    fn undefined_cell_in_group() {
        let (line, msg) = fails(&GOOD.replace("FIN\n", "GROUP_MA NOM=G\n M2\nFINSF\nFIN\n"));
        assert_eq!(line, 12);
        assert!(msg.contains("cell M2 (member of GROUP_MA G)"), "{msg}");
    }

    #[test]
    fn duplicate_node() {
        let (line, msg) = fails(&GOOD.replace(" N2 1 0 0", " N1 1 0 0"));
        assert_eq!(line, 6);
        assert!(
            msg.contains("node N1 is defined twice (first at line 5)"),
            "{msg}"
        );
    }

    #[test]
    fn duplicate_cell() {
        let (line, msg) = fails(&GOOD.replace(" M1 N1 N2\n", " M1 N1 N2\n M1 N2 N1\n"));
        assert_eq!(line, 10);
        assert!(
            msg.contains("cell M1 is defined twice (first at line 9)"),
            "{msg}"
        );
    }

    #[test]
    fn duplicate_group() {
        let extra = "GROUP_NO\n G N1\nFINSF\nGROUP_NO NOM=G\n N2\nFINSF\nFIN\n";
        let (line, msg) = fails(&GOOD.replace("FIN\n", extra));
        assert_eq!(line, 14);
        assert!(
            msg.contains("GROUP_NO G is defined twice (first at line 12)"),
            "{msg}"
        );
    }

    #[test]
    fn too_many_nodes_for_cell() {
        let (line, msg) = fails(&GOOD.replace("M1 N1 N2", "M1 N1 N2 N1"));
        assert_eq!(line, 9);
        assert!(
            msg.contains("SEG2 cell M1: expected 2 node name(s)"),
            "{msg}"
        );
    }

    #[test]
    fn too_few_nodes_before_finsf() {
        let (line, msg) = fails(&GOOD.replace("M1 N1 N2", "M1 N1"));
        assert_eq!(line, 9);
        assert!(msg.contains("found 1 words before FINSF"), "{msg}");
    }

    #[test]
    fn too_few_nodes_then_next_entry() {
        // M1 lacks a node; M2 on the next line must not be taken for it silently.
        let (line, msg) = fails(&GOOD.replace("M1 N1 N2", "M1 N1\n M2 N1 N2"));
        assert_eq!(line, 9);
        assert!(msg.contains("SEG2 cell M1"), "{msg}");
    }

    #[test]
    fn bad_number() {
        let (line, msg) = fails(&GOOD.replace("N2 1 0 0", "N2 1 0,5 0"));
        assert_eq!(line, 6);
        assert!(msg.contains("'0,5' is not a number"), "{msg}");
        let (line, msg) = fails(&GOOD.replace("N2 1 0 0", "N2 1 x 0"));
        assert_eq!(line, 6);
        assert!(msg.contains("'x' is not a number"), "{msg}");
    }

    #[test]
    fn entry_on_header_line_is_refused() {
        let (line, msg) = fails(&GOOD.replace("COOR_3D\n", "COOR_3D N0 0 0 0\n"));
        assert_eq!(line, 4);
        assert!(msg.contains("entries start on the next line"), "{msg}");
    }
}
