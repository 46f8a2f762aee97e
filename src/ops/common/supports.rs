//! The moving supports of a seismic excitation (CALC_CHAR_SEISME, DYNA_VIBRA EXCIT with
//! MULT_APPUI='OUI'): the nodes an occurrence names and the combination of their
//! constraint modes (MODE_STATIQUE's MODE_STAT) along DIRECTION.

use super::selection::selection;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::formula::AnyFunction;
use crate::mesh::select::select_nodes;
use crate::model::modes::{imposed_mode, ModeMeca};
use crate::model::Cmp;
use crate::store::tran_gene::StoredSupport;
use crate::store::{function as function_store, model, modes as mode_store, Store};

/// The constraint modes of a MODE_STATIQUE result with what each answers.
pub(crate) struct ConstraintModes {
    pub name: String,
    pub modes: ModeMeca,
    tags: Vec<crate::model::modes::StaticTag>,
}

impl ConstraintModes {
    /// Loads `name`; an error naming `key` if it holds no constraint mode.
    pub fn load(store: &Store, name: &str, key: &str) -> Result<ConstraintModes> {
        let modes = mode_store::load_modes(store, name)?;
        let tags = mode_store::load_static_tags(store, name)?;
        if tags.is_empty() {
            return Err(Error::validation(format!(
                "{name} is not a result of MODE_STATIQUE: it has no constraint mode"
            ))
            .keyword(key.to_string())
            .hint("compute the supports' modes with MODE_STATIQUE(MODE_STAT=_F(GROUP_NO=..., AVEC_CMP=...))"));
        }
        Ok(ConstraintModes {
            name: name.to_string(),
            modes,
            tags,
        })
    }

    /// ψ = Σ_node Σ_c dir_c · (constraint mode of node's component c), c over DX, DY, DZ
    /// (and DRX, DRY, DRZ for the 4th to 6th values of `dir`), in the full numbering.
    /// A nonzero component without its mode is an error naming `key`.
    pub fn combination(&self, nodes: &[String], dir: &[f64], key: &str) -> Result<Vec<f64>> {
        let mut psi = vec![0.0; self.modes.numbering.len()];
        for node in nodes {
            for (c, &d) in Cmp::ALL.iter().zip(dir) {
                if d == 0.0 {
                    continue;
                }
                let mode = imposed_mode(&self.tags, node, c.name())
                    .and_then(|k| self.modes.mode(k))
                    .ok_or_else(|| {
                        Error::validation(format!(
                            "{} has no constraint mode of {node} {} (DIRECTION gives it {d})",
                            self.name,
                            c.name()
                        ))
                        .keyword(key.to_string())
                        .hint("add that node and component to MODE_STATIQUE's MODE_STAT (the DOF must be blocked)")
                    })?;
                for (p, s) in psi.iter_mut().zip(&mode.shape) {
                    *p += d * s;
                }
            }
        }
        Ok(psi)
    }
}

/// The nodes NOEUD or GROUP_NO of `occ` name on `mesh_name`, in mesh order.
pub(crate) fn support_nodes(store: &Store, occ: &Args, mesh_name: &str) -> Result<Vec<String>> {
    let mesh = model::load_mesh(store, mesh_name)?;
    let idx = select_nodes(&mesh, &selection(occ).nodes_only())?;
    Ok(idx
        .into_iter()
        .filter_map(|i| mesh.nodes.get(i).map(|n| n.name.clone()))
        .collect())
}

/// The supports' share in the absolute motion of a DYNA_VIBRA result with moving supports
/// (MULT_APPUI='OUI' of REST_GENE_PHYS and RECU_FONCTION): Σ_e ψ_e · DEPL_e(t), VITE_e(t)
/// or ACCE_e(t), ψ_e in the full numbering of the constraint modes.
pub(crate) struct SupportShare {
    terms: Vec<(Vec<f64>, [AnyFunction; 3])>,
}

impl SupportShare {
    /// The supports of `result` (its stored payload); an error naming `key` when it was
    /// computed with fixed supports.
    pub fn load(
        store: &Store,
        result: &str,
        supports: &[StoredSupport],
        key: &str,
    ) -> Result<SupportShare> {
        if supports.is_empty() {
            return Err(Error::validation(format!(
                "{result} was computed without moving supports: its motion is absolute already"
            ))
            .keyword(key.to_string())
            .hint("MULT_APPUI='OUI' restores the absolute motion of a DYNA_VIBRA with EXCIT MULT_APPUI='OUI'"));
        }
        let mut terms = Vec::with_capacity(supports.len());
        for s in supports {
            let modes = ConstraintModes::load(store, &s.mode_stat, key)?;
            let psi = modes.combination(&s.nodes, &s.direction, key)?;
            let f = |name: &str| function_store::load_any_function(store, name);
            terms.push((psi, [f(&s.depl)?, f(&s.vite)?, f(&s.acce)?]));
        }
        Ok(SupportShare { terms })
    }

    /// g_e(t) of every support e, g its DEPL, VITE or ACCE function as `field` says:
    /// evaluated once per instant, whatever the number of DOFs restored.
    pub fn values(&self, field: &str, t: f64) -> Result<Vec<f64>> {
        let k = match field {
            "DEPL" => 0,
            "VITE" => 1,
            _ => 2,
        };
        self.terms.iter().map(|(_, fns)| fns[k].eval(t)).collect()
    }

    /// Σ_e ψ_e[dof] · g_e for the `values` of one instant.
    pub fn combine(&self, values: &[f64], dof: usize) -> f64 {
        self.terms
            .iter()
            .zip(values)
            .map(|((psi, _), g)| psi.get(dof).copied().unwrap_or(0.0) * g)
            .sum()
    }
}
