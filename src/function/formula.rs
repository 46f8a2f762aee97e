//! Formulas (`formule`, FORMULE): a function given by an expression of its parameters,
//! evaluated by the command language's own evaluator (`lang::formula`), and
//! [`AnyFunction`], what the operators that take "a function of INST" read: a tabulated
//! function (`fonction_sdaster`) or a formula of one parameter.
//!
//! A formula's constants are numbers fixed when FORMULE ran (its other keywords and the
//! command file's variables it uses); its functions are `math`'s and `abs min max float
//! int round`. Its names are checked when it is built, so that a misspelt name is an error
//! of FORMULE, not of the first evaluation.

use super::Function;
use crate::error::{Error, Result};
use crate::lang::formula::{check_names, Expression, Scope};
use crate::value::Value;
use serde::{Deserialize, Serialize};
use std::cell::RefCell;

/// What is stored of a formula.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FormulaDef {
    /// Its parameters (NOM_PARA), in order.
    pub nom_para: Vec<String>,
    /// The expression as written (VALE).
    pub vale: String,
    /// Names of the expression bound to numbers at definition.
    pub constants: Vec<(String, f64)>,
}

/// A formula ready to evaluate.
#[derive(Debug)]
pub struct Formula {
    /// Concept name, for messages.
    pub name: String,
    def: FormulaDef,
    expr: Expression,
    /// The constants bound; the parameters are bound at each evaluation.
    scope: RefCell<Scope>,
}

fn is_identifier(s: &str) -> bool {
    let mut c = s.chars();
    c.next()
        .is_some_and(|f| f.is_ascii_alphabetic() || f == '_')
        && c.all(|x| x.is_ascii_alphanumeric() || x == '_')
}

impl Formula {
    /// Parses and checks `def`: the parameters are distinct names, the expression parses,
    /// and every name it reads is a parameter, a constant or `pi`, every function it calls
    /// one of the scope's. Errors name NOM_PARA or VALE.
    pub fn new(name: &str, def: FormulaDef) -> Result<Formula> {
        if def.nom_para.is_empty() {
            return Err(
                Error::validation(format!("formula {name} has no parameter")).keyword("NOM_PARA"),
            );
        }
        for (i, p) in def.nom_para.iter().enumerate() {
            if !is_identifier(p) {
                return Err(Error::validation(format!(
                    "'{p}' cannot name a parameter of formula {name}: a parameter is a name \
                     (letters, digits, _)"
                ))
                .keyword("NOM_PARA"));
            }
            if def.nom_para[..i].contains(p) {
                return Err(Error::validation(format!(
                    "parameter '{p}' of formula {name} is given twice"
                ))
                .keyword("NOM_PARA"));
            }
        }
        let expr = Expression::parse(&def.vale).map_err(|e| e.keyword("VALE"))?;
        let mut scope = Scope::new();
        for (n, x) in &def.constants {
            scope.bind(n, *x);
        }
        let constants: Vec<String> = def.constants.iter().map(|(c, _)| c.clone()).collect();
        check_names(&expr, &def.nom_para, &constants)
            .map_err(|e| e.keyword("VALE"))
            .map_err(|e| Error {
                message: format!("formula {name}: {}", e.message),
                ..e
            })?;
        Ok(Formula {
            name: name.to_string(),
            def,
            expr,
            scope: RefCell::new(scope),
        })
    }

    pub fn def(&self) -> &FormulaDef {
        &self.def
    }

    pub fn nom_para(&self) -> &[String] {
        &self.def.nom_para
    }

    /// The value at `args` (one per parameter, in NOM_PARA's order).
    pub fn eval(&self, args: &[f64]) -> Result<f64> {
        let at = || {
            self.def
                .nom_para
                .iter()
                .zip(args)
                .map(|(p, x)| format!("{p}={x}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if args.len() != self.def.nom_para.len() {
            return Err(Error::input(format!(
                "formula {} takes {} parameter(s) ({}), given {}",
                self.name,
                self.def.nom_para.len(),
                self.def.nom_para.join(", "),
                args.len()
            )));
        }
        let mut scope = self.scope.try_borrow_mut().map_err(|_| {
            Error::internal(format!("formula {} evaluated inside itself", self.name))
        })?;
        for (p, x) in self.def.nom_para.iter().zip(args) {
            scope.bind(p, *x);
        }
        let v = self.expr.eval(&mut scope).map_err(|e| Error {
            message: format!(
                "formula {} at {}: {} (in '{}')",
                self.name,
                at(),
                e.message,
                self.expr.text()
            ),
            ..e
        })?;
        let x = match v {
            Value::Real(x) => x,
            Value::Int(i) => i as f64,
            Value::Bool(b) => f64::from(u8::from(b)),
            other => {
                return Err(Error::input(format!(
                    "formula {} at {} gives {}, not a number",
                    self.name,
                    at(),
                    other.kind_name()
                )))
            }
        };
        if !x.is_finite() {
            return Err(Error::input(format!(
                "formula {} at {} is not finite",
                self.name,
                at()
            )));
        }
        Ok(x)
    }
}

/// A function of one parameter: tabulated, or a formula of one parameter.
#[derive(Debug)]
pub enum AnyFunction {
    Tabulated(Function),
    /// Boxed: a formula (its parsed expression and scope) is much larger than a table.
    Formula(Box<Formula>),
}

impl AnyFunction {
    /// `f` as a function of one parameter: a formula of several parameters is refused.
    pub fn of_formula(f: Formula) -> Result<AnyFunction> {
        if f.nom_para().len() != 1 {
            return Err(Error::input(format!(
                "formula {} has {} parameters ({}): a function of one parameter is expected here",
                f.name,
                f.nom_para().len(),
                f.nom_para().join(", ")
            )));
        }
        Ok(AnyFunction::Formula(Box::new(f)))
    }

    pub fn name(&self) -> &str {
        match self {
            AnyFunction::Tabulated(f) => &f.name,
            AnyFunction::Formula(f) => &f.name,
        }
    }

    /// The name of its parameter.
    pub fn nom_para(&self) -> &str {
        match self {
            AnyFunction::Tabulated(f) => &f.nom_para,
            AnyFunction::Formula(f) => f.nom_para().first().map_or("", String::as_str),
        }
    }

    /// The value at `x`.
    pub fn eval(&self, x: f64) -> Result<f64> {
        match self {
            AnyFunction::Tabulated(f) => f.eval(x),
            AnyFunction::Formula(f) => f.eval(&[x]),
        }
    }

    /// The values at every abscissa of `xs`, in order (CALC_FONC_INTERP).
    pub fn sample(&self, xs: &[f64]) -> Result<Vec<f64>> {
        xs.iter().map(|&x| self.eval(x)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn def(vale: &str, para: &[&str], constants: &[(&str, f64)]) -> FormulaDef {
        FormulaDef {
            nom_para: para.iter().map(|s| s.to_string()).collect(),
            vale: vale.to_string(),
            constants: constants.iter().map(|(n, x)| (n.to_string(), *x)).collect(),
        }
    }

    #[test]
    fn evaluates_as_the_expression_written_in_rust() {
        // Same f64 operations in the same order: equal to the last bit.
        let w = 2.0 * std::f64::consts::PI * 10.0;
        let f = Formula::new(
            "ACCE1",
            def("sin(OMEGAA*INST) ", &["INST"], &[("OMEGAA", w)]),
        )
        .unwrap();
        for t in [0.0, 0.0123, 0.5, 1.0] {
            assert_eq!(f.eval(&[t]).unwrap(), (w * t).sin());
        }
        let g = Formula::new("G", def("X**2 + 3*Y - pi", &["X", "Y"], &[])).unwrap();
        assert_eq!(
            g.eval(&[1.5, -2.0]).unwrap(),
            1.5f64.powf(2.0) + 3.0 * -2.0 - std::f64::consts::PI
        );
        assert!(g
            .eval(&[1.0])
            .unwrap_err()
            .message
            .contains("takes 2 parameter"));
        assert!(AnyFunction::of_formula(g).is_err());
        let any = AnyFunction::of_formula(f).unwrap();
        assert_eq!(any.nom_para(), "INST");
        assert_eq!(
            any.sample(&[0.0, 0.025]).unwrap(),
            vec![0.0, (w * 0.025).sin()]
        );
    }

    #[test]
    fn names_are_checked_when_built() {
        let err =
            Formula::new("F", def("sin(OMEGA*INST)", &["INST"], &[("OMEGAA", 1.0)])).unwrap_err();
        assert_eq!(err.keyword.as_deref(), Some("VALE"));
        assert!(err.message.contains("formula F: name 'OMEGA'"), "{err}");
        assert_eq!(err.hint.as_deref(), Some("did you mean 'OMEGAA'?"));
        let err = Formula::new("F", def("sine(INST)", &["INST"], &[])).unwrap_err();
        assert!(err.message.contains("'sine' is not a function"), "{err}");
        assert_eq!(err.hint.as_deref(), Some("did you mean 'sin'?"));
        let err = Formula::new("F", def("sin(INST", &["INST"], &[])).unwrap_err();
        assert_eq!(err.keyword.as_deref(), Some("VALE"));
        let err = Formula::new("F", def("INST", &["INST", "INST"], &[])).unwrap_err();
        assert_eq!(err.keyword.as_deref(), Some("NOM_PARA"));
        let err = Formula::new("F", def("1", &["2X"], &[])).unwrap_err();
        assert_eq!(err.keyword.as_deref(), Some("NOM_PARA"));
        let err = Formula::new("F", def("os.sin(INST)", &["INST"], &[])).unwrap_err();
        assert!(err.message.contains("'os'"), "{err}");
    }

    #[test]
    fn evaluation_errors_name_the_formula_and_the_parameter() {
        let f = Formula::new("F", def("log(INST)", &["INST"], &[])).unwrap();
        let err = f.eval(&[-1.0]).unwrap_err();
        assert!(err.message.contains("formula F at INST=-1"), "{err}");
        assert!(err.message.contains("math domain error"), "{err}");
        let f = Formula::new("F", def("'a'", &["INST"], &[])).unwrap();
        assert!(f.eval(&[0.0]).unwrap_err().message.contains("a text"));
    }
}
