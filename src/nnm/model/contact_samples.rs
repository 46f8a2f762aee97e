//! The contact unknowns as time samples of a point's displacements: the displacement of a
//! shock's DOFs sampled over one period, and the contact unknowns that the physical root of
//! each law gives at those samples (a start guess, and the reference of the frequency
//! defect, root_defect.rs).

use crate::nnm::error::Result;
use crate::nnm::model::law;
use crate::nnm::model::system::{ShockSys, System};

/// Samples of the contact unknowns consistent with the displacements of `x` (scaled).
pub(in crate::nnm) fn init_contact(sys: &System, x: &mut [f64]) -> Result<()> {
    let lay = sys.lay;
    let smp = sys.sampler();
    for sh in &sys.shocks {
        let u = shock_displacements(sys, sh, x);
        let own = law::own_from_u(sh.law, sh.gap, sh.alpha, sh.eta, &u)?;
        for (v, mut s) in own.into_iter().enumerate() {
            let o = sh.offset + v * lay.n_coef_nonl;
            smp.analyse(&mut s, lay.h_nonl, &mut x[o..o + lay.n_coef_nonl]);
        }
    }
    Ok(())
}

/// Time samples (the system's sampler) of the displacement of each of `sh`'s DOFs in `x`.
pub(in crate::nnm) fn shock_displacements(sys: &System, sh: &ShockSys, x: &[f64]) -> Vec<Vec<f64>> {
    let lay = sys.lay;
    let smp = sys.sampler();
    let mut ws = smp.scratch();
    sh.dofs
        .iter()
        .map(|&d| {
            let mut s = vec![0.0; smp.n()];
            let u = &x[lay.u(d)..lay.u(d) + lay.n_coef_lin];
            smp.synth_with(u, lay.h_lin, &mut s, &mut ws);
            s
        })
        .collect()
}
