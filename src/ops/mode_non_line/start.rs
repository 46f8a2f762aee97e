//! MODE_NON_LINE's first-run start from linear modes: ETAT_INIT=_F(MODE_LINE=..., NUME_ORDRE=n)
//! as in Code_Aster, or, beyond Code_Aster, with NUME_ORDRE_QUAD=m a second mode of the same
//! frequency a quarter period behind the first: a whirl (docs/mode_non_line.md).

use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::assembly::AssembledMatrix;
use crate::model::modes::ModeMeca;
use crate::nnm::{self, Problem, Reduced, Settings, StartState};
use crate::ops::OpContext;
use crate::store::modes as mode_store;

/// The linear modes of ETAT_INIT/MODE_LINE, checked against the numbering of K.
fn load(
    ctx: &OpContext<'_>,
    etat: &Args,
    k: &AssembledMatrix,
    k_name: &str,
) -> Result<(String, ModeMeca)> {
    let modes_name = &etat.req_concept("MODE_LINE")?.name;
    let modes = mode_store::load_modes(ctx.store, modes_name)?;
    if modes.numbering.dofs != k.numbering.dofs {
        return Err(Error::input(format!(
            "{modes_name} is not expressed on the numbering of {k_name}"
        ))
        .keyword(etat.key_path("MODE_LINE")));
    }
    Ok((modes_name.clone(), modes))
}

/// The frequency (Hz) of the starting linear mode (REDUCTION's cut-off is relative to it).
pub fn linear_frequency(
    ctx: &OpContext<'_>,
    etat: &Args,
    k: &AssembledMatrix,
    k_name: &str,
) -> Result<f64> {
    let (modes_name, modes) = load(ctx, etat, k, k_name)?;
    let (_, omega) = pick(&modes, &modes_name, etat.req_int("NUME_ORDRE")?, k)
        .map_err(|e| e.keyword(etat.key_path("NUME_ORDRE")))?;
    Ok(omega / (2.0 * std::f64::consts::PI))
}

/// The corrected start point from the linear mode(s) named in ETAT_INIT; on a reduced
/// problem, the modes in its coordinates.
pub fn from_linear_modes(
    ctx: &OpContext<'_>,
    etat: &Args,
    (problem, reduction): (&Problem, Option<&Reduced>),
    settings: &Settings,
    k: &AssembledMatrix,
    k_name: &str,
) -> Result<StartState> {
    let (modes_name, modes) = load(ctx, etat, k, k_name)?;
    let modes_name = &modes_name;
    // A full-model shape and pulsation, as the problem's coordinates see them.
    let on_problem = |(shape, omega): (Vec<f64>, f64)| -> Result<(Vec<f64>, f64)> {
        match reduction {
            Some(r) => Ok(r.start_mode(problem, &shape)?),
            None => Ok((shape, omega)),
        }
    };
    let nume_ordre = etat.req_int("NUME_ORDRE")?;
    let (shape, omega) = on_problem(
        pick(&modes, modes_name, nume_ordre, k)
            .map_err(|e| e.keyword(etat.key_path("NUME_ORDRE")))?,
    )?;
    let coef = etat.req_real("COEF_AMPL")?;
    let Some(quad_order) = etat.int("NUME_ORDRE_QUAD") else {
        return Ok(nnm::start_from_mode(
            problem, settings, &shape, coef, omega,
        )?);
    };
    let quad_kw = etat.key_path("NUME_ORDRE_QUAD");
    if quad_order == nume_ordre {
        return Err(Error::validation(format!(
            "NUME_ORDRE_QUAD ({quad_order}) must differ from NUME_ORDRE ({nume_ordre})"
        ))
        .keyword(quad_kw)
        .hint("give the other mode of the degenerate pair, e.g. NUME_ORDRE=1, NUME_ORDRE_QUAD=2"));
    }
    let (quad, omega_quad) = on_problem(
        pick(&modes, modes_name, quad_order, k).map_err(|e| e.keyword(quad_kw.clone()))?,
    )?;
    nnm::check_degenerate_pair(omega, omega_quad).map_err(|e| {
        let e = Error::from(e);
        Error {
            message: format!(
                "NUME_ORDRE_QUAD={quad_order} and NUME_ORDRE={nume_ordre}: {}",
                e.message
            ),
            keyword: Some(quad_kw.clone()),
            ..e
        }
    })?;
    Ok(nnm::start_from_mode_pair(
        problem, settings, &shape, &quad, coef, omega, omega_quad,
    )?)
}

/// Alarm MODE_NON_LINE_11: the start from the linear mode could not be corrected at
/// COEF_AMPL = `coef` (`why`), only at `fraction` of that amplitude, where the branch
/// starts instead.
pub fn approached_alarm(coef: f64, fraction: f64, why: &str) -> String {
    format!(
        "the start could not be corrected at COEF_AMPL={coef} ({why}); it was corrected at \
         {fraction:.4} of that amplitude (COEF_AMPL={:.4e}), approached from smaller \
         amplitudes, and the branch starts there: its first rows lie below the amplitude asked, \
         and DIR_EVOLUTION=-1 climbs through it; the usual cause is a linear mode scaled deep \
         into a stiff stop: a smaller COEF_AMPL, at which the mode barely reaches the stops, \
         starts on the branch directly",
        coef * fraction
    )
}

/// Shape on the free DOFs and pulsation of mode `order` of `modes`.
fn pick(modes: &ModeMeca, name: &str, order: i64, k: &AssembledMatrix) -> Result<(Vec<f64>, f64)> {
    let mode = usize::try_from(order)
        .ok()
        .and_then(|n| modes.mode(n))
        .ok_or_else(|| {
            Error::input(format!(
                "{name} has no mode NUME_ORDRE={order} (available: {})",
                modes.available()
            ))
        })?;
    let shape = k.restrict(&mode.shape).ok_or_else(|| {
        Error::store(format!(
            "mode {order} of {name} is shorter than its numbering"
        ))
    })?;
    Ok((shape, mode.omega2.max(0.0).sqrt()))
}
