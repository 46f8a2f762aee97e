//! Elementary matrices (CALC_MATR_ELEM): one dense matrix per model element, in global axes.
//!
//! Damping (OPTION='AMOR_MECA'), Code_Aster's convention: C_e = AMOR_ALPHA K_e + AMOR_BETA M_e
//! with the coefficients of the element's material (ELAS; absent: 0; ALPHA multiplies the
//! stiffness, BETA the mass), plus, on discrete elements, their A_ characteristic
//! (AFFE_CARA_ELEM DISCRET, laid out as the K_ one). K_e and M_e are the element's own
//! matrices, computed here or given (CALC_MATR_ELEM's RIGI_MECA and MASS_MECA).

use super::beam::{
    bar_mass, bar_stiffness_local, beam_mass_local, beam_stiffness_local, BeamProps,
};
use super::cara::{CaraElem, DiscreteValue, Incomplete, Repere};
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
use std::collections::BTreeMap;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum MatrixKind {
    RigiMeca,
    MassMeca,
    /// Viscous damping (Rayleigh from the materials, discrete dampers A_...).
    AmorMeca,
}

impl MatrixKind {
    pub fn parse(option: &str) -> Option<MatrixKind> {
        match option {
            "RIGI_MECA" => Some(MatrixKind::RigiMeca),
            "MASS_MECA" => Some(MatrixKind::MassMeca),
            "AMOR_MECA" => Some(MatrixKind::AmorMeca),
            _ => None,
        }
    }
    pub fn aster_name(self) -> &'static str {
        match self {
            MatrixKind::RigiMeca => "RIGI_MECA",
            MatrixKind::MassMeca => "MASS_MECA",
            MatrixKind::AmorMeca => "AMOR_MECA",
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

/// An OPTION of CALC_MATR_ELEM or ASSEMBLAGE: the matrix kind, and whether the lumped
/// (diagonal) mass is asked (MASS_MECA_DIAG).
pub fn parse_option(option: &str) -> Option<(MatrixKind, bool)> {
    match option {
        "MASS_MECA_DIAG" => Some((MatrixKind::MassMeca, true)),
        other => MatrixKind::parse(other).map(|k| (k, false)),
    }
}

impl ElemMatrices {
    /// The cell of the first element matrix with a nonzero term off its diagonal: where a
    /// lumped mass (MASS_MECA_DIAG) would differ from the consistent one. aster-nl gives
    /// MASS_MECA_DIAG only where the two are the same (discrete masses M_T_D_N, M_T_D_L,
    /// M_TR_D_N without offset, diagonal M_T_N...), and refuses the others.
    pub fn first_off_diagonal(&self) -> Option<usize> {
        self.elements.iter().find_map(|e| {
            let n = e.dofs.len();
            let off = e
                .values
                .iter()
                .enumerate()
                .any(|(k, v)| k / n.max(1) != k % n.max(1) && *v != 0.0);
            off.then_some(e.cell)
        })
    }

    /// Whether every value of every element matrix is zero (AMOR_MECA on a model without
    /// any damping).
    pub fn is_zero(&self) -> bool {
        self.elements
            .iter()
            .all(|e| e.values.iter().all(|v| *v == 0.0))
    }
}

/// The element matrices AMOR_MECA takes instead of computing K_e and M_e itself
/// (CALC_MATR_ELEM's RIGI_MECA and MASS_MECA); `None`: computed.
#[derive(Clone, Copy, Debug, Default)]
pub struct GivenMatrices<'a> {
    pub rigi: Option<&'a ElemMatrices>,
    pub mass: Option<&'a ElemMatrices>,
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
    /// Element matrices given to AMOR_MECA (of `kind`, RIGI_MECA or MASS_MECA) that do not
    /// fit the model.
    Given {
        kind: MatrixKind,
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
            ElemError::Given { kind, reason } => {
                write!(
                    f,
                    "the {} element matrices given: {reason}",
                    kind.aster_name()
                )
            }
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
/// materials are reported together, naming the cells and their groups. AMOR_MECA computes
/// the K_e and M_e it needs ([`compute_damping_matrices`] takes them given).
pub fn compute_elem_matrices(
    kind: MatrixKind,
    inp: &ElemInputs<'_>,
    loads: Vec<(String, KinematicLoad)>,
) -> Result<ElemMatrices, ElemError> {
    match kind {
        MatrixKind::RigiMeca => each_element(kind, inp, loads, |e| {
            element_matrix(Base::Stiffness, inp, e)
        }),
        MatrixKind::MassMeca => {
            each_element(kind, inp, loads, |e| element_matrix(Base::Mass, inp, e))
        }
        MatrixKind::AmorMeca => compute_damping_matrices(inp, loads, GivenMatrices::default()),
    }
}

/// The damping matrices (OPTION='AMOR_MECA') of every model element: C_e = AMOR_ALPHA K_e +
/// AMOR_BETA M_e from the element's material (no material: no Rayleigh part), plus the A_
/// characteristic of a discrete element. K_e and M_e come from `given` when given (they
/// must be of the same model), else are computed; neither is needed, nor computed, where
/// its coefficient is zero (a beam without RHO and without AMOR_BETA has a damping matrix).
pub fn compute_damping_matrices(
    inp: &ElemInputs<'_>,
    loads: Vec<(String, KinematicLoad)>,
    given: GivenMatrices<'_>,
) -> Result<ElemMatrices, ElemError> {
    let rigi = given_by_cell(inp, given.rigi, MatrixKind::RigiMeca)?;
    let mass = given_by_cell(inp, given.mass, MatrixKind::MassMeca)?;
    each_element(MatrixKind::AmorMeca, inp, loads, |e| {
        damping_matrix(inp, e, rigi.as_ref(), mass.as_ref())
    })
}

/// The given element matrices of `kind` by cell, checked to be of `kind` and of the model.
fn given_by_cell<'a>(
    inp: &ElemInputs<'_>,
    given: Option<&'a ElemMatrices>,
    kind: MatrixKind,
) -> Result<Option<BTreeMap<usize, &'a ElemMatrix>>, ElemError> {
    let Some(g) = given else {
        return Ok(None);
    };
    if g.kind != kind {
        return Err(ElemError::Given {
            kind,
            reason: format!(
                "they are {} matrices, {} ones are expected",
                g.kind.aster_name(),
                kind.aster_name()
            ),
        });
    }
    if g.model != inp.model_name {
        return Err(ElemError::Given {
            kind,
            reason: format!(
                "they are computed on the model {}, not on {}",
                g.model, inp.model_name
            ),
        });
    }
    Ok(Some(g.elements.iter().map(|m| (m.cell, m)).collect()))
}

/// Run `f` on every model element and gather the elements it cannot compute.
fn each_element(
    kind: MatrixKind,
    inp: &ElemInputs<'_>,
    loads: Vec<(String, KinematicLoad)>,
    mut f: impl FnMut(&ModelElement) -> Result<Outcome, ElemError>,
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
        match f(e)? {
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

/// The two matrices an element has of its own; damping combines them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Base {
    Stiffness,
    Mass,
}

/// The DOFs (node, component) of a model element and the coordinates of its nodes.
type ElementDofs = (Vec<(usize, Cmp)>, Vec<[f64; 3]>);

fn element_dofs(inp: &ElemInputs<'_>, e: &ModelElement) -> Result<ElementDofs, ElemError> {
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
    Ok((dofs, coords))
}

/// The matrix of a discrete characteristic (K_, M_ or A_) in global axes: rotated from the
/// element's frame when given with REPERE='LOCAL' on a segment.
fn discrete_value_matrix(
    inp: &ElemInputs<'_>,
    e: &ModelElement,
    dv: &DiscreteValue,
    coords: &[[f64; 3]],
) -> Result<Vec<f64>, ElemError> {
    let frame = if dv.repere == Repere::Local && dv.spec.on_segment {
        Some(frame_of(inp, e, coords)?)
    } else {
        None
    };
    Ok(discrete_matrix(
        dv,
        e.modelisation.components().len(),
        frame.as_ref(),
    ))
}

/// The damping matrix of one element (module documentation); `rigi` and `mass` are the
/// given K_e and M_e by cell.
fn damping_matrix(
    inp: &ElemInputs<'_>,
    e: &ModelElement,
    rigi: Option<&BTreeMap<usize, &ElemMatrix>>,
    mass: Option<&BTreeMap<usize, &ElemMatrix>>,
) -> Result<Outcome, ElemError> {
    let (dofs, coords) = element_dofs(inp, e)?;
    let n = dofs.len();
    let elas = elas_of(inp, e.cell);
    let mut values = match e.modelisation {
        m if m.is_discrete() => {
            let Some(d) = inp.cara.and_then(|c| c.discrete.get(&e.cell)) else {
                return Ok(Outcome::NoCara);
            };
            match &d.damping {
                Some(dv) => discrete_value_matrix(inp, e, dv, &coords)?,
                None => vec![0.0; n * n],
            }
        }
        Modelisation::PouDE | Modelisation::Barre => {
            let sections = inp.cara.map(|c| {
                if e.modelisation == Modelisation::PouDE {
                    &c.beams
                } else {
                    &c.bars
                }
            });
            if !sections.is_some_and(|s| s.contains_key(&e.cell)) {
                return Ok(Outcome::NoCara);
            }
            if elas.is_none() {
                return Ok(Outcome::NoMaterial);
            }
            vec![0.0; n * n]
        }
        _ => return Err(Error::internal("unhandled modelisation").into()),
    };
    let (alpha, beta) = elas.map_or((0.0, 0.0), |el| (el.amor_alpha, el.amor_beta));
    for (coef, base, given, kind) in [
        (alpha, Base::Stiffness, rigi, MatrixKind::RigiMeca),
        (beta, Base::Mass, mass, MatrixKind::MassMeca),
    ] {
        if coef == 0.0 {
            continue;
        }
        let own = match given {
            Some(by_cell) => {
                let Some(g) = by_cell.get(&e.cell) else {
                    let cell = describe_cells(inp.mesh, &[e.cell]);
                    return Err(ElemError::Given {
                        kind,
                        reason: format!("they have no matrix for {cell}"),
                    });
                };
                if g.dofs != dofs || g.values.len() != n * n {
                    let cell = describe_cells(inp.mesh, &[e.cell]);
                    return Err(ElemError::Given {
                        kind,
                        reason: format!("their matrix of {cell} is not on the element's DOFs"),
                    });
                }
                g.values.clone()
            }
            None => match element_matrix(base, inp, e)? {
                Outcome::Done(m) => m.values,
                other => return Ok(other),
            },
        };
        for (c, k) in values.iter_mut().zip(&own) {
            *c += coef * k;
        }
    }
    Ok(Outcome::Done(ElemMatrix {
        cell: e.cell,
        dofs,
        values,
    }))
}

fn element_matrix(
    base: Base,
    inp: &ElemInputs<'_>,
    e: &ModelElement,
) -> Result<Outcome, ElemError> {
    let (dofs, coords) = element_dofs(inp, e)?;
    let n = dofs.len();
    let values = match e.modelisation {
        m if m.is_discrete() => {
            let Some(d) = inp.cara.and_then(|c| c.discrete.get(&e.cell)) else {
                return Ok(Outcome::NoCara);
            };
            if d.stiffness.is_none() && d.mass.is_none() && d.damping.is_none() {
                return Ok(Outcome::NoCara);
            }
            let dv = match base {
                Base::Stiffness => d.stiffness.as_ref(),
                Base::Mass => d.mass.as_ref(),
            };
            match dv {
                // A discrete element with only a mass has a zero stiffness (and vice versa; a
                // damper alone has both zero).
                None => vec![0.0; n * n],
                Some(dv) => discrete_value_matrix(inp, e, dv, &coords)?,
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
            match base {
                Base::Stiffness if beam => {
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
                Base::Stiffness => {
                    rotate_to_global(&bar_stiffness_local(elas.e, s.a, l), 6, &frame, 3)
                }
                Base::Mass => {
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
