//! ARCHIVAGE with PAS_ARCH and INST together (Archive::EveryAnd): the union of every k-th
//! step and the listed instants, in order, each once, with the listed values as accurate
//! as when they are archived alone. On m = 1, k = 1 from x = 1 (x = cos t, no shock).

use super::*;

fn archived(scheme: Scheme, archive: &Archive) -> Trajectory {
    let s = one_dof(1.0);
    run(
        &s,
        &mut [],
        (&[1.0], &[0.0]),
        scheme,
        TimeGrid {
            t0: 0.0,
            t_end: 1.0,
            dt: 0.01,
        },
        archive,
    )
    .unwrap()
}

#[test]
fn pas_arch_with_inst_keeps_the_union_once_each() {
    // 0.3 is a step's end and a 10th step, 0.255 and 0.777 fall inside steps, 0 is the
    // start.
    let listed = vec![0.0, 0.255, 0.3, 0.777];
    for scheme in [
        Scheme::DiffCentre,
        Scheme::from_name("RUNGE_KUTTA_54").unwrap(),
    ] {
        let both = archived(scheme, &Archive::EveryAnd(10, listed.clone()));
        let alone = archived(scheme, &Archive::Instants(listed.clone()));
        assert!(
            both.t.windows(2).all(|w| w[1] > w[0]),
            "{scheme:?}: {:?}",
            both.t
        );
        for &ti in &listed {
            let i = both.t.iter().position(|&t| (t - ti).abs() < 1e-12);
            let j = alone.t.iter().position(|&t| (t - ti).abs() < 1e-12);
            let (Some(i), Some(j)) = (i, j) else {
                panic!("{scheme:?}: {ti} not archived: {:?}", both.t)
            };
            // The same value as archived alone (to round-off: the same steps).
            assert!(
                (both.q_at(i)[0] - alone.q_at(j)[0]).abs() < 1e-12,
                "{scheme:?} at {ti}"
            );
            // And close to the solution the scheme approximates to second order at
            // h = 0.01 (or to its tolerance): cos t for RUNGE_KUTTA_54; for DIFF_CENTRE,
            // Code_Aster's form, which takes the initial velocity as the velocity of the
            // half step before t0 (v_{-1/2} = 0: q is symmetric about −h/2), cos(t + h/2)/
            // cos(h/2), an O(h) phase lead on cos t (1.3e-3 at 0.255).
            let exact = match scheme {
                Scheme::DiffCentre => (ti + 0.005).cos() / 0.005f64.cos(),
                _ => ti.cos(),
            };
            assert!(
                (both.q_at(i)[0] - exact).abs() < 1e-4,
                "{scheme:?} at {ti}: {} vs {exact}",
                both.q_at(i)[0]
            );
        }
        if scheme == Scheme::DiffCentre {
            // Every 10th step of 100 (0, 0.1, ..., 1) and the two listed between steps
            // (0 and 0.3 are both, kept once).
            assert_eq!(both.t.len(), 11 + 2, "{:?}", both.t);
        } else {
            // The end and the listed ones at least; each step's instant once.
            assert!(both.t.len() > listed.len(), "{:?}", both.t);
        }
    }
}
