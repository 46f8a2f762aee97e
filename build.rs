//! Embeds every operator catalog `commands/*.toml` in the binary: writes
//! `$OUT_DIR/catalog_files.rs`, a sorted list of `(file name, include_str!(...))`, and
//! beside it `JSON`, each file's content converted to JSON here (or `None` where the
//! conversion failed: the run then parses the TOML and reports its error). The TOML files
//! stay the only source; the JSON spares a run the TOML parser, several times slower than
//! serde_json on the same data (src/catalog/mod.rs reads it).

use std::fmt::Write as _;
use std::fs;
use std::path::Path;

fn main() {
    println!("cargo:rerun-if-changed=commands");
    // The manifest directory of this build, read when the script runs (not `env!`, fixed
    // when the script was compiled: a target directory copied from another checkout would
    // then embed that checkout's catalogs).
    let manifest = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
    let dir = Path::new(&manifest).join("commands");
    let mut files: Vec<_> = fs::read_dir(&dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    let mut out = String::from("pub static FILES: &[(&str, &str)] = &[\n");
    let mut json = String::from("pub static JSON: &[Option<&str>] = &[\n");
    for p in &files {
        let name = p
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        out.push_str(&format!(
            "    ({name:?}, include_str!({:?})),\n",
            p.display().to_string()
        ));
        let converted = fs::read_to_string(p).ok().and_then(|t| to_json(&t));
        match converted {
            Some(j) => json.push_str(&format!("    Some({j:?}),\n")),
            None => json.push_str("    None,\n"),
        }
    }
    out.push_str("];\n");
    json.push_str("];\n");
    out.push_str(&json);
    let out_dir = std::env::var("OUT_DIR").unwrap_or_else(|_| ".".into());
    if let Err(e) = fs::write(Path::new(&out_dir).join("catalog_files.rs"), out) {
        panic!("cannot write the catalog list: {e}");
    }
}

/// The TOML document as JSON, `None` if it does not parse or holds a value JSON cannot
/// say exactly (a date, an infinite or NaN float).
fn to_json(text: &str) -> Option<String> {
    let table: toml::Table = text.parse().ok()?;
    let mut s = String::with_capacity(text.len());
    write_value(&toml::Value::Table(table), &mut s)?;
    Some(s)
}

fn write_value(v: &toml::Value, s: &mut String) -> Option<()> {
    match v {
        toml::Value::String(t) => write_str(t, s),
        toml::Value::Integer(i) => write!(s, "{i}").ok()?,
        // `{:?}` is the shortest text that reads back to the same f64, always with a dot
        // or an exponent, so serde_json reads it as a float as TOML did.
        toml::Value::Float(f) if f.is_finite() => write!(s, "{f:?}").ok()?,
        toml::Value::Float(_) | toml::Value::Datetime(_) => return None,
        toml::Value::Boolean(b) => s.push_str(if *b { "true" } else { "false" }),
        toml::Value::Array(a) => {
            s.push('[');
            for (i, x) in a.iter().enumerate() {
                if i > 0 {
                    s.push(',');
                }
                write_value(x, s)?;
            }
            s.push(']');
        }
        toml::Value::Table(t) => {
            s.push('{');
            for (i, (k, x)) in t.iter().enumerate() {
                if i > 0 {
                    s.push(',');
                }
                write_str(k, s);
                s.push(':');
                write_value(x, s)?;
            }
            s.push('}');
        }
    }
    Some(())
}

fn write_str(t: &str, s: &mut String) {
    s.push('"');
    for c in t.chars() {
        match c {
            '"' => s.push_str("\\\""),
            '\\' => s.push_str("\\\\"),
            '\n' => s.push_str("\\n"),
            '\r' => s.push_str("\\r"),
            '\t' => s.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(s, "\\u{:04x}", c as u32);
            }
            c => s.push(c),
        }
    }
    s.push('"');
}
