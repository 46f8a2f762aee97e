//! Python builtins and `math` functions available to `.comm` files. Functions take
//! evaluated values and return a value or an error message (the evaluator adds the span).

use super::arith::{self, num_of, MAX_SEQ_LEN};
use super::ast::BinOp;
use crate::value::Value;

/// Functions of the `math` module (usable once imported).
pub const MATH_FUNCS: &[&str] = &[
    "sqrt", "sin", "cos", "tan", "exp", "log", "log10", "atan", "atan2", "asin", "acos", "fabs",
    "floor", "ceil", "pow", "sinh", "cosh", "tanh", "hypot", "degrees", "radians",
];

/// Constants of the `math` module.
pub fn math_const(name: &str) -> Option<f64> {
    match name {
        "pi" => Some(std::f64::consts::PI),
        "e" => Some(std::f64::consts::E),
        "tau" => Some(std::f64::consts::TAU),
        _ => None,
    }
}

/// The scalar functions of `numpy` a command file may call, and the math function that
/// computes each on a number (Code_Aster's files write `np.sqrt(2.)`).
pub fn numpy_function(name: &str) -> Option<&'static str> {
    let f = match name {
        "arcsin" => "asin",
        "arccos" => "acos",
        "arctan" => "atan",
        "arctan2" => "atan2",
        "abs" | "absolute" | "fabs" => "fabs",
        "power" => "pow",
        "deg2rad" => "radians",
        "rad2deg" => "degrees",
        other => {
            return MATH_FUNCS
                .iter()
                .copied()
                .find(|f| *f == other && *f != "pow")
        }
    };
    Some(f)
}

/// Constants of `numpy`.
pub fn numpy_const(name: &str) -> Option<f64> {
    match name {
        "pi" => Some(std::f64::consts::PI),
        "e" => Some(std::f64::consts::E),
        _ => None,
    }
}

/// Builtin functions, always available.
pub const BUILTINS: &[&str] = &[
    "abs",
    "float",
    "int",
    "min",
    "max",
    "len",
    "range",
    "list",
    "tuple",
    "sum",
    "str",
    "round",
    "print",
    "enumerate",
    "zip",
];

type R = std::result::Result<Value, String>;

fn arity(f: &str, args: &[Value], min: usize, max: usize) -> Result<(), String> {
    if args.len() < min || args.len() > max {
        let want = if min == max {
            format!("{min}")
        } else {
            format!("{min} to {max}")
        };
        return Err(format!(
            "{f}() takes {want} argument(s), got {}",
            args.len()
        ));
    }
    Ok(())
}

/// Argument `i` (arity is checked before, so a miss is only a defensive error).
fn nth<'a>(f: &str, args: &'a [Value], i: usize) -> Result<&'a Value, String> {
    args.get(i)
        .ok_or_else(|| format!("{f}() is missing argument {}", i + 1))
}

fn num(f: &str, v: &Value) -> Result<f64, String> {
    num_of(v).ok_or_else(|| format!("{f}() needs a number, got {}", v.kind_name()))
}

fn finite(f: &str, x: f64) -> R {
    if x.is_finite() {
        Ok(Value::Real(x))
    } else {
        Err(format!(
            "{f}(): math range error (result is not a finite number)"
        ))
    }
}

fn domain(f: &str, ok: bool, x: f64) -> Result<(), String> {
    if ok {
        Ok(())
    } else {
        Err(format!("{f}(): math domain error (argument {x})"))
    }
}

/// A real to an integer, as Python's int()/floor()/ceil() (which never overflow there).
fn to_int(f: &str, x: f64) -> R {
    // i64 holds [-2^63, 2^63); 2^63 is exact in f64 (i64::MAX is not).
    let bound = 2f64.powi(63);
    if (-bound..bound).contains(&x) {
        Ok(Value::Int(x as i64))
    } else {
        Err(format!("{f}(): {x} cannot be converted to an integer"))
    }
}

/// Calls `math.<f>`.
pub fn call_math(f: &str, args: &[Value]) -> R {
    if args.iter().any(|a| matches!(a, Value::Unknown)) {
        return Ok(Value::Unknown);
    }
    let one = |args: &[Value]| -> Result<f64, String> {
        arity(f, args, 1, 1)?;
        num(f, nth(f, args, 0)?)
    };
    let two = |args: &[Value]| -> Result<(f64, f64), String> {
        arity(f, args, 2, 2)?;
        Ok((num(f, nth(f, args, 0)?)?, num(f, nth(f, args, 1)?)?))
    };
    match f {
        "sqrt" => {
            let x = one(args)?;
            domain(f, x >= 0.0, x)?;
            finite(f, x.sqrt())
        }
        "sin" => finite(f, one(args)?.sin()),
        "cos" => finite(f, one(args)?.cos()),
        "tan" => finite(f, one(args)?.tan()),
        "sinh" => finite(f, one(args)?.sinh()),
        "cosh" => finite(f, one(args)?.cosh()),
        "tanh" => finite(f, one(args)?.tanh()),
        "exp" => finite(f, one(args)?.exp()),
        "atan" => finite(f, one(args)?.atan()),
        "fabs" => finite(f, one(args)?.abs()),
        "degrees" => finite(f, one(args)?.to_degrees()),
        "radians" => finite(f, one(args)?.to_radians()),
        "asin" | "acos" => {
            let x = one(args)?;
            domain(f, (-1.0..=1.0).contains(&x), x)?;
            finite(f, if f == "asin" { x.asin() } else { x.acos() })
        }
        "log10" => {
            let x = one(args)?;
            domain(f, x > 0.0, x)?;
            finite(f, x.log10())
        }
        "log" => {
            arity(f, args, 1, 2)?;
            let x = num(f, nth(f, args, 0)?)?;
            domain(f, x > 0.0, x)?;
            match args.get(1) {
                None => finite(f, x.ln()),
                Some(b) => {
                    let b = num(f, b)?;
                    domain(f, b > 0.0 && b != 1.0, b)?;
                    finite(f, x.ln() / b.ln())
                }
            }
        }
        "floor" => to_int(f, one(args)?.floor()),
        "ceil" => to_int(f, one(args)?.ceil()),
        "atan2" => {
            let (y, x) = two(args)?;
            finite(f, y.atan2(x))
        }
        "hypot" => {
            let (x, y) = two(args)?;
            finite(f, x.hypot(y))
        }
        "pow" => {
            let (x, y) = two(args)?;
            arith::binary(BinOp::Pow, &Value::Real(x), &Value::Real(y))
        }
        _ => Err(format!("module 'math' has no function '{f}'")),
    }
}

/// Calls a builtin; `print` is handled by the evaluator (it needs the host).
pub fn call_builtin(f: &str, args: &[Value]) -> R {
    if args.iter().any(|a| matches!(a, Value::Unknown)) {
        return Ok(Value::Unknown);
    }
    match f {
        "abs" => {
            arity(f, args, 1, 1)?;
            match nth(f, args, 0)? {
                Value::Real(r) => Ok(Value::Real(r.abs())),
                v => match num_of(v) {
                    Some(_) => arith::unary(super::ast::UnOp::Plus, v).and_then(|v| match v {
                        Value::Int(i) => i
                            .checked_abs()
                            .map(Value::Int)
                            .ok_or_else(|| "integer overflow in abs()".into()),
                        other => Ok(other),
                    }),
                    None => Err(format!("abs() needs a number, got {}", v.kind_name())),
                },
            }
        }
        "float" => {
            arity(f, args, 1, 1)?;
            match nth(f, args, 0)? {
                Value::Str(s) => match s.trim().parse::<f64>() {
                    Ok(x) if x.is_finite() => Ok(Value::Real(x)),
                    _ => Err(format!("could not convert '{s}' to a real")),
                },
                v => Ok(Value::Real(num(f, v)?)),
            }
        }
        "int" => {
            arity(f, args, 1, 1)?;
            match nth(f, args, 0)? {
                Value::Str(s) => s
                    .trim()
                    .parse::<i64>()
                    .map(Value::Int)
                    .map_err(|_| format!("could not convert '{s}' to an integer")),
                Value::Real(r) => to_int(f, r.trunc()),
                v => Ok(Value::Int(num(f, v)? as i64)),
            }
        }
        "round" => {
            arity(f, args, 1, 2)?;
            let x = num(f, nth(f, args, 0)?)?;
            match args.get(1) {
                // Python rounds halves to even.
                None => to_int(f, x.round_ties_even()),
                Some(Value::Int(n)) => {
                    let scale = 10f64.powi(i32::try_from(*n).unwrap_or(0).clamp(-300, 300));
                    let r = (x * scale).round_ties_even() / scale;
                    Ok(Value::Real(if r.is_finite() { r } else { x }))
                }
                Some(v) => Err(format!(
                    "round() needs an integer number of digits, got {}",
                    v.kind_name()
                )),
            }
        }
        "min" | "max" => {
            let items: &[Value] = match args {
                [Value::Seq(items)] => items,
                _ => args,
            };
            let mut best: Option<(&Value, f64)> = None;
            for v in items {
                let x = num(f, v)?;
                let better = match best {
                    None => true,
                    Some((_, b)) => (f == "min" && x < b) || (f == "max" && x > b),
                };
                if better {
                    best = Some((v, x));
                }
            }
            best.map(|(v, _)| v.clone())
                .ok_or_else(|| format!("{f}() of an empty list"))
        }
        "len" => {
            arity(f, args, 1, 1)?;
            match nth(f, args, 0)? {
                Value::Seq(items) => Ok(Value::Int(items.len() as i64)),
                Value::Str(s) => Ok(Value::Int(s.chars().count() as i64)),
                Value::Fact(k) => Ok(Value::Int(k.len() as i64)),
                Value::Table(t) => Ok(Value::Int(t.rows.len() as i64)),
                Value::Unknown => Ok(Value::Unknown),
                v => Err(format!("len() of {}", v.kind_name())),
            }
        }
        "range" => range(args),
        "enumerate" => {
            arity(f, args, 1, 1)?;
            let items = seq_items(f, nth(f, args, 0)?)?;
            let out = items
                .into_iter()
                .enumerate()
                .map(|(i, v)| Value::Seq(vec![Value::Int(i as i64), v]));
            Ok(Value::Seq(out.collect()))
        }
        "zip" => {
            let lists = args
                .iter()
                .map(|a| seq_items(f, a))
                .collect::<Result<Vec<_>, _>>()?;
            let n = lists.iter().map(Vec::len).min().unwrap_or(0);
            let rows = (0..n)
                .map(|i| Value::Seq(lists.iter().filter_map(|l| l.get(i).cloned()).collect()));
            Ok(Value::Seq(rows.collect()))
        }
        "list" | "tuple" => {
            arity(f, args, 0, 1)?;
            match args.first() {
                None => Ok(Value::Seq(vec![])),
                Some(Value::Seq(items)) => Ok(Value::Seq(items.clone())),
                Some(Value::Str(s)) => Ok(Value::Seq(
                    s.chars().map(|c| Value::Str(c.to_string())).collect(),
                )),
                Some(v) => Err(format!(
                    "{f}() needs a list, a tuple or a text, got {}",
                    v.kind_name()
                )),
            }
        }
        "sum" => {
            arity(f, args, 1, 2)?;
            let first = nth(f, args, 0)?;
            let Value::Seq(items) = first else {
                return Err(format!("sum() needs a list, got {}", first.kind_name()));
            };
            let mut acc = args.get(1).cloned().unwrap_or(Value::Int(0));
            for v in items {
                if num_of(v).is_none() {
                    return Err(format!("sum() needs numbers, got {}", v.kind_name()));
                }
                acc = arith::binary(BinOp::Add, &acc, v)?;
            }
            Ok(acc)
        }
        "str" => {
            arity(f, args, 1, 1)?;
            Ok(Value::Str(to_text(nth(f, args, 0)?)))
        }
        _ => Err(format!("name '{f}' is not defined")),
    }
}

/// The items of a list, or the characters of a text.
fn seq_items(f: &str, v: &Value) -> Result<Vec<Value>, String> {
    match v {
        Value::Seq(items) => Ok(items.clone()),
        Value::Str(s) => Ok(s.chars().map(|c| Value::Str(c.to_string())).collect()),
        v => Err(format!(
            "{f}() needs a list, a tuple or a text, got {}",
            v.kind_name()
        )),
    }
}

/// `str(v)`: texts without quotes, everything else as Python prints it.
pub fn to_text(v: &Value) -> String {
    match v {
        Value::Str(s) => s.clone(),
        other => other.to_string(),
    }
}

fn range(args: &[Value]) -> R {
    arity("range", args, 1, 3)?;
    let mut ints = Vec::new();
    for a in args {
        match a {
            Value::Int(i) => ints.push(*i),
            Value::Bool(b) => ints.push(i64::from(*b)),
            v => return Err(format!("range() needs integers, got {}", v.kind_name())),
        }
    }
    let (start, stop, step) = match ints.as_slice() {
        [stop] => (0, *stop, 1),
        [start, stop] => (*start, *stop, 1),
        [start, stop, step] => (*start, *stop, *step),
        _ => return Err("range() takes 1 to 3 arguments".into()),
    };
    if step == 0 {
        return Err("range() step must not be zero".into());
    }
    // Number of items, computed in i128 so that no bound can overflow.
    let (s, e, st) = (i128::from(start), i128::from(stop), i128::from(step));
    let count = if st > 0 {
        (e - s + st - 1).div_euclid(st)
    } else {
        (s - e - st - 1).div_euclid(-st)
    }
    .max(0);
    if count > MAX_SEQ_LEN as i128 {
        return Err(format!(
            "range() would have {count} items, more than the limit {MAX_SEQ_LEN}"
        ));
    }
    let out = (0..count)
        .map(|k| Value::Int((s + k * st) as i64))
        .collect();
    Ok(Value::Seq(out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use Value::{Int, Real, Seq};

    fn ints(v: &[i64]) -> Value {
        Seq(v.iter().map(|i| Int(*i)).collect())
    }

    #[test]
    fn ranges_like_python() {
        assert_eq!(range(&[Int(3)]), Ok(ints(&[0, 1, 2])));
        assert_eq!(range(&[Int(1), Int(7), Int(3)]), Ok(ints(&[1, 4])));
        assert_eq!(range(&[Int(5), Int(0), Int(-2)]), Ok(ints(&[5, 3, 1])));
        assert_eq!(range(&[Int(5), Int(0)]), Ok(ints(&[])));
        assert!(range(&[Int(0), Int(1), Int(0)]).is_err());
        assert!(range(&[Int(i64::MIN), Int(i64::MAX)]).is_err());
        assert!(range(&[Real(3.)]).is_err());
    }

    #[test]
    fn math_functions_and_domains() {
        // Exact in binary floating point.
        assert_eq!(call_math("sqrt", &[Int(16)]), Ok(Real(4.0)));
        assert_eq!(call_math("log", &[Int(8), Int(2)]), Ok(Real(3.0)));
        assert_eq!(call_math("floor", &[Real(-1.5)]), Ok(Int(-2)));
        assert_eq!(call_math("ceil", &[Real(1.2)]), Ok(Int(2)));
        assert_eq!(
            call_math("sqrt", &[Int(-1)]),
            Err("sqrt(): math domain error (argument -1)".into())
        );
        assert!(call_math("exp", &[Real(1000.)]).is_err());
        assert!(call_math("acos", &[Real(1.5)]).is_err());
        assert!(call_math("floor", &[Real(1e300)]).is_err());
        assert!(call_math("sqrt", &[]).is_err());
    }

    #[test]
    fn builtins_like_python() {
        assert_eq!(call_builtin("int", &[Real(-2.7)]), Ok(Int(-2)));
        assert_eq!(call_builtin("round", &[Real(2.5)]), Ok(Int(2)));
        assert_eq!(
            call_builtin("max", &[Int(1), Real(2.5), Int(2)]),
            Ok(Real(2.5))
        );
        assert_eq!(call_builtin("min", &[ints(&[3, 1, 2])]), Ok(Int(1)));
        assert_eq!(
            call_builtin("sum", &[Seq(vec![Int(1), Real(0.5)])]),
            Ok(Real(1.5))
        );
        assert_eq!(call_builtin("len", &[ints(&[3, 1])]), Ok(Int(2)));
        assert_eq!(
            call_builtin("str", &[Real(1.0)]),
            Ok(Value::Str("1.0".into()))
        );
        assert_eq!(
            call_builtin("float", &[Value::Str(" 2e3 ".into())]),
            Ok(Real(2000.))
        );
        assert_eq!(call_builtin("abs", &[Int(-3)]), Ok(Int(3)));
        assert!(call_builtin("abs", &[Int(i64::MIN)]).is_err());
        assert!(call_builtin("max", &[Seq(vec![])]).is_err());
        assert!(call_builtin("int", &[Real(f64::MAX)]).is_err());
        let pairs = call_builtin("zip", &[ints(&[1, 2, 3]), Value::Str("ab".into())]);
        let want = Seq(vec![
            Seq(vec![Int(1), Value::Str("a".into())]),
            Seq(vec![Int(2), Value::Str("b".into())]),
        ]);
        assert_eq!(pairs, Ok(want));
        assert_eq!(
            call_builtin("enumerate", &[ints(&[7])]),
            Ok(Seq(vec![ints(&[0, 7])]))
        );
    }
}
