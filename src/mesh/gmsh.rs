//! Reader of Gmsh `.msh` ASCII meshes, formats 2.2 and 4.1.
//!
//! Nodes are named `N<tag>` and cells `M<tag>` (the Code_Aster convention for converted
//! meshes). Each physical group becomes a GROUP_MA (its cells, in file order) and a
//! GROUP_NO (the nodes of those cells, in order of first appearance), named by
//! `$PhysicalNames`, or `GM<tag>` / `GN<tag>` when unnamed (as Code_Aster's PRE_GMSH does).
//! Node order within a cell is kept as Gmsh writes it.

use super::{Cell, CellKind, Group, Mesh, Node};
use crate::error::{Error, Result};
use std::collections::HashMap;
use std::path::Path;

pub fn read_file(path: &Path) -> Result<Mesh> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::input(format!("cannot read the mesh file {}: {e}", path.display())))?;
    parse(&text, &path.display().to_string())
}

/// The cell kind of a Gmsh element type number.
fn kind_of(ty: i64) -> Option<CellKind> {
    Some(match ty {
        15 => CellKind::Poi1,
        1 => CellKind::Seg2,
        8 => CellKind::Seg3,
        2 => CellKind::Tria3,
        3 => CellKind::Quad4,
        4 => CellKind::Tetra4,
        5 => CellKind::Hexa8,
        6 => CellKind::Penta6,
        7 => CellKind::Pyram5,
        9 => CellKind::Tria6,
        16 => CellKind::Quad8,
        _ => return None,
    })
}

/// Topological dimension of a cell kind (a physical group lives in one dimension).
pub fn kind_dim(k: CellKind) -> usize {
    match k {
        CellKind::Poi1 => 0,
        CellKind::Seg2 | CellKind::Seg3 => 1,
        CellKind::Tria3 | CellKind::Tria6 | CellKind::Quad4 | CellKind::Quad8 => 2,
        _ => 3,
    }
}

/// A line cursor that remembers line numbers for messages.
struct Lines<'a> {
    lines: Vec<(usize, &'a str)>,
    pos: usize,
    file: &'a str,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str, file: &'a str) -> Self {
        let lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty())
            .collect();
        Lines {
            lines,
            pos: 0,
            file,
        }
    }
    fn err(&self, msg: impl Into<String>, line: usize) -> Error {
        Error::input(msg).at_line(self.file, line)
    }
    /// A tag of a node, an element or an entity: a positive integer (Gmsh numbers from 1).
    fn tag(&self, word: &str, what: &str, n: usize) -> Result<i64> {
        match word.parse::<i64>() {
            Ok(t) if t > 0 => Ok(t),
            Ok(t) => Err(self.err(format!("{what} tag {t}: tags are positive integers"), n)),
            Err(_) => Err(self.err(
                format!("{what} tag '{word}' is not a positive integer that fits in 64 bits"),
                n,
            )),
        }
    }
    fn last_line(&self) -> usize {
        self.lines.last().map_or(1, |l| l.0)
    }
    /// The next non-empty line, or an error saying which section was cut short.
    fn next(&mut self, section: &str) -> Result<(usize, &'a str)> {
        let l = self.lines.get(self.pos).copied().ok_or_else(|| {
            self.err(format!("the file ends inside ${section}"), self.last_line())
                .hint("the file looks truncated")
        })?;
        self.pos += 1;
        Ok(l)
    }
    /// The next line split into words, each parsed as `T`.
    fn nums<T: std::str::FromStr>(&mut self, section: &str, what: &str) -> Result<(usize, Vec<T>)> {
        let (n, l) = self.next(section)?;
        if l.starts_with('$') {
            return Err(self.err(
                format!("${section} ends early: expected {what}, found {l}"),
                n,
            ));
        }
        let v = l
            .split_whitespace()
            .map(|w| {
                w.parse::<T>().map_err(|_| {
                    self.err(
                        format!("${section}: '{w}' is not a valid number ({what})"),
                        n,
                    )
                })
            })
            .collect::<Result<Vec<T>>>()?;
        Ok((n, v))
    }
    /// Skip to `$End<section>`.
    fn end(&mut self, section: &str) -> Result<()> {
        let want = format!("$End{section}");
        loop {
            let (_, l) = self.next(section)?;
            if l == want {
                return Ok(());
            }
        }
    }
    /// Expect exactly `$End<section>` as the next line.
    fn expect_end(&mut self, section: &str) -> Result<()> {
        let (n, l) = self.next(section)?;
        if l != format!("$End{section}") {
            return Err(self
                .err(format!("expected $End{section}, found '{l}'"), n)
                .hint("the count at the start of the section does not match its lines"));
        }
        Ok(())
    }
}

/// Count and number-of-words checks shared by both versions.
fn need(
    l: &Lines<'_>,
    v: &[impl Sized],
    min: usize,
    n: usize,
    section: &str,
    what: &str,
) -> Result<()> {
    if v.len() < min {
        return Err(l.err(
            format!(
                "${section}: expected {what} ({min} numbers), found {}",
                v.len()
            ),
            n,
        ));
    }
    Ok(())
}

/// The blocks of a 4.1 section must add up to the total its header announces.
fn check_total(l: &Lines<'_>, found: usize, announced: i64, line: usize, what: &str) -> Result<()> {
    if found as i64 != announced {
        return Err(l.err(
            format!("the header announces {announced} {what}, the blocks hold {found}"),
            line,
        ));
    }
    Ok(())
}

/// A number of the `$Entities` section (read as reals, because of the bounding boxes) that
/// must be an integer.
fn whole(l: &Lines<'_>, v: f64, n: usize, what: &str) -> Result<i64> {
    if v.fract() == 0.0 && v.abs() < 9.0e15 {
        Ok(v as i64)
    } else {
        Err(l.err(
            format!("$Entities: {what} must be an integer, found {v}"),
            n,
        ))
    }
}

/// An entity dimension of a 4.1 block: 0 to 3.
fn entity_dim(l: &Lines<'_>, v: i64, n: usize) -> Result<usize> {
    match usize::try_from(v) {
        Ok(d) if d <= 3 => Ok(d),
        _ => Err(l.err(
            format!("entity dimension {v}: Gmsh entities have dimension 0 to 3"),
            n,
        )),
    }
}

fn to_usize(l: &Lines<'_>, v: i64, n: usize, what: &str) -> Result<usize> {
    usize::try_from(v).map_err(|_| l.err(format!("{what} must not be negative, found {v}"), n))
}

/// What both versions produce before groups are built.
#[derive(Default)]
struct Parsed {
    nodes: Vec<Node>,
    node_tag: HashMap<i64, usize>,
    /// Element tag -> line where it was first defined.
    cell_tags: HashMap<i64, usize>,
    cells: Vec<Cell>,
    /// For each cell, its physical tags (with the dimension of the cell).
    phys: Vec<Vec<i64>>,
    /// (dim, tag) -> name
    names: HashMap<(usize, i64), String>,
    /// Physical (dim, tag) in order of declaration in $PhysicalNames.
    name_order: Vec<(usize, i64)>,
}

pub fn parse(text: &str, file: &str) -> Result<Mesh> {
    // Gmsh itself reads a file saved with a UTF-8 byte order mark.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut l = Lines::new(text, file);
    let (n0, first) = l.next("MeshFormat")?;
    if first != "$MeshFormat" {
        return Err(l
            .err(format!("expected $MeshFormat, found '{first}'"), n0)
            .hint("this does not look like a Gmsh .msh file"));
    }
    let (nv, head) = l.next("MeshFormat")?;
    let mut words = head.split_whitespace();
    let version = words.next().unwrap_or("");
    let file_type = words.next().unwrap_or("");
    if file_type != "0" {
        return Err(l
            .err("binary .msh files are not supported", nv)
            .hint("save the mesh as ASCII (Gmsh: File > Export, 'Save all elements', ASCII)"));
    }
    let v4 = match version {
        "2.2" | "2.1" | "2" | "2.0" => false,
        "4.1" => true,
        _ => {
            return Err(l
                .err(
                    format!("Gmsh format version {version} is not supported"),
                    nv,
                )
                .hint("export as MSH 2.2 or 4.1 ASCII"))
        }
    };
    l.expect_end("MeshFormat")?;

    let mut p = Parsed::default();
    // Physical tags of the 4.1 entities: (dim, entity tag) -> physical tags.
    let mut entities: HashMap<(usize, i64), Vec<i64>> = HashMap::new();
    let mut saw_nodes = false;
    let mut saw_elements = false;
    while l.pos < l.lines.len() {
        let (n, head) = l.next("")?;
        match head {
            "$PhysicalNames" => read_physical_names(&mut l, &mut p)?,
            "$Entities" if v4 => entities = read_entities(&mut l)?,
            "$Nodes" => {
                if saw_nodes {
                    return Err(l
                        .err("a second $Nodes section", n)
                        .hint("a mesh has one $Nodes section; merge the two"));
                }
                if v4 {
                    read_nodes_41(&mut l, &mut p)?
                } else {
                    read_nodes_22(&mut l, &mut p)?
                }
                saw_nodes = true;
            }
            "$Elements" => {
                if !saw_nodes {
                    return Err(l.err("$Elements comes before $Nodes", n));
                }
                if saw_elements {
                    return Err(l
                        .err("a second $Elements section", n)
                        .hint("a mesh has one $Elements section; merge the two"));
                }
                if v4 {
                    read_elements_41(&mut l, &mut p, &entities)?
                } else {
                    read_elements_22(&mut l, &mut p)?
                }
                saw_elements = true;
            }
            h if h.starts_with("$End") => {
                return Err(l.err(format!("unexpected '{h}'"), n));
            }
            h if h.starts_with('$') => {
                // Sections we do not use ($Periodic, $NodeData...) are skipped whole.
                let section = h[1..].to_string();
                l.end(&section)?;
            }
            h => return Err(l.err(format!("expected a $Section, found '{h}'"), n)),
        }
    }
    if !saw_nodes || !saw_elements {
        return Err(l
            .err(
                format!(
                    "the file has no ${} section",
                    if saw_nodes { "Elements" } else { "Nodes" }
                ),
                l.last_line(),
            )
            .hint("the file looks truncated"));
    }
    Ok(build(p))
}

fn read_physical_names(l: &mut Lines<'_>, p: &mut Parsed) -> Result<()> {
    const S: &str = "PhysicalNames";
    let (n, count) = l.nums::<i64>(S, "the number of names")?;
    need(l, &count, 1, n, S, "the number of names")?;
    for _ in 0..count[0] {
        let (n, line) = l.next(S)?;
        let mut it = line.splitn(3, char::is_whitespace);
        let dim = it.next().and_then(|w| w.parse::<usize>().ok());
        let tag = it.next().and_then(|w| w.parse::<i64>().ok());
        let name = match it.next().map(str::trim) {
            Some(q) if q.starts_with('"') => match q[1..].find('"') {
                Some(close) => Some(q[1..1 + close].to_string()),
                None => {
                    return Err(l
                        .err(format!("${S}: the name {q} has no closing quote"), n)
                        .hint("a physical name is written between double quotes"));
                }
            },
            other => other.map(str::to_string),
        };
        match (dim, tag, name) {
            (Some(d), Some(t), Some(name)) if !name.is_empty() => {
                if p.names.insert((d, t), name).is_none() {
                    p.name_order.push((d, t));
                }
            }
            _ => {
                return Err(l.err(
                    format!("${S}: expected `dim tag \"name\"`, found '{line}'"),
                    n,
                ))
            }
        }
    }
    l.expect_end(S)
}

fn read_entities(l: &mut Lines<'_>) -> Result<HashMap<(usize, i64), Vec<i64>>> {
    const S: &str = "Entities";
    let (n, counts) = l.nums::<f64>(S, "the numbers of points, curves, surfaces, volumes")?;
    need(
        l,
        &counts,
        4,
        n,
        S,
        "numPoints numCurves numSurfaces numVolumes",
    )?;
    let mut out = HashMap::new();
    for (dim, &count) in counts.iter().take(4).enumerate() {
        if !(count >= 0.0 && count.fract() == 0.0) {
            return Err(l.err(
                format!("${S}: the number of entities of dimension {dim} must be a count, found {count}"),
                n,
            ));
        }
        // A count beyond the lines of the file fails at the end of the file.
        let mut left = count;
        while left > 0.0 {
            left -= 1.0;
            // point: tag x y z nphys phys...; others: tag 6 bbox numbers nphys phys... nbound ...
            let (n, v) = l.nums::<f64>(S, "an entity")?;
            let at = if dim == 0 { 4 } else { 7 };
            need(l, &v, at + 1, n, S, "an entity with its physical tags")?;
            let tag = whole(l, v[0], n, "an entity tag")?;
            let nphys = whole(l, v[at], n, "numPhysicalTags")?;
            let phys = usize::try_from(nphys)
                .ok()
                .and_then(|k| v.get(at + 1..(at + 1).checked_add(k)?))
                .ok_or_else(|| {
                    l.err(
                        format!("${S}: the entity lists fewer physical tags than {nphys}"),
                        n,
                    )
                })?;
            let phys = phys
                .iter()
                .map(|&t| whole(l, t, n, "a physical tag"))
                .collect::<Result<Vec<i64>>>()?;
            out.insert((dim, tag), phys);
        }
    }
    l.expect_end(S)?;
    Ok(out)
}

fn add_node(l: &Lines<'_>, p: &mut Parsed, tag: i64, xyz: &[f64], n: usize) -> Result<()> {
    if let Some(bad) = xyz.iter().take(3).find(|c| !c.is_finite()) {
        return Err(l.err(
            format!("node {tag} has the coordinate {bad}: coordinates must be finite numbers"),
            n,
        ));
    }
    if p.node_tag.insert(tag, p.nodes.len()).is_some() {
        return Err(l.err(format!("node {tag} is defined twice"), n));
    }
    p.nodes.push(Node {
        name: format!("N{tag}"),
        coords: [xyz[0], xyz[1], xyz[2]],
    });
    Ok(())
}

fn read_nodes_22(l: &mut Lines<'_>, p: &mut Parsed) -> Result<()> {
    const S: &str = "Nodes";
    let (n, count) = l.nums::<i64>(S, "the number of nodes")?;
    need(l, &count, 1, n, S, "the number of nodes")?;
    for _ in 0..count[0] {
        let (n, line) = l.next(S)?;
        if line.starts_with('$') {
            return Err(l.err(
                format!("${S} ends early: expected tag x y z, found {line}"),
                n,
            ));
        }
        let mut words = line.split_whitespace();
        let tag = l.tag(words.next().unwrap_or(""), "node", n)?;
        let xyz = words
            .map(|w| {
                w.parse::<f64>()
                    .map_err(|_| l.err(format!("${S}: '{w}' is not a valid number (x y z)"), n))
            })
            .collect::<Result<Vec<f64>>>()?;
        need(l, &xyz, 3, n, S, "x y z after the tag")?;
        add_node(l, p, tag, &xyz, n)?;
    }
    l.expect_end(S)
}

fn read_nodes_41(l: &mut Lines<'_>, p: &mut Parsed) -> Result<()> {
    const S: &str = "Nodes";
    let (n, head) = l.nums::<i64>(S, "numEntityBlocks numNodes minNodeTag maxNodeTag")?;
    need(
        l,
        &head,
        4,
        n,
        S,
        "numEntityBlocks numNodes minNodeTag maxNodeTag",
    )?;
    for _ in 0..head[0] {
        let (n, b) = l.nums::<i64>(S, "entityDim entityTag parametric numNodesInBlock")?;
        need(
            l,
            &b,
            4,
            n,
            S,
            "entityDim entityTag parametric numNodesInBlock",
        )?;
        entity_dim(l, b[0], n)?;
        if b[2] != 0 {
            return Err(l.err("parametric nodes are not supported", n));
        }
        let count = to_usize(l, b[3], n, "numNodesInBlock")?;
        // The count comes from the file: the tags grow as they are read, never reserved.
        let mut tags = Vec::new();
        for _ in 0..count {
            let (n, t) = l.next(S)?;
            if t.starts_with('$') {
                return Err(l.err(
                    format!("${S} ends early: expected a node tag, found {t}"),
                    n,
                ));
            }
            let mut words = t.split_whitespace();
            tags.push((l.tag(words.next().unwrap_or(""), "node", n)?, n));
            if words.next().is_some() {
                return Err(l.err(format!("${S}: expected one node tag, found '{t}'"), n));
            }
        }
        for (tag, _) in tags {
            let (n, v) = l.nums::<f64>(S, "x y z")?;
            need(l, &v, 3, n, S, "x y z")?;
            add_node(l, p, tag, &v, n)?;
        }
    }
    check_total(l, p.nodes.len(), head[1], n, "nodes")?;
    l.expect_end(S)
}

fn add_cell(
    l: &Lines<'_>,
    p: &mut Parsed,
    tag: i64,
    ty: i64,
    node_tags: &[i64],
    phys: Vec<i64>,
    n: usize,
) -> Result<()> {
    if tag <= 0 {
        return Err(l.err(format!("element tag {tag}: tags are positive integers"), n));
    }
    if let Some(&first) = p.cell_tags.get(&tag) {
        return Err(l.err(
            format!("element {tag} is defined twice (first at line {first})"),
            n,
        ));
    }
    p.cell_tags.insert(tag, n);
    let kind = kind_of(ty).ok_or_else(|| {
        l.err(format!("element {tag} has type {ty}, which is not supported"), n)
            .hint("supported types: 15 point, 1 line2, 8 line3, 2 tri3, 9 tri6, 3 quad4, 16 quad8, 4 tet4, 5 hex8, 6 prism, 7 pyramid")
    })?;
    if node_tags.len() != kind.node_count() {
        return Err(l.err(
            format!(
                "element {tag} of type {ty} ({}) needs {} nodes, found {}",
                kind.aster_name(),
                kind.node_count(),
                node_tags.len()
            ),
            n,
        ));
    }
    let nodes = node_tags
        .iter()
        .map(|t| {
            p.node_tag.get(t).copied().ok_or_else(|| {
                l.err(
                    format!("element {tag} uses node {t}, which is not in $Nodes"),
                    n,
                )
            })
        })
        .collect::<Result<Vec<_>>>()?;
    p.cells.push(Cell {
        name: format!("M{tag}"),
        kind,
        nodes,
    });
    p.phys.push(phys);
    Ok(())
}

fn read_elements_22(l: &mut Lines<'_>, p: &mut Parsed) -> Result<()> {
    const S: &str = "Elements";
    let (n, count) = l.nums::<i64>(S, "the number of elements")?;
    need(l, &count, 1, n, S, "the number of elements")?;
    for _ in 0..count[0] {
        // tag type ntags tags... nodes...
        let (n, v) = l.nums::<i64>(S, "an element")?;
        need(l, &v, 3, n, S, "elm-number elm-type number-of-tags")?;
        let ntags = to_usize(l, v[2], n, "number-of-tags")?;
        let tags = 3usize
            .checked_add(ntags)
            .and_then(|end| v.get(3..end))
            .ok_or_else(|| l.err(format!("element {} lists fewer tags than {ntags}", v[0]), n))?;
        // The first tag is the physical group; 0 means none.
        let phys = tags
            .first()
            .filter(|&&t| t != 0)
            .map(|&t| vec![t])
            .unwrap_or_default();
        add_cell(l, p, v[0], v[1], &v[3 + tags.len()..], phys, n)?;
    }
    l.expect_end(S)
}

fn read_elements_41(
    l: &mut Lines<'_>,
    p: &mut Parsed,
    entities: &HashMap<(usize, i64), Vec<i64>>,
) -> Result<()> {
    const S: &str = "Elements";
    let (n, head) = l.nums::<i64>(S, "numEntityBlocks numElements minElementTag maxElementTag")?;
    need(
        l,
        &head,
        4,
        n,
        S,
        "numEntityBlocks numElements minElementTag maxElementTag",
    )?;
    for _ in 0..head[0] {
        let (n, b) = l.nums::<i64>(S, "entityDim entityTag elementType numElementsInBlock")?;
        need(
            l,
            &b,
            4,
            n,
            S,
            "entityDim entityTag elementType numElementsInBlock",
        )?;
        let dim = entity_dim(l, b[0], n)?;
        let phys = entities.get(&(dim, b[1])).cloned().unwrap_or_default();
        for _ in 0..b[3] {
            let (n, v) = l.nums::<i64>(S, "an element")?;
            need(l, &v, 1, n, S, "an element")?;
            add_cell(l, p, v[0], b[2], &v[1..], phys.clone(), n)?;
        }
    }
    check_total(l, p.cells.len(), head[1], n, "elements")?;
    l.expect_end(S)
}

/// Turn physical tags into groups: named ones in `$PhysicalNames` order, then unnamed ones
/// by increasing (dim, tag). Groups with the same name in several dimensions are merged.
fn build(p: Parsed) -> Mesh {
    let mut keys: Vec<(usize, i64)> = p.name_order.clone();
    let mut unnamed: Vec<(usize, i64)> = Vec::new();
    for (c, tags) in p.cells.iter().zip(&p.phys) {
        for &t in tags {
            let k = (kind_dim(c.kind), t);
            if !p.names.contains_key(&k) && !unnamed.contains(&k) {
                unnamed.push(k);
            }
        }
    }
    unnamed.sort_unstable();
    keys.extend(unnamed);
    // (group, physical tag when unnamed)
    let mut cell_groups: Vec<(Group, Option<i64>)> = Vec::new();
    for k in keys {
        let members: Vec<usize> = p
            .cells
            .iter()
            .zip(&p.phys)
            .enumerate()
            .filter(|(_, (c, tags))| kind_dim(c.kind) == k.0 && tags.contains(&k.1))
            .map(|(i, _)| i)
            .collect();
        let (name, unnamed) = match p.names.get(&k) {
            Some(n) => (n.clone(), None),
            None => (format!("GM{}", k.1), Some(k.1)),
        };
        match cell_groups.iter_mut().find(|(g, _)| g.name == name) {
            Some((g, _)) => g.members.extend(members),
            None => cell_groups.push((Group { name, members }, unnamed)),
        }
    }
    let mut mesh = Mesh {
        dim: if p.nodes.iter().any(|n| n.coords[2] != 0.0) {
            3
        } else {
            2
        },
        nodes: p.nodes,
        cells: p.cells,
        node_groups: Vec::new(),
        cell_groups: Vec::new(),
    };
    mesh.node_groups = cell_groups
        .iter()
        .map(|(g, unnamed)| Group {
            name: match unnamed {
                Some(t) => format!("GN{t}"),
                None => g.name.clone(),
            },
            members: mesh.nodes_of_cells(&g.members),
        })
        .collect();
    mesh.cell_groups = cell_groups.into_iter().map(|(g, _)| g).collect();
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    const V22: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n$Elements\n1\n1 1 2 0 1 1 2\n$EndElements\n";

    fn fails(text: &str) -> (usize, String) {
        let e = parse(text, "t.msh").expect_err("the file should be refused");
        assert_eq!(e.kind, crate::error::ErrorKind::Input);
        let loc = e.location.clone().expect("errors carry a location");
        (loc.span.line, e.to_string())
    }

    #[test]
    fn names_follow_code_aster_convention() {
        let m = parse(V22, "t.msh").unwrap();
        assert_eq!(m.nodes[1].name, "N2");
        assert_eq!(m.cells[0].name, "M1");
        assert!(m.cell_groups.is_empty(), "physical tag 0 means no group");
        assert_eq!(m.dim, 2);
    }

    #[test]
    fn unnamed_physical_group_is_named_by_tag() {
        let m = parse(&V22.replace("1 1 2 0 1 1 2", "1 1 2 7 1 1 2"), "t.msh").unwrap();
        assert_eq!(m.cell_group("GM7").unwrap().members, vec![0]);
        assert_eq!(m.node_group("GN7").unwrap().members, vec![0, 1]);
    }

    #[test]
    fn unsupported_element_type() {
        let (line, msg) = fails(&V22.replace("1 1 2 0 1 1 2", "1 11 2 0 1 1 2"));
        assert_eq!(line, 11);
        assert!(msg.contains("type 11, which is not supported"), "{msg}");
    }

    #[test]
    fn undefined_node() {
        let (line, msg) = fails(&V22.replace("1 1 2 0 1 1 2", "1 1 2 0 1 1 5"));
        assert_eq!(line, 11);
        assert!(msg.contains("uses node 5, which is not in $Nodes"), "{msg}");
    }

    #[test]
    fn wrong_node_count() {
        let (line, msg) = fails(&V22.replace("1 1 2 0 1 1 2", "1 1 2 0 1 1 2 2"));
        assert_eq!(line, 11);
        assert!(msg.contains("needs 2 nodes, found 3"), "{msg}");
    }

    #[test]
    fn bad_number() {
        let (line, msg) = fails(&V22.replace("2 1 0 0", "2 1 zero 0"));
        assert_eq!(line, 7);
        assert!(msg.contains("'zero' is not a valid number"), "{msg}");
    }

    #[test]
    fn truncated_file() {
        let cut = &V22[..V22.find("$EndElements").unwrap()];
        let (line, msg) = fails(cut);
        assert_eq!(line, 11);
        assert!(msg.contains("ends inside $Elements"), "{msg}");
    }

    #[test]
    fn count_mismatch() {
        let (line, msg) = fails(&V22.replace("$Nodes\n2\n", "$Nodes\n3\n"));
        assert_eq!(line, 8);
        assert!(msg.contains("$Nodes ends early"), "{msg}");
    }

    #[test]
    fn duplicate_node_tag() {
        let (line, msg) = fails(&V22.replace("2 1 0 0", "1 1 0 0"));
        assert_eq!(line, 7);
        assert!(msg.contains("node 1 is defined twice"), "{msg}");
    }

    #[test]
    fn binary_and_unknown_versions_refused() {
        let (line, msg) = fails(&V22.replace("2.2 0 8", "2.2 1 8"));
        assert_eq!(line, 2);
        assert!(msg.contains("binary"), "{msg}");
        let (_, msg) = fails(&V22.replace("2.2 0 8", "3.0 0 8"));
        assert!(msg.contains("version 3.0"), "{msg}");
    }

    #[test]
    fn v41_total_must_match_blocks() {
        let t =
            "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n0 1 0 1\n1\n0 0 0\n$EndNodes\n";
        let (line, msg) = fails(t);
        assert_eq!(line, 5);
        assert!(
            msg.contains("announces 2 nodes, the blocks hold 1"),
            "{msg}"
        );
    }

    const V41: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n0 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n$Elements\n1 1 1 1\n1 1 1 1\n1 1 2\n$EndElements\n";

    #[test]
    fn v41_reference_file_reads() {
        let m = parse(V41, "t.msh").unwrap();
        assert_eq!((m.nodes.len(), m.cells.len()), (2, 1));
    }

    #[test]
    fn a_huge_node_count_is_not_reserved() {
        // The count is read from the file; reserving it aborted the process.
        // (The tags run into the coordinate lines, whose "0 0 0" is no tag.)
        let (line, msg) = fails(&V41.replace("0 1 0 2\n", "0 1 0 4000000000000000000\n"));
        assert_eq!(line, 9, "{msg}");
        let cut = V41.replace(
            "0 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n",
            "0 1 0 4000000000000000000\n1\n",
        );
        let (_, msg) = fails(&cut);
        assert!(msg.contains("ends"), "{msg}");
    }

    #[test]
    fn duplicate_element_tags_are_refused() {
        let t = V22.replace(
            "$Elements\n1\n1 1 2 0 1 1 2",
            "$Elements\n2\n1 1 2 0 1 1 2\n1 1 2 0 1 2 1",
        );
        let (line, msg) = fails(&t);
        assert_eq!(line, 12);
        assert!(
            msg.contains("element 1 is defined twice (first at line 11)"),
            "{msg}"
        );
    }

    #[test]
    fn tags_must_be_positive_and_fit() {
        let (line, msg) = fails(&V22.replace("2 1 0 0", "0 1 0 0"));
        assert_eq!(line, 7);
        assert!(msg.contains("tags are positive"), "{msg}");
        let (_, msg) = fails(&V22.replace("2 1 0 0", "-3 1 0 0"));
        assert!(msg.contains("tags are positive"), "{msg}");
        let (_, msg) = fails(&V22.replace("2 1 0 0", "99999999999999999999999 1 0 0"));
        assert!(msg.contains("fits in 64 bits"), "{msg}");
        let (_, msg) = fails(&V22.replace("1 1 2 0 1 1 2", "0 1 2 0 1 1 2"));
        assert!(msg.contains("tags are positive"), "{msg}");
        let (_, msg) = fails(&V41.replace("1\n2\n0 0 0", "1\n1e30\n0 0 0"));
        assert!(msg.contains("positive integer"), "{msg}");
    }

    #[test]
    fn non_finite_coordinates_are_refused_with_their_line() {
        for bad in ["nan", "inf", "-inf", "1e400"] {
            let (line, msg) = fails(&V22.replace("2 1 0 0", &format!("2 {bad} 0 0")));
            assert_eq!(line, 7, "{bad}");
            assert!(msg.contains("must be finite"), "{msg}");
            let (line, msg) = fails(&V41.replace("1 0 0\n", &format!("1 {bad} 0\n")));
            assert_eq!(line, 10, "{bad}");
            assert!(msg.contains("must be finite"), "{msg}");
        }
    }

    #[test]
    fn a_second_nodes_or_elements_section_is_refused() {
        let nodes = "$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n";
        let (line, msg) = fails(&V22.replace(nodes, &format!("{nodes}{nodes}")));
        assert_eq!(line, 9);
        assert!(msg.contains("a second $Nodes"), "{msg}");
        let elems = "$Elements\n1\n1 1 2 0 1 1 2\n$EndElements\n";
        let (_, msg) = fails(&format!("{V22}{elems}"));
        assert!(msg.contains("a second $Elements"), "{msg}");
    }

    #[test]
    fn entity_dimensions_above_three_are_refused() {
        let (line, msg) = fails(&V41.replace("0 1 0 2\n", "4 1 0 2\n"));
        assert_eq!(line, 6);
        assert!(msg.contains("dimension 0 to 3"), "{msg}");
        let (line, msg) = fails(&V41.replace("1 1 1 1\n1 1 2", "7 1 1 1\n1 1 2"));
        assert_eq!(line, 14);
        assert!(msg.contains("dimension 0 to 3"), "{msg}");
    }

    #[test]
    fn an_unterminated_physical_name_is_refused() {
        let names = "$PhysicalNames\n1\n1 1 \"left\n$EndPhysicalNames\n";
        let t = V22.replace("$Nodes\n", &format!("{names}$Nodes\n"));
        let (line, msg) = fails(&t);
        assert_eq!(line, 6);
        assert!(msg.contains("no closing quote"), "{msg}");
        let ok = t.replace("\"left\n", "\"left side\"\n");
        let m = parse(&ok.replace("1 1 2 0 1 1 2", "1 1 2 1 1 1 2"), "t.msh").unwrap();
        assert_eq!(m.cell_groups[0].name, "left side");
    }

    #[test]
    fn a_byte_order_mark_is_accepted() {
        let m = parse(&format!("\u{feff}{V22}"), "t.msh").unwrap();
        assert_eq!(m.nodes.len(), 2);
    }

    #[test]
    fn absurd_entity_counts_fail_cleanly() {
        let ent = "$Entities\n0 1 0 0\n1 0 0 0 1 0 0 1e300 1 2 0\n$EndEntities\n";
        let t = V41.replace("$Nodes\n", &format!("{ent}$Nodes\n"));
        let (_, msg) = fails(&t);
        assert!(
            msg.contains("fewer physical tags") || msg.contains("integer"),
            "{msg}"
        );
        let ent = "$Entities\n0 1e300 0 0\n$EndEntities\n";
        let (_, msg) = fails(&V41.replace("$Nodes\n", &format!("{ent}$Nodes\n")));
        assert!(msg.contains("$Entities"), "{msg}");
    }

    #[test]
    fn multiple_physical_tags_of_an_entity_give_several_groups() {
        let m = read_file(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/meshes/mixed41.msh"),
        )
        .unwrap();
        // Surface 2 carries physical tags 10 ("quads") and 12 (unnamed).
        assert_eq!(m.cell_group("GM12").unwrap().members, vec![1]);
        assert_eq!(m.cell_group("quads").unwrap().members, vec![0, 1]);
        assert_eq!(m.cells[1].name, "M20");
        assert_eq!(m.cells[1].kind, CellKind::Quad8);
    }
}
