//! One-shot timing of CALC_MODES numerics: `cargo run --release --example modes_bench --
//! [chain|beam|membrane] [DOFs] [modes] [dense|lanczos]`; run under `/usr/bin/time -v` for the peak memory.
//! Prints wall time, the solver used and the largest relative error on ω against the
//! closed form.

// Each user of the shared model builders needs only some of them.
#[allow(dead_code)]
#[path = "../benches/common/models.rs"]
mod models;

use aster_nl::linalg::eigen::{solve_modes, EigenOptions, Method, ModeRequest};
use std::f64::consts::PI;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model = args.get(1).map(String::as_str).unwrap_or("chain");
    let ndof: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let nev: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(10);
    let opts = EigenOptions {
        force: match args.get(4).map(String::as_str) {
            Some("dense") => Some(Method::Dense),
            Some("lanczos") => Some(Method::Lanczos),
            _ => None,
        },
        ..Default::default()
    };
    let t0 = Instant::now();
    let ((k, m), exact): (models::Pair, Box<dyn Fn(usize) -> f64>) = match model {
        "membrane" => {
            // A strip 5:8, as close to ndof DOFs as the grid allows.
            let nx = ((ndof as f64 * 5.0 / 8.0).sqrt()).round() as usize;
            let ny = ndof / nx;
            let w = models::membrane_omegas(nx, ny, nev);
            (models::membrane(nx, ny), Box::new(move |j| w[j - 1]))
        }
        "beam" => {
            let ne = ndof / 2;
            (models::beam(ne), Box::new(|j| (j as f64 * PI).powi(2)))
        }
        _ => (
            models::spring_chain(ndof),
            Box::new(move |j| 2.0 * (j as f64 * PI / (2.0 * (ndof as f64 + 1.0))).sin()),
        ),
    };
    let t_build = t0.elapsed();
    let t1 = Instant::now();
    let set = match solve_modes(&k, &m, &ModeRequest::Smallest { n: nev }, &opts) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let t_solve = t1.elapsed();
    let err = set
        .omega2
        .iter()
        .enumerate()
        .map(|(i, w)| (w.sqrt() - exact(i + 1)).abs() / exact(i + 1))
        .fold(0.0, f64::max);
    println!("model {model}, {} DOFs, {nev} modes", k.nrows());
    println!("method: {}", set.method);
    println!(
        "build {:.3} s, solve {:.3} s",
        t_build.as_secs_f64(),
        t_solve.as_secs_f64()
    );
    println!("max relative error on ω vs closed form: {err:.2e}");
    println!(
        "max residual: {:.2e}",
        set.residuals.iter().fold(0.0f64, |a, r| a.max(*r))
    );
}
