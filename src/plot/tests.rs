//! Drawing to files: valid PNGs of the requested size, SVGs that carry the texts, and the
//! treatment of data that cannot be drawn.

use super::*;

const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A];

/// Decode a PNG file and return its size, checking the signature first.
pub(crate) fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert!(bytes.len() > 1000, "a PNG of {} bytes", bytes.len());
    assert_eq!(bytes[..8], PNG_SIGNATURE);
    let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png).unwrap();
    (img.width(), img.height())
}

/// A picture is more than a blank page: count the pixels that are neither white nor grey
/// grid (the curves are coloured).
fn coloured_pixels(path: &Path) -> usize {
    let img = image::open(path).unwrap().to_rgb8();
    img.pixels()
        .filter(|p| {
            let [r, g, b] = p.0;
            let (hi, lo) = (r.max(g).max(b), r.min(g).min(b));
            hi - lo > 60
        })
        .count()
}

/// The texts of an SVG file, trimmed, in order.
pub(crate) fn svg_texts(path: &Path) -> Vec<String> {
    let svg = std::fs::read_to_string(path).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(60)]);
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..];
            Some(body[..body.find("</text>")?].trim().to_string())
        })
        .collect()
}

/// Whether `texts` holds every one of `wanted`, exactly.
pub(crate) fn has_texts(texts: &[String], wanted: &[&str]) {
    for w in wanted {
        assert!(
            texts.iter().any(|t| t == w),
            "missing text {w:?} in {texts:?}"
        );
    }
}

fn two_curves() -> XyPlot {
    let x: Vec<f64> = (0..50).map(|i| f64::from(i) * 0.1).collect();
    XyPlot {
        title: "Two curves".into(),
        x_label: "INST (s)".into(),
        y_label: "DEPL (m)".into(),
        series: vec![
            Series::new("sine", x.clone(), x.iter().map(|t| t.sin()).collect()),
            Series::new("cosine", x.clone(), x.iter().map(|t| t.cos()).collect())
                .line(LineStyle::Dashed)
                .marker(Marker::Circle),
            Series::new("", x.clone(), x.iter().map(|t| 0.5 * t.cos()).collect())
                .line(LineStyle::Dotted),
        ],
        ..XyPlot::default()
    }
}

#[test]
fn png_is_valid_and_has_the_requested_size() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("curves.png");
    let sum = xy_plot(&two_curves(), &path, ImageFormat::Png).unwrap();
    assert_eq!(png_size(&path), DEFAULT_SIZE);
    assert_eq!(sum.points, 150);
    assert_eq!(sum.skipped_note(), None);
    // Two coloured 2-px curves over ~800 px draw thousands of coloured pixels.
    assert!(coloured_pixels(&path) > 1000);
}

#[test]
fn svg_carries_title_axis_labels_and_legend() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("curves.svg");
    xy_plot(&two_curves(), &path, ImageFormat::Svg).unwrap();
    let texts = svg_texts(&path);
    has_texts(
        &texts,
        &["Two curves", "INST (s)", "DEPL (m)", "sine", "cosine"],
    );
    // The third curve has no legend entry: the legend holds exactly two labels.
    assert_eq!(texts.iter().filter(|t| t.contains("sine")).count(), 2);
}

#[test]
fn log_axis_skips_non_positive_values_and_counts_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("log.svg");
    let spec = XyPlot {
        x_scale: Scale::Log,
        series: vec![Series::new(
            "c",
            vec![0.0, -1.0, 1e-3, 1e-2, 1e-1, f64::NAN],
            vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        )],
        ..XyPlot::default()
    };
    let sum = xy_plot(&spec, &path, ImageFormat::Svg).unwrap();
    assert_eq!((sum.points, sum.skipped_log, sum.skipped_nan), (3, 2, 1));
    let note = sum.skipped_note().unwrap();
    assert!(
        note.contains("2 point(s) with a non-positive value on a log axis"),
        "{note}"
    );
    // Decade labels of the log axis are in the picture.
    has_texts(&svg_texts(&path), &["0.001", "0.01", "0.1"]);
}

#[test]
fn nothing_drawable_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("none.png");
    let spec = XyPlot {
        title: "T".into(),
        y_scale: Scale::Log,
        series: vec![Series::new("c", vec![1.0, 2.0], vec![0.0, -3.0])],
        ..XyPlot::default()
    };
    let err = xy_plot(&spec, &path, ImageFormat::Png).unwrap_err();
    assert!(err.message.contains("nothing to draw in 'T'"), "{err}");
    assert!(
        err.message.contains("2 point(s) with a non-positive"),
        "{err}"
    );
    assert!(!path.exists());
    let empty = XyPlot::default();
    let err = xy_plot(&empty, &path, ImageFormat::Svg).unwrap_err();
    assert!(err.message.contains("no curve"), "{err}");
}

#[test]
fn bad_ranges_and_directories_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let mut spec = two_curves();
    spec.x_range = Some((0.0, 10.0));
    spec.x_scale = Scale::Log;
    let err = xy_plot(&spec, &dir.path().join("a.png"), ImageFormat::Png).unwrap_err();
    assert_eq!(err.keyword.as_deref(), Some("BORNE_X"));
    let err = xy_plot(
        &two_curves(),
        &dir.path().join("no/such/dir/a.png"),
        ImageFormat::Png,
    )
    .unwrap_err();
    assert!(err.message.contains("cannot draw the picture"), "{err}");
}

#[test]
fn extreme_values_are_refused_or_drawn_never_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x.png");
    let wide = XyPlot {
        series: vec![Series::new("w", vec![-1e308, 1e308], vec![0.0, 1.0])],
        ..XyPlot::default()
    };
    let err = xy_plot(&wide, &path, ImageFormat::Png).unwrap_err();
    assert!(err.message.contains("too wide to draw"), "{err}");
    // The same values on a log y axis span 616 decades: drawable.
    let tall = XyPlot {
        y_scale: Scale::Log,
        series: vec![Series::new("t", vec![0.0, 1.0], vec![1e-308, 1e308])],
        ..XyPlot::default()
    };
    assert_eq!(xy_plot(&tall, &path, ImageFormat::Png).unwrap().points, 2);
    // Tiny values and a span near the rounding of their magnitude.
    let tiny = XyPlot {
        series: vec![Series::new(
            "t",
            vec![1e18, 1e18 + 4096.0],
            vec![1e-310, 2e-310],
        )],
        ..XyPlot::default()
    };
    assert_eq!(xy_plot(&tiny, &path, ImageFormat::Png).unwrap().points, 2);
}

#[test]
fn constant_and_single_point_curves_draw() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("one.png");
    let spec = XyPlot {
        series: vec![Series::new("p", vec![2.0], vec![5.0]).marker(Marker::Square)],
        ..XyPlot::default()
    };
    assert_eq!(xy_plot(&spec, &path, ImageFormat::Png).unwrap().points, 1);
    assert_eq!(png_size(&path), DEFAULT_SIZE);
}

/// A hardening backbone: f = f0 (1 + E^0.3) over 1e-4..10, stable then unstable then
/// stable, not evaluated at the end, with one bifurcation row; first row at E = 0.
pub(crate) fn synthetic_fe() -> Vec<FePoint> {
    let n = 60;
    (0..n)
        .map(|i| {
            let energy = if i == 0 {
                0.0
            } else {
                10f64.powf(-4.0 + 5.0 * f64::from(i) / f64::from(n - 1))
            };
            let stability = match i {
                0..=24 => Stability::Stable,
                25..=34 => Stability::Unstable,
                35..=49 => Stability::Stable,
                _ => Stability::NotEvaluated,
            };
            FePoint {
                energy,
                freq: 0.5033 * (1.0 + energy.powf(0.3)),
                stability,
                bifurcation: i == 25 || i == 35,
                reprise: 0,
            }
        })
        .collect()
}

#[test]
fn frequency_energy_styles_and_legend() {
    let rows = synthetic_fe();
    let spec = nnm::frequency_energy_spec(&rows, "sdnd122");
    // Four runs (stable, unstable, stable, not evaluated) plus the bifurcation markers.
    assert_eq!(spec.series.len(), 5);
    let lines: Vec<LineStyle> = spec.series.iter().map(|s| s.line).collect();
    assert_eq!(
        lines,
        [
            LineStyle::Solid,
            LineStyle::Dashed,
            LineStyle::Solid,
            LineStyle::Solid,
            LineStyle::None
        ]
    );
    // The second stable run repeats no legend entry; runs join at their shared point.
    assert_eq!(spec.series[2].label, None);
    assert_eq!(spec.series[1].x.first(), spec.series[0].x.last());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fe.svg");
    let sum = frequency_energy(&rows, "sdnd122", &path, ImageFormat::Svg).unwrap();
    // The E = 0 row cannot go on the log axis, and the first run is its only owner.
    assert_eq!(sum.skipped_log, 1);
    has_texts(
        &svg_texts(&path),
        &[
            "sdnd122",
            "ENERGIE (J)",
            "FREQUENCE (Hz)",
            "stable",
            "unstable",
            "stability not evaluated",
            "bifurcation",
            "0.001",
            "10⁻⁴",
        ],
    );
    let png = dir.path().join("fe.png");
    frequency_energy(&rows, "sdnd122", &png, ImageFormat::Png).unwrap();
    assert_eq!(png_size(&png), DEFAULT_SIZE);
}

fn orbit() -> History {
    // x = cos t, v = -sin t over one period: the phase portrait is the unit circle.
    let inst: Vec<f64> = (0..=64)
        .map(|i| 2.0 * std::f64::consts::PI * f64::from(i) / 64.0)
        .collect();
    History {
        label: "NUME_ORDRE 1".into(),
        depl: inst.iter().map(|t| t.cos()).collect(),
        vite: inst.iter().map(|t| -t.sin()).collect(),
        inst,
    }
}

#[test]
fn time_history_and_phase_portrait() {
    let dir = tempfile::tempdir().unwrap();
    let th = dir.path().join("th.svg");
    let sum = time_history(&[orbit()], "history", "N2 DX", &th, ImageFormat::Svg).unwrap();
    // Both panels draw the 65 samples.
    assert_eq!(sum.points, 130);
    has_texts(
        &svg_texts(&th),
        // With their units (before: "DEPL N2 DX", "INST").
        &["history", "DEPL N2 DX (m)", "VITE N2 DX (m/s)", "INST (s)"],
    );
    let ph = dir.path().join("ph.png");
    phase_portrait(&[orbit()], "phase", "N2 DX", &ph, ImageFormat::Png).unwrap();
    assert_eq!(png_size(&ph), DEFAULT_SIZE);
    let th_png = dir.path().join("th.png");
    time_history(&[orbit()], "history", "N2 DX", &th_png, ImageFormat::Png).unwrap();
    assert_eq!(png_size(&th_png), (1024, 1024));
}

/// After a `reuse=` restart the table holds a second run (NUME_REPRISE 1) that starts back
/// at low energy: the curve breaks there instead of drawing a chord from the end of the
/// first run (8.9 J) to the start of the second (0.018 J), while a change of stability
/// inside one run stays joined.
#[test]
fn frequency_energy_breaks_where_nume_reprise_changes() {
    let point = |energy: f64, stability, reprise| FePoint {
        energy,
        freq: 0.5 + 0.01 * energy.ln().max(0.0),
        stability,
        bifurcation: false,
        reprise,
    };
    let rows = vec![
        point(0.01, Stability::Stable, 0),
        point(1.0, Stability::Stable, 0),
        point(8.9, Stability::Unstable, 0),
        point(0.018, Stability::Unstable, 1),
        point(0.5, Stability::Unstable, 1),
    ];
    let spec = nnm::frequency_energy_spec(&rows, "restart");
    // Stable run, unstable run of reprise 0 (joined to the stable one), reprise 1.
    assert_eq!(spec.series.len(), 3);
    assert_eq!(spec.series[1].x, vec![1.0, 8.9]);
    assert_eq!(spec.series[2].x, vec![0.018, 0.5]);
    assert_eq!(spec.series[2].repeats, 0);
    // No series holds both 8.9 and 0.018: no chord.
    assert!(spec
        .series
        .iter()
        .all(|s| !(s.x.contains(&8.9) && s.x.contains(&0.018))));
}
