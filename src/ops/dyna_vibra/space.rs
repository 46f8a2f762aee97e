//! The space DYNA_VIBRA integrates in: the generalized coordinates of a modal basis (GENE)
//! or the free DOFs of assembled matrices (PHYS). It gives the structure (M, K, C), the
//! rows taking the coordinates to a node's DX, DY, DZ, and the vectors of ETAT_INIT and
//! EXCIT in its coordinates.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::modes::ModeMeca;
use crate::model::{AssembledMatrix, Cmp, DofNumbering};
use crate::ops::common::gene::numbering_and_basis;
use crate::ops::common::instants::{by_order, matching};
use crate::ops::proj_vect_base::on_numbering;
use crate::ops::OpContext;
use crate::store::{dyna_trans as dyna_store, gene, matrix};
use crate::transient::{DenseMatrix, DenseStructure, NodeRows, SparseStructure, Structure};
use std::collections::HashMap;

/// The coordinates of the run.
pub enum Space {
    Gene {
        /// The NUME_DDL_GENE of the matrices, and the basis.
        numbering: String,
        basis: String,
        modes: ModeMeca,
    },
    Phys {
        numbering: DofNumbering,
        /// Eliminated DOFs (numbering's and AFFE_CHAR_CINE's).
        eliminated: Vec<bool>,
        /// Full index of each free DOF, in order.
        free: Vec<usize>,
    },
}

const MATRICES: [&str; 3] = ["MATR_MASS", "MATR_RIGI", "MATR_AMOR"];

impl Space {
    /// The space and the structure of the call's matrices.
    pub fn read(ctx: &OpContext<'_>, args: &Args) -> Result<(Space, Box<dyn Structure>)> {
        let gene = args.req_text("BASE_CALCUL")? == "GENE";
        let want = if gene {
            "matr_asse_gene_r"
        } else {
            "matr_asse_depl_r"
        };
        for key in MATRICES {
            if let Some(c) = args.concept(key).filter(|c| c.ty != want && c.ty != "?") {
                return Err(Error::validation(format!(
                    "{} is a {}; BASE_CALCUL='{}' takes a {want}",
                    c.name,
                    c.ty,
                    if gene { "GENE" } else { "PHYS" }
                ))
                .keyword(format!("DYNA_VIBRA/{key}"))
                .hint(if gene {
                    "project the matrices with PROJ_MATR_BASE, or set BASE_CALCUL='PHYS'"
                } else {
                    "give the assembled matrices, or set BASE_CALCUL='GENE'"
                }));
            }
        }
        if gene {
            read_gene(ctx, args)
        } else {
            read_phys(ctx, args)
        }
    }

    pub fn mesh(&self) -> &str {
        match self {
            Space::Gene { modes, .. } => &modes.numbering.mesh,
            Space::Phys { numbering, .. } => &numbering.mesh,
        }
    }

    pub fn size(&self) -> usize {
        match self {
            Space::Gene { modes, .. } => modes.modes.len(),
            Space::Phys { free, .. } => free.len(),
        }
    }

    /// The rows giving DX, DY, DZ of `node` from the coordinates; `None` when the node has
    /// none of the three.
    pub fn node_rows(&self, node: &str) -> Option<NodeRows> {
        let cmps = [Cmp::Dx, Cmp::Dy, Cmp::Dz];
        match self {
            Space::Gene { modes, .. } => {
                let at: Vec<Option<usize>> = cmps
                    .iter()
                    .map(|&c| modes.numbering.index_of(node, c))
                    .collect();
                if at.iter().all(Option::is_none) {
                    return None;
                }
                let row = |k: usize| -> Vec<f64> {
                    modes
                        .modes
                        .iter()
                        .map(|m| at[k].map_or(0.0, |i| m.shape[i]))
                        .collect()
                };
                Some(NodeRows::from_modes(&row(0), &row(1), &row(2)))
            }
            Space::Phys {
                numbering, free, ..
            } => {
                let full: Vec<Option<usize>> =
                    cmps.iter().map(|&c| numbering.index_of(node, c)).collect();
                if full.iter().all(Option::is_none) {
                    return None;
                }
                let reduced = |k: usize| full[k].and_then(|f| free.binary_search(&f).ok());
                Some(NodeRows::selection([reduced(0), reduced(1), reduced(2)]))
            }
        }
    }

    /// The coordinates of a vector given to `key` (ETAT_INIT's DEPL or VITE, EXCIT's
    /// VECT_ASSE_GENE or VECT_ASSE).
    pub fn vector(&self, ctx: &OpContext<'_>, occ: &Args, key: &str) -> Result<Vec<f64>> {
        let c = occ.req_concept(key)?;
        let kw = occ.key_path(key);
        match self {
            Space::Gene {
                numbering,
                basis,
                modes,
            } => {
                if c.ty == "cham_no_sdaster" {
                    return Err(Error::validation(format!(
                        "{} is a nodal field; BASE_CALCUL='GENE' takes a generalized vector",
                        c.name
                    ))
                    .keyword(kw)
                    .hint("project it with PROJ_VECT_BASE"));
                }
                let v = gene::load_vector(ctx.store, &c.name)?;
                // Another numbering of the same basis (NUME_DDL_GENE next to PROJ_BASE's
                // own) gives the same coordinates: Code_Aster checks the basis and the size.
                let same_basis = v.meta.basis == *basis && v.meta.size == modes.modes.len();
                if v.meta.numbering != *numbering && !same_basis {
                    return Err(Error::input(format!(
                        "{} is numbered by {}, the matrices by {numbering}",
                        c.name, v.meta.numbering
                    ))
                    .keyword(kw));
                }
                Ok(v.values)
            }
            Space::Phys {
                numbering,
                eliminated,
                free,
            } => {
                if c.ty == "vect_asse_gene" {
                    return Err(Error::validation(format!(
                        "{} is a generalized vector; BASE_CALCUL='PHYS' takes a nodal field",
                        c.name
                    ))
                    .keyword(kw));
                }
                let field = gene::load_field(ctx.store, &c.name)?;
                let on_dofs = ModeMeca {
                    numbering: DofNumbering {
                        eliminated: eliminated.clone(),
                        ..numbering.clone()
                    },
                    numbering_name: String::new(),
                    modes: Vec::new(),
                };
                let full = on_numbering(&field, &on_dofs, &c.name).map_err(|e| e.keyword(kw))?;
                Ok(free.iter().map(|&i| full[i]).collect())
            }
        }
    }
}

impl Space {
    /// The displacement and velocity of ETAT_INIT's RESULTAT at its NUME_ORDRE or
    /// INST_INIT (by default its last instant), in this space's coordinates, and that
    /// instant, on the physical DOFs (a modal basis restarts with its acceleration and its
    /// shocks' internal variables: `restart.rs`).
    pub fn state_of_result(
        &self,
        ctx: &OpContext<'_>,
        init: &Args,
    ) -> Result<(Vec<f64>, Vec<f64>, f64)> {
        let c = init.req_concept("RESULTAT")?;
        let kw = init.key_path("RESULTAT");
        match self {
            Space::Gene { .. } => Err(Error::internal(
                "a start on a modal basis is read by dyna_vibra::restart",
            )),
            Space::Phys {
                numbering, free, ..
            } => {
                if c.ty != "dyna_trans" {
                    return Err(Error::validation(format!(
                        "{} is a result on a modal basis; BASE_CALCUL='PHYS' starts from a dyna_trans",
                        c.name
                    ))
                    .keyword(kw));
                }
                let stored = dyna_store::stored_fields(ctx.store, &c.name)?;
                if !(stored.contains(&"DEPL") && stored.contains(&"VITE")) {
                    return Err(Error::input(format!(
                        "{} holds {} only: a start needs its DEPL and VITE",
                        c.name,
                        stored.join(" and ")
                    ))
                    .keyword(kw));
                }
                let times = dyna_store::instants(ctx.store, &c.name)?;
                let i = instant(init, &times)?;
                let t0 = times[i];
                let rows =
                    dyna_store::displacements_and_velocities(ctx.store, &c.name, i as i64 + 1)?;
                let index = numbering.index_map();
                // Full index -> (DEPL, VITE) of the instant.
                let mut at: HashMap<usize, (f64, f64)> = HashMap::with_capacity(rows.len());
                for (node, cmp, d, v) in &rows {
                    if let Some(&k) = Cmp::parse(cmp).and_then(|c| index.get(&(node.as_str(), c))) {
                        at.insert(k, (*d, *v));
                    }
                }
                let mut q = Vec::with_capacity(free.len());
                let mut v = Vec::with_capacity(free.len());
                for &f in free {
                    let Some(&(d, w)) = at.get(&f) else {
                        let dof = &numbering.dofs[f];
                        return Err(Error::input(format!(
                            "{} has no DEPL and VITE of {} {}, a free DOF of the matrices",
                            c.name,
                            dof.node,
                            dof.cmp.name()
                        ))
                        .keyword(kw)
                        .hint("start from a result on the same model and boundary conditions"));
                    };
                    q.push(d);
                    v.push(w);
                }
                Ok((q, v, t0))
            }
        }
    }
}

/// The index among the stored instants `times` that NUME_ORDRE or INST_INIT of `init`
/// names; the last one by default.
pub(super) fn instant(init: &Args, times: &[f64]) -> Result<usize> {
    if times.is_empty() {
        return Err(
            Error::input("the result has no stored instant").keyword(init.key_path("RESULTAT"))
        );
    }
    if let Some(k) = init.int("NUME_ORDRE") {
        return by_order(k, times, init.key_path("NUME_ORDRE"));
    }
    let Some(t) = init.real("INST_INIT") else {
        return Ok(times.len() - 1);
    };
    matching(init, times, t)?.ok_or_else(|| {
        Error::validation(format!(
            "INST_INIT = {t:e} is not a stored instant of the result (within PRECISION = {:e})",
            init.real("PRECISION").unwrap_or_default()
        ))
        .keyword(init.key_path("INST_INIT"))
    })
}

fn read_gene(ctx: &OpContext<'_>, args: &Args) -> Result<(Space, Box<dyn Structure>)> {
    let mut mats = Vec::new();
    for key in MATRICES {
        let Some(c) = args.concept(key) else {
            mats.push(None);
            continue;
        };
        mats.push(Some((key, gene::load_matrix(ctx.store, &c.name)?)));
    }
    let mass = mats[0]
        .as_ref()
        .map(|m| &m.1)
        .ok_or_else(|| Error::validation("MATR_MASS is required"))?;
    let numbering = mass.meta.numbering.clone();
    for (key, m) in mats.iter().flatten() {
        if m.meta.numbering != numbering {
            return Err(Error::input(format!(
                "{key} is numbered by {}, MATR_MASS by {numbering}",
                m.meta.numbering
            ))
            .keyword(format!("DYNA_VIBRA/{key}"))
            .hint("project every matrix with the same NUME_DDL_GENE"));
        }
    }
    let (num, modes) = numbering_and_basis(ctx.store, &numbering, None, "DYNA_VIBRA")?;
    let dense = |values: &[f64]| DenseMatrix::from_row_major(num.size, values);
    let stiffness = mats[1]
        .as_ref()
        .map(|m| dense(&m.1.values))
        .ok_or_else(|| Error::validation("MATR_RIGI is required"))?;
    let damping = mats[2].as_ref().map(|m| dense(&m.1.values));
    let mut structure = DenseStructure::new(dense(&mass.values), stiffness, damping)?;
    if args.has("AMOR_MODAL") {
        structure = structure.with_damping_ratios(&super::damping_ratios(args, num.size)?)?;
    }
    Ok((
        Space::Gene {
            numbering,
            basis: num.basis,
            modes,
        },
        Box::new(structure),
    ))
}

fn read_phys(ctx: &OpContext<'_>, args: &Args) -> Result<(Space, Box<dyn Structure>)> {
    let mut mats: Vec<Option<AssembledMatrix>> = Vec::new();
    for key in MATRICES {
        mats.push(match args.concept(key) {
            Some(c) => Some(matrix::load_matrix(ctx.store, &c.name)?),
            None => None,
        });
    }
    let mass = mats[0]
        .as_ref()
        .ok_or_else(|| Error::validation("MATR_MASS is required"))?;
    // MATR_MASS and MATR_RIGI (MATR_AMOR, the third, is the damping's place).
    for (key, m) in MATRICES.iter().zip(&mats).take(2) {
        if let (Some(m), Some(c)) = (m, args.concept(key)) {
            m.refuse_damping(&c.name, &format!("DYNA_VIBRA/{key}"))?;
        }
    }
    for (key, m) in MATRICES.iter().zip(&mats).skip(1) {
        if let Some(m) = m {
            if !m.same_dofs(mass) {
                return Err(Error::input(format!(
                    "{key} is not assembled on the DOF numbering and boundary conditions of MATR_MASS"
                ))
                .keyword(format!("DYNA_VIBRA/{key}"))
                .hint("assemble every matrix with the same NUME_DDL and CHAR_CINE"));
            }
        }
    }
    if args.has("AMOR_MODAL") {
        return Err(Error::validation(
            "AMOR_MODAL needs a modal basis: with BASE_CALCUL='PHYS' give MATR_AMOR",
        )
        .keyword("DYNA_VIBRA/AMOR_MODAL"));
    }
    mass.refuse_relations("DYNA_VIBRA (BASE_CALCUL='PHYS')")
        .map_err(|e| e.keyword("DYNA_VIBRA/MATR_MASS"))?;
    let free = mass.free_dofs();
    let n = free.len();
    if n == 0 {
        return Err(
            Error::input("every DOF is blocked: there is nothing to integrate")
                .keyword("DYNA_VIBRA/MATR_MASS"),
        );
    }
    // The lower triangles on the free DOFs (with LIAISON_DDL relations, of TᵀAT).
    let lower = |m: &AssembledMatrix| -> Result<Vec<(usize, usize, f64)>> {
        let mut t = m.reduced_triplets()?;
        t.retain(|&(i, j, _)| i >= j);
        Ok(t)
    };
    let structure = SparseStructure::new(
        n,
        lower(mass)?,
        lower(
            mats[1]
                .as_ref()
                .ok_or_else(|| Error::validation("MATR_RIGI is required"))?,
        )?,
        mats[2].as_ref().map(lower).transpose()?,
    )?;
    Ok((
        Space::Phys {
            numbering: mass.numbering.clone(),
            eliminated: mass.eliminated.clone(),
            free,
        },
        Box::new(structure),
    ))
}
