//! Persistence of function concepts: a `fonction_sdaster` is one json payload (its points),
//! a `formule` another (its parameters, its expression, its constants).

use super::Store;
use crate::error::{Error, Result};
use crate::function::formula::{AnyFunction, Formula, FormulaDef};
use crate::function::Function;

const KEY: &str = "function";
const FORMULA_KEY: &str = "formula";

/// Save the formula `def` under the (registered) concept `concept`.
pub fn save_formula(store: &Store, concept: &str, def: &FormulaDef) -> Result<()> {
    store.put_json(concept, FORMULA_KEY, def)
}

/// Load the formula concept `concept`, parsed and checked again.
pub fn load_formula(store: &Store, concept: &str) -> Result<Formula> {
    let def: FormulaDef = store.get_json(concept, FORMULA_KEY)?;
    Formula::new(concept, def).map_err(|e| Error {
        message: format!("stored formula {concept}: {}", e.message),
        ..e
    })
}

/// The function of one parameter `concept`: a `fonction_sdaster` (DEFI_FONCTION,
/// RECU_FONCTION, CALC_FONC_INTERP...) or a `formule` of one parameter.
pub fn load_any_function(store: &Store, concept: &str) -> Result<AnyFunction> {
    match store.concept_type(concept)?.as_deref() {
        Some("formule") => AnyFunction::of_formula(load_formula(store, concept)?),
        _ => load_function(store, concept).map(AnyFunction::Tabulated),
    }
}

/// Save `f` under the (registered) concept `concept`.
pub fn save_function(store: &Store, concept: &str, f: &Function) -> Result<()> {
    store.put_json(concept, KEY, f)
}

/// Load the function concept `concept`; its `name` is the concept's name.
pub fn load_function(store: &Store, concept: &str) -> Result<Function> {
    let mut f: Function = store.get_json(concept, KEY)?;
    f.name = concept.to_string();
    f.check()?;
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::function::{Interp, Prol};

    #[test]
    fn round_trip() {
        let s = Store::in_memory().unwrap();
        s.register_concept("F", "fonction_sdaster", "DEFI_FONCTION", "t.comm", 1)
            .unwrap();
        let mut f = Function::new("F", "FREQ", "AMOR", vec![1.0, 2.0], vec![0.1, 0.3]).unwrap();
        f.interpol = (Interp::Lin, Interp::Log);
        f.prol_droite = Prol::Constant;
        save_function(&s, "F", &f).unwrap();
        assert_eq!(load_function(&s, "F").unwrap(), f);
        // A fonction_sdaster read as any function is the same function.
        let any = load_any_function(&s, "F").unwrap();
        assert_eq!(any.eval(1.5).unwrap(), f.eval(1.5).unwrap());
    }

    #[test]
    fn formula_round_trip() {
        let s = Store::in_memory().unwrap();
        s.register_concept("G", "formule", "FORMULE", "t.comm", 1)
            .unwrap();
        let def = FormulaDef {
            nom_para: vec!["INST".into()],
            vale: "A*INST**2".into(),
            constants: vec![("A".into(), 0.5)],
        };
        save_formula(&s, "G", &def).unwrap();
        assert_eq!(load_formula(&s, "G").unwrap().def(), &def);
        let g = load_any_function(&s, "G").unwrap();
        assert_eq!((g.name(), g.nom_para()), ("G", "INST"));
        assert_eq!(g.eval(3.0).unwrap(), 0.5 * 3.0f64.powf(2.0));
    }
}
