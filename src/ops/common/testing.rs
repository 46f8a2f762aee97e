//! The comparison behind every TEST_* operator (TEST_TABLE, TEST_FONCTION, TEST_RESU...),
//! with Code_Aster's semantics:
//!
//! - `VALE_CALC` is a non-regression value: compared with the tolerance `TOLE_MACHINE`,
//!   reference type `NON_REGRESSION`.
//! - `VALE_REFE` is a reference value of type `REFERENCE` (`ANALYTIQUE`, `SOURCE_EXTERNE`,
//!   `AUTRE_ASTER`, `NON_DEFINI`), compared with `PRECISION`.
//! - Both may be given: two checks, two lines.
//! - `CRITERE='RELATIF'` compares `|calc - ref| / |ref|`, `'ABSOLU'` compares
//!   `|calc - ref|`. When the reference is 0, a relative error means nothing: like
//!   Code_Aster we then compare absolutely, with the tolerance times `ORDRE_GRANDEUR`,
//!   and the printed line says so.
//! - `CRITERE` and `TOLE_MACHINE` may hold two values, as in Code_Aster: the first is the
//!   test's (criterion of both checks, tolerance of the non-regression one), the second
//!   the extraction's (how TEST_RESU finds its INST); one value serves both.
//! - Every default (CRITERE, TOLE_MACHINE, PRECISION, ORDRE_GRANDEUR, VALE_ABS) and bound is
//!   the catalog's (`commands/TEST_*.toml`): the checks read validated `Args`.
//! - Integers (`VALE_CALC_I`, `VALE_REFE_I`) and texts (`_K`) must be equal exactly.
//! - `aster-nl run --tole-machine X` (beyond Code_Aster) raises every real non-regression
//!   tolerance to at least X, for files whose VALE_CALC were computed by another code:
//!   the line then says `--tole-machine`. References (VALE_REFE) keep their PRECISION.
//!
//! Each check gives a [`TestOutcome`] whose line reads like Code_Aster's:
//! ` OK   ANALYTIQUE      0.646693927     0.646700000   9.39E-04%      0.1%`.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::ops::TestOutcome;
use crate::table::filter::Critere;
use crate::table::print::format_e;
use crate::value::Value;

/// A computed or reference value.
#[derive(Clone, Debug, PartialEq)]
pub enum TestValue {
    R(f64),
    I(i64),
    K(String),
}

/// Allowed REFERENCE values.
pub const REFERENCES: &[&str] = &["ANALYTIQUE", "SOURCE_EXTERNE", "AUTRE_ASTER", "NON_DEFINI"];

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    pub critere: Critere,
    pub precision: f64,
    /// Scale of the absolute comparison used when a relative one meets a zero reference.
    pub ordre_grandeur: f64,
}

impl Tolerance {
    pub fn relative(precision: f64) -> Tolerance {
        Tolerance {
            critere: Critere::Relatif,
            precision,
            ordre_grandeur: 1.0,
        }
    }
}

/// Nine significant digits, fixed notation for moderate magnitudes (like the example
/// lines of Code_Aster's test reports), scientific otherwise.
fn fmt_real(x: f64) -> String {
    if x == 0.0 {
        return "0.0".to_string();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor();
    if (-4.0..9.0).contains(&mag) {
        let decimals = (8.0 - mag).max(0.0) as usize;
        format!("{x:.decimals$}")
    } else {
        format_e(x, 8)
    }
}

fn fmt_value(v: &TestValue) -> String {
    match v {
        TestValue::R(x) => fmt_real(*x),
        TestValue::I(i) => i.to_string(),
        TestValue::K(s) => format!("'{s}'"),
    }
}

/// Shortest decimal text of a tolerance after rounding away binary noise (1e-3*100 → 0.1).
fn fmt_tol(x: f64) -> String {
    let rounded: f64 = format!("{x:.12e}").parse().unwrap_or(x);
    format!("{rounded}")
}

/// The column labels printed above the OK/NOOK lines of one test occurrence, aligned
/// with them.
pub fn header_line() -> String {
    format!(
        " {:<4} {:<15} {:>16} {:>16} {:>11} {:>9}",
        "", "REFERENCE", "VALE_REFE", "VALE_CALC", "ERREUR", "TOLE"
    )
}

fn line(
    ok: bool,
    kind: &str,
    reference: &TestValue,
    computed: &TestValue,
    err: &str,
    tol: &str,
    note: &str,
) -> String {
    format!(
        " {:<4} {:<15} {:>16} {:>16} {:>11} {:>9}{}",
        if ok { "OK" } else { "NOOK" },
        kind,
        fmt_value(reference),
        fmt_value(computed),
        err,
        tol,
        note
    )
}

/// Compare `computed` with `reference`. `reference_kind` is printed: `NON_REGRESSION` for
/// VALE_CALC, the REFERENCE keyword for VALE_REFE.
pub fn check(
    computed: &TestValue,
    reference: &TestValue,
    reference_kind: &str,
    tol: Tolerance,
) -> TestOutcome {
    let mk = |ok: bool, err: String, tol: String, note: &str| TestOutcome {
        ok,
        line: line(ok, reference_kind, reference, computed, &err, &tol, note),
    };
    match (computed, reference) {
        (TestValue::K(c), TestValue::K(r)) => mk(c == r, "-".into(), "-".into(), ""),
        (TestValue::I(c), TestValue::I(r)) => {
            mk(c == r, c.abs_diff(*r).to_string(), "0".into(), "")
        }
        (TestValue::K(_), _) | (_, TestValue::K(_)) => mk(
            false,
            "-".into(),
            "-".into(),
            "  (a text cannot be compared with a number)",
        ),
        _ => {
            let c = num(computed);
            let r = num(reference);
            let diff = (c - r).abs();
            let (err, tol_v, relative, note) = match tol.critere {
                Critere::Relatif if r != 0.0 => (diff / r.abs(), tol.precision, true, ""),
                Critere::Relatif => (
                    diff,
                    tol.precision * tol.ordre_grandeur,
                    false,
                    "  (reference 0: compared absolutely)",
                ),
                Critere::Absolu => (diff, tol.precision, false, ""),
            };
            // `<=` is false for NaN: a NaN result is NOOK.
            let ok = err <= tol_v;
            if relative {
                mk(
                    ok,
                    format!("{}%", format_e(err * 100.0, 2)),
                    format!("{}%", fmt_tol(tol_v * 100.0)),
                    note,
                )
            } else {
                mk(ok, format_e(err, 2), fmt_tol(tol_v), note)
            }
        }
    }
}

fn num(v: &TestValue) -> f64 {
    match v {
        TestValue::R(x) => *x,
        TestValue::I(i) => *i as f64,
        TestValue::K(_) => f64::NAN,
    }
}

/// The value given to VALE_CALC / VALE_CALC_I / VALE_CALC_K (prefix `VALE_CALC`) or to
/// the `VALE_REFE` family, if any.
fn given(args: &Args, prefix: &str) -> Result<Option<TestValue>> {
    let wrong = |key: &str, what: &str| {
        Error::validation(format!("expected {what}")).keyword(args.key_path(key))
    };
    if args.has(prefix) {
        // An integer written for a real keyword is a real.
        return match args.value(prefix) {
            Some(Value::Seq(v)) if v.len() > 1 => Err(wrong(prefix, "one value")),
            _ => args
                .real(prefix)
                .map(|x| Some(TestValue::R(x)))
                .ok_or_else(|| wrong(prefix, "a real")),
        };
    }
    let ki = format!("{prefix}_I");
    if args.has(&ki) {
        return args
            .int(&ki)
            .map(|x| Some(TestValue::I(x)))
            .ok_or_else(|| wrong(&ki, "an integer"));
    }
    let kk = format!("{prefix}_K");
    if args.has(&kk) {
        return args
            .text(&kk)
            .map(|x| Some(TestValue::K(x.to_string())))
            .ok_or_else(|| wrong(&kk, "a text"));
    }
    Ok(None)
}

/// CRITERE as Code_Aster reads it: one value for the test and the extraction, or two,
/// `(test, extraction)` — the test's criterion (for VALE_CALC and VALE_REFE alike) and
/// the one that finds the tested instant or parameter in a result (TEST_RESU's INST).
pub fn criteres(args: &Args) -> Result<(Critere, Critere)> {
    let parse = |s: &str| {
        Critere::parse(s).ok_or_else(|| {
            Error::validation(format!("unknown CRITERE '{s}'"))
                .keyword(args.key_path("CRITERE"))
                .hint("use 'RELATIF' or 'ABSOLU'")
        })
    };
    match args.req_texts("CRITERE")?.as_slice() {
        [one] => {
            let c = parse(one)?;
            Ok((c, c))
        }
        [test, extraction] => Ok((parse(test)?, parse(extraction)?)),
        _ => Err(Error::validation("expected one or two values")
            .keyword(args.key_path("CRITERE"))
            .hint("CRITERE=('RELATIF', 'ABSOLU'): the test's criterion, then the extraction's")),
    }
}

/// TOLE_MACHINE as Code_Aster reads it: `(tolerance, precision)`, the tolerance of the
/// non-regression test and the precision that finds the tested instant (one value: both).
pub fn tole_machine(args: &Args) -> Result<(f64, f64)> {
    match args.req_reals("TOLE_MACHINE")?.as_slice() {
        [one] => Ok((*one, *one)),
        [tol, prec] => Ok((*tol, *prec)),
        _ => Err(Error::validation("expected one or two non-negative reals")
            .keyword(args.key_path("TOLE_MACHINE"))
            .hint("TOLE_MACHINE=(1.e-6, 1.e-4): the test's tolerance, then the extraction's precision")),
    }
}

/// How a TEST_RESU occurrence finds its instant: the second TOLE_MACHINE and CRITERE
/// values (Code_Aster's extraction precision), or the only ones.
pub fn extraction(args: &Args) -> Result<(f64, Critere)> {
    Ok((tole_machine(args)?.1, criteres(args)?.1))
}

/// Run the checks asked by one TEST_* occurrence (keywords VALE_CALC[_I|_K],
/// VALE_REFE[_I|_K], REFERENCE, CRITERE, PRECISION, TOLE_MACHINE, ORDRE_GRANDEUR,
/// VALE_ABS) on the
/// computed value: one outcome for VALE_CALC, one for VALE_REFE.
pub fn checks_from_args(args: &Args, computed: &TestValue) -> Result<Vec<TestOutcome>> {
    checks_with_floor(args, computed, None)
}

/// [`checks_from_args`] with the real non-regression tolerance raised to at least
/// `tole_machine_floor` (the `--tole-machine` option of `aster-nl run`).
pub fn checks_with_floor(
    args: &Args,
    computed: &TestValue,
    tole_machine_floor: Option<f64>,
) -> Result<Vec<TestOutcome>> {
    // Defaults and bounds (tolerances >= 0) are the catalog's, filled and checked by the
    // validation.
    let (critere, _) = criteres(args)?;
    // TOLE_MACHINE may hold a second value (the extraction's precision, `extraction`).
    let one_real = |key: &str| -> Result<f64> {
        args.real(key).ok_or_else(|| {
            Error::validation("expected a non-negative real").keyword(args.key_path(key))
        })
    };
    let ordre_grandeur = one_real("ORDRE_GRANDEUR")?;
    // VALE_ABS='OUI': the absolute value of the computed value is tested.
    let abs_value;
    let computed = match (args.req_text("VALE_ABS")?, computed) {
        ("OUI", TestValue::R(x)) => {
            abs_value = TestValue::R(x.abs());
            &abs_value
        }
        ("OUI", TestValue::I(i)) => {
            abs_value = TestValue::I(i.abs());
            &abs_value
        }
        _ => computed,
    };
    let mut out = Vec::new();
    if let Some(calc) = given(args, "VALE_CALC")? {
        let file_tol = tole_machine(args)?.0;
        let widened = matches!(calc, TestValue::R(_))
            && tole_machine_floor.is_some_and(|floor| floor > file_tol);
        let tol = Tolerance {
            critere,
            precision: if widened {
                tole_machine_floor.unwrap_or(file_tol)
            } else {
                file_tol
            },
            ordre_grandeur,
        };
        let mut outcome = check(computed, &calc, "NON_REGRESSION", tol);
        if widened {
            outcome.line.push_str("  (--tole-machine)");
        }
        out.push(outcome);
    }
    let refe = given(args, "VALE_REFE")?;
    match (refe, args.text("REFERENCE")) {
        (Some(refe), Some(kind)) => {
            if !REFERENCES.contains(&kind) {
                return Err(Error::validation(format!("unknown REFERENCE '{kind}'"))
                    .keyword(args.key_path("REFERENCE"))
                    .hint(format!("use one of {}", REFERENCES.join(", "))));
            }
            let tol = Tolerance {
                critere,
                precision: one_real("PRECISION")?,
                ordre_grandeur,
            };
            out.push(check(computed, &refe, kind, tol));
        }
        (Some(_), None) => {
            return Err(Error::validation("VALE_REFE needs REFERENCE")
                .keyword(args.key_path("REFERENCE"))
                .hint(format!(
                    "say where the reference comes from: {}",
                    REFERENCES.join(", ")
                )))
        }
        (None, Some(_)) => {
            return Err(Error::validation("REFERENCE is given without VALE_REFE")
                .keyword(args.key_path("VALE_REFE")))
        }
        (None, None) => {}
    }
    if out.is_empty() {
        return Err(Error::validation("nothing to test")
            .keyword(args.path.clone())
            .hint("give VALE_CALC (non-regression) and/or VALE_REFE with REFERENCE"));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::value::Span;

    #[test]
    fn relative_check_prints_like_code_aster() {
        let o = check(
            &TestValue::R(0.6467),
            &TestValue::R(0.646693927),
            "ANALYTIQUE",
            Tolerance::relative(1e-3),
        );
        assert!(o.ok);
        // |0.6467 - 0.646693927| / 0.646693927 = 9.39e-6 = 9.39E-04 %.
        let words: Vec<&str> = o.line.split_whitespace().collect();
        assert_eq!(
            words,
            vec![
                "OK",
                "ANALYTIQUE",
                "0.646693927",
                "0.646700000",
                "9.39E-04%",
                "0.1%"
            ]
        );
        assert!(o.line.starts_with(" OK  "));
    }

    #[test]
    fn relative_boundary_and_nook() {
        // 1.0011 vs 1: relative error 1.1e-3 > 1e-3 → NOOK; 1.0009 → OK.
        let t = Tolerance::relative(1e-3);
        assert!(!check(&TestValue::R(1.0011), &TestValue::R(1.0), "ANALYTIQUE", t).ok);
        let o = check(&TestValue::R(1.0011), &TestValue::R(1.0), "ANALYTIQUE", t);
        assert!(o.line.starts_with(" NOOK"));
        assert!(check(&TestValue::R(1.0009), &TestValue::R(1.0), "ANALYTIQUE", t).ok);
        assert!(!check(&TestValue::R(f64::NAN), &TestValue::R(1.0), "ANALYTIQUE", t).ok);
    }

    #[test]
    fn zero_reference_is_compared_absolutely() {
        let t = Tolerance::relative(1e-3);
        let o = check(&TestValue::R(5e-4), &TestValue::R(0.0), "ANALYTIQUE", t);
        assert!(o.ok && o.line.contains("compared absolutely"), "{}", o.line);
        assert!(!check(&TestValue::R(2e-3), &TestValue::R(0.0), "ANALYTIQUE", t).ok);
        let t = Tolerance {
            ordre_grandeur: 10.0,
            ..t
        };
        assert!(check(&TestValue::R(2e-3), &TestValue::R(0.0), "ANALYTIQUE", t).ok);
    }

    #[test]
    fn absolute_integer_and_text() {
        let t = Tolerance {
            critere: Critere::Absolu,
            precision: 0.01,
            ordre_grandeur: 1.0,
        };
        assert!(
            check(
                &TestValue::R(100.009),
                &TestValue::R(100.0),
                "AUTRE_ASTER",
                t
            )
            .ok
        );
        assert!(
            !check(
                &TestValue::R(100.011),
                &TestValue::R(100.0),
                "AUTRE_ASTER",
                t
            )
            .ok
        );
        let r = Tolerance::relative(0.5);
        assert!(check(&TestValue::I(3), &TestValue::I(3), "NON_REGRESSION", r).ok);
        assert!(!check(&TestValue::I(3), &TestValue::I(4), "NON_REGRESSION", r).ok);
        assert!(
            check(
                &TestValue::K("OUI".into()),
                &TestValue::K("OUI".into()),
                "NON_DEFINI",
                r
            )
            .ok
        );
        assert!(!check(&TestValue::K("1".into()), &TestValue::I(1), "NON_DEFINI", r).ok);
    }

    /// The checks of TEST_TABLE(TABLE=T, NOM_PARA='X', <simple>) on `computed`, the call
    /// validated as a user's (the catalog's defaults filled in).
    fn checks(simple: Vec<(&str, Value)>, computed: f64) -> Result<Vec<TestOutcome>> {
        let mut a = Args::new("TEST_TABLE");
        let table = Value::Concept(crate::value::ConceptRef {
            name: "T".into(),
            ty: "table_sdaster".into(),
        });
        a.simple = [("TABLE", table), ("NOM_PARA", Value::Str("X".into()))]
            .into_iter()
            .chain(simple)
            .map(|(k, v)| (k.to_string(), v, Span::default()))
            .collect();
        let a = crate::catalog::validate_args("TEST_TABLE", &a, None, "test.comm")?;
        checks_from_args(&a, &TestValue::R(computed))
    }

    #[test]
    fn calc_and_refe_give_two_checks() {
        let out = checks(
            vec![
                ("VALE_CALC", Value::Real(2.0000015)),
                ("VALE_REFE", Value::Real(2.001)),
                ("REFERENCE", Value::Str("ANALYTIQUE".into())),
            ],
            2.0,
        )
        .unwrap();
        // Non-regression: 7.5e-7 > 1e-6? no: 1.5e-6/2.0000015 = 7.5e-7 <= 1e-6 → OK.
        // Reference: 1e-3/2.001 = 5.0e-4 <= 1e-3 → OK.
        assert_eq!(out.len(), 2);
        assert!(out[0].ok && out[0].line.contains("NON_REGRESSION"));
        assert!(out[1].ok && out[1].line.contains("ANALYTIQUE"));
        // VALE_ABS='OUI' tests |-2| = 2.
        let abs = vec![
            ("VALE_CALC", Value::Real(2.0)),
            ("VALE_ABS", Value::Str("OUI".into())),
        ];
        assert!(checks(abs, -2.0).unwrap()[0].ok);
        // The catalog's TOLE_MACHINE (1e-6) applies: 5e-6 relative is NOOK.
        assert!(!checks(vec![("VALE_CALC", Value::Real(2.00001))], 2.0).unwrap()[0].ok);
        // The catalog's ORDRE_GRANDEUR (1): a zero reference compared absolutely.
        let zero = vec![("VALE_CALC", Value::Real(0.0))];
        let out = checks(zero, 5e-7).unwrap();
        assert!(
            out[0].ok && out[0].line.contains("compared absolutely"),
            "{}",
            out[0].line
        );
        let e = checks(vec![("VALE_REFE", Value::Real(2.0))], 2.0).unwrap_err();
        assert!(e.message.contains("REFERENCE"), "{}", e.message);
        assert!(checks(vec![], 2.0).is_err());
    }

    /// Code_Aster's two-value CRITERE and TOLE_MACHINE: the first values are the test's
    /// (for VALE_CALC and VALE_REFE alike), the second the extraction's.
    #[test]
    fn two_value_critere_and_tole_machine_test_with_the_first() {
        let texts = |a: &str, b: &str| Value::Seq(vec![Value::Str(a.into()), Value::Str(b.into())]);
        let reals = |a: f64, b: f64| Value::Seq(vec![Value::Real(a), Value::Real(b)]);
        // 1.0005 against 1.0: 5e-4 relative, OK at PRECISION 1e-3.
        let refe = |critere: Value, computed: f64| {
            checks(
                vec![
                    ("VALE_REFE", Value::Real(1.0)),
                    ("REFERENCE", Value::Str("ANALYTIQUE".into())),
                    ("PRECISION", Value::Real(1e-3)),
                    ("CRITERE", critere),
                ],
                computed,
            )
            .unwrap()
        };
        // A reference of 1e-4 and a computed 5e-4: relative error 4 (NOOK), absolute 4e-4
        // (OK at 1e-3). ('ABSOLU', 'RELATIF') tests absolutely, ('RELATIF', 'ABSOLU')
        // relatively: the second value plays no part in the check.
        let small = |critere: Value| {
            checks(
                vec![
                    ("VALE_REFE", Value::Real(1e-4)),
                    ("REFERENCE", Value::Str("ANALYTIQUE".into())),
                    ("PRECISION", Value::Real(1e-3)),
                    ("CRITERE", critere),
                ],
                5e-4,
            )
            .unwrap()
        };
        assert!(small(texts("ABSOLU", "RELATIF"))[0].ok);
        assert!(!small(texts("RELATIF", "ABSOLU"))[0].ok);
        assert!(refe(texts("RELATIF", "ABSOLU"), 1.0005)[0].ok);
        // TOLE_MACHINE=(1e-2, 1e-6): the non-regression test has 1e-2.
        let calc = |tole: Value| {
            checks(
                vec![("VALE_CALC", Value::Real(2.0)), ("TOLE_MACHINE", tole)],
                2.01,
            )
            .unwrap()[0]
                .ok
        };
        assert!(calc(reals(1e-2, 1e-6)));
        assert!(!calc(reals(1e-6, 1e-2)));
        assert!(!calc(Value::Real(1e-6)));
    }
}
