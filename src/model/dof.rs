//! Degree-of-freedom components, in Code_Aster order.

use serde::{Deserialize, Serialize};

/// A displacement component. The declaration order is Code_Aster's numbering order
/// (DX DY DZ DRX DRY DRZ), which `Ord` follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum Cmp {
    Dx,
    Dy,
    Dz,
    Drx,
    Dry,
    Drz,
}

impl Cmp {
    pub const ALL: [Cmp; 6] = [Cmp::Dx, Cmp::Dy, Cmp::Dz, Cmp::Drx, Cmp::Dry, Cmp::Drz];

    /// Code_Aster name (`DX`, ..., `DRZ`).
    pub fn name(self) -> &'static str {
        match self {
            Cmp::Dx => "DX",
            Cmp::Dy => "DY",
            Cmp::Dz => "DZ",
            Cmp::Drx => "DRX",
            Cmp::Dry => "DRY",
            Cmp::Drz => "DRZ",
        }
    }

    pub fn parse(name: &str) -> Option<Cmp> {
        Cmp::ALL.into_iter().find(|c| c.name() == name)
    }
}

impl std::fmt::Display for Cmp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
