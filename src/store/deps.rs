//! Generations and dependencies of concepts.
//!
//! Concepts refer to each other by name (a MODE_NON_LINE table names its K and M and
//! rebuilds the problem from them when it is used again). A name can be given to a new
//! concept at any time (`K = ASSEMBLAGE(...)` again, in the same file or after POURSUITE), so
//! a name alone does not say that the concept is still the one a result was computed from.
//!
//! - Every registration of a concept gets a new **generation** (a counter of the study,
//!   never reused): `concept_generations(name, generation)`. A concept changed in place
//!   (`reuse=`) gets a new one too.
//! - An operator whose result refers to another concept by name records it:
//!   `concept_deps(concept, depends_on, generation)`, with the generation `depends_on` had.
//! - Before an operator runs, the interpreter checks the dependencies of every concept given
//!   to it ([`Store::check_dependencies`]): a dependency that was reassigned, changed in
//!   place or destroyed since is an error naming both concepts.

use super::Store;
use crate::error::{Error, Result};
use rusqlite::params;

pub(super) const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS concept_generations (
    name TEXT PRIMARY KEY,
    generation INTEGER NOT NULL
);
CREATE TABLE IF NOT EXISTS concept_deps (
    concept TEXT NOT NULL,
    depends_on TEXT NOT NULL,
    generation INTEGER NOT NULL,
    PRIMARY KEY (concept, depends_on)
);
";

impl Store {
    /// Give `name` a new generation (a registration, or a change in place).
    pub fn new_generation(&self, name: &str) -> Result<i64> {
        let last: Option<String> = self.row(
            "SELECT value FROM meta WHERE key = 'last_generation'",
            [],
            |r| r.get(0),
        )?;
        let next = last.and_then(|v| v.parse::<i64>().ok()).unwrap_or(0) + 1;
        self.exec(
            "INSERT OR REPLACE INTO meta(key, value) VALUES ('last_generation', ?1)",
            params![next.to_string()],
        )?;
        self.exec(
            "INSERT OR REPLACE INTO concept_generations(name, generation) VALUES (?1, ?2)",
            params![name, next],
        )?;
        Ok(next)
    }

    /// The generation of `name`: `None` if there is no such concept, 0 for a concept
    /// written before generations were recorded.
    pub fn generation(&self, name: &str) -> Result<Option<i64>> {
        if self.concept_type(name)?.is_none() {
            return Ok(None);
        }
        let g: Option<i64> = self.row(
            "SELECT generation FROM concept_generations WHERE name = ?1",
            params![name],
            |r| r.get(0),
        )?;
        Ok(Some(g.unwrap_or(0)))
    }

    /// Record that `concept` refers to `depends_on` as it is now.
    pub fn record_dependency(&self, concept: &str, depends_on: &str) -> Result<()> {
        let g = self.generation(depends_on)?.ok_or_else(|| {
            Error::internal(format!(
                "{concept} depends on {depends_on}, which is not a concept"
            ))
        })?;
        self.exec(
            "INSERT OR REPLACE INTO concept_deps(concept, depends_on, generation) VALUES (?1, ?2, ?3)",
            params![concept, depends_on, g],
        )?;
        Ok(())
    }

    /// Give `to` the dependencies of `from` (a copy of a concept refers to what it did).
    pub fn copy_dependencies(&self, from: &str, to: &str) -> Result<()> {
        self.exec(
            "INSERT OR REPLACE INTO concept_deps(concept, depends_on, generation)
             SELECT ?2, depends_on, generation FROM concept_deps WHERE concept = ?1",
            params![from, to],
        )?;
        Ok(())
    }

    /// The recorded dependencies of `concept`: (depends_on, generation).
    pub fn dependencies(&self, concept: &str) -> Result<Vec<(String, i64)>> {
        let mut stmt = self.conn().prepare_cached(
            "SELECT depends_on, generation FROM concept_deps WHERE concept = ?1 ORDER BY rowid",
        )?;
        let rows = stmt.query_map(params![concept], |r| Ok((r.get(0)?, r.get(1)?)))?;
        Ok(rows.collect::<rusqlite::Result<Vec<_>>>()?)
    }

    /// Refuse to use `concept` if something it was computed from has changed since.
    pub fn check_dependencies(&self, concept: &str) -> Result<()> {
        for (on, recorded) in self.dependencies(concept)? {
            match self.generation(&on)? {
                Some(now) if now == recorded => {}
                Some(_) => {
                    let by = self
                        .concepts()?
                        .into_iter()
                        .find(|c| c.name == on)
                        .map(|c| format!(" (by {} at {}:{})", c.operator, c.file, c.line))
                        .unwrap_or_default();
                    return Err(Error::validation(format!(
                        "{concept} was computed from {on}, but {on} has been redefined since{by}: \
                         {concept} does not belong to the new {on}"
                    ))
                    .hint(format!(
                        "recompute {concept} from the new {on}, or keep the old {on} under another name"
                    )));
                }
                None => {
                    return Err(Error::validation(format!(
                        "{concept} was computed from {on}, which no longer exists (destroyed)"
                    ))
                    .hint(format!("recompute {concept}, or keep {on}")));
                }
            }
        }
        Ok(())
    }

    /// Forget what `name` records (its generation and its dependencies): it is deleted.
    pub(super) fn drop_dependency_data(&self, name: &str) -> Result<()> {
        self.exec("DELETE FROM concept_deps WHERE concept = ?1", params![name])?;
        self.exec(
            "DELETE FROM concept_generations WHERE name = ?1",
            params![name],
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reg(s: &Store, name: &str) {
        s.register_concept(name, "matr_asse_depl_r", "ASSEMBLAGE", "x.comm", 1)
            .unwrap();
    }

    #[test]
    fn a_reassigned_dependency_is_stale() {
        let s = Store::in_memory().unwrap();
        reg(&s, "K");
        s.register_concept("MNL", "table_container", "MODE_NON_LINE", "x.comm", 2)
            .unwrap();
        s.record_dependency("MNL", "K").unwrap();
        s.check_dependencies("MNL").unwrap();
        reg(&s, "K");
        let e = s.check_dependencies("MNL").unwrap_err();
        assert!(e.message.contains("MNL was computed from K"), "{e}");
        assert!(e.message.contains("redefined"), "{e}");
        s.delete_concept("K").unwrap();
        let e = s.check_dependencies("MNL").unwrap_err();
        assert!(e.message.contains("no longer exists"), "{e}");
    }

    #[test]
    fn generations_are_never_reused() {
        let s = Store::in_memory().unwrap();
        reg(&s, "K");
        let g1 = s.generation("K").unwrap().unwrap();
        s.delete_concept("K").unwrap();
        assert_eq!(s.generation("K").unwrap(), None);
        reg(&s, "K");
        assert!(s.generation("K").unwrap().unwrap() > g1);
    }
}
