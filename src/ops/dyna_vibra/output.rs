//! DYNA_VIBRA's result as SQL tables: the generalized coordinates (GENE, `tran_gene`) or the
//! free DOFs' fields (PHYS, `dyna_trans`, the layout REST_MODE_NONL writes), and the shocks'
//! samples in `<name>_CHOC` (store/tran_gene.rs).

use super::memory;
use super::shocks::ShockName;
use super::space::Space;
use crate::error::Result;
use crate::ops::OpContext;
use crate::store::tran_gene::{self, Payload, StoredShock, StoredSupport};
use crate::store::{dyna_trans as dyna_store, table as table_store};
use crate::table::{Cell, ColKind, Table};
use crate::transient::{ShockSample, Trajectory};

pub fn store(
    ctx: &mut OpContext<'_>,
    name: &str,
    space: &Space,
    shocks: &[ShockName],
    supports: &[StoredSupport],
    tr: &Trajectory,
) -> Result<()> {
    let (ty, table) = match space {
        Space::Gene { .. } => ("tran_gene", generalized_table(name, tr)?),
        Space::Phys {
            numbering, free, ..
        } => {
            let mut t = field_header(
                format!("DYNA_VIBRA {name}: displacements, velocities and accelerations"),
                &dyna_store::FIELDS,
            )?;
            for (i, time) in tr.t.iter().enumerate() {
                let (q, v, a) = (tr.q_at(i), tr.v_at(i), tr.a_at(i));
                for (d, &full) in free.iter().enumerate() {
                    let dof = &numbering.dofs[full];
                    t.push_row(vec![
                        Cell::I(i as i64 + 1),
                        Cell::R(*time),
                        Cell::K(dof.node.clone()),
                        Cell::K(dof.cmp.name().to_string()),
                        Cell::R(q[d]),
                        Cell::R(v[d]),
                        Cell::R(a[d]),
                    ])?;
                }
            }
            ("dyna_trans", t)
        }
    };
    ctx.create(name, ty)?;
    table_store::save_table(ctx.store, name, &table)?;
    if let Space::Phys {
        numbering,
        eliminated,
        ..
    } = space
    {
        dyna_store::save_layout(
            ctx.store,
            name,
            &dyna_store::Layout::of(numbering, eliminated),
        )?;
    }
    let shock_table = if shocks.is_empty() {
        None
    } else {
        let sub = tran_gene::shock_table_name(name);
        ctx.create(&sub, "table_sdaster")?;
        table_store::save_table(ctx.store, &sub, &shock_samples(name, shocks, tr)?)?;
        Some(sub)
    };
    let (base, numbering, basis) = match space {
        Space::Gene {
            numbering, basis, ..
        } => ("GENE", numbering.clone(), basis.clone()),
        Space::Phys { .. } => ("PHYS", String::new(), String::new()),
    };
    tran_gene::save_payload(
        ctx.store,
        name,
        &Payload {
            base: base.to_string(),
            numbering,
            basis,
            shocks: shocks
                .iter()
                .map(|s| StoredShock {
                    intitule: s.intitule.clone(),
                    node1: s.node1.clone(),
                    node2: s.node2.clone(),
                    obstacle: s.obstacle.clone(),
                    relation: s.relation.clone(),
                })
                .collect(),
            shock_table,
            supports: supports.to_vec(),
        },
    )?;
    // The absolute motion is restored from these (REST_GENE_PHYS, RECU_FONCTION with
    // MULT_APPUI='OUI'): a later change to one of them is reported there.
    for s in supports {
        for dep in [&s.mode_stat, &s.acce, &s.vite, &s.depl] {
            ctx.store.record_dependency(name, dep)?;
        }
    }
    Ok(())
}

/// The columns of a time history of `fields` (of DEPL, VITE, ACCE), as REST_MODE_NONL
/// writes them.
pub(crate) fn field_header(title: String, fields: &[&str]) -> Result<Table> {
    let mut t = Table::new(title);
    for (c, kind) in [
        ("NUME_ORDRE", ColKind::I),
        ("INST", ColKind::R),
        ("NOEUD", ColKind::K),
        ("NOM_CMP", ColKind::K),
    ] {
        t.add_column(c, kind)?;
    }
    for f in fields {
        t.add_column(f, ColKind::R)?;
    }
    Ok(t)
}

fn generalized_table(name: &str, tr: &Trajectory) -> Result<Table> {
    let mut t = Table::new(format!("DYNA_VIBRA {name}: generalized coordinates"));
    for (c, kind) in [
        ("NUME_ORDRE", ColKind::I),
        ("INST", ColKind::R),
        ("NUME_CMP", ColKind::I),
        ("DEPL", ColKind::R),
        ("VITE", ColKind::R),
        ("ACCE", ColKind::R),
    ] {
        t.add_column(c, kind)?;
    }
    for (i, time) in tr.t.iter().enumerate() {
        let (q, v, a) = (tr.q_at(i), tr.v_at(i), tr.a_at(i));
        for j in 0..tr.n {
            t.push_row(vec![
                Cell::I(i as i64 + 1),
                Cell::R(*time),
                Cell::I(j as i64 + 1),
                Cell::R(q[j]),
                Cell::R(v[j]),
                Cell::R(a[j]),
            ])?;
        }
    }
    Ok(t)
}

fn shock_samples(name: &str, shocks: &[ShockName], tr: &Trajectory) -> Result<Table> {
    let mut t = Table::new(format!("DYNA_VIBRA {name}: shocks"));
    for (c, kind) in [
        ("NUME_ORDRE", ColKind::I),
        ("INST", ColKind::R),
        ("INTITULE", ColKind::K),
        ("NOEUD", ColKind::K),
    ] {
        t.add_column(c, kind)?;
    }
    for p in ShockSample::NAMES {
        t.add_column(p, ColKind::R)?;
    }
    // Node 2's position: Code_Aster's internal variables 7 to 9 (VARI_INTERNE, VINTi).
    let two_nodes = shocks.iter().any(|s| s.node2.is_some());
    if two_nodes {
        for p in tran_gene::NODE2_POSITION {
            t.add_column(p, ColKind::R)?;
        }
    }
    // The internal variables a restart goes on from, for the laws that have them.
    let friction = shocks.iter().any(|s| s.friction);
    let buckling = shocks.iter().any(|s| s.relation == "FLAMBAGE");
    if friction {
        for p in tran_gene::FRICTION_MEMORY {
            t.add_column(p, ColKind::R)?;
        }
    }
    if buckling {
        for p in tran_gene::BUCKLING_MEMORY {
            t.add_column(p, ColKind::R)?;
        }
    }
    for (i, time) in tr.t.iter().enumerate() {
        for (s, shock) in shocks.iter().enumerate() {
            let sample = &tr.shocks[s][i];
            let mut row = vec![
                Cell::I(i as i64 + 1),
                Cell::R(*time),
                Cell::K(shock.intitule.clone()),
                Cell::K(shock.node1.clone()),
            ];
            row.extend(
                ShockSample::NAMES
                    .iter()
                    .map(|p| Cell::R(sample.get(p).unwrap_or(f64::NAN))),
            );
            if two_nodes {
                row.extend(sample.loc2.map(Cell::R));
            }
            if friction {
                row.extend(memory::friction(&sample.state).map(Cell::R));
            }
            if buckling {
                row.extend(memory::buckling(&sample.state).map(Cell::R));
            }
            t.push_row(row)?;
        }
    }
    Ok(t)
}
