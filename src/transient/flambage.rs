//! FLAMBAGE: the buckling shock of DYNA_VIBRA (COMPORTEMENT RELATION='FLAMBAGE', or the
//! FLAMBAGE factor of Code_Aster 13.x): a stop whose support buckles when the contact force
//! reaches a critical value, then crushes under a lower post-buckling force and keeps the
//! crush.
//!
//! The law acts on the normal penetration p = −d of the obstacle's distance d (`obstacle.rs`,
//! the same geometry as DIS_CHOC: d < 0 in contact) and on the normal velocity v_N = ḋ
//! (negative while the contact loads, positive while it unloads). As Code_Aster computes it
//! (routines `mdflam`, `dtmforc_flam`, `dtmprep_noli_flam` of versions 15 and 16):
//!
//! - **Before buckling** (crush c = 0): the elastic stop F = RIGI_NOR·p − AMOR_NOR·v_N,
//!   never below 0, as long as p < (FNOR_CRIT + AMOR_NOR·v_N)/RIGI_NOR. The evaluation that
//!   reaches it gives F = FNOR_CRIT and marks the element buckled (c = 1e-20, Code_Aster's
//!   flag), its unloading stiffness k_u = RIGI_NOR.
//! - **Loading beyond the largest penetration reached so far** (p > p_max and v_N ≤ 0):
//!   * up to p₀ = FNOR_CRIT/RIGI_NOR + LARG_PLAT: a plateau F = FNOR_CRIT, the crush
//!     following the node, c = p − FNOR_CRIT/k_u;
//!   * from p₀ to p₁ = p₀ + ENFO_FL: the force falls linearly from FNOR_CRIT to
//!     FNOR_POST_FL (ENFO_FL is 1e-20 by default: a sudden drop), the crush jumps to
//!     LARG_PLAT and k_u = F/(p − c);
//!   * beyond p₁: the post-buckling plateau F = FNOR_POST_FL, the crush following the node,
//!     c = p − FNOR_POST_FL/k_u with the post-buckling stiffness k_u. By default k_u =
//!     FNOR_POST_FL/(FNOR_CRIT/RIGI_NOR + ENFO_FL), the line from (LARG_PLAT, 0) to
//!     (p₁, FNOR_POST_FL); DEPL_POST_FL and RIGI_POST_FL give further crushes and their
//!     stiffnesses, interpolated in between (the crush and k_u as functions of the total
//!     penetration c_j + FNOR_POST_FL/k_j), the last one kept beyond; RIGI_NOR_POST_FL
//!     (Code_Aster 13 and 14) is the post-buckling stiffness of a crush starting at
//!     FNOR_CRIT/RIGI_NOR − FNOR_POST_FL/RIGI_NOR_POST_FL.
//! - **Unloading or reloading below p_max** (v_N > 0 or p ≤ p_max): elastic from the crushed
//!   position, F = k_u·(p − c) − C·v_N, capped by the envelope above (FNOR_CRIT before p₀,
//!   the falling line between p₀ and p₁, FNOR_POST_FL beyond), never below 0; the contact
//!   is lost when p < c (F = 0), i.e. at the crushed position, not at the original one.
//! - Damping C (AMOR_NOR before buckling, AMOR_FL in the fall, AMOR_POST_FL on the
//!   post-buckling segments, AMOR_NOR by default): with CRIT_AMOR='INCLUS' (the default) it
//!   is inside the force the thresholds are compared with; with 'EXCLUS' it is added after
//!   the comparison (F − C·v_N, never below 0, and 0 when p < c).
//! - The crush never goes below 0.
//! - Out of contact (d > 0) the law is not evaluated: F = 0 and its state is kept.
//!
//! The internal variables ([`BucklingState`]) are Code_Aster's: the crush c (DEFPLA, read
//! by POST_DYNA_MODA_T as ECRAS_RESI), the unloading stiffness k_u (RIGIFL), the largest
//! penetration p_max (DEFMAX) and the current damping (CFL). Like the stick/slip memory of
//! DIS_CHOC they advance at accepted steps only (`dis_choc.rs`).
//!
//! Departures: Code_Aster raises alarm ALGORITH5_86 when the penetration passes the last
//! DEPL_POST_FL; the law keeps the last stiffness there, as Code_Aster does, silently.
//! RIGI_NOR_POST_FL is read into this law (version 15's): Code_Aster 13's own law, which
//! took it, set the crush and the post-buckling stiffness at the very evaluation that
//! buckles, where version 15 sets them at the next loading one; the two differ only if the
//! contact unloads right at that step.

use super::error::{invalid, TransientError};

/// Code_Aster's value of the crush at the evaluation that buckles the element: nonzero, so
/// that the element is known to have buckled.
pub const BUCKLED_FLAG: f64 = 1e-20;

/// A post-buckling segment: the crush c_j (plastic displacement), its unloading stiffness
/// k_j, the total penetration c_j + FNOR_POST_FL/k_j where it holds, and its damping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PostSegment {
    pub crush: f64,
    pub stiffness: f64,
    pub total: f64,
    pub damping: f64,
}

/// The parameters of a FLAMBAGE shock, checked ([`Buckling::new`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Buckling {
    /// RIGI_NOR, AMOR_NOR: the stop before buckling.
    pub rigi_nor: f64,
    pub amor_nor: f64,
    /// FNOR_CRIT: the force that buckles the element.
    pub fnor_crit: f64,
    /// FNOR_POST_FL: the post-buckling force.
    pub fnor_post_fl: f64,
    /// ENFO_FL: the penetration over which the force falls from FNOR_CRIT to FNOR_POST_FL.
    pub enfo_fl: f64,
    /// The end of the plateau at FNOR_CRIT: FNOR_CRIT/RIGI_NOR + LARG_PLAT.
    pub plateau_end: f64,
    /// The post-buckling segments, the first one reached at plateau_end + ENFO_FL.
    pub segments: Vec<PostSegment>,
    /// CRIT_AMOR='INCLUS' (true, the default) or 'EXCLUS'.
    pub damping_in_criterion: bool,
}

/// What a user gives for a FLAMBAGE shock (the keywords, defaults applied).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BucklingSpec {
    pub rigi_nor: f64,
    pub amor_nor: f64,
    pub fnor_crit: f64,
    pub fnor_post_fl: f64,
    /// ENFO_FL (Code_Aster's default 1e-20).
    pub enfo_fl: f64,
    /// LARG_PLAT (default 0).
    pub larg_plat: f64,
    /// AMOR_FL (default AMOR_NOR).
    pub amor_fl: Option<f64>,
    /// DEPL_POST_FL, RIGI_POST_FL, AMOR_POST_FL (the same length, the last optional).
    pub depl_post_fl: Vec<f64>,
    pub rigi_post_fl: Vec<f64>,
    pub amor_post_fl: Vec<f64>,
    /// RIGI_NOR_POST_FL (Code_Aster 13 and 14).
    pub rigi_nor_post_fl: Option<f64>,
    pub damping_in_criterion: bool,
}

/// The internal variables of a FLAMBAGE shock (module doc), all zero before any contact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BucklingState {
    /// The crush c (Code_Aster's DEFPLA; POST_DYNA_MODA_T's ECRAS_RESI): > 0 once buckled.
    pub crush: f64,
    /// The unloading stiffness k_u (RIGIFL).
    pub stiffness: f64,
    /// The largest penetration reached (DEFMAX).
    pub max_penetration: f64,
    /// The damping of the current segment (CFL).
    pub damping: f64,
}

impl BucklingState {
    /// Whether the element has buckled.
    pub fn buckled(&self) -> bool {
        self.crush > 0.0
    }
}

/// One evaluation of the law: the normal force, its slopes for an implicit scheme (dF/dp,
/// −dF/dv_N), and the state it leaves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BucklingForce {
    pub force: f64,
    pub stiffness: f64,
    pub damping: f64,
    pub state: BucklingState,
}

fn positive(kw: &str, v: f64) -> Result<(), TransientError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(kw, format!("must be > 0, got {v:e}")))
    }
}

fn non_negative(kw: &str, v: f64) -> Result<(), TransientError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(invalid(kw, format!("must be ≥ 0, got {v:e}")))
    }
}

impl Buckling {
    /// The law of `spec`, with Code_Aster's derived quantities, or an error naming the
    /// keyword (as `FLAMBAGE/KEY`).
    pub fn new(spec: &BucklingSpec) -> Result<Buckling, TransientError> {
        positive("FLAMBAGE/RIGI_NOR", spec.rigi_nor)?;
        non_negative("FLAMBAGE/AMOR_NOR", spec.amor_nor)?;
        positive("FLAMBAGE/FNOR_CRIT", spec.fnor_crit)?;
        positive("FLAMBAGE/FNOR_POST_FL", spec.fnor_post_fl)?;
        if spec.fnor_post_fl > spec.fnor_crit {
            return Err(invalid(
                "FLAMBAGE/FNOR_POST_FL",
                format!(
                    "{:e} is above FNOR_CRIT = {:e}: the force after buckling is at most the \
                     critical one",
                    spec.fnor_post_fl, spec.fnor_crit
                ),
            ));
        }
        positive("FLAMBAGE/ENFO_FL", spec.enfo_fl)?;
        non_negative("FLAMBAGE/LARG_PLAT", spec.larg_plat)?;
        if let Some(c) = spec.amor_fl {
            non_negative("FLAMBAGE/AMOR_FL", c)?;
        }
        let n = spec.depl_post_fl.len();
        if spec.rigi_post_fl.len() != n {
            return Err(invalid(
                "FLAMBAGE/RIGI_POST_FL",
                format!(
                    "{} value(s) for {n} of DEPL_POST_FL: give one stiffness per crush",
                    spec.rigi_post_fl.len()
                ),
            ));
        }
        if !spec.amor_post_fl.is_empty() && spec.amor_post_fl.len() != n {
            return Err(invalid(
                "FLAMBAGE/AMOR_POST_FL",
                format!(
                    "{} value(s) for {n} of DEPL_POST_FL: give one damping per crush",
                    spec.amor_post_fl.len()
                ),
            ));
        }
        let crit_pen = spec.fnor_crit / spec.rigi_nor;
        let first_damping = spec.amor_fl.unwrap_or(spec.amor_nor);
        let (first_crush, first_stiffness, plateau_end) = match spec.rigi_nor_post_fl {
            Some(k) => {
                positive("FLAMBAGE/RIGI_NOR_POST_FL", k)?;
                if spec.larg_plat != 0.0 || n > 0 {
                    return Err(invalid(
                        "FLAMBAGE/RIGI_NOR_POST_FL",
                        "RIGI_NOR_POST_FL (Code_Aster 13 and 14) sets the post-buckling \
                         stiffness alone: it does not go with LARG_PLAT or DEPL_POST_FL",
                    ));
                }
                let crush = crit_pen - spec.fnor_post_fl / k;
                if crush < 0.0 {
                    return Err(invalid(
                        "FLAMBAGE/RIGI_NOR_POST_FL",
                        format!(
                            "FNOR_POST_FL/RIGI_NOR_POST_FL = {:e} exceeds FNOR_CRIT/RIGI_NOR = \
                             {crit_pen:e}: the post-buckling line would start before the stop",
                            spec.fnor_post_fl / k
                        ),
                    ));
                }
                (crush, k, crit_pen)
            }
            None => (
                spec.larg_plat,
                spec.fnor_post_fl / (crit_pen + spec.enfo_fl),
                crit_pen + spec.larg_plat,
            ),
        };
        let mut segments = Vec::with_capacity(n + 1);
        segments.push(PostSegment {
            crush: first_crush,
            stiffness: first_stiffness,
            total: first_crush + spec.fnor_post_fl / first_stiffness,
            damping: first_damping,
        });
        for j in 0..n {
            let crush = spec.depl_post_fl[j];
            let stiffness = spec.rigi_post_fl[j];
            non_negative("FLAMBAGE/DEPL_POST_FL", crush)?;
            positive("FLAMBAGE/RIGI_POST_FL", stiffness)?;
            let damping = spec.amor_post_fl.get(j).copied().unwrap_or(first_damping);
            non_negative("FLAMBAGE/AMOR_POST_FL", damping)?;
            segments.push(PostSegment {
                crush,
                stiffness,
                total: crush + spec.fnor_post_fl / stiffness,
                damping,
            });
        }
        for w in segments.windows(2) {
            if w[1].crush < w[0].crush {
                return Err(invalid(
                    "FLAMBAGE/DEPL_POST_FL",
                    "the crushes must increase (from LARG_PLAT)",
                ));
            }
            if w[1].total < w[0].total {
                return Err(invalid(
                    "FLAMBAGE/RIGI_POST_FL",
                    "DEPL_POST_FL + FNOR_POST_FL/RIGI_POST_FL must increase: a crush's \
                     total penetration cannot come before the previous one's",
                ));
            }
        }
        Ok(Buckling {
            rigi_nor: spec.rigi_nor,
            amor_nor: spec.amor_nor,
            fnor_crit: spec.fnor_crit,
            fnor_post_fl: spec.fnor_post_fl,
            enfo_fl: spec.enfo_fl,
            plateau_end,
            segments,
            damping_in_criterion: spec.damping_in_criterion,
        })
    }

    /// The penetration where the post-buckling plateau begins (p₁).
    fn post_start(&self) -> f64 {
        self.segments[0].total
    }

    /// The slope of the fall from FNOR_CRIT to FNOR_POST_FL (negative).
    fn fall_slope(&self) -> f64 {
        (self.fnor_post_fl - self.fnor_crit) / self.enfo_fl
    }

    /// The largest stiffness the shock can show (for the stability estimate).
    pub fn stiffness_bound(&self) -> f64 {
        self.segments
            .iter()
            .map(|s| s.stiffness)
            .fold(self.rigi_nor, f64::max)
    }

    /// The force at penetration `pen` = −d (≥ 0 in contact) and normal velocity `vn`, from
    /// the internal variables `state` (module doc). Pure: the state it would leave is in
    /// the result.
    pub fn force(&self, pen: f64, vn: f64, state: &BucklingState) -> BucklingForce {
        let mut st = *state;
        let included = self.damping_in_criterion;
        let (c_crit, c_state) = if included {
            (self.amor_nor, state.damping)
        } else {
            (0.0, 0.0)
        };
        let kn = self.rigi_nor;
        let mut force;
        // The slopes of the branch taken (for NEWMARK's Newton iterations).
        let (mut dfdp, mut dfdv) = (0.0, 0.0);
        if state.crush <= 0.0 {
            st.stiffness = kn;
            st.damping = self.amor_nor;
            if pen < 0.0 {
                force = 0.0;
            } else if pen < (self.fnor_crit + c_crit * vn) / kn {
                force = (kn * pen - c_crit * vn).max(0.0);
                if force > 0.0 {
                    (dfdp, dfdv) = (kn, c_crit);
                }
            } else {
                force = self.fnor_crit;
                st.crush = BUCKLED_FLAG;
            }
        } else if pen < state.crush {
            force = 0.0;
        } else if vn > 0.0 || pen <= state.max_penetration {
            // Elastic from the crushed position, under the envelope.
            force = state.stiffness * (pen - state.crush) - c_state * vn;
            (dfdp, dfdv) = (state.stiffness, c_state);
            if included {
                let p1 = self.post_start();
                let fall = self.fnor_crit + self.fall_slope() * (pen - self.plateau_end);
                if pen < self.plateau_end && force >= self.fnor_crit {
                    force = self.fnor_crit;
                    (dfdp, dfdv) = (0.0, 0.0);
                } else if force >= fall && pen < p1 {
                    force = fall;
                    (dfdp, dfdv) = (self.fall_slope(), 0.0);
                } else if force >= self.fnor_post_fl && pen >= p1 {
                    force = self.fnor_post_fl;
                    (dfdp, dfdv) = (0.0, 0.0);
                }
                if force < 0.0 {
                    force = 0.0;
                    (dfdp, dfdv) = (0.0, 0.0);
                }
            }
        } else {
            force = self.load_beyond(pen, &mut st);
        }
        if st.crush < 0.0 {
            st.crush = 0.0;
        }
        if pen > st.max_penetration {
            st.max_penetration = pen;
        }
        if !included {
            force -= st.damping * vn;
            dfdv += st.damping;
            if force < 0.0 || pen < st.crush {
                force = 0.0;
                (dfdp, dfdv) = (0.0, 0.0);
            }
        }
        BucklingForce {
            force,
            stiffness: dfdp,
            damping: dfdv,
            state: st,
        }
    }

    /// Loading beyond the largest penetration: the plateau, the fall or the post-buckling
    /// plateau, moving the crush along (module doc). Returns the force; `st` updated.
    fn load_beyond(&self, pen: f64, st: &mut BucklingState) -> f64 {
        let p1 = self.post_start();
        if pen < self.plateau_end {
            st.crush = pen - self.fnor_crit / st.stiffness;
            return self.fnor_crit;
        }
        if pen < p1 {
            let first = &self.segments[0];
            let rise = pen - self.plateau_end;
            let force = self.fnor_crit + self.fall_slope() * rise;
            st.stiffness = force / (pen - st.crush);
            st.crush = first.crush;
            st.damping = self.amor_nor + (first.damping - self.amor_nor) / self.enfo_fl * rise;
            return force;
        }
        let f = self.fnor_post_fl;
        let last = self.segments[self.segments.len() - 1];
        if self.segments.len() < 2 || pen > last.total {
            // One segment, or beyond the last one: its stiffness kept.
            let seg = if self.segments.len() < 2 {
                self.segments[0]
            } else {
                last
            };
            st.stiffness = f / (seg.total - seg.crush);
            st.crush = pen - f / st.stiffness;
            st.damping = seg.damping;
            return f;
        }
        for w in self.segments.windows(2) {
            if pen >= w[0].total && pen < w[1].total {
                let alpha = (pen - w[0].total) / (w[1].total - w[0].total);
                st.crush = w[0].crush + alpha * (w[1].crush - w[0].crush);
                st.damping = w[0].damping + alpha * (w[1].damping - w[0].damping);
                st.stiffness = f / (pen - st.crush);
            }
        }
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// sdnd105a's element: RIGI_NOR 1, FNOR_CRIT 1, FNOR_POST_FL 0.5, defaults.
    fn sdnd105a() -> Buckling {
        Buckling::new(&BucklingSpec {
            rigi_nor: 1.0,
            fnor_crit: 1.0,
            fnor_post_fl: 0.5,
            enfo_fl: 1e-20,
            damping_in_criterion: true,
            ..BucklingSpec::default()
        })
        .unwrap()
    }

    /// Loads the law through the penetrations `pens` at velocity `vn`, committing each.
    fn walk(law: &Buckling, pens: &[f64], vn: f64, st: &mut BucklingState) -> Vec<f64> {
        pens.iter()
            .map(|&p| {
                let r = law.force(p, vn, st);
                *st = r.state;
                r.force
            })
            .collect()
    }

    /// The default post-buckling stiffness is FNOR_POST_FL/(FNOR_CRIT/RIGI_NOR + ENFO_FL):
    /// 0.5 for sdnd105a, where the crush after a penetration p is p − 1.
    #[test]
    fn elastic_then_buckled_then_post_buckling_plateau() {
        let law = sdnd105a();
        assert_eq!(law.segments[0].stiffness, 0.5);
        assert_eq!(law.post_start(), 1.0);
        let mut st = BucklingState::default();
        // Elastic below FNOR_CRIT/RIGI_NOR = 1.
        assert_eq!(
            walk(&law, &[0.25, 0.5, 0.99], -1.0, &mut st),
            [0.25, 0.5, 0.99]
        );
        assert!(!st.buckled());
        // The evaluation that reaches it: FNOR_CRIT, buckled.
        assert_eq!(walk(&law, &[1.01], -1.0, &mut st), [1.0]);
        assert_eq!(st.crush, BUCKLED_FLAG);
        assert_eq!(st.stiffness, 1.0);
        // Loading on: the post-buckling plateau, the crush following the node.
        assert_eq!(walk(&law, &[2.0, 4.0], -1.0, &mut st), [0.5, 0.5]);
        assert_eq!(st.crush, 3.0);
        assert_eq!(st.stiffness, 0.5);
        assert_eq!(st.max_penetration, 4.0);
        // Unloading: elastic from the crush with k_u = 0.5, lost below the crush.
        let f = walk(&law, &[3.8, 3.2, 2.9], 1.0, &mut st);
        assert!((f[0] - 0.4).abs() < 1e-15 && (f[1] - 0.1).abs() < 1e-15 && f[2] == 0.0);
        assert_eq!(st.crush, 3.0);
        // Reloading up to p_max: elastic again, back to FNOR_POST_FL there.
        assert!((walk(&law, &[3.5], -1.0, &mut st)[0] - 0.25).abs() < 1e-15);
        assert!((walk(&law, &[3.99], -1.0, &mut st)[0] - 0.495).abs() < 1e-15);
        assert_eq!(walk(&law, &[4.0], -1.0, &mut st)[0], 0.5);
        assert_eq!(st.crush, 3.0);
        // Beyond it: the plateau again, crushing further.
        assert_eq!(walk(&law, &[4.5], -1.0, &mut st)[0], 0.5);
        assert_eq!(st.crush, 3.5);
    }

    /// LARG_PLAT and ENFO_FL: a plateau at FNOR_CRIT, then a linear fall to FNOR_POST_FL.
    #[test]
    fn plateau_and_fall() {
        let law = Buckling::new(&BucklingSpec {
            rigi_nor: 10.0,
            fnor_crit: 2.0,
            fnor_post_fl: 1.0,
            enfo_fl: 0.1,
            larg_plat: 0.3,
            damping_in_criterion: true,
            ..BucklingSpec::default()
        })
        .unwrap();
        // p₀ = 0.2 + 0.3, p₁ = 0.6; k_1 = 1/(0.2 + 0.1).
        assert!((law.plateau_end - 0.5).abs() < 1e-15);
        assert!((law.post_start() - 0.6).abs() < 1e-15);
        let mut st = BucklingState::default();
        let f = walk(&law, &[0.1, 0.2, 0.4, 0.55, 0.7], -1.0, &mut st);
        assert!((f[0] - 1.0).abs() < 1e-15);
        assert_eq!(f[1], 2.0); // buckles
        assert_eq!(f[2], 2.0); // plateau
        assert!((f[3] - 1.5).abs() < 1e-12); // half-way down the fall
        assert_eq!(f[4], 1.0); // post-buckling plateau
        assert!((st.stiffness - 1.0 / 0.3).abs() < 1e-12);
        assert!((st.crush - (0.7 - 0.3)).abs() < 1e-12);
    }

    /// RIGI_NOR_POST_FL (Code_Aster 13): the post-buckling line from the crush
    /// FNOR_CRIT/RIGI_NOR − FNOR_POST_FL/RIGI_NOR_POST_FL.
    #[test]
    fn rigi_nor_post_fl_sets_the_post_buckling_line() {
        let law = Buckling::new(&BucklingSpec {
            rigi_nor: 1.0,
            fnor_crit: 1.0,
            fnor_post_fl: 0.5,
            enfo_fl: 1e-20,
            rigi_nor_post_fl: Some(2.0),
            damping_in_criterion: true,
            ..BucklingSpec::default()
        })
        .unwrap();
        let mut st = BucklingState::default();
        walk(&law, &[1.0, 3.0], -1.0, &mut st);
        assert_eq!(st.stiffness, 2.0);
        assert_eq!(st.crush, 2.75);
    }

    #[test]
    fn bad_parameters_name_their_keyword() {
        let base = BucklingSpec {
            rigi_nor: 1.0,
            fnor_crit: 1.0,
            fnor_post_fl: 0.5,
            enfo_fl: 1e-20,
            ..BucklingSpec::default()
        };
        let key = |s: BucklingSpec| match Buckling::new(&s) {
            Err(TransientError::Invalid { keyword, .. }) => keyword,
            other => panic!("{other:?}"),
        };
        assert_eq!(
            key(BucklingSpec {
                fnor_crit: 0.0,
                ..base.clone()
            }),
            "FLAMBAGE/FNOR_CRIT"
        );
        assert_eq!(
            key(BucklingSpec {
                fnor_post_fl: 2.0,
                ..base.clone()
            }),
            "FLAMBAGE/FNOR_POST_FL"
        );
        assert_eq!(
            key(BucklingSpec {
                rigi_nor_post_fl: Some(0.25),
                ..base.clone()
            }),
            "FLAMBAGE/RIGI_NOR_POST_FL"
        );
        assert_eq!(
            key(BucklingSpec {
                depl_post_fl: vec![1.0],
                ..base.clone()
            }),
            "FLAMBAGE/RIGI_POST_FL"
        );
        assert_eq!(
            key(BucklingSpec {
                depl_post_fl: vec![2.0, 1.0],
                rigi_post_fl: vec![1.0, 1.0],
                ..base
            }),
            "FLAMBAGE/DEPL_POST_FL"
        );
    }
}
