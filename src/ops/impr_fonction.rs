//! IMPR_FONCTION: print functions as tables of points (FORMAT='TABLEAU'), as a Grace
//! project file (FORMAT='XMGRACE'), or draw them (FORMAT='PNG' | 'SVG', aster-nl). A curve is a function (COURBE=_F(FONCTION=...)) or
//! lists of points (COURBE=_F(ABSCISSE=..., ORDONNEE=...)).

use super::common::output::write_unit;
use super::common::plot_args::{picture, Picture};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::Function;
use crate::plot::units::{is_component, with_unit};
use crate::plot::{xy_plot, LineStyle, Marker, Series, XyPlot};
use crate::store::function::load_function;
use crate::table::print::{tableau, FormatR};
use crate::table::{Cell, ColKind, Column, Table};

/// The points of `f` as a two-column table (NOM_PARA, NOM_RESU).
pub fn as_table(f: &Function) -> Result<Table> {
    points_table(
        &format!("FONCTION {}", f.name),
        &f.nom_para,
        &f.nom_resu,
        &f.x,
        &f.y,
    )
}

fn points_table(title: &str, para: &str, resu: &str, x: &[f64], y: &[f64]) -> Result<Table> {
    let col = |name: &str, v: &[f64]| {
        (
            Column {
                name: name.to_string(),
                kind: ColKind::R,
            },
            v.iter().map(|&x| Cell::R(x)).collect::<Vec<_>>(),
        )
    };
    // A function whose parameter and result share a name still prints both columns.
    let resu = if resu == para {
        format!("{resu}_")
    } else {
        resu.to_string()
    };
    Table::from_columns(title, vec![col(para, x), col(&resu, y)])
}

/// One COURBE occurrence: its points, the names of its axes and its default legend.
struct Curve {
    name: String,
    para: String,
    resu: String,
    x: Vec<f64>,
    y: Vec<f64>,
}

fn curve(ctx: &OpContext<'_>, c: &Args) -> Result<Curve> {
    if let Some(fc) = c.concept("FONCTION") {
        let f =
            load_function(ctx.store, &fc.name).map_err(|e| e.keyword(c.key_path("FONCTION")))?;
        return Ok(Curve {
            name: f.name,
            para: f.nom_para,
            resu: f.nom_resu,
            x: f.x,
            y: f.y,
        });
    }
    let (Some(x), Some(y)) = (c.reals("ABSCISSE"), c.reals("ORDONNEE")) else {
        return Err(
            Error::validation("a curve needs FONCTION, or ABSCISSE and ORDONNEE")
                .keyword(c.key_path("FONCTION")),
        );
    };
    if x.len() != y.len() {
        return Err(
            Error::validation(format!("{} abscissas for {} ordinates", x.len(), y.len()))
                .keyword(c.key_path("ORDONNEE")),
        );
    }
    Ok(Curve {
        name: String::new(),
        para: "ABSCISSE".into(),
        resu: "ORDONNEE".into(),
        x,
        y,
    })
}

/// STYLE as xmgrace numbers it: 0 no line, 1 solid, 2 dotted, 3 and more dashed.
fn line_style(n: i64) -> LineStyle {
    match n {
        0 => LineStyle::None,
        1 => LineStyle::Solid,
        2 => LineStyle::Dotted,
        _ => LineStyle::Dashed,
    }
}

/// MARQUEUR as xmgrace numbers it: 0 none, 1 circle, 2 square, 3 to 7 diamond and
/// triangles (drawn as triangles), 8 and more plus/cross/star (drawn as crosses).
fn marker(n: i64) -> Marker {
    match n {
        0 => Marker::None,
        1 => Marker::Circle,
        2 => Marker::Square,
        3..=7 => Marker::Triangle,
        _ => Marker::Cross,
    }
}

/// COULEUR in xmgrace's default map (0 white is drawn black: a white curve is invisible).
fn color(n: i64) -> (u8, u8, u8) {
    match n {
        2 => (220, 30, 30),
        3 => (30, 160, 30),
        4 => (30, 60, 220),
        5 => (220, 200, 0),
        6 => (150, 80, 30),
        7 => (150, 150, 150),
        8 => (140, 30, 200),
        9 => (0, 190, 210),
        10 => (220, 0, 200),
        11 => (255, 140, 0),
        12 => (90, 40, 160),
        13 => (120, 20, 40),
        14 => (60, 210, 190),
        15 => (0, 140, 70),
        _ => (0, 0, 0),
    }
}

/// TRI: sort the points by X, Y, X then Y, or Y then X (N: as given).
fn sort_points(x: &mut Vec<f64>, y: &mut Vec<f64>, tri: &str) {
    let mut pts: Vec<(f64, f64)> = x.iter().copied().zip(y.iter().copied()).collect();
    match tri {
        "X" => pts.sort_by(|a, b| a.0.total_cmp(&b.0)),
        "Y" => pts.sort_by(|a, b| a.1.total_cmp(&b.1)),
        "XY" => pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1))),
        "YX" => pts.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0))),
        _ => return,
    }
    *x = pts.iter().map(|p| p.0).collect();
    *y = pts.iter().map(|p| p.1).collect();
}

fn series(c: &Args, mut cv: Curve) -> Series {
    if let Some(tri) = c.text("TRI") {
        sort_points(&mut cv.x, &mut cv.y, tri);
    }
    // Not a catalog default: without LEGENDE a curve is labelled with its function's name.
    let label = c.text("LEGENDE").unwrap_or(&cv.name);
    let mut s = Series::new(label, cv.x, cv.y);
    if let Some(n) = c.int("STYLE") {
        s = s.line(line_style(n));
    }
    if let Some(n) = c.int("MARQUEUR") {
        s = s.marker(marker(n));
    }
    if let Some(n) = c.int("COULEUR") {
        s = s.color(color(n));
    }
    s
}

/// The curves of COURBE, their axes named after the first one.
fn curves(ctx: &OpContext<'_>, args: &Args) -> Result<XyPlot> {
    let mut spec = XyPlot::default();
    for c in args.facts_or_empty("COURBE") {
        let cv = curve(ctx, c)?;
        // The axes are named after the first curve's parameter and result.
        if spec.series.is_empty() {
            // With units where the name says them (INST (s), FREQUENCE (Hz)); a component
            // (DX of a RECU_FONCTION) may be a displacement, a velocity or an acceleration.
            spec.x_label = with_unit(&cv.para, &cv.para, None);
            spec.y_label = if is_component(&cv.resu) {
                cv.resu.clone()
            } else {
                with_unit(&cv.resu, &cv.resu, None)
            };
        }
        spec.series.push(series(c, cv));
    }
    Ok(spec)
}

fn draw(ctx: &mut OpContext<'_>, args: &Args, pic: &Picture) -> Result<()> {
    let mut spec = curves(ctx, args)?;
    pic.apply(&mut spec);
    let summary = xy_plot(&spec, &pic.path, pic.format).map_err(|e| match e.keyword {
        None => e.keyword("IMPR_FONCTION/COURBE"),
        Some(_) => e,
    })?;
    pic.report(ctx, &summary)
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    if let Some(pic) = picture(ctx, args)? {
        return draw(ctx, args, &pic);
    }
    // Defaults are the catalog's (commands/IMPR_FONCTION.toml), filled by the validation.
    let format = args.req_text("FORMAT")?;
    if format == "XMGRACE" {
        return grace_project(ctx, args);
    }
    if format != "TABLEAU" {
        return Err(
            Error::validation(format!("FORMAT '{format}' is not supported"))
                .keyword("IMPR_FONCTION/FORMAT")
                .hint("use 'TABLEAU', or 'PNG' / 'SVG' for a picture"),
        );
    }
    // IMPR_FONCTION has no FORMAT_R keyword: the values print as IMPR_TABLE's default.
    let fmt = FormatR::parse("E12.5")?;
    let mut text = String::new();
    for (k, c) in args.facts_or_empty("COURBE").iter().enumerate() {
        let cv = curve(ctx, c)?;
        let title = if cv.name.is_empty() {
            format!("COURBE {}", k + 1)
        } else {
            format!("FONCTION {}", cv.name)
        };
        let t = points_table(&title, &cv.para, &cv.resu, &cv.x, &cv.y)?;
        text.push_str(&tableau(&t, &t.title, fmt, " "));
    }
    let unite = args.req_int("UNITE")?;
    write_unit(ctx, unite, &text)
}

/// FORMAT='XMGRACE': the curves as a Grace project written to UNITE (Code_Aster's file
/// without PILOTE); a PILOTE (Grace drawing or showing it) is not offered.
fn grace_project(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    if let Some(p) = args.text("PILOTE").filter(|p| !p.is_empty()) {
        return Err(Error::validation(format!(
            "PILOTE='{p}': aster-nl does not run Grace; without PILOTE, FORMAT='XMGRACE' \
             writes the Grace project file"
        ))
        .keyword("IMPR_FONCTION/PILOTE")
        .hint("for a picture, use FORMAT='PNG' or 'SVG'"));
    }
    let mut spec = curves(ctx, args)?;
    if let Some(t) = args.text("TITRE") {
        spec.title = t.to_string();
    }
    let unite = args.req_int("UNITE")?;
    write_unit(ctx, unite, &crate::plot::grace::project(&spec))
}
