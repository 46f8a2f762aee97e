//! DIS_CHOC: the shock force of DYNA_VIBRA (COMPORTEMENT RELATION='DIS_CHOC') between a
//! node and an obstacle, or between two nodes, with its stick/slip state and its outputs.
//!
//! Code_Aster's facts (routines `dtmforc_choc`, `fnorm`, `ftang`, `dtmprep_noli_choc`):
//! - Positions: node i at its initial coordinates + its displacement Φ_i q, in the obstacle
//!   frame relative to ORIG_OBST (`obstacle.rs`); two-node types use node 1 − node 2.
//! - Contact when the normal distance d ≤ 0. Normal force F_N = −RIGI_NOR·d − AMOR_NOR·v_N
//!   with v_N = (0, cos θ, sin θ)·(relative local velocity) = ḋ, clipped at 0 (never
//!   adhesive: the damping part cannot pull).
//! - Friction (FROTTEMENT='COULOMB': μ_s = μ_d = COULOMB; 'COULOMB_STAT_DYNA': μ_s =
//!   COULOMB_STAT, μ_d = COULOMB_DYNA), in contact only. Tangential velocity
//!   v_T = (−sin θ·v_y + cos θ·v_z, v_x). Slip is kept while not sticking, v_T·v_T,old ≥ 0
//!   and |v_T| > 1e-6 (absolute, Code_Aster's threshold): F_T = −μ_d F_N v_T/|v_T|, and the
//!   stick anchor moves with the node. Otherwise a stick trial F_T = F_T,anchor − RIGI_TAN·Δx_T
//!   − AMOR_TAN·v_T (Δx_T the tangential travel since the anchor); if |F_T| > μ_s F_N it
//!   slips (F_T = −μ_d F_N v_T/|v_T|, zero when v_T = 0) and the anchor is reset there.
//!   Out of contact the anchor follows the node and the forces and v_N, v_T are zero.
//! - Force on node 1 in the local frame: (F_T2, F_N cos θ − F_T1 sin θ, F_N sin θ + F_T1 cos θ);
//!   node 2 gets the opposite.
//! - AMOR_TAN not given with RIGI_TAN > 0: Code_Aster computes one
//!   ([`optimized_tangential_damping`]).
//! - Outputs (RECU_FONCTION NOEUD_CHOC PARA_Y): FN, FT1, FT2, VN, VT1, VT2, DXLOC, DYLOC,
//!   DZLOC (local position of node 1 relative to ORIG_OBST) and VINT1..VINT20 (the 20
//!   internal variables, [`ShockSample::vint`]).
//!
//! The state ([`ShockState`]) is advanced only at accepted steps: [`Shock::evaluate`] is
//! pure and returns the state the step would leave.
//!
//! A FLAMBAGE shock ([`Shock::with_buckling`]) has the same geometry and outputs; its
//! normal force is the buckling law of `flambage.rs`, whose internal variables ride in the
//! same state ([`ShockState::buckling`]), and it has no friction.

use super::error::{check_len, invalid, TransientError};
use super::flambage::{Buckling, BucklingState};
use super::obstacle::{
    normal_gap, obstacle_frame, rest_signs, Clearance, Gap, LocalFrame, ObstacleKind,
};
use super::support::SupportMotion;

/// Code_Aster's absolute threshold on |v_T| below which slip is not kept (ftang).
pub const SLIP_VELOCITY_THRESHOLD: f64 = 1e-6;

/// Three rows (DX, DY, DZ of a node in the global frame) of the map q ↦ node displacement,
/// sparse: the mode shapes at the node (generalized basis) or a selection (physical basis).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeRows {
    pub rows: [Vec<(usize, f64)>; 3],
}

impl NodeRows {
    /// From the mode shapes at the node: `dx[j]`, `dy[j]`, `dz[j]` of mode j.
    pub fn from_modes(dx: &[f64], dy: &[f64], dz: &[f64]) -> NodeRows {
        let row = |c: &[f64]| {
            c.iter()
                .copied()
                .enumerate()
                .filter(|p| p.1 != 0.0)
                .collect()
        };
        NodeRows {
            rows: [row(dx), row(dy), row(dz)],
        }
    }

    /// Physical basis: the free DOF indices of DX, DY, DZ (`None`: blocked, always zero).
    pub fn selection(dofs: [Option<usize>; 3]) -> NodeRows {
        let row = |d: Option<usize>| d.map(|i| vec![(i, 1.0)]).unwrap_or_default();
        NodeRows {
            rows: [row(dofs[0]), row(dofs[1]), row(dofs[2])],
        }
    }

    /// Node displacement (global) for the coordinates q.
    pub fn apply(&self, q: &[f64]) -> [f64; 3] {
        let mut u = [0.0; 3];
        for (ui, row) in u.iter_mut().zip(&self.rows) {
            *ui = row
                .iter()
                .map(|&(j, c)| c * q.get(j).copied().unwrap_or(0.0))
                .sum();
        }
        u
    }

    /// out += Φᵀ f (a global nodal force as generalized forces).
    pub fn add_transpose(&self, f: [f64; 3], out: &mut [f64]) {
        for (fi, row) in f.iter().zip(&self.rows) {
            for &(j, c) in row {
                if let Some(o) = out.get_mut(j) {
                    *o += c * fi;
                }
            }
        }
    }

    fn max_index(&self) -> Option<usize> {
        self.rows.iter().flatten().map(|p| p.0).max()
    }

    /// self − other, merged row by row (the relative rows of a two-node shock).
    fn minus(&self, other: &NodeRows) -> NodeRows {
        let mut out = NodeRows::default();
        for c in 0..3 {
            let mut r: Vec<(usize, f64)> = self.rows[c].clone();
            r.extend(other.rows[c].iter().map(|&(j, v)| (j, -v)));
            r.sort_by_key(|p| p.0);
            let mut merged: Vec<(usize, f64)> = Vec::with_capacity(r.len());
            for (j, v) in r {
                match merged.last_mut() {
                    Some(last) if last.0 == j => last.1 += v,
                    _ => merged.push((j, v)),
                }
            }
            merged.retain(|p| p.1 != 0.0);
            out.rows[c] = merged;
        }
        out
    }
}

/// FROTTEMENT of CHOC.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Friction {
    None,
    /// COULOMB = μ (static and dynamic).
    Coulomb {
        mu: f64,
    },
    /// COULOMB_STAT, COULOMB_DYNA.
    CoulombStatDyna {
        stat: f64,
        dyna: f64,
    },
}

impl Friction {
    /// (μ_static, μ_dynamic).
    pub fn coefficients(self) -> (f64, f64) {
        match self {
            Friction::None => (0.0, 0.0),
            Friction::Coulomb { mu } => (mu, mu),
            Friction::CoulombStatDyna { stat, dyna } => (stat, dyna),
        }
    }

    pub fn active(self) -> bool {
        let (s, d) = self.coefficients();
        s.abs() > f64::EPSILON || d.abs() > f64::EPSILON
    }
}

/// One CHOC occurrence, as the operator reads it (lengths in the mesh's unit).
#[derive(Clone, Debug, PartialEq)]
pub struct ShockSpec {
    pub obstacle: ObstacleKind,
    pub orig_obst: [f64; 3],
    pub norm_obst: [f64; 3],
    /// ANGL_VRIL in degrees, `None` when absent (the frame rule differs, obstacle.rs).
    pub angl_vril: Option<f64>,
    /// Initial coordinates of node 1 and, for the BI_ types, node 2.
    pub node1: [f64; 3],
    pub node2: Option<[f64; 3]>,
    pub jeu: f64,
    pub dist1: f64,
    pub dist2: f64,
    pub rigi_nor: f64,
    pub amor_nor: f64,
    pub rigi_tan: f64,
    pub amor_tan: f64,
    pub friction: Friction,
    /// UNIDIRECTIONNEL='OUI': the friction acts along the local x axis only (the axis
    /// Code_Aster's INFO lists for it; for a PLAN_ or BI_PLAN_ obstacle, NORM_OBST), the
    /// tangential sliding across it is free.
    pub friction_along_x_only: bool,
}

/// The stick/slip memory of a shock (VINT13..VINT20).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShockState {
    pub sticking: bool,
    /// Tangential force at the anchor (start of the current stick).
    pub old_ft: [f64; 2],
    /// Relative local position of the anchor.
    pub old_xl: [f64; 3],
    /// Tangential velocity of the last evaluation.
    pub old_vt: [f64; 2],
    /// The internal variables of a FLAMBAGE shock (`flambage.rs`); zero for DIS_CHOC.
    pub buckling: BucklingState,
}

impl ShockState {
    /// The stick/slip memory as Code_Aster's VINT13..VINT20: sticking (1/0), the F_T
    /// anchor (2), the anchor (3), the previous v_T (2).
    pub fn friction_memory(&self) -> [f64; 8] {
        [
            if self.sticking { 1.0 } else { 0.0 },
            self.old_ft[0],
            self.old_ft[1],
            self.old_xl[0],
            self.old_xl[1],
            self.old_xl[2],
            self.old_vt[0],
            self.old_vt[1],
        ]
    }

    /// Sets the stick/slip memory from its VINT13..VINT20 values.
    pub fn set_friction_memory(&mut self, v: &[f64; 8]) {
        self.sticking = v[0] != 0.0;
        self.old_ft = [v[1], v[2]];
        self.old_xl = [v[3], v[4], v[5]];
        self.old_vt = [v[6], v[7]];
    }
}

/// What RECU_FONCTION reads for a shock at an archived instant.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShockSample {
    pub f_n: f64,
    pub f_t1: f64,
    pub f_t2: f64,
    pub v_n: f64,
    pub v_t1: f64,
    pub v_t2: f64,
    /// Local position of node 1 relative to ORIG_OBST (DXLOC, DYLOC, DZLOC).
    pub loc1: [f64; 3],
    /// The same for node 2 (zero for one-node shocks): VINT7..VINT9.
    pub loc2: [f64; 3],
    /// The state after this evaluation (VINT13..VINT20).
    pub state: ShockState,
}

impl ShockSample {
    /// Code_Aster's parameter names, in RECU_FONCTION's order (VINTi are extra).
    pub const NAMES: [&'static str; 9] = [
        "FN", "FT1", "FT2", "VN", "VT1", "VT2", "DXLOC", "DYLOC", "DZLOC",
    ];

    /// The 20 internal variables in Code_Aster's order: FN, FT1, FT2, node 1 local x y z,
    /// node 2 local x y z, VN, VT1, VT2, sticking (1/0), F_T anchor (2), anchor (3),
    /// previous v_T (2).
    pub fn vint(&self) -> [f64; 20] {
        let m = self.state.friction_memory();
        [
            self.f_n,
            self.f_t1,
            self.f_t2,
            self.loc1[0],
            self.loc1[1],
            self.loc1[2],
            self.loc2[0],
            self.loc2[1],
            self.loc2[2],
            self.v_n,
            self.v_t1,
            self.v_t2,
            m[0],
            m[1],
            m[2],
            m[3],
            m[4],
            m[5],
            m[6],
            m[7],
        ]
    }

    /// A value by its Code_Aster name ("FN", ..., "DZLOC", "VINT1".."VINT20").
    pub fn get(&self, name: &str) -> Option<f64> {
        let name = name.trim();
        Some(match name {
            "FN" => self.f_n,
            "FT1" => self.f_t1,
            "FT2" => self.f_t2,
            "VN" => self.v_n,
            "VT1" => self.v_t1,
            "VT2" => self.v_t2,
            "DXLOC" => self.loc1[0],
            "DYLOC" => self.loc1[1],
            "DZLOC" => self.loc1[2],
            _ => {
                let i: usize = name.strip_prefix("VINT")?.parse().ok()?;
                return (1..=20).contains(&i).then(|| self.vint()[i - 1]);
            }
        })
    }
}

/// The result of one evaluation of a shock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShockEval {
    /// Force on node 1, global frame (node 2 gets the opposite).
    pub force: [f64; 3],
    pub gap: Gap,
    pub sample: ShockSample,
    /// A FLAMBAGE shock's normal slopes (dF_N/dp, −dF_N/dv_N) at this evaluation (the
    /// tangent of NEWMARK's iterations); `None` for DIS_CHOC.
    pub buckling_slopes: Option<(f64, f64)>,
}

/// A shock ready to integrate: geometry, law, rows and its committed state.
#[derive(Clone, Debug)]
pub struct Shock {
    pub spec: ShockSpec,
    pub frame: LocalFrame,
    signs: [f64; 2],
    rows1: NodeRows,
    rows2: Option<NodeRows>,
    /// Rows of the relative displacement (node 1 − node 2, or node 1).
    rel: NodeRows,
    /// The state of the last accepted step.
    pub state: ShockState,
    /// The supports' motion its nodes follow (MULT_APPUI; empty: fixed supports).
    support: SupportMotion,
    /// RELATION='FLAMBAGE': the buckling law replaces the normal force (no friction).
    buckling: Option<Buckling>,
}

impl Shock {
    /// Checks the parameters and builds the frame; `rows2` is required for the BI_ types
    /// and ignored otherwise.
    pub fn new(
        spec: ShockSpec,
        rows1: NodeRows,
        rows2: Option<NodeRows>,
    ) -> Result<Shock, TransientError> {
        for (kw, v) in [
            ("CHOC/JEU", spec.jeu),
            ("CHOC/DIST_1", spec.dist1),
            ("CHOC/DIST_2", spec.dist2),
            ("CHOC/RIGI_NOR", spec.rigi_nor),
            ("CHOC/AMOR_NOR", spec.amor_nor),
            ("CHOC/RIGI_TAN", spec.rigi_tan),
            ("CHOC/AMOR_TAN", spec.amor_tan),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(invalid(kw, format!("must be finite and ≥ 0, got {v:e}")));
            }
        }
        let (ms, md) = spec.friction.coefficients();
        if !(ms.is_finite() && md.is_finite() && ms >= 0.0 && md >= 0.0) {
            return Err(invalid("CHOC/COULOMB", "friction coefficients must be ≥ 0"));
        }
        let two = spec.obstacle.two_nodes();
        let (rows2, node2) = if two {
            let r2 = rows2.ok_or_else(|| {
                invalid(
                    "CHOC/NOEUD_2",
                    format!("{} needs a second node", spec.obstacle.name()),
                )
            })?;
            let n2 = spec
                .node2
                .ok_or_else(|| invalid("CHOC/NOEUD_2", "the coordinates of node 2 are missing"))?;
            (Some(r2), n2)
        } else {
            (None, [0.0; 3])
        };
        let frame = obstacle_frame(
            spec.obstacle,
            spec.norm_obst,
            spec.angl_vril,
            spec.node1,
            spec.node2,
        )?;
        let l1 = frame.to_local(sub(spec.node1, spec.orig_obst));
        let rel0 = if two {
            let l2 = frame.to_local(sub(node2, spec.orig_obst));
            sub(l1, l2)
        } else {
            l1
        };
        let rel = match &rows2 {
            Some(r2) => rows1.minus(r2),
            None => rows1.clone(),
        };
        Ok(Shock {
            signs: rest_signs(rel0),
            frame,
            rows1,
            rows2,
            rel,
            state: ShockState::default(),
            support: SupportMotion::default(),
            buckling: None,
            spec,
        })
    }

    /// RELATION='FLAMBAGE': the normal force is the buckling law (`flambage.rs`) instead of
    /// RIGI_NOR·penetration, without friction.
    pub fn with_buckling(mut self, law: Buckling) -> Shock {
        self.buckling = Some(law);
        self
    }

    /// The buckling law, for a FLAMBAGE shock.
    pub fn buckling(&self) -> Option<&Buckling> {
        self.buckling.as_ref()
    }

    /// The shock's nodes follow moving supports (MULT_APPUI): q is then the motion relative
    /// to them, and the gap and velocities are taken on the absolute motion.
    pub fn set_support(&mut self, support: SupportMotion) {
        self.support = support;
    }

    /// Largest generalized index the rows use (for a size check).
    pub fn max_index(&self) -> Option<usize> {
        let a = self.rows1.max_index();
        let b = self.rows2.as_ref().and_then(NodeRows::max_index);
        a.max(b)
    }

    /// Relative rows (node 1 − node 2, or node 1).
    pub fn relative_rows(&self) -> &NodeRows {
        &self.rel
    }

    fn clearance(&self) -> Clearance {
        Clearance {
            jeu: self.spec.jeu,
            dist1: self.spec.dist1,
            dist2: self.spec.dist2,
        }
    }

    /// Local positions of node 1 and node 2 (zero for one node) relative to ORIG_OBST.
    fn local_positions(&self, u1: [f64; 3], u2: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let o = self.spec.orig_obst;
        let p1 = add(self.spec.node1, u1);
        let l1 = self.frame.to_local(sub(p1, o));
        let l2 = match (self.rows2.is_some(), self.spec.node2) {
            (true, Some(n2)) => self.frame.to_local(sub(add(n2, u2), o)),
            _ => [0.0; 3],
        };
        (l1, l2)
    }

    /// Node displacements (global) of nodes 1 and 2 for q, relative to the supports.
    fn node_displacements(&self, q: &[f64]) -> ([f64; 3], [f64; 3]) {
        let u1 = self.rows1.apply(q);
        let u2 = self.rows2.as_ref().map(|r| r.apply(q)).unwrap_or([0.0; 3]);
        (u1, u2)
    }

    /// Absolute node displacements (global) of nodes 1 and 2 at t for q: with moving
    /// supports, their motion is added.
    pub fn node_displacements_at(&self, t: f64, q: &[f64]) -> ([f64; 3], [f64; 3]) {
        self.with_support(q, || self.support.displacement(t))
    }

    /// Absolute node velocities (global) of nodes 1 and 2 at t for q̇.
    pub fn node_velocities_at(&self, t: f64, v: &[f64]) -> ([f64; 3], [f64; 3]) {
        self.with_support(v, || self.support.velocity(t))
    }

    /// Φ x at nodes 1 and 2, plus the supports' share when they move.
    fn with_support(&self, x: &[f64], share: impl Fn() -> [[f64; 3]; 2]) -> ([f64; 3], [f64; 3]) {
        let (a1, a2) = self.node_displacements(x);
        if self.support.is_empty() {
            return (a1, a2);
        }
        let [s1, s2] = share();
        (add(a1, s1), add(a2, s2))
    }

    /// The relative velocity of the shock (node 1 − node 2, or node 1) at t, absolute
    /// with moving supports.
    fn relative_velocity(&self, t: f64, v: &[f64]) -> [f64; 3] {
        let dv = self.rel.apply(v);
        if self.support.is_empty() {
            return dv;
        }
        let [s1, s2] = self.support.velocity(t);
        let s = if self.rows2.is_some() {
            sub(s1, s2)
        } else {
            s1
        };
        add(dv, s)
    }

    /// Normal distance from the node displacements (the event function of the adaptive
    /// schemes).
    pub fn gap_from_displacements(&self, u1: [f64; 3], u2: [f64; 3]) -> Gap {
        let (l1, l2) = self.local_positions(u1, u2);
        normal_gap(self.spec.obstacle, l1, l2, self.clearance(), self.signs)
    }

    /// The force for the state (q, v) with fixed supports (any t), from the stick/slip
    /// memory `state` (pure).
    #[cfg(test)]
    pub fn evaluate(&self, q: &[f64], v: &[f64], state: &ShockState) -> ShockEval {
        self.evaluate_at(0.0, q, v, state)
    }

    /// The force for the state (q, v) at t (the supports' motion at t), from the
    /// stick/slip memory `state` (pure).
    pub fn evaluate_at(&self, t: f64, q: &[f64], v: &[f64], state: &ShockState) -> ShockEval {
        let (u1, u2) = self.node_displacements_at(t, q);
        let (l1, l2) = self.local_positions(u1, u2);
        let two = self.rows2.is_some();
        let d = if two { sub(l1, l2) } else { l1 };
        let dv = self.frame.to_local(self.relative_velocity(t, v));
        let gap = normal_gap(self.spec.obstacle, l1, l2, self.clearance(), self.signs);
        let mut sample = ShockSample {
            loc1: l1,
            loc2: l2,
            ..ShockSample::default()
        };
        if let Some(law) = &self.buckling {
            return self.buckling_eval(law, gap, dv, state, sample);
        }
        let mut new_state = ShockState::default();
        let mut flocal = [0.0; 3];
        if gap.dnorm <= 0.0 {
            let vn = dv[1] * gap.cos + dv[2] * gap.sin;
            let fnorm = (-self.spec.rigi_nor * gap.dnorm - self.spec.amor_nor * vn).max(0.0);
            sample.f_n = fnorm;
            sample.v_n = vn;
            flocal = [0.0, fnorm * gap.cos, fnorm * gap.sin];
            if self.spec.friction.active() {
                let (ft, vt, st) = self.tangential(fnorm, d, dv, gap, state);
                flocal[0] += ft[1];
                flocal[1] -= ft[0] * gap.sin;
                flocal[2] += ft[0] * gap.cos;
                sample.f_t1 = ft[0];
                sample.f_t2 = ft[1];
                sample.v_t1 = vt[0];
                sample.v_t2 = vt[1];
                new_state = st;
            } else {
                // The sliding velocity, recorded without friction too (the wear power
                // FN·|V_T| of POST_DYNA_MODA_T needs it).
                let vt = tangential_velocity(dv, gap);
                sample.v_t1 = vt[0];
                sample.v_t2 = vt[1];
            }
        } else {
            new_state.old_xl = d;
        }
        sample.state = new_state;
        ShockEval {
            force: self.frame.to_global(flocal),
            gap,
            sample,
            buckling_slopes: None,
        }
    }

    /// A FLAMBAGE shock (Code_Aster's `dtmforc_flam`): in contact the buckling law gives the
    /// normal force and advances its internal variables; out of contact the force is zero
    /// and they are kept. No friction: FT1, FT2, VT1, VT2 stay zero, and VN is recorded in
    /// contact only.
    fn buckling_eval(
        &self,
        law: &Buckling,
        gap: Gap,
        dv: [f64; 3],
        state: &ShockState,
        mut sample: ShockSample,
    ) -> ShockEval {
        let mut new_state = ShockState {
            buckling: state.buckling,
            ..ShockState::default()
        };
        let mut flocal = [0.0; 3];
        let mut slopes = (0.0, 0.0);
        if gap.dnorm <= 0.0 {
            let vn = dv[1] * gap.cos + dv[2] * gap.sin;
            let r = law.force(-gap.dnorm, vn, &state.buckling);
            sample.f_n = r.force;
            sample.v_n = vn;
            flocal = [0.0, r.force * gap.cos, r.force * gap.sin];
            new_state.buckling = r.state;
            slopes = (r.stiffness, r.damping);
        }
        sample.state = new_state;
        ShockEval {
            force: self.frame.to_global(flocal),
            gap,
            sample,
            buckling_slopes: Some(slopes),
        }
    }

    /// Code_Aster's stick/slip algorithm (module doc): (F_T, v_T, new state).
    fn tangential(
        &self,
        fnorm: f64,
        d: [f64; 3],
        dv: [f64; 3],
        gap: Gap,
        state: &ShockState,
    ) -> ([f64; 2], [f64; 2], ShockState) {
        let (mu_s, mu_d) = self.spec.friction.coefficients();
        let (c, s) = (gap.cos, gap.sin);
        let mut vt = tangential_velocity(dv, gap);
        // One direction: the sliding across the local x axis neither slides nor sticks,
        // so the first tangential component of the force stays zero.
        let across = if self.spec.friction_along_x_only {
            0.0
        } else {
            1.0
        };
        vt[0] *= across;
        let scal = vt[0] * state.old_vt[0] + vt[1] * state.old_vt[1];
        let nvt = vt[0].hypot(vt[1]);
        let mut st = *state;
        let slip_force = |nvt: f64| {
            if nvt <= f64::EPSILON {
                [0.0, 0.0]
            } else {
                [-mu_d * fnorm * vt[0] / nvt, -mu_d * fnorm * vt[1] / nvt]
            }
        };
        let ft;
        if scal >= 0.0 && !state.sticking && nvt > SLIP_VELOCITY_THRESHOLD {
            ft = slip_force(nvt);
            st.old_ft = ft;
            st.old_xl = d;
        } else {
            let ox = state.old_xl;
            let dxt = [
                across * (-(d[1] - ox[1]) * s + (d[2] - ox[2]) * c),
                d[0] - ox[0],
            ];
            st.sticking = true;
            let trial = [
                state.old_ft[0] - self.spec.rigi_tan * dxt[0] - self.spec.amor_tan * vt[0],
                state.old_ft[1] - self.spec.rigi_tan * dxt[1] - self.spec.amor_tan * vt[1],
            ];
            if trial[0].hypot(trial[1]) > mu_s * fnorm {
                st.sticking = false;
                ft = slip_force(nvt);
                st.old_ft = ft;
                st.old_xl = d;
            } else {
                ft = trial;
            }
        }
        st.old_vt = vt;
        (ft, vt, st)
    }

    /// out += (generalized force of `eval`): Φ₁ᵀ F − Φ₂ᵀ F.
    pub fn add_generalized(&self, eval: &ShockEval, out: &mut [f64]) {
        self.rel.add_transpose(eval.force, out);
    }

    /// Tangent of the force on node 1 with respect to the relative global displacement
    /// and velocity, at an evaluation (normal penalty and, when sticking, the tangential
    /// spring; the turning of a circle's normal is left out): (K, C), 3×3 global, such
    /// that δF ≈ −K δx − C δv.
    pub fn tangent(&self, eval: &ShockEval) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
        let mut k = [[0.0; 3]; 3];
        let mut c = [[0.0; 3]; 3];
        if eval.sample.f_n <= 0.0 {
            return (k, c);
        }
        let g = eval.gap;
        let n = self.frame.to_global([0.0, g.cos, g.sin]);
        let add = |m: &mut [[f64; 3]; 3], w: f64, a: [f64; 3]| {
            for i in 0..3 {
                for j in 0..3 {
                    m[i][j] += w * a[i] * a[j];
                }
            }
        };
        // A FLAMBAGE shock: the slopes of the branch its law took.
        let (kn, cn) = eval
            .buckling_slopes
            .unwrap_or((self.spec.rigi_nor, self.spec.amor_nor));
        add(&mut k, kn, n);
        add(&mut c, cn, n);
        if self.spec.friction.active() && eval.sample.state.sticking {
            let t1 = self.frame.to_global([0.0, -g.sin, g.cos]);
            let t2 = self.frame.to_global([1.0, 0.0, 0.0]);
            for t in [t1, t2] {
                add(&mut k, self.spec.rigi_tan, t);
                add(&mut c, self.spec.amor_tan, t);
            }
        }
        (k, c)
    }

    /// A bound of the stiffness the shock can add, 3×3 global on the relative
    /// displacement (for the stability estimate): RIGI_NOR on the normal directions the
    /// obstacle can take, RIGI_TAN on the tangential ones when there is friction.
    pub fn stiffness_bound(&self) -> [[f64; 3]; 3] {
        let kn = self
            .buckling
            .as_ref()
            .map_or(self.spec.rigi_nor, Buckling::stiffness_bound);
        let kt = if self.spec.friction.active() {
            self.spec.rigi_tan
        } else {
            0.0
        };
        let local = match self.spec.obstacle {
            ObstacleKind::PlanY | ObstacleKind::BiPlanY => [kt, kn, kt],
            ObstacleKind::PlanZ | ObstacleKind::BiPlanZ => [kt, kt, kn],
            _ => [kt, kn.max(kt), kn.max(kt)],
        };
        let r = &self.frame.rows;
        let mut b = [[0.0; 3]; 3];
        for (i, bi) in b.iter_mut().enumerate() {
            for (j, bij) in bi.iter_mut().enumerate() {
                *bij = (0..3).map(|l| r[l][i] * local[l] * r[l][j]).sum();
            }
        }
        b
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// Code_Aster's AMOR_TAN when it is not given and RIGI_TAN > 0 (`dtmprep_noli_choc`): the
/// mode j with the largest m_j·|tangential part of its relative node displacement| (rigid
/// modes, ω_j⁴ < 1e-10, skipped) gives m = m_j, k = ω_j² m_j, ξ its damping ratio, and
/// AMOR_TAN = max(0, 2√(m (k + RIGI_TAN)) − 2 ξ √(k m)). `modal_mass`, `omega2`,
/// `damping_ratio` per generalized coordinate.
pub fn optimized_tangential_damping(
    shock: &Shock,
    modal_mass: &[f64],
    omega2: &[f64],
    damping_ratio: &[f64],
) -> Result<f64, TransientError> {
    let n = modal_mass.len();
    check_len("omega2", omega2.len(), n)?;
    check_len("damping ratios", damping_ratio.len(), n)?;
    let mut best: Option<(usize, f64)> = None;
    let mut e = vec![0.0; n];
    for j in 0..n {
        if omega2[j] * omega2[j] < 1e-10 {
            continue;
        }
        e.iter_mut().for_each(|x| *x = 0.0);
        e[j] = 1.0;
        let l = shock.frame.to_local(shock.rel.apply(&e));
        let t2 = match shock.spec.obstacle {
            ObstacleKind::PlanY | ObstacleKind::BiPlanY => l[0] * l[0] + l[2] * l[2],
            ObstacleKind::PlanZ | ObstacleKind::BiPlanZ => l[0] * l[0] + l[1] * l[1],
            _ => l[0] * l[0],
        };
        let w = modal_mass[j] * t2.sqrt();
        if best.is_none_or(|(_, b)| w > b) {
            best = Some((j, w));
        }
    }
    let Some((j, _)) = best else { return Ok(0.0) };
    let m = modal_mass[j];
    let k = omega2[j] * m;
    let kt = shock.spec.rigi_tan;
    let xi = damping_ratio[j];
    Ok((2.0 * (m * (k + kt)).sqrt() - 2.0 * xi * (k * m).sqrt()).max(0.0))
}

/// The sliding velocity (V_T1, V_T2) in the tangent plane of the contact: along the
/// contact's tangent in the local (y, z) plane, and along the local x axis.
fn tangential_velocity(dv: [f64; 3], gap: Gap) -> [f64; 2] {
    [-gap.sin * dv[1] + gap.cos * dv[2], dv[0]]
}
