use super::*;

#[test]
fn catalogs_parse_and_are_consistent() {
    let problems = check_consistency();
    assert!(problems.is_empty(), "catalog problems:\n{}", problems.join("\n"));
    assert!(operator_names().contains(&"MODE_NON_LINE"));
}
