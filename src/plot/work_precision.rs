//! Work–precision figures: error against wall time and against right-hand-side evaluations
//! (log–log, one curve per integrator), and the long-run relative energy error against time.

use super::xy::{LegendCorner, Mark, Panel, Scale, Series, StackedFigure};

/// One integrator's curve: `(wall time s, evaluations, error)` per rung.
pub struct Curve {
    /// Legend entry (integrator and order).
    pub label: String,
    /// `(seconds, evaluations, error)` from coarse to fine.
    pub rungs: Vec<(f64, f64, f64)>,
}

/// Error at the final time against wall time (top) and against evaluations (bottom).
pub fn figure(title: String, subtitle: String, curves: &[Curve]) -> StackedFigure {
    let panel = |x_label: &str, pick: fn(&(f64, f64, f64)) -> f64| {
        let mut p = Panel::new(x_label, "error at the final time")
            .with_x_scale(Scale::Log)
            .with_y_scale(Scale::Log)
            .with_legend(LegendCorner::LowerLeft);
        for c in curves {
            p = p.with_series(Series::marked(
                c.label.clone(),
                c.rungs.iter().map(|r| (pick(r), r.2)).collect(),
                if c.rungs.len() == 1 {
                    Mark::Points
                } else {
                    Mark::LineAndPoints
                },
            ));
        }
        p
    };
    StackedFigure {
        title,
        subtitle,
        panels: vec![
            panel("wall time per run (s)", |r| r.0),
            panel(
                "right-hand-side evaluations (steps for splitting methods)",
                |r| r.1,
            ),
        ],
        width: 1000,
        panel_height: 760,
    }
}

/// The relative energy error's maximum per logarithmic time bin, one line per method.
pub fn long_figure(title: String, subtitle: String, lines: Vec<Series>) -> StackedFigure {
    let mut panel = Panel::new(
        "time (s)",
        "relative energy error |E − E₀|/|E₀| (maximum per log-time bin)",
    )
    .with_x_scale(Scale::Log)
    .with_y_scale(Scale::Log)
    .with_legend(LegendCorner::UpperLeft);
    for s in lines {
        panel = panel.with_series(s);
    }
    StackedFigure {
        title,
        subtitle,
        panels: vec![panel],
        width: 1000,
        panel_height: 700,
    }
}
