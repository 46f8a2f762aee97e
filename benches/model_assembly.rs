//! Element matrices + numbering + assembly + reduction of a 3D beam of 5000 POU_D_E
//! elements (30 006 DOFs), the path every modal / MODE_NON_LINE run takes once.

use aster_nl::mesh::select::{Names, Selection};
use aster_nl::mesh::{Cell, CellKind, Group, Mesh, Node};
use aster_nl::model::cara::{Section, SectionAssignment};
use aster_nl::model::fe_model::ModelAssignment;
use aster_nl::model::loads::{Condition, ImposedComponent};
use aster_nl::model::material::{Elas, MaterialAssignment};
use aster_nl::model::{
    assemble, compute_elem_matrices, CaraElem, Cmp, DofNumbering, ElemInputs, KinematicLoad,
    LoadKind, Material, MaterialField, MatrixKind, Model, Modelisation,
};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let n = 5000;
    let mesh = Mesh {
        dim: 3,
        nodes: (0..=n)
            .map(|i| Node {
                name: format!("N{i}"),
                coords: [i as f64 * 0.01, 0.0, 0.0],
            })
            .collect(),
        cells: (0..n)
            .map(|i| Cell {
                name: format!("S{i}"),
                kind: CellKind::Seg2,
                nodes: vec![i, i + 1],
            })
            .collect(),
        node_groups: vec![Group {
            name: "LEFT".into(),
            members: vec![0],
        }],
        cell_groups: vec![],
    };
    // The specs the operators would build from AFFE_MODELE(TOUT='OUI', POU_D_E),
    // AFFE_CARA_ELEM(POUTRE=CERCLE R=0.01), DEFI_MATERIAU(ELAS) and a clamp on LEFT.
    let everywhere = Selection {
        all: true,
        ..Selection::default()
    };
    let model = Model::build(
        "MA",
        &mesh,
        &[ModelAssignment {
            modelisation: Modelisation::PouDE,
            on: everywhere.clone(),
            keyword: "AFFE/MODELISATION".into(),
        }],
    )
    .unwrap();
    let mut cara = CaraElem::new("MO", &model);
    cara.add_beam(
        &model,
        &mesh,
        &SectionAssignment {
            on: everywhere.clone(),
            section: Section::circle(0.01, None),
            keyword: "POUTRE".into(),
        },
    )
    .unwrap();
    cara.check_complete(&model, &mesh).unwrap();
    let mat = Material {
        elas: Some(Elas::new(2e11, 0.3, Some(7800.0)).unwrap()),
    };
    let field = MaterialField::build(
        "MA",
        &mesh,
        &[MaterialAssignment {
            on: everywhere,
            name: "S".into(),
            material: mat,
        }],
    )
    .unwrap();
    let left = Selection {
        node_groups: Names {
            names: vec!["LEFT".into()],
            keyword: "MECA_IMPO/GROUP_NO".into(),
        },
        ..Selection::default()
    };
    let clamp = KinematicLoad::build(
        LoadKind::Cine,
        "MO",
        &model,
        &mesh,
        &[Condition {
            on: left,
            components: Cmp::ALL
                .iter()
                .map(|&cmp| ImposedComponent {
                    cmp,
                    value: 0.0,
                    keyword: format!("MECA_IMPO/{cmp}"),
                })
                .collect(),
            clamp: false,
            keyword: "MECA_IMPO".into(),
        }],
    )
    .unwrap();
    let inp = ElemInputs {
        model_name: "MO",
        model: &model,
        mesh: &mesh,
        field: Some(&field),
        cara: Some(&cara),
    };
    c.bench_function("beam_5000_K_and_M_assembled_reduced", |b| {
        b.iter(|| {
            let ke = compute_elem_matrices(MatrixKind::RigiMeca, &inp, vec![]).unwrap();
            let me = compute_elem_matrices(MatrixKind::MassMeca, &inp, vec![]).unwrap();
            let num = DofNumbering::from_elem_matrices(&mesh, &[&ke]).unwrap();
            let k = assemble(&num, &mesh, &[&ke], &[&clamp]).unwrap();
            let m = assemble(&num, &mesh, &[&me], &[&clamp]).unwrap();
            black_box((k.reduced().unwrap(), m.reduced().unwrap()))
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
