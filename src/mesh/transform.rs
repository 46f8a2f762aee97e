//! Moving the nodes of a mesh (MODI_MAILLAGE): random perturbation, translation, scaling.

use super::Mesh;

/// A small deterministic generator (SplitMix64): the same perturbation on every run and
/// every machine, which a reproducible study needs; its statistical quality is ample for
/// breaking symmetries.
pub struct SplitMix64(u64);

impl SplitMix64 {
    pub fn new(seed: u64) -> SplitMix64 {
        SplitMix64(seed)
    }
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1): the top 53 bits as the mantissa.
    pub fn next_unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// The seed of MODI_MAILLAGE's perturbation (fixed: runs are reproducible).
pub const PERTURBATION_SEED: u64 = 0x6173_7465_722d_6e6c;

/// Adds `alea * r * extent[d]` to coordinate `d` of every node, `r` uniform in [0, 1)
/// drawn per node and direction, `extent[d]` the mesh's extent in direction `d` before
/// the perturbation. Returns the largest displacement of a coordinate.
pub fn perturb(mesh: &mut Mesh, alea: f64, rng: &mut SplitMix64) -> f64 {
    let extent = extents(mesh);
    let mut largest = 0.0_f64;
    for node in &mut mesh.nodes {
        for (c, e) in node.coords.iter_mut().zip(extent) {
            // Drawn even where the extent is zero, so that the numbers a direction gets do
            // not depend on the other directions.
            let shift = alea * rng.next_unit() * e;
            *c += shift;
            largest = largest.max(shift.abs());
        }
    }
    largest
}

/// `max - min` of each coordinate over the nodes (0 for an empty mesh).
pub fn extents(mesh: &Mesh) -> [f64; 3] {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for n in &mesh.nodes {
        for d in 0..3 {
            lo[d] = lo[d].min(n.coords[d]);
            hi[d] = hi[d].max(n.coords[d]);
        }
    }
    let mut e = [0.0; 3];
    for d in 0..3 {
        if hi[d] >= lo[d] {
            e[d] = hi[d] - lo[d];
        }
    }
    e
}

/// Adds `t` to every node (a 2-component `t` leaves z unchanged).
pub fn translate(mesh: &mut Mesh, t: [f64; 3]) {
    for node in &mut mesh.nodes {
        for (c, dt) in node.coords.iter_mut().zip(t) {
            *c += dt;
        }
    }
}

/// Multiplies every coordinate by `factor`.
pub fn scale(mesh: &mut Mesh, factor: f64) {
    for node in &mut mesh.nodes {
        for c in &mut node.coords {
            *c *= factor;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Node;

    fn line(xs: &[f64]) -> Mesh {
        Mesh {
            dim: 3,
            nodes: xs
                .iter()
                .enumerate()
                .map(|(i, &x)| Node {
                    name: format!("N{}", i + 1),
                    coords: [x, 2.0, 0.0],
                })
                .collect(),
            cells: Vec::new(),
            node_groups: Vec::new(),
            cell_groups: Vec::new(),
        }
    }

    #[test]
    fn perturbation_stays_within_alea_times_the_extent_and_spares_flat_directions() {
        let mut m = line(&[0.0, 1.0, 4.0]);
        let before = m.clone();
        let alea = 1e-3;
        let largest = perturb(&mut m, alea, &mut SplitMix64::new(PERTURBATION_SEED));
        assert!(largest > 0.0 && largest < alea * 4.0, "{largest}");
        for (a, b) in m.nodes.iter().zip(&before.nodes) {
            let dx = a.coords[0] - b.coords[0];
            assert!((0.0..alea * 4.0).contains(&dx), "{dx}");
            // y and z: the mesh is flat there.
            assert_eq!(a.coords[1], b.coords[1]);
            assert_eq!(a.coords[2], b.coords[2]);
        }
        // Reproducible: the same seed gives the same mesh.
        let mut again = before.clone();
        perturb(&mut again, alea, &mut SplitMix64::new(PERTURBATION_SEED));
        assert_eq!(again, m);
    }

    #[test]
    fn uniform_numbers_cover_the_unit_interval() {
        let mut r = SplitMix64::new(1);
        let xs: Vec<f64> = (0..10_000).map(|_| r.next_unit()).collect();
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
        // Mean of U(0,1) is 1/2 with standard deviation 1/sqrt(12 n) = 0.0029 here.
        let mean = xs.iter().sum::<f64>() / xs.len() as f64;
        assert!((mean - 0.5).abs() < 0.015, "{mean}");
    }

    #[test]
    fn translation_and_scaling() {
        let mut m = line(&[1.0, 3.0]);
        translate(&mut m, [1.0, -2.0, 0.5]);
        assert_eq!(m.nodes[1].coords, [4.0, 0.0, 0.5]);
        scale(&mut m, 2.0);
        assert_eq!(m.nodes[0].coords, [4.0, 0.0, 1.0]);
    }
}
