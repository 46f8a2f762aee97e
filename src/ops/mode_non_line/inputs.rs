//! MODE_NON_LINE's keywords read into the engine's typed inputs: the settings and step
//! control of RESOLUTION, the stop bounds, the shocks of CHOC and the cubic springs of
//! RESSORT_CUBIQUE with their nodes, the
//! restart's harmonic counts, the cost of the call checked before anything is allocated,
//! and the notes on ORIG_OBST.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::nnm::{self, Continuation, Harmonics, Point, Problem, Settings};
use crate::ops::common::nodes::{one_node_of_group, OneNode};
use crate::ops::OpContext;
use crate::store::matrix;
use crate::store::mnl::{MnlSetup, StoredShock};

use super::problem::RESSORT_CUBIQUE;

/// One INFO line per CERCLE shock with a non-zero ORIG_OBST: aster-nl takes it in metres
/// (what the keyword means, and what Code_Aster's own energy routine assumes), while
/// Code_Aster's MODE_NON_LINE equations take it unscaled in units of the largest JEU, i.e.
/// put the ring centre at ORIG_OBST·JEU_max (docs/mode_non_line.md, "ORIG_OBST").
pub(super) fn orig_obst_notes(shocks: &[StoredShock]) -> Vec<String> {
    let g = shocks.iter().map(|s| s.gap).fold(0.0f64, f64::max);
    // 12 significant digits: 3e-3 × 1e-2 prints as 3e-5, not 3.0000000000000004e-5.
    let num = |c: f64| match format!("{c:.11e}").parse::<f64>() {
        Ok(0.0) => "0".to_string(),
        Ok(r) => format!("{r:e}"),
        Err(_) => format!("{c:e}"),
    };
    let fmt = |v: [f64; 3]| format!("({}, {}, {})", num(v[0]), num(v[1]), num(v[2]));
    shocks
        .iter()
        .enumerate()
        .filter(|(_, s)| s.obstacle == "CERCLE" && s.origin.iter().any(|&c| c != 0.0))
        .map(|(i, s)| {
            let ca = s.origin.map(|c| c * g);
            format!(
                "  CHOC {}: ORIG_OBST={} is the ring centre in metres; Code_Aster would have put \
                 it at ORIG_OBST x JEU = {} m (it takes ORIG_OBST in units of the largest JEU, {:e} m); \
                 to reproduce a Code_Aster result give ORIG_OBST={}",
                i + 1,
                fmt(s.origin),
                fmt(ca),
                g,
                fmt(ca)
            )
        })
        .collect()
}

/// Refuse a call that cannot fit in memory, warn about one that will take very long: from
/// the sizes alone, before the engine allocates anything.
pub(super) fn check_budget(ctx: &mut OpContext<'_>, problem: &Problem, s: &Settings) -> Result<()> {
    use crate::nnm::budget;
    use crate::ops::common::resources;
    // Own unknowns and displacement components per law, as the law says (model/law/).
    let shocks = problem
        .shocks
        .iter()
        .map(|c| budget::ShockSizes {
            unknowns: c.law.n_own(),
            components: c.law.n_comp(),
        })
        .collect::<Vec<_>>();
    let sizes = budget::MnlSizes {
        n_dofs: problem.k.nrows(),
        nnz: problem.k.compute_nnz() + problem.m.compute_nnz(),
        h_lin: s.harmonics.h_lin,
        h_nonl: if problem.shocks.is_empty() {
            s.harmonics.h_lin
        } else {
            s.harmonics.h_nonl
        },
        shocks,
        order: s.continuation.order,
        stored_points: s.continuation.n_branches as f64 * s.continuation.n_points_per_branch as f64,
    };
    resources::check_memory(
        "MODE_NON_LINE/RESOLUTION (NB_HARM_LINE, NB_HARM_NONL, NB_ORDRE_MAN, NB_BRANCHE, NB_PAS_MAN)",
        "the harmonic-balance continuation",
        budget::memory_estimate(&sizes),
    )?;
    resources::warn_long_work(
        ctx,
        "MODE_NON_LINE/RESOLUTION",
        "the continuation",
        budget::mnl_branch_flops(&sizes) * s.continuation.n_branches as f64,
    )
}

pub(super) fn settings(args: &Args) -> Result<Settings> {
    let r = args.req_fact("RESOLUTION")?;
    // The bounds (at least 1, NB_ORDRE_MAN at least 2) are the catalog's.
    let usize_of = |key: &str| r.req_count(key);
    let h_lin = usize_of("NB_HARM_LINE")?;
    let h_nonl = usize_of("NB_HARM_NONL")?;
    if h_nonl < h_lin {
        return Err(Error::validation(format!(
            "NB_HARM_NONL ({h_nonl}) must be at least NB_HARM_LINE ({h_lin})"
        ))
        .keyword("MODE_NON_LINE/RESOLUTION/NB_HARM_NONL")
        .hint("the contact forces need at least as many harmonics as the displacements"));
    }
    let direction = args.req_fact("ETAT_INIT")?.req_int("DIR_EVOLUTION")?;
    let det_test = r.req_text("TEST_BIFURCATION")? != "SERIE";
    resolution_settings(r, det_test, if direction >= 0 { 1 } else { -1 })
}

/// The harmonics and continuation settings of a RESOLUTION block (MODE_NON_LINE's keywords,
/// which REPONSE_FORCEE_NL shares), with the determinant test and the direction each
/// operator decides.
pub(crate) fn resolution_settings(r: &Args, det_test: bool, direction: i32) -> Result<Settings> {
    // The bounds (at least 1, NB_ORDRE_MAN at least 2) are the catalog's.
    let usize_of = |key: &str| r.req_count(key);
    Ok(Settings {
        harmonics: Harmonics {
            h_lin: usize_of("NB_HARM_LINE")?,
            h_nonl: usize_of("NB_HARM_NONL")?,
        },
        continuation: Continuation {
            n_branches: usize_of("NB_BRANCHE")?,
            n_points_per_branch: usize_of("NB_PAS_MAN")?,
            order: usize_of("NB_ORDRE_MAN")?,
            prec_man: r.req_real("PREC_MAN")?,
            prec_newton: r.req_real("PREC_NEWTON")?,
            iter_newton_max: usize_of("ITER_NEWTON_MAXI")?,
            bif_terms: usize_of("CRIT_ORDR_BIFURCATION")?,
            bif_tol: r.req_real("RESI_RELA_BIFURCATION")?,
            det_test,
            direction,
        },
    })
}

/// RESOLUTION/NB_REPRISE_PAS_MAXI, NB_BRANCHE_SANS_PROGRES, ECART_LOI_CHOC_MAXI, SAUT_RACINE_MAXI,
/// RAPPORT_CORRECTION_MAXI, TRAVAIL_CHOC_MINI, AMOR_FICTIF_MAXI (BAISSE_FREQ_MAXI once the
/// start is known),
/// ECART_ENERGIE_MAXI and APPROX_MAN (aster-nl extensions; default and bounds in the
/// catalog).
pub(super) fn step_control(args: &Args) -> Result<nnm::StepControl> {
    let r = args.req_fact("RESOLUTION")?;
    Ok(nnm::StepControl {
        retries_max: r.req_count("NB_REPRISE_PAS_MAXI")?,
        stall_branches: r.req_count("NB_BRANCHE_SANS_PROGRES")?,
        law_defect_max: Some(r.req_real("ECART_LOI_CHOC_MAXI")?),
        root_jump_max: Some(r.req_real("SAUT_RACINE_MAXI")?).filter(|&v| v > 0.0),
        correction_ratio_max: Some(r.req_real("RAPPORT_CORRECTION_MAXI")?).filter(|&v| v > 0.0),
        spread_max: r.real("ECART_ENERGIE_MAXI"),
        work_min: Some(r.req_real("TRAVAIL_CHOC_MINI")?),
        gamma_max: Some(r.req_real("AMOR_FICTIF_MAXI")?),
        // Set once the start is known (the mode the family starts from).
        frequency_floor: None,
        approximation: match r.req_text("APPROX_MAN")? {
            "PADE" => nnm::Approximation::Pade,
            _ => nnm::Approximation::Series,
        },
    })
}

/// RESOLUTION/ENER_MAX, FREQ_MAX, DEPL_MAX (aster-nl extensions): the run stops normally
/// after the first branch with a row past one of them.
pub(super) struct StopBounds {
    energy: Option<f64>,
    frequency: Option<f64>,
    displacement: Option<f64>,
}

impl StopBounds {
    /// Which bound a row of `pts` has passed, said in words.
    pub(super) fn passed(
        &self,
        problem: &Problem,
        s: &Settings,
        pts: &[Point],
    ) -> Result<Option<String>> {
        for p in pts {
            if let Some(e) = self.energy.filter(|&e| p.energy >= e) {
                return Ok(Some(format!(
                    "ENERGIE = {:.6e} passed ENER_MAX = {e:.6e}",
                    p.energy
                )));
            }
            if let Some(f) = self.frequency.filter(|&f| p.frequency >= f) {
                return Ok(Some(format!(
                    "FREQUENCE = {:.6e} Hz passed FREQ_MAX = {f:.6e} Hz",
                    p.frequency
                )));
            }
            if let Some(d) = self.displacement {
                let u = nnm::largest_displacement(problem, s, &p.x)?;
                if u >= d {
                    return Ok(Some(format!(
                        "the largest displacement {u:.6e} passed DEPL_MAX = {d:.6e}"
                    )));
                }
            }
        }
        Ok(None)
    }
}

pub(super) fn stop_bounds(args: &Args) -> Result<StopBounds> {
    let r = args.req_fact("RESOLUTION")?;
    Ok(StopBounds {
        energy: r.real("ENER_MAX"),
        frequency: r.real("FREQ_MAX"),
        displacement: r.real("DEPL_MAX"),
    })
}

pub(super) fn check_restart_harmonics(setup: &MnlSetup, harmonics: &Harmonics) -> Result<()> {
    if setup.h_lin != harmonics.h_lin || setup.h_nonl != harmonics.h_nonl {
        return Err(Error::validation(format!(
            "the start table was computed with NB_HARM_LINE={} and NB_HARM_NONL={}, this call asks for {} and {}",
            setup.h_lin, setup.h_nonl, harmonics.h_lin, harmonics.h_nonl
        ))
        .keyword("MODE_NON_LINE/RESOLUTION")
        .hint("a restart keeps the harmonics of the branch it continues"));
    }
    Ok(())
}

/// CHOC and RESSORT_CUBIQUE (MODE_NON_LINE, REPONSE_FORCEE_NL: the same keywords), each
/// error naming the calling operator.
pub(crate) fn shocks_from_args(ctx: &OpContext<'_>, args: &Args) -> Result<Vec<StoredShock>> {
    let mut out = Vec::new();
    for (i, c) in args.facts_or_empty("CHOC").iter().enumerate() {
        let kw = |k: &str| format!("{}/CHOC[{}]/{k}", ctx.op, i + 1);
        let obstacle = c.req_text("OBSTACLE")?.to_string();
        // One component (PLAN, BI_PLAN) or two (CERCLE): the catalog's bounds.
        let cmps = c.req_texts("NOM_CMP")?;
        // A ring lies in the plane of two different components: ('DX', 'DX') has no plane
        // (its tangent is singular, found only after a long failed start).
        if let [a, b] = cmps.as_slice() {
            if a == b {
                return Err(Error::validation(format!(
                    "NOM_CMP=('{a}', '{b}') names one component twice: OBSTACLE='{obstacle}' \
                     needs the two different components of the plane of its ring"
                ))
                .keyword(kw("NOM_CMP"))
                .hint("e.g. NOM_CMP=('DX', 'DY') for a ring in the XY plane"));
            }
        }
        let node = choc_node(ctx, args, c, &kw, "a shock")?;
        // Finite and > 0: the catalog's bounds (val_min = 0, excluded).
        let positive = |key: &str| c.req_real(key);
        let gap = positive("JEU")?;
        let stiffness = positive("RIGI_NOR")?;
        let regul = positive("PARA_REGUL")?;
        // Three reals: the catalog's default and bounds (min = max = 3).
        let origin: [f64; 3] = c
            .req_reals("ORIG_OBST")?
            .try_into()
            .map_err(|o: Vec<f64>| {
                Error::internal(format!(
                    "ORIG_OBST has {} values: its catalog needs min = max = 3",
                    o.len()
                ))
                .keyword(kw("ORIG_OBST"))
            })?;
        // Text in the catalog's list (its `into`).
        let loi_cercle = c.req_text("LOI_CERCLE")?.to_string();
        // The same shock twice doubles its stiffness without a word: refuse it.
        if let Some(j) = out
            .iter()
            .position(|s: &StoredShock| s.node == node && s.cmps == cmps)
        {
            return Err(Error::validation(format!(
                "CHOC[{}] acts on the same node and components as CHOC[{}]",
                i + 1,
                j + 1
            ))
            .keyword(format!("{}/CHOC[{}]", ctx.op, i + 1))
            .hint("give each shock once; two obstacles on one DOF are one BI_PLAN"));
        }
        out.push(StoredShock {
            obstacle,
            node,
            cmps,
            gap,
            stiffness,
            regul,
            origin,
            loi_cercle,
        });
    }
    cubic_springs(ctx, args, &mut out)?;
    Ok(out)
}

/// RESSORT_CUBIQUE (aster-nl extension): the cubic springs k₃u³, stored after the shocks
/// (the same stored form, TYPE_CHOC 'RESSORT_CUBIQUE', RIGI_NOR = RAIDEUR, JEU and
/// PARA_REGUL 0). Node, component and RAIDEUR (finite, > 0) as the catalog bounds them;
/// the same DOF twice is refused.
fn cubic_springs(ctx: &OpContext<'_>, args: &Args, out: &mut Vec<StoredShock>) -> Result<()> {
    let first = out.len();
    for (i, c) in args.facts_or_empty(RESSORT_CUBIQUE).iter().enumerate() {
        let kw = |k: &str| format!("{}/{RESSORT_CUBIQUE}[{}]/{k}", ctx.op, i + 1);
        let node = choc_node(ctx, args, c, &kw, "a cubic spring")?;
        let cmps = c.req_texts("NOM_CMP")?;
        if let Some(j) = out[first..]
            .iter()
            .position(|s| s.node == node && s.cmps == cmps)
        {
            return Err(Error::validation(format!(
                "{RESSORT_CUBIQUE}[{}] acts on the same node and component ({node}, {}) as \
                 {RESSORT_CUBIQUE}[{}]",
                i + 1,
                cmps.join(", "),
                j + 1
            ))
            .keyword(format!("{}/{RESSORT_CUBIQUE}[{}]", ctx.op, i + 1))
            .hint(
                "give each DOF one spring: two cubic springs on one DOF are one of RAIDEUR the sum",
            ));
        }
        out.push(StoredShock {
            obstacle: RESSORT_CUBIQUE.to_string(),
            node,
            cmps,
            gap: 0.0,
            // Finite and > 0: the catalog's bounds (val_min = 0, excluded).
            stiffness: c.req_real("RAIDEUR")?,
            regul: 0.0,
            origin: [0.0; 3],
            loi_cercle: String::new(),
        });
    }
    Ok(())
}

/// The node of a CHOC or a RESSORT_CUBIQUE (`what`, "a shock" or "a cubic spring"): NOEUD,
/// or a GROUP_NO holding exactly one node.
pub(crate) fn choc_node(
    ctx: &OpContext<'_>,
    args: &Args,
    c: &Args,
    kw: &dyn Fn(&str) -> String,
    what: &str,
) -> Result<String> {
    if let Some(n) = c.text("NOEUD") {
        return Ok(n.to_string());
    }
    let group = c.req_text("GROUP_NO")?;
    let k_name = &args.req_concept("MATR_RIGI")?.name;
    let numbering = matrix::load_matrix(ctx.store, k_name)?.numbering;
    let reason = format!("{what} acts on exactly one");
    one_node_of_group(
        ctx.store,
        &numbering.mesh,
        group,
        OneNode {
            reason: &reason,
            hint: Some("give the node with NOEUD=, or a GROUP_NO of one node"),
        },
        kw("GROUP_NO"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shock(obstacle: &str, gap: f64, origin: [f64; 3]) -> StoredShock {
        StoredShock {
            obstacle: obstacle.into(),
            node: "N1".into(),
            cmps: vec!["DX".into(), "DY".into()],
            gap,
            stiffness: 50.0,
            regul: 1e-4,
            origin,
            loi_cercle: "RAYON".into(),
        }
    }

    /// A non-zero ORIG_OBST of a CERCLE is reported with the centre Code_Aster would have
    /// used: ORIG_OBST times the largest JEU (here 0.02, of the second shock).
    #[test]
    fn orig_obst_note_names_code_aster_centre() {
        let notes = orig_obst_notes(&[
            shock("CERCLE", 0.01, [0.0, 3e-3, 0.0]),
            shock("BI_PLAN", 0.02, [0.0; 3]),
            shock("CERCLE", 0.01, [0.0; 3]),
        ]);
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(
            notes[0].starts_with("  CHOC 1: ORIG_OBST=(0, 3e-3, 0) is the ring centre in metres")
                && notes[0].contains("ORIG_OBST x JEU = (0, 6e-5, 0) m")
                && notes[0].contains("largest JEU, 2e-2 m"),
            "{}",
            notes[0]
        );
    }
}
