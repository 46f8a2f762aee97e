//! The rooms of the engine keep their one-way doors, a contact law is named only where it is
//! registered or read from the user, and docs/nnm.md lists the files as they are. All three
//! read the sources, so none can drift from them.
//!
//! A room is a folder of `src/nnm/` (`model`, `solve`, `continuation`, `analysis`, lowest
//! first); `follow.rs` and `mod.rs` stand above them all. A file may use its own room and
//! the rooms below it, never one above: a path `crate::nnm::ROOM::…`, an item of a group
//! `crate::nnm::{ROOM::…, Name}`, or a name `mod.rs` re-exports from a room. Test code (the
//! `tests` folder, `*_tests.rs` and `tests.rs` files, a file's `#[cfg(test)] mod tests`) may
//! reach anywhere.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const ROOMS: [&str; 4] = ["model", "solve", "continuation", "analysis"];

fn nnm_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src/nnm")
}

fn rank(room: &str) -> Option<usize> {
    ROOMS.iter().position(|r| *r == room)
}

/// Every `.rs` file under `dir`, sorted, as paths relative to `base`.
fn sources(dir: &Path, base: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            sources(&p, base, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p.strip_prefix(base).unwrap().to_path_buf());
        }
    }
}

/// Test code: a `tests` folder (the engine's, an operator's), `*_tests.rs`, `tests.rs`.
fn is_test_file(rel: &Path) -> bool {
    let name = rel.file_name().unwrap().to_string_lossy();
    rel.components().any(|c| c.as_os_str() == "tests")
        || name.ends_with("_tests.rs")
        || name == "tests.rs"
}

/// The production part of a file: what precedes its inline test module.
fn production(text: &str) -> &str {
    match text.find("#[cfg(test)]\nmod tests") {
        Some(i) => &text[..i],
        None => text,
    }
}

/// The room of each name `mod.rs` re-exports from a room (`pub use ROOM::…`).
fn reexports(mod_rs: &str) -> BTreeMap<String, String> {
    let mut names = BTreeMap::new();
    for statement in mod_rs.split(';') {
        let s = statement.trim();
        let Some(path) = s
            .strip_prefix("pub use ")
            .or_else(|| s.strip_prefix("pub(crate) use "))
        else {
            continue;
        };
        let room = path.split("::").next().unwrap_or("");
        if rank(room).is_none() {
            continue;
        }
        let tail = path.rsplit("::").next().unwrap_or("");
        let tail = tail.trim_start_matches('{').trim_end_matches('}');
        let list = match path.find('{') {
            Some(i) => &path[i + 1..path.len() - 1],
            None => tail,
        };
        for item in list.split(',') {
            let name = item.split(" as ").last().unwrap_or("").trim();
            if !name.is_empty() {
                names.insert(name.to_string(), room.to_string());
            }
        }
    }
    names
}

/// The first path segment of every use of `crate::nnm::` in `text`, groups flattened one
/// level (`crate::nnm::{model::law, Point}` gives `model` and `Point`).
fn heads(text: &str) -> Vec<String> {
    let key = "crate::nnm::";
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find(key) {
        rest = &rest[i + key.len()..];
        if let Some(body) = rest.strip_prefix('{') {
            let mut depth = 1;
            let mut end = 0;
            for (k, c) in body.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    _ => {}
                }
                if depth == 0 {
                    end = k;
                    break;
                }
            }
            let mut item = String::new();
            let mut depth = 0;
            for c in body[..end].chars().chain(std::iter::once(',')) {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        out.push(segment(&item));
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                item.push(c);
            }
        } else {
            out.push(segment(rest));
        }
    }
    out.retain(|s| !s.is_empty());
    out
}

fn segment(path: &str) -> String {
    path.trim()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// The room of a use's first segment: a room itself, or a name re-exported from one.
fn room_of(head: &str, names: &BTreeMap<String, String>) -> Option<String> {
    match rank(head) {
        Some(_) => Some(head.to_string()),
        None => names.get(head).cloned(),
    }
}

/// Each production file of a room, with the rooms above its own that it uses.
fn upward_doors() -> Vec<(PathBuf, Vec<String>)> {
    let dir = nnm_dir();
    let names = reexports(&std::fs::read_to_string(dir.join("mod.rs")).unwrap());
    let mut files = Vec::new();
    sources(&dir, &dir, &mut files);
    let mut found = Vec::new();
    for rel in files {
        let Some(own) = rel
            .components()
            .next()
            .and_then(|c| rank(&c.as_os_str().to_string_lossy()))
        else {
            continue;
        };
        if is_test_file(&rel) {
            continue;
        }
        let text = std::fs::read_to_string(dir.join(&rel)).unwrap();
        let mut above: Vec<String> = heads(production(&text))
            .iter()
            .filter_map(|h| room_of(h, &names).map(|r| (h.clone(), r)))
            .filter(|(_, r)| rank(r).unwrap() > own)
            .map(|(h, r)| format!("{h} ({r})"))
            .collect();
        above.sort();
        above.dedup();
        if !above.is_empty() {
            found.push((rel, above));
        }
    }
    found
}

#[test]
fn a_room_uses_only_itself_and_the_rooms_below() {
    let doors = upward_doors();
    assert!(
        doors.is_empty(),
        "files that use a room above their own (docs/nnm.md, 'Rooms'): {doors:?}"
    );
}

/// The check itself can fail: a use of a room above, in a group or by a re-exported name,
/// is found; a test module's is not.
#[test]
fn the_door_check_sees_groups_and_reexported_names() {
    let names = reexports(
        "pub use analysis::post::{PostProcessor, RowOutputs};\npub use model::point::Point;\n\
         pub use follow::{continue_branches};",
    );
    assert_eq!(
        names.get("PostProcessor").map(String::as_str),
        Some("analysis")
    );
    assert_eq!(names.get("Point").map(String::as_str), Some("model"));
    assert!(!names.contains_key("continue_branches"));
    let text = "use crate::nnm::{model::law, solve::contact::{self, Method}, PostProcessor};\n\
                fn f() { crate::nnm::analysis::orbit::time_history(); }\n\
                #[cfg(test)]\nmod tests { use crate::nnm::continuation::start; }";
    let heads = heads(production(text));
    assert_eq!(heads, ["model", "solve", "PostProcessor", "analysis"]);
    let rooms: Vec<_> = heads.iter().filter_map(|h| room_of(h, &names)).collect();
    assert_eq!(rooms, ["model", "solve", "analysis", "analysis"]);
}

/// The first sentence of a file's `//!` header.
fn summary(text: &str) -> String {
    let mut header = String::new();
    for line in text.lines() {
        let Some(l) = line.strip_prefix("//!") else {
            break;
        };
        let l = l.trim();
        if l.is_empty() {
            break;
        }
        if !header.is_empty() {
            header.push(' ');
        }
        header.push_str(l);
    }
    // A sentence ends at a period followed by a capital ("eq. (12)" does not end one).
    let end = header
        .match_indices(". ")
        .map(|(i, _)| i + 1)
        .find(|&i| header[i + 1..].starts_with(|c: char| c.is_uppercase()))
        .unwrap_or(header.len());
    header[..end].replace('|', "\\|")
}

const TABLE_START: &str =
    "<!-- files: generated by `UPDATE_DOCS=1 cargo test doors`; do not edit -->";
const TABLE_END: &str = "<!-- end of files -->";

/// The file table of docs/nnm.md: each room's files with the first sentence of their header.
fn file_table() -> String {
    let dir = nnm_dir();
    let mut files = Vec::new();
    sources(&dir, &dir, &mut files);
    let mut table = format!("{TABLE_START}\n| room | file | what it holds |\n|---|---|---|\n");
    for rel in files {
        let text = std::fs::read_to_string(dir.join(&rel)).unwrap();
        let room = match rel.components().count() {
            1 => "(front)".to_string(),
            _ => rel
                .components()
                .next()
                .unwrap()
                .as_os_str()
                .to_string_lossy()
                .into_owned(),
        };
        table.push_str(&format!(
            "| {room} | `{}` | {} |\n",
            rel.display(),
            summary(&text)
        ));
    }
    table.push_str(TABLE_END);
    table
}

#[test]
fn docs_nnm_lists_every_file_as_it_is() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/nnm.md");
    let doc = std::fs::read_to_string(&path).unwrap();
    let (Some(start), Some(end)) = (doc.find(TABLE_START), doc.find(TABLE_END)) else {
        panic!("docs/nnm.md has no generated file table ({TABLE_START} … {TABLE_END})");
    };
    let current = &doc[start..end + TABLE_END.len()];
    let table = file_table();
    if current != table && std::env::var_os("UPDATE_DOCS").is_some() {
        let updated = format!("{}{table}{}", &doc[..start], &doc[end + TABLE_END.len()..]);
        std::fs::write(&path, updated).unwrap();
        return;
    }
    assert!(
        current == table,
        "docs/nnm.md's file table is out of date: regenerate it with `UPDATE_DOCS=1 cargo test doors`"
    );
}

/// The production files that may name a contact law's variant: its registration, the
/// reading of CHOC, and the few places that list laws as such (the bench's route timing,
/// the ring's advice, the accuracy study's cases). Everything else asks the law
/// (model/law/), so a new law stays in its own file and its registration.
const NAMES_LAWS: [&str; 5] = [
    "nnm/model/law/mod.rs",
    "ops/mode_non_line/problem.rs",
    "nnm/analysis/route_timing.rs",
    "nnm/analysis/below_contact.rs",
    "accuracy/cases.rs",
];

#[test]
fn only_the_registration_and_the_readers_name_a_contact_law() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &src, &mut files);
    let naming: Vec<String> = files
        .iter()
        .filter(|rel| !is_test_file(rel))
        .filter(|rel| {
            let text = std::fs::read_to_string(src.join(rel)).unwrap();
            let prod = production(&text);
            [
                "ShockLaw::Plan",
                "ShockLaw::BiPlan",
                "ShockLaw::Cercle",
                "ShockLaw::RessortCubique",
                "ShockLaw::RESSORT_CUBIQUE",
            ]
            .iter()
            .any(|v| prod.contains(v))
        })
        .map(|rel| rel.to_string_lossy().into_owned())
        .collect();
    let mut allowed: Vec<String> = NAMES_LAWS.iter().map(|s| s.to_string()).collect();
    allowed.sort();
    let mut naming_sorted = naming.clone();
    naming_sorted.sort();
    assert_eq!(
        naming_sorted, allowed,
        "production files that name a contact law's variant (ask the law instead, model/law/)"
    );
}
