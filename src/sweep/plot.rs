//! The family of frequency–energy curves of a sweep, one curve per point, coloured by one
//! parameter: the picture IMPR_TABLE draws for one MODE_NON_LINE table, for all the points
//! at once (energy on a log axis; solid where stable or not evaluated, dashed where
//! unstable). The other parameters, if any, change the marker.

use super::merge::{META_TABLE, POINTS_TABLE, POINT_COLUMN};
use crate::error::{Error, ErrorKind, Result};
use crate::plot::nnm::Stability;
use crate::plot::{xy_plot, ImageFormat, LegendPosition, LineStyle, Marker, Scale, Series, XyPlot};
use rusqlite::{Connection, OpenFlags};
use std::path::{Path, PathBuf};

/// One point's curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// The colouring parameter's value (numeric), if it is a number.
    pub key: Option<f64>,
    /// The colouring parameter's value as text (for a parameter that is not a number).
    pub key_text: String,
    /// The other parameters that vary across the points, as `NAME=value, ...`: curves
    /// that share them share a marker.
    pub others: String,
    pub energy: Vec<f64>,
    pub freq: Vec<f64>,
    pub stability: Vec<Stability>,
}

/// What was drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct FamilyPicture {
    pub table: String,
    pub colour: String,
    pub curves: usize,
    pub files: Vec<PathBuf>,
}

/// Draw the family of a merged database to `stem.png` and `stem.svg`. `table` names the
/// MODE_NON_LINE table (default: the first one the runs created), `colour` the parameter
/// (default: the first). `Ok(None)` when the runs hold no MODE_NON_LINE table.
pub fn draw_family(
    merged: &Path,
    table: Option<&str>,
    colour: Option<&str>,
    stem: &Path,
) -> Result<Option<FamilyPicture>> {
    let conn = Connection::open_with_flags(merged, OpenFlags::SQLITE_OPEN_READ_ONLY)
        .map_err(|e| sql(merged, e))?;
    let params: Vec<String> = conn
        .query_row(
            &format!("SELECT value FROM \"{META_TABLE}\" WHERE key = 'params'"),
            [],
            |r| r.get::<_, String>(0),
        )
        .map_err(|e| sql(merged, e))
        .and_then(|t| {
            serde_json::from_str(&t)
                .map_err(|e| Error::new(ErrorKind::Store, format!("{META_TABLE}: {e}")))
        })?;
    let table = match table {
        Some(t) => t.to_string(),
        None => match first_mnl_table(&conn).map_err(|e| sql(merged, e))? {
            Some(t) => t,
            None => return Ok(None),
        },
    };
    let Some(colour) = colour
        .map(str::to_string)
        .or_else(|| params.first().cloned())
    else {
        return Ok(None);
    };
    let ci = params.iter().position(|p| *p == colour).ok_or_else(|| {
        Error::input(format!(
            "plot.colour: '{colour}' is not a parameter of the sweep ({})",
            params.join(", ")
        ))
    })?;
    let curves = read_curves(&conn, &table, &params, ci).map_err(|e| match e {
        rusqlite::Error::SqliteFailure(_, Some(m)) if m.contains("no such") => Error::input(
            format!("plot.table: the runs have no MODE_NON_LINE table {table} ({m})"),
        ),
        e => sql(merged, e),
    })?;
    if curves.is_empty() {
        return Ok(None);
    }
    let spec = family_spec(
        &curves,
        &colour,
        &format!("{table}: {} point(s), colour {colour}", curves.len()),
    );
    let mut files = Vec::new();
    for format in [ImageFormat::Png, ImageFormat::Svg] {
        let path = stem.with_extension(format.extension());
        xy_plot(&spec, &path, format)?;
        files.push(path);
    }
    Ok(Some(FamilyPicture {
        table,
        colour,
        curves: curves.len(),
        files,
    }))
}

/// The first table MODE_NON_LINE created in the runs (the merged `concepts` table).
fn first_mnl_table(conn: &Connection) -> rusqlite::Result<Option<String>> {
    let has_concepts: i64 = conn.query_row(
        "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'concepts'",
        [],
        |r| r.get(0),
    )?;
    if has_concepts == 0 {
        return Ok(None);
    }
    let mut stmt = conn.prepare(
        "SELECT name FROM concepts WHERE operator = 'MODE_NON_LINE' \
         AND name IN (SELECT name FROM sqlite_master WHERE type = 'table') \
         ORDER BY rowid LIMIT 1",
    )?;
    let mut rows = stmt.query([])?;
    match rows.next()? {
        Some(r) => Ok(Some(r.get(0)?)),
        None => Ok(None),
    }
}

fn read_curves(
    conn: &Connection,
    table: &str,
    params: &[String],
    colour: usize,
) -> rusqlite::Result<Vec<Curve>> {
    let qt = format!("\"{}\"", table.replace('"', "\"\""));
    let has_stab = {
        let mut stmt = conn.prepare(&format!("PRAGMA table_info({qt})"))?;
        let cols: Vec<String> = stmt
            .query_map([], |r| r.get::<_, String>(1))?
            .collect::<rusqlite::Result<_>>()?;
        cols.iter().any(|c| c.eq_ignore_ascii_case("STABILITE"))
    };
    let value_cols: Vec<String> = params
        .iter()
        .map(|p| format!("\"{}\"", p.replace('"', "\"\"")))
        .collect();
    let mut stmt = conn.prepare(&format!(
        "SELECT \"{POINT_COLUMN}\", {} FROM \"{POINTS_TABLE}\" \
         WHERE STATUS IN ('ok', 'nook') ORDER BY rowid",
        value_cols.join(", ")
    ))?;
    let points: Vec<(String, Vec<rusqlite::types::Value>)> = stmt
        .query_map([], |r| {
            let vals = (0..params.len())
                .map(|i| r.get::<_, rusqlite::types::Value>(i + 1))
                .collect::<rusqlite::Result<Vec<_>>>()?;
            Ok((r.get::<_, String>(0)?, vals))
        })?
        .collect::<rusqlite::Result<_>>()?;
    let stab = if has_stab { "STABILITE" } else { "NULL" };
    let mut rows = conn.prepare(&format!(
        "SELECT ENERGIE, FREQUENCE, {stab} FROM {qt} WHERE \"{POINT_COLUMN}\" = ?1 ORDER BY rowid"
    ))?;
    // Parameters with one value over the whole sweep say nothing about a curve.
    let varies: Vec<bool> = (0..params.len())
        .map(|i| points.iter().any(|(_, v)| v[i] != points[0].1[i]))
        .collect();
    let mut curves = Vec::new();
    for (point, vals) in points.iter() {
        let mut c = Curve {
            key: number(&vals[colour]),
            key_text: text(&vals[colour]),
            others: params
                .iter()
                .zip(vals)
                .enumerate()
                .filter(|(i, _)| *i != colour && varies[*i])
                .map(|(_, (p, v))| format!("{p}={}", text(v)))
                .collect::<Vec<_>>()
                .join(", "),
            energy: Vec::new(),
            freq: Vec::new(),
            stability: Vec::new(),
        };
        let mut q = rows.query([point])?;
        while let Some(r) = q.next()? {
            let (Some(e), Some(f)) = (r.get::<_, Option<f64>>(0)?, r.get::<_, Option<f64>>(1)?)
            else {
                continue;
            };
            c.energy.push(e);
            c.freq.push(f);
            c.stability.push(
                r.get::<_, Option<String>>(2)?
                    .map_or(Stability::NotEvaluated, |s| Stability::parse(&s)),
            );
        }
        if !c.energy.is_empty() {
            curves.push(c);
        }
    }
    Ok(curves)
}

/// Legend entries for colours (and for markers) at most: beyond, evenly spaced values
/// stand for the scale, which is ordered.
const LEGEND_MAX: usize = 10;

/// The plot of a family: one colour per value of the colouring parameter along a scale
/// ordered in lightness (log-spaced when its values span more than a decade), one marker
/// (then marker and dotted line) per combination of the other parameters. The legend lists
/// the colours, then the markers, not every curve: a sweep has too many.
pub fn family_spec(curves: &[Curve], colour: &str, title: &str) -> XyPlot {
    let nums: Vec<f64> = curves.iter().filter_map(|c| c.key).collect();
    let numeric = nums.len() == curves.len();
    let (lo, hi) = nums
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let log = numeric && lo > 0.0 && hi / lo > 10.0;
    // Distinct colour values in their order (numeric order for numbers).
    let mut keys: Vec<usize> = Vec::new();
    for (i, c) in curves.iter().enumerate() {
        if !keys.iter().any(|&k| curves[k].key_text == c.key_text) {
            keys.push(i);
        }
    }
    if numeric {
        keys.sort_by(|&a, &b| {
            curves[a]
                .key
                .partial_cmp(&curves[b].key)
                .unwrap_or(std::cmp::Ordering::Equal)
        });
    }
    let mut others: Vec<usize> = Vec::new();
    for (i, c) in curves.iter().enumerate() {
        if !others.iter().any(|&k| curves[k].others == c.others) {
            others.push(i);
        }
    }
    let position = |c: &Curve| -> f64 {
        match (numeric, c.key) {
            (true, Some(x)) if hi > lo => {
                if log {
                    (x.ln() - lo.ln()) / (hi.ln() - lo.ln())
                } else {
                    (x - lo) / (hi - lo)
                }
            }
            (true, _) => 0.5,
            _ => {
                let i = keys
                    .iter()
                    .position(|&k| curves[k].key_text == c.key_text)
                    .unwrap_or(0);
                if keys.len() > 1 {
                    i as f64 / (keys.len() - 1) as f64
                } else {
                    0.5
                }
            }
        }
    };
    // The scale's last tenths are too light on white for a thin line.
    let rgb = |c: &Curve| colour_scale(0.85 * position(c));
    const MARKERS: [Marker; 5] = [
        Marker::None,
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Cross,
    ];
    let style = |c: &Curve| -> (Marker, LineStyle) {
        let i = others
            .iter()
            .position(|&k| curves[k].others == c.others)
            .unwrap_or(0);
        let line = if (i / MARKERS.len()) % 2 == 1 {
            LineStyle::Dotted
        } else {
            LineStyle::Solid
        };
        (MARKERS[i % MARKERS.len()], line)
    };

    // Legend-only series first (drawn under the curves): one point of a curve, repeated
    // so that nothing is counted twice; a line of one point draws nothing.
    let mut series = Vec::new();
    let legend_entry = |label: String, c: &Curve, rgb: (u8, u8, u8), marker: Marker, line| {
        let mut s = Series::new(&label, vec![c.energy[0]], vec![c.freq[0]])
            .line(line)
            .marker(marker)
            .color(rgb)
            .width(2);
        s.repeats = 1;
        s
    };
    for k in spread(keys.len(), LEGEND_MAX) {
        let c = &curves[keys[k]];
        series.push(legend_entry(
            format!("{colour}={}", c.key_text),
            c,
            rgb(c),
            Marker::None,
            LineStyle::Solid,
        ));
    }
    if others.len() > 1 {
        for &k in others.iter().take(LEGEND_MAX) {
            let c = &curves[k];
            let (marker, line) = style(c);
            series.push(legend_entry(c.others.clone(), c, GREY, marker, line));
        }
    }
    for c in curves {
        let rgb = rgb(c);
        let (marker, base) = style(c);
        // Runs of one stability, each starting at the last point of the previous run.
        let mut start = 0;
        while start < c.energy.len() {
            let kind = c.stability[start];
            let end = c.stability[start..]
                .iter()
                .position(|s| *s != kind)
                .map_or(c.energy.len(), |n| start + n);
            let from = start.saturating_sub(1);
            let mut s = Series::new("", c.energy[from..end].to_vec(), c.freq[from..end].to_vec())
                .line(if kind == Stability::Unstable {
                    LineStyle::Dashed
                } else {
                    base
                })
                .marker(marker)
                .color(rgb)
                .width(2);
            s.repeats = start - from;
            series.push(s);
            start = end;
        }
    }
    XyPlot {
        title: title.to_string(),
        x_label: "ENERGIE (J)".into(),
        y_label: "FREQUENCE (Hz)".into(),
        x_scale: Scale::Log,
        y_scale: Scale::Lin,
        series,
        legend: LegendPosition::Auto,
        ..XyPlot::default()
    }
}

/// At most `max` of the indices `0..n`, evenly spread, first and last included.
fn spread(n: usize, max: usize) -> Vec<usize> {
    if n <= max || max < 2 {
        return (0..n.min(max.max(1))).collect();
    }
    let mut v: Vec<usize> = (0..max)
        .map(|i| ((i * (n - 1)) as f64 / (max - 1) as f64).round() as usize)
        .collect();
    v.dedup();
    v
}

const GREY: (u8, u8, u8) = (110, 110, 110);

/// A dark-blue → teal → yellow scale (viridis' end points and mid-tones), `t` in [0, 1]:
/// ordered in lightness, so the order of the values reads without a legend and in grey.
pub fn colour_scale(t: f64) -> (u8, u8, u8) {
    const STOPS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    };
    let x = t * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let mix = |p: f64, q: f64| (p + (q - p) * f).round().clamp(0.0, 255.0) as u8;
    (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

fn number(v: &rusqlite::types::Value) -> Option<f64> {
    match v {
        rusqlite::types::Value::Integer(i) => Some(*i as f64),
        rusqlite::types::Value::Real(x) => Some(*x),
        _ => None,
    }
}

fn text(v: &rusqlite::types::Value) -> String {
    match v {
        rusqlite::types::Value::Integer(i) => i.to_string(),
        rusqlite::types::Value::Real(x) => format!("{x:?}"),
        rusqlite::types::Value::Text(s) => s.clone(),
        rusqlite::types::Value::Null => "-".into(),
        rusqlite::types::Value::Blob(_) => "blob".into(),
    }
}

fn sql(db: &Path, e: rusqlite::Error) -> Error {
    Error::new(ErrorKind::Store, format!("{}: {e}", db.display()))
}
