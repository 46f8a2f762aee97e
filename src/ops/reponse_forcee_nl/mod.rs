//! REPONSE_FORCEE_NL (aster-nl extension): the forced-response curve of a damped structure
//! with shocks under a harmonic force, by harmonic balance continued in frequency (the
//! EHMAN engine with `Problem::forcing`; docs/forced_response.md).
//!
//! Glue only: reads the matrices, the damping (MATR_AMOR or AMOR_RAYLEIGH), the force
//! (EXCIT), the band, the shocks (MODE_NON_LINE's CHOC and RESSORT_CUBIQUE readers) and the
//! settings; runs the engine from the steady state at FREQ_MIN up to the first branch past
//! FREQ_MAX; stores one table row per point, turning points flagged, with each row's
//! Floquet stability unless STABILITE='NON' (`stability.rs`).

mod stability;

use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::modes::ModeMeca;
use crate::model::{AssembledMatrix, Cmp, DofNumbering};
use crate::nnm::stability::Floquet;
use crate::nnm::{self, Forcing, Point, Problem, Settings};
use crate::ops::mode_non_line::inputs::{choc_node, shocks_from_args};
use crate::ops::mode_non_line::problem::engine_shocks;
use crate::ops::proj_vect_base::on_numbering;
use crate::ops::OpContext;
use crate::store::{gene, matrix, table as table_store};
use crate::table::{Cell, ColKind, Table};
use faer::sparse::{SparseColMat, Triplet};
use std::f64::consts::PI;

/// A DOF whose amplitude is a column of the table.
struct Observed {
    column: String,
    dof: usize,
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let k_name = args.req_concept("MATR_RIGI")?.name.clone();
    let m_name = args.req_concept("MATR_MASS")?.name.clone();
    let k = matrix::load_matrix(ctx.store, &k_name)?;
    let m = matrix::load_matrix(ctx.store, &m_name)?;
    k.refuse_damping(&k_name, "REPONSE_FORCEE_NL/MATR_RIGI")?;
    m.refuse_damping(&m_name, "REPONSE_FORCEE_NL/MATR_MASS")?;
    if !k.same_dofs(&m) {
        return Err(Error::input(format!(
            "{k_name} and {m_name} are not assembled on the same DOF numbering and boundary conditions"
        ))
        .keyword("REPONSE_FORCEE_NL/MATR_MASS"));
    }
    k.refuse_relations("REPONSE_FORCEE_NL")
        .map_err(|e| e.keyword("REPONSE_FORCEE_NL/MATR_RIGI"))?;
    let (f_min, f_max) = band(args)?;
    let (k_red, m_red) = (k.reduced()?, m.reduced()?);
    let damping = damping(ctx, args, &k, (&k_red, &m_red))?;
    let force = force(ctx, args, &k)?;
    let observed = observed(ctx, args, &k)?;
    let stored = shocks_from_args(ctx, args)?;
    let problem = Problem {
        shocks: engine_shocks(&stored, &k)?,
        k: k_red,
        m: m_red,
        forcing: Some(Forcing { damping, force }),
    };
    let settings = settings(args)?;
    let control = step_control(args)?;
    refuse_a_band_without_resonance(&problem, settings.harmonics.h_lin, (f_min, f_max))?;

    let start = nnm::start_forced(&problem, &settings, 2.0 * PI * f_min)?;
    let first = start.point.clone();
    let mut lines = Vec::new();
    let mut left_band = false;
    let outcome = nnm::continue_controlled(&problem, &settings, control, start, &mut |rep, pts| {
        lines.push(format!(
            "  branch {:>4}: {:>3} pts  freq {:.6e} .. {:.6e} Hz  a_max {:.3e}  newton {:>2}{}",
            rep.branch,
            rep.points,
            rep.freq_range.0,
            rep.freq_range.1,
            rep.a_max,
            rep.newton_iterations,
            if rep.step_retries > 0 {
                format!("  step halved {} time(s)", rep.step_retries)
            } else {
                String::new()
            }
        ));
        // On until the curve leaves the band at either end.
        let inside = pts
            .last()
            .is_none_or(|p| p.frequency <= f_max && p.frequency >= f_min);
        left_band |= !inside;
        inside
    });
    let mut points = vec![first];
    points.extend(outcome.points);
    // The rows in the band: up to the first one past either end.
    let kept = points
        .iter()
        .position(|p| p.frequency > f_max || p.frequency < f_min * (1.0 - 1e-12))
        .unwrap_or(points.len());
    points.truncate(kept);

    let post = nnm::PostProcessor::new(&problem, &settings)?;
    let floquet = stability::analyse(ctx, args, &problem, &settings, &points)?;
    let table = curve_table(&post, &settings, &observed, &points, floquet.as_deref())?;
    ctx.create(&name, "table_sdaster")?;
    ctx.store.record_dependency(&name, &k_name)?;
    ctx.store.record_dependency(&name, &m_name)?;
    table_store::save_table(ctx.store, &name, &table)?;

    let folds = fold_rows(&points);
    ctx.say(&format!(
        "REPONSE_FORCEE_NL {name}: {} point(s) from {:.6e} to {:.6e} Hz, {} turning point(s)",
        points.len(),
        points.first().map_or(f64::NAN, |p| p.frequency),
        points.last().map_or(f64::NAN, |p| p.frequency),
        folds.iter().filter(|&&f| f).count(),
    ))?;
    if !left_band && outcome.error.is_none() {
        ctx.alarm(
            "REPONSE_FORCEE_NL_1",
            &format!(
                "the curve ends at {:.6e} Hz, inside the band: NB_BRANCHE = {} branches were \
                 not enough to reach FREQ_MAX = {f_max} Hz (or to leave the band below \
                 FREQ_MIN); raise NB_BRANCHE, or NB_PAS_MAN and PREC_MAN for longer branches",
                points.last().map_or(f64::NAN, |p| p.frequency),
                settings.continuation.n_branches
            ),
        )?;
    }
    if ctx.info >= 1 {
        for l in &lines {
            ctx.say(l)?;
        }
    }
    ctx.say(&format!(
        "  amplitude against frequency: SELECT NUME_ORDRE, FREQUENCE, {} FROM {name} ORDER BY NUME_ORDRE",
        observed.first().map_or("ENERGIE", |o| o.column.as_str())
    ))?;
    // A failed branch keeps the rows before it; the run then stops, as MODE_NON_LINE's.
    if let Some(e) = outcome.error {
        ctx.deferred_error = Some(e.into());
    }
    Ok(())
}

/// FREQ_MIN < FREQ_MAX (each positive: the catalog's bounds).
fn band(args: &Args) -> Result<(f64, f64)> {
    let (lo, hi) = (args.req_real("FREQ_MIN")?, args.req_real("FREQ_MAX")?);
    if lo >= hi {
        return Err(Error::input(format!(
            "the band is empty: FREQ_MIN = {lo} Hz is not below FREQ_MAX = {hi} Hz"
        ))
        .keyword("REPONSE_FORCEE_NL/FREQ_MAX")
        .hint("give FREQ_MIN < FREQ_MAX, FREQ_MIN below the resonances of interest"));
    }
    Ok((lo, hi))
}

/// A band that no harmonic of the forcing (up to NB_HARM_LINE) can bring to a natural
/// frequency of the structure, its shocks open or closed, is refused
/// (nnm::holds_no_resonance): its curve would be a flat response that answers nothing, and
/// is most often a band in the wrong unit (rad/s for Hz) or around the wrong mode.
fn refuse_a_band_without_resonance(
    problem: &Problem,
    h_lin: usize,
    (f_min, f_max): (f64, f64),
) -> Result<()> {
    if nnm::holds_no_resonance(problem, h_lin, f_min, f_max)? {
        return Err(Error::input(format!(
            "the band {f_min} to {f_max} Hz holds no resonance: no natural frequency of the \
             structure, with its shocks open or closed (RIGI_NOR), is within {:.0} % of a \
             harmonic 1 to NB_HARM_LINE = {h_lin} of a forcing frequency in it",
            100.0 * nnm::RESONANCE_MARGIN
        ))
        .keyword("REPONSE_FORCEE_NL/FREQ_MIN")
        .hint(
            "compute the natural frequencies (CALC_MODES) and put the band around one: FREQ_MIN \
             and FREQ_MAX are in Hz",
        ));
    }
    Ok(())
}

/// The damping matrix on the free DOFs: MATR_AMOR, or AMOR_ALPHA·K + AMOR_BETA·M.
fn damping(
    ctx: &OpContext<'_>,
    args: &Args,
    k: &AssembledMatrix,
    (k_red, m_red): (&SparseColMat<usize, f64>, &SparseColMat<usize, f64>),
) -> Result<SparseColMat<usize, f64>> {
    let c = match (args.concept("MATR_AMOR"), args.fact("AMOR_RAYLEIGH")) {
        (Some(c), _) => {
            let a = matrix::load_matrix(ctx.store, &c.name)?;
            if !a.same_dofs(k) {
                return Err(Error::input(format!(
                    "{} is not assembled on the DOF numbering and boundary conditions of MATR_RIGI",
                    c.name
                ))
                .keyword("REPONSE_FORCEE_NL/MATR_AMOR"));
            }
            a.reduced()?
        }
        (None, Some(r)) => {
            let (alpha, beta) = (r.req_real("AMOR_ALPHA")?, r.req_real("AMOR_BETA")?);
            combine(k_red, alpha, m_red, beta)?
        }
        (None, None) => {
            return Err(no_damping(
                "neither MATR_AMOR nor AMOR_RAYLEIGH is given",
                "REPONSE_FORCEE_NL/AMOR_RAYLEIGH",
            ))
        }
    };
    if c.val().iter().all(|&v| v == 0.0) {
        let key = match args.has("MATR_AMOR") {
            true => "REPONSE_FORCEE_NL/MATR_AMOR",
            false => "REPONSE_FORCEE_NL/AMOR_RAYLEIGH",
        };
        return Err(no_damping("the damping matrix is zero", key));
    }
    Ok(c)
}

fn no_damping(what: &str, key: &str) -> Error {
    Error::input(format!(
        "a forced response needs a damping: {what} (undamped, the response to a harmonic \
         force has no bounded peak at a resonance)"
    ))
    .keyword(key)
    .hint("give AMOR_RAYLEIGH=_F(AMOR_ALPHA=..., AMOR_BETA=...) or MATR_AMOR (ASSEMBLAGE, OPTION='AMOR_MECA')")
}

/// a·A + b·B, both n×n.
fn combine(
    a: &SparseColMat<usize, f64>,
    ca: f64,
    b: &SparseColMat<usize, f64>,
    cb: f64,
) -> Result<SparseColMat<usize, f64>> {
    let mut t = Vec::new();
    for (mat, coef) in [(a, ca), (b, cb)] {
        let sym = mat.symbolic();
        let (cp, ri, v) = (sym.col_ptr(), sym.row_idx(), mat.val());
        for j in 0..mat.ncols() {
            for p in cp[j]..cp[j + 1] {
                t.push(Triplet::new(ri[p], j, coef * v[p]));
            }
        }
    }
    SparseColMat::try_new_from_triplets(a.nrows(), a.ncols(), &t)
        .map_err(|e| Error::internal(format!("the Rayleigh damping matrix: {e:?}")))
}

/// The free DOF of `node`, `cmp` in K's numbering, or an error naming the keyword.
fn free_dof(k: &AssembledMatrix, node: &str, cmp: &str, key: String) -> Result<usize> {
    let missing = |why: &str| {
        Error::input(format!("DOF {cmp} of node {node} {why}"))
            .keyword(key.clone())
            .hint("name a component of the model's elements at that node, not blocked by a boundary condition")
    };
    let c = Cmp::parse(cmp).ok_or_else(|| missing("is not a displacement component"))?;
    let full = k
        .numbering
        .index_of(node, c)
        .ok_or_else(|| missing("does not exist in the numbering of MATR_RIGI"))?;
    k.reduced_index(full)
        .ok_or_else(|| missing("is blocked by a boundary condition (not a free DOF)"))
}

/// The force amplitudes on the free DOFs: the sum of the EXCIT occurrences.
fn force(ctx: &OpContext<'_>, args: &Args, k: &AssembledMatrix) -> Result<Vec<f64>> {
    let n = k.free_dofs().len();
    let mut f = vec![0.0; n];
    for (i, e) in args.facts_or_empty("EXCIT").iter().enumerate() {
        let kw = |key: &str| format!("REPONSE_FORCEE_NL/EXCIT[{}]/{key}", i + 1);
        if let Some(v) = e.concept("VECT_ASSE") {
            let field = gene::load_field(ctx.store, &v.name)?;
            let numbering = ModeMeca {
                numbering: DofNumbering {
                    eliminated: k.eliminated.clone(),
                    ..k.numbering.clone()
                },
                numbering_name: String::new(),
                modes: Vec::new(),
            };
            let full = on_numbering(&field, &numbering, &v.name)
                .map_err(|e| e.keyword(kw("VECT_ASSE")))?;
            let coef = e.req_real("COEF_MULT")?;
            for (j, dof) in k.free_dofs().into_iter().enumerate() {
                f[j] += coef * full[dof];
            }
            continue;
        }
        let node = choc_node(ctx, args, e, &kw, "a nodal force")?;
        let (Some(cmp), Some(amp)) = (e.text("NOM_CMP"), e.real("FORCE")) else {
            return Err(Error::input(
                "a nodal excitation (NOEUD or GROUP_NO) needs NOM_CMP and FORCE",
            )
            .keyword(kw("NOM_CMP")));
        };
        let d = free_dof(k, &node, cmp, kw("NOM_CMP"))?;
        f[d] += amp;
    }
    if f.iter().all(|&v| v == 0.0) {
        return Err(Error::input("the force is zero on every free DOF")
            .keyword("REPONSE_FORCEE_NL/EXCIT")
            .hint("give a non-zero FORCE, or a VECT_ASSE that loads a free DOF"));
    }
    Ok(f)
}

/// OBSERVATION: the DOFs whose amplitude is tabled, each with its column name.
fn observed(ctx: &OpContext<'_>, args: &Args, k: &AssembledMatrix) -> Result<Vec<Observed>> {
    let mut out: Vec<Observed> = Vec::new();
    for (i, o) in args.facts_or_empty("OBSERVATION").iter().enumerate() {
        let kw = |key: &str| format!("REPONSE_FORCEE_NL/OBSERVATION[{}]/{key}", i + 1);
        let node = choc_node(ctx, args, o, &kw, "an observation")?;
        let cmp = o.req_text("NOM_CMP")?;
        let dof = free_dof(k, &node, cmp, kw("NOM_CMP"))?;
        let column = format!("AMPL_{node}_{cmp}");
        if out.iter().any(|c| c.column == column) {
            return Err(
                Error::input(format!("{cmp} of node {node} is observed twice"))
                    .keyword(kw("NOM_CMP")),
            );
        }
        out.push(Observed { column, dof });
    }
    Ok(out)
}

/// RESOLUTION's settings (MODE_NON_LINE's keywords; no determinant test: its sign change
/// marks the bifurcations of the autonomous family, and a forced curve's turning points are
/// found from its rows).
fn settings(args: &Args) -> Result<Settings> {
    // Forward: from FREQ_MIN toward increasing frequency (the start's travel).
    crate::ops::mode_non_line::inputs::resolution_settings(args.req_fact("RESOLUTION")?, false, -1)
}

/// The retries and checks of a branch end that hold for a forced curve: the contact laws in
/// time, the jump onto another family, the no-progress guard. Not the checks of an
/// autonomous family (its fictitious damping, its frequency floor, the root of its law by
/// virtual work, the virial of its forces), which a forced response does not satisfy.
fn step_control(args: &Args) -> Result<nnm::StepControl> {
    let r = args.req_fact("RESOLUTION")?;
    Ok(nnm::StepControl {
        retries_max: r.req_count("NB_REPRISE_PAS_MAXI")?,
        stall_branches: r.req_count("NB_BRANCHE_SANS_PROGRES")?,
        law_defect_max: Some(r.req_real("ECART_LOI_CHOC_MAXI")?),
        correction_ratio_max: Some(r.req_real("RAPPORT_CORRECTION_MAXI")?).filter(|&v| v > 0.0),
        approximation: match r.req_text("APPROX_MAN")? {
            "PADE" => nnm::Approximation::Pade,
            _ => nnm::Approximation::Series,
        },
        ..nnm::StepControl::none()
    })
}

/// Whether each row is the one nearest a turning point of the frequency along the curve:
/// where the frequency steps change sign.
fn fold_rows(points: &[Point]) -> Vec<bool> {
    let mut folds = vec![false; points.len()];
    for i in 1..points.len().saturating_sub(1) {
        let before = points[i].frequency - points[i - 1].frequency;
        let after = points[i + 1].frequency - points[i].frequency;
        folds[i] = before * after < 0.0;
    }
    folds
}

/// The result table: one row per point, STABILITE and MODULE_MAX after PLI when computed.
fn curve_table(
    post: &nnm::PostProcessor,
    settings: &Settings,
    observed: &[Observed],
    points: &[Point],
    floquet: Option<&[Floquet]>,
) -> Result<Table> {
    let mut t = Table::new("REPONSE_FORCEE_NL");
    t.add_column("NUME_ORDRE", ColKind::I)?;
    t.add_column("FREQUENCE", ColKind::R)?;
    for o in observed {
        t.add_column(&o.column, ColKind::R)?;
    }
    t.add_column("ENERGIE", ColKind::R)?;
    t.add_column("PLI", ColKind::K)?;
    if floquet.is_some() {
        t.add_column("STABILITE", ColKind::K)?;
        t.add_column("MODULE_MAX", ColKind::R)?;
    }
    for (name, kind) in [
        ("RESIDU", ColKind::R),
        ("ECART_LOI_CHOC", ColKind::R),
        ("BRANCHE", ColKind::I),
        ("NB_REPRISE_PAS", ColKind::I),
    ] {
        t.add_column(name, kind)?;
    }
    let h = settings.harmonics.h_lin;
    let nl = 2 * h + 1;
    let folds = fold_rows(points);
    for (j, p) in points.iter().enumerate() {
        let defect = post.row_with_defect(&p.x, p.law_defect)?.law_defect;
        let mut row = vec![Cell::I(j as i64 + 1), Cell::R(p.frequency)];
        for o in observed {
            let c = &p.x[o.dof * nl..(o.dof + 1) * nl];
            row.push(Cell::R(nnm::peak_amplitude(c, h)));
        }
        row.extend([
            Cell::R(p.energy_mean),
            Cell::K(if folds[j] { "OUI" } else { "NON" }.into()),
        ]);
        if let Some(f) = floquet.and_then(|f| f.get(j)) {
            row.extend([Cell::K(f.label().into()), Cell::R(f.max_modulus)]);
        }
        row.extend([
            Cell::R(p.residual),
            Cell::R(defect),
            Cell::I(p.branch as i64),
            Cell::I(p.step_retries as i64),
        ]);
        t.push_row(row)?;
    }
    Ok(t)
}
