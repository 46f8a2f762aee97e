//! Speed of the EHMAN engine on the sdnd122a settings (one DOF against a wall: H_l = 5,
//! H_nl = 200, NB_ORDRE_MAN = 20, PREC_MAN = 1e-14, 105 branches) and on a 20-DOF chain,
//! and of MODE_NON_LINE's post-processing of the rows (Fourier coefficients and the
//! contact-law check, `PostProcessor`). Run: `cargo bench --bench nnm_sdnd122a`.

use aster_nl::nnm::{
    continue_branches, start_from_mode, Continuation, Harmonics, PostProcessor, Problem, Settings,
    Shock, ShockLaw,
};
use criterion::{criterion_group, criterion_main, Criterion};
use faer::sparse::{SparseColMat, Triplet};

fn sparse(n: usize, e: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let t: Vec<Triplet<usize, usize, f64>> =
        e.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
    SparseColMat::try_new_from_triplets(n, n, &t).expect("valid triplets")
}

fn settings(h_nonl: usize, n_branches: usize) -> Settings {
    Settings {
        harmonics: Harmonics { h_lin: 5, h_nonl },
        continuation: Continuation {
            n_branches,
            n_points_per_branch: 1,
            order: 20,
            prec_man: 1e-14,
            prec_newton: 1e-9,
            iter_newton_max: 15,
            bif_terms: 3,
            bif_tol: 1e-4,
            det_test: true,
            direction: 1,
        },
    }
}

fn sdnd122a(c: &mut Criterion) {
    let p = Problem {
        forcing: None,
        k: sparse(1, &[(0, 0, 10.0)]),
        m: sparse(1, &[(0, 0, 1.0)]),
        shocks: vec![Shock {
            law: ShockLaw::Plan,
            dofs: vec![0],
            gap: 0.01,
            stiffness: 50.0,
            regul: 5e-5,
        }],
    };
    let s = settings(200, 105);
    // The rows of the first 20 branches, post-processed as MODE_NON_LINE does: one
    // PostProcessor, then every row (displacement and force coefficients, law defect).
    let rows = {
        let s20 = settings(200, 20);
        let st = start_from_mode(&p, &s20, &[1.0], 1.0, 10f64.sqrt()).expect("start");
        let out = continue_branches(&p, &s20, st, &mut |_, _| {});
        assert!(out.error.is_none());
        out.points
    };
    let mut g = c.benchmark_group("ehman");
    g.sample_size(10);
    g.bench_function("sdnd122a_105_branches_hnl200", |b| {
        b.iter(|| {
            let st = start_from_mode(&p, &s, &[1.0], 1.0, 10f64.sqrt()).expect("start");
            let out = continue_branches(&p, &s, st, &mut |_, _| {});
            assert!(out.error.is_none());
            out.points.len()
        })
    });
    g.bench_function("sdnd122a_post_20_rows_hnl200", |b| {
        b.iter(|| {
            let post = PostProcessor::new(&p, &s).expect("post-processor");
            rows.iter()
                .map(|r| post.row(&r.x).expect("row").law_defect)
                .fold(0.0, f64::max)
        })
    });
    g.finish();
}

// No plots: the machine may lack the fonts criterion's plotting backend needs.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = sdnd122a
}
criterion_main!(benches);
