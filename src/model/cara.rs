//! Element characteristics (AFFE_CARA_ELEM): discrete stiffness/mass/damping values, beam
//! and bar sections, orientations.

use super::fe_model::{Model, Modelisation};
use super::frame::Orientation;
use super::select::{describe_cells, model_point_cells, model_select_cells};
use crate::error::{Error, Result};
use crate::mesh::select::Selection;
use crate::mesh::{CellKind, Mesh};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Repere {
    Global,
    Local,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum DiscreteCategory {
    /// K_...
    Stiffness,
    /// M_...
    Mass,
    /// A_... (viscous damping: the discrete part of OPTION='AMOR_MECA'; modal analysis
    /// does not use it)
    Damping,
}

/// How the VALE list of a discrete CARA fills the element matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum DiscreteForm {
    /// `*_D_N` / `*_D_L` stiffness or damping: one value per nodal component; on a SEG2
    /// the matrix is [[D, -D], [-D, D]].
    Diagonal,
    /// M_T_D_N: one mass on the node's translations.
    NodalMass,
    /// M_T_D_L: the mass of the segment, lumped half on each node.
    SegmentMass,
    /// M_TR_D_N: (m, CDG x y z, Ixx Iyy Izz Ixy Ixz Iyz).
    RigidBodyMass,
    /// `*_N` / `*_L` with SYME='OUI': the upper triangle, column by column
    /// (a11, a12, a22, a13, a23, a33, ...).
    Symmetric,
}

/// What a CARA name means.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct DiscreteSpec {
    pub category: DiscreteCategory,
    pub form: DiscreteForm,
    /// `_L` (SEG2) rather than `_N` (POI1).
    pub on_segment: bool,
    /// `TR` (translations and rotations) rather than `T`.
    pub rotations: bool,
}

impl DiscreteSpec {
    /// Parse a Code_Aster discrete CARA name (K_T_D_N, M_TR_D_N, K_T_L, ...).
    pub fn parse(cara: &str) -> Option<DiscreteSpec> {
        let parts: Vec<&str> = cara.split('_').collect();
        let (cat, rot, diag, place) = match parts.as_slice() {
            [c, r, "D", p] => (*c, *r, true, *p),
            [c, r, p] => (*c, *r, false, *p),
            _ => return None,
        };
        let category = match cat {
            "K" => DiscreteCategory::Stiffness,
            "M" => DiscreteCategory::Mass,
            "A" => DiscreteCategory::Damping,
            _ => return None,
        };
        let rotations = match rot {
            "T" => false,
            "TR" => true,
            _ => return None,
        };
        let on_segment = match place {
            "N" => false,
            "L" => true,
            _ => return None,
        };
        let form = match (category, diag, rotations, on_segment) {
            (_, false, _, _) => DiscreteForm::Symmetric,
            (DiscreteCategory::Mass, true, false, false) => DiscreteForm::NodalMass,
            (DiscreteCategory::Mass, true, false, true) => DiscreteForm::SegmentMass,
            (DiscreteCategory::Mass, true, true, false) => DiscreteForm::RigidBodyMass,
            // M_TR_D_L is not supported.
            (DiscreteCategory::Mass, true, true, true) => return None,
            _ => DiscreteForm::Diagonal,
        };
        Some(DiscreteSpec {
            category,
            form,
            on_segment,
            rotations,
        })
    }

    /// Number of VALE values for `nd` components per node.
    pub fn value_count(&self, nd: usize) -> usize {
        let nodes = if self.on_segment { 2 } else { 1 };
        match self.form {
            DiscreteForm::Diagonal => nd,
            DiscreteForm::NodalMass | DiscreteForm::SegmentMass => 1,
            DiscreteForm::RigidBodyMass => 10,
            DiscreteForm::Symmetric => {
                let n = nd * nodes;
                n * (n + 1) / 2
            }
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DiscreteValue {
    pub cara: String,
    pub spec: DiscreteSpec,
    pub values: Vec<f64>,
    pub repere: Repere,
}

/// The characteristics of one discrete element (a later DISCRET occurrence of the same
/// category overrides an earlier one, as in Code_Aster).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DiscreteCara {
    pub stiffness: Option<DiscreteValue>,
    pub mass: Option<DiscreteValue>,
    pub damping: Option<DiscreteValue>,
}

/// Section properties of a beam or bar.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Section {
    /// SECTION: CERCLE, RECTANGLE or GENERALE.
    pub kind: String,
    pub a: f64,
    /// Second moment about local y (governs bending in the local xz plane).
    pub iy: f64,
    /// Second moment about local z (governs bending in the local xy plane).
    pub iz: f64,
    /// Torsion constant.
    pub jx: f64,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaraElem {
    pub model: String,
    pub mesh: String,
    pub discrete: BTreeMap<usize, DiscreteCara>,
    /// POUTRE sections by cell.
    pub beams: BTreeMap<usize, Section>,
    /// BARRE sections by cell (only `a` matters).
    pub bars: BTreeMap<usize, Section>,
    pub orientations: BTreeMap<usize, Orientation>,
}

/// Components per node of a discrete modelisation.
pub fn discrete_components(m: Modelisation) -> usize {
    m.components().len()
}

impl Section {
    /// CERCLE: a disc of radius `r`, or a tube of thickness `ep` (0 < ep <= r).
    pub fn circle(r: f64, ep: Option<f64>) -> Section {
        let ri = ep.map_or(0.0, |ep| r - ep);
        let pi = std::f64::consts::PI;
        let i = pi / 4.0 * (r.powi(4) - ri.powi(4));
        Section {
            kind: "CERCLE".to_string(),
            a: pi * (r * r - ri * ri),
            iy: i,
            iz: i,
            jx: 2.0 * i,
        }
    }

    /// RECTANGLE: a solid rectangle, `hy` along local y, `hz` along local z.
    pub fn rectangle(hy: f64, hz: f64) -> Section {
        // Torsion constant of a solid rectangle (Roark), a >= b:
        // J = a b³ [1/3 − 0.21 (b/a)(1 − b⁴/(12 a⁴))], within ~0.5 % of the series.
        let (a, b) = if hy >= hz { (hy, hz) } else { (hz, hy) };
        let jx =
            a * b.powi(3) * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b.powi(4) / (12.0 * a.powi(4))));
        Section {
            kind: "RECTANGLE".to_string(),
            a: hy * hz,
            iy: hy * hz.powi(3) / 12.0,
            iz: hz * hy.powi(3) / 12.0,
            jx,
        }
    }

    /// GENERALE: the properties themselves.
    pub fn general(a: f64, iy: f64, iz: f64, jx: f64) -> Section {
        Section {
            kind: "GENERALE".to_string(),
            a,
            iy,
            iz,
            jx,
        }
    }

    /// A bar's GENERALE section: only the area matters.
    pub fn bar(a: f64) -> Section {
        Section::general(a, 0.0, 0.0, 0.0)
    }
}

/// One occurrence of discrete characteristics: a matrix `cara` of `values` on the
/// discrete elements of `on`.
#[derive(Clone, Debug, PartialEq)]
pub struct DiscreteAssignment {
    pub on: Selection,
    /// The characteristic's name as given (K_T_D_L), for messages.
    pub cara: String,
    /// What that name means.
    pub spec: DiscreteSpec,
    pub values: Vec<f64>,
    pub repere: Repere,
    /// Keyword paths errors name: the occurrence, the name, the values.
    pub keyword: String,
    pub cara_keyword: String,
    pub values_keyword: String,
}

/// One occurrence of a beam or bar section on the cells of `on`.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionAssignment {
    pub on: Selection,
    pub section: Section,
    /// Keyword path of the occurrence, which errors name.
    pub keyword: String,
}

/// One occurrence of an orientation on the cells of `on`.
#[derive(Clone, Debug, PartialEq)]
pub struct OrientationAssignment {
    pub on: Selection,
    pub orientation: Orientation,
}

impl CaraElem {
    /// No characteristics yet on the elements of `model`: the operator adds each
    /// occurrence (later ones override earlier ones), then checks the result complete.
    pub fn new(model_name: &str, model: &Model) -> CaraElem {
        CaraElem {
            model: model_name.to_string(),
            mesh: model.mesh.clone(),
            discrete: BTreeMap::new(),
            beams: BTreeMap::new(),
            bars: BTreeMap::new(),
            orientations: BTreeMap::new(),
        }
    }

    /// Beam sections, on POU_D_E elements only.
    pub fn add_beam(&mut self, model: &Model, mesh: &Mesh, a: &SectionAssignment) -> Result<()> {
        let cells = cells_of(
            model,
            mesh,
            &a.on,
            &[Modelisation::PouDE],
            "a beam section",
            &a.keyword,
        )?;
        for c in cells {
            self.beams.insert(c, a.section.clone());
        }
        Ok(())
    }

    /// Bar sections, on BARRE elements only.
    pub fn add_bar(&mut self, model: &Model, mesh: &Mesh, a: &SectionAssignment) -> Result<()> {
        let cells = cells_of(
            model,
            mesh,
            &a.on,
            &[Modelisation::Barre],
            "a bar section",
            &a.keyword,
        )?;
        for c in cells {
            self.bars.insert(c, a.section.clone());
        }
        Ok(())
    }

    pub fn add_orientation(&mut self, mesh: &Mesh, a: &OrientationAssignment) -> Result<()> {
        for c in model_select_cells(mesh, &a.on)? {
            self.orientations.insert(c, a.orientation);
        }
        Ok(())
    }

    /// A discrete matrix on each element of `a.on`, which must fit the element: its cell
    /// kind, its components, the number of values.
    pub fn add_discrete(
        &mut self,
        model: &Model,
        mesh: &Mesh,
        a: &DiscreteAssignment,
    ) -> Result<()> {
        let (name, spec, values) = (&a.cara, a.spec, &a.values);
        let discrete = [
            Modelisation::DisT,
            Modelisation::DisTr,
            Modelisation::Dis2dT,
        ];
        let what = "a discrete characteristic";
        for c in cells_of(model, mesh, &a.on, &discrete, what, &a.keyword)? {
            let (Some(cell), Some(el)) = (mesh.cells.get(c), model.element_of(c)) else {
                continue;
            };
            let want_kind = if spec.on_segment {
                CellKind::Seg2
            } else {
                CellKind::Poi1
            };
            if cell.kind != want_kind {
                return Err(Error::input(format!(
                    "{name} is for {} cells but cell {} is a {}",
                    want_kind.aster_name(),
                    cell.name,
                    cell.kind.aster_name()
                ))
                .keyword(a.cara_keyword.clone())
                .hint(if spec.on_segment {
                    "use the _N form (e.g. K_T_D_N) on POI1 cells"
                } else {
                    "use the _L form (e.g. K_T_D_L) on SEG2 cells"
                }));
            }
            let rot_model = el.modelisation == Modelisation::DisTr;
            if spec.rotations != rot_model {
                return Err(Error::input(format!(
                    "{name} does not fit cell {} modelled as {}",
                    cell.name,
                    el.modelisation.aster_name()
                ))
                .keyword(a.cara_keyword.clone())
                .hint(if rot_model {
                    "DIS_TR elements take the K_TR_/M_TR_ forms"
                } else {
                    "DIS_T / 2D_DIS_T elements take the K_T_/M_T_ forms"
                }));
            }
            let nd = discrete_components(el.modelisation);
            if spec.form == DiscreteForm::RigidBodyMass && nd != 6 {
                return Err(Error::input(format!("{name} needs a 3D DIS_TR element"))
                    .keyword(a.cara_keyword.clone()));
            }
            let n = spec.value_count(nd);
            if values.len() != n {
                return Err(Error::input(format!(
                    "{name} on a {} element expects {n} values, got {}",
                    el.modelisation.aster_name(),
                    values.len()
                ))
                .keyword(a.values_keyword.clone()));
            }
            let dv = DiscreteValue {
                cara: name.clone(),
                spec,
                values: values.clone(),
                repere: a.repere,
            };
            let entry = self.discrete.entry(c).or_default();
            match spec.category {
                DiscreteCategory::Stiffness => entry.stiffness = Some(dv),
                DiscreteCategory::Mass => entry.mass = Some(dv),
                DiscreteCategory::Damping => entry.damping = Some(dv),
            }
        }
        Ok(())
    }

    /// Every discrete element needs a stiffness, a mass or a damping (a damper alone has
    /// zero stiffness and mass, as Code_Aster's A_ characteristics allow), every beam and
    /// every bar a section.
    pub fn check_complete(&self, model: &Model, mesh: &Mesh) -> Result<(), Incomplete> {
        let mut no_discrete = Vec::new();
        let mut no_beam = Vec::new();
        let mut no_bar = Vec::new();
        for e in &model.elements {
            match e.modelisation {
                m if m.is_discrete() => {
                    let ok = self.discrete.get(&e.cell).is_some_and(|d| {
                        d.stiffness.is_some() || d.mass.is_some() || d.damping.is_some()
                    });
                    if !ok {
                        no_discrete.push(e.cell);
                    }
                }
                Modelisation::PouDE if !self.beams.contains_key(&e.cell) => no_beam.push(e.cell),
                Modelisation::Barre if !self.bars.contains_key(&e.cell) => no_bar.push(e.cell),
                _ => {}
            }
        }
        if !no_discrete.is_empty() {
            return Err(Incomplete::Discrete(describe_cells(mesh, &no_discrete)));
        }
        if !no_beam.is_empty() {
            return Err(Incomplete::Beam(describe_cells(mesh, &no_beam)));
        }
        if !no_bar.is_empty() {
            return Err(Incomplete::Bar(describe_cells(mesh, &no_bar)));
        }
        Ok(())
    }
}

/// Elements left without the characteristic they need, each with the cells it names
/// (and their groups); the operator names the keyword.
#[derive(Clone, Debug, PartialEq)]
pub enum Incomplete {
    /// Discrete elements without stiffness, mass nor damping.
    Discrete(String),
    /// Beam elements without a section.
    Beam(String),
    /// Bar elements without a section.
    Bar(String),
}

impl std::fmt::Display for Incomplete {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Incomplete::Discrete(cells) => {
                write!(
                    f,
                    "discrete elements without stiffness, mass nor damping: {cells}"
                )
            }
            Incomplete::Beam(cells) => {
                write!(f, "beam elements (POU_D_E) without a section: {cells}")
            }
            Incomplete::Bar(cells) => write!(f, "bar elements (BARRE) without a section: {cells}"),
        }
    }
}

/// Cells selected by `on` that must all be modelled with one of `allowed`; `what` names
/// the characteristic in messages ("a beam section"), `keyword` is the occurrence's path.
fn cells_of(
    model: &Model,
    mesh: &Mesh,
    on: &Selection,
    allowed: &[Modelisation],
    what: &str,
    keyword: &str,
) -> Result<Vec<usize>> {
    let mut cells = model_select_cells(mesh, on)?;
    // Nodes (13.x): the point elements of the model on those nodes.
    for c in model_point_cells(model, mesh, on)? {
        if !cells.contains(&c) {
            cells.push(c);
        }
    }
    let bad: Vec<usize> = cells
        .iter()
        .copied()
        .filter(|&c| {
            !model
                .element_of(c)
                .is_some_and(|e| allowed.contains(&e.modelisation))
        })
        .collect();
    if !bad.is_empty() {
        let names: Vec<&str> = allowed.iter().map(|m| m.aster_name()).collect();
        return Err(Error::input(format!(
            "{what} given on {} which the model does not carry as {}",
            describe_cells(mesh, &bad),
            names.join(" / ")
        ))
        .keyword(keyword.to_string()));
    }
    Ok(cells)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cara_names_parse() {
        let k = DiscreteSpec::parse("K_T_D_L").unwrap();
        assert_eq!(k.form, DiscreteForm::Diagonal);
        assert!(k.on_segment && !k.rotations);
        assert_eq!(k.value_count(3), 3);
        assert_eq!(DiscreteSpec::parse("M_TR_D_N").unwrap().value_count(6), 10);
        assert_eq!(DiscreteSpec::parse("K_TR_L").unwrap().value_count(6), 78);
        assert_eq!(DiscreteSpec::parse("K_T_N").unwrap().value_count(2), 3);
        assert!(DiscreteSpec::parse("M_TR_D_L").is_none());
        assert!(DiscreteSpec::parse("K_X_D_N").is_none());
    }
}
