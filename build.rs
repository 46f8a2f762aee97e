//! Embeds every operator catalog `commands/*.toml` in the binary: writes
//! `$OUT_DIR/catalog_files.rs`, a sorted list of `(file name, include_str!(...))`.

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
    for p in &files {
        let name = p
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        out.push_str(&format!(
            "    ({name:?}, include_str!({:?})),\n",
            p.display().to_string()
        ));
    }
    out.push_str("];\n");
    let out_dir = std::env::var("OUT_DIR").unwrap_or_else(|_| ".".into());
    if let Err(e) = fs::write(Path::new(&out_dir).join("catalog_files.rs"), out) {
        panic!("cannot write the catalog list: {e}");
    }
}
