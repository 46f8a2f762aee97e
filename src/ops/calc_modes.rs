//! CALC_MODES: real modes of K φ = ω² M φ (OPTION PLUS_PETITE / BANDE / CENTRE).
//! MODE_ITER_SIMULT (the 13.x syntax: the option inside CALC_FREQ) runs the same
//! computation through [`run_with_option`].

use crate::args::Args;
use crate::error::{Error, Result};
use crate::linalg::eigen::norm::ModeNorm;
use crate::linalg::eigen::sym::SymSparse;
use crate::linalg::eigen::{self, EigenOptions, ModeRequest};
use crate::model::dof::Cmp;
use crate::model::modes::{Mode, ModeMeca};
use crate::ops::OpContext;
use crate::store::{matrix, modes as mode_store};
use crate::table::print::format_e;

// Defaults are the catalog's (commands/CALC_MODES.toml, MODE_ITER_SIMULT.toml), filled by
// the validation: the operator reads them with `req_*`.
/// Relative precision of a frequency below which CALC_MODES_2 warns (0.01 %): the bound
/// of `eigen::omega2_precision` is pessimistic (measured on a cantilever of POU_D_E:
/// bound 4.3e-4 and actual error 5e-6 at 1000 elements, 6.9e-3 and 1.5e-3 at 2000), so
/// only losses an engineer would see in a frequency are reported.
const FREQ_PRECISION_ALARM: f64 = 1e-4;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let option = args.req_text("OPTION")?.to_string();
    run_with_option(ctx, args, &option)
}

/// The modes `option` asks for (PLUS_PETITE, BANDE or CENTRE), the other settings read
/// from `args` as CALC_MODES names them (CALC_FREQ, VERI_MODE, NORM_MODE...).
pub fn run_with_option(ctx: &mut OpContext<'_>, args: &Args, option: &str) -> Result<()> {
    let op = ctx.op.to_string();
    let name = ctx.result_name()?.to_string();
    let k_name = &args.req_concept("MATR_RIGI")?.name;
    let m_name = &args.req_concept("MATR_MASS")?.name;
    let k = matrix::load_matrix(ctx.store, k_name)?;
    let m = matrix::load_matrix(ctx.store, m_name)?;
    k.refuse_damping(k_name, &format!("{op}/MATR_RIGI"))?;
    m.refuse_damping(m_name, &format!("{op}/MATR_MASS"))?;
    if !k.same_dofs(&m) {
        return Err(Error::input(format!(
            "{k_name} and {m_name} are not assembled on the same DOF numbering and boundary conditions"
        ))
        .keyword(format!("{op}/MATR_MASS"))
        .hint("assemble both matrices with the same NUME_DDL and CHAR_CINE"));
    }
    let numbering_name = matrix::matrix_numbering_name(ctx.store, k_name)?;
    let request = mode_request(args, option, &op)?;
    let kr = k.reduced()?;
    let mr = m.reduced()?;
    let free = k.free_dofs();
    if free.is_empty() {
        return Err(
            Error::input("every DOF is blocked: there is no mode to compute")
                .keyword(format!("{op}/MATR_RIGI")),
        );
    }
    check_definite(ctx, &kr, &mr, &k, k_name, m_name)?;
    let request = at_most_free(ctx, request, free.len(), &op)?;
    let set = match &request {
        Request::One(r) => eigen::solve_modes(&kr, &mr, r, &EigenOptions::default())?,
        Request::Nearest(freqs) => nearest_modes(&kr, &mr, freqs)?,
    };
    if ctx.info >= 2 {
        ctx.say(&format!(
            "{op}: {} DOFs ({} free), solver: {}",
            k.size(),
            free.len(),
            set.method
        ))?;
    }
    let calc_freq = args.req_fact("CALC_FREQ")?;
    let stop_band_empty = args.req_text("STOP_BANDE_VIDE")? != "NON";
    if set.omega2.is_empty()
        && matches!(request, Request::One(ModeRequest::Band { .. }))
        && stop_band_empty
    {
        return Err(Error::input("no mode in the requested band")
            .keyword(format!("{op}/CALC_FREQ/FREQ"))
            .hint("widen FREQ, or set STOP_BANDE_VIDE='NON' to accept an empty result"));
    }
    let norm = mode_norm(args, &k.numbering.dofs, &free, &op)?;
    let veri_mode = args.req_fact("VERI_MODE")?;
    let (seuil, stop_on_error) = (
        veri_mode.req_real("SEUIL")?,
        veri_mode.req_text("STOP_ERREUR")? != "NON",
    );
    let seuil_freq = calc_freq.req_real("SEUIL_FREQ")?;
    let ks = SymSparse::from_faer(&kr, "stiffness")?;
    let mut imprecise: Vec<String> = Vec::new();
    let mut modes = Vec::with_capacity(set.omega2.len());
    ctx.say(&format!(
        "{op} {name}: {} mode(s)\n  NUME_ORDRE  FREQUENCE (HZ)   ERREUR",
        set.omega2.len()
    ))?;
    for (i, (omega2, vector)) in set.omega2.iter().zip(&set.vectors).enumerate() {
        let mut phi = vector.clone();
        let gene = eigen::normalize(&mut phi, &kr, &mr, &norm)?;
        let residual = set.residuals.get(i).copied().unwrap_or(0.0);
        let freq = eigen::frequency(*omega2);
        // Relative precision of the frequency: half that of ω² (not for rigid-body modes,
        // whose ω² is round-off by nature).
        let precision = 0.5 * eigen::omega2_precision(&ks, &phi);
        if freq >= seuil_freq && precision > FREQ_PRECISION_ALARM && precision.is_finite() {
            imprecise.push(format!("mode {} ({freq:.6e} Hz) to {precision:.1e}", i + 1));
        }
        if residual > seuil {
            let msg = format!(
                "mode {} ({freq:.6e} Hz) has a relative residual {residual:.2e} above SEUIL={seuil:.1e}",
                i + 1
            );
            if stop_on_error {
                return Err(Error::numerical(msg).keyword(format!("{op}/VERI_MODE")));
            }
            ctx.alarm("CALC_MODES_1", &msg)?;
        }
        let rigid = if freq < seuil_freq {
            "  (rigid-body mode)"
        } else {
            ""
        };
        ctx.say(&format!(
            "  {:>10}  {:>14}   {}{rigid}",
            i + 1,
            format_e(freq, 6),
            format_e(residual, 2)
        ))?;
        let shape = k.expand(&phi)?;
        modes.push(Mode {
            nume_ordre: i + 1,
            freq,
            omega2: *omega2,
            mass_gene: gene.gen_mass,
            rigi_gene: gene.gen_stiff,
            shape,
            label: "DEPL".to_string(),
        });
    }
    if !imprecise.is_empty() {
        ctx.alarm(
            "CALC_MODES_2",
            &format!(
                "the mesh is so fine for these modes that double precision may leave their \
                 frequencies off by up to (relative): {}. Their stiffness terms cancel to that \
                 extent (bound ε·|φ|ᵀ|K||φ|/(2φᵀKφ)), whatever the solver, and ERREUR does not \
                 show it; fewer elements per wavelength give them more accurately",
                imprecise.join(", ")
            ),
        )?;
    }
    let result = ModeMeca {
        numbering: k.numbering.clone(),
        numbering_name,
        modes,
    };
    ctx.create(&name, "mode_meca")?;
    mode_store::save_modes(ctx.store, &name, &result)?;
    mode_store::save_matrices(
        ctx.store,
        &name,
        &mode_store::ModeMatrices {
            rigi: k_name.clone(),
            mass: m_name.clone(),
        },
    )
}

/// More modes asked (NMAX_FREQ, 10 by default) than the model has free DOFs: as Code_Aster
/// ("trop de modes demandés pour le nombre de DDL actifs"), every mode is computed, and
/// the run says so.
fn at_most_free(
    ctx: &mut OpContext<'_>,
    request: Request,
    free: usize,
    op: &str,
) -> Result<Request> {
    let capped = match request {
        Request::One(ModeRequest::Smallest { n }) if n > free => {
            (n, ModeRequest::Smallest { n: free })
        }
        Request::One(ModeRequest::Centre { f, n }) if n > free => {
            (n, ModeRequest::Centre { f, n: free })
        }
        other => return Ok(other),
    };
    ctx.say(&format!(
        "{op}: NMAX_FREQ={} modes asked but the model has {free} free DOFs: all {free} are computed",
        capped.0
    ))?;
    Ok(Request::One(capped.1))
}

/// What a call asks the solver: one request, or (OPTION='PROCHE') the mode nearest each
/// of several frequencies.
enum Request {
    One(ModeRequest),
    Nearest(Vec<f64>),
}

/// OPTION='PROCHE': the mode nearest each frequency, each found as CENTRE's one mode
/// closest to it; a mode nearest two of them is kept once. In increasing frequency.
fn nearest_modes(
    k: &faer::sparse::SparseColMat<usize, f64>,
    m: &faer::sparse::SparseColMat<usize, f64>,
    freqs: &[f64],
) -> Result<eigen::ModeSet> {
    let mut found: Vec<(f64, Vec<f64>, f64)> = Vec::new();
    let mut method = String::new();
    for &f in freqs {
        let set = eigen::solve_modes(
            k,
            m,
            &ModeRequest::Centre { f, n: 1 },
            &EigenOptions::default(),
        )?;
        method = set.method.clone();
        for ((w2, v), r) in set.omega2.into_iter().zip(set.vectors).zip(set.residuals) {
            // The same mode found again from another frequency (ω² equal to round-off).
            let again = found
                .iter()
                .any(|(o, _, _)| (o - w2).abs() <= 1e-10 * o.abs().max(w2.abs()));
            if !again {
                found.push((w2, v, r));
            }
        }
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut set = eigen::ModeSet {
        omega2: Vec::new(),
        vectors: Vec::new(),
        residuals: Vec::new(),
        method,
    };
    for (w2, v, r) in found {
        set.omega2.push(w2);
        set.vectors.push(v);
        set.residuals.push(r);
    }
    Ok(set)
}

fn mode_request(args: &Args, option: &str, op: &str) -> Result<Request> {
    let cf = args.req_fact("CALC_FREQ")?;
    // FREQ has no default: absent, it is an empty list (refused below for BANDE, CENTRE).
    let freqs = cf.reals("FREQ").unwrap_or_default();
    // At least 1: the catalog's bound.
    let n = cf.req_count("NMAX_FREQ")?;
    if option == "PROCHE" {
        if freqs.is_empty() {
            return Err(Error::validation(
                "OPTION='PROCHE' needs the frequencies to find the nearest modes of, FREQ=(f1, ...)",
            )
            .keyword(format!("{op}/CALC_FREQ/FREQ")));
        }
        return Ok(Request::Nearest(freqs));
    }
    if freqs.len() > 2 {
        return Err(Error::validation(format!(
            "OPTION='{option}' takes at most two frequencies, got {}",
            freqs.len()
        ))
        .keyword(format!("{op}/CALC_FREQ/FREQ")));
    }
    Ok(Request::One(match option {
        "PLUS_PETITE" => Ok(ModeRequest::Smallest { n }),
        "BANDE" => match freqs.as_slice() {
            [f1, f2] if f1 < f2 => Ok(ModeRequest::Band {
                f_min: *f1,
                f_max: *f2,
            }),
            _ => Err(Error::validation(format!(
                "OPTION='BANDE' needs FREQ=(f_min, f_max) with f_min < f_max, got {freqs:?}"
            ))
            .keyword(format!("{op}/CALC_FREQ/FREQ"))),
        },
        "CENTRE" => match freqs.as_slice() {
            [f] => Ok(ModeRequest::Centre { f: *f, n }),
            _ => Err(Error::validation(format!(
                "OPTION='CENTRE' needs one centre frequency FREQ=f, got {freqs:?}"
            ))
            .keyword(format!("{op}/CALC_FREQ/FREQ"))),
        },
        other => Err(
            Error::validation(format!("OPTION='{other}' is not supported"))
                .keyword(format!("{op}/OPTION")),
        ),
    }?))
}

/// NORM_MODE on the reduced (free) DOFs.
fn mode_norm(
    args: &Args,
    dofs: &[crate::model::numbering::NumberedDof],
    free: &[usize],
    op: &str,
) -> Result<ModeNorm> {
    // MODE_ITER_SIMULT has no NORM_MODE keyword: its modes are normalised as CALC_MODES's
    // are by default (not a default of a keyword it has; CALC_MODES reads its catalog's).
    let norme = match args.fact("NORM_MODE") {
        Some(n) => n.req_text("NORME")?,
        None => "TRAN_ROTA",
    };
    let mask = |keep: fn(Cmp) -> bool| -> Vec<bool> {
        free.iter()
            .map(|&i| dofs.get(i).is_some_and(|d| keep(d.cmp)))
            .collect()
    };
    Ok(match norme {
        "MASS_GENE" => ModeNorm::MassGene,
        "RIGI_GENE" => ModeNorm::RigiGene,
        "TRAN" => ModeNorm::LargestComponent {
            mask: mask(|c| matches!(c, Cmp::Dx | Cmp::Dy | Cmp::Dz)),
        },
        "TRAN_ROTA" => ModeNorm::LargestComponent {
            mask: mask(|_| true),
        },
        other => {
            return Err(
                Error::validation(format!("NORME='{other}' is not supported"))
                    .keyword(format!("{op}/NORM_MODE/NORME")),
            )
        }
    })
}

/// A negative stiffness or mass on a DOF, or a mass that is zero everywhere, has no
/// vibration modes: say so, instead of reporting an empty band.
fn check_definite(
    ctx: &mut OpContext<'_>,
    kr: &faer::sparse::SparseColMat<usize, f64>,
    mr: &faer::sparse::SparseColMat<usize, f64>,
    k: &crate::model::AssembledMatrix,
    k_name: &str,
    m_name: &str,
) -> Result<()> {
    use crate::linalg::sparse::diagonal;
    let free = k.free_dofs();
    let dof_name = |i: usize| {
        free.get(i)
            .and_then(|&f| k.numbering.dofs.get(f))
            .map(|d| format!("{} {}", d.node, d.cmp.name()))
            .unwrap_or_else(|| format!("DOF {i}"))
    };
    let (kd, md) = (diagonal(kr), diagonal(mr));
    for (name, kw, d) in [(k_name, "MATR_RIGI", &kd), (m_name, "MATR_MASS", &md)] {
        if let Some((i, v)) = d.iter().copied().enumerate().find(|(_, v)| *v < 0.0) {
            return Err(Error::input(format!(
                "{name} has the negative diagonal term {v:e} at {}: a stiffness or mass is negative, so there is no vibration mode",
                dof_name(i)
            ))
            .keyword(format!("CALC_MODES/{kw}"))
            .hint("check the signs of the values given to AFFE_CARA_ELEM and DEFI_MATERIAU"));
        }
    }
    if !md.is_empty() && md.iter().all(|&v| v == 0.0) {
        return Err(Error::input(format!(
            "{m_name} is zero on every free DOF: there is no mass, so there is no vibration mode"
        ))
        .keyword("CALC_MODES/MATR_MASS")
        .hint("give the masses (AFFE_CARA_ELEM M_T_D_N..., DEFI_MATERIAU RHO)"));
    }
    if let Some(i) = md.iter().position(|&v| v == 0.0) {
        ctx.alarm(
            "CALC_MODES_1",
            &format!(
                "{m_name} has no mass at {} (and maybe elsewhere): that DOF has no finite frequency",
                dof_name(i)
            ),
        )?;
    }
    Ok(())
}
