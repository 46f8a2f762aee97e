//! Persistence of function concepts (`fonction_sdaster`): one json payload.

use super::Store;
use crate::error::Result;
use crate::function::Function;

const KEY: &str = "function";

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
    }
}
