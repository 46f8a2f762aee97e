//! Persistence of table concepts (`table_sdaster`, `table_container`).
//!
//! Every table concept `T` is a real SQL table named exactly `T` (identifier quoted), one
//! column per parameter typed REAL / INTEGER / TEXT, rows in the table's order (SQLite's
//! rowid, kept by inserting in order). Metadata, keyed by concept:
//! - `table_meta(concept, title)`,
//! - `table_columns(concept, position, name, kind)` (kind `R`, `I`, `K`),
//! - `table_links(concept, row, column, target)`: the cells that name another concept
//!   (sub-tables, mode shapes...), `row` 0-based.
//!
//! Per-row objects a table owns (a sub-table per mode, say) are concepts named
//! [`sub_concept_name`] (`PARENT.COLUMN.0001`): deleting the table deletes them. Create the
//! table's own concept before them (a reassigned name first drops the old owned objects).
//!
//! Naming rule (docs/store.md): SQL names are case-insensitive, so a table concept may not
//! be named like one of our internal tables ([`INTERNAL_TABLES`], any case) nor like any
//! other non-table SQL object of the file, nor start with `sqlite_`: such names are
//! refused with a clear error.

use super::{Schema, Store};
use crate::error::{Error, Result};
use crate::table::{Cell, ColKind, Column, Table};
use rusqlite::{params, types::Value as SqlValue};
use std::collections::HashMap;

/// Internal tables of the store (present or future): no table concept may take these names.
pub const INTERNAL_TABLES: &[&str] = &[
    "meta",
    "concepts",
    "concept_data",
    "concept_generations",
    "concept_deps",
    "table_meta",
    "table_columns",
    "table_links",
    "mesh_nodes",
    "mesh_cells",
    "mesh_groups",
    "dof_numbering",
    "matrix_entries",
    "modes",
    "mode_shapes",
    "mnl_points",
    "mnl_fourier",
    "mnl_floquet",
    "mnl_basis",
    "gene_entries",
    "field_values",
    "meshes",
    "mesh_group_defs",
];

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS table_meta (
    concept TEXT PRIMARY KEY REFERENCES concepts(name) ON DELETE CASCADE,
    title TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS table_columns (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    position INTEGER NOT NULL,
    name TEXT NOT NULL,
    kind TEXT NOT NULL CHECK (kind IN ('R', 'I', 'K')),
    PRIMARY KEY (concept, position)
);
CREATE TABLE IF NOT EXISTS table_links (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    row INTEGER NOT NULL,
    \"column\" TEXT NOT NULL,
    target TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS table_links_concept ON table_links(concept);
";

fn ensure_schema(store: &Store) -> Result<()> {
    store.ensure_schema(Schema::Table, SCHEMA)
}

/// `"name"` with inner quotes doubled: any concept or parameter name is a safe identifier.
pub fn quote_ident(name: &str) -> String {
    format!("\"{}\"", name.replace('"', "\"\""))
}

fn is_table_concept(store: &Store, name: &str) -> Result<bool> {
    Ok(store
        .row(
            "SELECT 1 FROM table_meta WHERE concept = ?1",
            params![name],
            |_| Ok(()),
        )?
        .is_some())
}

/// Refuse a concept name whose SQL table would clash with an internal table.
pub fn check_table_name(store: &Store, name: &str) -> Result<()> {
    let lower = name.to_ascii_lowercase();
    let clash = |why: String| {
        Error::store(format!(
            "a table cannot be named {name}: {why} (SQL names ignore case)"
        ))
        .hint(format!("choose another name for the result, e.g. T_{name}"))
    };
    if name.is_empty() {
        return Err(Error::store("a table concept needs a name"));
    }
    if lower.starts_with("sqlite_") {
        return Err(clash("names starting with sqlite_ belong to SQLite".into()));
    }
    if let Some(t) = INTERNAL_TABLES.iter().find(|t| **t == lower) {
        return Err(clash(format!("the store keeps its own table '{t}'")));
    }
    ensure_schema(store)?;
    let other: Option<String> = store.row(
        "SELECT name FROM sqlite_master WHERE name = ?1 COLLATE NOCASE",
        params![name],
        |r| r.get(0),
    )?;
    if let Some(o) = other {
        // The only SQL object a table concept may meet is its own earlier version.
        let own = o == name && is_table_concept(store, name)?;
        if !own {
            return Err(clash(format!(
                "the database already holds an SQL object '{o}'"
            )));
        }
    }
    Ok(())
}

fn sql_type(kind: ColKind) -> &'static str {
    match kind {
        ColKind::R => "REAL",
        ColKind::I => "INTEGER",
        ColKind::K => "TEXT",
    }
}

/// A cell as SQLite binds it (borrowed: the text is not copied).
fn sql_value(c: &Cell) -> rusqlite::types::ToSqlOutput<'_> {
    use rusqlite::types::{ToSqlOutput, ValueRef};
    ToSqlOutput::Borrowed(match c {
        Cell::Null => ValueRef::Null,
        Cell::R(r) => ValueRef::Real(*r),
        Cell::I(v) => ValueRef::Integer(*v),
        Cell::K(s) => ValueRef::Text(s.as_bytes()),
    })
}

/// The name under which the rowid stays reachable (a column may shadow `rowid`).
fn rowid_alias(columns: &[Column]) -> Result<&'static str> {
    ["rowid", "_rowid_", "oid"]
        .into_iter()
        .find(|a| !columns.iter().any(|c| c.name.eq_ignore_ascii_case(a)))
        .ok_or_else(|| {
            Error::store("a table cannot have parameters named ROWID, _ROWID_ and OID at once")
        })
}

/// Save `t` as the table concept `concept` (already registered in `concepts`), replacing
/// what was stored under that name. Text cells that name an existing concept are recorded
/// in `table_links`.
pub fn save_table(store: &Store, concept: &str, t: &Table) -> Result<()> {
    check_table_name(store, concept)?;
    if store.concept_type(concept)?.is_none() {
        return Err(Error::internal(format!(
            "table {concept} saved before its concept was registered"
        )));
    }
    for (i, c) in t.columns.iter().enumerate() {
        if t.columns[..i]
            .iter()
            .any(|d| d.name.eq_ignore_ascii_case(&c.name))
        {
            return Err(Error::store(format!(
                "table {concept} has two parameters named {} (SQL column names ignore case)",
                c.name
            ))
            .hint("rename one of them (CALC_TABLE OPERATION='RENOMME')"));
        }
    }
    rowid_alias(&t.columns)?;
    // Saving again (CALC_TABLE reuse) keeps the owned per-row objects the new rows still
    // name and deletes the others.
    let old_owned: Vec<String> = if is_table_concept(store, concept)? {
        links(store, concept)?
            .into_iter()
            .map(|l| l.target)
            .filter(|tg| is_owned(concept, tg))
            .collect()
    } else {
        Vec::new()
    };
    drop_sql(store, concept)?;
    let conn = store.conn();
    let table = quote_ident(concept);
    let cols: Vec<String> = t
        .columns
        .iter()
        .map(|c| format!("{} {}", quote_ident(&c.name), sql_type(c.kind)))
        .collect();
    conn.execute_batch(&format!("CREATE TABLE {table} ({})", cols.join(", ")))?;
    store.exec(
        "INSERT INTO table_meta(concept, title) VALUES (?1, ?2)",
        params![concept, t.title],
    )?;
    for (pos, c) in t.columns.iter().enumerate() {
        store.exec(
            "INSERT INTO table_columns(concept, position, name, kind) VALUES (?1, ?2, ?3, ?4)",
            params![concept, pos as i64, c.name, c.kind.name()],
        )?;
    }
    if !t.columns.is_empty() {
        let names: Vec<String> = t.columns.iter().map(|c| quote_ident(&c.name)).collect();
        let marks: Vec<String> = (1..=t.columns.len()).map(|i| format!("?{i}")).collect();
        let mut ins = conn.prepare(&format!(
            "INSERT INTO {table} ({}) VALUES ({})",
            names.join(", "),
            marks.join(", ")
        ))?;
        let mut link = conn.prepare_cached(
            "INSERT INTO table_links(concept, row, \"column\", target) VALUES (?1, ?2, ?3, ?4)",
        )?;
        // Whether a text names a concept, asked once per distinct text: a time history
        // repeats the same node and component names on every row, and no concept is
        // created or removed while the rows are written.
        let mut names_concept: HashMap<&str, bool> = HashMap::new();
        for (i, row) in t.rows.iter().enumerate() {
            ins.execute(rusqlite::params_from_iter(row.iter().map(sql_value)))?;
            for (c, col) in row.iter().zip(&t.columns) {
                if let Cell::K(s) = c {
                    if s == concept {
                        continue;
                    }
                    let is_concept = match names_concept.get(s.as_str()) {
                        Some(&known) => known,
                        None => {
                            let known = store.concept_type(s)?.is_some();
                            names_concept.insert(s, known);
                            known
                        }
                    };
                    if is_concept {
                        link.execute(params![concept, i as i64, col.name, s])?;
                    }
                }
            }
        }
    } else if !t.rows.is_empty() {
        return Err(Error::internal(format!(
            "table {concept} has rows but no column"
        )));
    }
    let kept: std::collections::HashSet<String> = links(store, concept)?
        .into_iter()
        .map(|l| l.target)
        .collect();
    for tg in old_owned {
        if !kept.contains(&tg) && store.concept_type(&tg)?.is_some() {
            store.delete_concept(&tg)?;
        }
    }
    Ok(())
}

/// Load the table concept `concept`.
pub fn load_table(store: &Store, concept: &str) -> Result<Table> {
    ensure_schema(store)?;
    let conn = store.conn();
    let title: Option<String> = store.row(
        "SELECT title FROM table_meta WHERE concept = ?1",
        params![concept],
        |r| r.get(0),
    )?;
    let title = title
        .ok_or_else(|| Error::store(format!("{concept} is not a table stored in this database")))?;
    let mut stmt = conn.prepare_cached(
        "SELECT name, kind FROM table_columns WHERE concept = ?1 ORDER BY position",
    )?;
    let raw: Vec<(String, String)> = stmt
        .query_map(params![concept], |r| Ok((r.get(0)?, r.get(1)?)))?
        .collect::<rusqlite::Result<_>>()?;
    let columns = raw
        .into_iter()
        .map(|(name, kind)| {
            let kind = ColKind::parse(&kind).ok_or_else(|| {
                Error::store(format!(
                    "table {concept}: parameter {name} has unknown kind '{kind}'"
                ))
            })?;
            Ok(Column { name, kind })
        })
        .collect::<Result<Vec<_>>>()?;
    let mut t = Table::new(title);
    t.columns = columns;
    if t.columns.is_empty() {
        return Ok(t);
    }
    let names: Vec<String> = t.columns.iter().map(|c| quote_ident(&c.name)).collect();
    let mut q = conn.prepare(&format!(
        "SELECT {} FROM {} ORDER BY {}",
        names.join(", "),
        quote_ident(concept),
        rowid_alias(&t.columns)?
    ))?;
    let kinds: Vec<ColKind> = t.columns.iter().map(|c| c.kind).collect();
    let mut rows = q.query([])?;
    while let Some(r) = rows.next()? {
        let mut row = Vec::with_capacity(kinds.len());
        for (j, k) in kinds.iter().enumerate() {
            let v: SqlValue = r.get(j)?;
            let cell = match (v, k) {
                (SqlValue::Null, _) => Cell::Null,
                (SqlValue::Real(x), ColKind::R) => Cell::R(x),
                // SQLite may hand back a REAL column's integral value as an integer.
                (SqlValue::Integer(x), ColKind::R) => Cell::R(x as f64),
                (SqlValue::Integer(x), ColKind::I) => Cell::I(x),
                (SqlValue::Text(s), ColKind::K) => Cell::K(s),
                (other, _) => {
                    return Err(Error::store(format!(
                        "table {concept}: parameter {} holds {:?}, not a {} value",
                        t.columns.get(j).map(|c| c.name.as_str()).unwrap_or("?"),
                        other,
                        k.name()
                    )))
                }
            };
            row.push(cell);
        }
        t.rows.push(row);
    }
    Ok(t)
}

/// A cell of a table naming another concept.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Link {
    pub row: usize,
    pub column: String,
    pub target: String,
}

/// The cells of `concept` that name other concepts, in row order.
pub fn links(store: &Store, concept: &str) -> Result<Vec<Link>> {
    ensure_schema(store)?;
    let mut stmt = store.conn().prepare_cached(
        "SELECT row, \"column\", target FROM table_links WHERE concept = ?1 ORDER BY row, rowid",
    )?;
    let v = stmt
        .query_map(params![concept], |r| {
            Ok(Link {
                row: r.get::<_, i64>(0)?.max(0) as usize,
                column: r.get(1)?,
                target: r.get(2)?,
            })
        })?
        .collect::<rusqlite::Result<Vec<_>>>()?;
    Ok(v)
}

/// Name of the per-row object a table owns: `PARENT.COLUMN.0001` for row 1 (rows count
/// from 1 like NUME_ORDRE). A dot cannot appear in a Python name, so these never clash
/// with the user's concepts; the owning table's deletion deletes them.
pub fn sub_concept_name(parent: &str, column: &str, row: usize) -> String {
    format!("{parent}.{column}.{:04}", row + 1)
}

/// Whether `target` is a per-row object owned by the table `parent`.
fn is_owned(parent: &str, target: &str) -> bool {
    target
        .strip_prefix(parent)
        .is_some_and(|rest| rest.starts_with('.'))
}

/// Remove the SQL table and metadata of `concept` if it is a table concept (called by
/// `Store::drop_typed_data`), and the per-row objects it owns ([`sub_concept_name`]).
/// Does nothing for other concepts.
pub fn drop_table_data(store: &Store, concept: &str) -> Result<()> {
    ensure_schema(store)?;
    if !is_table_concept(store, concept)? {
        return Ok(());
    }
    for l in links(store, concept)? {
        if is_owned(concept, &l.target) && store.concept_type(&l.target)?.is_some() {
            store.delete_concept(&l.target)?;
        }
    }
    drop_sql(store, concept)
}

/// The SQL table and metadata of a table concept, without its owned objects.
fn drop_sql(store: &Store, concept: &str) -> Result<()> {
    let conn = store.conn();
    conn.execute_batch(&format!("DROP TABLE IF EXISTS {}", quote_ident(concept)))?;
    for sql in [
        "DELETE FROM table_meta WHERE concept = ?1",
        "DELETE FROM table_columns WHERE concept = ?1",
        "DELETE FROM table_links WHERE concept = ?1",
    ] {
        store.exec(sql, params![concept])?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::tests::sample;

    fn store_with(names: &[&str]) -> Store {
        let s = Store::in_memory().unwrap();
        for n in names {
            s.register_concept(n, "table_sdaster", "CREA_TABLE", "t.comm", 1)
                .unwrap();
        }
        s
    }

    #[test]
    fn round_trip_and_plain_sql() {
        let s = store_with(&["M1", "TAB"]);
        let mut t = sample();
        t.rows[1][1] = Cell::R(1.0e-300);
        save_table(&s, "TAB", &t).unwrap();
        assert_eq!(load_table(&s, "TAB").unwrap(), t);
        // The table is queryable with plain SQL, in row order.
        let mut q = s
            .conn()
            .prepare("SELECT NUME_ORDRE, FREQ FROM TAB")
            .unwrap();
        let got: Vec<(i64, f64)> = q
            .query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
            .unwrap()
            .collect::<rusqlite::Result<_>>()
            .unwrap();
        assert_eq!(got, vec![(1, 12.5), (2, 1.0e-300), (3, 25.0)]);
        // M1 is a concept: its cell is a link; M2 is not one.
        assert_eq!(
            links(&s, "TAB").unwrap(),
            vec![Link {
                row: 0,
                column: "NOM_SD".into(),
                target: "M1".into()
            }]
        );
    }

    #[test]
    fn saving_again_replaces_and_delete_drops() {
        let s = store_with(&["TAB"]);
        save_table(&s, "TAB", &sample()).unwrap();
        let small = sample().extract(&["FREQ".into()]).unwrap();
        save_table(&s, "TAB", &small).unwrap();
        assert_eq!(load_table(&s, "TAB").unwrap(), small);
        s.delete_concept("TAB").unwrap();
        let n: i64 = s
            .conn()
            .query_row(
                "SELECT count(*) FROM sqlite_master WHERE name='TAB'",
                [],
                |r| r.get(0),
            )
            .unwrap();
        assert_eq!(n, 0);
        let n: i64 = s
            .conn()
            .query_row("SELECT count(*) FROM table_columns", [], |r| r.get(0))
            .unwrap();
        assert_eq!(n, 0);
    }

    #[test]
    fn owned_sub_tables_go_with_their_table() {
        let s = store_with(&["MNL", "OTHER"]);
        let sub = sub_concept_name("MNL", "COEF_MODE", 0);
        assert_eq!(sub, "MNL.COEF_MODE.0001");
        s.register_concept(&sub, "table_sdaster", "MODE_NON_LINE", "t.comm", 1)
            .unwrap();
        save_table(&s, &sub, &sample()).unwrap();
        save_table(&s, "OTHER", &sample()).unwrap();
        let mut t = Table::new("");
        t.add_column("NUME_ORDRE", ColKind::I).unwrap();
        t.add_column("COEF_MODE", ColKind::K).unwrap();
        t.add_column("VOISIN", ColKind::K).unwrap();
        t.push_row(vec![
            Cell::I(1),
            Cell::K(sub.clone()),
            Cell::K("OTHER".into()),
        ])
        .unwrap();
        save_table(&s, "MNL", &t).unwrap();
        // The sub-table is a real SQL table too, queryable by its quoted name.
        let n: i64 = s
            .conn()
            .query_row("SELECT count(*) FROM \"MNL.COEF_MODE.0001\"", [], |r| {
                r.get(0)
            })
            .unwrap();
        assert_eq!(n, 3);
        // Saving MNL again (CALC_TABLE reuse) keeps the objects its rows still name...
        save_table(&s, "MNL", &t).unwrap();
        assert!(s.concept_type(&sub).unwrap().is_some());
        // ...and deleting MNL deletes them.
        s.delete_concept("MNL").unwrap();
        assert!(s.concept_type(&sub).unwrap().is_none());
        // OTHER is referred to, not owned: it stays.
        assert_eq!(load_table(&s, "OTHER").unwrap(), sample());
        // Saving a version of MNL whose rows no longer name the object deletes it.
        s.register_concept("MNL", "table_container", "MODE_NON_LINE", "t.comm", 2)
            .unwrap();
        s.register_concept(&sub, "table_sdaster", "MODE_NON_LINE", "t.comm", 2)
            .unwrap();
        save_table(&s, &sub, &sample()).unwrap();
        save_table(&s, "MNL", &t).unwrap();
        let mut emptied = t.clone();
        emptied.rows.clear();
        save_table(&s, "MNL", &emptied).unwrap();
        assert!(s.concept_type(&sub).unwrap().is_none());
    }

    #[test]
    fn internal_names_are_refused() {
        let s = store_with(&["CONCEPTS", "Modes", "sqlite_x"]);
        for n in ["CONCEPTS", "Modes", "sqlite_x"] {
            let err = save_table(&s, n, &sample()).unwrap_err();
            assert!(err.message.contains("cannot be named"), "{err}");
        }
    }

    use proptest::prelude::*;

    fn cell(kind: ColKind) -> BoxedStrategy<Cell> {
        let value = match kind {
            ColKind::R => any::<f64>()
                .prop_filter("SQLite stores NaN as NULL", |x| !x.is_nan())
                .prop_map(Cell::R)
                .boxed(),
            ColKind::I => any::<i64>().prop_map(Cell::I).boxed(),
            // Texts that look like numbers must stay texts.
            ColKind::K => prop_oneof![
                "[A-Za-z0-9_ .+-]{0,12}",
                Just("12".to_string()),
                Just("1.5E3".to_string())
            ]
            .prop_map(Cell::K)
            .boxed(),
        };
        prop_oneof![1 => Just(Cell::Null), 4 => value].boxed()
    }

    fn any_table() -> impl Strategy<Value = Table> {
        let kinds = prop::collection::vec(
            prop_oneof![Just(ColKind::R), Just(ColKind::I), Just(ColKind::K)],
            1..5,
        );
        (kinds, 0usize..8).prop_flat_map(|(kinds, n)| {
            let row: Vec<BoxedStrategy<Cell>> = kinds.iter().map(|&k| cell(k)).collect();
            prop::collection::vec(row, n).prop_map(move |rows| {
                let mut t = Table::new("random");
                for (j, k) in kinds.iter().enumerate() {
                    t.add_column(&format!("P{j}"), *k).unwrap();
                }
                for r in rows {
                    t.push_row(r).unwrap();
                }
                t
            })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Any table comes back from SQL exactly, cell types and row order included.
        #[test]
        fn any_table_round_trips(t in any_table()) {
            let s = store_with(&["T"]);
            save_table(&s, "T", &t).unwrap();
            prop_assert_eq!(load_table(&s, "T").unwrap(), t);
        }
    }

    #[test]
    fn odd_names_are_quoted() {
        let s = store_with(&["A\"B"]);
        let mut t = Table::new("");
        t.add_column("select", ColKind::K).unwrap();
        t.add_column("ROWID", ColKind::I).unwrap();
        t.push_row(vec![Cell::K("x".into()), Cell::I(7)]).unwrap();
        t.push_row(vec![Cell::Null, Cell::I(-1)]).unwrap();
        save_table(&s, "A\"B", &t).unwrap();
        assert_eq!(load_table(&s, "A\"B").unwrap(), t);
    }
}
