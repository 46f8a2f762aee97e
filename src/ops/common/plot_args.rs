//! The picture keywords shared by IMPR_FONCTION and IMPR_TABLE (aster-nl extensions):
//! FORMAT='PNG'|'SVG', FICHIER / UNITE, TITRE, LEGENDE_X, LEGENDE_Y, ECHELLE_X, ECHELLE_Y,
//! BORNE_X, BORNE_Y; and the report of where the picture went.

use super::output::picture_path;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::ops::OpContext;
use crate::plot::{ImageFormat, PlotSummary, Scale, XyPlot};
use std::path::PathBuf;

/// The picture options of one call.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    pub format: ImageFormat,
    pub path: PathBuf,
    pub title: Option<String>,
    pub x_label: Option<String>,
    pub y_label: Option<String>,
    pub x_scale: Option<Scale>,
    pub y_scale: Option<Scale>,
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
}

fn scale(args: &Args, key: &str) -> Result<Option<Scale>> {
    args.text(key)
        .map(|s| {
            Scale::parse(s).ok_or_else(|| {
                Error::validation(format!("unknown scale '{s}'"))
                    .keyword(args.key_path(key))
                    .hint("use 'LIN' or 'LOG'")
            })
        })
        .transpose()
}

fn range(args: &Args, key: &str) -> Result<Option<(f64, f64)>> {
    match args.reals(key).as_deref() {
        None => Ok(None),
        Some([a, b]) => Ok(Some((*a, *b))),
        Some(v) => Err(Error::validation(format!(
            "{key} takes two values (min, max), got {}",
            v.len()
        ))
        .keyword(args.key_path(key))),
    }
}

/// The picture asked for, or `None` when FORMAT is a text format.
pub fn picture(ctx: &OpContext<'_>, args: &Args) -> Result<Option<Picture>> {
    // FORMAT and UNITE: the catalog's defaults and bound (UNITE >= 1).
    let Some(format) = ImageFormat::parse(args.req_text("FORMAT")?) else {
        return Ok(None);
    };
    let unite = args.req_int("UNITE")?;
    let fichier = args.text("FICHIER");
    if fichier.is_some_and(|f| f.trim().is_empty()) {
        return Err(Error::validation("FICHIER is empty").keyword(args.key_path("FICHIER")));
    }
    let path = picture_path(ctx.units, fichier, unite, format.extension());
    super::output::check_output_path(ctx.units, &path).map_err(|e| {
        e.keyword(args.key_path(if fichier.is_some() {
            "FICHIER"
        } else {
            "UNITE"
        }))
    })?;
    Ok(Some(Picture {
        format,
        path,
        // A picture title is one line.
        title: args.texts("TITRE").map(|l| l.join(" ")),
        x_label: args.text("LEGENDE_X").map(str::to_string),
        y_label: args.text("LEGENDE_Y").map(str::to_string),
        x_scale: scale(args, "ECHELLE_X")?,
        y_scale: scale(args, "ECHELLE_Y")?,
        x_range: range(args, "BORNE_X")?,
        y_range: range(args, "BORNE_Y")?,
    }))
}

impl Picture {
    /// Apply the options given by the user over the picture's own defaults.
    pub fn apply(&self, spec: &mut XyPlot) {
        if let Some(t) = &self.title {
            spec.title = t.clone();
        }
        self.apply_x(spec);
        if let Some(l) = &self.y_label {
            spec.y_label = l.clone();
        }
        if let Some(s) = self.y_scale {
            spec.y_scale = s;
        }
        if self.y_range.is_some() {
            spec.y_range = self.y_range;
        }
    }

    /// Apply only the abscissa options (panels that share the x axis).
    pub fn apply_x(&self, spec: &mut XyPlot) {
        if let Some(l) = &self.x_label {
            spec.x_label = l.clone();
        }
        if let Some(s) = self.x_scale {
            spec.x_scale = s;
        }
        if self.x_range.is_some() {
            spec.x_range = self.x_range;
        }
    }

    /// Tell the user where the picture went and what could not be drawn.
    pub fn report(&self, ctx: &mut OpContext<'_>, summary: &PlotSummary) -> Result<()> {
        ctx.say(&format!(
            "{}: picture written to {} ({} points)",
            ctx.op,
            self.path.display(),
            summary.points
        ))?;
        if let Some(note) = summary.skipped_note() {
            ctx.alarm("PLOT_1", &format!("{}: {note}", self.path.display()))?;
        }
        Ok(())
    }
}
