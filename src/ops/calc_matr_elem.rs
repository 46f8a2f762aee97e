//! CALC_MATR_ELEM: element matrices RIGI_MECA / MASS_MECA / AMOR_MECA.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::elem::{compute_damping_matrices, parse_option, ElemError, GivenMatrices};
use crate::model::{
    compute_elem_matrices, ElemInputs, ElemMatrices, KinematicLoad, LoadKind, MatrixKind,
};
use crate::store::model::{
    load_cara_elem, load_elem_matrices, load_load, load_material_field, load_model_and_mesh,
    same_model, save_elem_matrices,
};
use crate::store::Store;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let option = args.req_text("OPTION")?;
    let (kind, lumped) = parse_option(option).ok_or_else(|| {
        Error::validation(format!("OPTION {option} is not supported"))
            .keyword("CALC_MATR_ELEM/OPTION")
            .hint("use RIGI_MECA, MASS_MECA, MASS_MECA_DIAG or AMOR_MECA")
    })?;
    let inputs = Inputs::from_args(args)?;
    let mats = if kind == MatrixKind::AmorMeca {
        let rigi = given(ctx.store, args, "RIGI_MECA")?;
        let mass = given(ctx.store, args, "MASS_MECA")?;
        let given = GivenMatrices {
            rigi: rigi.as_ref(),
            mass: mass.as_ref(),
        };
        let mats = inputs.damping_matrices(ctx.store, given)?;
        if mats.is_zero() {
            ctx.alarm("CALC_MATR_ELEM_1", NO_DAMPING)?;
        }
        mats
    } else {
        for key in ["RIGI_MECA", "MASS_MECA"] {
            if args.has(key) {
                return Err(Error::validation(format!(
                    "{key} is read by OPTION='AMOR_MECA' only, not by OPTION='{option}'"
                ))
                .keyword(args.key_path(key))
                .hint("remove it, or ask for OPTION='AMOR_MECA'"));
            }
        }
        let mats = inputs.elem_matrices(ctx.store, kind)?;
        if lumped {
            refuse_unlumped(ctx.store, &mats, "CALC_MATR_ELEM/OPTION")?;
        }
        mats
    };
    ctx.create(&name, "matr_elem_depl_r")?;
    save_elem_matrices(ctx.store, &name, &mats)
}

/// The message of the alarm of an AMOR_MECA matrix that is zero (CALC_MATR_ELEM_1,
/// ASSEMBLAGE_1): allowed, but likely not what was meant.
pub(crate) const NO_DAMPING: &str = "the AMOR_MECA matrix is zero: no material of the model \
     gives AMOR_ALPHA or AMOR_BETA (DEFI_MATERIAU ELAS) and no discrete element an A_ \
     characteristic (AFFE_CARA_ELEM DISCRET); a transient with it is undamped";

/// MASS_MECA_DIAG where the lumped mass would differ from the consistent one (an element
/// matrix with couplings): an error naming `keyword` and the cell.
pub(crate) fn refuse_unlumped(store: &Store, mats: &ElemMatrices, keyword: &str) -> Result<()> {
    let Some(cell) = mats.first_off_diagonal() else {
        return Ok(());
    };
    let mesh = crate::store::model::load_mesh(store, &mats.mesh)?;
    let name = mesh
        .cells
        .get(cell)
        .map(|c| c.name.clone())
        .unwrap_or_else(|| format!("#{}", cell + 1));
    Err(Error::validation(format!(
        "MASS_MECA_DIAG: the mass of cell {name} couples its DOFs, and aster-nl does not lump it \
         (it gives the lumped mass only where it equals the consistent one: discrete masses)"
    ))
    .keyword(keyword)
    .hint("ask for MASS_MECA (the consistent mass)"))
}

/// The element matrices given as `key` (RIGI_MECA or MASS_MECA of OPTION='AMOR_MECA').
fn given(store: &Store, args: &Args, key: &str) -> Result<Option<ElemMatrices>> {
    match args.concept(key) {
        Some(c) => Ok(Some(
            load_elem_matrices(store, &c.name).map_err(|e| e.keyword(args.key_path(key)))?,
        )),
        None => Ok(None),
    }
}

/// Concept names shared by CALC_MATR_ELEM and ASSEMBLAGE.
pub(crate) struct Inputs {
    pub model: String,
    pub cham_mater: Option<String>,
    pub cara_elem: Option<String>,
    pub charges: Vec<String>,
}

impl Inputs {
    pub(crate) fn from_args(args: &Args) -> Result<Inputs> {
        Ok(Inputs {
            model: args.req_concept("MODELE")?.name.clone(),
            cham_mater: args.concept("CHAM_MATER").map(|c| c.name.clone()),
            cara_elem: args.concept("CARA_ELEM").map(|c| c.name.clone()),
            charges: args
                .concepts("CHARGE")
                .unwrap_or_default()
                .into_iter()
                .map(|c| c.name)
                .collect(),
        })
    }

    /// The AFFE_CHAR_MECA loads of CHARGE, checked against the model.
    pub(crate) fn loads(&self, store: &Store) -> Result<Vec<(String, KinematicLoad)>> {
        let mut out = Vec::new();
        for c in &self.charges {
            let l = load_load(store, c)?;
            same_model("load", c, &l.model, &self.model).map_err(|e| e.keyword("CHARGE"))?;
            if l.kind != LoadKind::Meca {
                return Err(Error::input(format!("{c} is not an AFFE_CHAR_MECA load"))
                    .keyword("CHARGE")
                    .hint("AFFE_CHAR_CINE loads go to CHAR_CINE"));
            }
            out.push((c.clone(), l));
        }
        Ok(out)
    }

    pub(crate) fn elem_matrices(&self, store: &Store, kind: MatrixKind) -> Result<ElemMatrices> {
        self.compute(store, kind, |inp, loads| {
            compute_elem_matrices(kind, inp, loads)
        })
    }

    /// The AMOR_MECA element matrices, with the K_e and M_e of `given` where given.
    pub(crate) fn damping_matrices(
        &self,
        store: &Store,
        given: GivenMatrices<'_>,
    ) -> Result<ElemMatrices> {
        self.compute(store, MatrixKind::AmorMeca, |inp, loads| {
            compute_damping_matrices(inp, loads, given)
        })
    }

    /// Read the model, materials, characteristics and loads, and run `f` (element
    /// matrices of `kind`) on them.
    fn compute(
        &self,
        store: &Store,
        kind: MatrixKind,
        f: impl FnOnce(
            &ElemInputs<'_>,
            Vec<(String, KinematicLoad)>,
        ) -> std::result::Result<ElemMatrices, ElemError>,
    ) -> Result<ElemMatrices> {
        let (model, mesh) = load_model_and_mesh(store, &self.model)?;
        let field = match &self.cham_mater {
            Some(n) => {
                let f = load_material_field(store, n)?;
                if f.mesh != model.mesh {
                    return Err(Error::input(format!(
                        "CHAM_MATER {n} is on mesh {}, the model on {}",
                        f.mesh, model.mesh
                    ))
                    .keyword("CHAM_MATER"));
                }
                Some(f)
            }
            None => None,
        };
        let cara = match &self.cara_elem {
            Some(n) => {
                let c = load_cara_elem(store, n)?;
                same_model("CARA_ELEM", n, &c.model, &self.model)
                    .map_err(|e| e.keyword("CARA_ELEM"))?;
                Some(c)
            }
            None => None,
        };
        let inp = ElemInputs {
            model_name: &self.model,
            model: &model,
            mesh: &mesh,
            field: field.as_ref(),
            cara: cara.as_ref(),
        };
        f(&inp, self.loads(store)?).map_err(|e| elem_error(e, kind))
    }
}

/// What the element matrices of `kind` lack, named by the keyword of the concept that
/// should give it (CARA_ELEM, CHAM_MATER, RIGI_MECA, MASS_MECA), with what to do.
fn elem_error(e: ElemError, kind: MatrixKind) -> Error {
    let message = e.to_string();
    match e {
        ElemError::Incomplete(i) => super::affe_cara_elem::incomplete(i),
        ElemError::NoCharacteristics(_) => Error::input(message)
            .keyword("CARA_ELEM")
            .hint("discrete elements, beams and bars need AFFE_CARA_ELEM (DISCRET, POUTRE, BARRE)"),
        ElemError::NoElasticity(_) => Error::input(message)
            .keyword("CHAM_MATER")
            .hint("assign a material with ELAS=_F(E=..., NU=...) by AFFE_MATERIAU"),
        ElemError::NoDensity(_) if kind == MatrixKind::AmorMeca => Error::input(message)
            .keyword("CHAM_MATER")
            .hint("AMOR_BETA multiplies the mass matrix: add RHO to ELAS in DEFI_MATERIAU, or give AMOR_BETA=0"),
        ElemError::NoDensity(_) => Error::input(message)
            .keyword("CHAM_MATER")
            .hint("add RHO to ELAS in DEFI_MATERIAU"),
        ElemError::Given { kind: given, .. } => Error::input(message)
            .keyword(given.aster_name())
            .hint(format!(
                "give the {} element matrices CALC_MATR_ELEM computed on the same MODELE, or leave the keyword out to have them computed",
                given.aster_name()
            )),
        ElemError::Frame { .. } => Error::input(message).keyword("AFFE_CARA_ELEM/ORIENTATION"),
        ElemError::Other(e) => e,
    }
}
