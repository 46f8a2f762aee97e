//! Pictures of nonlinear normal modes.
//!
//! - Frequency–energy plot of a MODE_NON_LINE table: energy on a log axis (the modes of a
//!   shock problem span decades of energy), frequency on a linear one; the curve is solid
//!   where stable, dashed where unstable, thin grey where stability was not evaluated, and
//!   the bifurcation rows carry their own marker.
//! - Time history (displacement and velocity against time, stacked) and phase portrait
//!   (velocity against displacement) of a REST_MODE_NONL time history.

use super::units::with_unit;
use super::{
    stacked, xy_plot, ImageFormat, LegendPosition, LineStyle, Marker, PlotSummary, Scale, Series,
    XyPlot, DEFAULT_SIZE,
};
use crate::error::Result;
use std::path::Path;

/// STABILITE of a MODE_NON_LINE row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stability {
    Stable,
    Unstable,
    /// 'NON_EVALUE' (before CALC_STABILITE) or an empty cell.
    NotEvaluated,
}

impl Stability {
    /// 'STABLE', 'INSTABLE'; anything else is not evaluated.
    pub fn parse(s: &str) -> Stability {
        match s.trim() {
            "STABLE" => Stability::Stable,
            "INSTABLE" => Stability::Unstable,
            _ => Stability::NotEvaluated,
        }
    }

    fn legend(self) -> &'static str {
        match self {
            Stability::Stable => "stable",
            Stability::Unstable => "unstable",
            Stability::NotEvaluated => "stability not evaluated",
        }
    }

    fn style(self, s: Series) -> Series {
        match self {
            Stability::Stable => s.line(LineStyle::Solid).color(STABLE).width(3),
            Stability::Unstable => s.line(LineStyle::Dashed).color(UNSTABLE).width(3),
            Stability::NotEvaluated => s.line(LineStyle::Solid).color(GREY).width(1),
        }
    }
}

const STABLE: (u8, u8, u8) = (31, 119, 180);
const UNSTABLE: (u8, u8, u8) = (214, 39, 40);
const GREY: (u8, u8, u8) = (110, 110, 110);
const BIFURCATION: (u8, u8, u8) = (0, 0, 0);

/// One row of a MODE_NON_LINE table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FePoint {
    pub energy: f64,
    pub freq: f64,
    pub stability: Stability,
    pub bifurcation: bool,
    /// NUME_REPRISE: the run that computed the row. A `reuse=` restart appends a run that
    /// starts elsewhere on the family (often back at low energy): the curve breaks there.
    pub reprise: i64,
}

/// Frequency against energy (log), in row order.
pub fn frequency_energy(
    rows: &[FePoint],
    title: &str,
    path: &Path,
    format: ImageFormat,
) -> Result<PlotSummary> {
    xy_plot(&frequency_energy_spec(rows, title), path, format)
}

/// The plot of [`frequency_energy`], for callers that adjust it (ranges, size).
pub fn frequency_energy_spec(rows: &[FePoint], title: &str) -> XyPlot {
    let mut series = Vec::new();
    let mut labelled = Vec::new();
    // Runs of equal stability and NUME_REPRISE. A run of new stability starts at the last
    // point of the previous one so the curve stays continuous, the joining segment taking
    // the new run's style; a run of a new NUME_REPRISE does not (no chord between the end
    // of one computation and the start of the next).
    let mut start = 0;
    while start < rows.len() {
        let (kind, reprise) = (rows[start].stability, rows[start].reprise);
        let end = rows[start..]
            .iter()
            .position(|r| r.stability != kind || r.reprise != reprise)
            .map_or(rows.len(), |n| start + n);
        let from = match start.checked_sub(1) {
            Some(prev) if rows[prev].reprise == reprise => prev,
            _ => start,
        };
        let run = &rows[from..end];
        let label = if labelled.contains(&kind) {
            ""
        } else {
            labelled.push(kind);
            kind.legend()
        };
        let mut s = kind.style(Series::new(
            label,
            run.iter().map(|r| r.energy).collect(),
            run.iter().map(|r| r.freq).collect(),
        ));
        s.repeats = start - from;
        series.push(s);
        start = end;
    }
    let bif: Vec<&FePoint> = rows.iter().filter(|r| r.bifurcation).collect();
    if !bif.is_empty() {
        series.push(
            Series::new(
                "bifurcation",
                bif.iter().map(|r| r.energy).collect(),
                bif.iter().map(|r| r.freq).collect(),
            )
            .line(LineStyle::None)
            .marker(Marker::Triangle)
            .color(BIFURCATION)
            .width(3),
        );
        if let Some(s) = series.last_mut() {
            // The markers sit on rows the curve already counts.
            s.repeats = s.x.len();
        }
    }
    XyPlot {
        title: title.to_string(),
        x_label: "ENERGIE (J)".into(),
        y_label: "FREQUENCE (Hz)".into(),
        x_scale: Scale::Log,
        y_scale: Scale::Lin,
        series,
        // Stiffening shocks raise the frequency with the energy: the upper left is free.
        legend: LegendPosition::UpperLeft,
        ..XyPlot::default()
    }
}

/// The time history of one node component for one row (NUME_ORDRE) of a REST_MODE_NONL
/// table.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// Legend entry, e.g. `NUME_ORDRE 5`.
    pub label: String,
    pub inst: Vec<f64>,
    pub depl: Vec<f64>,
    pub vite: Vec<f64>,
}

/// Size of the stacked time-history picture: two panels of a 1024-wide plot.
pub const HISTORY_SIZE: (u32, u32) = (DEFAULT_SIZE.0, DEFAULT_SIZE.0);

/// Displacement (top) and velocity (bottom) against time. `what` names the node and
/// component (`N2 DX`) on the axis labels.
pub fn time_history(
    curves: &[History],
    title: &str,
    what: &str,
    path: &Path,
    format: ImageFormat,
) -> Result<PlotSummary> {
    let [depl, vite] = time_history_specs(curves, title, what);
    stacked(&[&depl, &vite], HISTORY_SIZE, path, format)
}

/// The two panels of [`time_history`].
pub fn time_history_specs(curves: &[History], title: &str, what: &str) -> [XyPlot; 2] {
    let cmp = what.split_whitespace().last();
    let panel = |y: fn(&History) -> &Vec<f64>, name: &str, title: &str| XyPlot {
        title: title.to_string(),
        x_label: with_unit("INST", "INST", None),
        y_label: with_unit(&format!("{name} {what}"), name, cmp),
        series: curves
            .iter()
            .map(|h| Series::new(&h.label, h.inst.clone(), y(h).clone()))
            .collect(),
        ..XyPlot::default()
    };
    [
        panel(|h| &h.depl, "DEPL", title),
        panel(|h| &h.vite, "VITE", ""),
    ]
}

/// Velocity against displacement: one closed orbit per periodic row.
pub fn phase_portrait(
    curves: &[History],
    title: &str,
    what: &str,
    path: &Path,
    format: ImageFormat,
) -> Result<PlotSummary> {
    xy_plot(&phase_portrait_spec(curves, title, what), path, format)
}

/// The plot of [`phase_portrait`].
pub fn phase_portrait_spec(curves: &[History], title: &str, what: &str) -> XyPlot {
    let cmp = what.split_whitespace().last();
    XyPlot {
        title: title.to_string(),
        x_label: with_unit(&format!("DEPL {what}"), "DEPL", cmp),
        y_label: with_unit(&format!("VITE {what}"), "VITE", cmp),
        series: curves
            .iter()
            .map(|h| Series::new(&h.label, h.depl.clone(), h.vite.clone()))
            .collect(),
        ..XyPlot::default()
    }
}
