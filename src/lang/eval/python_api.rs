//! The part of Code_Aster's Python API that its newer test files use around the commands
//! (docs/mode_non_line.md, "Files written with Code_Aster's Python API"):
//!
//! - `code_aster.init(...)` starts the study as DEBUT() does, `code_aster.init("--continue")`
//!   continues one as POURSUITE() does (their keywords, given in capitals, are passed on;
//!   the API's other options have no effect here), and
//!   `code_aster.close()` ends it as FIN() does;
//! - `MA = code_aster.Mesh()` then `MA.readAsterMeshFile("x.mail")` (or `readMedFile`,
//!   `readGmshFile`) reads the named file as LIRE_MAILLAGE does, into the concept MA; the
//!   file is looked for beside the command file, then in the working directory;
//! - `test = code_aster.TestCase()` and its assertions (`assertTrue`, `assertFalse`,
//!   `assertEqual`, `assertAlmostEqual` with `places` or `delta`, `assertGreater`,
//!   `assertGreaterEqual`, `assertLess`, `assertLessEqual`) count as tests, OK or NOOK, like
//!   the TEST_* operators; `test.printSummary()` does nothing (FIN prints the score).
//!
//! Anything else of the API is refused with an error that says what is supported.

use super::Evaluator;
use crate::error::Result;
use crate::lang::ast::{Arg, Name};
use crate::value::{ApiObject, CommandCall, Keyword, Span, Value};

/// The assertions a `code_aster.TestCase()` understands.
const ASSERTIONS: &[&str] = &[
    "assertTrue",
    "assertFalse",
    "assertEqual",
    "assertAlmostEqual",
    "assertGreater",
    "assertGreaterEqual",
    "assertLess",
    "assertLessEqual",
];

/// Python's truth of a value (the assertions' operand).
fn truth(v: &Value) -> bool {
    match v {
        Value::None => false,
        Value::Bool(b) => *b,
        Value::Int(i) => *i != 0,
        Value::Real(r) => *r != 0.0,
        Value::Str(s) => !s.is_empty(),
        Value::Seq(items) => !items.is_empty(),
        _ => true,
    }
}

impl Evaluator<'_> {
    /// `code_aster.NAME(...)`: `init`, `close`, `TestCase` and `Mesh`; None for any other
    /// name (the caller reports it as unsupported).
    pub(super) fn code_aster_call(
        &mut self,
        attr: &Name,
        args: &[Arg],
        span: Span,
    ) -> Result<Option<Value>> {
        match attr.text.as_str() {
            "init" => {
                let (pos, kws) = self.args(args)?;
                // "--continue" continues a study (POURSUITE); otherwise a new one (DEBUT).
                let continues = pos
                    .iter()
                    .any(|(v, _)| matches!(v, Value::Str(s) if s == "--continue"));
                let op = if continues { "POURSUITE" } else { "DEBUT" };
                self.study_command(op, kws, attr, span)
            }
            "close" => {
                let (_, kws) = self.args(args)?;
                self.study_command("FIN", kws, attr, span)
            }
            "TestCase" | "Mesh" => {
                let (pos, kws) = self.args(args)?;
                if let Some(s) = pos.first().map(|p| p.1).or(kws.first().map(|k| k.span)) {
                    return Err(self.syntax(
                        format!("code_aster.{}() takes no argument here", attr.text),
                        s,
                    ));
                }
                Ok(Some(Value::Api(if attr.text == "Mesh" {
                    ApiObject::Mesh
                } else {
                    ApiObject::TestCase
                })))
            }
            _ => Ok(None),
        }
    }

    /// DEBUT, POURSUITE or FIN for `code_aster.init(...)`/`close(...)`, with the keywords
    /// given in capitals (the command's own); the API's other options are dropped.
    fn study_command(
        &mut self,
        op: &str,
        kws: Vec<Keyword>,
        attr: &Name,
        span: Span,
    ) -> Result<Option<Value>> {
        let args: Vec<Keyword> = kws
            .into_iter()
            .filter(|k| super::is_upper_name(&k.name))
            .collect();
        let call = CommandCall {
            op: op.to_string(),
            result: None,
            reuse: None,
            args,
            span,
            op_span: attr.span,
        };
        self.host.call(call).map_err(|e| e.at(self.file, span))?;
        Ok(Some(Value::None))
    }

    /// `name.method(...)` on the API object `obj` bound to `name`.
    pub(super) fn api_method(
        &mut self,
        name: &str,
        obj: ApiObject,
        attr: &Name,
        args: &[Arg],
        span: Span,
    ) -> Result<Value> {
        match obj {
            ApiObject::Mesh => self.read_mesh(name, attr, args, span),
            ApiObject::TestCase => self.assertion(name, attr, args, span),
        }
    }

    /// `MA.readAsterMeshFile("x.mail")`: LIRE_MAILLAGE of that file into the concept MA.
    fn read_mesh(&mut self, name: &str, attr: &Name, args: &[Arg], span: Span) -> Result<Value> {
        let format = match attr.text.as_str() {
            "readAsterMeshFile" => "ASTER",
            "readMedFile" => "MED",
            "readGmshFile" => "GMSH",
            other => {
                return Err(self
                    .input(format!("code_aster.Mesh has no method '{other}' here"), attr.span)
                    .hint("read the mesh with readAsterMeshFile(\"file\"), readMedFile(\"file\") or readGmshFile(\"file\")"))
            }
        };
        let (pos, _) = self.args(args)?;
        let Some((Value::Str(path), _)) = pos.first() else {
            return Err(self
                .input(
                    format!("{name}.{}() needs the mesh file's name", attr.text),
                    span,
                )
                .hint(format!("write {name}.{}(\"mesh file\")", attr.text)));
        };
        let unit = self
            .host
            .map_file(path)
            .map_err(|e| e.at(self.file, span))?;
        let call = CommandCall {
            op: "LIRE_MAILLAGE".to_string(),
            result: Some(name.to_string()),
            reuse: None,
            args: vec![
                Keyword {
                    name: "FORMAT".to_string(),
                    value: Value::Str(format.to_string()),
                    span,
                },
                Keyword {
                    name: "UNITE".to_string(),
                    value: Value::Int(unit),
                    span,
                },
            ],
            span,
            op_span: attr.span,
        };
        let mesh = self.host.call(call).map_err(|e| e.at(self.file, span))?;
        self.env.bind(name, mesh);
        Ok(Value::None)
    }

    /// `test.assertAlmostEqual(a, b, delta=...)` and the other assertions: one test.
    fn assertion(&mut self, name: &str, attr: &Name, args: &[Arg], span: Span) -> Result<Value> {
        let what = attr.text.as_str();
        if what == "printSummary" {
            return Ok(Value::None);
        }
        if !ASSERTIONS.contains(&what) {
            return Err(self
                .input(
                    format!("code_aster.TestCase has no method '{what}' here"),
                    attr.span,
                )
                .hint(format!(
                    "supported: {}, printSummary",
                    ASSERTIONS.join(", ")
                )));
        }
        let (pos, kws) = self.args(args)?;
        let vals: Vec<Value> = pos.into_iter().map(|p| p.0).collect();
        if vals
            .iter()
            .chain(kws.iter().map(|k| &k.value))
            .any(|v| matches!(v, Value::Unknown))
        {
            // `aster-nl check`: the values are known only when the file runs.
            return Ok(Value::None);
        }
        let want = if matches!(what, "assertTrue" | "assertFalse") {
            1
        } else {
            2
        };
        if vals.len() < want {
            return Err(self.input(
                format!("{name}.{what}() needs {want} value(s), got {}", vals.len()),
                span,
            ));
        }
        let kw = |k: &str| kws.iter().find(|x| x.name == k).map(|x| x.value.clone());
        let num = |v: &Value| v.as_f64();
        let (ok, detail) = match what {
            "assertTrue" => (truth(&vals[0]), format!("{}", vals[0])),
            "assertFalse" => (!truth(&vals[0]), format!("{}", vals[0])),
            "assertEqual" => {
                let same = match (num(&vals[0]), num(&vals[1])) {
                    (Some(a), Some(b)) => a == b,
                    _ => vals[0] == vals[1],
                };
                (same, format!("{} == {}", vals[0], vals[1]))
            }
            "assertAlmostEqual" => {
                let (Some(a), Some(b)) = (num(&vals[0]), num(&vals[1])) else {
                    return Err(
                        self.input(format!("{name}.assertAlmostEqual() compares numbers"), span)
                    );
                };
                // unittest's rule: within `delta` when given, else equal once rounded to
                // `places` decimals (7 by default).
                match kw("delta").as_ref().and_then(num) {
                    Some(delta) => {
                        let ok = (a - b).abs() <= delta;
                        let rel = if ok { "<=" } else { ">" };
                        (
                            ok,
                            format!(
                                "{a:e} vs {b:e}, |difference| {:.3e} {rel} delta {delta:e}",
                                (a - b).abs()
                            ),
                        )
                    }
                    None => {
                        let places = kw("places").as_ref().and_then(num).unwrap_or(7.0);
                        let tol = 0.5 * 10f64.powf(-places);
                        (
                            (a - b).abs() < tol,
                            format!("{a:e} vs {b:e} to {places} places"),
                        )
                    }
                }
            }
            _ => {
                let (Some(a), Some(b)) = (num(&vals[0]), num(&vals[1])) else {
                    return Err(self.input(format!("{name}.{what}() compares numbers"), span));
                };
                let ok = match what {
                    "assertGreater" => a > b,
                    "assertGreaterEqual" => a >= b,
                    "assertLess" => a < b,
                    _ => a <= b,
                };
                (ok, format!("{a:e} vs {b:e}"))
            }
        };
        let line = format!(
            " {:<4} {name}.{what} (line {}): {detail}",
            if ok { "OK" } else { "NOOK" },
            span.line
        );
        self.host.record_test(ok, &line);
        Ok(Value::None)
    }
}
