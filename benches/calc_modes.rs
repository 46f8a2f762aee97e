//! CALC_MODES numerics: the 10 lowest modes of 10⁵-DOF models with shift-invert Lanczos.

// Each user of the shared model builders needs only some of them.
#[allow(dead_code)]
#[path = "common/models.rs"]
mod models;

use aster_nl::linalg::eigen::{solve_modes, EigenOptions, ModeRequest};
use criterion::{criterion_group, criterion_main, Criterion};

fn calc_modes(c: &mut Criterion) {
    let mut g = c.benchmark_group("calc_modes");
    g.sample_size(10);
    let req = ModeRequest::Smallest { n: 10 };
    let opts = EigenOptions::default();
    let (k, m) = models::spring_chain(100_000);
    g.bench_function("spring_chain_1e5_10_modes", |b| {
        b.iter(|| solve_modes(&k, &m, &req, &opts).expect("chain modes"))
    });
    // A banded 2D model (membrane, 250 × 400 grid): fill-in makes the factorisation the
    // dominant cost, as in real FE models. (A 10⁵-DOF Euler beam is not used: its stiffness
    // condition number ~ne⁴ ≈ 6e18 is beyond double precision.)
    let (k, m) = models::membrane(250, 400);
    g.bench_function("membrane_1e5_10_modes", |b| {
        b.iter(|| solve_modes(&k, &m, &req, &opts).expect("membrane modes"))
    });
    let (k, m) = models::beam(5_000);
    g.bench_function("beam_1e4_dofs_10_modes", |b| {
        b.iter(|| solve_modes(&k, &m, &req, &opts).expect("beam modes"))
    });
    g.finish();
}

// No plots: plotters here has no font backend (see the design notes), and criterion's
// report plotting would fail without one.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = calc_modes
}
criterion_main!(benches);
