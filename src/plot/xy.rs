//! Stacked panels of x–y series on linear or logarithmic axes.
//!
//! A [`StackedFigure`] is a title over panels stacked vertically, each a [`Panel`]: axis labels
//! (with units), a [`Scale`] per axis, and [`Series`] drawn as lines, points or both, with a
//! legend. Trajectories against time use linear x; a work–precision plot is one panel with
//! `Scale::Log` on both axes and point-and-line series.
//!
//! Points that an axis cannot show (non-finite, or `≤ 0` on a logarithmic axis) are left out;
//! a panel with nothing to show says so in its plot area. Long line series are thinned to a
//! min/max envelope per pixel column ([`decimate_min_max`]), which keeps every extreme.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{
    AsRangedCoord, DefaultFormatting, KeyPointHint, Ranged, ValueFormatter,
};
use plotters::prelude::*;

use super::{DrawResult, Figure, colour, font};

/// How an axis maps values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scale {
    /// Linear.
    #[default]
    Linear,
    /// Base-10 logarithmic (positive values only).
    Log,
}

impl Scale {
    fn shows(self, v: f64) -> bool {
        v.is_finite() && (self == Scale::Linear || v > 0.0)
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mark {
    /// A polyline.
    #[default]
    Line,
    /// Filled circles.
    Points,
    /// A polyline with a circle at every point.
    LineAndPoints,
}

/// One named series of `(x, y)` points, in drawing order.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry.
    pub label: String,
    /// The points.
    pub points: Vec<(f64, f64)>,
    /// Lines, points or both.
    pub mark: Mark,
}

impl Series {
    /// A line series.
    #[must_use]
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            mark: Mark::Line,
        }
    }

    /// A series with marks at its points (and lines between them with
    /// [`Mark::LineAndPoints`]).
    #[must_use]
    pub fn marked(label: impl Into<String>, points: Vec<(f64, f64)>, mark: Mark) -> Self {
        Series {
            label: label.into(),
            points,
            mark,
        }
    }
}

/// One chart: labelled axes with scales and its series.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// x-axis label, with unit (`time (s)`).
    pub x_label: String,
    /// y-axis label, with unit (`angle (rad)`).
    pub y_label: String,
    /// x-axis scale.
    pub x_scale: Scale,
    /// y-axis scale.
    pub y_scale: Scale,
    /// The series, drawn in order with the palette's colours.
    pub series: Vec<Series>,
    /// Where the legend goes: the corner the data leave empty.
    pub legend: LegendCorner,
}

/// A corner of the plot area for the legend.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LegendCorner {
    /// Upper right (the default).
    #[default]
    UpperRight,
    /// Upper left (energy errors that grow with time).
    UpperLeft,
    /// Lower left (work–precision diagrams: cheap and accurate is the impossible corner).
    LowerLeft,
}

impl Panel {
    /// An empty panel with linear axes.
    #[must_use]
    pub fn new(x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Panel {
            x_label: x_label.into(),
            y_label: y_label.into(),
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            series: Vec::new(),
            legend: LegendCorner::UpperRight,
        }
    }

    /// With the legend in `corner`.
    #[must_use]
    pub fn with_legend(mut self, corner: LegendCorner) -> Self {
        self.legend = corner;
        self
    }

    /// With the given x-axis scale.
    #[must_use]
    pub fn with_x_scale(mut self, scale: Scale) -> Self {
        self.x_scale = scale;
        self
    }

    /// With the given y-axis scale.
    #[must_use]
    pub fn with_y_scale(mut self, scale: Scale) -> Self {
        self.y_scale = scale;
        self
    }

    /// With one more series.
    #[must_use]
    pub fn with_series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// The points of every series that both axes can show.
    fn visible(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.series.iter().flat_map(|s| {
            s.points
                .iter()
                .copied()
                .filter(|&(x, y)| self.x_scale.shows(x) && self.y_scale.shows(y))
        })
    }
}

/// A title over panels stacked vertically, all of the same width.
#[derive(Debug, Clone, PartialEq)]
pub struct StackedFigure {
    /// Title (scene, integrator, …).
    pub title: String,
    /// A smaller second line under the title (parameters); empty for none.
    pub subtitle: String,
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
    /// Width in pixels.
    pub width: u32,
    /// Height of each panel in pixels.
    pub panel_height: u32,
}

/// Height of the title band in pixels, without and with a subtitle.
const TITLE_HEIGHT: u32 = 44;
const TITLE_AND_SUBTITLE_HEIGHT: u32 = 68;

impl StackedFigure {
    fn title_height(&self) -> u32 {
        if self.subtitle.is_empty() {
            TITLE_HEIGHT
        } else {
            TITLE_AND_SUBTITLE_HEIGHT
        }
    }
}

impl Figure for StackedFigure {
    fn size(&self) -> (u32, u32) {
        let n = u32::try_from(self.panels.len().max(1)).unwrap_or(u32::MAX);
        (
            self.width,
            self.title_height()
                .saturating_add(n.saturating_mul(self.panel_height)),
        )
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: f64,
    ) -> DrawResult<DB> {
        let px = |v: u32| px(v, scale);
        root.fill(&WHITE)?;
        let (title, body) = root.split_vertically(px(self.title_height()));
        title.draw(&Text::new(
            self.title.clone(),
            (px(16) as i32, px(12) as i32),
            font(22.0 * scale).color(&BLACK),
        ))?;
        if !self.subtitle.is_empty() {
            title.draw(&Text::new(
                self.subtitle.clone(),
                (px(16) as i32, px(42) as i32),
                font(15.0 * scale).color(&RGBColor(64, 64, 64)),
            ))?;
        }
        if self.panels.is_empty() {
            return Ok(());
        }
        let areas = body.split_evenly((self.panels.len(), 1));
        for (panel, area) in self.panels.iter().zip(&areas) {
            draw_panel(area, panel, self.width, scale)?;
        }
        Ok(())
    }
}

/// `v` figure pixels at `scale` device pixels each.
fn px(v: u32, scale: f64) -> u32 {
    (f64::from(v) * scale).round() as u32
}

/// The data range of `values` on an axis of `scale`, padded: 5 % each side on a linear axis
/// (±1, or ±10 % of the value, when all values are equal), whole decades on a log axis.
/// `None` when no value can be shown.
#[must_use]
pub fn axis_range(values: impl IntoIterator<Item = f64>, scale: Scale) -> Option<Range<f64>> {
    let (lo, hi) = values.into_iter().filter(|&v| scale.shows(v)).fold(
        None,
        |acc: Option<(f64, f64)>, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        },
    )?;
    Some(match scale {
        Scale::Linear => {
            if hi > lo {
                let pad = 0.05 * (hi - lo);
                (lo - pad)..(hi + pad)
            } else {
                let pad = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
                (lo - pad)..(hi + pad)
            }
        }
        Scale::Log => {
            let (a, mut b) = (lo.log10().floor(), hi.log10().ceil());
            if b <= a {
                b = a + 1.0;
            }
            10f64.powf(a)..10f64.powf(b)
        }
    })
}

/// Thins a series ordered in `x` to at most four points per bucket over `buckets` equal index
/// ranges: the first, the smallest `y`, the largest `y` and the last, in their original order.
/// Every extreme survives, so the envelope a line plot shows is unchanged.
#[must_use]
pub fn decimate_min_max(points: &[(f64, f64)], buckets: usize) -> Vec<(f64, f64)> {
    if buckets == 0 || points.len() <= 4 * buckets {
        return points.to_vec();
    }
    let mut out = Vec::with_capacity(4 * buckets);
    for b in 0..buckets {
        let chunk = &points[b * points.len() / buckets..(b + 1) * points.len() / buckets];
        if chunk.is_empty() {
            continue;
        }
        let (mut imin, mut imax) = (0, 0);
        for (i, p) in chunk.iter().enumerate() {
            if p.1 < chunk[imin].1 {
                imin = i;
            }
            if p.1 > chunk[imax].1 {
                imax = i;
            }
        }
        let mut keep = [0, imin, imax, chunk.len() - 1];
        keep.sort_unstable();
        let mut last = None;
        for i in keep {
            if last != Some(i) {
                out.push(chunk[i]);
                last = Some(i);
            }
        }
    }
    out
}

/// A base-10 logarithmic axis over `[lo, hi]`, `0 < lo < hi`.
///
/// Written here rather than taken from plotters' `log_scale()`, whose tick search drops every
/// tick below `f64::EPSILON` (it takes them for the zero point) and can lose an end decade to
/// rounding: relative energy errors live at 1e-16. Bold ticks are whole decades (every k-th
/// when there are too many), light ones add 2…9 × each decade when they fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Log10Axis {
    lo: f64,
    hi: f64,
}

impl Log10Axis {
    /// The axis over `range`; `None` unless `0 < start < end` and both are finite.
    #[must_use]
    pub fn new(range: Range<f64>) -> Option<Self> {
        (range.start > 0.0 && range.end > range.start && range.end.is_finite()).then_some(
            Log10Axis {
                lo: range.start,
                hi: range.end,
            },
        )
    }
}

impl Ranged for Log10Axis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let (a, b) = (self.lo.log10(), self.hi.log10());
        // Non-positive values map far below the axis (and are clipped by the plot area).
        let f = if *value > 0.0 {
            ((value.log10() - a) / (b - a)).clamp(-10.0, 11.0)
        } else {
            -10.0
        };
        limit.0 + (f * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        let max = hint.max_num_points().max(1);
        let first = (self.lo.log10() - 1e-9).ceil() as i32;
        let last = (self.hi.log10() + 1e-9).floor() as i32;
        let decade = |k: i32| format!("1e{k}").parse::<f64>().unwrap_or(f64::NAN);
        let count = usize::try_from(last - first + 1).unwrap_or(0);
        let stride = count.div_ceil(max).max(1);
        let mut points: Vec<f64> = (first..=last).step_by(stride).map(decade).collect();
        if hint.weight().allow_light_points() && stride == 1 {
            let minor: Vec<f64> = (first - 1..=last)
                .flat_map(|k| (2..=9).map(move |m| f64::from(m) * decade(k)))
                .filter(|v| (self.lo..=self.hi).contains(v))
                .collect();
            if points.len() + minor.len() <= max {
                points.extend(minor);
            }
        }
        points
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

/// `1e-10` style labels for logarithmic axes.
fn log_label(v: &f64) -> String {
    format!("{v:.0e}")
}

/// Labels for a linear axis over `range` with plotters' ticks (at most `labels` of them): as
/// many decimals as the tick spacing needs and no more, the same for every tick, scientific
/// notation for values of magnitude `≥ 1e5` or `< 1e-3`, and no `-0`.
fn linear_labels(range: &Range<f64>, labels: usize) -> impl Fn(&f64) -> String + use<> {
    use plotters::coord::ranged1d::BoldPoints;
    use plotters::coord::types::RangedCoordf64;
    let ticks = RangedCoordf64::from(range.clone()).key_points(BoldPoints(labels));
    let step = match ticks.as_slice() {
        [a, b, ..] => (b - a).abs(),
        _ => (range.end - range.start).abs(),
    };
    let magnitude = ticks
        .iter()
        .fold(0f64, |m, t| m.max(t.abs()))
        .max(range.start.abs().max(range.end.abs()) * 1e-3);
    let scientific = !(1e-3..1e5).contains(&magnitude);
    let exponent = |x: f64| if x > 0.0 { x.log10().floor() } else { 0.0 };
    let decimals = (-exponent(step)).max(0.0) as usize;
    let digits = (exponent(magnitude) - exponent(step)).max(0.0) as usize;
    move |v: &f64| {
        let v = if v.abs() < 1e-9 * step { 0.0 } else { *v };
        if scientific {
            if v == 0.0 {
                "0".to_string()
            } else {
                format!("{v:.digits$e}")
            }
        } else {
            format!("{v:.decimals$}")
        }
    }
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    width: u32,
    scale: f64,
) -> DrawResult<DB> {
    let x = axis_range(panel.visible().map(|p| p.0), panel.x_scale);
    let y = axis_range(panel.visible().map(|p| p.1), panel.y_scale);
    let (x, y, empty) = match (x, y) {
        (Some(x), Some(y)) => (x, y, false),
        _ => {
            let placeholder = |s: Scale| match s {
                Scale::Linear => 0.0..1.0,
                Scale::Log => 1e-16..1.0,
            };
            (placeholder(panel.x_scale), placeholder(panel.y_scale), true)
        }
    };
    let note = empty.then_some(match panel.y_scale {
        Scale::Log => "nothing to show on a log axis: every value is 0 or not finite",
        Scale::Linear => "no finite values to show",
    });
    let look = Look {
        note,
        buckets: width as usize,
        scale,
    };
    // A log axis range from `axis_range` is always positive; the fallback never runs.
    let log = |r: Range<f64>| Log10Axis::new(r).unwrap_or(Log10Axis { lo: 1e-16, hi: 1.0 });
    let x_linear = linear_labels(&x, X_LABELS);
    let y_linear = linear_labels(&y, Y_LABELS);
    match (panel.x_scale, panel.y_scale) {
        (Scale::Linear, Scale::Linear) => chart(area, panel, x, y, &x_linear, &y_linear, &look),
        (Scale::Linear, Scale::Log) => chart(area, panel, x, log(y), &x_linear, &log_label, &look),
        (Scale::Log, Scale::Linear) => chart(area, panel, log(x), y, &log_label, &y_linear, &look),
        (Scale::Log, Scale::Log) => {
            chart(area, panel, log(x), log(y), &log_label, &log_label, &look)
        }
    }
}

/// Most tick labels on an x axis and a y axis.
const X_LABELS: usize = 12;
const Y_LABELS: usize = 8;

/// How a panel is drawn, beyond its data.
struct Look<'a> {
    /// Text shown instead of the series when there is nothing to draw.
    note: Option<&'a str>,
    /// Pixel columns, for thinning long line series.
    buckets: usize,
    /// Device pixels per figure pixel.
    scale: f64,
}

/// Draws one panel on coordinates `x`, `y` (linear ranges or their `log_scale()`).
fn chart<DB, X, Y>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    x: X,
    y: Y,
    x_format: &dyn Fn(&f64) -> String,
    y_format: &dyn Fn(&f64) -> String,
    look: &Look<'_>,
) -> DrawResult<DB>
where
    DB: DrawingBackend,
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let s = look.scale;
    let px = |v: u32| px(v, s);
    let line_width = px(1).max(1);
    let mut chart = ChartBuilder::on(area)
        .margin_left(px(12))
        .margin_right(px(24))
        .margin_top(px(8))
        .margin_bottom(px(4))
        .x_label_area_size(px(44))
        .y_label_area_size(px(84))
        .build_cartesian_2d(x, y)?;
    {
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(panel.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .axis_desc_style(font(17.0 * s))
            .label_style(font(14.0 * s))
            .set_all_tick_mark_size(px(5))
            .axis_style(BLACK.stroke_width(line_width))
            .light_line_style(RGBColor(238, 238, 238).stroke_width(line_width))
            .bold_line_style(RGBColor(212, 212, 212).stroke_width(line_width))
            .x_labels(X_LABELS)
            .y_labels(Y_LABELS)
            .x_label_formatter(x_format)
            .y_label_formatter(y_format);
        mesh.draw()?;
    }
    if let Some(note) = look.note {
        let area = chart.plotting_area().strip_coord_spec();
        let (w, h) = area.dim_in_pixel();
        let (w, h) = (i32::try_from(w).unwrap_or(0), i32::try_from(h).unwrap_or(0));
        area.draw(&Text::new(
            note.to_string(),
            (w / 2, h / 2),
            font(16.0 * s).color(&RGBColor(96, 96, 96)).pos(
                plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Center,
                    plotters::style::text_anchor::VPos::Center,
                ),
            ),
        ))?;
        return Ok(());
    }
    for (i, series) in panel.series.iter().enumerate() {
        let colour = colour::series(i);
        // Past the palette's seven colours, the marker's shape and the line's dashes tell
        // series of the same colour apart: circles and solid lines, then squares and dashes,
        // then triangles and dots.
        let cycle = i / colour::SERIES_COLOURS;
        let points: Vec<(f64, f64)> = series
            .points
            .iter()
            .copied()
            .filter(|&(x, y)| panel.x_scale.shows(x) && panel.y_scale.shows(y))
            .collect();
        let line = colour.stroke_width(px(2));
        let radius = px(3);
        let line_points = match series.mark {
            Mark::Line => decimate_min_max(&points, look.buckets),
            Mark::Points => Vec::new(),
            Mark::LineAndPoints => points.clone(),
        };
        let dash = match cycle % 3 {
            0 => None,
            1 => Some((px(7), px(4))),
            _ => Some((px(2), px(3))),
        };
        let marks = if series.mark == Mark::Line {
            Vec::new()
        } else {
            points
        };
        let shape = cycle % 3;
        let filled = colour.filled();
        macro_rules! draw_marks {
            () => {
                match shape {
                    0 => {
                        chart.draw_series(marks.iter().map(|&p| Circle::new(p, radius, filled)))?
                    }
                    1 => chart.draw_series(marks.iter().map(|&p| {
                        let r = radius as i32;
                        EmptyElement::at(p) + Rectangle::new([(-r, -r), (r, r)], filled)
                    }))?,
                    _ => chart.draw_series(
                        marks
                            .iter()
                            .map(|&p| TriangleMarker::new(p, radius + px(1), filled)),
                    )?,
                }
            };
        }
        let has_line = !line_points.is_empty();
        // The line (or, without one, the marks) carries the legend entry; marks go on top.
        let anno = match dash {
            _ if !has_line => draw_marks!(),
            None => chart.draw_series(LineSeries::new(line_points.iter().copied(), line))?,
            Some((size, spacing)) => chart.draw_series(DashedLineSeries::new(
                line_points.iter().copied(),
                size,
                spacing,
                line,
            ))?,
        };
        // The legend's sample: the line (solid, dashed or dotted, as drawn) and the mark.
        let d = move |v: u32| px(v) as i32;
        let mark_style = if series.mark == Mark::Line {
            TRANSPARENT.filled()
        } else {
            filled
        };
        let r = radius as i32;
        let anno = anno.label(series.label.as_str());
        match shape {
            0 => anno.legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (d(22), 0)], line)
                    + Circle::new((d(11), 0), r, mark_style)
            }),
            1 => anno.legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (d(7), 0)], line)
                    + PathElement::new(vec![(d(15), 0), (d(22), 0)], line)
                    + Rectangle::new([(d(11) - r, -r), (d(11) + r, r)], mark_style)
            }),
            _ => anno.legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (d(2), 0)], line)
                    + PathElement::new(vec![(d(5), 0), (d(7), 0)], line)
                    + PathElement::new(vec![(d(15), 0), (d(17), 0)], line)
                    + PathElement::new(vec![(d(20), 0), (d(22), 0)], line)
                    + TriangleMarker::new((d(11), 0), r + 1, mark_style)
            }),
        };
        if has_line && !marks.is_empty() {
            draw_marks!();
        }
    }
    if !panel.series.is_empty() {
        chart
            .configure_series_labels()
            .position(match panel.legend {
                LegendCorner::UpperRight => SeriesLabelPosition::UpperRight,
                LegendCorner::UpperLeft => SeriesLabelPosition::UpperLeft,
                LegendCorner::LowerLeft => SeriesLabelPosition::LowerLeft,
            })
            .margin(px(10))
            .legend_area_size(px(30))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160).stroke_width(line_width))
            .label_font(font(15.0 * s))
            .draw()?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ranges_are_padded_and_log_ranges_are_decades() {
        let r = axis_range([0.0, 10.0, f64::NAN], Scale::Linear).unwrap();
        assert_eq!(r, -0.5..10.5);
        let r = axis_range([2.0, 2.0], Scale::Linear).unwrap();
        assert!((r.start - 1.8).abs() < 1e-15 && (r.end - 2.2).abs() < 1e-15);
        assert_eq!(axis_range([0.0], Scale::Linear).unwrap(), -1.0..1.0);
        let r = axis_range([0.0, 3e-15, 2e-12, -1.0], Scale::Log).unwrap();
        assert!((r.start / 1e-15 - 1.0).abs() < 1e-14 && (r.end / 1e-11 - 1.0).abs() < 1e-14);
        assert_eq!(axis_range([0.0, -1.0], Scale::Log), None);
        assert_eq!(axis_range([], Scale::Linear), None);
    }

    #[test]
    fn a_log_log_figure_with_marked_series_renders() {
        let errors = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12];
        let panel = Panel::new("right-hand-side evaluations", "error at t_end")
            .with_x_scale(Scale::Log)
            .with_y_scale(Scale::Log)
            .with_series(Series::marked(
                "gauss4",
                errors
                    .iter()
                    .enumerate()
                    .map(|(i, &e)| (1e3 * 10f64.powi(i as i32), e))
                    .collect(),
                Mark::LineAndPoints,
            ))
            .with_series(Series::marked(
                "rk4",
                vec![(2e3, 1e-5), (2e4, 1e-9), (0.0, 1.0)],
                Mark::Points,
            ));
        let figure = StackedFigure {
            title: "work–precision".into(),
            subtitle: String::new(),
            panels: vec![panel],
            width: 500,
            panel_height: 400,
        };
        let dir = tempfile::tempdir().unwrap();
        let svg = dir.path().join("wp.svg");
        super::super::save(&figure, &svg).unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        // Decade labels on both axes, and one circle per shown point (the point at x = 0
        // cannot be shown on a log axis and is left out) plus one in each legend entry.
        let labels: Vec<&str> = text
            .split("</text>")
            .filter_map(|t| t.rsplit('>').next())
            .map(str::trim)
            .collect();
        assert!(
            labels.contains(&"1e-8") && labels.contains(&"1e4"),
            "{labels:?}"
        );
        assert_eq!(text.matches("<circle").count(), 5 + 2 + 2);
    }

    #[test]
    fn series_past_the_palette_get_squares_then_triangles() {
        // 15 series of two points: colours repeat after 7, so series 8–14 draw squares and
        // dashes, series 15 triangles and dots; each marked series also marks its legend entry.
        let mut panel = Panel::new("x", "y")
            .with_x_scale(Scale::Log)
            .with_y_scale(Scale::Log);
        for i in 0..15 {
            let y = 10f64.powi(-i);
            panel = panel.with_series(Series::marked(
                format!("s{i}"),
                vec![(1.0, y), (10.0, y / 10.0)],
                Mark::LineAndPoints,
            ));
        }
        let figure = StackedFigure {
            title: "styles".into(),
            subtitle: String::new(),
            panels: vec![panel],
            width: 600,
            panel_height: 700,
        };
        let dir = tempfile::tempdir().unwrap();
        let svg = dir.path().join("styles.svg");
        super::super::save(&figure, &svg).unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        assert_eq!(text.matches("<circle").count(), 7 * 3);
        assert_eq!(text.matches("<polygon").count(), 3);
    }

    #[test]
    fn log_axis_ticks_are_decades_even_below_machine_epsilon() {
        let axis = Log10Axis::new(1e-17..1e-14).unwrap();
        assert_eq!(
            axis.key_points(plotters::coord::ranged1d::BoldPoints(10)),
            [1e-17, 1e-16, 1e-15, 1e-14]
        );
        let all = axis.key_points(100);
        assert_eq!(all.len(), 4 + 3 * 8);
        assert!(all.contains(&5e-16));
        // Too many decades for the hint: every other one.
        let wide = Log10Axis::new(1e-20..1.0).unwrap();
        assert!(wide.key_points(10).len() <= 11);
        assert_eq!(axis.map(&1e-17, (0, 300)), 0);
        assert_eq!(axis.map(&1e-14, (0, 300)), 300);
        assert_eq!(axis.map(&1e-16, (0, 300)), 100);
        assert!(Log10Axis::new(0.0..1.0).is_none());
    }

    #[test]
    fn linear_labels_use_the_decimals_the_ticks_need() {
        let f = linear_labels(&(-0.55..0.55), 8);
        assert_eq!(f(&-0.4), "-0.4");
        assert_eq!(f(&-1e-17), "0.0");
        assert_eq!(f(&0.2), "0.2");
        let f = linear_labels(&(0.0..10.0), 12);
        assert_eq!(f(&4.0), "4");
        let f = linear_labels(&(0.0..0.0002), 8);
        assert_eq!(f(&0.00015), "1.5e-4");
        assert_eq!(f(&0.0), "0");
        let f = linear_labels(&(0.0..3e5), 8);
        assert_eq!(f(&2e5), "2.0e5");
    }

    #[test]
    fn decimation_keeps_every_extreme_and_the_ends() {
        let points: Vec<(f64, f64)> = (0..10_000)
            .map(|i| {
                let t = f64::from(i) * 1e-3;
                (t, (7.0 * t).sin() + if i == 4321 { 5.0 } else { 0.0 })
            })
            .collect();
        let thin = decimate_min_max(&points, 100);
        assert!(thin.len() <= 400);
        assert_eq!(thin.first(), points.first());
        assert_eq!(thin.last(), points.last());
        assert!(thin.contains(&points[4321]), "the spike was lost");
        let min = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert!(thin.iter().any(|p| p.1 == min));
        assert!(thin.windows(2).all(|w| w[0].0 < w[1].0), "order lost");
        // Short series are untouched.
        assert_eq!(decimate_min_max(&points[..50], 100), points[..50].to_vec());
    }
}
