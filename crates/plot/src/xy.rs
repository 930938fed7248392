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
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::prelude::*;

use super::log_axis::{Log10Axis, log_label};
use super::title::Band;
use super::{DrawResult, Figure, colour, font, legend};

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
    /// A colour and mark of its own; `None`: by its place in the panel.
    pub look: Option<SeriesLook>,
}

/// A series' own colour (palette index: a group such as a method family) and variant within
/// the group (marker `variant % 3`: circle, square, triangle; line `variant / 3 % 3`: solid,
/// dashed, dotted).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SeriesLook {
    /// Palette index.
    pub colour: usize,
    /// Variant within the colour.
    pub variant: usize,
}

impl Series {
    /// A line series.
    #[must_use]
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            mark: Mark::Line,
            look: None,
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
            look: None,
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
    /// The series, drawn in order with the palette's colours; the legend is placed where it
    /// covers none of them ([`super::legend`]).
    pub series: Vec<Series>,
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
        }
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

/// The lowest a panel is laid out when the figure chooses its height (layout pixels).
const MIN_PANEL: u32 = 150;

impl StackedFigure {
    fn band(&self) -> Band {
        Band::new(&self.title, &self.subtitle, self.width)
    }
}

impl Figure for StackedFigure {
    fn size(&self) -> (u32, u32) {
        let n = u32::try_from(self.panels.len().max(1)).unwrap_or(u32::MAX);
        (
            self.width,
            self.band()
                .height()
                .saturating_add(n.saturating_mul(self.panel_height)),
        )
    }

    /// The width as given; the panels share the height left under the title.
    fn set_size(&mut self, (width, height): (u32, u32)) {
        let n = u32::try_from(self.panels.len().max(1)).unwrap_or(u32::MAX);
        self.width = width;
        self.panel_height = (height.saturating_sub(self.band().height()) / n).max(1);
    }

    /// The width as given; each panel 0.4 times as high as the figure is wide, at least
    /// [`MIN_PANEL`] and at most as high as it was.
    fn fit_width(&mut self, width: u32) {
        self.width = width;
        self.panel_height = (width * 2 / 5).clamp(MIN_PANEL, self.panel_height.max(MIN_PANEL));
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: f64,
    ) -> DrawResult<DB> {
        let px = |v: u32| px(v, scale);
        root.fill(&WHITE)?;
        let band = self.band();
        let (title, body) = root.split_vertically(px(band.height()));
        band.draw(&title, scale)?;
        if self.panels.is_empty() {
            return Ok(());
        }
        let areas = body.split_evenly((self.panels.len(), 1));
        let last = self.panels.len() - 1;
        // Panels above one with the same x axis leave its label to the bottom panel, and
        // every panel takes the right margin the widest outside legend needs, so that the
        // plot areas line up.
        let shared = |k: usize| k < last && self.panels[last].x_label == self.panels[k].x_label;
        let mut right = 0;
        for (k, (panel, area)) in self.panels.iter().zip(&areas).enumerate() {
            right = right.max(draw_panel(area, panel, self.width, scale, shared(k), None)?);
        }
        for (k, (panel, area)) in self.panels.iter().zip(&areas).enumerate() {
            draw_panel(area, panel, self.width, scale, shared(k), Some(right))?;
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
    shared_x: bool,
    right: Option<u32>,
) -> PanelResult<DB> {
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
        shared_x,
        right,
        measure: right.is_none(),
    };
    // A log axis range from `axis_range` is always positive; the fallback never runs.
    let log = |r: Range<f64>| Log10Axis::new(r).unwrap_or_else(Log10Axis::fallback);
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
    /// The x axis's label is the bottom panel's: tick labels only.
    shared_x: bool,
    /// The right margin (device pixels), the same for every panel of a figure.
    right: Option<u32>,
    /// Only find the right margin the panel needs; draw nothing.
    measure: bool,
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
) -> PanelResult<DB>
where
    DB: DrawingBackend,
    X: AsRangedCoord<Value = f64> + Clone,
    Y: AsRangedCoord<Value = f64> + Clone,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let s = look.scale;
    let px = |v: u32| px(v, s);
    let line_width = px(1).max(1);
    let build = |right: u32| {
        ChartBuilder::on(area)
            .margin_left(px(12))
            .margin_right(right)
            .margin_top(px(8))
            .margin_bottom(px(4))
            .x_label_area_size(px(if look.shared_x { 26 } else { 44 }))
            .y_label_area_size(px(84))
            .build_cartesian_2d(x.clone(), y.clone())
    };
    let base_right = px(24);
    let mut right = look.right.unwrap_or(base_right).max(base_right);
    let mut chart = build(right)?;
    let prepared: Vec<Prepared> = panel
        .series
        .iter()
        .enumerate()
        .map(|(i, series)| prepare(panel, i, series, look.buckets))
        .collect();
    let labels: Vec<&str> = panel.series.iter().map(|s| s.label.as_str()).collect();
    let legend_size = legend::size(area, &labels, s);
    let plot_rect = |chart: &ChartContext<'_, DB, _>| {
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        legend::Rect {
            x0: f64::from(xr.start),
            y0: f64::from(yr.start),
            x1: f64::from(xr.end),
            y1: f64::from(yr.end),
        }
    };
    let to_pixels = |chart: &ChartContext<'_, DB, _>, points: &[(f64, f64)]| {
        points
            .iter()
            .map(|p| {
                let (a, b) = chart.backend_coord(p);
                (f64::from(a), f64::from(b))
            })
            .collect::<Vec<_>>()
    };
    let drawn = legend::Drawn {
        lines: prepared
            .iter()
            .map(|p| to_pixels(&chart, &p.line))
            .collect(),
        marks: prepared
            .iter()
            .flat_map(|p| to_pixels(&chart, &p.marks))
            .collect(),
        reach: 5.0 * s,
    };
    let mut placement = legend::Placement::Outside;
    if !panel.series.is_empty() && look.note.is_none() {
        placement = legend::place(&plot_rect(&chart), legend_size, 6.0 * s, &drawn);
        let need = base_right + legend_size.0.round() as u32 + px(8);
        if placement == legend::Placement::Outside && right < need {
            right = need;
            chart = build(right)?;
        }
    }
    if look.measure {
        return Ok(right);
    }
    {
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(if look.shared_x {
            ""
        } else {
            panel.x_label.as_str()
        })
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
        return Ok(right);
    }
    for p in &prepared {
        let colour = p.sample.colour;
        let line = colour.stroke_width(px(2));
        let radius = px(3);
        let filled = colour.filled();
        match p.sample.dash {
            0 => chart.draw_series(LineSeries::new(p.line.iter().copied(), line))?,
            1 => chart.draw_series(DashedLineSeries::new(
                p.line.iter().copied(),
                px(7),
                px(4),
                line,
            ))?,
            _ => chart.draw_series(DashedLineSeries::new(
                p.line.iter().copied(),
                px(2),
                px(3),
                line,
            ))?,
        };
        match p.sample.marker {
            0 => chart.draw_series(p.marks.iter().map(|&q| Circle::new(q, radius, filled)))?,
            1 => chart.draw_series(p.marks.iter().map(|&q| {
                let r = radius as i32;
                EmptyElement::at(q) + Rectangle::new([(-r, -r), (r, r)], filled)
            }))?,
            _ => chart.draw_series(
                p.marks
                    .iter()
                    .map(|&q| TriangleMarker::new(q, radius + px(1), filled)),
            )?,
        };
    }
    if panel.series.is_empty() {
        return Ok(right);
    }
    let rect = plot_rect(&chart);
    let corner = match placement {
        legend::Placement::Inside(r) => (r.x0, r.y0),
        legend::Placement::Outside => (rect.x1 + 8.0 * s, rect.y0),
    };
    let base = area.get_base_pixel();
    let entries: Vec<(&str, legend::Sample)> = panel
        .series
        .iter()
        .zip(&prepared)
        .map(|(series, p)| (series.label.as_str(), p.sample))
        .collect();
    legend::draw(
        area,
        (
            corner.0.round() as i32 - base.0,
            corner.1.round() as i32 - base.1,
        ),
        &entries,
        s,
    )?;
    Ok(right)
}

/// What drawing a panel returns: the right margin it took (device pixels), wider than the
/// usual when its legend went outside.
type PanelResult<DB> = Result<u32, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A series ready to draw: its (thinned) polyline, its marks and its legend sample.
struct Prepared {
    line: Vec<(f64, f64)>,
    marks: Vec<(f64, f64)>,
    sample: legend::Sample,
}

/// The `i`-th series of `panel` as drawn.
fn prepare(panel: &Panel, i: usize, series: &Series, buckets: usize) -> Prepared {
    let points: Vec<(f64, f64)> = series
        .points
        .iter()
        .copied()
        .filter(|&(x, y)| panel.x_scale.shows(x) && panel.y_scale.shows(y))
        .collect();
    let line = match series.mark {
        Mark::Line => decimate_min_max(&points, buckets),
        Mark::Points => Vec::new(),
        Mark::LineAndPoints => points.clone(),
    };
    let marks = if series.mark == Mark::Line {
        Vec::new()
    } else {
        points
    };
    // Past the palette, the next cycle of colours gets squares and dashes, then triangles
    // and dots; a series with a look of its own (a family's colour, a method's mark) keeps it.
    let cycle = (i / colour::SERIES_COLOURS) % 3;
    let (hue, marker, dash) = series.look.map_or((i, cycle, cycle), |l| {
        (l.colour, l.variant % 3, (l.variant / 3) % 3)
    });
    Prepared {
        sample: legend::Sample {
            colour: colour::series(hue),
            marker,
            dash,
            line: !line.is_empty(),
            marks: series.mark != Mark::Line,
        },
        line,
        marks,
    }
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
            labels.contains(&"10⁻⁸") && labels.contains(&"10⁴"),
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
