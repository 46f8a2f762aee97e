//! "Did you mean" hints: the known names closest to a misspelt one.

pub use crate::suggest::closest;

/// A hint naming the closest candidates, or listing all of them when none is close.
pub fn hint(name: &str, candidates: &[&str]) -> String {
    let near = closest(name, candidates.iter().copied());
    if near.is_empty() {
        format!("allowed: {}", candidates.join(", "))
    } else {
        format!("did you mean {}?", near.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hint_names_the_close_ones_or_lists_all() {
        let c = ["MATR_RIGI", "MATR_MASS", "CHOC", "INFO"];
        assert_eq!(hint("MATR_RIGU", &c), "did you mean MATR_RIGI?");
        assert!(hint("ZZZZZZZZZ", &c).starts_with("allowed: MATR_RIGI"));
    }
}
