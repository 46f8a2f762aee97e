//! The location keywords of one factor keyword occurrence (TOUT='OUI', GROUP_MA, MAILLE,
//! GROUP_NO, NOEUD) as the mesh layer's [`Selection`], each list with its keyword path.

use crate::args::Args;
use crate::mesh::select::{Names, Selection};

/// The selection `occ` writes; keywords it does not have are empty lists.
pub(crate) fn selection(occ: &Args) -> Selection {
    Selection {
        all: occ
            .text("TOUT")
            .is_some_and(|t| t.eq_ignore_ascii_case("OUI")),
        cell_groups: names(occ, "GROUP_MA"),
        cells: names(occ, "MAILLE"),
        node_groups: names(occ, "GROUP_NO"),
        nodes: names(occ, "NOEUD"),
    }
}

/// The names given to `key` in `occ`, with the keyword's path.
pub(crate) fn names(occ: &Args, key: &str) -> Names {
    Names {
        names: occ.texts(key).unwrap_or_default(),
        keyword: occ.key_path(key),
    }
}
