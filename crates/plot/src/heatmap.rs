//! Heatmaps: a value on a grid of two parameters, in viridis, with a colour bar.
//!
//! A [`Heatmap`] has the grid's `x` and `y` values (increasing; any spacing) and a value per
//! cell; each cell is drawn as a rectangle reaching halfway to its neighbours (the outer cells
//! as far again outward), so a grid point sits at the centre of its cell. Cells without a
//! value (a failed point) are grey, and the figure says so. The colour bar on the right maps
//! the colour range, `[min, max]` of the finite values unless given, with ticks labelled as
//! on the value axis of any panel. Optional vertical marker lines (a critical value) and
//! curves (a theoretical boundary) are drawn dashed in white with a label.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{DrawResult, Figure, colour, font};

/// Grey of cells without a value.
const MISSING: RGBColor = RGBColor(190, 190, 190);

/// A vertical marker line at `x` with a label.
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// Where.
    pub x: f64,
    /// What it marks (`√(g/a)`).
    pub label: String,
}

/// A curve over the map (a theoretical boundary), drawn dashed with a label at its end.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// What it is.
    pub label: String,
    /// Its points, densely enough to look smooth.
    pub points: Vec<(f64, f64)>,
}

/// A value on a grid of two parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Heatmap {
    /// Title.
    pub title: String,
    /// A smaller second line (fixed parameters); empty for none.
    pub subtitle: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// Colour-bar label with unit.
    pub value_label: String,
    /// Grid values along x, increasing.
    pub xs: Vec<f64>,
    /// Grid values along y, increasing.
    pub ys: Vec<f64>,
    /// `values[j][i]`: the value at `(xs[i], ys[j])`; `None` where the point failed.
    pub values: Vec<Vec<Option<f64>>>,
    /// Colour range; `None`: the finite values' `[min, max]`.
    pub range: Option<(f64, f64)>,
    /// Vertical marker lines.
    pub markers: Vec<Marker>,
    /// Curves drawn over the cells.
    pub curves: Vec<Curve>,
    /// Draw x (log-spaced grid values) on a base-10 logarithmic scale.
    pub x_log: bool,
    /// Draw y on a base-10 logarithmic scale.
    pub y_log: bool,
    /// Colour by `log10` of the value (values `≤ 0` are drawn as missing).
    pub value_log: bool,
    /// The colour map.
    pub colour_map: colour::ColourMap,
    /// Width and height in pixels.
    pub size: (u32, u32),
}

/// Values of an axis as drawn: `log10 v` on a logarithmic axis (every `v > 0` there: log
/// spacing needs a positive range).
fn drawn(values: &[f64], log: bool) -> Vec<f64> {
    if log {
        values.iter().map(|v| v.log10()).collect()
    } else {
        values.to_vec()
    }
}

/// Labels of a logarithmic axis drawn in `log10` units: `10⁻⁴` at whole decades, two
/// significant digits between them (`3.2×10⁻⁴`).
pub(crate) fn log_labels(v: &f64) -> String {
    super::log_axis::power_label(10f64.powf(*v))
}

/// Cell edges of grid values `v`: midpoints between neighbours, and as far again outside.
fn edges(v: &[f64]) -> Vec<f64> {
    match v.len() {
        0 => Vec::new(),
        1 => vec![v[0] - 0.5, v[0] + 0.5],
        n => {
            let mut e = Vec::with_capacity(n + 1);
            e.push(v[0] - 0.5 * (v[1] - v[0]));
            for w in v.windows(2) {
                e.push(0.5 * (w[0] + w[1]));
            }
            e.push(v[n - 1] + 0.5 * (v[n - 1] - v[n - 2]));
            e
        }
    }
}

impl Heatmap {
    /// The colour range: the given one, or the finite values' extent (a unit range around a
    /// constant; `[0, 1]` when there is no finite value).
    #[must_use]
    pub fn colour_range(&self) -> (f64, f64) {
        if let Some(r) = self.range {
            return r;
        }
        let finite = self.values.iter().flatten().filter_map(|v| self.tone(*v));
        let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
        if !(lo <= hi) {
            (0.0, 1.0)
        } else if lo == hi {
            (lo - 0.5, hi + 0.5)
        } else {
            (lo, hi)
        }
    }

    /// What a cell's colour shows: the value, or its `log10` with [`Heatmap::value_log`];
    /// `None` for a cell drawn as missing.
    fn tone(&self, v: Option<f64>) -> Option<f64> {
        let v = v.filter(|v| v.is_finite())?;
        if self.value_log {
            (v > 0.0).then(|| v.log10())
        } else {
            Some(v)
        }
    }

    fn has_missing(&self) -> bool {
        self.values
            .iter()
            .flatten()
            .any(|v| self.tone(*v).is_none())
    }
}

/// The axis range of grid values `v` drawn with cell edges `e`: from the first to the last
/// grid value, or the single cell's edges.
fn domain(v: &[f64], e: &[f64]) -> Option<(f64, f64)> {
    match v {
        [] => None,
        [_] => Some((*e.first()?, *e.last()?)),
        [first, .., last] => Some((*first, *last)),
    }
}

/// White text at `at` (device pixels of `root`) with a dark halo of `1.5 · scale` pixels, so
/// it reads on the lightest and the darkest cells.
fn halo_text<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    text: &str,
    at: (i32, i32),
    pos: Pos,
    scale: f64,
) -> DrawResult<DB> {
    let r = (1.5 * scale).round().max(1.0) as i32;
    let style = font(15.0 * scale).pos(pos);
    let dark = RGBColor(20, 20, 20).mix(0.85);
    for (dx, dy) in [
        (-r, 0),
        (r, 0),
        (0, -r),
        (0, r),
        (-r, -r),
        (r, r),
        (-r, r),
        (r, -r),
    ] {
        root.draw(&Text::new(
            text.to_string(),
            (at.0 + dx, at.1 + dy),
            style.clone().color(&dark),
        ))?;
    }
    root.draw(&Text::new(text.to_string(), at, style.color(&WHITE)))
}

/// `v` figure pixels at `scale` device pixels each.
fn px(v: u32, scale: f64) -> u32 {
    (f64::from(v) * scale).round() as u32
}

/// Tick labels with the decimals the tick spacing needs.
fn label_for(step: f64) -> impl Fn(&f64) -> String {
    let decimals = if step > 0.0 && step < 1.0 {
        (-step.log10().floor()) as usize
    } else {
        0
    };
    move |v: &f64| {
        let v = if v.abs() < 1e-12 * step.max(1e-300) {
            0.0
        } else {
            *v
        };
        format!("{v:.decimals$}")
    }
}

/// A "nice" tick spacing (1, 2 or 5 × 10^k) for about `n` ticks over `span`.
fn nice_step(span: f64, n: usize) -> f64 {
    if !(span > 0.0) {
        return 1.0;
    }
    let raw = span / n.max(1) as f64;
    let p = 10f64.powf(raw.log10().floor());
    let f = raw / p;
    p * if f <= 1.0 {
        1.0
    } else if f <= 2.0 {
        2.0
    } else if f <= 5.0 {
        5.0
    } else {
        10.0
    }
}

impl Figure for Heatmap {
    fn size(&self) -> (u32, u32) {
        self.size
    }

    fn set_size(&mut self, size: (u32, u32)) {
        self.size = size;
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, s: f64) -> DrawResult<DB> {
        let px = |v: u32| px(v, s);
        let line = px(1).max(1);
        root.fill(&WHITE)?;
        let band = super::title::Band::new(&self.title, &self.subtitle, self.size.0);
        let (title, body) = root.split_vertically(px(band.height()));
        band.draw(&title, s)?;
        let (w, _) = body.dim_in_pixel();
        let bar_width = px(120);
        let (map_area, bar_area) = body.split_horizontally(w.saturating_sub(bar_width));

        // The map, in drawn coordinates (log10 of the values on a log axis: cells of a
        // log-spaced grid are then of equal size and the edges geometric means).
        let (xs, ys) = (drawn(&self.xs, self.x_log), drawn(&self.ys, self.y_log));
        let (xe, ye) = (edges(&xs), edges(&ys));
        // The axes span the swept domain: the outer cells' halves beyond it are clipped.
        let (Some((x0, x1)), Some((y0, y1))) = (domain(&xs, &xe), domain(&ys, &ye)) else {
            return Ok(());
        };
        let mut chart = ChartBuilder::on(&map_area)
            .margin_left(px(12))
            .margin_right(px(12))
            .margin_top(px(8))
            .margin_bottom(px(4))
            .x_label_area_size(px(48))
            .y_label_area_size(px(76))
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let x_linear = label_for(nice_step(x1 - x0, 10));
        let y_linear = label_for(nice_step(y1 - y0, 8));
        let x_fmt = |v: &f64| {
            if self.x_log {
                log_labels(v)
            } else {
                x_linear(v)
            }
        };
        let y_fmt = |v: &f64| {
            if self.y_log {
                log_labels(v)
            } else {
                y_linear(v)
            }
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .axis_desc_style(font(17.0 * s))
            .label_style(font(14.0 * s))
            .set_all_tick_mark_size(px(5))
            .axis_style(BLACK.stroke_width(line))
            .x_labels(10)
            .y_labels(8)
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .draw()?;
        let (lo, hi) = self.colour_range();
        let cells = self.values.iter().enumerate().flat_map(|(j, row)| {
            let (xe, ye) = (&xe, &ye);
            row.iter().enumerate().map(move |(i, v)| {
                let colour = match self.tone(*v) {
                    Some(v) => self.colour_map.at((v - lo) / (hi - lo)),
                    None => MISSING,
                };
                Rectangle::new([(xe[i], ye[j]), (xe[i + 1], ye[j + 1])], colour.filled())
            })
        });
        chart.draw_series(cells)?;
        let to_x = |x: f64| if self.x_log { x.log10() } else { x };
        let to_y = |y: f64| if self.y_log { y.log10() } else { y };
        for marker in &self.markers {
            let mx = to_x(marker.x);
            if !(x0..=x1).contains(&mx) {
                continue;
            }
            let dash = (y1 - y0) / 40.0;
            let dashes = (0..40).step_by(2).map(|k| {
                let a = y0 + k as f64 * dash;
                PathElement::new(vec![(mx, a), (mx, a + dash)], WHITE.stroke_width(px(2)))
            });
            chart.draw_series(dashes)?;
            let at = chart.backend_coord(&(mx, y1));
            halo_text(root, &marker.label, at, Pos::new(HPos::Left, VPos::Top), s)?;
        }
        for curve in &self.curves {
            let inside: Vec<(f64, f64)> = curve
                .points
                .iter()
                .map(|&(x, y)| (to_x(x), to_y(y)))
                .filter(|&(x, y)| (x0..=x1).contains(&x) && (y0..=y1).contains(&y))
                .collect();
            // Dashes: every other pair of consecutive points, in runs of four.
            let dashes = inside
                .windows(2)
                .enumerate()
                .filter(|(k, _)| (k / 4) % 2 == 0)
                .map(|(_, w)| PathElement::new(vec![w[0], w[1]], WHITE.stroke_width(px(2))));
            chart.draw_series(dashes)?;
            if let Some(end) = inside.last() {
                let at = chart.backend_coord(end);
                halo_text(
                    root,
                    &curve.label,
                    at,
                    Pos::new(HPos::Right, VPos::Bottom),
                    s,
                )?;
            }
        }
        // Draw the frame again over the cells.
        let frame = chart.plotting_area().strip_coord_spec();
        let (fw, fh) = frame.dim_in_pixel();
        frame.draw(&Rectangle::new(
            [(0, 0), (fw as i32 - 1, fh as i32 - 1)],
            BLACK.stroke_width(line),
        ))?;

        // The colour bar: a column of the map's colours with its own value axis.
        let mut bar = ChartBuilder::on(&bar_area)
            .margin_left(px(4))
            .margin_right(px(34))
            .margin_top(px(8))
            .margin_bottom(px(4) + px(48))
            .y_label_area_size(px(0))
            .right_y_label_area_size(px(52))
            .build_cartesian_2d(0.0..1.0, lo..hi)?;
        let v_linear = label_for(nice_step(hi - lo, 8));
        let v_fmt = |v: &f64| {
            if self.value_log {
                log_labels(v)
            } else {
                v_linear(v)
            }
        };
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_labels(8)
            .y_label_formatter(&v_fmt)
            .label_style(font(14.0 * s))
            .set_all_tick_mark_size(px(5))
            .axis_style(BLACK.stroke_width(line))
            .draw()?;
        let steps = 256;
        bar.draw_series((0..steps).map(|k| {
            let (a, b) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
            Rectangle::new(
                [(0.0, lo + a * (hi - lo)), (1.0, lo + b * (hi - lo))],
                self.colour_map.at(0.5 * (a + b)).filled(),
            )
        }))?;
        // The bar's label, written upward beside it, and the meaning of grey cells.
        let (bw, bh) = bar_area.dim_in_pixel();
        bar_area.draw(&Text::new(
            self.value_label.clone(),
            (bw as i32 - px(16) as i32, (bh / 2) as i32),
            font(17.0 * s)
                .transform(FontTransform::Rotate270)
                .color(&BLACK)
                .pos(Pos::new(HPos::Center, VPos::Center)),
        ))?;
        if self.has_missing() {
            bar_area.draw(&Rectangle::new(
                [
                    (px(8) as i32, bh as i32 - px(40) as i32),
                    (px(22) as i32, bh as i32 - px(26) as i32),
                ],
                MISSING.filled(),
            ))?;
            bar_area.draw(&Text::new(
                "failed".to_string(),
                (px(28) as i32, bh as i32 - px(33) as i32),
                font(14.0 * s)
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map() -> Heatmap {
        Heatmap {
            title: "free-hoop: maximum tilt".into(),
            subtitle: "M = 1, m = 0.1".into(),
            x_label: "omega0 (rad/s)".into(),
            y_label: "alpha0 (rad)".into(),
            value_label: "maximum tilt (rad)".into(),
            xs: vec![1.0, 2.0, 3.0, 4.0],
            ys: vec![0.1, 0.2, 0.4],
            values: vec![
                vec![Some(0.0), Some(0.1), Some(0.2), Some(0.3)],
                vec![Some(0.1), None, Some(0.3), Some(0.4)],
                vec![Some(0.2), Some(0.3), Some(0.4), Some(0.5)],
            ],
            range: None,
            markers: vec![Marker {
                x: 3.13,
                label: "sqrt(g/a)".into(),
            }],
            curves: vec![Curve {
                label: "equilibrium".into(),
                points: (0..50).map(|k| (1.0 + 0.06 * f64::from(k), 0.2)).collect(),
            }],
            x_log: false,
            y_log: false,
            value_log: false,
            colour_map: colour::ColourMap::Viridis,
            size: (700, 500),
        }
    }

    #[test]
    fn a_log_axis_is_drawn_in_decades_with_cells_of_equal_size() {
        let ys = [1e-6, 1e-5, 1e-4, 1e-3];
        let drawn_ys = drawn(&ys, true);
        let e = edges(&drawn_ys);
        let widths: Vec<f64> = e.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(widths.iter().all(|w| (w - 1.0).abs() < 1e-12), "{widths:?}");
        assert_eq!(log_labels(&-4.0), "10⁻⁴");
        assert_eq!(log_labels(&0.0), "10⁰");
        assert_eq!(log_labels(&-3.5), "3.2×10⁻⁴");
        assert_eq!(drawn(&ys, false), ys.to_vec());
    }

    #[test]
    fn cells_reach_halfway_to_their_neighbours() {
        assert_eq!(edges(&[1.0, 2.0, 4.0]), vec![0.5, 1.5, 3.0, 5.0]);
        assert_eq!(edges(&[2.0]), vec![1.5, 2.5]);
        assert!(edges(&[]).is_empty());
    }

    #[test]
    fn the_colour_range_spans_the_finite_values() {
        let mut m = map();
        assert_eq!(m.colour_range(), (0.0, 0.5));
        m.values = vec![vec![Some(2.0), None]];
        assert_eq!(m.colour_range(), (1.5, 2.5));
        m.values = vec![vec![None]];
        assert_eq!(m.colour_range(), (0.0, 1.0));
        m.range = Some((0.0, 1.5));
        assert_eq!(m.colour_range(), (0.0, 1.5));
    }

    #[test]
    fn a_heatmap_renders_with_labels_a_colour_bar_and_failed_cells() {
        let dir = tempfile::tempdir().unwrap();
        let svg = dir.path().join("map.svg");
        let png = dir.path().join("map.png");
        super::super::save(&map(), &svg).unwrap();
        super::super::save(&map(), &png).unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        for label in [
            "omega0 (rad/s)",
            "alpha0 (rad)",
            "maximum tilt (rad)",
            "failed",
            "equilibrium",
        ] {
            assert!(text.contains(label), "{label} missing");
        }
        // Twelve cells, one of them grey.
        assert!(
            text.contains("#BEBEBE") || text.contains("#bebebe"),
            "no grey cell"
        );
        assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    }
}
