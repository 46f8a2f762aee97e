//! Grammar and evaluation tests: every construct of the subset, and every error kind with
//! its message, line and column.

use super::*;
use crate::error::{Error, ErrorKind};
use crate::value::{CommandCall, ConceptRef, Keyword, Value};

/// Accepts the operators below, records every call and returns a concept named like the
/// result (type: the operator name in lower case).
#[derive(Default)]
struct Recorder {
    calls: Vec<CommandCall>,
    printed: Vec<String>,
}

/// Every `CO('NAME')` in a call's keywords, at any depth.
fn co_names(values: &[&Value], out: &mut Vec<String>) {
    for v in values {
        match v {
            Value::Co(n) => out.push(n.clone()),
            Value::Seq(items) => co_names(&items.iter().collect::<Vec<_>>(), out),
            Value::Fact(kws) => co_names(&kws.iter().map(|k| &k.value).collect::<Vec<_>>(), out),
            _ => {}
        }
    }
}

const OPS: &[&str] = &[
    "DEBUT",
    "FIN",
    "LIRE_MAILLAGE",
    "AFFE_MODELE",
    "AFFE_MATERIAU",
    "AFFE_CARA_ELEM",
    "ASSEMBLAGE",
    "MODE_NON_LINE",
    "CREA_TABLE",
    "TEST_TABLE",
    "FAIL",
];

impl Host for Recorder {
    fn is_operator(&self, name: &str) -> bool {
        OPS.contains(&name)
    }
    fn call(&mut self, call: CommandCall) -> crate::error::Result<Value> {
        if call.op == "FAIL" {
            return Err(Error::validation("FAIL always fails"));
        }
        let v = Value::Concept(ConceptRef {
            name: call.result.clone().unwrap_or_default(),
            ty: call.op.to_lowercase(),
        });
        self.calls.push(call);
        Ok(v)
    }
    fn operator_names(&self) -> Vec<String> {
        OPS.iter().map(|s| s.to_string()).collect()
    }
    /// The concepts the recorded calls created through CO('NAME'), as a real host's store
    /// would know them.
    fn lookup_concept(&self, name: &str) -> Option<ConceptRef> {
        let mut created = Vec::new();
        for c in &self.calls {
            co_names(
                &c.args.iter().map(|k| &k.value).collect::<Vec<_>>(),
                &mut created,
            );
        }
        created.iter().any(|n| n == name).then(|| ConceptRef {
            name: name.into(),
            ty: "co".into(),
        })
    }
    fn print(&mut self, text: &str) {
        self.printed.push(text.to_string());
    }
}

fn run_ok(text: &str) -> (Env, Recorder) {
    let src = Source::new("t.comm", text);
    let mut env = Env::new();
    let mut host = Recorder::default();
    if let Err(e) = run(&src, &mut env, &mut host) {
        panic!("unexpected error:\n{}", render_plain(&e, Some(&src)));
    }
    (env, host)
}

fn val(text: &str, name: &str) -> Value {
    let (env, _) = run_ok(text);
    env.get(name)
        .cloned()
        .unwrap_or_else(|| panic!("{name} not bound"))
}

/// The error, checked to point at `line:col` of t.comm.
fn run_err(text: &str, line: usize, col: usize) -> Error {
    run_err_limited(text, line, col, Limits::default())
}

fn run_err_limited(text: &str, line: usize, col: usize, limits: Limits) -> Error {
    let src = Source::new("t.comm", text);
    let mut env = Env::new();
    env.limits = limits;
    let e = match run(&src, &mut env, &mut Recorder::default()) {
        Ok(()) => panic!("no error for {text:?}"),
        Err(e) => e,
    };
    let loc = e
        .location
        .clone()
        .unwrap_or_else(|| panic!("no location: {e}"));
    assert_eq!(loc.file, "t.comm");
    assert_eq!((loc.span.line, loc.span.col), (line, col), "{e}");
    e
}

fn kw<'a>(kws: &'a [Keyword], name: &str) -> &'a Value {
    &kws.iter()
        .find(|k| k.name == name)
        .unwrap_or_else(|| panic!("no {name}"))
        .value
}

use Value::{Int, Real, Seq, Str};

// ---- numbers, strings, containers ------------------------------------------------

#[test]
fn numbers_in_every_python_form() {
    let (env, _) = run_ok("a=1\nb=1.\nc=.5\nd=1.e4\ne=2E-3\nf=-1\ng=1.5e+2\nh=007");
    let got: Vec<Value> = ["a", "b", "c", "d", "e", "f", "g", "h"]
        .iter()
        .map(|n| env.get(n).cloned().unwrap())
        .collect();
    assert_eq!(
        got,
        vec![
            Int(1),
            Real(1.),
            Real(0.5),
            Real(1.0e4),
            Real(2e-3),
            Int(-1),
            Real(150.),
            Int(7)
        ]
    );
}

#[test]
fn strings_quotes_escapes_and_concatenation() {
    assert_eq!(val("s='a\"b'", "s"), Str("a\"b".into()));
    assert_eq!(val("s=\"it's\"", "s"), Str("it's".into()));
    assert_eq!(val(r"s='a\'b\n\\'", "s"), Str("a'b\n\\".into()));
    assert_eq!(val("s='ab' \"cd\"", "s"), Str("abcd".into()));
    assert_eq!(val("s='ab' + 'cd'", "s"), Str("abcd".into()));
    assert_eq!(val("s='''x\ny'''", "s"), Str("x\ny".into()));
    assert_eq!(val(r"s=r'C:\d'", "s"), Str(r"C:\d".into()));
    assert_eq!(
        val("s='#not a comment'  # a comment", "s"),
        Str("#not a comment".into())
    );
}

#[test]
fn tuples_lists_and_trailing_commas() {
    assert_eq!(val("t=(1,)", "t"), Seq(vec![Int(1)]));
    assert_eq!(val("t=(1)", "t"), Int(1));
    assert_eq!(val("t=()", "t"), Seq(vec![]));
    assert_eq!(val("t=[1, 'a',]", "t"), Seq(vec![Int(1), Str("a".into())]));
    assert_eq!(val("t=1, 2", "t"), Seq(vec![Int(1), Int(2)]));
    assert_eq!(val("t=(0.,)*3", "t"), Seq(vec![Real(0.); 3]));
    assert_eq!(val("t=[1]+[2]", "t"), Seq(vec![Int(1), Int(2)]));
    assert_eq!(
        val("t=((1,2),[3])", "t"),
        Seq(vec![Seq(vec![Int(1), Int(2)]), Seq(vec![Int(3)])])
    );
    assert_eq!(val("x=(5, 6, 7)\nt=x[0]+x[-1]", "t"), Int(12));
    assert_eq!(val("t=True", "t"), Value::Bool(true));
    assert_eq!(val("t=None", "t"), Value::None);
}

// ---- arithmetic ------------------------------------------------------------------

#[test]
fn python_precedence_and_associativity() {
    assert_eq!(val("x=-2**2", "x"), Int(-4));
    assert_eq!(val("x=2**3**2", "x"), Int(512));
    assert_eq!(val("x=2**-1", "x"), Real(0.5));
    assert_eq!(val("x=(-2)**2", "x"), Int(4));
    assert_eq!(val("x=1+2*3-4", "x"), Int(3));
    assert_eq!(val("x=10-4-3", "x"), Int(3));
    assert_eq!(val("x=2*3**2", "x"), Int(18));
    assert_eq!(val("x=7/2", "x"), Real(3.5));
    assert_eq!(val("x=7//2", "x"), Int(3));
    assert_eq!(val("x=-7%3", "x"), Int(2));
    assert_eq!(val("x=- -+1", "x"), Int(1));
    assert_eq!(val("x=-2**-2**2", "x"), Real(-1.0 / 16.0));
    assert_eq!(val("x=(1+2)*(3+4)", "x"), Int(21));
}

#[test]
fn variables_feed_keywords() {
    let (_, host) = run_ok("k = 1.e4\nDEBUT(RIGI_NOR=10*k, T=(k, 2*k))");
    let args = &host.calls[0].args;
    assert_eq!(kw(args, "RIGI_NOR"), &Real(1.0e5));
    assert_eq!(kw(args, "T"), &Seq(vec![Real(1e4), Real(2e4)]));
}

// ---- statements, lines, comments ---------------------------------------------------

#[test]
fn semicolons_continuations_and_comments() {
    let (env, host) = run_ok(
        "# header\na = 1 ; b = 2;\nDEBUT(); FIN();  # two calls\nc = a + \\\n    b\nd = (a +  # inside\n     b)\n",
    );
    assert_eq!(env.get("c"), Some(&Int(3)));
    assert_eq!(env.get("d"), Some(&Int(3)));
    assert_eq!(host.calls.len(), 2);
    assert_eq!(host.calls[1].op, "FIN");
}

#[test]
fn call_spans_and_keyword_spans() {
    let text = "A = 1\nMAIL = LIRE_MAILLAGE(UNITE=20,\n    FORMAT='ASTER')";
    let (_, host) = run_ok(text);
    let c = &host.calls[0];
    assert_eq!((c.span.line, c.span.col), (2, 1));
    assert_eq!(
        &text[c.span.start..c.span.end],
        "MAIL = LIRE_MAILLAGE(UNITE=20,\n    FORMAT='ASTER')"
    );
    assert_eq!((c.op_span.line, c.op_span.col), (2, 8));
    assert_eq!(&text[c.op_span.start..c.op_span.end], "LIRE_MAILLAGE");
    let f = &c.args[1];
    assert_eq!(&text[f.span.start..f.span.end], "FORMAT='ASTER'");
    assert_eq!((f.span.line, f.span.col), (3, 5));
    assert_eq!(c.result.as_deref(), Some("MAIL"));
}

#[test]
fn factor_keywords_co_and_reuse() {
    let (env, host) = run_ok(
        "M = LIRE_MAILLAGE()\nASSEMBLAGE(NUME_DDL=CO('NU'), MATR_ASSE=(_F(MATRICE=CO('K'), OPTION='RIGI_MECA'),),)\n\
         M = LIRE_MAILLAGE(reuse=M, INFO=2)\nM2 = M",
    );
    let a = &host.calls[1];
    assert_eq!(a.result, None);
    assert_eq!(kw(&a.args, "NUME_DDL"), &Value::Co("NU".into()));
    let Seq(items) = kw(&a.args, "MATR_ASSE") else {
        panic!("not a seq")
    };
    let Value::Fact(f) = &items[0] else {
        panic!("not a fact")
    };
    assert_eq!(kw(f, "MATRICE"), &Value::Co("K".into()));
    // CO names become Python names once the macro has run.
    assert!(matches!(env.get("NU"), Some(Value::Concept(c)) if c.name == "NU"));
    let r = &host.calls[2];
    assert_eq!(r.reuse.as_ref().map(|c| c.name.as_str()), Some("M"));
    assert_eq!(r.args.len(), 1, "reuse is removed from args");
    assert!(
        matches!(env.get("M2"), Some(Value::Concept(c)) if c.name == "M" && c.ty == "lire_maillage")
    );
}

// ---- imports, math, builtins ------------------------------------------------------

/// numpy's scalar functions and constants, as Code_Aster's files use them (sdnd100d:
/// `import numpy as np` then `np.sqrt(2.)`); its arrays are refused by name.
#[test]
fn numpy_scalar_imports() {
    assert_eq!(
        val("import numpy as np\nx=np.sqrt(2.)*np.sqrt(2.)", "x"),
        Real(2.0_f64.sqrt() * 2.0_f64.sqrt())
    );
    assert_eq!(
        val("import numpy\nx=numpy.arctan2(1., 1.)*4", "x"),
        Real(std::f64::consts::PI)
    );
    assert_eq!(
        val(
            "import numpy as np\nx=np.power(2., 10)+np.abs(-1.)+np.pi",
            "x"
        ),
        Real(1025.0 + std::f64::consts::PI)
    );
    assert_eq!(
        val("from numpy import arcsin as a, pi\nx=2*a(1.)-pi", "x"),
        Real(0.0)
    );
    let e = run_err("import numpy as np\nx = np.array([1., 2.])", 2, 8);
    assert!(
        e.message.starts_with("numpy.array is not supported"),
        "{}",
        e.message
    );
    let e = run_err("import numpy as np\nx = np.sqrt", 2, 5);
    assert_eq!(e.message, "'np.sqrt' is a function: call it");
    let e = run_err("from numpy import linspace", 1, 19);
    assert_eq!(e.message, "cannot import 'linspace' from 'numpy'");
    // A variable of the module's name hides it, as in Python.
    assert_eq!(val("import numpy as np\nnp = 3\nx = np*2", "x"), Int(6));
}

#[test]
fn math_imports() {
    assert_eq!(
        val("from math import *\nx=sqrt(16)+floor(pi)", "x"),
        Real(7.0)
    );
    assert_eq!(
        val("import math\nx=math.sqrt(4)*math.pi", "x"),
        Real(2.0 * std::f64::consts::PI)
    );
    assert_eq!(
        val("from math import pi, sqrt\nx=sqrt(pi*pi)", "x"),
        Real(std::f64::consts::PI)
    );
    assert_eq!(
        val("from math import (log,\n  e)\nx=log(e)", "x"),
        Real(1.0)
    );
    assert_eq!(
        val("from math import log10 as lg\nx=lg(1000)", "x"),
        Real(3.0)
    );
    assert_eq!(val("from math import *\nx=log(8, 2)", "x"), Real(3.0));
    // code_aster imports of new-style files are accepted.
    assert_eq!(val("from code_aster.Commands import *\nx=1", "x"), Int(1));
}

#[test]
fn builtins_in_files() {
    assert_eq!(val("x=max(1, 2.5)+min((3, 4))+abs(-1)", "x"), Real(6.5));
    assert_eq!(val("x=len(list(range(1, 10, 2)))", "x"), Int(5));
    assert_eq!(val("x=sum([1, 2, 3])", "x"), Int(6));
    assert_eq!(val("x=int(2.9)+float(1)", "x"), Real(3.0));
    assert_eq!(val("x=str(2)+'b'", "x"), Str("2b".into()));
    assert_eq!(val("x=tuple(range(3))[-1]", "x"), Int(2));
    let (_, host) = run_ok("print('f =', 1.5)");
    assert_eq!(host.printed, vec!["f = 1.5".to_string()]);
}

// ---- loops --------------------------------------------------------------------------

#[test]
fn for_loops_nested_and_inline() {
    let (env, host) = run_ok(
        "s = 0\nfor i in range(3):\n    for x in (1, 2):\n        s = s + i*x\n    T = CREA_TABLE(I=i)\nfor y in [10]: s += y\nafter = 1\n",
    );
    // (0+1+2)*(1+2) from the nested loops, plus 10.
    assert_eq!(env.get("s"), Some(&Int(19)));
    assert_eq!(env.get("after"), Some(&Int(1)));
    assert_eq!(env.get("i"), Some(&Int(2)));
    assert_eq!(host.calls.len(), 3);
    assert_eq!(kw(&host.calls[2].args, "I"), &Int(2));
}

#[test]
fn inline_loop_bodies_indexing_and_reruns() {
    let text = "L = [2, 4, 8]\nn = 0\nfor i in range(len(L) - 1): n += L[i+1] - L[i]; DEBUT(I=i)\nlast = L[-len(L)]";
    let (env, host) = run_ok(text);
    assert_eq!(env.get("n"), Some(&Int(6)));
    assert_eq!(env.get("last"), Some(&Int(2)));
    assert_eq!(host.calls.len(), 2);
    // A parsed program can be executed again, with a fresh environment.
    let src = Source::new("t.comm", text);
    let program = parse(&src).unwrap();
    let mut h = Recorder::default();
    execute(&program, &src, &mut Env::new(), &mut h).unwrap();
    execute(&program, &src, &mut Env::new(), &mut h).unwrap();
    assert_eq!(h.calls.len(), 4);
}

#[test]
fn parsing_alone_needs_no_host_and_keeps_statement_order() {
    let p = parse(&Source::new(
        "t.comm",
        "DEBUT()\nfor i in (1,):\n    X = F(A=i)\nFIN()",
    ))
    .unwrap();
    let kinds: Vec<&str> = p
        .stmts
        .iter()
        .map(|s| match &s.kind {
            ast::StmtKind::Call(_) => "call",
            ast::StmtKind::For { body, .. } if body.len() == 1 => "for1",
            _ => "other",
        })
        .collect();
    assert_eq!(kinds, vec!["call", "for1", "call"]);
}

#[test]
fn tuple_unpacking_in_assignments_and_loops() {
    let (env, host) = run_ok(
        "a, b = 1, 2.5\nc, = (3,)\nfor i, f in enumerate((10., 20.)):\n    T = CREA_TABLE(I=i, F=f)\nfor x, y in zip((1, 2), 'ab'): last = y",
    );
    assert_eq!(env.get("a"), Some(&Int(1)));
    assert_eq!(env.get("b"), Some(&Real(2.5)));
    assert_eq!(env.get("c"), Some(&Int(3)));
    assert_eq!(env.get("last"), Some(&Str("b".into())));
    assert_eq!(kw(&host.calls[1].args, "F"), &Real(20.));
    assert_eq!(
        run_err("a, b = 1, 2, 3", 1, 8).message,
        "cannot unpack 3 values into 2 names"
    );
    assert_eq!(
        run_err("a, b = 1", 1, 1).message,
        "cannot unpack an integer into 2 names"
    );
}

#[test]
fn loop_bodies_with_tabs_comments_and_blank_lines() {
    let (env, _) = run_ok(
        "n = 0\nfor i in 1, 2:\n\n\t# comment at another indentation\n\tn += i\n\n\tn += 1\nend=n",
    );
    assert_eq!(env.get("end"), Some(&Int(5)));
}

// ---- fixtures ----------------------------------------------------------------------

#[test]
fn sample_study_from_the_brief() {
    let text = include_str!("../../tests/fixtures/modal_nnm.comm");
    let (env, host) = run_ok(text);
    let ops: Vec<&str> = host.calls.iter().map(|c| c.op.as_str()).collect();
    assert_eq!(
        ops,
        vec![
            "DEBUT",
            "LIRE_MAILLAGE",
            "AFFE_MODELE",
            "AFFE_CARA_ELEM",
            "ASSEMBLAGE",
            "MODE_NON_LINE",
            "MODE_NON_LINE",
            "CREA_TABLE",
            "CREA_TABLE",
            "FIN"
        ]
    );
    // f0 = sqrt(k/m)/(2 pi) with k = 10, m = 1.
    let f0 = (10.0f64).sqrt() / (2.0 * std::f64::consts::PI);
    assert_eq!(env.get("f0"), Some(&Real(f0)));
    let debut = &host.calls[0];
    assert_eq!(
        kw(&debut.args, "IGNORE_ALARM"),
        &Seq(vec![Str("SUPERVIS_1".into())])
    );
    let cara = &host.calls[3];
    let Seq(discret) = kw(&cara.args, "DISCRET") else {
        panic!()
    };
    assert_eq!(discret.len(), 2);
    let Value::Fact(d0) = &discret[0] else {
        panic!()
    };
    assert_eq!(kw(d0, "VALE"), &Seq(vec![Real(10.0), Real(0.), Real(0.)]));
    assert!(matches!(kw(&cara.args, "MODELE"), Value::Concept(c) if c.name == "MODELE"));
    let mnl = &host.calls[6];
    assert_eq!(mnl.reuse.as_ref().map(|c| c.name.as_str()), Some("MNL"));
    let tab = &host.calls[8];
    let Value::Fact(l) = kw(&tab.args, "LISTE") else {
        panic!()
    };
    assert_eq!(kw(l, "LISTE_R"), &Seq(vec![Real(1.0), Real(2.0)]));
}

#[test]
fn brief_sample_parses_and_reports_the_undefined_reused_concept() {
    let text = include_str!("../../tests/fixtures/brief_sample.comm");
    let program = parse(&Source::new("t.comm", text)).unwrap();
    // DEBUT, import, k, m, MAIL, MODELE, CARA, ASSEMBLAGE, f0, MNL, for, FIN.
    assert_eq!(program.stmts.len(), 12);
    // MNL is reused before any MNL = ... : Python would raise NameError there too.
    let e = run_err(text, 14, 25);
    assert_eq!(e.message, "name 'MNL' is not defined");
    assert_eq!(e.keyword.as_deref(), Some("reuse"));
}

#[test]
fn loops_and_lists_fixture() {
    let (env, host) = run_ok(include_str!("../../tests/fixtures/loops_and_lists.comm"));
    assert_eq!(env.get("total"), Some(&Real(9.0)));
    assert_eq!(env.get("last"), Some(&Real(4.5)));
    assert_eq!(env.get("w"), Some(&Real(2.0)));
    assert_eq!(env.get("msg"), Some(&Str("freqs done".into())));
    assert_eq!(host.calls.len(), 3 * 2 + 2);
    assert_eq!(host.printed, vec!["freqs done 9.0".to_string()]);
    let test = &host.calls[6];
    assert_eq!(test.op, "TEST_TABLE");
    assert!(matches!(kw(&test.args, "TABLE"), Value::Concept(c) if c.name == "TAB"));
}

#[test]
fn duffing_fixture() {
    let (env, host) = run_ok(include_str!("../../tests/fixtures/duffing_oscillator.comm"));
    let Some(Seq(chocs)) = env.get("CHOCS") else {
        panic!()
    };
    assert_eq!(chocs.len(), 2);
    let Value::Fact(c1) = &chocs[1] else { panic!() };
    assert_eq!(kw(c1, "RIGI_NOR"), &Real(1.0e5));
    assert_eq!(kw(c1, "JEU"), &Real(0.5e-3));
    let mnl = host.calls.iter().find(|c| c.op == "MODE_NON_LINE").unwrap();
    let Value::Fact(e) = kw(&mnl.args, "ETAT_INIT") else {
        panic!()
    };
    // omega/(2 pi) with omega = 2 pi 12.5; both roundings cancel to within 1 ulp.
    let Real(f) = kw(e, "FREQ") else { panic!() };
    assert!((f - 12.5).abs() <= 12.5 * f64::EPSILON, "{f}");
}

// ---- errors: message, line, column --------------------------------------------------

#[test]
fn syntax_errors_are_located() {
    let e = run_err("a = 1\nb = (1 +\nc = 2", 2, 5);
    assert_eq!(e.message, "'(' was never closed");
    assert_eq!(e.kind, ErrorKind::Syntax);
    assert_eq!(
        run_err("a = [1, 2)", 1, 10).message,
        "closing ')' does not match '['"
    );
    let e = run_err("a = (1,\n  2]", 2, 4);
    assert_eq!(e.hint.as_deref(), Some("it was opened at line 1, column 5"));
    assert_eq!(run_err("a = 1)", 1, 6).message, "unmatched ')'");
    let e = run_err("for i in range(3)\n    x = 1", 1, 18);
    assert_eq!(
        e.message,
        "invalid syntax: expected ':' or ',', found the end of the statement"
    );
    let e = run_err("DEBUT(A=1 B=2)", 1, 11);
    assert_eq!(e.message, "invalid syntax: expected ',' or ')', found 'B'");
    assert_eq!(e.hint.as_deref(), Some("a ',' may be missing"));
    assert_eq!(
        run_err("a = 1\ns = 'abc", 2, 5).message,
        "unterminated string"
    );
    let e = run_err(
        "DEBUT()\nMAIL = LIRE_MAILLAGE(UNITE=20 FORMAT='ASTER')",
        2,
        31,
    );
    assert!(
        e.message.starts_with("invalid syntax: expected"),
        "{}",
        e.message
    );
    assert!(e.message.ends_with("found 'F'"), "{}", e.message);
    let e = run_err("x = 1 +", 1, 8);
    assert_eq!(
        e.message,
        "invalid syntax: expected an expression, found the end of the statement"
    );
    let e = run_err("DEBUT(A==1)", 1, 8);
    assert!(e.hint.unwrap().contains("comparisons"));
}

#[test]
fn unsupported_constructs_are_named() {
    assert_eq!(
        run_err("a = 1\ndef f(x):\n    return x", 2, 1).message,
        "'def' is not supported in .comm files"
    );
    assert_eq!(
        run_err("while True:\n    x = 1", 1, 1).message,
        "'while' is not supported in .comm files"
    );
    assert_eq!(
        run_err("class A: pass", 1, 1).message,
        "'class' is not supported in .comm files"
    );
    assert_eq!(
        run_err("f = lambda x: x", 1, 5).message,
        "'lambda' is not supported in .comm files"
    );
    assert_eq!(
        run_err("x = 1 if a else 2", 1, 7).message,
        "'if' is not supported in .comm files"
    );
    assert_eq!(
        run_err("x = a and b", 1, 7).message,
        "the operator 'and' is not supported"
    );
    assert_eq!(
        run_err("d = {'a': 1}", 1, 5).message,
        "dictionaries ({...}) are not supported"
    );
    // A string prefix is named at the prefix, with what to write instead; an identifier
    // that merely ends in f before a quote is an ordinary syntax error.
    let e = run_err("DEBUT(TITRE=f'x = {x}')", 1, 13);
    assert!(
        e.message.starts_with("string prefixes such as f'...'"),
        "{}",
        e.message
    );
    assert!(e.hint.unwrap().contains("str("));
    assert!(run_err("x = rb'a'", 1, 5).message.contains("rb'...'"));
    let e = run_err("x = leaf'a'", 1, 9);
    assert!(e.message.starts_with("invalid syntax"), "{}", e.message);
    let e = run_err("import os", 1, 8);
    assert_eq!(e.message, "importing module 'os' is not supported");
    assert_eq!(
        run_err("from scipy import linalg", 1, 6).message,
        "importing module 'scipy' is not supported"
    );
    let e = run_err("x = 1\nx + 1", 2, 1);
    assert_eq!(
        e.message,
        "this statement does nothing: only calls may stand alone"
    );
    let e = run_err("L = [1]\nL.append(2)", 2, 3);
    assert_eq!(e.message, "calling methods (.append(...)) is not supported");
    assert_eq!(
        run_err("x = (1).real", 1, 9).message,
        "attributes (x.name) are not supported"
    );
    let e = run_err("X = AFFE_MODELE(MAILLAGE=LIRE_MAILLAGE())", 1, 26);
    assert_eq!(
        e.message,
        "operator 'LIRE_MAILLAGE' must be called in a statement of its own"
    );
}

#[test]
fn indentation_errors() {
    assert_eq!(run_err("a = 1\n  b = 2", 2, 3).message, "unexpected indent");
    assert_eq!(
        run_err("for i in (1,2):\nb = 2", 1, 1).message,
        "expected an indented block after 'for'"
    );
    assert_eq!(
        run_err("for i in (1,2):", 1, 1).message,
        "expected an indented block after 'for'"
    );
    let e = run_err("for i in (1,2):\n    a = 1\n  b = 2", 3, 3);
    assert_eq!(
        e.message,
        "unindent does not match any outer indentation level"
    );
    assert_eq!(
        run_err("for i in (1,2):\n    a = 1\n        b = 2", 3, 9).message,
        "unexpected indent"
    );
}

/// Code_Aster's supervisor preloads some math names: its files use them with no import,
/// and a file's own binding of such a name hides it, as in Python.
#[test]
fn code_aster_math_names_need_no_import() {
    assert_eq!(val("x = cos(pi / 4.)**2", "x"), Real(0.5000000000000001));
    assert_eq!(val("x = sqrt(16.) + log10(100.)", "x"), Real(6.0));
    assert_eq!(val("pi = 3\nx = pi", "x"), Int(3));
}

#[test]
fn name_errors() {
    let e = run_err("x = 1\ny = floor(2.)", 2, 5);
    assert_eq!(e.message, "name 'floor' is not defined");
    assert!(e.hint.unwrap().contains("from math import *"));
    let e = run_err("y = 2*tau", 1, 7);
    assert_eq!(e.message, "name 'tau' is not defined");
    assert!(e.hint.unwrap().contains("from math import *"));
    let e = run_err("y = math.sqrt(2.)", 1, 5);
    assert!(e.hint.unwrap().contains("import math"));
    let e = run_err("DEBUT()\nM = AFFE_MODELE(MAILLAGE=MAIL)", 2, 26);
    assert_eq!(e.message, "name 'MAIL' is not defined");
    let e = run_err("rigidity = 1\nx = rigidty", 2, 5);
    assert_eq!(e.hint.as_deref(), Some("did you mean 'rigidity'?"));
    let e = run_err("x = foo(1)", 1, 5);
    assert_eq!(e.message, "name 'foo' is not defined");
    let e = run_err("x = 1\nx(2)", 2, 1);
    assert_eq!(e.message, "'x' is an integer, not a function");
    let e = run_err("import math\nx = math.sqr(2)", 2, 10);
    assert_eq!(e.message, "module 'math' has no function 'sqr'");
    let e = run_err("from math import sqrtt", 1, 18);
    assert_eq!(e.message, "cannot import 'sqrtt' from 'math'");
}

#[test]
fn unknown_operator_suggests_close_names() {
    let e = run_err("DEBUT()\nM = AFFE_MODEL(A=1)", 2, 5);
    assert_eq!(e.message, "unknown operator 'AFFE_MODEL'");
    assert_eq!(e.hint.as_deref(), Some("did you mean 'AFFE_MODELE'?"));
    assert_eq!(run_err("QQQQQQ()", 1, 1).hint, None);
}

#[test]
fn evaluation_errors_point_at_the_expression() {
    let e = run_err("a = 'a'\nDEBUT(X=a*1.5)", 2, 9);
    assert_eq!(
        e.message,
        "unsupported operand types for '*': a text and a real"
    );
    assert_eq!(
        run_err("x = 1\ny = 2 + x/0", 2, 9).message,
        "division by zero"
    );
    assert_eq!(run_err("x = 1.5 // 0.", 1, 5).message, "division by zero");
    assert_eq!(
        run_err("x = 10**100", 1, 5).message,
        "integer overflow in '**'"
    );
    assert_eq!(
        run_err("x = 9223372036854775807 + 1", 1, 5).message,
        "integer overflow in '+'"
    );
    assert_eq!(
        run_err("x = 99999999999999999999", 1, 5).message,
        "integer literal is too large"
    );
    assert_eq!(
        run_err("x = 1e999", 1, 5).message,
        "real literal is out of range"
    );
    assert_eq!(
        run_err("x = 10.**400", 1, 5).message,
        "the result of '**' is not a finite number (overflow)"
    );
    assert_eq!(
        run_err("x = (1, 2)[2]", 1, 5).message,
        "index 2 is out of range (length 2)"
    );
    assert_eq!(
        run_err("x = range(10**8)", 1, 5).message,
        "range() would have 100000000 items, more than the limit 1000000"
    );
    assert_eq!(
        run_err("from math import *\nx = sqrt(-1)", 2, 5).message,
        "sqrt(): math domain error (argument -1)"
    );
    assert_eq!(
        run_err("for i in 3:\n    x = 1", 1, 10).message,
        "'for' needs a list, a tuple or a range, got an integer"
    );
    assert_eq!(
        run_err("x = 'a' % 2", 1, 5).message,
        "string formatting with '%' is not supported"
    );
    assert_eq!(
        run_err("x = -'a'", 1, 5).message,
        "bad operand for unary -: a text"
    );
    assert_eq!(
        run_err("x = len(1, 2)", 1, 5).message,
        "len() takes 1 argument(s), got 2"
    );
}

#[test]
fn call_errors() {
    let e = run_err("DEBUT(A=1,\n      A=2)", 2, 7);
    assert_eq!(e.message, "keyword 'A' is given twice");
    assert_eq!(e.keyword.as_deref(), Some("A"));
    assert_eq!(
        run_err("x = _F(A=1, A=2)", 1, 13).message,
        "keyword 'A' is given twice"
    );
    assert_eq!(
        run_err("DEBUT(1)", 1, 7).message,
        "arguments of operator 'DEBUT' must be keywords"
    );
    assert_eq!(
        run_err("x = _F(1)", 1, 8).message,
        "_F(...) takes only keywords KEY=value"
    );
    assert_eq!(
        run_err("x = CO(1)", 1, 5).message,
        "CO() takes one text: CO('NAME')"
    );
    let e = run_err("M = 1\nM = LIRE_MAILLAGE(reuse=M)", 2, 19);
    assert_eq!(e.message, "reuse= must name a concept, got an integer");
    let e = run_err("M = LIRE_MAILLAGE(reuse=N)", 1, 25);
    assert_eq!(e.message, "name 'N' is not defined");
    // A host error without location is located at the call statement.
    let e = run_err("DEBUT()\nX = FAIL(A=1)", 2, 1);
    assert_eq!(e.message, "FAIL always fails");
    assert_eq!(e.kind, ErrorKind::Validation);
}

#[test]
fn resource_limits_are_errors() {
    let deep = format!("x = {}1{}", "(".repeat(70), ")".repeat(70));
    assert_eq!(
        run_err(&deep, 1, 69).message,
        "brackets are nested too deeply (more than 64 levels)"
    );
    let long_sum = format!("x = 1{}", "+1".repeat(300));
    assert!(run_err(&long_sum, 1, 5)
        .message
        .starts_with("expression is too complex"));
    // Right-folded chains fail where the depth limit is crossed, inside the expression.
    for text in [
        format!("x = 2{}", "**2".repeat(300)),
        format!("x = {}1", "-".repeat(300)),
    ] {
        let e = parse(&Source::new("t.comm", text)).unwrap_err();
        assert!(
            e.message.starts_with("expression is too complex"),
            "{}",
            e.message
        );
        assert_eq!(e.location.map(|l| l.span.line), Some(1));
    }
    let small = Limits {
        max_steps: 1000,
        ..Limits::default()
    };
    let e = run_err_limited(
        "for i in range(100000):\n    for j in range(100000):\n        x = 1",
        3,
        9,
        small,
    );
    assert!(
        e.message.starts_with("more than 1000 statements"),
        "{}",
        e.message
    );
    let mut nested = String::new();
    for d in 0..25 {
        nested.push_str(&format!("{}for i{d} in (1,):\n", " ".repeat(d)));
    }
    nested.push_str(&format!("{}x = 1\n", " ".repeat(25)));
    assert!(run_err(&nested, 21, 21)
        .message
        .starts_with("loops are nested too deeply"));
}

#[test]
fn copying_big_lists_in_a_loop_is_stopped() {
    let small = Limits {
        max_steps: 1000,
        max_work: 10_000,
        ..Limits::default()
    };
    let e = run_err_limited(
        "L = list(range(500))\nfor i in range(1000):\n    M = L + L",
        3,
        9,
        small,
    );
    assert!(
        e.message.starts_with("more than 10000 list items"),
        "{}",
        e.message
    );
}

#[test]
fn docstrings_are_ignored() {
    let (env, _) = run_ok("\"\"\"Study of a beam.\n\nTwo modes.\"\"\"\nx = 1 ; 'note'");
    assert_eq!(env.get("x"), Some(&Int(1)));
}

#[test]
fn errors_in_keyword_values_name_the_keyword_path() {
    let e = run_err("DEBUT(CHOC=(_F(A=1), _F(JEU=1/0)))", 1, 29);
    assert_eq!(e.keyword.as_deref(), Some("CHOC/JEU"));
    let e = run_err("DEBUT(AFFE=_F(GROUP_MA='A', GROUP_MA='B'))", 1, 29);
    assert_eq!(e.keyword.as_deref(), Some("AFFE/GROUP_MA"));
    let e = run_err("DEBUT(MAILLAGE=MAIL)", 1, 16);
    assert_eq!(e.keyword.as_deref(), Some("MAILLAGE"));
    // Not inside an operator call: no keyword.
    assert_eq!(run_err("x = 1/0", 1, 5).keyword, None);
}

// ---- rendering ----------------------------------------------------------------------

#[test]
fn render_shows_line_and_caret() {
    let src = Source::new("t.comm", "DEBUT()\nM = AFFE_MODEL(A=1)\n");
    let e = run(&src, &mut Env::new(), &mut Recorder::default()).unwrap_err();
    let r = render_plain(&e, Some(&src));
    let lines: Vec<&str> = r.lines().collect();
    assert_eq!(lines[0], "  × unknown operator 'AFFE_MODEL'", "{r}");
    assert_eq!(lines[1], "   ╭─[t.comm:2:5]", "{r}");
    assert_eq!(lines[3], " 2 │ M = AFFE_MODEL(A=1)", "{r}");
    // The span is underlined under the operator name: 4 columns in, 10 characters.
    assert_eq!(lines[4], "   ·     ──────────", "{r}");
    assert!(r.contains("help: did you mean 'AFFE_MODELE'?"), "{r}");
    assert!(!r.contains('\x1b'));
}

/// POURSUITE: a concept of an earlier run is bound by no statement of the file; the
/// evaluator asks the host for it, and still reports names the host does not know.
#[test]
fn names_no_statement_bound_are_asked_to_the_host() {
    struct Continued(Vec<CommandCall>);
    impl Host for Continued {
        fn is_operator(&self, name: &str) -> bool {
            name == "TEST_RESU"
        }
        fn call(&mut self, call: CommandCall) -> crate::error::Result<Value> {
            self.0.push(call);
            Ok(Value::None)
        }
        fn lookup_concept(&self, name: &str) -> Option<ConceptRef> {
            (name == "MODES").then(|| ConceptRef {
                name: "MODES".into(),
                ty: "mode_meca".into(),
            })
        }
    }
    let src = Source::new("t.comm", "TEST_RESU(RESULTAT=MODES)\n");
    let mut host = Continued(Vec::new());
    run(&src, &mut Env::new(), &mut host).unwrap();
    assert_eq!(
        host.0[0].args[0].value,
        Value::Concept(ConceptRef {
            name: "MODES".into(),
            ty: "mode_meca".into()
        })
    );
    let src = Source::new("t.comm", "TEST_RESU(RESULTAT=MODE)\n");
    let e = run(&src, &mut Env::new(), &mut Continued(Vec::new())).unwrap_err();
    assert_eq!(e.message, "name 'MODE' is not defined");
}

/// `T.EXTR_TABLE()`, `tab.PARA[i]`, `len(tab)` and `T['PARA', i]` as Code_Aster's tables
/// define them: columns indexed from 0 like Python lists, cells of the concept from 1.
#[test]
fn table_contents_in_python() {
    struct Tables(Vec<CommandCall>);
    impl Host for Tables {
        fn is_operator(&self, name: &str) -> bool {
            name == "TEST"
        }
        fn call(&mut self, call: CommandCall) -> crate::error::Result<Value> {
            self.0.push(call);
            Ok(Value::None)
        }
        fn lookup_concept(&self, name: &str) -> Option<ConceptRef> {
            let ty = match name {
                "T" => "table_container",
                "M" => "maillage_sdaster",
                _ => return None,
            };
            Some(ConceptRef {
                name: name.into(),
                ty: ty.into(),
            })
        }
        fn table_contents(&mut self, table: &ConceptRef) -> crate::error::Result<Value> {
            Ok(Value::Table(std::sync::Arc::new(
                crate::value::TableValue {
                    name: table.name.clone(),
                    columns: vec!["E".into(), "F".into()],
                    rows: vec![
                        vec![Value::Real(1.5), Value::Real(10.0)],
                        vec![Value::Real(2.5), Value::None],
                    ],
                },
            )))
        }
    }
    let src = Source::new(
        "t.comm",
        "tab = T.EXTR_TABLE()\nTEST(A=tab.E[0], B=tab.F[-1], N=len(tab), C=T['E', 2], \
         L=tab.F)\n",
    );
    let mut host = Tables(Vec::new());
    run(&src, &mut Env::new(), &mut host).unwrap();
    let args = &host.0[0].args;
    assert_eq!(args[0].value, Value::Real(1.5));
    assert_eq!(args[1].value, Value::None);
    assert_eq!(args[2].value, Value::Int(2));
    assert_eq!(args[3].value, Value::Real(2.5));
    assert_eq!(
        args[4].value,
        Value::Seq(vec![Value::Real(10.0), Value::None])
    );

    for (text, col, msg) in [
        (
            "tab = T.EXTR_TABLE()\nx = tab.G[0]\n",
            9,
            "table T has no column 'G'",
        ),
        (
            "x = T['E', 0]\n",
            5,
            "table T has no row 0: rows count from 1 to 2",
        ),
        (
            "x = T[0]\n",
            5,
            "a table is indexed by ('PARA', row), got an integer",
        ),
        (
            "x = M.EXTR_TABLE()\n",
            5,
            "M is a maillage_sdaster: EXTR_TABLE() is a method of tables",
        ),
        (
            "x = T.EXTR_TABLE(1)\n",
            18,
            "EXTR_TABLE() takes no argument",
        ),
    ] {
        let src = Source::new("t.comm", text);
        let e = run(&src, &mut Env::new(), &mut Tables(Vec::new())).unwrap_err();
        assert_eq!(e.message, msg, "{text}");
        let line = text.lines().count();
        assert_eq!(
            e.location.map(|l| (l.span.line, l.span.col)),
            Some((line, col)),
            "{text}"
        );
    }
}

#[test]
fn the_code_aster_python_api_becomes_commands_and_the_rest_is_named_as_unsupported() {
    let text = "import code_aster\nfrom code_aster.Commands import *\n\
                code_aster.init(\"--test\", ERREUR=_F(ALARME='EXCEPTION'), debug=True)\n\
                test = code_aster.TestCase()\nMA = code_aster.Mesh()\n\
                test.assertTrue(True)\ntest.printSummary()\ncode_aster.Model()\n";
    let src = Source::new("t.py", text);
    let mut host = Recorder::default();
    let e = run(&src, &mut Env::new(), &mut host).unwrap_err();
    // init() is DEBUT with DEBUT's (capitalised) keywords; the API's own options are dropped.
    assert_eq!(host.calls.len(), 1, "{:?}", host.calls);
    assert_eq!(host.calls[0].op, "DEBUT");
    let names: Vec<&str> = host.calls[0].args.iter().map(|k| k.name.as_str()).collect();
    assert_eq!(names, ["ERREUR"]);
    assert!(
        e.message
            .starts_with("code_aster.Model(): this part of the Python API of Code_Aster"),
        "{}",
        e.message
    );
    assert_eq!(e.location.map(|l| l.span.line), Some(8));
    // init("--continue") continues a study: POURSUITE.
    let mut host = Recorder::default();
    let src = Source::new(
        "t.py",
        "import code_aster\ncode_aster.init(\"--continue\")\n",
    );
    run(&src, &mut Env::new(), &mut host).unwrap();
    let ops: Vec<&str> = host.calls.iter().map(|c| c.op.as_str()).collect();
    assert_eq!(ops, ["POURSUITE"]);
    // A mesh is read through the host's file mapping (the Recorder has none: an error that
    // names the file), an unknown assertion is refused with the supported list.
    for (line, want) in [
        (
            "MA.readAsterMeshFile('m.mail')\n",
            "reading the file 'm.mail' by its name",
        ),
        (
            "test.assertSomething(1)\n",
            "code_aster.TestCase has no method 'assertSomething'",
        ),
        (
            "MA.readMesh('m')\n",
            "code_aster.Mesh has no method 'readMesh'",
        ),
    ] {
        let text = format!(
            "import code_aster\ncode_aster.init()\ntest = code_aster.TestCase()\n\
             MA = code_aster.Mesh()\n{line}"
        );
        let e = run(
            &Source::new("t.py", &text),
            &mut Env::new(),
            &mut Recorder::default(),
        )
        .unwrap_err();
        assert!(e.message.contains(want), "{}", e.message);
    }
}
