//! "Did you mean" for every kind of name a user types: operators, keywords, Python
//! variables. One rule everywhere, so a typo is caught the same way wherever it is made.
//!
//! Distance: optimal-string-alignment (Levenshtein plus the swap of two neighbouring
//! characters as one edit, the commonest typo: `JUE` for `JEU`), case-insensitive, since
//! Code_Aster's names are upper case and users type `info=` as often as `INFO=`.
//! Closeness: at most one edit per three characters (at least one), so long Code_Aster names
//! with two or three typos are still found while short names do not match everything.
//! Bounded by length: a name longer than [`MAX_NAME`] gets no suggestion, and a candidate
//! whose length alone puts it too far is not compared, so that a hostile 70,000-character
//! name costs nothing (the distance is quadratic in the lengths).

/// The longest name suggestions are searched for (Code_Aster's names are 8 to 16
/// characters; Python variables of a command file rarely pass 30).
pub const MAX_NAME: usize = 64;

/// Edits (insert, delete, substitute, swap of neighbours) between two names, case-insensitive.
pub fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().flat_map(char::to_uppercase).collect();
    let b: Vec<char> = b.chars().flat_map(char::to_uppercase).collect();
    // Three rows of the dynamic programme: two back (for swaps), one back, current.
    let mut before: Vec<usize> = vec![0; b.len() + 1];
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for i in 0..a.len() {
        cur[0] = i + 1;
        for j in 0..b.len() {
            let subst = prev[j] + usize::from(a[i] != b[j]);
            let mut d = subst.min(prev[j + 1] + 1).min(cur[j] + 1);
            if i > 0 && j > 0 && a[i] == b[j - 1] && a[i - 1] == b[j] {
                d = d.min(before[j - 1] + 1);
            }
            cur[j + 1] = d;
        }
        std::mem::swap(&mut before, &mut prev);
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// Up to three candidates close to `name`, closest first (ties in the candidates' order of
/// sorting); a candidate differing only in case always counts as close.
pub fn closest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Vec<&'a str> {
    let len = name.chars().count();
    if len > MAX_NAME {
        return Vec::new();
    }
    let limit = (len / 3).max(1);
    let mut scored: Vec<(usize, &str)> = candidates
        .into_iter()
        // Every edit changes the length by one at most: a far length is a far name.
        .filter(|c| c.len() <= 4 * (MAX_NAME + limit) && c.chars().count().abs_diff(len) <= limit)
        .map(|c| (distance(name, c), c))
        .filter(|(d, _)| *d <= limit)
        .collect();
    scored.sort();
    scored.dedup_by(|a, b| a.1 == b.1);
    scored.into_iter().take(3).map(|(_, c)| c).collect()
}

/// "did you mean 'A' or 'B'? " for the candidates close to `name` (empty when none is):
/// the start of a hint.
pub fn did_you_mean<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    match closest(name, candidates).as_slice() {
        [] => String::new(),
        c => format!(
            "did you mean {}? ",
            c.iter()
                .map(|n| format!("'{n}'"))
                .collect::<Vec<_>>()
                .join(" or ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_counts_edits() {
        assert_eq!(distance("JEU", "JEU"), 0);
        assert_eq!(
            distance("JEU", "JUE"),
            1,
            "a swap of neighbours is one edit"
        );
        assert_eq!(distance("RIGI_NOR", "RIGINOR"), 1);
        assert_eq!(distance("info", "INFO"), 0);
        assert_eq!(distance("", "ABC"), 3);
        // The textbook Levenshtein example (no swap in it).
        assert_eq!(distance("kitten", "sitting"), 3);
        // Optimal string alignment: a swapped pair is not edited again.
        assert_eq!(distance("CA", "ABC"), 3);
    }

    #[test]
    fn closest_ranks_and_filters() {
        let c = ["MATR_RIGI", "MATR_MASS", "CHOC", "INFO"];
        assert_eq!(closest("MATR_RIGU", c), vec!["MATR_RIGI"]);
        assert_eq!(closest("MATR_MAS", c), vec!["MATR_MASS"]);
        assert_eq!(closest("CHCO", c), vec!["CHOC"]);
        assert_eq!(closest("info", c), vec!["INFO"]);
        assert!(closest("ZZZZZZZZZ", c).is_empty());
        // A short name is not close to every short name.
        assert!(closest("XY", ["AB", "CD"]).is_empty());
    }

    #[test]
    fn long_names_are_not_compared() {
        // Two 1,000-character names one edit apart: compared, they would be "close" (and a
        // 70,000-character pair would take 4.9e9 steps); past MAX_NAME none is searched.
        let defined = "A".repeat(1000);
        let typed = format!("{}B", "A".repeat(999));
        assert!(closest(&typed, [defined.as_str()]).is_empty());
        assert_eq!(
            closest("MATR_RIGU", [defined.as_str(), "MATR_RIGI"]),
            vec!["MATR_RIGI"]
        );
        let at_bound = "A".repeat(MAX_NAME);
        let near = format!("{}B", "A".repeat(MAX_NAME - 1));
        assert_eq!(closest(&near, [at_bound.as_str()]), vec![at_bound.as_str()]);
    }
}
