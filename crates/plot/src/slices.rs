//! Slices of a map: the value against the x parameter along a few rows of the grid, as line
//! series in one panel ([`super::xy`]).

use super::xy::{Mark, Panel, Scale, Series, StackedFigure};

/// One row of the grid: its label (`alpha0 = 0.5 rad`) and its `(x, value)` points; points
/// without a value (failed) are left out.
#[derive(Debug, Clone, PartialEq)]
pub struct Slice {
    /// Legend entry.
    pub label: String,
    /// `(x, value)` in increasing x.
    pub points: Vec<(f64, Option<f64>)>,
}

/// Which of `n` rows to show: at most `k`, evenly spread, first and last included.
#[must_use]
pub fn pick_rows(n: usize, k: usize) -> Vec<usize> {
    if n <= k {
        return (0..n).collect();
    }
    if k <= 1 {
        return vec![0];
    }
    let mut rows: Vec<usize> = (0..k)
        .map(|i| ((i * (n - 1)) as f64 / (k - 1) as f64).round() as usize)
        .collect();
    rows.dedup();
    rows
}

/// Series with at most this many points get a mark at each, so a few computed points do not
/// pass for a continuous curve.
pub const SPARSE: usize = 40;

/// A line series, marked at its points when it has at most [`SPARSE`] of them.
#[must_use]
pub fn sparse_marked(label: String, points: Vec<(f64, f64)>) -> Series {
    if points.len() <= SPARSE {
        Series::marked(label, points, Mark::LineAndPoints)
    } else {
        Series::line(label, points)
    }
}

/// The figure: `title` over one panel of the slices.
#[must_use]
pub fn figure(
    title: String,
    subtitle: String,
    x_label: &str,
    value_label: &str,
    x_log: bool,
    slices: &[Slice],
) -> StackedFigure {
    let mut panel = Panel::new(x_label, value_label);
    if x_log {
        panel.x_scale = Scale::Log;
    }
    for s in slices {
        let points = s
            .points
            .iter()
            .filter_map(|&(x, v)| v.filter(|v| v.is_finite()).map(|v| (x, v)))
            .collect();
        panel = panel.with_series(sparse_marked(s.label.clone(), points));
    }
    StackedFigure {
        title,
        subtitle,
        panels: vec![panel],
        width: 900,
        panel_height: 520,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_spread_with_both_ends() {
        assert_eq!(pick_rows(3, 5), vec![0, 1, 2]);
        assert_eq!(pick_rows(30, 5), vec![0, 7, 15, 22, 29]);
        assert_eq!(pick_rows(10, 1), vec![0]);
    }

    #[test]
    fn failed_points_are_left_out() {
        let f = figure(
            "t".into(),
            String::new(),
            "x",
            "y",
            false,
            &[Slice {
                label: "a".into(),
                points: vec![
                    (0.0, Some(1.0)),
                    (1.0, None),
                    (2.0, Some(f64::NAN)),
                    (3.0, Some(2.0)),
                ],
            }],
        );
        assert_eq!(f.panels[0].series[0].points, vec![(0.0, 1.0), (3.0, 2.0)]);
        // Two computed points are marked, not drawn as a bare line.
        assert_eq!(f.panels[0].series[0].mark, Mark::LineAndPoints);
        let dense = sparse_marked("d".into(), vec![(0.0, 0.0); SPARSE + 1]);
        assert_eq!(dense.mark, Mark::Line);
    }
}
