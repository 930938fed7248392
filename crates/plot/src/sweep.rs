//! The figures of a sweep folder: the map of the first metric over a two-axis grid, with the
//! scene's guides ([`tumble_scenarios::Scene::map_guides`]), and its slices.

use std::path::Path;

use crate::Result;
use tumble_scenarios::{Guide, StepControl};
use tumble_studies::sweep::{Metric, PointRow, Sampling, Status, SweepDefinition};

use crate as plot;
use crate::labels;
use tumble_scenarios::display::symbol;

fn metric_label(m: &Metric) -> String {
    if m.unit().is_empty() {
        m.description().to_string()
    } else {
        format!("{} ({})", m.description(), m.unit())
    }
}

/// The plot files' stem for metric `m`: `tilt` for the tilt metrics, else the metric's name
/// with every character other than a letter, digit, `.`, `-` or `_` written `_`
/// (`max:alpha` → `max_alpha`, `first_time:tilt>0.5` → `first_time_tilt_0.5`).
pub fn plot_stem(m: &Metric) -> String {
    if m.needs_tilt() {
        return "tilt".to_string();
    }
    m.name()
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The fixed parameters, for subtitles.
fn fixed_parameters(def: &SweepDefinition) -> String {
    labels::parameters(
        def.params
            .iter()
            .filter(|(n, _)| !def.axes.iter().any(|a| a.parameter == *n)),
    )
}

/// What to draw of a sweep: which of its metrics, and along how many rows of the grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Choice {
    /// Index into the sweep's metrics.
    pub metric: usize,
    /// Most slices (rows of the grid) to draw.
    pub slices: usize,
    /// Colour the map on a base-10 logarithmic scale.
    pub log_colour: bool,
    /// The map's colour map.
    pub colour_map: super::colour::ColourMap,
}

impl Default for Choice {
    fn default() -> Self {
        Choice {
            metric: 0,
            slices: 5,
            log_colour: false,
            colour_map: super::colour::ColourMap::Viridis,
        }
    }
}

/// The figures of a complete grid sweep: the map (two axes with increasing grid values) and
/// the slices, with the files' stem.
pub struct Figures {
    /// `tilt`, or the metric's name made safe for a file name.
    pub stem: String,
    /// The map, for a two-axis grid.
    pub map: Option<plot::heatmap::Heatmap>,
    /// The metric against the first axis.
    pub slices: plot::xy::StackedFigure,
}

/// Draws the map and slices of a complete grid sweep with `opts`; returns the file names
/// written.
pub fn draw_plots(
    def: &SweepDefinition,
    dir: &Path,
    rows: &[PointRow],
    opts: &plot::FigureOptions,
) -> Result<Vec<String>> {
    let Some(figures) = figures(def, rows, &Choice::default()) else {
        return Ok(Vec::new());
    };
    let mut written = Vec::new();
    for ext in ["png", "svg"] {
        if let Some(map) = &figures.map {
            let name = format!("{}-map.{ext}", figures.stem);
            plot::save_with(map, &dir.join(&name), opts)?;
            written.push(name);
        }
    }
    for ext in ["png", "svg"] {
        let name = format!("{}-slices.{ext}", figures.stem);
        plot::save_with(&figures.slices, &dir.join(&name), opts)?;
        written.push(name);
    }
    Ok(written)
}

/// The figures of metric `choice.metric` of a sweep over a grid of one or two axes; `None`
/// for random sampling, more than two axes or a metric the sweep does not have.
pub fn figures(def: &SweepDefinition, rows: &[PointRow], choice: &Choice) -> Option<Figures> {
    let k = choice.metric;
    let metric = def.metrics.get(k)?;
    if def.sampling != Sampling::Grid || def.axes.len() > 2 {
        return None;
    }
    let info = def.scene.info();
    let stem = plot_stem(metric);
    let value = |row: &PointRow| {
        (row.status == Status::Ok)
            .then(|| row.metrics.get(k).copied().flatten())
            .flatten()
    };
    let x_axis = &def.axes[0];
    let xs = x_axis.grid_values();
    let increasing = |v: &[f64]| v.windows(2).all(|w| w[0] < w[1]);
    let horizon = format!("over t in [0, {}] s", def.plan.t_end);
    let subtitle = format!(
        "{}, {}; {}",
        def.plan.integrator(),
        step_words(def.plan.step),
        fixed_parameters(def)
    );
    let x_label = labels::axis(x_axis.parameter, x_axis.unit);
    if def.axes.len() == 1 {
        // The rows' own x values: a refined sweep has some points of the grid only.
        let slice = plot::slices::Slice {
            label: metric.name().to_string(),
            points: rows.iter().map(|r| (r.values[0], value(r))).collect(),
        };
        let slices = plot::slices::figure(
            format!("{} {horizon}", metric.description()),
            subtitle,
            &x_label,
            &metric_label(metric),
            x_axis.is_log(),
            &[slice],
        );
        return Some(Figures {
            stem,
            map: None,
            slices,
        });
    }
    let y_axis = &def.axes[1];
    let ys = y_axis.grid_values();
    let (nx, ny) = (xs.len(), ys.len());
    let grid = painted_grid(def, rows, nx, ny, &value);
    let map = (increasing(&xs) && increasing(&ys)).then(|| {
        let (markers, curves) = guides(def, &xs);
        plot::heatmap::Heatmap {
            title: format!("{}: {} {horizon}", info.name, metric.description()),
            subtitle: subtitle.clone(),
            x_label: x_label.clone(),
            y_label: labels::axis(y_axis.parameter, y_axis.unit),
            value_label: metric_label(metric),
            xs: xs.clone(),
            ys: ys.clone(),
            values: grid,
            range: None,
            markers,
            curves,
            x_log: x_axis.is_log(),
            y_log: y_axis.is_log(),
            value_log: choice.log_colour,
            colour_map: choice.colour_map,
            size: (1000, 720),
        }
    });
    // A refined map's slices run along rows of its coarse grid (computed across the whole
    // range) through the points computed on them.
    let stride = def.refine.as_ref().map_or(1, |r| 1usize << r.levels);
    let candidates: Vec<usize> = (0..ny)
        .filter(|&j| j % stride == 0 || j + 1 == ny)
        .collect();
    let slices: Vec<plot::slices::Slice> = plot::slices::pick_rows(candidates.len(), choice.slices)
        .into_iter()
        .map(|k| candidates[k])
        .map(|j| plot::slices::Slice {
            label: format!(
                "{} = {}{}",
                symbol(y_axis.parameter),
                if y_axis.is_log() {
                    plot::heatmap::log_labels(&ys[j].log10())
                } else {
                    labels::value(ys[j])
                },
                if y_axis.unit.is_empty() {
                    String::new()
                } else {
                    format!(" {}", y_axis.unit)
                }
            ),
            points: rows
                .iter()
                .filter(|r| r.index as usize % ny == j)
                .map(|r| (r.values[0], value(r)))
                .collect(),
        })
        .collect();
    let slices = plot::slices::figure(
        format!(
            "{}: {} {horizon}, against {}",
            info.name,
            metric.description(),
            symbol(x_axis.parameter)
        ),
        subtitle,
        &x_label,
        &metric_label(metric),
        x_axis.is_log(),
        &slices,
    );
    Some(Figures { stem, map, slices })
}

/// The map's cells, `values[j][i]` at `(xs[i], ys[j])` (points are numbered with the last
/// (y) axis fastest). A refined sweep's point of level `ℓ` (of `L`) is drawn at its own size:
/// it fills the cells within `2^(L−ℓ−1)` grid steps of it, coarse levels first, so that each
/// finer point covers the part of the coarser ones' cells it refines.
fn painted_grid(
    def: &SweepDefinition,
    rows: &[PointRow],
    nx: usize,
    ny: usize,
    value: &dyn Fn(&PointRow) -> Option<f64>,
) -> Vec<Vec<Option<f64>>> {
    let mut grid = vec![vec![None; nx]; ny];
    let Some(refine) = &def.refine else {
        for row in rows {
            let (i, j) = ((row.index as usize) / ny, (row.index as usize) % ny);
            grid[j][i] = value(row);
        }
        return grid;
    };
    let mut by_level: Vec<(u32, &PointRow)> = rows
        .iter()
        .map(|r| (def.level(r.index).unwrap_or(refine.levels), r))
        .collect();
    by_level.sort_by_key(|(level, r)| (*level, r.index));
    for (level, row) in by_level {
        let half = (1usize << (refine.levels - level.min(refine.levels))) / 2;
        let (i, j) = ((row.index as usize) / ny, (row.index as usize) % ny);
        let v = value(row);
        for line in &mut grid[j.saturating_sub(half)..=(j + half).min(ny - 1)] {
            for cell in &mut line[i.saturating_sub(half)..=(i + half).min(nx - 1)] {
                *cell = v;
            }
        }
    }
    grid
}

/// The scene's guides for a map of `def` whose first axis takes the values `xs`: vertical
/// markers and curves.
fn guides(
    def: &SweepDefinition,
    xs: &[f64],
) -> (Vec<plot::heatmap::Marker>, Vec<plot::heatmap::Curve>) {
    let axes: Vec<&str> = def.axes.iter().map(|a| a.parameter).collect();
    let range = (
        xs.first().copied().unwrap_or(0.0),
        xs.last().copied().unwrap_or(0.0),
    );
    let (mut markers, mut curves) = (Vec::new(), Vec::new());
    for guide in def.scene.map_guides(&def.params, &axes, range) {
        match guide {
            Guide::Vertical { x, label } => markers.push(plot::heatmap::Marker { x, label }),
            Guide::Curve { label, points } => curves.push(plot::heatmap::Curve { label, points }),
        }
    }
    (markers, curves)
}

/// A sweep's step or tolerance in words: `fixed step dt = 0.01 s`, `tolerance 1e-10`.
pub fn step_words(step: StepControl) -> String {
    match step {
        StepControl::Fixed(h) => format!("fixed step dt = {h} s"),
        StepControl::Tolerance(tol) => format!("tolerance {tol:e}"),
    }
}
