//! Axes: the map from data to plotting coordinates, tick positions and tick labels.
//!
//! A log axis is drawn as a linear axis in u = log10(v): the ticks are then ours to choose
//! (decades, with 2 and 5 added when the range is short), and a range that holds no power
//! of ten still gets labels, which plotters' own log coordinate does not guarantee.

/// Scale of one axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    Lin,
    Log,
}

impl Scale {
    /// ECHELLE_X / ECHELLE_Y: 'LIN' or 'LOG'.
    pub fn parse(s: &str) -> Option<Scale> {
        match s {
            "LIN" => Some(Scale::Lin),
            "LOG" => Some(Scale::Log),
            _ => None,
        }
    }

    /// Plotting coordinate of the data value `v`; `None` when it cannot be drawn (not
    /// finite, or not positive on a log axis).
    pub fn to_plot(self, v: f64) -> Option<f64> {
        match self {
            _ if !v.is_finite() => None,
            Scale::Lin => Some(v),
            Scale::Log if v > 0.0 => Some(v.log10()),
            Scale::Log => None,
        }
    }

    /// Data value of the plotting coordinate `u`.
    pub fn to_data(self, u: f64) -> f64 {
        match self {
            Scale::Lin => u,
            Scale::Log => 10f64.powf(u),
        }
    }
}

/// One axis ready to draw, in plotting coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    pub scale: Scale,
    pub lo: f64,
    pub hi: f64,
    /// Labelled ticks (and bold grid lines).
    pub major: Vec<f64>,
    /// Light grid lines.
    pub minor: Vec<f64>,
    /// Spacing of the major ticks (data units on a linear axis), to choose label digits.
    step: f64,
    /// A log axis too short for its mantissas (fewer than three labels): its ticks are
    /// multiples of this data step, labelled as a linear axis's.
    fine: Option<f64>,
}

/// About 5 to 10 labelled ticks read well at 1024 pixels.
const TARGET_TICKS: f64 = 6.0;

impl Axis {
    /// An axis covering the plotting coordinates `[lo, hi]` (both finite), with a small
    /// margin when `margin` (data given by the user with BORNE_* gets none).
    pub fn new(scale: Scale, lo: f64, hi: f64, margin: bool) -> Axis {
        let (mut lo, mut hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        if hi - lo <= f64::EPSILON * hi.abs().max(lo.abs()).max(1e-300) {
            // One value: open a window around it (half a decade on a log axis).
            let half = match scale {
                Scale::Log => 0.5,
                Scale::Lin if lo == 0.0 => 1.0,
                Scale::Lin => 0.1 * lo.abs(),
            };
            lo -= half;
            hi += half;
        } else if margin {
            let pad = 0.04 * (hi - lo);
            lo -= pad;
            hi += pad;
        }
        match scale {
            Scale::Lin => lin_axis(lo, hi),
            Scale::Log => log_axis(lo, hi),
        }
    }

    /// Label of the tick at plotting coordinate `u`.
    pub fn label(&self, u: f64) -> String {
        match (self.scale, self.fine) {
            (Scale::Lin, _) => lin_label(u, self.step),
            (Scale::Log, Some(step)) => lin_label(Scale::Log.to_data(u), step),
            (Scale::Log, None) => log_label(u),
        }
    }
}

/// 1, 2 or 5 times a power of ten, the smallest at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let p = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|s| *s >= raw * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// Multiples of `step` in `[lo, hi]`.
fn multiples(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    // A few dozen at most in practice; more means a degenerate step: draw no tick.
    if last.saturating_sub(first) > 1000 {
        return Vec::new();
    }
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            // Print 0, not -0 or 1e-17, at the origin.
            if v.abs() < step * 1e-9 {
                0.0
            } else {
                v
            }
        })
        .collect()
}

fn lin_axis(lo: f64, hi: f64) -> Axis {
    let step = nice_step((hi - lo) / TARGET_TICKS);
    let minor_step = if (step / 10f64.powf(step.log10().floor()) - 2.0).abs() < 1e-9 {
        step / 4.0
    } else {
        step / 5.0
    };
    Axis {
        scale: Scale::Lin,
        lo,
        hi,
        major: multiples(lo, hi, step),
        minor: multiples(lo, hi, minor_step),
        step,
        fine: None,
    }
}

fn log_axis(lo: f64, hi: f64) -> Axis {
    let decades = hi - lo;
    // Labelled decades every `every` decades so that about TARGET_TICKS remain.
    let every = (decades / TARGET_TICKS).ceil().max(1.0);
    let mut major = multiples(lo, hi, every);
    let mut minor = Vec::new();
    let d0 = lo.floor() as i64;
    let d1 = hi.ceil() as i64;
    for d in d0..=d1 {
        for m in 2..=9 {
            let u = d as f64 + f64::from(m).log10();
            if u >= lo && u <= hi {
                minor.push(u);
                // A short range (about two decades or less) also labels 2 and 5.
                if decades < 2.5 && (m == 2 || m == 5) {
                    major.push(u);
                }
            }
        }
    }
    // Less than a decade (or fewer than two labels): label every mantissa inside.
    if decades < 1.0 || major.len() < 2 {
        major = minor.clone();
        major.extend(multiples(lo, hi, 1.0));
    }
    major.sort_by(f64::total_cmp);
    major.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    if decades > 12.0 {
        // Too many minor lines to read: keep the decades only.
        minor = multiples(lo, hi, 1.0);
    }
    // Fewer than three labels (a range inside one or two mantissa steps, such as the top
    // of a branch, 8.9 to 9.6 J): round values in data units instead, as a linear axis
    // labels them, so that the reader can still read a value off the axis.
    let mut fine = None;
    if major.len() < 3 {
        let (a, b) = (Scale::Log.to_data(lo), Scale::Log.to_data(hi));
        let step = nice_step((b - a) / TARGET_TICKS);
        major = multiples(a, b, step)
            .into_iter()
            .filter(|v| *v > 0.0)
            .map(f64::log10)
            .collect();
        minor = multiples(a, b, step / 2.0)
            .into_iter()
            .filter(|v| *v > 0.0)
            .map(f64::log10)
            .collect();
        fine = Some(step);
    }
    Axis {
        scale: Scale::Log,
        lo,
        hi,
        major,
        minor,
        step: every,
        fine,
    }
}

/// Digits enough to tell ticks `step` apart.
fn lin_label(v: f64, step: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let big = v.abs().max(step);
    if big >= 1e5 || step < 1e-4 {
        // Scientific: as many mantissa digits as the step needs relative to the value.
        let digits = ((v.abs().log10().floor() - step.log10().floor()).max(0.0) as usize).min(6);
        return format!("{v:.digits$e}");
    }
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// Superscript digits for 10ⁿ labels (DejaVu Sans has them).
fn superscript(n: i64) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect()
}

/// `0.01`, `20`, `1000` for moderate decades; `10⁻⁵`, `2×10⁶` beyond.
fn log_label(u: f64) -> String {
    let d = u.floor();
    let mantissa = (10f64.powf(u - d) * 1000.0).round() / 1000.0;
    let (mantissa, d) = if mantissa >= 10.0 {
        (1.0, d + 1.0)
    } else {
        (mantissa, d)
    };
    let d = d as i64;
    if (-3..=4).contains(&d) {
        let v = mantissa * 10f64.powi(d as i32);
        let decimals = (-d).max(0) as usize;
        return format!("{v:.decimals$}");
    }
    let m = format!("{mantissa}");
    if m == "1" {
        format!("10{}", superscript(d))
    } else {
        format!("{m}×10{}", superscript(d))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(0.13), 0.2);
        assert_eq!(nice_step(3.0), 5.0);
        assert_eq!(nice_step(7.0), 10.0);
        assert_eq!(nice_step(1.0), 1.0);
    }

    #[test]
    fn linear_ticks_are_round_and_inside() {
        let a = Axis::new(Scale::Lin, 0.0, 1.0, false);
        // Span 1 / 6 → step 0.2: 0, 0.2, ..., 1.
        assert_eq!(a.major.len(), 6);
        assert!(a.major.iter().all(|&u| (a.lo..=a.hi).contains(&u)));
        let labels: Vec<String> = a.major.iter().map(|&u| a.label(u)).collect();
        assert_eq!(labels, ["0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        // A constant series still gets a window.
        let c = Axis::new(Scale::Lin, 3.0, 3.0, true);
        assert!(c.lo < 3.0 && c.hi > 3.0);
    }

    #[test]
    fn log_ticks_label_decades() {
        // 1e-4 .. 1e2: six decades, every one labelled.
        let a = Axis::new(Scale::Log, -4.0, 2.0, false);
        let labels: Vec<String> = a.major.iter().map(|&u| a.label(u)).collect();
        assert_eq!(labels, ["10⁻⁴", "0.001", "0.01", "0.1", "1", "10", "100"]);
        // 8 minor lines per decade.
        assert_eq!(a.minor.len(), 6 * 8);
    }

    #[test]
    fn short_log_range_without_a_decade_still_has_labels() {
        // 2 .. 8: no power of ten inside.
        let a = Axis::new(Scale::Log, 2f64.log10(), 8f64.log10(), false);
        let labels: Vec<String> = a.major.iter().map(|&u| a.label(u)).collect();
        assert_eq!(labels, ["2", "3", "4", "5", "6", "7", "8"]);
    }

    #[test]
    fn short_log_range_inside_one_mantissa_step_gets_round_labels() {
        // 8.9 .. 9.6 J (the top of a branch): no mantissa 2..9 or decade inside but 9;
        // before, the axis had the single label "9". Now steps of 0.2 (0.7 / 6 rounded up
        // to 1, 2 or 5 times a power of ten); 9.6 / 0.2 is 47.999... in binary, so the
        // last tick is 9.4.
        let a = Axis::new(Scale::Log, 8.9f64.log10(), 9.6f64.log10(), false);
        let labels: Vec<String> = a.major.iter().map(|&u| a.label(u)).collect();
        assert_eq!(labels, ["9.0", "9.2", "9.4"]);
        // 1.2e-5 .. 1.5e-5: steps of 5e-7 in scientific notation (1.2e-5 / 5e-7 comes
        // back from the log as 24.000...01, so the first tick is 1.25e-5).
        let b = Axis::new(Scale::Log, 1.2e-5f64.log10(), 1.5e-5f64.log10(), false);
        let labels: Vec<String> = b.major.iter().map(|&u| b.label(u)).collect();
        assert_eq!(
            labels,
            ["1.25e-5", "1.30e-5", "1.35e-5", "1.40e-5", "1.45e-5", "1.50e-5"]
        );
        // Two decades keep their decade labels.
        let c = Axis::new(Scale::Log, -2.0, 0.0, false);
        assert_eq!(c.fine, None);
    }

    #[test]
    fn log_axis_drops_what_it_cannot_draw() {
        assert_eq!(Scale::Log.to_plot(0.0), None);
        assert_eq!(Scale::Log.to_plot(-1.0), None);
        assert_eq!(Scale::Lin.to_plot(f64::NAN), None);
        assert_eq!(Scale::Log.to_plot(100.0), Some(2.0));
        assert_eq!(Scale::Lin.to_plot(-1.0), Some(-1.0));
    }

    #[test]
    fn scientific_labels_for_large_values() {
        let a = Axis::new(Scale::Lin, 0.0, 4e6, false);
        assert_eq!(a.label(2e6), "2e6");
        let b = Axis::new(Scale::Lin, 0.0, 5e-5, false);
        assert_eq!(b.label(1e-5), "1e-5");
        assert_eq!(log_label(-6.0 + 2f64.log10()), "2×10⁻⁶");
    }
}
