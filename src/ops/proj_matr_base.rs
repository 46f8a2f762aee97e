//! PROJ_MATR_BASE: the generalized matrix ΦᵀAΦ of an assembled matrix on a basis.

use super::common::gene::{numbering_and_basis, vectors};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::linalg::projection::project_matrix;
use crate::model::MatrixKind;
use crate::store::gene::{self, GeneMatrix, GeneMeta};
use crate::store::matrix;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let num_name = args.req_concept("NUME_DDL_GENE")?.name.clone();
    let base = args.req_concept("BASE")?.name.clone();
    let a_name = args.req_concept("MATR_ASSE")?.name.clone();
    project(
        ctx,
        &name,
        &num_name,
        &base,
        &a_name,
        "PROJ_MATR_BASE",
        "PROJ_MATR_BASE/MATR_ASSE",
    )
}

/// Above this relative coupling |a_ij|/√|a_ii a_jj| the off-diagonal terms STOCKAGE='DIAG'
/// drops are not round-off (normal modes give 1e-12 or less).
const DIAG_COUPLING_ALARM: f64 = 1e-6;

/// Create `name`, the generalized matrix of `a_name` on the basis `base` numbered by
/// `num_name` (PROJ_MATR_BASE, and PROJ_BASE for each MATR_ASSE_GENE). `op` prefixes the
/// keyword paths of errors about the numbering, `matrix_key` is the path of the matrix.
pub(crate) fn project(
    ctx: &mut OpContext<'_>,
    name: &str,
    num_name: &str,
    base: &str,
    a_name: &str,
    op: &str,
    matrix_key: &str,
) -> Result<()> {
    let (num, modes) = numbering_and_basis(ctx.store, num_name, Some(base), op)?;
    let a = matrix::load_matrix(ctx.store, a_name)?;
    if a.numbering.dofs != modes.numbering.dofs {
        return Err(Error::input(format!(
            "{a_name} is not assembled on the DOF numbering of the basis {base}"
        ))
        .keyword(matrix_key)
        .hint(
            "assemble the matrix with the NUME_DDL of the matrices the modes were computed from",
        ));
    }
    let mut values = project_matrix(a.size(), &a.triplets, &vectors(&modes))?;
    if num.storage == "DIAG" {
        // Code_Aster's diagonal storage keeps the diagonal only (a basis orthogonal for
        // the matrix: the rest is round-off). A basis that is not (a Ritz basis, a
        // non-proportional damping) loses real couplings: say how large.
        let n = num.size;
        let coupling = (0..n * n)
            .filter(|k| k / n != k % n)
            .map(|k| {
                let (i, j) = (k / n, k % n);
                let scale = (values[i * n + i] * values[j * n + j]).abs().sqrt();
                if scale > 0.0 {
                    values[k].abs() / scale
                } else {
                    0.0
                }
            })
            .fold(0.0f64, f64::max);
        if coupling > DIAG_COUPLING_ALARM {
            ctx.alarm(
                "PROJ_MATR_BASE_1",
                &format!(
                    "{name}: {base} is not orthogonal for {a_name}, and STOCKAGE='DIAG' drops \
                     couplings up to {coupling:.1e} of the diagonal terms; number the basis \
                     with STOCKAGE='PLEIN' to keep them"
                ),
            )?;
        }
        for (k, v) in values.iter_mut().enumerate() {
            if k / num.size != k % num.size {
                *v = 0.0;
            }
        }
    }
    let kind = match a.kind {
        MatrixKind::RigiMeca => "RIGI",
        MatrixKind::MassMeca => "MASS",
        MatrixKind::AmorMeca => "AMOR",
    };
    ctx.create(name, "matr_asse_gene_r")?;
    ctx.store.record_dependency(name, num_name)?;
    gene::save_matrix(
        ctx.store,
        name,
        &GeneMatrix {
            meta: GeneMeta {
                numbering: num_name.to_string(),
                basis: base.to_string(),
                size: num.size,
                kind: kind.to_string(),
            },
            values,
        },
    )
}
