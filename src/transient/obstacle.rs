//! DEFI_OBSTACLE's geometry as DYNA_VIBRA uses it: the obstacle's local frame (NORM_OBST,
//! ANGL_VRIL, node 1 → node 2) and the normal distance with its direction.
//!
//! Code_Aster's conventions (routines `mdchan`, `angvx`, `angvxy`, `gloloc`/`rot3d`,
//! `distno`; `dtmprep_noli_choc` for the sign of the two-node obstacles):
//! - Local x is NORM_OBST. With α = atan2(n_y, n_x), β = −atan2(n_z, √(n_x² + n_y²)) and γ
//!   the twist, the local coordinates are R (X − ORIG_OBST) with R = R_x(γ) R_y(β) R_z(α)
//!   (each elementary rotation with its entries below 1e-6 set to zero, as `rot3d` does).
//!   The rows of R are the local axes: x = NORM_OBST/|NORM_OBST|, and for γ = 0 local y =
//!   (−sin α, cos α, 0) (horizontal), local z = x × y.
//! - γ: ANGL_VRIL (degrees) when given. Otherwise γ = 0, except for BI_PLAN_Y, where local
//!   y is the part of (node 2 − node 1) normal to x, and BI_PLAN_Z, where local z is the part
//!   of (node 2 − node 1) normal to x (local y from (node 2 − node 1) × x).
//! - Normal distance (< 0 in contact) and the direction (0, cos θ, sin θ) of the force on
//!   node 1, from the local position y, z of node 1 (relative to ORIG_OBST) and, for the
//!   two-node obstacles, of node 2:
//!   - PLAN_Y: JEU − |y|, direction −sign(y) ŷ; PLAN_Z: JEU − |z|, −sign(z) ẑ. So
//!     "PLAN" is two planes at ±JEU around ORIG_OBST (Code_Aster's `distno` takes |y|).
//!   - BI_PLAN_Y: (y₂ − y₁)·s − DIST_1 − DIST_2 with s the sign of y₂ − y₁ at rest,
//!     direction −s ŷ; BI_PLAN_Z likewise on z.
//!   - CERCLE: JEU − r with r = √(y² + z²), direction −(y, z)/r (−ŷ at the centre).
//!   - BI_CERCLE: r₁₂ − DIST_1 − DIST_2, r₁₂ = |(y₁ − y₂, z₁ − z₂)|, direction
//!     (y₁ − y₂, z₁ − z₂)/r₁₂; BI_CERC_INT (node 1 inside a ring of node 2):
//!     DIST_2 − DIST_1 − r₁₂, direction (y₂ − y₁, z₂ − z₁)/r₁₂.
//!
//!   A force on node 1 is F_N (0, cos θ, sin θ) in the local frame; node 2 gets its
//!   opposite.
//! - ∂(distance)/∂(relative local position) is (0, cos θ, sin θ) for every type, which the
//!   implicit scheme's tangent uses.
//!
//! Not supported: obstacles given by a table of points (TYPE='DISCRET', `distno`'s
//! last case); `ObstacleKind::from_name` returns `None` for them.

use super::error::{invalid, TransientError};

/// The obstacle types of DEFI_OBSTACLE that DIS_CHOC handles here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ObstacleKind {
    PlanY,
    PlanZ,
    BiPlanY,
    BiPlanZ,
    Cercle,
    BiCercle,
    BiCercleInt,
}

impl ObstacleKind {
    /// DEFI_OBSTACLE's TYPE; `None` for DISCRET (tables of points) and unknown names.
    pub fn from_name(name: &str) -> Option<ObstacleKind> {
        Some(match name.trim() {
            "PLAN_Y" => ObstacleKind::PlanY,
            "PLAN_Z" => ObstacleKind::PlanZ,
            "BI_PLAN_Y" => ObstacleKind::BiPlanY,
            "BI_PLAN_Z" => ObstacleKind::BiPlanZ,
            "CERCLE" => ObstacleKind::Cercle,
            "BI_CERCLE" => ObstacleKind::BiCercle,
            "BI_CERC_INT" => ObstacleKind::BiCercleInt,
            _ => return None,
        })
    }

    /// Code_Aster's name.
    pub fn name(self) -> &'static str {
        match self {
            ObstacleKind::PlanY => "PLAN_Y",
            ObstacleKind::PlanZ => "PLAN_Z",
            ObstacleKind::BiPlanY => "BI_PLAN_Y",
            ObstacleKind::BiPlanZ => "BI_PLAN_Z",
            ObstacleKind::Cercle => "CERCLE",
            ObstacleKind::BiCercle => "BI_CERCLE",
            ObstacleKind::BiCercleInt => "BI_CERC_INT",
        }
    }

    /// The BI_ types involve node 2 (the others ignore it, as Code_Aster does).
    pub fn two_nodes(self) -> bool {
        matches!(
            self,
            ObstacleKind::BiPlanY
                | ObstacleKind::BiPlanZ
                | ObstacleKind::BiCercle
                | ObstacleKind::BiCercleInt
        )
    }

    /// Whether the normal lies along a fixed local axis (plane types) or turns in the
    /// local (y, z) plane (circle types).
    pub fn fixed_normal(self) -> bool {
        !matches!(
            self,
            ObstacleKind::Cercle | ObstacleKind::BiCercle | ObstacleKind::BiCercleInt
        )
    }
}

/// The obstacle frame: `rows[i]` is local axis i (x, y, z) in global coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalFrame {
    pub rows: [[f64; 3]; 3],
}

fn clean(x: f64) -> f64 {
    if x.abs() < 1e-6 {
        0.0
    } else {
        x
    }
}

fn matmul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for (i, ci) in c.iter_mut().enumerate() {
        for (j, cij) in ci.iter_mut().enumerate() {
            *cij = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

impl LocalFrame {
    /// R = R_x(γ) R_y(β) R_z(α), Code_Aster's nautical angles (radians).
    pub fn from_angles(alpha: f64, beta: f64, gamma: f64) -> LocalFrame {
        let (sa, ca) = (clean(alpha.sin()), clean(alpha.cos()));
        let (sb, cb) = (clean(beta.sin()), clean(beta.cos()));
        let (sg, cg) = (clean(gamma.sin()), clean(gamma.cos()));
        let rz = [[ca, sa, 0.0], [-sa, ca, 0.0], [0.0, 0.0, 1.0]];
        let ry = [[cb, 0.0, -sb], [0.0, 1.0, 0.0], [sb, 0.0, cb]];
        let rx = [[1.0, 0.0, 0.0], [0.0, cg, sg], [0.0, -sg, cg]];
        LocalFrame {
            rows: matmul(&rx, &matmul(&ry, &rz)),
        }
    }

    pub fn identity() -> LocalFrame {
        LocalFrame::from_angles(0.0, 0.0, 0.0)
    }

    /// Local components of a global vector.
    pub fn to_local(&self, g: [f64; 3]) -> [f64; 3] {
        let r = &self.rows;
        [
            r[0][0] * g[0] + r[0][1] * g[1] + r[0][2] * g[2],
            r[1][0] * g[0] + r[1][1] * g[1] + r[1][2] * g[2],
            r[2][0] * g[0] + r[2][1] * g[1] + r[2][2] * g[2],
        ]
    }

    /// Global components of a local vector.
    pub fn to_global(&self, l: [f64; 3]) -> [f64; 3] {
        let r = &self.rows;
        [
            r[0][0] * l[0] + r[1][0] * l[1] + r[2][0] * l[2],
            r[0][1] * l[0] + r[1][1] * l[1] + r[2][1] * l[2],
            r[0][2] * l[0] + r[1][2] * l[1] + r[2][2] * l[2],
        ]
    }
}

/// α, β of a direction (`angvx`): zero where the arguments vanish.
fn angles_x(gx: [f64; 3]) -> (f64, f64) {
    let tiny = f64::MIN_POSITIVE;
    let alpha = if gx[0].abs() <= tiny && gx[1].abs() <= tiny {
        0.0
    } else {
        gx[1].atan2(gx[0])
    };
    let p = (gx[0] * gx[0] + gx[1] * gx[1]).sqrt();
    let beta = if gx[2].abs() <= tiny && p <= tiny {
        0.0
    } else {
        -gx[2].atan2(p)
    };
    (alpha, beta)
}

/// α, β, γ with x along `gx` and y along the part of `gn` normal to x (`angvxy`).
fn angles_xy(gx: [f64; 3], gn: [f64; 3]) -> (f64, f64, f64) {
    let (alpha, beta) = angles_x(gx);
    let partial = LocalFrame::from_angles(alpha, beta, 0.0).to_local(gn);
    let tiny = f64::MIN_POSITIVE;
    let gamma = if partial[2].abs() <= tiny && partial[1].abs() <= tiny {
        0.0
    } else {
        partial[2].atan2(partial[1])
    };
    (alpha, beta, gamma)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The obstacle frame by Code_Aster's rule (module doc). `angl_vril` in degrees.
pub fn obstacle_frame(
    kind: ObstacleKind,
    norm_obst: [f64; 3],
    angl_vril: Option<f64>,
    node1: [f64; 3],
    node2: Option<[f64; 3]>,
) -> Result<LocalFrame, TransientError> {
    let len = norm_obst.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(len > 0.0 && len.is_finite()) {
        return Err(invalid(
            "CHOC/NORM_OBST",
            "the obstacle's axis is the zero vector (or not finite)",
        ));
    }
    if let Some(deg) = angl_vril {
        let (a, b) = angles_x(norm_obst);
        return Ok(LocalFrame::from_angles(a, b, deg.to_radians()));
    }
    let axis_12 = || {
        node2.map(|p2| sub(p2, node1)).ok_or_else(|| {
            invalid(
                "CHOC/NOEUD_2",
                format!("{} needs a second node", kind.name()),
            )
        })
    };
    let (a, b, g) = match kind {
        ObstacleKind::BiPlanY => angles_xy(norm_obst, axis_12()?),
        ObstacleKind::BiPlanZ => angles_xy(norm_obst, cross(axis_12()?, norm_obst)),
        _ => {
            let (a, b) = angles_x(norm_obst);
            (a, b, 0.0)
        }
    };
    Ok(LocalFrame::from_angles(a, b, g))
}

/// Fortran's SIGN(1, x): +1 for x ≥ 0 (and for +0), −1 otherwise.
fn sign1(x: f64) -> f64 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The signs Code_Aster stores at rest for the BI_PLAN types: −sign(y₁ − y₂), −sign(z₁ − z₂)
/// of the relative local position (node 1 minus node 2; node 1 alone for one node).
pub fn rest_signs(rel_local: [f64; 3]) -> [f64; 2] {
    [-sign1(rel_local[1]), -sign1(rel_local[2])]
}

/// Normal distance and the force direction (0, cos θ, sin θ) on node 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gap {
    pub dnorm: f64,
    pub cos: f64,
    pub sin: f64,
}

/// Sizes of an obstacle: JEU, DIST_1, DIST_2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clearance {
    pub jeu: f64,
    pub dist1: f64,
    pub dist2: f64,
}

/// The normal distance of `distno` from the local positions of node 1 and node 2 (node 2
/// ignored by the one-node types) and the rest signs of [`rest_signs`].
pub fn normal_gap(
    kind: ObstacleKind,
    x1: [f64; 3],
    x2: [f64; 3],
    c: Clearance,
    signs: [f64; 2],
) -> Gap {
    match kind {
        ObstacleKind::PlanY => Gap {
            dnorm: c.jeu - x1[1].abs(),
            cos: -sign1(x1[1]),
            sin: 0.0,
        },
        ObstacleKind::PlanZ => Gap {
            dnorm: c.jeu - x1[2].abs(),
            cos: 0.0,
            sin: -sign1(x1[2]),
        },
        ObstacleKind::BiPlanY => Gap {
            dnorm: (x2[1] - x1[1]) * signs[0] - c.dist1 - c.dist2,
            cos: -signs[0],
            sin: 0.0,
        },
        ObstacleKind::BiPlanZ => Gap {
            dnorm: (x2[2] - x1[2]) * signs[1] - c.dist1 - c.dist2,
            cos: 0.0,
            sin: -signs[1],
        },
        ObstacleKind::Cercle => {
            let r = x1[1].hypot(x1[2]);
            let (cos, sin) = if r != 0.0 {
                (-x1[1] / r, -x1[2] / r)
            } else {
                (-1.0, 0.0)
            };
            Gap {
                dnorm: c.jeu - r,
                cos,
                sin,
            }
        }
        ObstacleKind::BiCercle => {
            let (dy, dz) = (x1[1] - x2[1], x1[2] - x2[2]);
            let r = dy.hypot(dz);
            let (cos, sin) = if r != 0.0 {
                (dy / r, dz / r)
            } else {
                (1.0, 0.0)
            };
            Gap {
                dnorm: r - c.dist1 - c.dist2,
                cos,
                sin,
            }
        }
        ObstacleKind::BiCercleInt => {
            let (dy, dz) = (x2[1] - x1[1], x2[2] - x1[2]);
            let r = dy.hypot(dz);
            let (cos, sin) = if r > 0.0 {
                (dy / r, dz / r)
            } else {
                (-1.0, 0.0)
            };
            Gap {
                dnorm: c.dist2 - c.dist1 - r,
                cos,
                sin,
            }
        }
    }
}
