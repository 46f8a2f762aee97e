//! Checks of a mesh after reading (LIRE_MAILLAGE/VERI_MAIL): things that are legal but
//! usually mistakes, reported as alarms.

use super::Mesh;

/// One finding: an alarm id and its message.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    pub id: &'static str,
    pub message: String,
}

/// Names shown in a message before "...".
const SHOWN: usize = 5;

fn list(names: &[&str]) -> String {
    let mut s = names
        .iter()
        .take(SHOWN)
        .copied()
        .collect::<Vec<_>>()
        .join(", ");
    if names.len() > SHOWN {
        s.push_str(", ...");
    }
    s
}

/// Orphan nodes, cells using a node twice, and pairs of nodes closer than `aplat` times
/// the typical cell size ([`typical_size`]).
pub fn verify(mesh: &Mesh, aplat: f64) -> Vec<Finding> {
    let mut out = Vec::new();
    let mut used = vec![false; mesh.nodes.len()];
    let mut repeated = Vec::new();
    for c in &mesh.cells {
        for (k, &n) in c.nodes.iter().enumerate() {
            if let Some(u) = used.get_mut(n) {
                *u = true;
            }
            if c.nodes[..k].contains(&n) && !repeated.contains(&c.name.as_str()) {
                repeated.push(c.name.as_str());
            }
        }
    }
    let orphans: Vec<&str> = mesh
        .nodes
        .iter()
        .zip(&used)
        .filter(|(_, &u)| !u)
        .map(|(n, _)| n.name.as_str())
        .collect();
    if !orphans.is_empty() {
        out.push(Finding {
            id: "MAILLAGE_ORPHAN_NODES",
            message: format!(
                "{} node(s) belong to no cell: {}",
                orphans.len(),
                list(&orphans)
            ),
        });
    }
    if !repeated.is_empty() {
        out.push(Finding {
            id: "MAILLAGE_DEGENERATE_CELLS",
            message: format!(
                "{} cell(s) use the same node twice: {}",
                repeated.len(),
                list(&repeated)
            ),
        });
    }
    let close = coincident_nodes(mesh, aplat);
    if !close.is_empty() {
        let pairs: Vec<String> = close
            .iter()
            .map(|&(a, b)| format!("{}-{}", mesh.nodes[a].name, mesh.nodes[b].name))
            .collect();
        let refs: Vec<&str> = pairs.iter().map(String::as_str).collect();
        out.push(Finding {
            id: "MAILLAGE_COINCIDENT_NODES",
            message: format!(
                "{} pair(s) of nodes are closer than {aplat} times the typical cell size: {}",
                close.len(),
                list(&refs)
            ),
        });
    }
    out
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The size against which nodes count as coincident: the median over the cells of their
/// longest edge (between any two of their nodes), so that a uniformly fine mesh (a beam of
/// 2000 elements: nodes 1/2000 of its length apart) raises nothing while a pair of nodes far
/// closer than the cells around them does; the bounding-box diagonal when no cell has two
/// distinct nodes (a mesh of point cells).
fn typical_size(mesh: &Mesh, diag: f64) -> f64 {
    let mut sizes: Vec<f64> = mesh
        .cells
        .iter()
        .filter_map(|c| {
            let pts: Vec<[f64; 3]> = c
                .nodes
                .iter()
                .filter_map(|&n| mesh.nodes.get(n).map(|p| p.coords))
                .collect();
            let longest = pts
                .iter()
                .enumerate()
                .flat_map(|(i, &a)| pts[i + 1..].iter().map(move |&b| distance(a, b)))
                .fold(0.0f64, f64::max);
            (longest > 0.0 && longest.is_finite()).then_some(longest)
        })
        .collect();
    if sizes.is_empty() {
        return diag;
    }
    let mid = sizes.len() / 2;
    *sizes.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// Pairs of node indices closer than `aplat` times the typical cell size. Nodes are sorted
/// along x so only neighbours within the tolerance in x are compared.
fn coincident_nodes(mesh: &Mesh, aplat: f64) -> Vec<(usize, usize)> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for n in &mesh.nodes {
        for k in 0..3 {
            lo[k] = lo[k].min(n.coords[k]);
            hi[k] = hi[k].max(n.coords[k]);
        }
    }
    let diag = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    if mesh.nodes.len() < 2 || !diag.is_finite() || diag == 0.0 {
        return Vec::new();
    }
    let tol = aplat * typical_size(mesh, diag);
    let mut order: Vec<usize> = (0..mesh.nodes.len()).collect();
    order.sort_by(|&a, &b| mesh.nodes[a].coords[0].total_cmp(&mesh.nodes[b].coords[0]));
    let mut out = Vec::new();
    for (i, &a) in order.iter().enumerate() {
        let pa = mesh.nodes[a].coords;
        for &b in &order[i + 1..] {
            let pb = mesh.nodes[b].coords;
            if pb[0] - pa[0] > tol {
                break;
            }
            if distance(pa, pb) < tol {
                out.push((a.min(b), a.max(b)));
            }
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Cell, CellKind, Node};

    #[test]
    fn finds_orphans_degenerate_cells_and_close_nodes() {
        let node = |name: &str, x: f64| Node {
            name: name.into(),
            coords: [x, 0.0, 0.0],
        };
        // Cells of 0.5, 0.49 and 0.01 (median of the longest edges 0.49; S1 has none), APLAT
        // 1e-3: nodes 1e-4 apart (B, C, in no common cell) are coincident, 1e-2 apart (D,
        // E) not.
        let m = Mesh {
            dim: 3,
            nodes: vec![
                node("A", 0.0),
                node("B", 1.0),
                node("C", 1.0 + 1e-4),
                node("D", 0.5),
                node("E", 0.51),
            ],
            cells: vec![
                Cell {
                    name: "S1".into(),
                    kind: CellKind::Seg2,
                    nodes: vec![0, 0],
                },
                Cell {
                    name: "S2".into(),
                    kind: CellKind::Seg2,
                    nodes: vec![3, 1],
                },
                Cell {
                    name: "S3".into(),
                    kind: CellKind::Seg2,
                    nodes: vec![3, 4],
                },
                Cell {
                    name: "S4".into(),
                    kind: CellKind::Seg2,
                    nodes: vec![2, 4],
                },
            ],
            ..Mesh::default()
        };
        let f = verify(&m, 1e-3);
        let ids: Vec<&str> = f.iter().map(|x| x.id).collect();
        assert_eq!(
            ids,
            vec!["MAILLAGE_DEGENERATE_CELLS", "MAILLAGE_COINCIDENT_NODES"]
        );
        assert!(f[0].message.contains("S1"), "{}", f[0].message);
        assert!(
            f[1].message.contains("1 pair(s)") && f[1].message.contains("B-C"),
            "{}",
            f[1].message
        );

        // A uniformly fine chain (2000 cells of 1/2000): nothing is coincident.
        let fine = Mesh {
            dim: 3,
            nodes: (0..=2000)
                .map(|i| node(&format!("N{i}"), i as f64 / 2000.0))
                .collect(),
            cells: (0..2000)
                .map(|i| Cell {
                    name: format!("M{i}"),
                    kind: CellKind::Seg2,
                    nodes: vec![i, i + 1],
                })
                .collect(),
            ..Mesh::default()
        };
        assert!(verify(&fine, 1e-3).is_empty());

        let mut m2 = m.clone();
        m2.nodes.push(node("LONE", 0.7));
        let f = verify(&m2, 1e-3);
        assert_eq!(f[0].id, "MAILLAGE_ORPHAN_NODES");
        assert!(f[0].message.contains("LONE"));
    }
}
