//! A Grace (xmgrace) project file of xy curves, the text IMPR_FONCTION's FORMAT='XMGRACE'
//! writes: a title, the axes' labels, then one set per curve (its legend and its points,
//! one `x y` line each, closed by `&`). Grace reads the file; nothing is drawn here.

use super::XyPlot;

/// A label or title as Grace reads it: within double quotes, which it cannot escape.
fn quoted(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "'"))
}

/// The project file of `spec`'s curves (their styles are Grace's defaults).
pub fn project(spec: &XyPlot) -> String {
    let mut out = String::from("# Grace project file\n@version 50122\n");
    out.push_str(&format!("@title {}\n", quoted(&spec.title)));
    out.push_str("@g0 on\n@with g0\n");
    out.push_str(&format!("@    xaxis label {}\n", quoted(&spec.x_label)));
    out.push_str(&format!("@    yaxis label {}\n", quoted(&spec.y_label)));
    for (k, s) in spec.series.iter().enumerate() {
        if let Some(l) = &s.label {
            out.push_str(&format!("@    s{k} legend {}\n", quoted(l)));
        }
    }
    for (k, s) in spec.series.iter().enumerate() {
        out.push_str(&format!("@target G0.S{k}\n@type xy\n"));
        for (x, y) in s.x.iter().zip(&s.y) {
            // 17 significant digits: the points read back exactly.
            out.push_str(&format!("{x:.16e} {y:.16e}\n"));
        }
        out.push_str("&\n");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::Series;

    #[test]
    fn one_set_per_curve_with_exact_points() {
        let spec = XyPlot {
            title: "a \"b\"".into(),
            x_label: "INST".into(),
            y_label: "DX".into(),
            series: vec![
                Series::new("F", vec![0.0, 0.1], vec![1.0, -2.5]),
                Series::new("G", vec![1.0], vec![3.0]),
            ],
            ..XyPlot::default()
        };
        let text = project(&spec);
        assert!(text.contains("@title \"a 'b'\"\n"));
        assert!(text.contains("@    s1 legend \"G\"\n"));
        assert!(
            text.contains("@target G0.S0\n@type xy\n0.0000000000000000e0 1.0000000000000000e0\n")
        );
        let points: Vec<f64> = text
            .lines()
            .filter(|l| !l.starts_with(['@', '#', '&']))
            .flat_map(|l| l.split(' ').map(|v| v.parse::<f64>().unwrap()))
            .collect();
        assert_eq!(points, vec![0.0, 1.0, 0.1, -2.5, 1.0, 3.0]);
        assert_eq!(text.matches("&\n").count(), 2);
    }
}
