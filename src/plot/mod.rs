//! Pictures: curves drawn to PNG or SVG files with plotters. Pure drawing, no SQL.
//!
//! - [`xy_plot`]: general curves (IMPR_FONCTION, IMPR_TABLE with NOM_PARA); [`grace`]
//!   the same curves as a Grace project file (IMPR_FONCTION's FORMAT='XMGRACE').
//! - [`nnm`]: the pictures of nonlinear modes: frequency–energy (MODE_NON_LINE tables),
//!   time history and phase portrait (REST_MODE_NONL tables).
//!
//! Text is drawn with DejaVu Sans, shipped in `assets/fonts` and registered once, so no
//! system font library is needed. Points that cannot be drawn (NaN, not positive on a log
//! axis) are skipped and counted in the returned [`PlotSummary`]; nothing left to draw is
//! an error, never a panic.

pub mod axis;
pub mod data;
mod draw;
pub mod grace;
pub mod nnm;
pub mod tables;
pub mod units;

pub use axis::Scale;
pub use nnm::{
    frequency_energy, frequency_energy_spec, phase_portrait, phase_portrait_spec, time_history,
    time_history_specs, FePoint, History, Stability, HISTORY_SIZE,
};

use crate::error::{Error, Result};
use std::path::Path;
use std::sync::OnceLock;

/// Picture file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Svg,
}

impl ImageFormat {
    /// FORMAT='PNG' | 'SVG'.
    pub fn parse(s: &str) -> Option<ImageFormat> {
        match s {
            "PNG" => Some(ImageFormat::Png),
            "SVG" => Some(ImageFormat::Svg),
            _ => None,
        }
    }
    pub fn extension(self) -> &'static str {
        match self {
            ImageFormat::Png => "png",
            ImageFormat::Svg => "svg",
        }
    }
}

/// How a curve joins its points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineStyle {
    Solid,
    Dashed,
    Dotted,
    /// Markers only.
    None,
}

/// Symbol drawn at every point of a curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    None,
    Circle,
    Square,
    Triangle,
    Cross,
}

/// Where the legend box goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LegendPosition {
    /// The corner the curves cross least.
    Auto,
    UpperLeft,
    UpperRight,
    LowerLeft,
    LowerRight,
}

/// One curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend entry; `None` keeps the curve out of the legend.
    pub label: Option<String>,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub line: LineStyle,
    pub marker: Marker,
    /// RGB; `None` takes the next colour of the palette.
    pub color: Option<(u8, u8, u8)>,
    /// Line width in pixels.
    pub width: u32,
    /// Leading points that repeat points of an earlier series (a join between two styled
    /// runs, markers on a curve): drawn, but not counted in the [`PlotSummary`].
    pub repeats: usize,
}

impl Series {
    /// A solid curve without markers, palette colour, 2 pixels wide.
    pub fn new(label: &str, x: Vec<f64>, y: Vec<f64>) -> Series {
        Series {
            label: Some(label.to_string()).filter(|l| !l.is_empty()),
            x,
            y,
            line: LineStyle::Solid,
            marker: Marker::None,
            color: None,
            width: 2,
            repeats: 0,
        }
    }
    pub fn line(mut self, line: LineStyle) -> Series {
        self.line = line;
        self
    }
    pub fn marker(mut self, marker: Marker) -> Series {
        self.marker = marker;
        self
    }
    pub fn color(mut self, rgb: (u8, u8, u8)) -> Series {
        self.color = Some(rgb);
        self
    }
    pub fn width(mut self, width: u32) -> Series {
        self.width = width;
        self
    }
}

/// A picture of curves on one pair of axes.
#[derive(Clone, Debug, PartialEq)]
pub struct XyPlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_scale: Scale,
    pub y_scale: Scale,
    /// Axis ranges in data units (BORNE_X / BORNE_Y); `None` fits the data.
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    pub series: Vec<Series>,
    pub legend: LegendPosition,
    /// Pixels (width, height).
    pub size: (u32, u32),
}

/// Default picture size in pixels.
pub const DEFAULT_SIZE: (u32, u32) = (1024, 768);

impl Default for XyPlot {
    fn default() -> Self {
        XyPlot {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            x_scale: Scale::Lin,
            y_scale: Scale::Lin,
            x_range: None,
            y_range: None,
            series: Vec::new(),
            legend: LegendPosition::Auto,
            size: DEFAULT_SIZE,
        }
    }
}

/// What was drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PlotSummary {
    /// Points drawn.
    pub points: usize,
    /// Points skipped because a coordinate is NaN or infinite.
    pub skipped_nan: usize,
    /// Points skipped because a coordinate is not positive on a log axis.
    pub skipped_log: usize,
}

impl PlotSummary {
    /// A sentence for the user about skipped points, if any.
    pub fn skipped_note(&self) -> Option<String> {
        let mut parts = Vec::new();
        if self.skipped_log > 0 {
            parts.push(format!(
                "{} point(s) with a non-positive value on a log axis",
                self.skipped_log
            ));
        }
        if self.skipped_nan > 0 {
            parts.push(format!(
                "{} point(s) with a NaN or infinite value",
                self.skipped_nan
            ));
        }
        if parts.is_empty() {
            None
        } else {
            Some(format!("not drawn: {}", parts.join(", ")))
        }
    }

    fn add(&mut self, other: PlotSummary) {
        self.points += other.points;
        self.skipped_nan += other.skipped_nan;
        self.skipped_log += other.skipped_log;
    }
}

/// Register the embedded font under "sans-serif", once per process.
fn ensure_font() -> Result<()> {
    static FONT: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    FONT.get_or_init(|| {
        plotters::style::register_font(
            "sans-serif",
            plotters::style::FontStyle::Normal,
            include_bytes!("../../assets/fonts/DejaVuSans.ttf"),
        )
        .map_err(|_| "the embedded DejaVu Sans font could not be read".to_string())
    })
    .clone()
    .map_err(Error::internal)
}

/// Draw `spec` to `path`.
pub fn xy_plot(spec: &XyPlot, path: &Path, format: ImageFormat) -> Result<PlotSummary> {
    draw::render(&[spec], (1, 1), spec.size, path, format)
}

/// Draw several plots stacked vertically in one picture of `size` pixels.
pub fn stacked(
    panels: &[&XyPlot],
    size: (u32, u32),
    path: &Path,
    format: ImageFormat,
) -> Result<PlotSummary> {
    draw::render(panels, (panels.len(), 1), size, path, format)
}

#[cfg(test)]
pub(crate) mod tests;
