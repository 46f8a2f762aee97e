//! Many rows into one table, a few hundred per INSERT statement.
//!
//! Why: a model of 10⁵ DOFs writes over a million matrix entries and as many mode-shape
//! values; one `INSERT ... VALUES (?, ?, ?, ?)` per row spent most of ASSEMBLAGE's time in
//! SQLite's per-statement work (bind, step, reset), not in the B-tree. A multi-row VALUES
//! list pays that once per [`ROWS_PER_STATEMENT`] rows. The rows and their order are the
//! same as row by row.

use crate::error::Result;
use rusqlite::types::{ToSqlOutput, ValueRef};
use rusqlite::{params_from_iter, Connection};

/// Rows per INSERT: large enough that the per-statement work is negligible, small enough
/// that a statement's parameters (rows × columns) stay far below SQLite's limit of 32 766.
pub const ROWS_PER_STATEMENT: usize = 256;

/// `INSERT INTO table(columns) VALUES (...), (...)` with `rows` placeholder groups.
fn insert_sql(table: &str, columns: &[&str], rows: usize) -> String {
    let group = format!("({})", vec!["?"; columns.len()].join(", "));
    format!(
        "INSERT INTO {table}({}) VALUES {}",
        columns.join(", "),
        vec![group; rows].join(", ")
    )
}

/// Inserts every row of `rows` (one value per column of `columns`) into `table`.
pub fn insert_rows<'a, const C: usize>(
    conn: &Connection,
    table: &str,
    columns: [&str; C],
    rows: impl IntoIterator<Item = [ValueRef<'a>; C]>,
) -> Result<()> {
    let full = insert_sql(table, &columns, ROWS_PER_STATEMENT);
    let mut values: Vec<ValueRef<'a>> = Vec::with_capacity(ROWS_PER_STATEMENT * C);
    for row in rows {
        values.extend_from_slice(&row);
        if values.len() == ROWS_PER_STATEMENT * C {
            conn.prepare_cached(&full)?.execute(params_from_iter(
                values.iter().map(|v| ToSqlOutput::Borrowed(*v)),
            ))?;
            values.clear();
        }
    }
    if !values.is_empty() {
        // The tail has its own length: prepared once, not kept in the statement cache.
        conn.prepare(&insert_sql(table, &columns, values.len() / C))?
            .execute(params_from_iter(
                values.iter().map(|v| ToSqlOutput::Borrowed(*v)),
            ))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_land_in_order_across_full_statements_and_the_tail() {
        let conn = Connection::open_in_memory().unwrap();
        conn.execute_batch("CREATE TABLE t(name TEXT, i INTEGER, x REAL)")
            .unwrap();
        // Two full statements and a tail of 3 rows.
        let n = 2 * ROWS_PER_STATEMENT + 3;
        insert_rows(
            &conn,
            "t",
            ["name", "i", "x"],
            (0..n).map(|i| {
                [
                    ValueRef::Text(b"K"),
                    ValueRef::Integer(i as i64),
                    ValueRef::Real(0.5 * i as f64),
                ]
            }),
        )
        .unwrap();
        let rows: Vec<(String, i64, f64)> = conn
            .prepare("SELECT name, i, x FROM t ORDER BY rowid")
            .unwrap()
            .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
            .unwrap()
            .collect::<std::result::Result<_, _>>()
            .unwrap();
        assert_eq!(rows.len(), n);
        for (i, r) in rows.iter().enumerate() {
            assert_eq!(r, &("K".to_string(), i as i64, 0.5 * i as f64));
        }
        // No rows: nothing written, no statement with an empty VALUES list.
        insert_rows::<3>(&conn, "t", ["name", "i", "x"], std::iter::empty()).unwrap();
    }
}
