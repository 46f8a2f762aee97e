//! `np.savetxt(fname, X, ...)`: numbers written to a text file as numpy writes them. X is a
//! list of numbers (one per line, as numpy writes a 1-D array) or a list of rows (one row
//! per line); `fmt` is one printf conversion for every number (`%.18e`, numpy's default;
//! `%e`, `%E`, `%f`, `%g`, `%d` with width and precision), `delimiter`, `newline`, `header`,
//! `footer` and `comments` as numpy's. The host writes the file (beside the command file).

use super::Evaluator;
use crate::error::Result;
use crate::lang::ast::Arg;
use crate::value::{Span, Value};

/// savetxt's arguments after X, in numpy's positional order.
const OPTIONS: [&str; 6] = [
    "fmt",
    "delimiter",
    "newline",
    "header",
    "footer",
    "comments",
];

/// One printf conversion: `%[-+ 0][width][.precision]conv`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Conversion {
    left: bool,
    plus: bool,
    zero: bool,
    width: usize,
    precision: Option<usize>,
    conv: char,
}

fn parse_fmt(fmt: &str) -> std::result::Result<Conversion, String> {
    let bad = || {
        format!(
            "fmt='{fmt}': aster-nl's savetxt takes one printf conversion for every number \
             (%.18e, %.6f, %12.5E, %g, %d, ...)"
        )
    };
    let rest = fmt.strip_prefix('%').ok_or_else(bad)?;
    let mut c = Conversion {
        left: false,
        plus: false,
        zero: false,
        width: 0,
        precision: None,
        conv: 'e',
    };
    let mut chars = rest.chars().peekable();
    while let Some(&f) = chars.peek() {
        match f {
            '-' => c.left = true,
            '+' => c.plus = true,
            '0' => c.zero = true,
            ' ' => {}
            _ => break,
        }
        chars.next();
    }
    let digits = |chars: &mut std::iter::Peekable<std::str::Chars>| {
        let mut n = String::new();
        while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
            n.push(d);
            chars.next();
        }
        n
    };
    let w = digits(&mut chars);
    c.width = if w.is_empty() {
        0
    } else {
        w.parse().map_err(|_| bad())?
    };
    if chars.peek() == Some(&'.') {
        chars.next();
        let p = digits(&mut chars);
        c.precision = Some(if p.is_empty() {
            0
        } else {
            p.parse().map_err(|_| bad())?
        });
    }
    c.conv = chars.next().ok_or_else(bad)?;
    if chars.next().is_some() || !"eEfFgGdi".contains(c.conv) || c.width > 100 {
        return Err(bad());
    }
    if c.precision.is_some_and(|p| p > 100) {
        return Err(bad());
    }
    Ok(c)
}

/// `x` in C's exponent form: mantissa, 'e', sign, at least two exponent digits.
fn exponent_form(x: f64, precision: usize, upper: bool) -> String {
    let s = format!("{x:.precision$e}");
    let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
    let (sign, digits) = match exp.strip_prefix('-') {
        Some(d) => ('-', d),
        None => ('+', exp),
    };
    let e = if upper { 'E' } else { 'e' };
    format!("{mantissa}{e}{sign}{digits:0>2}")
}

/// C's %g: with P significant digits and X the exponent %e would print, %e when X < -4 or
/// X >= P, else %f with P - 1 - X decimals; trailing zeros removed.
fn general_form(x: f64, precision: usize, upper: bool) -> String {
    let p = precision.max(1);
    let e_form = exponent_form(x, p - 1, upper);
    let at = e_form.find(['e', 'E']).unwrap_or(e_form.len());
    let exp: i64 = e_form[at..]
        .trim_start_matches(['e', 'E'])
        .parse()
        .unwrap_or(0);
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if exp < -4 || exp >= p as i64 {
        let (m, e) = e_form.split_at(at);
        format!("{}{e}", trim(m))
    } else {
        let decimals = (p as i64 - 1 - exp).max(0) as usize;
        trim(&format!("{x:.decimals$}"))
    }
}

impl Conversion {
    fn apply(&self, x: f64) -> String {
        let p = self.precision.unwrap_or(6);
        let mut s = if !x.is_finite() {
            if x.is_nan() {
                "nan".to_string()
            } else if x > 0.0 {
                "inf".to_string()
            } else {
                "-inf".to_string()
            }
        } else {
            match self.conv {
                'e' | 'E' => exponent_form(x, p, self.conv == 'E'),
                'f' | 'F' => format!("{x:.p$}"),
                'g' | 'G' => general_form(x, p, self.conv == 'G'),
                // %d of a real truncates toward zero, as Python's does.
                _ => format!("{}", x.trunc() as i64),
            }
        };
        if self.plus && !s.starts_with('-') {
            s.insert(0, '+');
        }
        if s.len() < self.width {
            let pad = self.width - s.len();
            if self.left {
                s.push_str(&" ".repeat(pad));
            } else if self.zero && x.is_finite() {
                let at = usize::from(s.starts_with(['-', '+']));
                s.insert_str(at, &"0".repeat(pad));
            } else {
                s.insert_str(0, &" ".repeat(pad));
            }
        }
        s
    }
}

/// The options of one savetxt call.
struct Options {
    conversion: Conversion,
    delimiter: String,
    newline: String,
    header: String,
    footer: String,
    comments: String,
}

/// The text savetxt writes for `x`.
fn text_of(x: &Value, o: &Options) -> std::result::Result<String, String> {
    let number = |v: &Value| {
        v.as_f64().ok_or_else(|| {
            format!(
                "savetxt writes numbers: X holds {} where a number was expected",
                v.kind_name()
            )
        })
    };
    let Value::Seq(items) = x else {
        return Err(format!(
            "savetxt's X is a list (or a list of rows), not {}",
            x.kind_name()
        ));
    };
    let mut out = String::new();
    let comment = |out: &mut String, text: &str| {
        for line in text.split('\n') {
            out.push_str(&o.comments);
            out.push_str(line);
            out.push_str(&o.newline);
        }
    };
    if !o.header.is_empty() {
        comment(&mut out, &o.header);
    }
    for item in items {
        let row: Vec<f64> = match item {
            Value::Seq(cells) => cells.iter().map(number).collect::<Result<_, _>>()?,
            v => vec![number(v)?],
        };
        let cells: Vec<String> = row.iter().map(|v| o.conversion.apply(*v)).collect();
        out.push_str(&cells.join(&o.delimiter));
        out.push_str(&o.newline);
    }
    if !o.footer.is_empty() {
        comment(&mut out, &o.footer);
    }
    Ok(out)
}

impl Evaluator<'_> {
    /// `np.savetxt(fname, X, fmt=..., delimiter=..., ...)`.
    pub(super) fn numpy_savetxt(&mut self, args: &[Arg], span: Span) -> Result<Value> {
        let (pos, kws) = self.args(args)?;
        if pos.len() < 2 && !kws.iter().any(|k| k.name == "X") {
            return Err(self.input(
                "np.savetxt(fname, X, ...) takes the file's name and the values",
                span,
            ));
        }
        let mut named: Vec<(String, Value, Span)> = Vec::new();
        let positional = ["fname", "X"].iter().chain(OPTIONS.iter());
        if pos.len() > 2 + OPTIONS.len() {
            return Err(self.input("np.savetxt() takes at most 8 positional arguments", span));
        }
        for (n, (v, s)) in positional.zip(pos) {
            named.push((n.to_string(), v, s));
        }
        for k in kws {
            if !["fname", "X"].contains(&k.name.as_str()) && !OPTIONS.contains(&k.name.as_str()) {
                return Err(self
                    .input(
                        format!("np.savetxt() has no argument '{}' here", k.name),
                        k.span,
                    )
                    .hint(format!("it takes fname, X, {}", OPTIONS.join(", "))));
            }
            if named.iter().any(|n| n.0 == k.name) {
                return Err(self.input(format!("argument '{}' is given twice", k.name), k.span));
            }
            named.push((k.name, k.value, k.span));
        }
        let get = |n: &str| named.iter().find(|g| g.0 == n);
        if named.iter().any(|n| matches!(n.1, Value::Unknown)) {
            return Ok(Value::None); // `check`: the values exist only when the file runs
        }
        let text_arg = |n: &str, default: &str| -> std::result::Result<String, (String, Span)> {
            match get(n) {
                None => Ok(default.to_string()),
                Some((_, Value::Str(s), _)) => Ok(s.clone()),
                Some((_, v, s)) => Err((
                    format!("np.savetxt({n}=...) is a text, not {}", v.kind_name()),
                    *s,
                )),
            }
        };
        let opts = (|| {
            let fmt = text_arg("fmt", "%.18e")?;
            let conversion =
                parse_fmt(&fmt).map_err(|m| (m, get("fmt").map(|g| g.2).unwrap_or(span)))?;
            Ok::<_, (String, Span)>(Options {
                conversion,
                delimiter: text_arg("delimiter", " ")?,
                newline: text_arg("newline", "\n")?,
                header: text_arg("header", "")?,
                footer: text_arg("footer", "")?,
                comments: text_arg("comments", "# ")?,
            })
        })();
        let opts = opts.map_err(|(m, s)| self.input(m, s))?;
        let fname = match get("fname") {
            Some((_, Value::Str(s), _)) => s.clone(),
            Some((_, v, s)) => {
                return Err(self.input(
                    format!("np.savetxt's fname is a file name, not {}", v.kind_name()),
                    *s,
                ))
            }
            None => return Err(self.input("np.savetxt() needs fname, the file's name", span)),
        };
        let (x, xspan) = match get("X") {
            Some((_, v, s)) => (v.clone(), *s),
            None => return Err(self.input("np.savetxt() needs X, the values", span)),
        };
        let text = text_of(&x, &opts).map_err(|m| self.input(m, xspan))?;
        self.host
            .save_text(&fname, &text)
            .map_err(|e| e.at(self.file, span))?;
        Ok(Value::None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmt(f: &str, x: f64) -> String {
        parse_fmt(f).unwrap().apply(x)
    }

    /// The strings Python's `'%...' % x` gives for these (checked with Python 3).
    #[test]
    fn conversions_match_python() {
        assert_eq!(fmt("%.18e", 1698.44669074479), "1.698446690744789976e+03");
        assert_eq!(fmt("%.3e", -0.00012345), "-1.234e-04");
        assert_eq!(fmt("%E", 1e100), "1.000000E+100");
        assert_eq!(fmt("%.2f", 2.345), "2.35");
        assert_eq!(fmt("%8.3f", -1.5), "  -1.500");
        assert_eq!(format!("{}|", fmt("%-8.3f", 1.5)), "1.500   |");
        assert_eq!(fmt("%08.3f", -1.5), "-001.500");
        assert_eq!(fmt("%g", 0.0001), "0.0001");
        assert_eq!(fmt("%g", 0.00001), "1e-05");
        assert_eq!(fmt("%g", 123456.0), "123456");
        assert_eq!(fmt("%g", 1234567.0), "1.23457e+06");
        assert_eq!(fmt("%.3g", 2.5), "2.5");
        assert_eq!(fmt("%g", 999999.5), "1e+06");
        assert_eq!(fmt("%g", 0.0), "0");
        assert_eq!(fmt("%d", -2.7), "-2");
        assert_eq!(fmt("%+.1f", 2.0), "+2.0");
        assert!(parse_fmt("%s").is_err());
        assert!(parse_fmt("%.3f %.3f").is_err());
        assert!(parse_fmt("x").is_err());
    }

    #[test]
    fn rows_and_columns_as_numpy_writes_them() {
        let o = Options {
            conversion: parse_fmt("%.1f").unwrap(),
            delimiter: ",".into(),
            newline: "\n".into(),
            header: "a,b".into(),
            footer: String::new(),
            comments: "# ".into(),
        };
        let rows = Value::Seq(vec![
            Value::Seq(vec![Value::Real(1.0), Value::Int(2)]),
            Value::Seq(vec![Value::Real(3.0), Value::Real(4.25)]),
        ]);
        assert_eq!(text_of(&rows, &o).unwrap(), "# a,b\n1.0,2.0\n3.0,4.2\n");
        let col = Value::Seq(vec![Value::Real(1.0), Value::Real(2.0)]);
        let o = Options {
            header: String::new(),
            ..o
        };
        assert_eq!(text_of(&col, &o).unwrap(), "1.0\n2.0\n");
        let bad = Value::Seq(vec![Value::Str("x".into())]);
        assert!(text_of(&bad, &o).unwrap_err().contains("a text"));
        assert!(text_of(&Value::Real(1.0), &o).is_err());
    }
}
