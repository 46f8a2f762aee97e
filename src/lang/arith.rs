//! Python 3 arithmetic on [`Value`]s, without panics: integer overflow, division by zero,
//! non-finite reals and oversized sequences are errors (messages without location; the
//! evaluator adds the span of the offending expression).

use super::ast::{BinOp, UnOp};
use crate::value::Value;

/// Longest list or text a `*` or `+` may build.
pub const MAX_SEQ_LEN: usize = 1_000_000;

pub type OpResult = std::result::Result<Value, String>;

/// Bools count as integers, as in Python.
fn int_of(v: &Value) -> Option<i64> {
    match v {
        Value::Int(i) => Some(*i),
        Value::Bool(b) => Some(i64::from(*b)),
        _ => None,
    }
}

pub fn num_of(v: &Value) -> Option<f64> {
    match v {
        Value::Real(r) => Some(*r),
        _ => int_of(v).map(|i| i as f64),
    }
}

fn real(op: &str, r: f64) -> OpResult {
    if r.is_finite() {
        Ok(Value::Real(r))
    } else {
        Err(format!(
            "the result of '{op}' is not a finite number (overflow)"
        ))
    }
}

fn overflow(op: BinOp) -> String {
    format!("integer overflow in '{}'", op.symbol())
}

pub fn unary(op: UnOp, v: &Value) -> OpResult {
    match (op, v) {
        (_, Value::Unknown) => Ok(Value::Unknown),
        (UnOp::Plus, Value::Real(r)) => Ok(Value::Real(*r)),
        (UnOp::Neg, Value::Real(r)) => Ok(Value::Real(-r)),
        (_, v) => match int_of(v) {
            Some(i) if op == UnOp::Plus => Ok(Value::Int(i)),
            Some(i) => i
                .checked_neg()
                .map(Value::Int)
                .ok_or_else(|| "integer overflow in '-'".to_string()),
            None => Err(format!(
                "bad operand for unary {}: {}",
                if op == UnOp::Neg { "-" } else { "+" },
                v.kind_name()
            )),
        },
    }
}

pub fn binary(op: BinOp, a: &Value, b: &Value) -> OpResult {
    if matches!(a, Value::Unknown) || matches!(b, Value::Unknown) {
        return Ok(Value::Unknown);
    }
    if let (Some(x), Some(y)) = (int_of(a), int_of(b)) {
        return int_op(op, x, y);
    }
    if let (Some(x), Some(y)) = (num_of(a), num_of(b)) {
        return real_op(op, x, y);
    }
    match (op, a, b) {
        (BinOp::Add, Value::Str(x), Value::Str(y)) => {
            check_len(x.len() + y.len())?;
            Ok(Value::Str(format!("{x}{y}")))
        }
        (BinOp::Add, Value::Seq(x), Value::Seq(y)) => {
            check_len(x.len() + y.len())?;
            Ok(Value::Seq(x.iter().chain(y).cloned().collect()))
        }
        (BinOp::Mul, Value::Seq(_) | Value::Str(_), n) if int_of(n).is_some() => {
            repeat(a, int_of(n))
        }
        (BinOp::Mul, n, Value::Seq(_) | Value::Str(_)) if int_of(n).is_some() => {
            repeat(b, int_of(n))
        }
        (BinOp::Mod, Value::Str(_), _) => Err("string formatting with '%' is not supported".into()),
        _ => Err(format!(
            "unsupported operand types for '{}': {} and {}",
            op.symbol(),
            a.kind_name(),
            b.kind_name()
        )),
    }
}

fn check_len(n: usize) -> Result<(), String> {
    if n > MAX_SEQ_LEN {
        Err(format!(
            "the result would have {n} items, more than the limit {MAX_SEQ_LEN}"
        ))
    } else {
        Ok(())
    }
}

fn repeat(v: &Value, n: Option<i64>) -> OpResult {
    let n = usize::try_from(n.unwrap_or(0).max(0)).unwrap_or(usize::MAX);
    match v {
        Value::Str(s) => {
            check_len(s.len().saturating_mul(n))?;
            Ok(Value::Str(s.repeat(n)))
        }
        Value::Seq(items) => {
            check_len(items.len().saturating_mul(n))?;
            let mut out = Vec::with_capacity(items.len() * n);
            for _ in 0..n {
                out.extend(items.iter().cloned());
            }
            Ok(Value::Seq(out))
        }
        _ => Err(format!("cannot repeat {}", v.kind_name())),
    }
}

fn int_op(op: BinOp, x: i64, y: i64) -> OpResult {
    let zero = || Err("division by zero".to_string());
    match op {
        BinOp::Add => x.checked_add(y).map(Value::Int).ok_or_else(|| overflow(op)),
        BinOp::Sub => x.checked_sub(y).map(Value::Int).ok_or_else(|| overflow(op)),
        BinOp::Mul => x.checked_mul(y).map(Value::Int).ok_or_else(|| overflow(op)),
        // Python 3: int / int is a real.
        BinOp::Div if y == 0 => zero(),
        BinOp::Div => real("/", x as f64 / y as f64),
        BinOp::FloorDiv | BinOp::Mod if y == 0 => zero(),
        BinOp::FloorDiv => {
            let q = x.checked_div(y).ok_or_else(|| overflow(op))?;
            // Python rounds towards minus infinity.
            let adjust = x % y != 0 && ((x < 0) != (y < 0));
            Ok(Value::Int(if adjust { q - 1 } else { q }))
        }
        BinOp::Mod => {
            let r = x.checked_rem(y).unwrap_or(0); // only MIN % -1, which is 0
                                                   // Python's remainder has the sign of the divisor.
            Ok(Value::Int(if r != 0 && ((r < 0) != (y < 0)) {
                r + y
            } else {
                r
            }))
        }
        BinOp::Pow if y >= 0 => {
            let e = u32::try_from(y).map_err(|_| overflow(op))?;
            x.checked_pow(e).map(Value::Int).ok_or_else(|| overflow(op))
        }
        BinOp::Pow => real_op(op, x as f64, y as f64),
    }
}

fn real_op(op: BinOp, x: f64, y: f64) -> OpResult {
    let s = op.symbol();
    match op {
        BinOp::Add => real(s, x + y),
        BinOp::Sub => real(s, x - y),
        BinOp::Mul => real(s, x * y),
        BinOp::Div | BinOp::FloorDiv | BinOp::Mod if y == 0.0 => Err("division by zero".into()),
        BinOp::Div => real(s, x / y),
        BinOp::FloorDiv => real(s, (x / y).floor()),
        BinOp::Mod => {
            let r = x % y;
            real(
                s,
                if r != 0.0 && ((r < 0.0) != (y < 0.0)) {
                    r + y
                } else {
                    r
                },
            )
        }
        BinOp::Pow => {
            if x == 0.0 && y < 0.0 {
                return Err("0.0 cannot be raised to a negative power".into());
            }
            if x < 0.0 && y.fract() != 0.0 {
                return Err("a negative number cannot be raised to a fractional power".into());
            }
            real(s, x.powf(y))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Value::{Int, Real};

    #[test]
    fn python_integer_semantics() {
        assert_eq!(binary(BinOp::Div, &Int(7), &Int(2)), Ok(Real(3.5)));
        assert_eq!(binary(BinOp::FloorDiv, &Int(-7), &Int(2)), Ok(Int(-4)));
        assert_eq!(binary(BinOp::FloorDiv, &Int(7), &Int(-2)), Ok(Int(-4)));
        assert_eq!(binary(BinOp::Mod, &Int(-7), &Int(2)), Ok(Int(1)));
        assert_eq!(binary(BinOp::Mod, &Int(7), &Int(-2)), Ok(Int(-1)));
        assert_eq!(binary(BinOp::Mod, &Int(i64::MIN), &Int(-1)), Ok(Int(0)));
        assert_eq!(binary(BinOp::Pow, &Int(2), &Int(-1)), Ok(Real(0.5)));
        assert_eq!(binary(BinOp::Pow, &Int(3), &Int(4)), Ok(Int(81)));
        assert_eq!(binary(BinOp::Add, &Value::Bool(true), &Int(1)), Ok(Int(2)));
    }

    #[test]
    fn python_real_semantics() {
        assert_eq!(binary(BinOp::Mod, &Real(-7.5), &Int(2)), Ok(Real(0.5)));
        assert_eq!(binary(BinOp::FloorDiv, &Real(7.5), &Int(2)), Ok(Real(3.0)));
        assert_eq!(binary(BinOp::Mul, &Int(2), &Real(1.5)), Ok(Real(3.0)));
    }

    #[test]
    fn errors_instead_of_panics() {
        assert_eq!(
            binary(BinOp::Div, &Int(1), &Int(0)),
            Err("division by zero".into())
        );
        assert_eq!(
            binary(BinOp::FloorDiv, &Int(i64::MIN), &Int(-1)),
            Err("integer overflow in '//'".into())
        );
        assert!(binary(BinOp::Pow, &Int(9), &Int(99)).is_err());
        assert!(binary(BinOp::Pow, &Int(2), &Int(i64::MAX)).is_err());
        assert!(binary(BinOp::Pow, &Real(10.), &Int(400)).is_err());
        assert!(binary(BinOp::Pow, &Real(-8.), &Real(1. / 3.)).is_err());
        assert!(binary(BinOp::Mul, &Value::Seq(vec![Int(1)]), &Int(i64::MAX)).is_err());
        assert!(unary(UnOp::Neg, &Int(i64::MIN)).is_err());
        assert_eq!(
            binary(BinOp::Mul, &Value::Str("a".into()), &Real(1.5)),
            Err("unsupported operand types for '*': a text and a real".into())
        );
    }

    #[test]
    fn sequences_and_texts() {
        let t = Value::Seq(vec![Real(0.)]);
        assert_eq!(
            binary(BinOp::Mul, &t, &Int(3)),
            Ok(Value::Seq(vec![Real(0.); 3]))
        );
        assert_eq!(
            binary(BinOp::Mul, &Int(2), &Value::Str("ab".into())),
            Ok(Value::Str("abab".into()))
        );
        assert_eq!(
            binary(BinOp::Add, &Value::Str("a".into()), &Value::Str("b".into())),
            Ok(Value::Str("ab".into()))
        );
        assert_eq!(binary(BinOp::Mul, &t, &Int(-2)), Ok(Value::Seq(vec![])));
    }
}
