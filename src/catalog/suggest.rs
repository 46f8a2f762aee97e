//! "Did you mean" hints: the known names closest to a misspelt one.

/// Levenshtein distance between two names, case-insensitive (users type `info=` for `INFO=`).
pub fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().flat_map(char::to_uppercase).collect();
    let b: Vec<char> = b.chars().flat_map(char::to_uppercase).collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for (i, ca) in a.iter().enumerate() {
        cur[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let subst = prev[j] + usize::from(ca != cb);
            cur[j + 1] = subst.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// Up to three candidates close to `name`, best first. "Close" grows with the length of the
/// name so that long Code_Aster names with one or two typos are still found.
pub fn closest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Vec<&'a str> {
    let limit = (name.chars().count() / 3).max(2);
    let mut scored: Vec<(usize, &str)> = candidates
        .into_iter()
        .map(|c| (distance(name, c), c))
        .filter(|(d, c)| *d <= limit || c.eq_ignore_ascii_case(name))
        .collect();
    scored.sort();
    scored.dedup_by(|a, b| a.1 == b.1);
    scored.into_iter().take(3).map(|(_, c)| c).collect()
}

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
    fn distance_counts_edits() {
        assert_eq!(distance("JEU", "JEU"), 0);
        assert_eq!(distance("JEU", "JUE"), 2);
        assert_eq!(distance("RIGI_NOR", "RIGINOR"), 1);
        assert_eq!(distance("info", "INFO"), 0);
        assert_eq!(distance("", "ABC"), 3);
    }

    #[test]
    fn closest_ranks_and_filters() {
        let c = ["MATR_RIGI", "MATR_MASS", "CHOC", "INFO"];
        assert_eq!(closest("MATR_RIGU", c), vec!["MATR_RIGI"]);
        assert_eq!(closest("MATR_MAS", c), vec!["MATR_MASS"]);
        assert!(closest("ZZZZZZZZZ", c).is_empty());
        assert!(hint("ZZZZZZZZZ", &c).starts_with("allowed: MATR_RIGI"));
    }
}
