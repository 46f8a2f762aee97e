//! Merging the runs of a sweep into one SQLite database.
//!
//! Every table of every run is present once in the merged file, with the rows of all runs
//! one after the other (each run's rows in their own order), and in front of the run's
//! columns:
//!
//! - `SWEEP_POINT`: the point the row comes from (its directory name);
//! - one column per sweep parameter, holding the point's value (`SWEEP_<NAME>` where the
//!   table already has a column of that name, as `MNL_CHOC` has `JEU`).
//!
//! `SWEEP_POINTS` lists every point (values, `STATUS` ok / nook / failed / missing,
//! `ERROR`, `SECONDS`, `DB`); `SWEEP_META` holds the parameter names. The tables of a
//! failed run are not merged (a failed run may hold the concepts created before its error,
//! which `SWEEP_POINTS.DB` still names). The run databases are only read (opened
//! read-only); the merged file is built beside its destination and renamed into place, so
//! an interrupted merge leaves the previous one, and only a merged database is ever
//! replaced.

use super::layout::{self, Outcome};
use super::value::ParamValue;
use crate::error::{Error, ErrorKind, Result};
use rusqlite::{params_from_iter, Connection, OpenFlags};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

pub const POINTS_TABLE: &str = "SWEEP_POINTS";
pub const META_TABLE: &str = "SWEEP_META";
pub const POINT_COLUMN: &str = "SWEEP_POINT";

/// One run to merge.
#[derive(Clone, Debug)]
pub struct RunInput {
    /// The point's name (its directory, or the database's path for a run of no sweep).
    pub point: String,
    /// Its value of each parameter of the merge (`None`: the run has no such parameter).
    pub values: Vec<Option<ParamValue>>,
    /// `None`: the point has not run (missing).
    pub outcome: Option<Outcome>,
    pub error: String,
    pub seconds: Option<f64>,
    /// Its database, if one exists.
    pub db: Option<PathBuf>,
}

/// What a merge did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MergeReport {
    /// Runs whose tables were merged.
    pub runs: usize,
    /// Tables in the merged file (besides SWEEP_POINTS and SWEEP_META).
    pub tables: usize,
    /// Rows copied.
    pub rows: u64,
}

/// A table of the merged file.
struct Target {
    /// As first seen (SQL names ignore case: the key of the map is lower case).
    name: String,
    /// Its columns from the runs, lower case, to see new ones.
    columns: Vec<String>,
    /// The name of each parameter's column in this table.
    param_columns: Vec<String>,
}

/// Merge `runs` (parameters `params`) into the database `out`.
pub fn merge(out: &Path, params: &[String], runs: &[RunInput]) -> Result<MergeReport> {
    check_destination(out, runs)?;
    let tmp = layout::temp_sibling(out);
    // Our temporary: made exclusively (never through a link, never over a file that is
    // there), removed only while the path still names it.
    let made = crate::store::own_file::create_new(&tmp).map_err(|e| {
        io(format!(
            "cannot create {}, where the merged database is built: {e}",
            tmp.display()
        ))
        .hint("remove that file if an interrupted merge left it, or merge to another file")
    })?;
    let r = build(&tmp, out, params, runs);
    match r {
        Ok(report) => {
            std::fs::rename(&tmp, out).map_err(|e| {
                crate::store::own_file::remove_if_ours(&made, &tmp);
                io(format!("cannot write {}: {e}", out.display()))
            })?;
            Ok(report)
        }
        Err(e) => {
            crate::store::own_file::remove_if_ours(&made, &tmp);
            Err(e)
        }
    }
}

/// Only a merged database (one with SWEEP_POINTS) is replaced, and never by a merge that
/// reads it.
fn check_destination(out: &Path, runs: &[RunInput]) -> Result<()> {
    if !out.exists() {
        return Ok(());
    }
    let same = |a: &Path| match (a.canonicalize(), out.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    };
    if runs.iter().filter_map(|r| r.db.as_deref()).any(same) {
        return Err(io(format!(
            "{} is both the merged database and one of the runs",
            out.display()
        )));
    }
    let ours = Connection::open_with_flags(out, OpenFlags::SQLITE_OPEN_READ_ONLY)
        .ok()
        .and_then(|c| {
            c.query_row(
                "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?1",
                [POINTS_TABLE],
                |r| r.get::<_, i64>(0),
            )
            .ok()
        })
        .is_some_and(|n| n == 1);
    if !ours {
        return Err(io(format!(
            "{} exists and is not a merged database (no {POINTS_TABLE} table): it is left alone",
            out.display()
        ))
        .hint("name another file for the merged database"));
    }
    Ok(())
}

/// Build the merged file at `path` (a temporary, renamed to `out` when complete).
fn build(path: &Path, out: &Path, params: &[String], runs: &[RunInput]) -> Result<MergeReport> {
    let conn = Connection::open_with_flags(
        path,
        OpenFlags::SQLITE_OPEN_READ_WRITE
            | OpenFlags::SQLITE_OPEN_CREATE
            | OpenFlags::SQLITE_OPEN_URI
            | OpenFlags::SQLITE_OPEN_NO_MUTEX,
    )
    .map_err(|e| writing(out, out, e))?;
    // A file under construction, renamed into place only when complete: no journal needed.
    conn.execute_batch("PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF;")
        .map_err(|e| writing(out, out, e))?;

    let types = param_types(params.len(), runs);
    let mut cols = vec![format!("{} TEXT", q(POINT_COLUMN))];
    for (p, t) in params.iter().zip(&types) {
        cols.push(format!("{} {t}", q(p)));
    }
    for c in ["STATUS TEXT", "ERROR TEXT", "SECONDS REAL", "DB TEXT"] {
        cols.push(c.to_string());
    }
    conn.execute_batch(&format!(
        "CREATE TABLE {} ({});
         CREATE TABLE {} (key TEXT PRIMARY KEY, value TEXT);",
        q(POINTS_TABLE),
        cols.join(", "),
        q(META_TABLE)
    ))
    .map_err(|e| writing(out, out, e))?;
    let names = serde_json::to_string(params).map_err(|e| Error::internal(e.to_string()))?;
    conn.execute(
        &format!("INSERT INTO {} VALUES ('params', ?1)", q(META_TABLE)),
        [names],
    )
    .map_err(|e| writing(out, out, e))?;

    let mut targets: HashMap<String, Target> = HashMap::new();
    let mut report = MergeReport::default();
    for run in runs {
        let mut row: Vec<rusqlite::types::Value> = vec![run.point.clone().into()];
        row.extend(run.values.iter().map(|v| {
            v.as_ref()
                .map_or(rusqlite::types::Value::Null, ParamValue::sql)
        }));
        row.push(
            run.outcome
                .map_or("missing", Outcome::name)
                .to_string()
                .into(),
        );
        row.push(run.error.clone().into());
        row.push(run.seconds.map_or(rusqlite::types::Value::Null, Into::into));
        row.push(run.db.as_ref().map_or(rusqlite::types::Value::Null, |d| {
            d.display().to_string().into()
        }));
        let marks = vec!["?"; row.len()].join(", ");
        conn.execute(
            &format!("INSERT INTO {} VALUES ({marks})", q(POINTS_TABLE)),
            params_from_iter(row),
        )
        .map_err(|e| writing(out, out, e))?;
        let Some(db) = &run.db else { continue };
        if matches!(run.outcome, Some(Outcome::Failed) | None) {
            continue;
        }
        report.rows += copy_run(&conn, db, out, params, &types, run, &mut targets)?;
        report.runs += 1;
    }
    report.tables = targets.len();
    Ok(report)
}

/// Copy every table of one run into the merged file, in one transaction.
fn copy_run(
    conn: &Connection,
    db: &Path,
    out: &Path,
    params: &[String],
    types: &[&str],
    run: &RunInput,
    targets: &mut HashMap<String, Target>,
) -> Result<u64> {
    if !db.is_file() {
        return Err(io(format!("{}: no such database", db.display())));
    }
    conn.execute("ATTACH DATABASE ?1 AS run", [read_only_uri(db)])
        .map_err(|e| sql(db, e))?;
    let r = copy_attached(conn, db, out, params, types, run, targets);
    let detach = conn.execute_batch("DETACH DATABASE run");
    let n = r?;
    detach.map_err(|e| sql(db, e))?;
    Ok(n)
}

fn copy_attached(
    conn: &Connection,
    db: &Path,
    out: &Path,
    params: &[String],
    types: &[&str],
    run: &RunInput,
    targets: &mut HashMap<String, Target>,
) -> Result<u64> {
    let tables: Vec<(String, String)> = {
        let mut stmt = conn
            .prepare(
                "SELECT name, coalesce(sql, '') FROM run.sqlite_master \
                 WHERE type = 'table' AND name NOT LIKE 'sqlite\\_%' ESCAPE '\\' ORDER BY rowid",
            )
            .map_err(|e| sql(db, e))?;
        let rows = stmt
            .query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
            .map_err(|e| sql(db, e))?;
        rows.collect::<rusqlite::Result<_>>()
            .map_err(|e| sql(db, e))?
    };
    if tables
        .iter()
        .any(|(t, _)| t.eq_ignore_ascii_case(POINTS_TABLE))
    {
        return Err(io(format!(
            "{} is itself a merged database: merge the runs it came from",
            db.display()
        )));
    }
    conn.execute_batch("BEGIN").map_err(|e| sql(db, e))?;
    let r = (|| -> Result<u64> {
        let mut rows = 0u64;
        for (table, create_sql) in &tables {
            if create_sql
                .trim_start()
                .to_ascii_uppercase()
                .starts_with("CREATE VIRTUAL")
            {
                continue;
            }
            let columns = table_columns(conn, db, table)?;
            let target = ensure_target(conn, db, params, types, table, &columns, targets)?;
            let mut names: Vec<String> = vec![q(POINT_COLUMN)];
            names.extend(target.param_columns.iter().map(|c| q(c)));
            names.extend(columns.iter().map(|(c, _)| q(c)));
            let marks: Vec<String> = (1..=params.len() + 1).map(|i| format!("?{i}")).collect();
            let source_cols: Vec<String> = columns.iter().map(|(c, _)| q(c)).collect();
            let order = if create_sql.to_ascii_uppercase().contains("WITHOUT ROWID") {
                ""
            } else {
                " ORDER BY rowid"
            };
            let insert = format!(
                "INSERT INTO main.{} ({}) SELECT {}{}{} FROM run.{}{order}",
                q(&target.name),
                names.join(", "),
                marks.join(", "),
                if source_cols.is_empty() { "" } else { ", " },
                source_cols.join(", "),
                q(table),
            );
            let mut binds: Vec<rusqlite::types::Value> = vec![run.point.clone().into()];
            binds.extend(run.values.iter().map(|v| {
                v.as_ref()
                    .map_or(rusqlite::types::Value::Null, ParamValue::sql)
            }));
            rows += conn
                .execute(&insert, params_from_iter(binds))
                .map_err(|e| writing(db, out, e))? as u64;
        }
        Ok(rows)
    })();
    match r {
        Ok(n) => {
            conn.execute_batch("COMMIT")
                .map_err(|e| writing(db, out, e))?;
            Ok(n)
        }
        Err(e) => {
            let _ = conn.execute_batch("ROLLBACK");
            Err(e)
        }
    }
}

/// (name, declared type) of a table of the attached run.
fn table_columns(conn: &Connection, db: &Path, table: &str) -> Result<Vec<(String, String)>> {
    let mut stmt = conn
        .prepare(&format!("PRAGMA run.table_info({})", q(table)))
        .map_err(|e| sql(db, e))?;
    let rows = stmt
        .query_map([], |r| Ok((r.get::<_, String>(1)?, r.get::<_, String>(2)?)))
        .map_err(|e| sql(db, e))?;
    rows.collect::<rusqlite::Result<_>>()
        .map_err(|e| sql(db, e))
}

/// The merged table for `table`: created at its first run, widened by columns later runs
/// bring.
fn ensure_target<'a>(
    conn: &Connection,
    db: &Path,
    params: &[String],
    types: &[&str],
    table: &str,
    columns: &[(String, String)],
    targets: &'a mut HashMap<String, Target>,
) -> Result<&'a Target> {
    let key = table.to_ascii_lowercase();
    if !targets.contains_key(&key) {
        let has = |name: &str| columns.iter().any(|(c, _)| c.eq_ignore_ascii_case(name));
        if has(POINT_COLUMN) {
            return Err(io(format!(
                "{}: table {table} has a column {POINT_COLUMN}, the name the merge gives the point",
                db.display()
            )));
        }
        let param_columns: Vec<String> = params
            .iter()
            .map(|p| {
                if has(p) || p.eq_ignore_ascii_case(POINT_COLUMN) {
                    format!("SWEEP_{p}")
                } else {
                    p.clone()
                }
            })
            .collect();
        if let Some(p) = param_columns.iter().find(|p| has(p)) {
            return Err(io(format!(
                "{}: table {table} has a column {p}, the name the merge gives a parameter",
                db.display()
            )));
        }
        let mut defs = vec![format!("{} TEXT", q(POINT_COLUMN))];
        defs.extend(
            param_columns
                .iter()
                .zip(types)
                .map(|(c, t)| format!("{} {t}", q(c))),
        );
        defs.extend(columns.iter().map(|(c, t)| format!("{} {t}", q(c))));
        conn.execute_batch(&format!(
            "CREATE TABLE main.{} ({})",
            q(table),
            defs.join(", ")
        ))
        .map_err(|e| sql(db, e))?;
        targets.insert(
            key.clone(),
            Target {
                name: table.to_string(),
                columns: columns
                    .iter()
                    .map(|(c, _)| c.to_ascii_lowercase())
                    .collect(),
                param_columns,
            },
        );
    } else if let Some(t) = targets.get_mut(&key) {
        for (c, ty) in columns {
            let lc = c.to_ascii_lowercase();
            if t.columns.contains(&lc) {
                continue;
            }
            if lc == POINT_COLUMN.to_ascii_lowercase()
                || t.param_columns.iter().any(|p| p.eq_ignore_ascii_case(c))
            {
                return Err(io(format!(
                    "{}: table {table} has a column {c}, which the merged table uses for the sweep",
                    db.display()
                )));
            }
            conn.execute_batch(&format!(
                "ALTER TABLE main.{} ADD COLUMN {} {ty}",
                q(&t.name),
                q(c)
            ))
            .map_err(|e| sql(db, e))?;
            t.columns.push(lc);
        }
    }
    targets
        .get(&key)
        .ok_or_else(|| Error::internal(format!("merge: table {table} was not created")))
}

/// The SQL type of each parameter column: INTEGER when every value is an integer (or a
/// boolean), REAL when numbers mix, TEXT otherwise.
fn param_types(n: usize, runs: &[RunInput]) -> Vec<&'static str> {
    (0..n)
        .map(|i| {
            let vals = runs
                .iter()
                .filter_map(|r| r.values.get(i).and_then(Option::as_ref));
            let mut ty = "INTEGER";
            for v in vals {
                ty = match (ty, v) {
                    (_, ParamValue::Text(_) | ParamValue::Tuple(_)) => return "TEXT",
                    ("INTEGER", ParamValue::Real(_)) => "REAL",
                    (t, _) => t,
                };
            }
            ty
        })
        .collect()
}

/// `file:` URI opening `db` read-only (`?`, `#` and `%` escaped).
fn read_only_uri(db: &Path) -> String {
    let abs = std::path::absolute(db).unwrap_or_else(|_| db.to_path_buf());
    let mut s = String::from("file:");
    for c in abs.to_string_lossy().chars() {
        match c {
            '%' => s.push_str("%25"),
            '?' => s.push_str("%3f"),
            '#' => s.push_str("%23"),
            c => s.push(c),
        }
    }
    s.push_str("?mode=ro");
    s
}

/// A quoted SQL identifier.
fn q(name: &str) -> String {
    format!("\"{}\"", name.replace('"', "\"\""))
}

fn sql(db: &Path, e: rusqlite::Error) -> Error {
    Error::new(ErrorKind::Store, format!("{}: {e}", db.display()))
}

/// An SQLite error of a statement that writes the merged file (reading run `db`, or `out`
/// itself): a full disk or a failed write is the merged database `out`'s, and named so.
fn writing(db: &Path, out: &Path, e: rusqlite::Error) -> Error {
    let write_failed = matches!(&e, rusqlite::Error::SqliteFailure(f, _)
        if matches!(f.code, rusqlite::ErrorCode::DiskFull | rusqlite::ErrorCode::SystemIoFailure));
    if write_failed {
        Error::new(
            ErrorKind::Io,
            format!("cannot write the merged database {}: {e}", out.display()),
        )
        .hint("free space on its disk, or merge to a file on another disk")
    } else {
        sql(db, e)
    }
}

fn io(msg: String) -> Error {
    Error::new(ErrorKind::Io, msg)
}
