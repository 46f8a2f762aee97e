//! `aster-nl check` and mesh groups: the meshes a file reads (from the files beside it, the
//! units or the continued database), the groups later calls create, and the GROUP_NO /
//! GROUP_MA names a call gives that no mesh has, reported with the run's own error
//! ([`crate::mesh::select`]: the groups listed, "did you mean").
//!
//! Conservative on purpose: a name is reported only when every mesh the file can use is
//! known, and a group that a call creates (DEFI_GROUP's NOM, CREA_MAILLAGE's NOM_GROUP_MA,
//! CREA_GROUP_NO with TOUT_GROUP_MA) counts as present in every mesh from then on.

use crate::args::Args;
use crate::error::Error;
use crate::mesh::select::{self, Names, Selection};
use crate::mesh::Mesh;
use crate::value::{Span, Value};
use std::collections::BTreeSet;

/// What `check` knows of the meshes of a file.
#[derive(Default)]
pub struct MeshGroups {
    /// Meshes read, by concept name.
    meshes: Vec<(String, Mesh)>,
    /// Some mesh of the file could not be read here (or its groups are only known when the
    /// file runs): no group name is reported.
    incomplete: bool,
    /// Groups created by calls of the file: present in every mesh.
    created_nodes: BTreeSet<String>,
    created_cells: BTreeSet<String>,
}

impl MeshGroups {
    /// A mesh read by the file (LIRE_MAILLAGE) or taken from the continued database.
    pub fn add(&mut self, concept: &str, mesh: Mesh) {
        self.meshes.retain(|(n, _)| n != concept);
        self.meshes.push((concept.to_string(), mesh));
    }

    /// A mesh whose groups `check` cannot know (a file it cannot read, a value known
    /// only when the file runs).
    pub fn give_up(&mut self) {
        self.incomplete = true;
    }

    /// Groups that a call creates (`op` with validated `args`): taken as present from now on.
    pub fn note_created(&mut self, op: &str, args: &Args) {
        match op {
            "DEFI_GROUP" => {
                for occ in args.facts_or_empty("CREA_GROUP_NO") {
                    self.created_nodes
                        .extend(occ.texts("NOM").unwrap_or_default());
                    // GROUP_MA without NOM: node groups named after the cell groups.
                    if !occ.has("NOM") {
                        self.created_nodes
                            .extend(occ.texts("GROUP_MA").unwrap_or_default());
                    }
                    if occ.text("TOUT_GROUP_MA").is_some() {
                        // One node group per cell group, of the same name.
                        let cells: Vec<String> = self
                            .meshes
                            .iter()
                            .flat_map(|(_, m)| m.cell_groups.iter().map(|g| g.name.clone()))
                            .chain(self.created_cells.iter().cloned())
                            .collect();
                        self.created_nodes.extend(cells);
                    }
                }
                for occ in args.facts_or_empty("CREA_GROUP_MA") {
                    self.created_cells
                        .extend(occ.texts("NOM").unwrap_or_default());
                }
            }
            "CREA_MAILLAGE" => {
                for occ in args.facts_or_empty("CREA_POI1") {
                    self.created_cells
                        .extend(occ.texts("NOM_GROUP_MA").unwrap_or_default());
                }
            }
            _ => {}
        }
    }

    /// The GROUP_NO and GROUP_MA names of a call (at every level) that no mesh has, each
    /// with the span of the keyword that gave it (the error names it as `OP/FACT[i]/KEY`).
    /// The call's MAILLAGE, when it names a mesh read here, is the only one looked in.
    pub fn unknown_names(&self, args: &Args) -> Vec<(Error, Span)> {
        if self.incomplete || self.meshes.is_empty() {
            return Vec::new();
        }
        let meshes: Vec<&Mesh> = match args.concept("MAILLAGE") {
            Some(c) if self.meshes.iter().any(|(n, _)| *n == c.name) => self
                .meshes
                .iter()
                .filter(|(n, _)| *n == c.name)
                .map(|(_, m)| m)
                .collect(),
            _ => self.meshes.iter().map(|(_, m)| m).collect(),
        };
        let mut out = Vec::new();
        self.walk(args, &args.path, &meshes, &mut out);
        out
    }

    /// One occurrence `occ`, whose keyword path (with its occurrence number) is `at`.
    fn walk(&self, occ: &Args, at: &str, meshes: &[&Mesh], out: &mut Vec<(Error, Span)>) {
        // DETR_GROUP_* names groups to remove: a missing one is not an error of the run.
        let removing = occ.path.contains("DETR_GROUP_");
        for (key, value, span) in &occ.simple {
            let node = match key.as_str() {
                "GROUP_NO" => true,
                "GROUP_MA" => false,
                _ => continue,
            };
            if removing || matches!(value, Value::Unknown) {
                continue;
            }
            for name in occ.texts(key).unwrap_or_default() {
                let created = if node {
                    &self.created_nodes
                } else {
                    &self.created_cells
                };
                if created.contains(&name) {
                    continue;
                }
                let names = Names {
                    names: vec![name.clone()],
                    keyword: occ.key_path(key),
                };
                let sel = if node {
                    Selection {
                        node_groups: names,
                        ..Selection::default()
                    }
                } else {
                    Selection {
                        cell_groups: names,
                        ..Selection::default()
                    }
                };
                let found = |m: &&Mesh| {
                    if node {
                        m.node_group(&name).is_some()
                    } else {
                        m.cell_group(&name).is_some()
                    }
                };
                if meshes.iter().any(found) {
                    continue;
                }
                let Some(mesh) = meshes.first() else {
                    continue;
                };
                let err = if node {
                    select::select_nodes(mesh, &sel).err()
                } else {
                    select::select_cells(mesh, &sel).err()
                };
                if let Some(mut error) = err {
                    error.keyword = Some(format!("{at}/{key}"));
                    out.push((error, *span));
                }
            }
        }
        for (name, occurrences, _) in &occ.factor {
            for (i, o) in occurrences.iter().enumerate() {
                let at = match occurrences.len() {
                    1 => format!("{at}/{name}"),
                    _ => format!("{at}/{name}[{}]", i + 1),
                };
                self.walk(o, &at, meshes, out);
            }
        }
    }
}
