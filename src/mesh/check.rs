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
/// the diagonal of the bounding box.
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
                "{} pair(s) of nodes are closer than {aplat} times the mesh size: {}",
                close.len(),
                list(&refs)
            ),
        });
    }
    out
}

/// Pairs of node indices closer than `aplat` times the bounding-box diagonal. Nodes are
/// sorted along x so only neighbours within the tolerance in x are compared.
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
    let tol = aplat * diag;
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
            let d2: f64 = (0..3).map(|k| (pa[k] - pb[k]).powi(2)).sum();
            if d2.sqrt() < tol {
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
        // Size 1 (diagonal), APLAT 1e-3: nodes 1e-4 apart are coincident, 1e-2 apart not.
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
                    nodes: vec![1, 2],
                },
                Cell {
                    name: "S3".into(),
                    kind: CellKind::Seg2,
                    nodes: vec![3, 4],
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

        let mut m2 = m.clone();
        m2.nodes.push(node("LONE", 0.7));
        let f = verify(&m2, 1e-3);
        assert_eq!(f[0].id, "MAILLAGE_ORPHAN_NODES");
        assert!(f[0].message.contains("LONE"));
    }
}
