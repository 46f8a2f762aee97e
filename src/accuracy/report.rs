//! The study's tables: markdown for the documentation, CSV for other tools.

use super::measure::{Measurement, ORDER, POINTS_PER_BRANCH, PREC_NEWTON};
use super::pareto::{cost_error, pareto_front, recommend};
use super::CaseResult;
use std::fmt::Write;

/// The accuracy targets a user is given settings for.
pub const TARGETS: [f64; 3] = [1e-3, 1e-4, 1e-5];

fn on_front(ms: &[Measurement]) -> Vec<bool> {
    let mut f = vec![false; ms.len()];
    for i in pareto_front(&cost_error(ms)) {
        f[i] = true;
    }
    f
}

fn settings_cells(m: &Measurement) -> String {
    let c = &m.config;
    format!(
        "{} | {} | {} | {:e} | {:e}",
        sweep_label(c),
        c.h_lin,
        c.h_nonl,
        c.regul,
        c.prec_man
    )
}

/// The sweep's name, with the samples per coefficient of an exact-law correction.
fn sweep_label(c: &super::cases::Config) -> String {
    if c.exact_law > 0 {
        format!("{} ({} samples/coef.)", c.sweep, c.exact_law)
    } else {
        c.sweep.to_string()
    }
}

fn error_cell(m: &Measurement) -> String {
    if m.ok() {
        format!("{:.2e}", m.max_rel_error)
    } else {
        "failed".into()
    }
}

/// Markdown: the settings, then the table of every measurement (Pareto points marked with
/// ★) and the recommended settings per target.
pub fn markdown(r: &CaseResult) -> String {
    let ms = &r.measurements;
    let (lo, hi) = r.case.range();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Case `{}`: energy range [{lo:.3e}, {hi:.3e}] J (1.2 to 20 times the first-contact \
         energy {:.3e} J); NB_ORDRE_MAN = {ORDER}, NB_PAS_MAN = {POINTS_PER_BRANCH}, \
         PREC_NEWTON = {PREC_NEWTON:.0e}; one thread; {} build. Cost = CPU time of the run \
         (the machine is shared: wall time also counts other processes).\n",
        r.case.kind.name(),
        r.case.contact_energy,
        build_profile()
    );
    if let Some(m) = &r.reference {
        let c = &m.config;
        let _ = writeln!(
            s,
            "Reference: NB_HARM_LINE = {}, NB_HARM_NONL = {}, PARA_REGUL = {:e}, PREC_MAN = \
             {:e}, NB_PAS_MAN = {} ({} branches, {} points, {:.1} s CPU).\n",
            c.h_lin,
            c.h_nonl,
            c.regul,
            c.prec_man,
            super::measure::REFERENCE_POINTS_PER_BRANCH,
            m.branches,
            m.points,
            m.cpu_seconds
        );
    }
    let front = on_front(ms);
    s.push_str(
        "| sweep | NB_HARM_LINE | NB_HARM_NONL | PARA_REGUL | PREC_MAN | max rel. error | CPU (s) | wall (s) | branches | points | Pareto |\n",
    );
    s.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|\n");
    for (m, &p) in ms.iter().zip(&front) {
        let _ = writeln!(
            s,
            "| {} | {} | {:.3} | {:.3} | {} | {} | {} |",
            settings_cells(m),
            error_cell(m),
            m.cpu_seconds,
            m.seconds,
            m.branches,
            m.points,
            if p { "★" } else { "" }
        );
    }
    let failures: Vec<String> = ms
        .iter()
        .filter_map(|m| {
            m.failure
                .as_ref()
                .map(|f| format!("- {}: {f}", settings_cells(m).replace(" | ", ", ")))
        })
        .collect();
    if !failures.is_empty() {
        let _ = writeln!(s, "\nFailed runs:\n{}", failures.join("\n"));
    }
    s.push_str("\n| target | cheapest setting meeting it | error | CPU (s) |\n");
    s.push_str("|---:|---|---:|---:|\n");
    for rec in recommend(ms, &TARGETS) {
        match rec.index {
            Some(i) => {
                let m = &ms[i];
                let c = &m.config;
                let _ = writeln!(
                    s,
                    "| {:.0e} | NB_HARM_LINE={}, NB_HARM_NONL={}, PARA_REGUL={:e}, PREC_MAN={:e} | {:.2e} | {:.3} |",
                    rec.target, c.h_lin, c.h_nonl, c.regul, c.prec_man, m.max_rel_error, m.cost()
                );
            }
            None => {
                let _ = writeln!(s, "| {:.0e} | none measured | | |", rec.target);
            }
        }
    }
    s.push_str(&det_cost_table(r));
    s
}

/// The profile this binary was built with, as the tables state it.
fn build_profile() -> &'static str {
    if cfg!(debug_assertions) {
        "debug-assertion (dev/test profile)"
    } else {
        "release"
    }
}

/// Markdown table of the cost of the determinant-sign bifurcation test; empty if it was
/// not measured.
fn det_cost_table(r: &CaseResult) -> String {
    if r.det_cost.is_empty() {
        return String::new();
    }
    let n_dof = r.case.problem.k.nrows();
    let mut s = format!(
        "\nCost of TEST_BIFURCATION = 'SERIE_DETERMINANT' (the default) against 'SERIE': \
         each setting run {} times with and without the test, alternately; the run with the \
         least CPU time of each is shown. Extra solves per branch end: \
         n_dof·(2·NB_HARM_LINE + 1) + 2 with n_dof = {n_dof}.\n\n",
        super::DET_REPEATS
    );
    s.push_str(
        "| NB_HARM_LINE | NB_HARM_NONL | PARA_REGUL | PREC_MAN | extra solves / branch | branches (SERIE / SERIE_DET.) | error (SERIE / SERIE_DET.) | CPU SERIE (s) | CPU SERIE_DET. (s) | extra CPU |\n",
    );
    s.push_str("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for d in &r.det_cost {
        let c = &d.config;
        let extra = d.on.cost() / d.off.cost() - 1.0;
        let _ = writeln!(
            s,
            "| {} | {} | {:e} | {:e} | {} | {} / {} | {} / {} | {:.3} | {:.3} | {:+.1} % |",
            c.h_lin,
            c.h_nonl,
            c.regul,
            c.prec_man,
            n_dof * (2 * c.h_lin + 1) + 2,
            d.off.branches,
            d.on.branches,
            error_cell(&d.off),
            error_cell(&d.on),
            d.off.cost(),
            d.on.cost(),
            100.0 * extra
        );
    }
    s
}

/// CSV, one row per measurement, header first; failed runs have an empty error. The runs
/// of the bifurcation-test comparison follow (sweep SERIE / SERIE_DET, never Pareto).
pub fn csv(r: &CaseResult) -> String {
    let mut front = on_front(&r.measurements);
    let mut rows: Vec<&Measurement> = r.measurements.iter().collect();
    for d in &r.det_cost {
        rows.push(&d.off);
        rows.push(&d.on);
        front.extend([false, false]);
    }
    let mut s = String::from(
        "case,sweep,nb_harm_line,nb_harm_nonl,para_regul,prec_man,nb_ordre_man,nb_pas_man,max_rel_error,cpu_s,wall_s,branches,points,points_in_range,pareto,failure\n",
    );
    for (m, &p) in rows.into_iter().zip(&front) {
        let c = &m.config;
        let _ = writeln!(
            s,
            "{},{},{},{},{:e},{:e},{ORDER},{POINTS_PER_BRANCH},{},{:.3},{:.3},{},{},{},{},\"{}\"",
            r.case.kind.name(),
            sweep_label(c),
            c.h_lin,
            c.h_nonl,
            c.regul,
            c.prec_man,
            if m.ok() {
                format!("{:.6e}", m.max_rel_error)
            } else {
                String::new()
            },
            m.cpu_seconds,
            m.seconds,
            m.branches,
            m.points,
            m.points_in_range,
            p,
            m.failure.as_deref().unwrap_or("").replace('"', "'")
        );
    }
    s
}
