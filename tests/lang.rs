//! Robustness of the `.comm` language: whatever the input, `parse` and `execute` return
//! (an error or success) and never panic or overflow the stack.

use aster_nl::error::Result;
use aster_nl::lang::{self, Env, Host, Source};
use aster_nl::value::{CommandCall, ConceptRef, Value};
use proptest::prelude::*;

/// Accepts every upper-case name as an operator and returns a concept.
struct AnyOperator;

impl Host for AnyOperator {
    fn is_operator(&self, name: &str) -> bool {
        name.chars().next().is_some_and(|c| c.is_ascii_uppercase())
    }
    fn call(&mut self, call: CommandCall) -> Result<Value> {
        Ok(Value::Concept(ConceptRef {
            name: call.result.unwrap_or_default(),
            ty: "x".into(),
        }))
    }
    fn lookup_concept(&self, name: &str) -> Option<ConceptRef> {
        Some(ConceptRef {
            name: name.into(),
            ty: "co".into(),
        })
    }
    fn print(&mut self, _text: &str) {}
}

/// Parses and runs; also renders any error (rendering must not panic either).
fn run(text: &str) -> bool {
    let src = Source::new("fuzz.comm", text);
    let result = lang::run(&src, &mut Env::new(), &mut AnyOperator);
    if let Err(e) = &result {
        let r = lang::render_plain(e, Some(&src));
        assert!(r.starts_with("  × "), "{r}");
        assert!(r.contains(&e.message), "{r}");
        if let Some(loc) = &e.location {
            assert!(loc.span.line >= 1 && loc.span.col >= 1, "{e}");
            assert!(
                loc.span.start <= loc.span.end && loc.span.end <= text.len(),
                "{e}"
            );
        }
    }
    result.is_ok()
}

const TOKENS: &[&str] = &[
    "DEBUT",
    "FIN",
    "MAIL",
    "LIRE_MAILLAGE",
    "_F",
    "CO",
    "reuse",
    "x",
    "k",
    "i",
    "L",
    "math",
    "sqrt",
    "pi",
    "range",
    "len",
    "max",
    "for",
    "in",
    "from",
    "import",
    "*",
    "as",
    "=",
    "+",
    "-",
    "*",
    "/",
    "//",
    "%",
    "**",
    "+=",
    "(",
    ")",
    "[",
    "]",
    ",",
    ";",
    ":",
    ".",
    "1",
    "0",
    "2.5",
    ".5",
    "1.e4",
    "2E-3",
    "99999999999999999999",
    "'a'",
    "\"b\"",
    "'''c'''",
    "#c",
    "\n",
    "\n    ",
    "\n\t",
    "\\\n",
    " ",
    "True",
    "None",
    "def",
    "if",
    "{",
    "}",
    "'",
    "\"",
    "\\",
    "é",
];

fn token_soup() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(TOKENS), 0..60).prop_map(|t| t.join(" "))
}

/// Small valid-looking statements, so that the soup also reaches the evaluator.
fn statements() -> impl Strategy<Value = String> {
    let stmt = prop_oneof![
        Just("x = 1".to_string()),
        Just("L = (1, 2.5, 'a')".to_string()),
        Just("from math import *".to_string()),
        Just("MAIL = LIRE_MAILLAGE(UNITE=20)".to_string()),
        Just("for i in range(3):".to_string()),
        Just("    x = x * i".to_string()),
        Just("DEBUT(A=_F(B=L[-1]), C=CO('N'))".to_string()),
        Just("k = x ** 40".to_string()),
        Just("x = L * 3".to_string()),
        Just("x = 'a' * x".to_string()),
        Just("x = sqrt(x) / (x - 1)".to_string()),
        Just("MAIL = LIRE_MAILLAGE(reuse=MAIL, X=x)".to_string()),
        token_soup(),
    ];
    prop::collection::vec(stmt, 0..12).prop_map(|s| s.join("\n"))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        run(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn token_soups_never_panic(text in token_soup()) {
        run(&text);
    }

    #[test]
    fn statement_mixes_never_panic(text in statements()) {
        run(&text);
    }
}

#[test]
fn deepest_accepted_nesting_fits_on_a_test_thread_stack() {
    // 64 levels is the scanner's limit; each kind of bracket goes through different rules.
    let parens = format!("x = {}1{}", "(".repeat(64), ")".repeat(64));
    assert!(run(&parens));
    let lists = format!("x = {}1{}", "[".repeat(64), "]".repeat(64));
    assert!(run(&lists));
    let calls = format!("x = {}1{}", "_F(A=".repeat(64), ")".repeat(64));
    assert!(run(&calls));
    let mixed = format!("x = {}1{}", "abs(-(".repeat(32), "))".repeat(32));
    assert!(run(&mixed));
}

#[test]
fn crlf_files_work() {
    let text = "from math import *\r\nk = 4.\r\nfor i in (1, 2):\r\n    x = sqrt(k) * i\r\nDEBUT(A=(1,\r\n  2))\r\n";
    let src = Source::new("crlf.comm", text);
    let mut env = Env::new();
    lang::run(&src, &mut env, &mut AnyOperator).unwrap();
    assert_eq!(env.get("x"), Some(&Value::Real(4.0)));
}
