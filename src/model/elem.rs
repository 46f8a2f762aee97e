//! Elementary matrices (CALC_MATR_ELEM): one dense matrix per model element, in global axes.

use super::beam::{
    bar_mass, bar_stiffness_local, beam_mass_local, beam_stiffness_local, BeamProps,
};
use super::cara::{CaraElem, Incomplete, Repere};
use super::discrete::discrete_matrix;
use super::dof::Cmp;
use super::fe_model::{Model, ModelElement, Modelisation};
use super::frame::{length, rotate_to_global, segment_frame, Frame};
use super::loads::KinematicLoad;
use super::material::{Elas, MaterialField};
use super::select::describe_cells;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum MatrixKind {
    RigiMeca,
    MassMeca,
}

impl MatrixKind {
    pub fn parse(option: &str) -> Option<MatrixKind> {
        match option {
            "RIGI_MECA" => Some(MatrixKind::RigiMeca),
            "MASS_MECA" => Some(MatrixKind::MassMeca),
            _ => None,
        }
    }
    pub fn aster_name(self) -> &'static str {
        match self {
            MatrixKind::RigiMeca => "RIGI_MECA",
            MatrixKind::MassMeca => "MASS_MECA",
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ElemMatrix {
    /// Cell index in the mesh.
    pub cell: usize,
    /// (node index, component) of each row/column.
    pub dofs: Vec<(usize, Cmp)>,
    /// Dense row-major `dofs.len()`² values, global axes.
    pub values: Vec<f64>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ElemMatrices {
    pub kind: MatrixKind,
    pub model: String,
    pub mesh: String,
    pub elements: Vec<ElemMatrix>,
    /// AFFE_CHAR_MECA loads given with CHARGE (their blocked DOFs join the numbering).
    pub load_names: Vec<String>,
    pub loads: Vec<KinematicLoad>,
}

/// What CALC_MATR_ELEM reads.
pub struct ElemInputs<'a> {
    pub model_name: &'a str,
    pub model: &'a Model,
    pub mesh: &'a Mesh,
    pub field: Option<&'a MaterialField>,
    pub cara: Option<&'a CaraElem>,
}

/// Why element matrices cannot be computed, in the model's terms (each with the cells it
/// names and their groups); the operator names the keyword and says what to do.
#[derive(Clone, Debug)]
pub enum ElemError {
    /// The characteristics given leave elements without one.
    Incomplete(Incomplete),
    /// Elements that need characteristics (discrete, beams, bars) and were given none.
    NoCharacteristics(String),
    /// Beams and bars without an elastic material.
    NoElasticity(String),
    /// Beams and bars whose material has no density, for a mass matrix.
    NoDensity(String),
    /// The local axes of a segment cannot be built from its orientation.
    Frame {
        cell: String,
        reason: String,
    },
    Other(Error),
}

impl std::fmt::Display for ElemError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ElemError::Incomplete(e) => write!(f, "{e}"),
            ElemError::NoCharacteristics(cells) => {
                write!(f, "no element characteristics for {cells}")
            }
            ElemError::NoElasticity(cells) => write!(f, "no material with ELAS on {cells}"),
            ElemError::NoDensity(cells) => write!(f, "MASS_MECA needs the density RHO on {cells}"),
            ElemError::Frame { cell, reason } => write!(f, "cell {cell}: {reason}"),
            ElemError::Other(e) => write!(f, "{e}"),
        }
    }
}

impl From<Error> for ElemError {
    fn from(e: Error) -> Self {
        ElemError::Other(e)
    }
}

/// The error as it stands, without a keyword (operators name theirs: CALC_MATR_ELEM).
impl From<ElemError> for Error {
    fn from(e: ElemError) -> Self {
        match e {
            ElemError::Other(e) => e,
            e => Error::input(e.to_string()),
        }
    }
}

/// Compute the element matrices of every model element. Missing characteristics or
/// materials are reported together, naming the cells and their groups.
pub fn compute_elem_matrices(
    kind: MatrixKind,
    inp: &ElemInputs<'_>,
    loads: Vec<(String, KinematicLoad)>,
) -> Result<ElemMatrices, ElemError> {
    if let Some(c) = inp.cara {
        c.check_complete(inp.model, inp.mesh)
            .map_err(ElemError::Incomplete)?;
    }
    let mut elements = Vec::with_capacity(inp.model.elements.len());
    let mut no_cara = Vec::new();
    let mut no_mat = Vec::new();
    let mut no_rho = Vec::new();
    for e in &inp.model.elements {
        match element_matrix(kind, inp, e)? {
            Outcome::Done(m) => elements.push(m),
            Outcome::NoCara => no_cara.push(e.cell),
            Outcome::NoMaterial => no_mat.push(e.cell),
            Outcome::NoRho => no_rho.push(e.cell),
        }
    }
    if !no_cara.is_empty() {
        return Err(ElemError::NoCharacteristics(describe_cells(
            inp.mesh, &no_cara,
        )));
    }
    if !no_mat.is_empty() {
        return Err(ElemError::NoElasticity(describe_cells(inp.mesh, &no_mat)));
    }
    if !no_rho.is_empty() {
        return Err(ElemError::NoDensity(describe_cells(inp.mesh, &no_rho)));
    }
    let (load_names, loads) = loads.into_iter().unzip();
    Ok(ElemMatrices {
        kind,
        model: inp.model_name.to_string(),
        mesh: inp.model.mesh.clone(),
        elements,
        load_names,
        loads,
    })
}

enum Outcome {
    Done(ElemMatrix),
    NoCara,
    NoMaterial,
    NoRho,
}

fn frame_of(inp: &ElemInputs<'_>, e: &ModelElement, p: &[[f64; 3]]) -> Result<Frame, ElemError> {
    let orientation = inp.cara.and_then(|c| c.orientations.get(&e.cell));
    let (Some(a), Some(b)) = (p.first(), p.get(1)) else {
        return Err(Error::internal("segment without two nodes").into());
    };
    segment_frame(*a, *b, orientation).map_err(|reason| {
        let cell = inp
            .mesh
            .cells
            .get(e.cell)
            .map(|c| c.name.as_str())
            .unwrap_or("?");
        ElemError::Frame {
            cell: cell.to_string(),
            reason: reason.to_string(),
        }
    })
}

fn elas_of(inp: &ElemInputs<'_>, cell: usize) -> Option<Elas> {
    inp.field?.material_of(cell)?.1.elas
}

fn element_matrix(
    kind: MatrixKind,
    inp: &ElemInputs<'_>,
    e: &ModelElement,
) -> Result<Outcome, ElemError> {
    let cell = inp
        .mesh
        .cells
        .get(e.cell)
        .ok_or_else(|| Error::internal(format!("model cell {} outside the mesh", e.cell)))?;
    let cmps = e.modelisation.components();
    let dofs: Vec<(usize, Cmp)> = cell
        .nodes
        .iter()
        .flat_map(|&n| cmps.iter().map(move |&c| (n, c)))
        .collect();
    let coords: Vec<[f64; 3]> = cell
        .nodes
        .iter()
        .filter_map(|&n| inp.mesh.nodes.get(n).map(|x| x.coords))
        .collect();
    let n = dofs.len();
    let values = match e.modelisation {
        m if m.is_discrete() => {
            let Some(d) = inp.cara.and_then(|c| c.discrete.get(&e.cell)) else {
                return Ok(Outcome::NoCara);
            };
            if d.stiffness.is_none() && d.mass.is_none() {
                return Ok(Outcome::NoCara);
            }
            let dv = match kind {
                MatrixKind::RigiMeca => d.stiffness.as_ref(),
                MatrixKind::MassMeca => d.mass.as_ref(),
            };
            match dv {
                // A discrete element with only a mass has a zero stiffness (and vice versa).
                None => vec![0.0; n * n],
                Some(dv) => {
                    let frame = if dv.repere == Repere::Local && dv.spec.on_segment {
                        Some(frame_of(inp, e, &coords)?)
                    } else {
                        None
                    };
                    discrete_matrix(dv, cmps.len(), frame.as_ref())
                }
            }
        }
        Modelisation::PouDE | Modelisation::Barre => {
            let section = inp.cara.and_then(|c| {
                if e.modelisation == Modelisation::PouDE {
                    c.beams.get(&e.cell)
                } else {
                    c.bars.get(&e.cell)
                }
            });
            let Some(s) = section else {
                return Ok(Outcome::NoCara);
            };
            let Some(elas) = elas_of(inp, e.cell) else {
                return Ok(Outcome::NoMaterial);
            };
            let frame = frame_of(inp, e, &coords)?;
            let l = match (coords.first(), coords.get(1)) {
                (Some(a), Some(b)) => length(*a, *b),
                _ => return Err(Error::internal("segment without two nodes").into()),
            };
            let beam = e.modelisation == Modelisation::PouDE;
            match kind {
                MatrixKind::RigiMeca if beam => {
                    let p = BeamProps {
                        e: elas.e,
                        g: elas.shear_modulus(),
                        a: s.a,
                        iy: s.iy,
                        iz: s.iz,
                        jx: s.jx,
                    };
                    rotate_to_global(&beam_stiffness_local(&p, l), 12, &frame, 3)
                }
                MatrixKind::RigiMeca => {
                    rotate_to_global(&bar_stiffness_local(elas.e, s.a, l), 6, &frame, 3)
                }
                MatrixKind::MassMeca => {
                    let Some(rho) = elas.rho else {
                        return Ok(Outcome::NoRho);
                    };
                    if beam {
                        rotate_to_global(&beam_mass_local(rho, s.a, s.iy, s.iz, l), 12, &frame, 3)
                    } else {
                        bar_mass(rho, s.a, l)
                    }
                }
            }
        }
        _ => return Err(Error::internal("unhandled modelisation").into()),
    };
    Ok(Outcome::Done(ElemMatrix {
        cell: e.cell,
        dofs,
        values,
    }))
}
