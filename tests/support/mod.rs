//! What the tests that run the binary on `.comm` files share: where the testcases are, and
//! one run with its exit code and output. Each test file takes what it uses.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// `testcases/<name>` of the repository.
pub fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("testcases")
        .join(name)
}

/// `aster-nl run comm --db db`: (exit code, output).
pub fn run_file(comm: &Path, db: &Path) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
        .arg("run")
        .arg(comm)
        .arg("--db")
        .arg(db)
        .output()
        .unwrap();
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (o.status.code(), out)
}
