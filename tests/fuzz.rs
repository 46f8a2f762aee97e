//! Fuzzing the `aster-nl` binary with mutated inputs (issue 11): every command file of
//! `testcases/` (and `testcases/hard/`) and every mesh of `testcases/meshes/` is mutated
//! (bytes, lines, numbers, keywords), then `check` and `run` are executed on the mutants in
//! a child process under a memory limit and a timeout. Whatever the input, the process must
//! end by itself with exit code 0, 1 or 2: no panic, no abort, no signal, no hang.
//!
//! In CI this runs a bounded number of mutants (a minute or two). A long campaign:
//!
//! ```sh
//! FUZZ_CHECKS=100000 FUZZ_RUNS=5000 FUZZ_MESHES=20000 FUZZ_SEED=7 \
//!   nice -n 19 cargo test --release --test fuzz -- --nocapture
//! ```
//!
//! Findings (the input, the command and its output) are written under
//! `target/fuzz-findings/`; the test fails if there is any.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Address-space limit of each child (bytes): far below the machine, far above any case.
const MEMORY_LIMIT_KB: u64 = 4 * 1024 * 1024;

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// A small deterministic generator (xorshift64*): reproducible from FUZZ_SEED.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}

/// Tokens a hostile but fair user might type.
const TOKENS: &[&str] = &[
    "0",
    "-1",
    "1e400",
    "-1e400",
    "nan",
    "1e-320",
    "9223372036854775807",
    "18446744073709551616",
    "100000",
    "1e9",
    "0.",
    "(",
    ")",
    "[",
    "]",
    "_F(",
    ",",
    "=",
    "'",
    "\"",
    "\\",
    "#",
    "\n",
    "\t",
    " ",
    "\u{feff}",
    "é",
    "CO('K2')",
    "reuse=",
    "DEBUT()",
    "POURSUITE()",
    "FIN()",
    "None",
    "for i in range(3):",
    "    ",
    "from math import *",
    "**",
    "/0",
    "1/0.",
    "2**1000",
    "NB_HARM_NONL=",
    "NB_INST=",
    "NB_PAS_MAN=",
    "NB_BRANCHE=",
    "JEU=",
    "RIGI_NOR=",
    "UNITE=",
    "FICHIER='x.db'",
    "CHOC=_F(",
    "MATR_RIGI=",
    "TABLE=",
    "NUME_ORDRE=",
    "DETRUIRE(CONCEPT=_F(NOM=K))",
    "$Nodes",
    "$EndNodes",
    "$Elements",
    "COOR_3D",
    "FINSF",
    "FIN",
    "SEG2",
    "POI1",
    "GROUP_MA",
    "N1",
    "M1",
    "-0",
    "+",
    "-",
];

/// One mutation of `text`.
fn mutate(rng: &mut Rng, text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out: Vec<u8> = bytes.to_vec();
    let n_mut = 1 + rng.below(3);
    for _ in 0..n_mut {
        let len = out.len().max(1);
        match rng.below(9) {
            // Delete a range.
            0 => {
                let a = rng.below(len);
                let b = (a + 1 + rng.below(40)).min(out.len());
                if a < b {
                    out.drain(a..b);
                }
            }
            // Insert a token.
            1 | 2 => {
                let at = rng.below(len + 1).min(out.len());
                let tok = rng.pick(TOKENS);
                out.splice(at..at, tok.bytes());
            }
            // Replace a number by an extreme one.
            3 | 4 => {
                let starts: Vec<usize> = (0..out.len())
                    .filter(|&i| {
                        out[i].is_ascii_digit() && (i == 0 || !out[i - 1].is_ascii_alphanumeric())
                    })
                    .collect();
                if !starts.is_empty() {
                    let a = starts[rng.below(starts.len())];
                    let mut b = a;
                    while b < out.len() && (out[b].is_ascii_digit() || b".eE-+".contains(&out[b])) {
                        b += 1;
                    }
                    let tok = rng.pick(&[
                        "0",
                        "-1",
                        "1e400",
                        "nan",
                        "100000",
                        "1000000000",
                        "9223372036854775807",
                        "1e-300",
                        "2",
                        "3.5",
                        "-0.",
                        "1e6",
                    ]);
                    out.splice(a..b, tok.bytes());
                }
            }
            // Duplicate a line.
            5 => {
                let s = String::from_utf8_lossy(&out).into_owned();
                let lines: Vec<&str> = s.split('\n').collect();
                let i = rng.below(lines.len());
                let mut v: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
                v.insert(i, lines[i].to_string());
                out = v.join("\n").into_bytes();
            }
            // Delete a line.
            6 => {
                let s = String::from_utf8_lossy(&out).into_owned();
                let mut v: Vec<&str> = s.split('\n').collect();
                if v.len() > 1 {
                    v.remove(rng.below(v.len()));
                }
                out = v.join("\n").into_bytes();
            }
            // Flip a byte (printable).
            7 => {
                if !out.is_empty() {
                    let i = rng.below(out.len());
                    const PRINTABLE: &[u8] = b" !\"#$%&'()*+,-./0123456789:;<=>?@AZ[\\]^_az{|}~";
                    out[i] = PRINTABLE[rng.below(PRINTABLE.len())];
                }
            }
            // Truncate.
            _ => {
                let at = rng.below(len).min(out.len());
                out.truncate(at);
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// How one child ended.
enum Ending {
    Ok,
    Finding(String),
}

/// Run the binary with `args` in `dir` under the memory limit; `timeout` ends a hang.
fn run_child(dir: &Path, args: &[&str], timeout: Duration) -> Ending {
    let bin = env!("CARGO_BIN_EXE_aster-nl");
    let mut cmd = Command::new("sh");
    cmd.arg("-c")
        .arg(format!("ulimit -v {MEMORY_LIMIT_KB}; exec \"$0\" \"$@\""))
        .arg(bin)
        .args(args)
        .current_dir(dir)
        .env("RUST_BACKTRACE", "0")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let mut child = match cmd.spawn() {
        Ok(c) => c,
        Err(e) => return Ending::Finding(format!("cannot start: {e}")),
    };
    // Read stderr on a thread so that a chatty child never blocks on a full pipe.
    let mut stderr = child.stderr.take();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        if let Some(e) = stderr.as_mut() {
            let _ = e.read_to_string(&mut s);
        }
        s
    });
    let started = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(st)) => break Some(st),
            Ok(None) if started.elapsed() > timeout => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(_) => break None,
        }
    };
    let err = reader.join().unwrap_or_default();
    match status {
        None => Ending::Finding(format!("no end after {timeout:?} (hang)\n{err}")),
        Some(st) => match st.code() {
            Some(0..=2) if !err.contains("panicked") => Ending::Ok,
            Some(c) => Ending::Finding(format!("exit code {c}\n{err}")),
            None => Ending::Finding(format!("killed by a signal ({st:?})\n{err}")),
        },
    }
}

fn files(dir: &Path, ext: &[&str]) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    p.extension()
                        .and_then(|e| e.to_str())
                        .is_some_and(|e| ext.contains(&e))
                })
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

struct Campaign {
    findings_dir: PathBuf,
    findings: Vec<String>,
    counts: [usize; 3],
}

impl Campaign {
    /// A progress line every 1000 mutants (a long campaign can be read while it runs).
    fn progress(&self) {
        let total: usize = self.counts.iter().sum();
        if total.is_multiple_of(1000) {
            println!(
                "fuzz progress: {} check, {} run, {} mesh mutants; {} finding(s)",
                self.counts[0],
                self.counts[1],
                self.counts[2],
                self.findings.len()
            );
        }
    }

    fn record(&mut self, what: &str, input_name: &str, input: &str, ending: Ending) {
        if let Ending::Finding(why) = ending {
            let n = self.findings.len();
            let _ = std::fs::create_dir_all(&self.findings_dir);
            let base = self.findings_dir.join(format!("{n:04}-{input_name}"));
            let _ = std::fs::write(&base, input);
            let _ = std::fs::write(base.with_extension("why"), format!("{what}\n{why}"));
            self.findings.push(format!(
                "{what} on {}: {}",
                base.display(),
                why.lines().next().unwrap_or("")
            ));
        }
    }
}

#[test]
fn mutated_inputs_never_crash_or_hang() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let seed = env_usize("FUZZ_SEED", 11) as u64;
    let n_checks = env_usize("FUZZ_CHECKS", 600);
    let n_runs = env_usize("FUZZ_RUNS", 40);
    let n_meshes = env_usize("FUZZ_MESHES", 200);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ seed.wrapping_mul(0x1000_0000_01B3));
    let mut comms = files(&root.join("testcases"), &["comm"]);
    comms.extend(files(&root.join("testcases/hard"), &["comm"]));
    comms.extend(files(&root.join("testcases/errors"), &["comm"]));
    assert!(!comms.is_empty());
    let texts: Vec<(PathBuf, String)> = comms
        .iter()
        .map(|p| (p.clone(), std::fs::read_to_string(p).unwrap()))
        .collect();
    let work = tempfile::tempdir().unwrap();
    let mut c = Campaign {
        findings_dir: root.join("target/fuzz-findings"),
        findings: Vec::new(),
        counts: [0; 3],
    };

    // `check` on mutants of every command file, in turn.
    for i in 0..n_checks {
        let (path, text) = &texts[i % texts.len()];
        let mutant = mutate(&mut rng, text);
        let f = work.path().join("m.comm");
        std::fs::write(&f, &mutant).unwrap();
        let e = run_child(work.path(), &["check", "m.comm"], Duration::from_secs(30));
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        c.record("check", &name, &mutant, e);
        c.counts[0] += 1;
        c.progress();
    }

    // `run` on mutants, beside the case's mesh, with a database of its own. The cases that
    // take more than a second as they are stay out of the CI budget unless asked for.
    let quick: Vec<&(PathBuf, String)> = texts
        .iter()
        .filter(|(p, _)| {
            let n = p.file_name().unwrap().to_string_lossy();
            std::env::var_os("FUZZ_ALL_RUNS").is_some()
                || [
                    "chain_fixed_fixed",
                    "chain_free_free",
                    "beam_cantilever",
                    "tables_functions",
                    "poursuite_debut",
                    "sdnd122a",
                    "syntax",
                    "catalog",
                    "runtime",
                    "nook",
                ]
                .iter()
                .any(|q| n.starts_with(q))
        })
        .collect();
    for i in 0..n_runs {
        let (path, text) = quick[i % quick.len()];
        let mutant = mutate(&mut rng, text);
        let case_dir = work.path().join(format!("run{}", i % 4));
        let _ = std::fs::remove_dir_all(&case_dir);
        std::fs::create_dir_all(&case_dir).unwrap();
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        for ext in ["mail", "msh"] {
            let m = path.with_extension(ext);
            if m.exists() {
                std::fs::copy(&m, case_dir.join(format!("{stem}.{ext}"))).unwrap();
            }
        }
        let comm = format!("{stem}.comm");
        std::fs::write(case_dir.join(&comm), &mutant).unwrap();
        let e = run_child(&case_dir, &["run", &comm], Duration::from_secs(60));
        c.record("run", &comm, &mutant, e);
        c.counts[1] += 1;
        c.progress();
    }

    // Mutated meshes through LIRE_MAILLAGE.
    let meshes: Vec<(PathBuf, String)> = files(&root.join("testcases/meshes"), &["mail", "msh"])
        .into_iter()
        .chain(files(&root.join("testcases"), &["mail"]))
        .map(|p| {
            let t = std::fs::read_to_string(&p).unwrap();
            (p, t)
        })
        .collect();
    let mesh_dir = work.path().join("mesh");
    std::fs::create_dir_all(&mesh_dir).unwrap();
    for i in 0..n_meshes {
        let (path, text) = &meshes[i % meshes.len()];
        let mutant = mutate(&mut rng, text);
        let ext = path.extension().unwrap().to_string_lossy().into_owned();
        let format = if ext == "msh" { "GMSH" } else { "ASTER" };
        std::fs::write(mesh_dir.join(format!("m.{ext}")), &mutant).unwrap();
        std::fs::write(
            mesh_dir.join("m.comm"),
            format!("DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='{format}', UNITE=20)\nFIN()\n"),
        )
        .unwrap();
        let _ = std::fs::remove_file(mesh_dir.join("m.db"));
        let e = run_child(
            &mesh_dir,
            &["run", "m.comm", "--unit", &format!("20=m.{ext}")],
            Duration::from_secs(30),
        );
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        c.record("run (mesh)", &name, &mutant, e);
        c.counts[2] += 1;
        c.progress();
    }

    println!(
        "fuzz (seed {seed}): {} check, {} run, {} mesh mutants; {} finding(s)",
        c.counts[0],
        c.counts[1],
        c.counts[2],
        c.findings.len()
    );
    assert!(
        c.findings.is_empty(),
        "{} finding(s):\n{}",
        c.findings.len(),
        c.findings.join("\n")
    );
}

/// What one in-process input did: nothing wrong, or a panic / a hang with its message.
fn in_process<F: FnOnce() + Send + 'static>(work: F, timeout: Duration) -> Ending {
    let (done, wait) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
        let _ = done.send(outcome.map_err(|p| {
            p.downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "panic".to_string())
        }));
    });
    match wait.recv_timeout(timeout) {
        Ok(Ok(())) => Ending::Ok,
        Ok(Err(msg)) => Ending::Finding(format!("panicked: {msg}")),
        Err(_) => Ending::Finding(format!("no end after {timeout:?} (hang)")),
    }
}

/// The same mutants through the library, without a process per input: the parser, the
/// static checker and the rendering of every error it reports (what `aster-nl check`
/// does), and the ASTER and Gmsh mesh readers on mutated meshes. A process costs about a
/// tenth of a second, so this is how a campaign reaches 10⁵ inputs in minutes; aborts and
/// memory limits stay the business of the process campaign above.
///
/// ```sh
/// FUZZ_INPROC_CHECKS=100000 FUZZ_INPROC_MESHES=30000 FUZZ_SEED=7 \
///   nice -n 19 cargo test --release --test fuzz in_process -- --nocapture
/// ```
#[test]
fn mutated_inputs_never_panic_in_process() {
    use aster_nl::lang::{render_plain, Source};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let seed = env_usize("FUZZ_SEED", 11) as u64;
    let n_checks = env_usize("FUZZ_INPROC_CHECKS", 3000);
    let n_meshes = env_usize("FUZZ_INPROC_MESHES", 1000);
    let mut rng = Rng(0x2545_F491_4F6C_DD1D ^ seed.wrapping_mul(0x1000_0000_01B3));
    let mut comms = files(&root.join("testcases"), &["comm"]);
    comms.extend(files(&root.join("testcases/hard"), &["comm"]));
    comms.extend(files(&root.join("testcases/errors"), &["comm"]));
    let texts: Vec<(String, String)> = comms
        .iter()
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read_to_string(p).unwrap())
        })
        .collect();
    let meshes: Vec<(String, String)> = files(&root.join("testcases/meshes"), &["mail", "msh"])
        .into_iter()
        .chain(files(&root.join("testcases"), &["mail"]))
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read_to_string(&p).unwrap())
        })
        .collect();
    assert!(!texts.is_empty() && !meshes.is_empty());
    // A panic is caught and recorded; the default hook would print each one as it happens.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut c = Campaign {
        findings_dir: root.join("target/fuzz-findings/in-process"),
        findings: Vec::new(),
        counts: [0; 3],
    };
    let started = Instant::now();
    let mut n_errors = 0usize;
    let errors_seen = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
    for i in 0..n_checks {
        let (name, text) = &texts[i % texts.len()];
        let mutant = mutate(&mut rng, text);
        let src = Source {
            name: name.clone(),
            text: mutant.clone(),
        };
        let seen = errors_seen.clone();
        let e = in_process(
            move || {
                let errors =
                    aster_nl::interp::check_source(&src, aster_nl::interp::CheckOptions::default());
                for e in &errors {
                    // Rendering is where the column-65,536 panic lived (issue 11, item 5).
                    let shown = render_plain(e, Some(&src));
                    assert!(!shown.is_empty(), "an error renders as nothing");
                }
                seen.fetch_add(errors.len().min(1), std::sync::atomic::Ordering::Relaxed);
            },
            Duration::from_secs(30),
        );
        c.record("check (in process)", name, &mutant, e);
        c.counts[0] += 1;
        c.progress();
    }
    n_errors += errors_seen.load(std::sync::atomic::Ordering::Relaxed);
    for i in 0..n_meshes {
        let (name, text) = &meshes[i % meshes.len()];
        let mutant = mutate(&mut rng, text);
        let (m, file) = (mutant.clone(), name.clone());
        let e = in_process(
            move || {
                let _ = if file.ends_with(".msh") {
                    aster_nl::mesh::gmsh::parse(&m, &file)
                } else {
                    aster_nl::mesh::aster::parse(&m, &file)
                };
            },
            Duration::from_secs(30),
        );
        c.record("mesh (in process)", name, &mutant, e);
        c.counts[2] += 1;
        c.progress();
    }
    std::panic::set_hook(hook);
    println!(
        "fuzz in process (seed {seed}): {} check mutants ({} with errors reported), {} mesh mutants in {:.1} s; {} finding(s)",
        c.counts[0],
        n_errors,
        c.counts[2],
        started.elapsed().as_secs_f64(),
        c.findings.len()
    );
    // The mutations must exercise the error paths, not only files that stay valid.
    assert!(
        n_checks == 0 || n_errors * 4 >= n_checks,
        "{n_errors} of {n_checks} mutants gave an error"
    );
    assert!(
        c.findings.is_empty(),
        "{} finding(s):\n{}",
        c.findings.len(),
        c.findings.join("\n")
    );
}

#[test]
fn the_in_process_harness_reports_a_panic_and_a_hang() {
    assert!(matches!(
        in_process(|| (), Duration::from_secs(5)),
        Ending::Ok
    ));
    match in_process(|| panic!("on purpose"), Duration::from_secs(5)) {
        Ending::Finding(why) => assert!(why.contains("on purpose"), "{why}"),
        Ending::Ok => panic!("a panic was not seen"),
    }
    let hang = in_process(
        || std::thread::sleep(Duration::from_secs(3)),
        Duration::from_millis(100),
    );
    assert!(matches!(hang, Ending::Finding(ref w) if w.contains("hang")));
}

// ---- issue 35: the families the first campaign missed ----

/// A command file of one of the generated families: values that grow by doubling or by
/// nesting, very long names, huge list literals given to keywords. Each ends with operator
/// calls that use what it built, so that `check` and `run` carry the values into
/// validation, messages and the store.
fn generated(rng: &mut Rng) -> (String, &'static str) {
    let n = |rng: &mut Rng, top: usize| 1 + rng.below(top);
    let use_x =
        "T = CREA_TABLE(TITRE=x, LISTE=_F(PARA='X', LISTE_R=x))\nprint(x)\nIMPR_TABLE(TABLE=T)\n";
    match rng.below(9) {
        0 => (
            format!("DEBUT()\nx = (1.0,)\nfor i in range({}):\n    x = (x, x)\n{use_x}FIN()\n", n(rng, 64)),
            "growth: x = (x, x)",
        ),
        1 => (
            format!("DEBUT()\nx = [0.5]\nfor i in range({}):\n    x = x + x\ny = sum(x)\n{use_x}FIN()\n", n(rng, 64)),
            "growth: x = x + x",
        ),
        2 => (
            format!("DEBUT()\nx = [0]\nfor i in range({}):\n    x = [x]\n{use_x}FIN()\n", n(rng, 300_000)),
            "growth: x = [x]",
        ),
        3 => (
            format!(
                "DEBUT()\nx = 'ab'\nfor i in range({}):\n    x = x * {}\n    x = str((x, x))\n{use_x}FIN()\n",
                n(rng, 40),
                n(rng, 9)
            ),
            "growth: texts",
        ),
        4 => (
            format!("DEBUT()\nx = _F(A=1)\nfor i in range({}):\n    x = _F(A=x, B=x)\n{use_x}FIN()\n", n(rng, 300)),
            "growth: _F(A=x, B=x)",
        ),
        5 => (
            format!(
                "DEBUT()\nx = [1.0] * {}\nfor i in range({}):\n    n = len(x) + len(list(x))\n{use_x}FIN()\n",
                n(rng, 1_000_000),
                n(rng, 100_000)
            ),
            "growth: a long list read in a loop",
        ),
        6 => {
            // A very long undefined name beside a similar defined one.
            let len = n(rng, 100_000);
            let defined = "N".repeat(len);
            let typed = format!("{}M", "N".repeat(len.saturating_sub(1)));
            let op = if rng.below(2) == 0 { "CREA_TABLEE" } else { "X" };
            (
                format!("{defined} = 1\nx = {typed}\nT = {op}{}(LISTE=1)\n", "Q".repeat(len)),
                "long names",
            )
        }
        7 => {
            let kw = rng.pick(&[
                "MATR_ELEM", "NUME_DDL", "GROUP_NO", "NOEUD", "TITRE", "LISTE_R", "VALE", "CHOC",
                "TOUT", "INFO", "NB_INST",
            ]);
            let item = rng.pick(&["0.0", "'A'", "1", "_F(X=1)", "None", "(1, 2)"]);
            let op = rng.pick(&["ASSE_MATRICE", "DEFI_GROUP", "CREA_TABLE", "MODE_NON_LINE", "DEFI_FONCTION"]);
            (
                format!("DEBUT()\nA = {op}({kw}=[{item}]*10**{})\nFIN()\n", rng.below(8)),
                "huge list literals",
            )
        }
        _ => {
            // A literal list written out in the file.
            let items = n(rng, 200_000);
            let list = vec!["0.0"; items].join(", ");
            (
                format!("DEBUT()\nA = ASSE_MATRICE(MATR_ELEM=[{list}], NUME_DDL=({list}))\nFIN()\n"),
                "huge list literals (written out)",
            )
        }
    }
}

/// Byte mutations of a binary file (MED/HDF5): flips, overwritten ranges, truncations,
/// duplicated and deleted blocks.
fn mutate_bytes(rng: &mut Rng, bytes: &[u8]) -> Vec<u8> {
    let mut out = bytes.to_vec();
    for _ in 0..1 + rng.below(4) {
        let len = out.len().max(1);
        match rng.below(6) {
            0 | 1 => {
                let i = rng.below(len).min(out.len().saturating_sub(1));
                if let Some(b) = out.get_mut(i) {
                    *b ^= 1 << rng.below(8);
                }
            }
            2 => {
                let a = rng.below(len);
                for i in a..(a + 1 + rng.below(64)).min(out.len()) {
                    out[i] = rng.next() as u8;
                }
            }
            3 => out.truncate(rng.below(len)),
            4 => {
                let a = rng.below(len).min(out.len());
                let b = (a + rng.below(512)).min(out.len());
                let block = out[a..b].to_vec();
                let at = rng.below(len).min(out.len());
                out.splice(at..at, block);
            }
            _ => {
                let a = rng.below(len).min(out.len());
                let b = (a + rng.below(512)).min(out.len());
                out.drain(a..b);
            }
        }
    }
    out
}

/// A file of the user's beside the study, as it was before a run: its kind and bytes
/// (a link: its target's path and the target's bytes).
#[derive(Debug, PartialEq)]
enum Kept {
    File(Vec<u8>),
    Link(PathBuf, Vec<u8>),
}

fn kept(p: &Path) -> Option<Kept> {
    let m = std::fs::symlink_metadata(p).ok()?;
    if m.file_type().is_symlink() {
        let t = std::fs::read_link(p).ok()?;
        let bytes = std::fs::read(&t).unwrap_or_default();
        return Some(Kept::Link(t, bytes));
    }
    std::fs::read(p).ok().map(Kept::File)
}

fn mkfifo(p: &Path) {
    let c = std::ffi::CString::new(p.to_str().unwrap()).unwrap();
    // SAFETY: mkfifo on a NUL-terminated path of the campaign's directory.
    unsafe { libc::mkfifo(c.as_ptr(), 0o600) };
}

/// The families through the binary, each case in a fresh directory:
/// - generated command files (growth, long names, huge literals) through `check` and `run`;
/// - FIFOs, devices and directories as the command file, a mesh unit, an output unit,
///   FICHIER and `--db`;
/// - files of the user's beside the study (`.lock`, `-journal`, `-wal`, `-shm`, links to a
///   file of the user's) before DEBUT and POURSUITE: every one must be left as it was.
///
/// Each must end by itself with 0, 1 or 2 under the memory limit, and `check` must not
/// print more than a megabyte. `FUZZ_FAMILIES` sets the count (CI: a few seconds).
#[test]
fn hostile_families_never_crash_hang_or_touch_a_users_file() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let seed = env_usize("FUZZ_SEED", 11) as u64;
    let n_cases = env_usize("FUZZ_FAMILIES", 24);
    let mut rng = Rng(0x5851_F42D_4C95_7F2D ^ seed.wrapping_mul(0x1000_0000_01B3));
    let work = tempfile::tempdir().unwrap();
    let mut c = Campaign {
        findings_dir: root.join("target/fuzz-findings/families"),
        findings: Vec::new(),
        counts: [0; 3],
    };
    let table_comm = "DEBUT()\nT = CREA_TABLE(LISTE=_F(PARA='X', LISTE_R=(1., 2.)))\n\
                      IMPR_TABLE(TABLE=T, UNITE=30)\nIMPR_TABLE(TABLE=T, FORMAT='PNG', NOM_PARA=('X', 'X'), FICHIER='out.png')\nFIN()\n";
    let mut per_family: std::collections::BTreeMap<&str, usize> = Default::default();
    for i in 0..n_cases {
        let dir = work.path().join(format!("c{i}"));
        std::fs::create_dir_all(&dir).unwrap();
        let family = i % 3;
        match family {
            0 => {
                let (text, name) = generated(&mut rng);
                *per_family.entry(name).or_default() += 1;
                std::fs::write(dir.join("g.comm"), &text).unwrap();
                let cmd = if rng.below(2) == 0 { "check" } else { "run" };
                let e = run_child(&dir, &[cmd, "g.comm"], Duration::from_secs(120));
                c.record(&format!("{cmd} ({name})"), "g.comm", &text, e);
            }
            1 => {
                // A special file in one of the places a user names a file.
                let special = match rng.below(4) {
                    0 => {
                        mkfifo(&dir.join("sp"));
                        "sp"
                    }
                    1 => "/dev/zero",
                    2 => "/dev/null",
                    _ => {
                        std::fs::create_dir_all(dir.join("sp")).unwrap();
                        "sp"
                    }
                };
                std::fs::write(dir.join("t.comm"), table_comm).unwrap();
                let fichier = table_comm.replace("'out.png'", &format!("'{special}'"));
                std::fs::write(dir.join("f.comm"), &fichier).unwrap();
                std::fs::write(
                    dir.join("m.comm"),
                    "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\nFIN()\n",
                )
                .unwrap();
                let unit30 = format!("30={special}");
                let unit20 = format!("20={special}");
                let how: Vec<&str> = match rng.below(6) {
                    0 => vec!["run", special],
                    1 => vec!["check", special],
                    2 => vec!["run", "t.comm", "--unit", &unit30],
                    3 => vec!["run", "f.comm"],
                    4 => vec!["run", "m.comm", "--unit", &unit20],
                    _ => vec!["run", "t.comm", "--db", special],
                };
                *per_family.entry("special files").or_default() += 1;
                let e = run_child(&dir, &how, Duration::from_secs(60));
                c.record(&format!("{how:?}"), "t.comm", table_comm, e);
            }
            _ => {
                // Files of the user's beside the study, then DEBUT (or POURSUITE of a
                // study made first).
                let poursuite = rng.below(2) == 0;
                std::fs::write(dir.join("t.comm"), table_comm).unwrap();
                if poursuite {
                    let _ = run_child(
                        &dir,
                        &["run", "t.comm", "--db", "s.db"],
                        Duration::from_secs(60),
                    );
                }
                std::fs::write(dir.join("precious.txt"), b"precious").unwrap();
                let mut placed = Vec::new();
                for suffix in [".lock", "-journal", "-wal", "-shm"] {
                    let p = dir.join(format!("s.db{suffix}"));
                    match rng.below(4) {
                        0 => std::fs::write(&p, format!("user's {suffix}")).unwrap(),
                        1 => std::os::unix::fs::symlink(dir.join("precious.txt"), &p).unwrap(),
                        2 => std::os::unix::fs::symlink(dir.join("nowhere"), &p).unwrap(),
                        _ => continue,
                    }
                    placed.push(p);
                }
                let before: Vec<Option<Kept>> = placed.iter().map(|p| kept(p)).collect();
                let comm = if poursuite { "p.comm" } else { "t.comm" };
                std::fs::write(dir.join("p.comm"), "POURSUITE()\nFIN()\n").unwrap();
                *per_family.entry("files beside the study").or_default() += 1;
                let e = run_child(
                    &dir,
                    &["run", comm, "--db", "s.db"],
                    Duration::from_secs(60),
                );
                let after: Vec<Option<Kept>> = placed.iter().map(|p| kept(p)).collect();
                let e = match e {
                    Ending::Ok if before != after || dir.join("nowhere").exists() => Ending::Finding(
                        format!("a file of the user's changed: {placed:?}\nbefore {before:?}\nafter {after:?}"),
                    ),
                    e => e,
                };
                c.record(
                    &format!("run {comm} beside {placed:?}"),
                    comm,
                    table_comm,
                    e,
                );
            }
        }
        c.counts[0] += 1;
        c.progress();
        let _ = std::fs::remove_dir_all(&dir);
    }
    println!(
        "fuzz families (seed {seed}): {} cases {per_family:?}; {} finding(s)",
        c.counts[0],
        c.findings.len()
    );
    assert!(
        c.findings.is_empty(),
        "{} finding(s):\n{}",
        c.findings.len(),
        c.findings.join("\n")
    );
}

/// Binary MED meshes, byte-mutated, through the MED reader in process (`FUZZ_INPROC_MED`)
/// and through `run` (`FUZZ_MED_RUNS`): no panic, no hang, no abort.
#[test]
fn mutated_med_meshes_never_crash_or_hang() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let seed = env_usize("FUZZ_SEED", 11) as u64;
    let n_inproc = env_usize("FUZZ_INPROC_MED", 300);
    let n_runs = env_usize("FUZZ_MED_RUNS", 6);
    let mut rng = Rng(0x9E6C_63D0_676A_9A99 ^ seed.wrapping_mul(0x1000_0000_01B3));
    let mut meds = files(&root.join("testcases"), &["med"]);
    meds.extend(files(&root.join("testcases/meshes"), &["med"]));
    assert!(!meds.is_empty());
    let originals: Vec<(String, Vec<u8>)> = meds
        .iter()
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(p).unwrap(),
            )
        })
        .collect();
    let work = tempfile::tempdir().unwrap();
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut c = Campaign {
        findings_dir: root.join("target/fuzz-findings/med"),
        findings: Vec::new(),
        counts: [0; 3],
    };
    for i in 0..n_inproc {
        let (name, bytes) = &originals[i % originals.len()];
        let mutant = mutate_bytes(&mut rng, bytes);
        let path = work.path().join(format!("m{}.med", i % 8));
        std::fs::write(&path, &mutant).unwrap();
        let p = path.clone();
        let e = in_process(
            move || {
                let _ = aster_nl::mesh::med::read_file(&p, None);
            },
            Duration::from_secs(30),
        );
        c.record(
            "med (in process)",
            name,
            &String::from_utf8_lossy(&mutant),
            e,
        );
        c.counts[2] += 1;
        c.progress();
    }
    std::panic::set_hook(hook);
    let dir = work.path().join("run");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("m.comm"),
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\nFIN()\n",
    )
    .unwrap();
    for i in 0..n_runs {
        let (name, bytes) = &originals[i % originals.len()];
        let mutant = mutate_bytes(&mut rng, bytes);
        std::fs::write(dir.join("m.med"), &mutant).unwrap();
        let _ = std::fs::remove_file(dir.join("m.db"));
        let e = run_child(
            &dir,
            &["run", "m.comm", "--unit", "20=m.med"],
            Duration::from_secs(60),
        );
        c.record("run (med)", name, &String::from_utf8_lossy(&mutant), e);
        c.counts[2] += 1;
        c.progress();
    }
    println!(
        "fuzz med (seed {seed}): {n_inproc} in process, {n_runs} runs; {} finding(s)",
        c.findings.len()
    );
    assert!(
        c.findings.is_empty(),
        "{} finding(s):\n{}",
        c.findings.len(),
        c.findings.join("\n")
    );
}
