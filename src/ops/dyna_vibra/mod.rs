//! DYNA_VIBRA (TYPE_CALCUL='TRAN'): a transient response with localized shocks, on a modal
//! basis (GENE: result `tran_gene`) or on the physical DOFs (PHYS: result `dyna_trans`).
//! Glue only: the keywords are read into the integrator's inputs (`space.rs`, `shocks.rs`,
//! here), the integration is `crate::transient`, the tables are written by `output.rs`
//! (the shocks' internal variables as columns: `memory.rs`); a start from a stored
//! instant and reuse= are `restart.rs`.

mod basis_check;
mod memory;
mod output;
mod restart;
mod shocks;
mod space;
mod supports;

use super::common::progress::Progress;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::{function as function_store, model};
use crate::transient::{
    contact_pulsations, integrate_from, optimized_tangential_damping, Archive, Forcing, Scheme,
    Shock, Structure, TimeGrid, VelocityFloor,
};
use space::Space;

pub(crate) use output::field_header;
pub use shocks::ShockName;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let reuse = ctx.reuse.map(str::to_string);
    let name = match &reuse {
        Some(r) => r.clone(),
        None => ctx.result_name()?.to_string(),
    };
    let (space, structure) = Space::read(ctx, args)?;
    let mesh = model::load_mesh(ctx.store, space.mesh())?;
    let shocks::CallShocks {
        mut shocks,
        names,
        ignored,
    } = shocks::read(ctx, args, &space, &mesh)?;
    for (intitule, n2) in &ignored {
        ctx.alarm(
            "DYNA_VIBRA_4",
            &format!(
                "shock {intitule}: its obstacle acts on node 1 alone, as in Code_Aster (a shock \
                 between two nodes is a BI_PLAN_Y/Z, BI_CERCLE or BI_CERC_INT obstacle): \
                 NOEUD_2 = {n2} is ignored"
            ),
        )?;
    }
    default_tangential_damping(args, &space, &mut shocks)?;
    let supports = supports::read(ctx, args, &space)?;
    supports::attach(ctx, &supports, &mut shocks, &names)?;
    let veri = match args.fact("VERI_CHOC") {
        Some(v) => Some(basis_check::VeriChoc {
            seuil: v.req_real("SEUIL")?,
            stop: v.req_text("STOP_CRITERE")? == "OUI",
        }),
        None => None,
    };
    basis_check::check(ctx, &space, &shocks, &names, veri)?;
    let n = space.size();
    let start = initial_state(ctx, args, &space, &names, reuse.as_deref(), n)?;
    if let Some(r) = &start.restart {
        // The shocks go on from their internal variables at that instant.
        for (shock, sample) in shocks.iter_mut().zip(&r.samples) {
            shock.state = sample.state;
        }
    }
    let forcing = excitations(ctx, args, &space)?;
    let times = time_grid(args, start.t0)?;
    let scheme = scheme(args, &times)?;
    let archive = archive(args, &times)?;
    check_step(ctx, &scheme, &times, structure.as_ref(), &shocks, &names)?;
    let progress = Progress::new(ctx.progress, 1000, "DYNA_VIBRA", "‰ of the interval");
    let mut done = 0u64;
    let mut trajectory = integrate_from(
        structure.as_ref(),
        &mut shocks,
        &forcing,
        (&start.q, &start.v),
        start.restart.as_ref().map(|r| r.a.as_slice()),
        scheme,
        times,
        &archive,
        &mut |fraction| {
            let now = (fraction * 1000.0) as u64;
            while done < now.min(1000) {
                progress.inc();
                done += 1;
            }
        },
    )
    .map_err(|e| in_operator(e.into()))?;
    progress.finish();
    let mut continued = None;
    if let Some(r) = start.restart {
        // The row of the start instant is the stored one (the shocks as stored there).
        if trajectory.t.first().is_some_and(|&t| t == r.t0) {
            for (series, sample) in trajectory.shocks.iter_mut().zip(&r.samples) {
                if let Some(first) = series.first_mut() {
                    *first = *sample;
                }
            }
        }
        if let Some(history) = r.history {
            continued = Some((r.index + 1, r.t0));
            trajectory = restart::continued(history, trajectory, r.t0);
        }
    }
    if let Some(&t) = trajectory.steps_forced.first() {
        let msg = format!(
            "{} step(s) of ADAPT_ORDRE were kept after NMAX_ITER_PAS tries although still too \
             long for the motion (NB_POIN_PERIODE points per apparent period), the first at \
             t = {t:e} s: raise NMAX_ITER_PAS or lower PAS",
            trajectory.steps_forced.len()
        );
        ctx.alarm("DYNAMIQUE_18", &msg)?;
    }
    if ctx.info >= 2 {
        say_events(ctx, &names, &trajectory)?;
    }
    let stored: Vec<_> = supports.into_iter().map(|s| s.stored).collect();
    output::store(ctx, &name, &space, &names, &stored, &trajectory)?;
    if let Some((kept, t0)) = continued {
        ctx.say(&format!(
            "DYNA_VIBRA {name} (reuse): its first {kept} instants kept, up to {t0:e} s; the run goes on from there"
        ))?;
    }
    ctx.say(&format!(
        "DYNA_VIBRA {name}: {} archived instants from {:e} to {:e} s, {} steps ({} rejected), {} shock(s), {} contact change(s) located",
        trajectory.t.len(),
        trajectory.t.first().copied().unwrap_or(times.t0),
        times.t_end,
        trajectory.steps_taken,
        trajectory.steps_rejected,
        names.len(),
        trajectory.events.len()
    ))
}

/// Fewer steps per contact than a fixed-step scheme needs. A contact lasts about π/ω_c,
/// ω_c the shock's normal stiffness against the mass its node carries
/// (`transient::contact_time`). NEWMARK with ω_c·PAS above 1 steps over contacts and gains
/// energy at each release (measured: the energy of a one-DOF impact oscillator grows
/// without bound at 1.5 times DIFF_CENTRE's limit): refused. Fewer than 10 steps per
/// contact: alarm DYNA_VIBRA_1 (the impacts are resolved coarsely). DIFF_CENTRE's own
/// limit, 2/ω_max, is checked by the integrator.
fn check_step(
    ctx: &mut OpContext<'_>,
    scheme: &Scheme,
    times: &TimeGrid,
    structure: &dyn Structure,
    shocks: &[Shock],
    names: &[ShockName],
) -> Result<()> {
    if matches!(
        scheme,
        Scheme::Adaptive(_) | Scheme::Adapt(_) | Scheme::Devoge(_)
    ) || shocks.is_empty()
    {
        return Ok(());
    }
    let (_, h) = times.fixed_steps();
    let pulsations = contact_pulsations(structure, shocks).map_err(|e| in_operator(e.into()))?;
    for (w, name) in pulsations.iter().zip(names) {
        if *w <= 0.0 {
            continue;
        }
        let duration = std::f64::consts::PI / w;
        if matches!(scheme, Scheme::Newmark { .. }) && w * h > 1.0 {
            return Err(Error::input(format!(
                "PAS = {h:e} is longer than 1/ω_c = {:e} s for shock {}: its contact lasts about \
                 {duration:e} s (π/ω_c, ω_c = √(RIGI_NOR/m), m the mass its node carries), and \
                 NEWMARK with such a step steps over contacts and gains energy at each release",
                1.0 / w,
                name.intitule
            ))
            .keyword("DYNA_VIBRA/INCREMENT/PAS")
            .hint(format!(
                "take PAS below {:e} (10 steps per contact), or SCHEMA='RUNGE_KUTTA_54', which \
                 ends a step at every contact change",
                duration / 10.0
            )));
        }
        if h > duration / 10.0 {
            ctx.alarm(
                "DYNA_VIBRA_1",
                &format!(
                    "shock {}: a contact lasts about {duration:e} s (π/ω_c) and PAS = {h:e} \
                     gives it {:.1} steps: impacts are resolved coarsely. Take PAS below {:e}, \
                     or SCHEMA='RUNGE_KUTTA_54'",
                    name.intitule,
                    duration / h,
                    duration / 10.0
                ),
            )?;
        }
    }
    Ok(())
}

/// INFO=2: the contact changes the adaptive schemes located (the first 100).
fn say_events(
    ctx: &mut OpContext<'_>,
    names: &[ShockName],
    tr: &crate::transient::Trajectory,
) -> Result<()> {
    const SHOWN: usize = 100;
    for e in tr.events.iter().take(SHOWN) {
        let shock = names.get(e.shock).map_or("?", |n| n.intitule.as_str());
        let what = if e.onset {
            "contact begins"
        } else {
            "contact ends"
        };
        ctx.say(&format!("  t = {:.9e} s  {shock}: {what}", e.t))?;
    }
    if tr.events.len() > SHOWN {
        ctx.say(&format!(
            "  ... and {} more contact changes",
            tr.events.len() - SHOWN
        ))?;
    }
    Ok(())
}

/// An error of the integrator with its keyword as a path of this operator.
fn in_operator(mut e: Error) -> Error {
    if let Some(k) = e.keyword.as_deref() {
        if !k.starts_with("DYNA_VIBRA") {
            e.keyword = Some(format!("DYNA_VIBRA/{k}"));
        }
    }
    e
}

/// AMOR_TAN not given with RIGI_TAN > 0 on a modal basis: the damping Code_Aster derives
/// from RIGI_TAN and the modal masses and frequencies (docs/dyna_vibra.md).
fn default_tangential_damping(args: &Args, space: &Space, shocks: &mut [Shock]) -> Result<()> {
    let Space::Gene { modes, .. } = space else {
        return Ok(());
    };
    let occurrences = if args.has("COMPORTEMENT") {
        args.facts_or_empty("COMPORTEMENT")
    } else {
        args.facts_or_empty("CHOC")
    };
    let mass: Vec<f64> = modes.modes.iter().map(|m| m.mass_gene).collect();
    let omega2: Vec<f64> = modes.modes.iter().map(|m| m.omega2).collect();
    let ratios = damping_ratios(args, mass.len())?;
    for (shock, occ) in shocks.iter_mut().zip(occurrences) {
        if occ.has("AMOR_TAN") || shock.spec.rigi_tan <= 0.0 {
            continue;
        }
        shock.spec.amor_tan = optimized_tangential_damping(shock, &mass, &omega2, &ratios)
            .map_err(|e| shocks::in_occurrence(e.into(), occ))?;
    }
    Ok(())
}

/// AMOR_MODAL's ratios for n coordinates (the last repeated), zero without it.
pub(crate) fn damping_ratios(args: &Args, n: usize) -> Result<Vec<f64>> {
    let Some(amor) = args.fact("AMOR_MODAL") else {
        return Ok(vec![0.0; n]);
    };
    let given = amor.req_reals("AMOR_REDUIT")?;
    let last = given.last().copied().unwrap_or(0.0);
    Ok((0..n)
        .map(|i| given.get(i).copied().unwrap_or(last))
        .collect())
}

/// The start of the run: q0, v0, and from a stored result its instant (where the run
/// starts) and, on a modal basis, the rest of the stored state (`restart.rs`).
struct Start {
    q: Vec<f64>,
    v: Vec<f64>,
    t0: Option<f64>,
    restart: Option<restart::Restart>,
}

fn initial_state(
    ctx: &OpContext<'_>,
    args: &Args,
    space: &Space,
    names: &[ShockName],
    reuse: Option<&str>,
    n: usize,
) -> Result<Start> {
    let init = args.fact("ETAT_INIT");
    let from = init.and_then(|i| i.concept("RESULTAT").map(|c| (i, c.name.clone())));
    if let Some(r) = reuse {
        // The catalog checks it for DYNA_VIBRA; DYNA_TRAN_MODAL comes here renamed.
        if from.as_ref().map(|f| f.1.as_str()) != Some(r) {
            return Err(Error::validation(format!(
                "reuse={r} needs ETAT_INIT/RESULTAT={r}: the reused result is the one the run \
                 goes on from"
            ))
            .keyword("DYNA_VIBRA/ETAT_INIT/RESULTAT"));
        }
        if matches!(space, Space::Phys { .. }) {
            return Err(Error::validation(format!(
                "reuse={r}: a run on the physical DOFs cannot extend a result; reuse= goes on \
                 with a result on a modal basis (BASE_CALCUL='GENE')"
            ))
            .keyword("DYNA_VIBRA/ETAT_INIT/RESULTAT")
            .hint("assign the continued run to a new name"));
        }
    }
    if let Some((init, _)) = from {
        return match space {
            Space::Gene { .. } => {
                let r = restart::read(ctx, init, space, names, reuse.is_some())?;
                Ok(Start {
                    q: r.q.clone(),
                    v: r.v.clone(),
                    t0: Some(r.t0),
                    restart: Some(r),
                })
            }
            Space::Phys { .. } => {
                let (q, v, t0) = space.state_of_result(ctx, init)?;
                Ok(Start {
                    q,
                    v,
                    t0: Some(t0),
                    restart: None,
                })
            }
        };
    }
    let mut q = vec![0.0; n];
    let mut v = vec![0.0; n];
    if let Some(init) = init {
        if init.has("DEPL") {
            q = space.vector(ctx, init, "DEPL")?;
        }
        if init.has("VITE") {
            v = space.vector(ctx, init, "VITE")?;
        }
    }
    Ok(Start {
        q,
        v,
        t0: None,
        restart: None,
    })
}

fn excitations(ctx: &OpContext<'_>, args: &Args, space: &Space) -> Result<Vec<Forcing>> {
    let key = match space {
        Space::Gene { .. } => "VECT_ASSE_GENE",
        Space::Phys { .. } => "VECT_ASSE",
    };
    let mut out = Vec::new();
    for occ in args.facts_or_empty("EXCIT") {
        if !occ.has(key) {
            return Err(
                Error::validation(format!("this BASE_CALCUL takes its force as {key}"))
                    .keyword(occ.key_path(key)),
            );
        }
        let f = space.vector(ctx, occ, key)?;
        // ACCE (a support's acceleration, CALC_CHAR_SEISME's load) multiplies the force as
        // FONC_MULT does.
        let multiplier = ["FONC_MULT", "ACCE"]
            .into_iter()
            .find_map(|k| occ.concept(k).map(|c| (k, c)));
        let forcing = match multiplier {
            Some((k, c)) => {
                let g = function_store::load_any_function(ctx.store, &c.name)
                    .map_err(|e| e.keyword(occ.key_path(k)))?;
                // A value the function cannot give (outside an EXCLU domain) makes the
                // force NaN, which the integrator stops on, naming the instant.
                Forcing {
                    generalized_force: f,
                    multiplier: Box::new(move |t| g.eval(t).unwrap_or(f64::NAN)),
                }
            }
            None => Forcing::constant(f, occ.req_real("COEF_MULT")?),
        };
        out.push(forcing);
    }
    Ok(out)
}

/// SCHEMA_TEMPS, with INCREMENT/NB_PAS_MAXI: a fixed-step run of more steps is refused
/// before it starts, an adaptive one stops there.
fn scheme(args: &Args, times: &TimeGrid) -> Result<Scheme> {
    let inc = args.req_fact("INCREMENT")?;
    let most = usize::try_from(inc.req_int("NB_PAS_MAXI")?).unwrap_or(usize::MAX);
    let st = args.req_fact("SCHEMA_TEMPS")?;
    let name = st.req_text("SCHEMA")?;
    let mut scheme = Scheme::from_name(name).ok_or_else(|| {
        Error::validation(format!("SCHEMA='{name}' is not available"))
            .keyword(st.key_path("SCHEMA"))
    })?;
    match &mut scheme {
        Scheme::Newmark { beta, gamma } => {
            *beta = st.req_real("BETA")?;
            *gamma = st.req_real("GAMMA")?;
        }
        Scheme::Adaptive(o) => {
            o.max_steps = most;
            o.tolerance = st.req_real("TOLERANCE")?;
            o.alpha = st.req_real("ALPHA")?;
            o.pas_mini = st.real("PAS_MINI");
            o.pas_maxi = st.real("PAS_MAXI");
            o.nmax_iter_pas = usize::try_from(st.req_int("NMAX_ITER_PAS")?).unwrap_or(1);
            o.locate_contacts = st.req_text("LOCALISATION_CHOC")? == "OUI";
        }
        Scheme::Adapt(o) => {
            o.max_steps = most;
            o.points_per_period = st.req_int("NB_POIN_PERIODE")? as f64;
            o.nmax_iter_pas = usize::try_from(st.req_int("NMAX_ITER_PAS")?).unwrap_or(1);
            o.coef_mult = st.req_real("COEF_MULT_PAS")?;
            o.coef_divi = st.req_real("COEF_DIVI_PAS")?;
            o.pas_mini = st.real("PAS_MINI");
            o.pas_maxi = st.real("PAS_MAXI");
            o.pas_limi_rela = st.req_real("PAS_LIMI_RELA")?;
            o.velocity_floor = match st.req_text("VITE_MIN")? {
                "MAXI" => VelocityFloor::Maxi,
                _ => VelocityFloor::Norm,
            };
        }
        Scheme::Devoge(o) => {
            o.max_steps = most;
            o.tolerance = st.req_real("TOLERANCE")?;
            o.alpha = st.req_real("ALPHA")?;
            o.pas_mini = st.real("PAS_MINI");
            o.pas_maxi = st.real("PAS_MAXI");
        }
        Scheme::DiffCentre => {}
    }
    if !matches!(
        scheme,
        Scheme::Adaptive(_) | Scheme::Adapt(_) | Scheme::Devoge(_)
    ) {
        let span = times.t_end - times.t0;
        // The count before it is made an integer: a PAS 1e-20 of the interval must not wrap.
        let steps = (span / times.dt).ceil();
        if steps > most as f64 {
            return Err(Error::input(format!(
                "INCREMENT gives {steps:e} steps of PAS = {:e} over [{:e}, {:e}], more than \
                 NB_PAS_MAXI = {most}: such a run would not end in a reasonable time",
                times.dt, times.t0, times.t_end
            ))
            .keyword(inc.key_path("PAS"))
            .hint(
                "check PAS and INST_FIN, or raise NB_PAS_MAXI if the run is meant to be that long",
            ));
        }
    }
    Ok(scheme)
}

/// INCREMENT's interval and step; `start`: the instant of ETAT_INIT's RESULTAT, where the
/// run starts whatever INST_INIT says (as Code_Aster's `mdptem` does).
fn time_grid(args: &Args, start: Option<f64>) -> Result<TimeGrid> {
    let inc = args.req_fact("INCREMENT")?;
    let mut grid = match inc.reals("LIST_INST") {
        Some(list) => uniform_grid(inc, &list)?,
        None => TimeGrid {
            t0: inc.req_real("INST_INIT")?,
            t_end: inc.req_real("INST_FIN")?,
            dt: inc.req_real("PAS")?,
        },
    };
    if let Some(t0) = start {
        grid.t0 = t0;
        if grid.t_end.is_nan() || grid.t_end <= t0 {
            return Err(Error::validation(format!(
                "INST_FIN = {:e} is not after {t0:e}, the instant of ETAT_INIT/RESULTAT the run \
                 starts from",
                grid.t_end
            ))
            .keyword(inc.key_path("INST_FIN")));
        }
    }
    if grid.t_end <= grid.t0 || grid.t_end.is_nan() || grid.t0.is_nan() {
        return Err(Error::validation(format!(
            "INST_FIN = {:e} is not after INST_INIT = {:e}",
            grid.t_end, grid.t0
        ))
        .keyword(inc.key_path("INST_FIN")));
    }
    if grid.dt > grid.t_end - grid.t0 {
        return Err(Error::validation(format!(
            "PAS = {:e} is longer than the interval [{:e}, {:e}]",
            grid.dt, grid.t0, grid.t_end
        ))
        .keyword(inc.key_path("PAS")));
    }
    Ok(grid)
}

/// INCREMENT/LIST_INST: its first instant (or INST_INIT), its last (or INST_FIN) and its
/// step, which must be the same all along.
fn uniform_grid(inc: &Args, list: &[f64]) -> Result<TimeGrid> {
    let kw = inc.key_path("LIST_INST");
    let (Some(&first), Some(&last)) = (list.first(), list.last()) else {
        return Err(Error::validation("LIST_INST is empty").keyword(kw));
    };
    if list.len() < 2 {
        return Err(Error::validation("LIST_INST needs at least two instants").keyword(kw));
    }
    let dt = list[1] - list[0];
    if let Some(i) = list
        .windows(2)
        .position(|w| w[1] <= w[0] || ((w[1] - w[0]) - dt).abs() > 1e-6 * dt.abs())
    {
        return Err(Error::validation(format!(
            "LIST_INST has unequal steps ({:e} then {:e} at instant {}): DYNA_VIBRA's schemes take one step",
            dt,
            list[i + 1] - list[i],
            i + 2
        ))
        .keyword(kw)
        .hint("give INCREMENT=_F(INST_FIN=..., PAS=...) and the instants to keep in ARCHIVAGE/INST"));
    }
    Ok(TimeGrid {
        t0: inc.real("INST_INIT").unwrap_or(first),
        t_end: inc.real("INST_FIN").unwrap_or(last),
        dt,
    })
}

fn archive(args: &Args, times: &TimeGrid) -> Result<Archive> {
    let Some(a) = args.fact("ARCHIVAGE") else {
        return Ok(Archive::Every(1));
    };
    if let Some(list) = a.reals("INST").or_else(|| a.reals("LIST_INST")) {
        let span = times.t_end - times.t0;
        // Instants a rounding of the file puts a hair outside the interval are its ends.
        let slack = 1e-9 * span;
        if let Some(t) = list
            .iter()
            .find(|&&t| t < times.t0 - slack || t > times.t_end + slack)
        {
            return Err(Error::validation(format!(
                "INST = {t:e} is outside the interval [{:e}, {:e}]",
                times.t0, times.t_end
            ))
            .keyword(a.key_path("INST")));
        }
        let mut list: Vec<f64> = list
            .into_iter()
            .map(|t| t.clamp(times.t0, times.t_end))
            .collect();
        list.sort_by(f64::total_cmp);
        list.dedup();
        // PAS_ARCH with INST: both (Code_Aster's union); the catalog bounds PAS_ARCH ≥ 1.
        return Ok(match a.int("PAS_ARCH") {
            Some(every) => Archive::EveryAnd(usize::try_from(every).unwrap_or(1).max(1), list),
            None => Archive::Instants(list),
        });
    }
    let every = a.int("PAS_ARCH").unwrap_or(1);
    Ok(Archive::Every(usize::try_from(every).unwrap_or(1).max(1)))
}
