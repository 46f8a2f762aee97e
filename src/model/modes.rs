//! Real modes (`mode_meca`): frequencies, generalized quantities and shapes on a DOF
//! numbering. Produced by CALC_MODES; REST_MODE_NONL(TYPE_RESU='MODE_MECA') writes the
//! Fourier coefficients of a nonlinear mode in the same form (one "mode" per coefficient).

use super::numbering::DofNumbering;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Mode {
    /// 1-based order number (NUME_ORDRE), also the mode number (NUME_MODE).
    pub nume_ordre: usize,
    /// Frequency in Hz.
    pub freq: f64,
    /// ω² as computed (may be slightly negative for rigid-body modes).
    pub omega2: f64,
    pub mass_gene: f64,
    pub rigi_gene: f64,
    /// Shape in the full numbering (0 on eliminated DOFs).
    pub shape: Vec<f64>,
    /// Label of the field (e.g. `DEPL`, or `FOURIER_C1` for a Fourier coefficient).
    pub label: String,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModeMeca {
    pub numbering: DofNumbering,
    /// Name of the numbering concept the modes are expressed on.
    pub numbering_name: String,
    pub modes: Vec<Mode>,
}

impl ModeMeca {
    pub fn mode(&self, nume_ordre: usize) -> Option<&Mode> {
        self.modes.iter().find(|m| m.nume_ordre == nume_ordre)
    }

    /// The numbers of the stored modes, for error messages.
    pub fn available(&self) -> String {
        let n: Vec<String> = self
            .modes
            .iter()
            .map(|m| m.nume_ordre.to_string())
            .collect();
        if n.is_empty() {
            "none".to_string()
        } else {
            n.join(", ")
        }
    }
}

/// What kind of static deformation a vector of MODE_STATIQUE is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum StaticKind {
    /// MODE_STAT: a unit imposed displacement of a blocked DOF (constraint mode).
    Imposed,
    /// FORCE_NODALE: a unit force on a free DOF (attachment mode).
    Force,
    /// PSEUDO_MODE: a unit acceleration of the whole structure along a direction.
    Acceleration,
}

/// What one vector of a MODE_STATIQUE result answers: Code_Aster's NOEUD_CMP (the node and
/// component, or for a pseudo-mode 'ACCE' and the axis or NOM_DIR) and its kind.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StaticTag {
    pub nume_ordre: usize,
    pub kind: StaticKind,
    pub node: String,
    pub cmp: String,
}

impl StaticTag {
    /// Code_Aster's NOEUD_CMP: the node name padded to 8 characters, then the component.
    pub fn noeud_cmp(&self) -> String {
        format!("{:<8}{}", self.node, self.cmp)
    }
}

/// The vector of `tags` answering a unit imposed displacement of (node, cmp).
pub fn imposed_mode(tags: &[StaticTag], node: &str, cmp: &str) -> Option<usize> {
    tags.iter()
        .find(|t| t.kind == StaticKind::Imposed && t.node == node && t.cmp == cmp)
        .map(|t| t.nume_ordre)
}
