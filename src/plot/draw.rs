//! The plotters side: one chart per panel, on a bitmap or SVG backend.

use super::axis::Axis;
use super::data::{bounds, clean, Cleaned};
use super::{ensure_font, ImageFormat, LegendPosition, LineStyle, Marker, PlotSummary, XyPlot};
use crate::error::{Error, Result};
use plotters::chart::SeriesAnno;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters_backend::DrawingErrorKind;
use std::path::Path;

/// Distinct colours that survive grey printing reasonably (the usual "tab10" hues).
const PALETTE: [(u8, u8, u8); 8] = [
    (31, 119, 180),
    (214, 39, 40),
    (44, 160, 44),
    (255, 127, 14),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (23, 190, 207),
];

const FONT: &str = "sans-serif";

/// A panel ready to draw: cleaned series and axes.
struct Prepared<'a> {
    spec: &'a XyPlot,
    series: Vec<Cleaned>,
    x: Axis,
    y: Axis,
}

fn axis_for(
    scale: super::Scale,
    range: Option<(f64, f64)>,
    data: (f64, f64),
    which: &str,
) -> Result<Axis> {
    match range {
        // Values near ±f64::MAX leave no finite span to divide into ticks.
        None if !(data.1 - data.0).is_finite() => Err(Error::input(format!(
            "the {which} values span [{:e}, {:e}]: too wide to draw",
            scale.to_data(data.0),
            scale.to_data(data.1)
        ))
        .hint(format!("give BORNE_{which}, or a LOG scale"))),
        None => Ok(Axis::new(scale, data.0, data.1, true)),
        Some((a, b)) => match (scale.to_plot(a), scale.to_plot(b)) {
            (Some(u), Some(v)) if u != v && (v - u).is_finite() => {
                Ok(Axis::new(scale, u, v, false))
            }
            _ => Err(
                Error::input(format!("the {which} axis range ({a}, {b}) cannot be drawn"))
                    .keyword(format!("BORNE_{which}"))
                    .hint("give two different finite bounds, positive on a log axis"),
            ),
        },
    }
}

fn prepare<'a>(spec: &'a XyPlot, summary: &mut PlotSummary) -> Result<Prepared<'a>> {
    let mut local = PlotSummary::default();
    let series = spec
        .series
        .iter()
        .map(|s| clean(s, spec.x_scale, spec.y_scale, &mut local))
        .collect::<Result<Vec<_>>>()?;
    summary.add(local);
    let Some((bx, by)) = bounds(&series) else {
        let what = if spec.series.is_empty() {
            "no curve was given".to_string()
        } else if local.skipped_nan + local.skipped_log == 0 {
            "the curves have no point".to_string()
        } else {
            local
                .skipped_note()
                .unwrap_or_else(|| "no drawable point".to_string())
        };
        return Err(Error::input(format!(
            "nothing to draw{}: {what}",
            if spec.title.is_empty() {
                String::new()
            } else {
                format!(" in '{}'", spec.title)
            }
        ))
        .hint("a log axis (ECHELLE_X/ECHELLE_Y='LOG') needs positive values"));
    };
    Ok(Prepared {
        spec,
        x: axis_for(spec.x_scale, spec.x_range, bx, "X")?,
        y: axis_for(spec.y_scale, spec.y_range, by, "Y")?,
        series,
    })
}

/// Draw the panels in a (rows, columns) grid to `path`.
pub(super) fn render(
    panels: &[&XyPlot],
    grid: (usize, usize),
    size: (u32, u32),
    path: &Path,
    format: ImageFormat,
) -> Result<PlotSummary> {
    ensure_font()?;
    if size.0 < 200 || size.1 < 150 {
        return Err(Error::input(format!(
            "a picture of {}×{} pixels is too small to draw",
            size.0, size.1
        )));
    }
    let mut summary = PlotSummary::default();
    let prepared = panels
        .iter()
        .map(|p| prepare(p, &mut summary))
        .collect::<Result<Vec<_>>>()?;
    let failed = |e: String| {
        Error::input(format!("cannot draw the picture {}: {e}", path.display()))
            .hint("check that the directory exists and is writable")
    };
    match format {
        ImageFormat::Png => {
            let root = BitMapBackend::new(path, size).into_drawing_area();
            draw_all(&root, &prepared, grid).map_err(|e| failed(e.to_string()))?;
            root.present().map_err(|e| failed(e.to_string()))?;
        }
        ImageFormat::Svg => {
            let root = SVGBackend::new(path, size).into_drawing_area();
            draw_all(&root, &prepared, grid).map_err(|e| failed(e.to_string()))?;
            root.present().map_err(|e| failed(e.to_string()))?;
        }
    }
    Ok(summary)
}

type DrawResult<DB> =
    std::result::Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

fn draw_all<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[Prepared<'_>],
    grid: (usize, usize),
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let areas = root.split_evenly(grid);
    for (area, p) in areas.iter().zip(panels) {
        draw_panel(area, p)?;
    }
    Ok(())
}

fn rgb(c: (u8, u8, u8)) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

fn draw_panel<'c, DB: DrawingBackend + 'c>(
    area: &'c DrawingArea<DB, Shift>,
    p: &Prepared<'_>,
) -> DrawResult<DB> {
    let spec = p.spec;
    let (xa, ya) = (&p.x, &p.y);
    // The y label area grows with the longest tick label (about 9 px a character at 16 px).
    let longest = ya
        .major
        .iter()
        .map(|&u| ya.label(u).chars().count())
        .max()
        .unwrap_or(1);
    let y_area = 34 + 9 * longest as u32;
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(y_area);
    if !spec.title.is_empty() {
        builder.caption(&spec.title, (FONT, 26));
    }
    let mut chart = builder.build_cartesian_2d(Ticked::new(xa), Ticked::new(ya))?;
    let xfmt = |u: &f64| xa.label(*u);
    let yfmt = |u: &f64| ya.label(*u);
    chart
        .configure_mesh()
        .x_desc(spec.x_label.as_str())
        .y_desc(spec.y_label.as_str())
        .x_label_formatter(&xfmt)
        .y_label_formatter(&yfmt)
        .label_style((FONT, 16))
        .axis_desc_style((FONT, 20))
        .bold_line_style(RGBColor(205, 205, 205))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()?;

    let mut labelled = false;
    for (k, (s, c)) in spec.series.iter().zip(&p.series).enumerate() {
        let color = rgb(s.color.unwrap_or(PALETTE[k % PALETTE.len()]));
        let style = ShapeStyle {
            color: color.to_rgba(),
            filled: false,
            stroke_width: s.width.max(1),
        };
        let width = s.width.max(1);
        let (line, marker) = (s.line, s.marker);
        // The legend entry goes on the first thing drawn: the first line piece, or the
        // markers of a curve without line. A series annotation borrows the chart, so it is
        // labelled at once.
        let mut pending = s.label.as_deref();
        let mut legend = |a: &mut SeriesAnno<'c, DB>| {
            if let Some(label) = pending.take() {
                a.label(label).legend(move |(x, y)| LegendGlyph {
                    at: (x, y),
                    line,
                    marker,
                    style,
                });
                labelled = true;
            }
        };
        for seg in &c.segments {
            let pts = seg.iter().copied();
            let dash = match line {
                LineStyle::Solid => {
                    legend(chart.draw_series(LineSeries::new(pts, style))?);
                    continue;
                }
                LineStyle::Dashed => (5 * width + 4, 3 * width + 3),
                LineStyle::Dotted => (width, 2 * width + 3),
                LineStyle::None => break,
            };
            legend(chart.draw_series(DashedLineSeries::new(pts, dash.0, dash.1, style))?);
        }
        let r = 3 + width;
        let ri = r as i32;
        let filled = style.filled();
        let pts = c.points();
        match marker {
            Marker::None => {}
            Marker::Circle => legend(chart.draw_series(pts.map(|q| Circle::new(q, r, filled)))?),
            Marker::Square => {
                legend(chart.draw_series(pts.map(|q| {
                    EmptyElement::at(q) + Rectangle::new([(-ri, -ri), (ri, ri)], filled)
                }))?)
            }
            Marker::Triangle => {
                legend(chart.draw_series(pts.map(|q| TriangleMarker::new(q, r + 2, filled)))?)
            }
            Marker::Cross => legend(chart.draw_series(pts.map(|q| Cross::new(q, r, style)))?),
        }
    }
    if labelled {
        chart
            .configure_series_labels()
            .position(match spec.legend {
                LegendPosition::Auto => emptiest_corner(p),
                LegendPosition::UpperLeft => SeriesLabelPosition::UpperLeft,
                LegendPosition::UpperRight => SeriesLabelPosition::UpperRight,
                LegendPosition::LowerLeft => SeriesLabelPosition::LowerLeft,
                LegendPosition::LowerRight => SeriesLabelPosition::LowerRight,
            })
            .margin(12)
            .legend_area_size(36)
            .label_font((FONT, 16))
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(120, 120, 120))
            .draw()?;
    }
    Ok(())
}

/// The corner of the plot whose legend-sized box holds the fewest points (ties: upper
/// right, upper left, lower right, lower left, in that order).
fn emptiest_corner(p: &Prepared<'_>) -> SeriesLabelPosition {
    // A legend covers roughly a third of the width and a quarter of the height.
    let (w, h) = (0.35, 0.25);
    let (xs, ys) = (
        (p.x.hi - p.x.lo).max(f64::MIN_POSITIVE),
        (p.y.hi - p.y.lo).max(f64::MIN_POSITIVE),
    );
    let corners = [
        (
            SeriesLabelPosition::UpperRight,
            (1.0 - w, 1.0),
            (1.0 - h, 1.0),
        ),
        (SeriesLabelPosition::UpperLeft, (0.0, w), (1.0 - h, 1.0)),
        (SeriesLabelPosition::LowerRight, (1.0 - w, 1.0), (0.0, h)),
        (SeriesLabelPosition::LowerLeft, (0.0, w), (0.0, h)),
    ];
    let count = |(x0, x1): (f64, f64), (y0, y1): (f64, f64)| {
        p.series
            .iter()
            .flat_map(Cleaned::points)
            .filter(|&(u, v)| {
                let (a, b) = ((u - p.x.lo) / xs, (v - p.y.lo) / ys);
                (x0..=x1).contains(&a) && (y0..=y1).contains(&b)
            })
            .count()
    };
    let mut best = SeriesLabelPosition::UpperRight;
    let mut fewest = usize::MAX;
    for (pos, xr, yr) in corners {
        let n = count(xr, yr);
        if n < fewest {
            fewest = n;
            best = pos;
        }
    }
    best
}

/// A linear coordinate in plotting units whose grid lines are the axis' own ticks (bold:
/// labelled ticks, light: minor ones). plotters' `WithKeyPoints` would do, but it loses
/// the default value formatting that `configure_mesh` asks for, so this small one keeps it.
struct Ticked {
    inner: RangedCoordf64,
    major: Vec<f64>,
    minor: Vec<f64>,
}

impl Ticked {
    fn new(a: &Axis) -> Ticked {
        Ticked {
            inner: (a.lo..a.hi).into(),
            major: a.major.clone(),
            minor: a.minor.clone(),
        }
    }
}

impl Ranged for Ticked {
    type FormatOption = plotters::coord::ranged1d::DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: plotters::coord::ranged1d::KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.major.clone()
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.inner.range()
    }
}

/// The legend sample: 30 pixels of the line style with the marker in its middle. Its own
/// element type, because the legend closure must return one concrete type for every
/// line/marker combination (a boxed `DynElement` would force a `'static` backend).
struct LegendGlyph {
    at: (i32, i32),
    line: LineStyle,
    marker: Marker,
    style: ShapeStyle,
}

impl<'a> PointCollection<'a, (i32, i32)> for &'a LegendGlyph {
    type Point = &'a (i32, i32);
    type IntoIter = std::iter::Once<&'a (i32, i32)>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<DB: DrawingBackend> Drawable<DB> for LegendGlyph {
    fn draw<I: Iterator<Item = (i32, i32)>>(
        &self,
        mut pos: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> std::result::Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = pos.next() else {
            return Ok(());
        };
        let pieces: &[(i32, i32)] = match self.line {
            LineStyle::Solid => &[(0, 30)],
            LineStyle::Dashed => &[(0, 8), (11, 19), (22, 30)],
            LineStyle::Dotted => &[(3, 5), (9, 11), (15, 17), (21, 23), (27, 29)],
            LineStyle::None => &[],
        };
        for &(a, b) in pieces {
            backend.draw_path([(x + a, y), (x + b, y)], &self.style)?;
        }
        let r = 3 + self.style.stroke_width as i32;
        let c = (x + 15, y);
        let f = self.style.filled();
        match self.marker {
            Marker::None => Ok(()),
            Marker::Circle => backend.draw_circle(c, r as u32, &f, true),
            Marker::Square => backend.draw_rect((c.0 - r, c.1 - r), (c.0 + r, c.1 + r), &f, true),
            Marker::Triangle => {
                let h = r + 2;
                // Same proportions as plotters' TriangleMarker.
                let (dx, dy) = ((f64::from(h) * 0.866) as i32, h / 2);
                backend.fill_polygon(
                    [(c.0, c.1 - h), (c.0 - dx, c.1 + dy), (c.0 + dx, c.1 + dy)],
                    &f,
                )
            }
            Marker::Cross => {
                backend.draw_path([(c.0 - r, c.1 - r), (c.0 + r, c.1 + r)], &self.style)?;
                backend.draw_path([(c.0 - r, c.1 + r), (c.0 + r, c.1 - r)], &self.style)
            }
        }
    }
}
