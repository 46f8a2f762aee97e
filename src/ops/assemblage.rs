//! ASSEMBLAGE macro: element matrices, numbering, assembled matrices and load vectors in
//! one call; the numbering, each matrix and each vector are new concepts named by CO('...').

use super::asse_vecteur::nodal_forces;
use super::calc_matr_elem::Inputs;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::elem::GivenMatrices;
use crate::model::{assemble, ElemMatrices, KinematicLoad, LoadKind, MatrixKind};
use crate::store::function::load_function;
use crate::store::gene::save_field;
use crate::store::matrix::{load_numbering, save_matrix, save_numbering};
use crate::store::model::{load_load, load_mesh, same_model};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let inputs = Inputs::from_args(args)?;
    let occs = args.facts_or_empty("MATR_ASSE");
    let mut wanted = Vec::new();
    // The MASS_MECA_DIAG requests (checked once their element matrices are computed).
    let mut lumped_keys: Vec<(String, String)> = Vec::new();
    for occ in occs {
        let co = occ.co("MATRICE").ok_or_else(|| {
            Error::validation("expected CO('NAME')").keyword(occ.key_path("MATRICE"))
        })?;
        let option = occ.req_text("OPTION")?;
        let (kind, lumped) = crate::model::elem::parse_option(option).ok_or_else(|| {
            Error::validation(format!("OPTION {option} is not supported"))
                .keyword(occ.key_path("OPTION"))
                .hint("use RIGI_MECA, MASS_MECA, MASS_MECA_DIAG or AMOR_MECA")
        })?;
        if lumped {
            lumped_keys.push((co.to_string(), occ.key_path("OPTION")));
        }
        // Two matrices under one name: the second would silently replace the first.
        let vector = |c: &str| {
            args.facts_or_empty("VECT_ASSE")
                .iter()
                .any(|v| v.co("VECTEUR") == Some(c))
        };
        if wanted.iter().any(|(w, _)| w == co) || args.co("NUME_DDL") == Some(co) || vector(co) {
            return Err(Error::validation(format!(
                "CO('{co}') is given twice: each result of ASSEMBLAGE needs its own name"
            ))
            .keyword(occ.key_path("MATRICE")));
        }
        wanted.push((co.to_string(), kind));
    }
    // Element matrices of each requested kind (the stiffness defines the numbering, as in
    // Code_Aster, whatever the order of MATR_ASSE). The damping is computed last, from the
    // stiffness and mass element matrices of the same call when it asks for them.
    let mut elems: Vec<(String, ElemMatrices)> = Vec::new();
    for (co, kind) in wanted.iter().filter(|(_, k)| *k != MatrixKind::AmorMeca) {
        let mats = inputs.elem_matrices(ctx.store, *kind)?;
        if let Some((_, key)) = lumped_keys.iter().find(|(c, _)| c == co) {
            super::calc_matr_elem::refuse_unlumped(ctx.store, &mats, key)?;
        }
        elems.push((co.clone(), mats));
    }
    for (co, _) in wanted.iter().filter(|(_, k)| *k == MatrixKind::AmorMeca) {
        let of_kind = |kind| elems.iter().find(|(_, m)| m.kind == kind).map(|(_, m)| m);
        let given = GivenMatrices {
            rigi: of_kind(MatrixKind::RigiMeca),
            mass: of_kind(MatrixKind::MassMeca),
        };
        let damping = inputs.damping_matrices(ctx.store, given)?;
        if damping.is_zero() {
            ctx.alarm("ASSEMBLAGE_1", super::calc_matr_elem::NO_DAMPING)?;
        }
        elems.push((co.clone(), damping));
    }
    // The concepts in the order of MATR_ASSE.
    elems.sort_by_key(|(co, _)| wanted.iter().position(|(w, _)| w == co));
    let (num_name, num) = match (args.co("NUME_DDL"), args.concept("NUME_DDL")) {
        (Some(co), _) => {
            let base = match elems.iter().find(|(_, m)| m.kind == MatrixKind::RigiMeca) {
                Some((_, m)) => m.clone(),
                None => inputs.elem_matrices(ctx.store, MatrixKind::RigiMeca)?,
            };
            let mesh = load_mesh(ctx.store, &base.mesh)?;
            let num = crate::model::DofNumbering::from_elem_matrices(&mesh, &[&base])
                .map_err(super::nume_ddl::numbering_error)?;
            ctx.create(co, "nume_ddl_sdaster")?;
            save_numbering(ctx.store, co, &num)?;
            (co.to_string(), num)
        }
        (None, Some(c)) => (c.name.clone(), load_numbering(ctx.store, &c.name)?),
        (None, None) => {
            return Err(
                Error::validation("NUME_DDL is required (CO('NAME') or a numbering)")
                    .keyword("ASSEMBLAGE/NUME_DDL"),
            )
        }
    };
    let mut cine = Vec::new();
    for c in args.concepts("CHAR_CINE").unwrap_or_default() {
        let l = load_load(ctx.store, &c.name)?;
        same_model("CHAR_CINE", &c.name, &l.model, &inputs.model)
            .map_err(|e| e.keyword("CHAR_CINE"))?;
        if l.kind != LoadKind::Cine {
            return Err(
                Error::input(format!("{} is not an AFFE_CHAR_CINE load", c.name))
                    .keyword("CHAR_CINE"),
            );
        }
        cine.push(l);
    }
    let crefs: Vec<&KinematicLoad> = cine.iter().collect();
    let mesh = load_mesh(ctx.store, &num.mesh)?;
    for (co, m) in &elems {
        let a = assemble(&num, &mesh, &[m], &crefs).map_err(super::asse_matrice::assembly_error)?;
        ctx.create(co, "matr_asse_depl_r")?;
        save_matrix(ctx.store, co, &a, &num_name)?;
    }
    for occ in args.facts_or_empty("VECT_ASSE") {
        let co = occ.co("VECTEUR").ok_or_else(|| {
            Error::validation("expected CO('NAME')").keyword(occ.key_path("VECTEUR"))
        })?;
        let charges: Vec<String> = occ
            .concepts("CHARGE")
            .unwrap_or_default()
            .into_iter()
            .map(|c| c.name)
            .collect();
        let factor = match occ.concept("FONC_MULT") {
            Some(f) => load_function(ctx.store, &f.name)?
                .eval(occ.req_real("INST")?)
                .map_err(|e| e.keyword(occ.key_path("FONC_MULT")))?,
            None => 1.0,
        };
        let field = nodal_forces(
            ctx.store,
            &num,
            &num_name,
            &charges,
            factor,
            (&occ.key_path("CHARGE"), "ASSEMBLAGE/NUME_DDL"),
        )?;
        ctx.create(co, "cham_no_sdaster")?;
        save_field(ctx.store, co, &field)?;
    }
    Ok(())
}
