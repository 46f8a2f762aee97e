//! The study file of a sweep (TOML): the template, the values of the parameters (a grid or a
//! list), the units to map, how to run (local pool or Slurm) and what to draw.
//!
//! Every error names the study file, the line and the key, and says what was expected.

use super::value::ParamValue;
use crate::error::{Error, Result};
use crate::lang::diag::LineIndex;
use crate::lang::Source;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Where the points run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scheduler {
    /// A bounded pool of processes on this machine.
    Local,
    /// One Slurm job array, one task per point.
    Slurm,
}

/// Slurm settings (`[slurm]`): everything is optional; Slurm's own defaults apply.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SlurmSettings {
    pub partition: Option<String>,
    /// `--time` of one task, in Slurm's format (`MM`, `HH:MM:SS`, `D-HH`).
    pub time: Option<String>,
    /// At most this many tasks of the array run at once (`--array=...%N`).
    pub max_running: Option<u32>,
    /// Largest array one `sbatch` submits (the cluster's MaxArraySize - 1 at most); more
    /// points are submitted as several arrays.
    pub array_chunk: usize,
    /// Extra `sbatch` options, passed as they are (`--mem=2G`, `--account=...`).
    pub sbatch_args: Vec<String>,
    /// The aster-nl binary the tasks run (default: this one); must be reachable from the
    /// compute nodes.
    pub exe: Option<PathBuf>,
}

/// Slurm's default MaxArraySize is 1001: indices 0..=1000.
pub const DEFAULT_ARRAY_CHUNK: usize = 1000;

/// What the sweep draws at the end (`[plot]`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlotSettings {
    /// The MODE_NON_LINE table to draw (default: the first the runs created).
    pub table: Option<String>,
    /// The parameter that colours the curves (default: the first parameter).
    pub colour: Option<String>,
}

/// One point of the sweep: a value for every parameter, in the study's parameter order.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub values: Vec<ParamValue>,
}

/// A parsed study file.
#[derive(Clone, Debug)]
pub struct Study {
    /// The study file itself.
    pub path: PathBuf,
    /// The `.comm` template (absolute or relative to the working directory, as resolved).
    pub template: PathBuf,
    /// Output directory (`out =`, else `<study stem>.sweep` beside the study file).
    pub out: PathBuf,
    /// Logical units mapped for every point, paths resolved against the study's directory.
    pub units: Vec<(i64, PathBuf)>,
    /// Parameter names, in the order the study file gives them.
    pub params: Vec<String>,
    /// Where each parameter's values were written in the study file (for errors).
    pub param_spans: Vec<Range<usize>>,
    pub points: Vec<Point>,
    pub scheduler: Scheduler,
    /// Local processes at once (`[run] jobs`); `None`: the machine's cores.
    pub jobs: Option<usize>,
    /// Seconds one point may run before it is stopped and counted as failed.
    pub timeout: Option<f64>,
    pub slurm: SlurmSettings,
    pub plot: PlotSettings,
    /// The study file's text, for error messages that point into it.
    pub source: Source,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    template: Spanned<String>,
    out: Option<Spanned<String>>,
    #[serde(default)]
    units: BTreeMap<String, Spanned<String>>,
    grid: Option<Spanned<BTreeMap<String, Spanned<toml::Value>>>>,
    list: Option<Spanned<BTreeMap<String, Spanned<toml::Value>>>>,
    #[serde(default)]
    run: RawRun,
    #[serde(default)]
    slurm: RawSlurm,
    #[serde(default)]
    plot: RawPlot,
}

#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRun {
    scheduler: Option<Spanned<String>>,
    jobs: Option<Spanned<i64>>,
    timeout: Option<Spanned<f64>>,
}

#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSlurm {
    partition: Option<String>,
    time: Option<String>,
    max_running: Option<Spanned<i64>>,
    array_chunk: Option<Spanned<i64>>,
    #[serde(default)]
    sbatch_args: Vec<String>,
    exe: Option<String>,
}

#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlot {
    table: Option<String>,
    colour: Option<Spanned<String>>,
}

/// Largest sweep one study may describe: far beyond any cluster's array limits, small
/// enough that a typo (`[grid]` with five 100-value lists) is refused before any file is
/// written.
pub const MAX_POINTS: usize = 1_000_000;

impl Study {
    /// Read and check a study file.
    pub fn load(path: &Path) -> Result<Study> {
        let text = crate::text_file::read(path, "the study file")?;
        Study::parse(path, text)
    }

    /// Check a study file's text; `path` names it and anchors its relative paths.
    pub fn parse(path: &Path, text: String) -> Result<Study> {
        let source = Source {
            name: path.display().to_string(),
            text,
        };
        let at = |msg: String, span: Option<Range<usize>>| -> Error {
            let idx = LineIndex::new(&source.text);
            let e = Error::input(msg);
            match span {
                Some(r) => e.at(&source.name, idx.span(r.start, r.end)),
                None => e.at_line(&source.name, 1),
            }
        };
        let raw: RawStudy = toml::from_str(&source.text).map_err(|e| {
            at(format!("study file: {}", e.message().trim_end()), e.span()).hint(STUDY_HINT)
        })?;
        let base = path.parent().unwrap_or(Path::new(""));
        let resolve = |p: &str| -> PathBuf {
            let p = PathBuf::from(p);
            if p.is_absolute() {
                p
            } else {
                base.join(p)
            }
        };

        let template = resolve(raw.template.get_ref());
        if !template.is_file() {
            return Err(at(
                format!("template: {} does not exist", template.display()),
                Some(raw.template.span()),
            )
            .hint("the template path is relative to the study file"));
        }
        let out = match &raw.out {
            Some(o) if o.get_ref().trim().is_empty() => {
                return Err(at("out: an empty directory name".into(), Some(o.span())))
            }
            Some(o) => resolve(o.get_ref()),
            None => {
                let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("study");
                base.join(format!("{stem}.sweep"))
            }
        };

        let mut units = Vec::new();
        for (k, v) in &raw.units {
            let n: i64 = k.parse().map_err(|_| {
                at(format!("units: '{k}' is not a unit number"), Some(v.span()))
                    .hint("write e.g. `20 = \"mesh.mail\"` under [units]")
            })?;
            let p = resolve(v.get_ref());
            if !p.is_file() {
                return Err(at(
                    format!("units.{k}: {} does not exist", p.display()),
                    Some(v.span()),
                ));
            }
            units.push((n, p));
        }

        let (table, zipped) = match (raw.grid, raw.list) {
            (Some(g), None) => (g, false),
            (None, Some(l)) => (l, true),
            (Some(_), Some(l)) => {
                return Err(at(
                    "a study has either [grid] (every combination) or [list] (the i-th value of each parameter), not both".into(),
                    Some(l.span()),
                ))
            }
            (None, None) => {
                return Err(at(
                    "no parameters: the study needs a [grid] or a [list] table".into(),
                    None,
                )
                .hint(STUDY_HINT))
            }
        };
        let table_span = table.span();
        let mut entries: Vec<(String, Spanned<toml::Value>)> =
            table.into_inner().into_iter().collect();
        if entries.is_empty() {
            return Err(
                at("the parameter table is empty".into(), Some(table_span)).hint(STUDY_HINT)
            );
        }
        // TOML tables come back sorted by name; the study's own order (the order of the
        // lines) is the natural one for the grid's loops and the database's columns.
        entries.sort_by_key(|(_, v)| v.span().start);
        let mut params = Vec::new();
        let mut param_spans = Vec::new();
        let mut columns: Vec<Vec<ParamValue>> = Vec::new();
        // A value that is not an array fixes the parameter for every point.
        let mut fixed: Vec<bool> = Vec::new();
        for (name, value) in &entries {
            if !is_identifier(name) {
                return Err(at(
                    format!("parameter '{name}' is not a Python name"),
                    Some(value.span()),
                )
                .hint("a parameter is a variable of the template: letters, digits, _"));
            }
            let vals = match value.get_ref() {
                toml::Value::Array(items) => items
                    .iter()
                    .map(ParamValue::from_toml)
                    .collect::<std::result::Result<Vec<_>, _>>(),
                // A single value fixes the parameter for every point.
                scalar => ParamValue::from_toml(scalar).map(|v| vec![v]),
            }
            .map_err(|m| at(format!("{name}: {m}"), Some(value.span())))?;
            if vals.is_empty() {
                return Err(at(
                    format!("{name}: an empty list of values"),
                    Some(value.span()),
                ));
            }
            params.push(name.clone());
            param_spans.push(value.span());
            fixed.push(!matches!(value.get_ref(), toml::Value::Array(_)));
            columns.push(vals);
        }

        let points = if zipped {
            let first = fixed.iter().position(|f| !f).unwrap_or(0);
            let n = columns[first].len();
            if let Some(i) = (0..columns.len()).find(|&i| !fixed[i] && columns[i].len() != n) {
                return Err(at(
                    format!(
                        "[list]: {} has {} value(s) but {} has {n}: the i-th point takes the i-th value of every parameter",
                        params[i],
                        columns[i].len(),
                        params[first]
                    ),
                    Some(param_spans[i].clone()),
                )
                .hint("give every parameter as many values, or use [grid] for every combination"));
            }
            (0..n)
                .map(|i| Point {
                    values: columns
                        .iter()
                        .zip(&fixed)
                        .map(|(c, &f)| c[if f { 0 } else { i }].clone())
                        .collect(),
                })
                .collect()
        } else {
            let total = columns
                .iter()
                .try_fold(1usize, |acc, c| acc.checked_mul(c.len()))
                .filter(|&t| t <= MAX_POINTS)
                .ok_or_else(|| {
                    at(
                        format!("[grid]: more than {MAX_POINTS} combinations"),
                        Some(table_span.clone()),
                    )
                })?;
            grid_points(&columns, total)
        };
        for (i, p) in points.iter().enumerate() {
            if let Some(j) = points[..i].iter().position(|q| q == p) {
                return Err(at(
                    format!(
                        "points {} and {} are the same ({}): each point runs once",
                        j + 1,
                        i + 1,
                        describe(&params, p)
                    ),
                    Some(table_span.clone()),
                ));
            }
        }

        let scheduler = match raw.run.scheduler.as_ref() {
            None => Scheduler::Local,
            Some(s) => match s.get_ref().as_str() {
                "local" => Scheduler::Local,
                "slurm" => Scheduler::Slurm,
                other => {
                    return Err(at(
                        format!("run.scheduler: '{other}', expected 'local' or 'slurm'"),
                        Some(s.span()),
                    ))
                }
            },
        };
        let jobs = match raw.run.jobs {
            None => None,
            Some(j) if *j.get_ref() >= 1 => Some(*j.get_ref() as usize),
            Some(j) => {
                return Err(at(
                    format!("run.jobs: {}, expected at least 1", j.get_ref()),
                    Some(j.span()),
                ))
            }
        };
        let timeout = match raw.run.timeout {
            None => None,
            Some(t) if *t.get_ref() > 0.0 && t.get_ref().is_finite() => Some(*t.get_ref()),
            Some(t) => {
                return Err(at(
                    format!(
                        "run.timeout: {}, expected a positive number of seconds",
                        t.get_ref()
                    ),
                    Some(t.span()),
                ))
            }
        };
        let positive = |v: &Option<Spanned<i64>>, key: &str| -> Result<Option<i64>> {
            match v {
                None => Ok(None),
                Some(x) if *x.get_ref() >= 1 => Ok(Some(*x.get_ref())),
                Some(x) => Err(at(
                    format!("slurm.{key}: {}, expected at least 1", x.get_ref()),
                    Some(x.span()),
                )),
            }
        };
        let slurm = SlurmSettings {
            partition: raw.slurm.partition,
            time: raw.slurm.time,
            max_running: positive(&raw.slurm.max_running, "max_running")?
                .map(|n| u32::try_from(n).unwrap_or(u32::MAX)),
            array_chunk: positive(&raw.slurm.array_chunk, "array_chunk")?
                .map_or(DEFAULT_ARRAY_CHUNK, |n| n as usize),
            sbatch_args: raw.slurm.sbatch_args,
            exe: raw.slurm.exe.map(|e| resolve(&e)),
        };
        if let Some(c) = &raw.plot.colour {
            if !params.iter().any(|p| p == c.get_ref()) {
                return Err(at(
                    format!(
                        "plot.colour: '{}' is not a parameter of the study ({})",
                        c.get_ref(),
                        params.join(", ")
                    ),
                    Some(c.span()),
                ));
            }
        }
        let plot = PlotSettings {
            table: raw.plot.table,
            colour: raw.plot.colour.map(|c| c.into_inner()),
        };
        Ok(Study {
            path: path.to_path_buf(),
            template,
            out,
            units,
            params,
            param_spans,
            points,
            scheduler,
            jobs,
            timeout,
            slurm,
            plot,
            source,
        })
    }

    /// An error pointing at parameter `i`'s values in the study file.
    pub fn param_error(&self, i: usize, msg: String) -> Error {
        let idx = LineIndex::new(&self.source.text);
        let r = self.param_spans.get(i).cloned().unwrap_or(0..0);
        Error::input(msg).at(&self.source.name, idx.span(r.start, r.end))
    }
}

const STUDY_HINT: &str = "a study file has `template = \"case.comm\"` and a [grid] or [list] of \
parameter values, e.g. [grid] JEU = [0.005, 0.01] (docs/sweeps.md)";

/// Every combination, the first parameter varying slowest (nested loops in file order).
fn grid_points(columns: &[Vec<ParamValue>], total: usize) -> Vec<Point> {
    let mut points = Vec::with_capacity(total);
    for mut k in 0..total {
        let mut values = vec![ParamValue::Int(0); columns.len()];
        for (j, c) in columns.iter().enumerate().rev() {
            values[j] = c[k % c.len()].clone();
            k /= c.len();
        }
        points.push(Point { values });
    }
    points
}

/// `JEU=0.01, RIGI_NOR=50.0`
pub fn describe(params: &[String], p: &Point) -> String {
    params
        .iter()
        .zip(&p.values)
        .map(|(n, v)| format!("{n}={}", v.display()))
        .collect::<Vec<_>>()
        .join(", ")
}

fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}
