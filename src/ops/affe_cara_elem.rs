//! AFFE_CARA_ELEM: discrete characteristics, beam and bar sections, orientations.

use super::common::section::{bar_section, beam_section};
use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::model::cara::{
    DiscreteAssignment, DiscreteSpec, Incomplete, OrientationAssignment, Repere, SectionAssignment,
};
use crate::model::frame::Orientation;
use crate::model::{CaraElem, Model};
use crate::store::model::{load_model_and_mesh, save_cara_elem};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let model_name = args.req_concept("MODELE")?.name.clone();
    let (model, mesh) = load_model_and_mesh(ctx.store, &model_name)?;
    let cara = cara_elem(&model_name, &model, &mesh, args)?;
    ctx.create(&name, "cara_elem")?;
    save_cara_elem(ctx.store, &name, &cara)
}

/// Read DISCRET / DISCRET_2D / POUTRE / BARRE / ORIENTATION, each occurrence just before
/// it is added (errors come in the user's order), then check that every element that
/// needs a characteristic got one.
pub(crate) fn cara_elem(
    model_name: &str,
    model: &Model,
    mesh: &Mesh,
    args: &Args,
) -> Result<CaraElem> {
    let mut cara = CaraElem::new(model_name, model);
    for key in ["DISCRET", "DISCRET_2D"] {
        for occ in args.facts_or_empty(key) {
            cara.add_discrete(model, mesh, &discrete(occ)?)?;
        }
    }
    for occ in args.facts_or_empty("POUTRE") {
        cara.add_beam(model, mesh, &section(occ, beam_section(occ)?))?;
    }
    for occ in args.facts_or_empty("BARRE") {
        cara.add_bar(model, mesh, &section(occ, bar_section(occ)?))?;
    }
    for occ in args.facts_or_empty("ORIENTATION") {
        let orientation = orientation(occ)?;
        cara.add_orientation(
            mesh,
            &OrientationAssignment {
                on: selection(occ),
                orientation,
            },
        )?;
    }
    cara.check_complete(model, mesh).map_err(incomplete)?;
    Ok(cara)
}

/// Elements left without a characteristic, named by the factor keyword that gives it.
pub(crate) fn incomplete(e: Incomplete) -> Error {
    let (factor, hint) = match e {
        Incomplete::Discrete(_) => (
            "DISCRET",
            Some("give each discrete element a K_..., M_... or A_... characteristic (a zero stiffness K_T_D_N=(0,0,0) is allowed)"),
        ),
        Incomplete::Beam(_) => ("POUTRE", None),
        Incomplete::Bar(_) => ("BARRE", None),
    };
    let err = Error::input(e.to_string()).keyword(format!("AFFE_CARA_ELEM/{factor}"));
    match hint {
        Some(h) => err.hint(h),
        None => err,
    }
}

/// One DISCRET or DISCRET_2D occurrence.
fn discrete(occ: &Args) -> Result<DiscreteAssignment> {
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
    let repere = match occ.req_text("REPERE")? {
        "LOCAL" => Repere::Local,
        _ => Repere::Global,
    };
    Ok(DiscreteAssignment {
        on: selection(occ),
        cara: name,
        spec,
        values: occ.reals("VALE").unwrap_or_default(),
        repere,
        keyword: occ.path.clone(),
        cara_keyword: occ.key_path("CARA"),
        values_keyword: occ.key_path("VALE"),
    })
}

/// A POUTRE or BARRE occurrence with its section.
fn section(occ: &Args, section: crate::model::cara::Section) -> SectionAssignment {
    SectionAssignment {
        on: selection(occ),
        section,
        keyword: occ.path.clone(),
    }
}

/// ORIENTATION's CARA and VALE.
fn orientation(occ: &Args) -> Result<Orientation> {
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
