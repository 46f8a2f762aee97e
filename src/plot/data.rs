//! From user data to drawable polylines: points that cannot be drawn (NaN, infinite, not
//! positive on a log axis) are dropped and break the line there, and are counted.

use super::axis::Scale;
use super::{PlotSummary, Series};
use crate::error::{Error, Result};

/// A series in plotting coordinates: runs of consecutive drawable points.
#[derive(Clone, Debug, PartialEq)]
pub struct Cleaned {
    pub segments: Vec<Vec<(f64, f64)>>,
}

impl Cleaned {
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.segments.iter().flatten().copied()
    }
}

/// Map a series to plotting coordinates, counting what is dropped into `summary`.
pub fn clean(s: &Series, xs: Scale, ys: Scale, summary: &mut PlotSummary) -> Result<Cleaned> {
    if s.x.len() != s.y.len() {
        return Err(Error::input(format!(
            "curve {}: {} abscissas for {} ordinates",
            s.label.as_deref().unwrap_or("(no legend)"),
            s.x.len(),
            s.y.len()
        )));
    }
    let mut segments = Vec::new();
    let mut current = Vec::new();
    for (k, (&x, &y)) in s.x.iter().zip(&s.y).enumerate() {
        let counted = k >= s.repeats;
        match (xs.to_plot(x), ys.to_plot(y)) {
            (Some(u), Some(v)) => {
                current.push((u, v));
                summary.points += usize::from(counted);
            }
            _ => {
                match (counted, x.is_finite() && y.is_finite()) {
                    (false, _) => {}
                    (true, false) => summary.skipped_nan += 1,
                    (true, true) => summary.skipped_log += 1,
                }
                if !current.is_empty() {
                    segments.push(std::mem::take(&mut current));
                }
            }
        }
    }
    if !current.is_empty() {
        segments.push(current);
    }
    Ok(Cleaned { segments })
}

/// Smallest and largest plotting coordinates of the cleaned series (x then y).
pub fn bounds(all: &[Cleaned]) -> Option<((f64, f64), (f64, f64))> {
    let mut it = all.iter().flat_map(Cleaned::points);
    let (x0, y0) = it.next()?;
    Some(it.fold(((x0, x0), (y0, y0)), |((a, b), (c, d)), (x, y)| {
        ((a.min(x), b.max(x)), (c.min(y), d.max(y)))
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_points_break_the_line_and_are_counted() {
        let s = Series::new(
            "s",
            vec![1.0, 10.0, 0.0, 100.0, f64::NAN, 1000.0],
            vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        );
        let mut sum = PlotSummary::default();
        let c = clean(&s, Scale::Log, Scale::Lin, &mut sum).unwrap();
        assert_eq!(
            c.segments,
            vec![
                vec![(0.0, 1.0), (1.0, 2.0)],
                vec![(2.0, 4.0)],
                vec![(3.0, 6.0)]
            ]
        );
        assert_eq!((sum.points, sum.skipped_log, sum.skipped_nan), (4, 1, 1));
        assert_eq!(bounds(&[c]), Some(((0.0, 3.0), (1.0, 6.0))));
    }

    #[test]
    fn repeated_points_are_drawn_but_not_counted() {
        let mut s = Series::new("s", vec![0.0, 1.0, 2.0], vec![1.0, 2.0, 3.0]);
        s.repeats = 2;
        let mut sum = PlotSummary::default();
        let c = clean(&s, Scale::Log, Scale::Lin, &mut sum).unwrap();
        assert_eq!(c.segments, vec![vec![(0.0, 2.0), (2f64.log10(), 3.0)]]);
        // The x = 0 point is a repeat: not counted as skipped either.
        assert_eq!((sum.points, sum.skipped_log), (1, 0));
    }

    #[test]
    fn mismatched_lengths_are_an_error() {
        let s = Series::new("s", vec![1.0], vec![]);
        let err = clean(&s, Scale::Lin, Scale::Lin, &mut PlotSummary::default()).unwrap_err();
        assert!(err.message.contains("1 abscissas for 0 ordinates"), "{err}");
    }
}
