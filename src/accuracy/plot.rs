//! Error against time, log-log, one colour per sweep, the Pareto front joined and ringed.
//! Text uses DejaVu Sans embedded in the binary: the machines this runs on may have no
//! system fonts.

use super::measure::Measurement;
use super::pareto::{cost_error, pareto_front};
use super::CaseResult;
use crate::error::{Error, ErrorKind, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::Path;

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

fn io(what: &Path, e: impl std::fmt::Display) -> Error {
    Error::new(
        ErrorKind::Io,
        format!("cannot draw {}: {e}", what.display()),
    )
}

const SWEEPS: [(&str, RGBColor); 11] = [
    ("base", RGBColor(0, 0, 0)),
    ("sdnd122", RGBColor(140, 86, 75)),
    ("H_nl", RGBColor(31, 119, 180)),
    ("eta", RGBColor(214, 39, 40)),
    ("H_l", RGBColor(44, 160, 44)),
    ("PREC_MAN", RGBColor(148, 103, 189)),
    ("diagonal", RGBColor(255, 127, 14)),
    ("coarse", RGBColor(188, 189, 34)),
    ("fine", RGBColor(23, 190, 207)),
    ("reference", RGBColor(127, 127, 127)),
    ("exact", RGBColor(227, 119, 194)),
];

/// Decade bounds around the finite values, with a little margin.
fn bounds(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = v
        .filter(|x| x.is_finite() && *x > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    if !lo.is_finite() {
        return (1e-3, 1.0);
    }
    (
        10f64.powf((lo.log10() - 0.1).floor()),
        10f64.powf((hi.log10() + 0.1).ceil()),
    )
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    r: &CaseResult,
) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let ms: &[Measurement] = &r.measurements;
    let ce = cost_error(ms);
    let front = pareto_front(&ce);
    root.fill(&WHITE)?;
    let (area, note) = root.split_vertically(615);
    let (t0, t1) = bounds(ce.iter().map(|p| p.0));
    let (e0, e1) = bounds(ce.iter().map(|p| p.1));
    let mut chart = ChartBuilder::on(&area)
        .caption(
            format!(
                "{}: max relative frequency error against CPU time",
                r.case.kind.name()
            ),
            ("sans-serif", 22),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((t0..t1).log_scale(), (e0..e1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("CPU time of the whole branch (s, one thread)")
        .y_desc("max |f / f_ref - 1| over the range")
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .label_style(("sans-serif", 14))
        .draw()?;
    chart
        .draw_series(LineSeries::new(
            front.iter().map(|&i| ce[i]),
            ShapeStyle::from(&BLACK).stroke_width(1),
        ))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
    chart.draw_series(
        front
            .iter()
            .map(|&i| Circle::new(ce[i], 9, ShapeStyle::from(&BLACK).stroke_width(2))),
    )?;
    for (sweep, c) in SWEEPS {
        let pts: Vec<(f64, f64)> = ms
            .iter()
            .zip(&ce)
            .filter(|(m, p)| m.config.sweep == sweep && p.0.is_finite())
            .map(|(_, p)| *p)
            .collect();
        if pts.is_empty() {
            continue;
        }
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 5, c.filled())))?
            .label(sweep)
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, c.filled()));
    }
    // Label the Pareto points with their (H_l, H_nl, η, PREC_MAN).
    chart.draw_series(front.iter().map(|&i| {
        let c = &ms[i].config;
        // Beside the ring, not on it.
        EmptyElement::at(ce[i])
            + Text::new(
                format!("{}/{}/{:e}/{:e}", c.h_lin, c.h_nonl, c.regul, c.prec_man),
                (11, 2),
                ("sans-serif", 11).into_font(),
            )
    }))?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()?;
    note.draw(&Text::new(
        "labels: NB_HARM_LINE/NB_HARM_NONL/PARA_REGUL/PREC_MAN",
        (80, 10),
        ("sans-serif", 12).into_font(),
    ))?;
    root.present()
}

/// Writes `<stem>.png` and `<stem>.svg` (800×650).
pub fn plot(r: &CaseResult, stem: &Path) -> Result<()> {
    // Registering twice replaces the same font: harmless.
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| Error::internal("the embedded DejaVu Sans font is invalid"))?;
    let png = stem.with_extension("png");
    draw(BitMapBackend::new(&png, (800, 650)).into_drawing_area(), r).map_err(|e| io(&png, e))?;
    let svg = stem.with_extension("svg");
    draw(SVGBackend::new(&svg, (800, 650)).into_drawing_area(), r).map_err(|e| io(&svg, e))?;
    Ok(())
}
