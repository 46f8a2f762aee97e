//! How big a value of the language is, counted as it is built: its items at every level of
//! nesting (a text counts its bytes) and how deeply it nests. The evaluator bounds both
//! ([`super::Limits`]) before it keeps a value, so that `x = (x, x)` in a loop stops at a
//! clear error instead of doubling until the memory runs out, and `a = [a]` stops before
//! copying ever deeper values makes the loop quadratic (and their recursive drop overflows
//! the stack).

use crate::value::Value;

/// The size of a value: `items` counts every list, item, text byte, table cell and keyword
/// (with its name's bytes) at every level (saturating, never overflowing); `depth` is 0 for
/// a scalar, 1 for a flat list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Extent {
    pub items: u64,
    pub depth: usize,
}

impl Extent {
    /// The extent of a list holding values of these extents.
    pub fn list_of(parts: impl IntoIterator<Item = Extent>) -> Extent {
        let mut e = Extent { items: 1, depth: 1 };
        for p in parts {
            e.push(p);
        }
        e
    }

    /// Add one more item of extent `part` to this list.
    pub fn push(&mut self, part: Extent) {
        self.items = self.items.saturating_add(part.items);
        self.depth = self.depth.max(part.depth + 1);
    }

    /// `n` copies of this value's items in one list (`[...] * n`, `'...' * n`).
    pub fn repeated(self, n: u64) -> Extent {
        Extent {
            items: self
                .items
                .saturating_sub(1)
                .saturating_mul(n)
                .saturating_add(1),
            depth: self.depth,
        }
    }

    /// The items of two lists (or texts) joined (`a + b`).
    pub fn joined(self, other: Extent) -> Extent {
        Extent {
            items: self.items.saturating_add(other.items).saturating_sub(1),
            depth: self.depth.max(other.depth),
        }
    }
}

/// The extent of `v`. Recursion follows nesting, which the evaluator bounds.
pub fn extent(v: &Value) -> Extent {
    match v {
        Value::Str(s) => Extent {
            items: (s.len() as u64).max(1),
            depth: 0,
        },
        Value::Seq(items) => Extent::list_of(items.iter().map(extent)),
        // A keyword carries its name (a string of its own) besides its value.
        Value::Fact(kws) => Extent::list_of(kws.iter().map(|k| {
            let v = extent(&k.value);
            Extent {
                items: v.items.saturating_add(1 + k.name.len() as u64),
                depth: v.depth,
            }
        })),
        Value::Api(_) => Extent { items: 1, depth: 0 },
        Value::Table(t) => Extent {
            items: t
                .rows
                .iter()
                .map(|r| r.iter().map(|c| extent(c).items).sum::<u64>())
                .sum::<u64>()
                .saturating_add(1),
            depth: 2,
        },
        _ => Extent { items: 1, depth: 0 },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doubling_and_nesting_are_counted() {
        let mut x = Value::Seq(vec![Value::Real(1.0)]);
        for _ in 0..10 {
            x = Value::Seq(vec![x.clone(), x]);
        }
        // 2^10 reals and 2^11 - 1 lists.
        assert_eq!(
            extent(&x),
            Extent {
                items: 1024 + 2047,
                depth: 11
            }
        );
        let flat = extent(&Value::Seq(vec![Value::Int(0); 5]));
        assert_eq!(flat.repeated(3).items, 16);
        assert_eq!(flat.joined(flat).items, 11);
        assert_eq!(extent(&Value::Str("abc".into())).items, 3);
        assert_eq!(flat.repeated(u64::MAX).items, u64::MAX);
    }
}
