//! MODI_MAILLAGE: moves the nodes of a mesh in place (reuse): DEFORME/ALEA, TRANSLATION,
//! ECHELLE, in Code_Aster's order. The numerics are in `mesh::transform`.

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::mesh::transform::{self, SplitMix64, PERTURBATION_SEED};
use crate::store::mesh::{load_mesh, save_mesh};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let source = args.req_concept("MAILLAGE")?.name.clone();
    let mut mesh = load_mesh(ctx.store, &source)?;

    if let Some(def) = args.fact("DEFORME") {
        let alea = def.req_real("ALEA")?;
        let largest = transform::perturb(&mut mesh, alea, &mut SplitMix64::new(PERTURBATION_SEED));
        ctx.say(&format!(
            "{name}: DEFORME/ALEA={alea:e}: {} node(s) moved at random, by at most {largest:.3e} along a coordinate",
            mesh.nodes.len()
        ))?;
    }
    if let Some(t) = args.reals("TRANSLATION") {
        let mut v = [0.0; 3];
        for (d, x) in v.iter_mut().zip(&t) {
            *d = *x;
        }
        transform::translate(&mut mesh, v);
    }
    if let Some(f) = args.real("ECHELLE") {
        transform::scale(&mut mesh, f);
    }
    if ctx.info >= 2 {
        ctx.say(&format!("{name}: {}", mesh.summary()))?;
    }
    let exists = ctx.store.concept_type(&name)?.as_deref() == Some("maillage_sdaster");
    if !(exists && ctx.reuse == Some(name.as_str())) {
        ctx.create(&name, "maillage_sdaster")?;
    }
    save_mesh(ctx.store, &name, &mesh)
}
