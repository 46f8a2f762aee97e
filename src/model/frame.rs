//! Local axes of segment elements and rotation of element matrices to global axes.

use serde::{Deserialize, Serialize};

/// Rows are the local axes x, y, z written in global coordinates.
pub type Frame = [[f64; 3]; 3];

/// ORIENTATION of a segment (AFFE_CARA_ELEM).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Orientation {
    /// VECT_Y: the local y axis is this vector made orthogonal to the element axis.
    VectY([f64; 3]),
    /// ANGL_VRIL: twist angle γ in degrees about the element axis, from the default frame.
    AnglVril(f64),
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Length of the segment p1-p2.
pub fn length(p1: [f64; 3], p2: [f64; 3]) -> f64 {
    norm([p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]])
}

/// Local frame of the segment p1 -> p2, Code_Aster convention: x along the segment; by
/// default (nautical angles α, β from the axis, γ = 0) the local y axis is horizontal,
/// y = (-sin α, cos α, 0), and for a vertical segment (α = 0 by convention) y = global Y.
/// Errors (as text, the caller names the cell) for a zero-length segment or a VECT_Y
/// parallel to the axis.
pub fn segment_frame(
    p1: [f64; 3],
    p2: [f64; 3],
    orientation: Option<&Orientation>,
) -> std::result::Result<Frame, String> {
    let d = [p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]];
    let l = norm(d);
    if l <= 0.0 || !l.is_finite() {
        return Err("zero-length segment: its local axes are undefined".into());
    }
    let x = [d[0] / l, d[1] / l, d[2] / l];
    // Horizontal projection; below 1e-12 of the length the segment counts as vertical.
    let h = (x[0] * x[0] + x[1] * x[1]).sqrt();
    let (sa, ca) = if h > 1e-12 {
        (x[1] / h, x[0] / h)
    } else {
        (0.0, 1.0)
    };
    let y0 = [-sa, ca, 0.0];
    let z0 = cross(x, y0);
    let (y, z) = match orientation {
        None => (y0, z0),
        Some(Orientation::AnglVril(deg)) => {
            let (s, c) = deg.to_radians().sin_cos();
            (
                [
                    c * y0[0] + s * z0[0],
                    c * y0[1] + s * z0[1],
                    c * y0[2] + s * z0[2],
                ],
                [
                    -s * y0[0] + c * z0[0],
                    -s * y0[1] + c * z0[1],
                    -s * y0[2] + c * z0[2],
                ],
            )
        }
        Some(Orientation::VectY(v)) => {
            let a = dot(*v, x);
            let w = [v[0] - a * x[0], v[1] - a * x[1], v[2] - a * x[2]];
            let n = norm(w);
            // Relative test: a VECT_Y within ~1e-9 rad of the axis defines no plane.
            if n <= 1e-9 * norm(*v) || n == 0.0 {
                return Err("VECT_Y is parallel to the element axis".into());
            }
            let y = [w[0] / n, w[1] / n, w[2] / n];
            (y, cross(x, y))
        }
    };
    Ok([x, y, z])
}

/// Global matrix Tᵀ K T of a local n×n row-major matrix, T block-diagonal with the frame
/// (3×3 blocks, or the in-plane 2×2 block when `block == 2`).
pub fn rotate_to_global(local: &[f64], n: usize, frame: &Frame, block: usize) -> Vec<f64> {
    let mut t = vec![0.0; n * n];
    for b in 0..n / block {
        for i in 0..block {
            for j in 0..block {
                t[(b * block + i) * n + b * block + j] = frame[i][j];
            }
        }
    }
    // kt = K T, then out = Tᵀ (K T).
    let mut kt = vec![0.0; n * n];
    for i in 0..n {
        for k in 0..n {
            let a = local[i * n + k];
            if a != 0.0 {
                for j in 0..n {
                    kt[i * n + j] += a * t[k * n + j];
                }
            }
        }
    }
    let mut out = vec![0.0; n * n];
    for k in 0..n {
        for i in 0..n {
            let a = t[k * n + i];
            if a != 0.0 {
                for j in 0..n {
                    out[i * n + j] += a * kt[k * n + j];
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_frame_is_horizontal_y_and_right_handed() {
        let f = segment_frame([0.0; 3], [1.0, 1.0, 1.0], None).unwrap();
        assert!(f[1][2].abs() < 1e-15, "local y horizontal");
        let z = cross(f[0], f[1]);
        for i in 0..3 {
            assert!((z[i] - f[2][i]).abs() < 1e-14);
        }
        // vertical element: y = global Y
        let v = segment_frame([0.0; 3], [0.0, 0.0, 2.0], None).unwrap();
        assert!((v[1][1] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn vect_y_and_twist_agree() {
        // Element along X: default y = Y, a 90° twist gives y = Z, as VECT_Y=(0,0,1).
        let a = segment_frame(
            [0.0; 3],
            [2.0, 0.0, 0.0],
            Some(&Orientation::AnglVril(90.0)),
        )
        .unwrap();
        let b = segment_frame(
            [0.0; 3],
            [2.0, 0.0, 0.0],
            Some(&Orientation::VectY([0.3, 0.0, 5.0])),
        )
        .unwrap();
        for i in 0..3 {
            for j in 0..3 {
                assert!((a[i][j] - b[i][j]).abs() < 1e-14);
            }
        }
        assert!(segment_frame(
            [0.0; 3],
            [1.0, 0.0, 0.0],
            Some(&Orientation::VectY([2.0, 0.0, 0.0]))
        )
        .is_err());
    }
}
