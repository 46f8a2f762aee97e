//! Moving supports (multi-support excitation, Code_Aster's MULT_APPUI='OUI'). The
//! coordinates q describe the motion relative to the supports; a shock acts on the
//! absolute motion, so each of its nodes is displaced by Σ_e ψ_e d_e(t) on top of Φ q,
//! with ψ_e the excitation's constraint mode at the node (its support's unit displacement,
//! MODE_STATIQUE) and d_e(t) the support's displacement (EXCIT DEPL); its velocity by
//! Σ_e ψ_e ḋ_e(t) (EXCIT VITE). The obstacles stay fixed in the absolute frame.

use std::rc::Rc;

/// A function of time (a support's displacement or velocity).
pub type TimeFn = Rc<dyn Fn(f64) -> f64>;

/// One excitation's share in a shock's node motion.
#[derive(Clone)]
pub struct SupportTerm {
    /// ψ_e at node 1 and node 2 (global DX, DY, DZ; zero for a one-node shock's node 2).
    pub psi: [[f64; 3]; 2],
    pub depl: TimeFn,
    pub vite: TimeFn,
}

/// The support motion a shock's nodes follow (empty: fixed supports).
#[derive(Clone, Default)]
pub struct SupportMotion {
    terms: Vec<SupportTerm>,
}

impl std::fmt::Debug for SupportMotion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SupportMotion")
            .field("terms", &self.terms.len())
            .finish()
    }
}

impl SupportMotion {
    pub fn new(terms: Vec<SupportTerm>) -> SupportMotion {
        SupportMotion { terms }
    }

    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// The displacement of nodes 1 and 2 due to the supports at t.
    pub fn displacement(&self, t: f64) -> [[f64; 3]; 2] {
        self.sum(t, |term, t| (term.depl)(t))
    }

    /// The velocity of nodes 1 and 2 due to the supports at t.
    pub fn velocity(&self, t: f64) -> [[f64; 3]; 2] {
        self.sum(t, |term, t| (term.vite)(t))
    }

    fn sum(&self, t: f64, value: impl Fn(&SupportTerm, f64) -> f64) -> [[f64; 3]; 2] {
        let mut out = [[0.0; 3]; 2];
        for term in &self.terms {
            let d = value(term, t);
            for (node, psi) in out.iter_mut().zip(&term.psi) {
                for (o, p) in node.iter_mut().zip(psi) {
                    *o += p * d;
                }
            }
        }
        out
    }
}
