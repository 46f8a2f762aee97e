//! Element characteristics (AFFE_CARA_ELEM): discrete stiffness/mass/damping values, beam
//! and bar sections, orientations.

use super::fe_model::{Model, Modelisation};
use super::frame::Orientation;
use super::select::{describe_cells, model_point_cells, model_select_cells};
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::{CellKind, Mesh};
use crate::ops::common::selection::selection;
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
    /// A_... (damping: stored, unused by modal analysis)
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

fn named_values(occ: &Args) -> Result<Vec<(String, f64)>> {
    let names = occ.texts("CARA").unwrap_or_default();
    let vals = occ.reals("VALE").unwrap_or_default();
    if names.len() != vals.len() {
        return Err(Error::input(format!(
            "CARA has {} names but VALE has {} values",
            names.len(),
            vals.len()
        ))
        .keyword(occ.key_path("VALE"))
        .hint("give one value per CARA name, in the same order"));
    }
    Ok(names.into_iter().zip(vals).collect())
}

fn positive(occ: &Args, name: &str, v: f64) -> Result<f64> {
    if v > 0.0 && v.is_finite() {
        Ok(v)
    } else {
        Err(Error::input(format!("{name} must be positive, got {v}")).keyword(occ.key_path("VALE")))
    }
}

/// Section properties from SECTION / CARA / VALE.
pub fn section_from_args(occ: &Args) -> Result<Section> {
    let kind = occ.req_text("SECTION")?.to_string();
    let vals = named_values(occ)?;
    let get = |n: &str| vals.iter().find(|(k, _)| k == n).map(|(_, v)| *v);
    let allowed: &[&str] = match kind.as_str() {
        "CERCLE" => &["R", "EP"],
        "RECTANGLE" => &["H", "HY", "HZ"],
        "GENERALE" => &["A", "IY", "IZ", "JX"],
        other => {
            return Err(Error::input(format!("SECTION {other} is not supported"))
                .keyword(occ.key_path("SECTION"))
                .hint("use CERCLE, RECTANGLE or GENERALE"))
        }
    };
    if let Some((bad, _)) = vals.iter().find(|(k, _)| !allowed.contains(&k.as_str())) {
        return Err(
            Error::input(format!("CARA {bad} is not available for SECTION='{kind}'"))
                .keyword(occ.key_path("CARA"))
                .hint(format!("expected among {}", allowed.join(", "))),
        );
    }
    let need = |n: &str| {
        get(n).ok_or_else(|| {
            Error::input(format!("SECTION='{kind}' needs CARA '{n}'")).keyword(occ.key_path("CARA"))
        })
    };
    let s = match kind.as_str() {
        "CERCLE" => {
            let r = positive(occ, "R", need("R")?)?;
            let ri = match get("EP") {
                None => 0.0,
                Some(ep) => {
                    let ep = positive(occ, "EP", ep)?;
                    if ep > r {
                        return Err(Error::input(format!("EP = {ep} is larger than R = {r}"))
                            .keyword(occ.key_path("VALE")));
                    }
                    r - ep
                }
            };
            let pi = std::f64::consts::PI;
            let i = pi / 4.0 * (r.powi(4) - ri.powi(4));
            Section {
                kind,
                a: pi * (r * r - ri * ri),
                iy: i,
                iz: i,
                jx: 2.0 * i,
            }
        }
        "RECTANGLE" => {
            let (hy, hz) = match (get("H"), get("HY"), get("HZ")) {
                (Some(h), None, None) => (h, h),
                (None, Some(hy), Some(hz)) => (hy, hz),
                _ => {
                    return Err(Error::input(
                        "SECTION='RECTANGLE' needs either H, or both HY and HZ",
                    )
                    .keyword(occ.key_path("CARA")))
                }
            };
            let hy = positive(occ, "HY", hy)?;
            let hz = positive(occ, "HZ", hz)?;
            // Torsion constant of a solid rectangle (Roark), a >= b:
            // J = a b³ [1/3 − 0.21 (b/a)(1 − b⁴/(12 a⁴))], within ~0.5 % of the series.
            let (a, b) = if hy >= hz { (hy, hz) } else { (hz, hy) };
            let jx = a
                * b.powi(3)
                * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b.powi(4) / (12.0 * a.powi(4))));
            Section {
                kind,
                a: hy * hz,
                iy: hy * hz.powi(3) / 12.0,
                iz: hz * hy.powi(3) / 12.0,
                jx,
            }
        }
        _ => Section {
            a: positive(occ, "A", need("A")?)?,
            iy: positive(occ, "IY", need("IY")?)?,
            iz: positive(occ, "IZ", need("IZ")?)?,
            jx: positive(occ, "JX", need("JX")?)?,
            kind,
        },
    };
    Ok(s)
}

/// Bar section: GENERALE with CARA 'A', or CERCLE with 'R' (and optional 'EP').
pub fn bar_section_from_args(occ: &Args) -> Result<Section> {
    let kind = occ.req_text("SECTION")?;
    if kind == "GENERALE" {
        let vals = named_values(occ)?;
        return match vals.as_slice() {
            [(n, a)] if n == "A" => Ok(Section {
                kind: kind.to_string(),
                a: positive(occ, "A", *a)?,
                iy: 0.0,
                iz: 0.0,
                jx: 0.0,
            }),
            _ => Err(
                Error::input("BARRE with SECTION='GENERALE' needs CARA='A' alone")
                    .keyword(occ.key_path("CARA")),
            ),
        };
    }
    if kind != "CERCLE" {
        return Err(
            Error::input(format!("SECTION {kind} is not supported for BARRE"))
                .keyword(occ.key_path("SECTION"))
                .hint("use GENERALE (CARA='A') or CERCLE (CARA='R')"),
        );
    }
    section_from_args(occ)
}

impl CaraElem {
    /// AFFE_CARA_ELEM: read DISCRET / DISCRET_2D / POUTRE / BARRE / ORIENTATION, then check
    /// that every element that needs a characteristic got one.
    pub fn build(model_name: &str, model: &Model, mesh: &Mesh, args: &Args) -> Result<CaraElem> {
        let mut cara = CaraElem {
            model: model_name.to_string(),
            mesh: model.mesh.clone(),
            discrete: BTreeMap::new(),
            beams: BTreeMap::new(),
            bars: BTreeMap::new(),
            orientations: BTreeMap::new(),
        };
        for key in ["DISCRET", "DISCRET_2D"] {
            for occ in args.facts_or_empty(key) {
                cara.add_discrete(model, mesh, occ)?;
            }
        }
        for occ in args.facts_or_empty("POUTRE") {
            let s = section_from_args(occ)?;
            for c in cells_of(model, mesh, occ, &[Modelisation::PouDE], "POUTRE")? {
                cara.beams.insert(c, s.clone());
            }
        }
        for occ in args.facts_or_empty("BARRE") {
            let s = bar_section_from_args(occ)?;
            for c in cells_of(model, mesh, occ, &[Modelisation::Barre], "BARRE")? {
                cara.bars.insert(c, s.clone());
            }
        }
        for occ in args.facts_or_empty("ORIENTATION") {
            let o = orientation_from_args(occ)?;
            for c in model_select_cells(mesh, &selection(occ))? {
                cara.orientations.insert(c, o);
            }
        }
        cara.check_complete(model, mesh)?;
        Ok(cara)
    }

    fn add_discrete(&mut self, model: &Model, mesh: &Mesh, occ: &Args) -> Result<()> {
        let name = occ.req_text("CARA")?.to_string();
        let spec = DiscreteSpec::parse(&name).ok_or_else(|| {
            Error::input(format!("unknown or unsupported discrete CARA {name}"))
                .keyword(occ.key_path("CARA"))
                .hint("supported: K_T_D_N K_T_D_L K_TR_D_N K_TR_D_L K_T_N K_T_L K_TR_N K_TR_L, M_T_D_N M_T_D_L M_TR_D_N M_T_N M_T_L M_TR_N M_TR_L, A_... like K_...")
        })?;
        if occ.text("SYME").is_some_and(|s| s != "OUI") {
            return Err(
                Error::input("only symmetric discrete matrices are supported")
                    .keyword(occ.key_path("SYME"))
                    .hint("use SYME='OUI'"),
            );
        }
        let repere = match occ.text("REPERE").unwrap_or("GLOBAL") {
            "LOCAL" => Repere::Local,
            _ => Repere::Global,
        };
        let values = occ.reals("VALE").unwrap_or_default();
        let discrete = [
            Modelisation::DisT,
            Modelisation::DisTr,
            Modelisation::Dis2dT,
        ];
        for c in cells_of(model, mesh, occ, &discrete, "DISCRET")? {
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
                    "CARA {name} is for {} cells but cell {} is a {}",
                    want_kind.aster_name(),
                    cell.name,
                    cell.kind.aster_name()
                ))
                .keyword(occ.key_path("CARA"))
                .hint(if spec.on_segment {
                    "use the _N form (e.g. K_T_D_N) on POI1 cells"
                } else {
                    "use the _L form (e.g. K_T_D_L) on SEG2 cells"
                }));
            }
            let rot_model = el.modelisation == Modelisation::DisTr;
            if spec.rotations != rot_model {
                return Err(Error::input(format!(
                    "CARA {name} does not fit cell {} modelled as {}",
                    cell.name,
                    el.modelisation.aster_name()
                ))
                .keyword(occ.key_path("CARA"))
                .hint(if rot_model {
                    "DIS_TR elements take the K_TR_/M_TR_ forms"
                } else {
                    "DIS_T / 2D_DIS_T elements take the K_T_/M_T_ forms"
                }));
            }
            let nd = discrete_components(el.modelisation);
            if spec.form == DiscreteForm::RigidBodyMass && nd != 6 {
                return Err(Error::input(format!("{name} needs a 3D DIS_TR element"))
                    .keyword(occ.key_path("CARA")));
            }
            let n = spec.value_count(nd);
            if values.len() != n {
                return Err(Error::input(format!(
                    "CARA {name} on a {} element expects {n} values in VALE, got {}",
                    el.modelisation.aster_name(),
                    values.len()
                ))
                .keyword(occ.key_path("VALE")));
            }
            let dv = DiscreteValue {
                cara: name.clone(),
                spec,
                values: values.clone(),
                repere,
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

    /// Every discrete element needs a stiffness or a mass, every beam a POUTRE section,
    /// every bar a BARRE section.
    pub fn check_complete(&self, model: &Model, mesh: &Mesh) -> Result<()> {
        let mut no_discrete = Vec::new();
        let mut no_beam = Vec::new();
        let mut no_bar = Vec::new();
        for e in &model.elements {
            match e.modelisation {
                m if m.is_discrete() => {
                    let ok = self
                        .discrete
                        .get(&e.cell)
                        .is_some_and(|d| d.stiffness.is_some() || d.mass.is_some());
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
            return Err(Error::input(format!(
                "discrete elements without stiffness nor mass: {}",
                describe_cells(mesh, &no_discrete)
            ))
            .keyword("AFFE_CARA_ELEM/DISCRET")
            .hint("give each discrete element a K_... or M_... characteristic (a zero stiffness K_T_D_N=(0,0,0) is allowed)"));
        }
        if !no_beam.is_empty() {
            return Err(Error::input(format!(
                "beam elements (POU_D_E) without a section: {}",
                describe_cells(mesh, &no_beam)
            ))
            .keyword("AFFE_CARA_ELEM/POUTRE"));
        }
        if !no_bar.is_empty() {
            return Err(Error::input(format!(
                "bar elements (BARRE) without a section: {}",
                describe_cells(mesh, &no_bar)
            ))
            .keyword("AFFE_CARA_ELEM/BARRE"));
        }
        Ok(())
    }
}

/// Cells selected by `occ` that must all be modelled with one of `allowed`.
fn cells_of(
    model: &Model,
    mesh: &Mesh,
    occ: &Args,
    allowed: &[Modelisation],
    key: &str,
) -> Result<Vec<usize>> {
    let mut cells = model_select_cells(mesh, &selection(occ))?;
    // NOEUD / GROUP_NO (13.x): the point elements of the model on those nodes.
    for c in model_point_cells(model, mesh, &selection(occ))? {
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
            "{key} given on {} which the model does not carry as {}",
            describe_cells(mesh, &bad),
            names.join(" / ")
        ))
        .keyword(occ.path.clone()));
    }
    Ok(cells)
}

fn orientation_from_args(occ: &Args) -> Result<Orientation> {
    let cara = occ.req_text("CARA")?;
    let vale = occ.reals("VALE").unwrap_or_default();
    match (cara, vale.as_slice()) {
        ("VECT_Y", [x, y, z]) => Ok(Orientation::VectY([*x, *y, *z])),
        ("ANGL_VRIL", [g]) => Ok(Orientation::AnglVril(*g)),
        ("VECT_Y", v) | ("ANGL_VRIL", v) => Err(Error::input(format!(
            "CARA {cara} expects {} values in VALE, got {}",
            if cara == "VECT_Y" { 3 } else { 1 },
            v.len()
        ))
        .keyword(occ.key_path("VALE"))),
        _ => Err(
            Error::input(format!("ORIENTATION CARA {cara} is not supported"))
                .keyword(occ.key_path("CARA"))
                .hint("use VECT_Y or ANGL_VRIL"),
        ),
    }
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
