//! The `simulate --plot` figure: a scene's coordinates, their rates and the relative energy
//! error against time.
//!
//! Panels, top to bottom: one per kind of coordinate (angles in rad, positions in m, others
//! without a unit), one per kind of rate (rad/s, m/s), the hoop's tilt when the run has a
//! `tilt` column that is not identically zero (a hoop that stays vertical has nothing to show),
//! and the relative energy error `|E − E₀|/|E₀|` on a logarithmic axis when the run has an
//! `energy_rel_err` column.
//!
//! Scenes name their coordinates but not their units, so the unit is read from the name
//! ([`quantity`]): Greek angle names (`alpha`, `phi`, `theta`, `psi`, …) are angles in
//! radians, `x`, `y`, `z` (and `r`, `s`) lengths in metres.

use super::xy::{Panel, Scale, Series, StackedFigure};

/// What a coordinate measures: a kind (`angle`) and its SI unit (`rad`; empty if unknown).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Quantity {
    /// Kind, for the axis label.
    pub kind: &'static str,
    /// SI unit of the coordinate (empty when unknown).
    pub unit: &'static str,
    /// SI unit of its rate.
    pub rate_unit: &'static str,
}

const ANGLES: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "phi", "theta", "psi", "chi", "eta", "xi",
];
const LENGTHS: &[&str] = &["x", "y", "z", "r", "s"];

/// The quantity a coordinate named `name` measures, from its name with any trailing digits
/// or underscores removed (`theta1`, `x_2`).
#[must_use]
pub fn quantity(name: &str) -> Quantity {
    let stem = name
        .trim_end_matches(|c: char| c.is_ascii_digit() || c == '_')
        .to_ascii_lowercase();
    if ANGLES.contains(&stem.as_str()) {
        Quantity {
            kind: "angle",
            unit: "rad",
            rate_unit: "rad/s",
        }
    } else if LENGTHS.contains(&stem.as_str()) {
        Quantity {
            kind: "position",
            unit: "m",
            rate_unit: "m/s",
        }
    } else {
        Quantity {
            kind: "coordinate",
            unit: "",
            rate_unit: "",
        }
    }
}

fn with_unit(label: &str, unit: &str) -> String {
    if unit.is_empty() {
        label.to_string()
    } else {
        format!("{label} ({unit})")
    }
}

/// A run to plot: column names (`t` first) and the values of each column (column-major: one
/// `Vec` per column, all of the same length).
#[derive(Debug, Clone, Copy)]
pub struct Run<'a> {
    /// Column names, as in the CSV header; the first is `t`.
    pub columns: &'a [String],
    /// `values[j][i]`: column `j` at row `i`.
    pub values: &'a [Vec<f64>],
    /// The scene's coordinates (rates are `<name>_dot`).
    pub coordinates: &'a [&'a str],
}

impl Run<'_> {
    fn column(&self, name: &str) -> Option<&[f64]> {
        let j = self.columns.iter().position(|c| c == name)?;
        self.values.get(j).map(Vec::as_slice)
    }

    fn series(&self, name: &str, label: &str) -> Option<Series> {
        let t = self.column("t")?;
        let y = self.column(name)?;
        Some(Series::line(
            label,
            t.iter().copied().zip(y.iter().copied()).collect(),
        ))
    }
}

/// The figure: `title` over coordinate, rate and energy-error panels (see the module doc).
#[must_use]
pub fn figure(title: impl Into<String>, run: &Run<'_>) -> StackedFigure {
    const TIME: &str = "time t (s)";
    let mut panels = Vec::new();
    // Group coordinates by quantity, keeping the scene's order.
    let mut groups: Vec<(Quantity, Vec<&str>)> = Vec::new();
    for &c in run.coordinates {
        let q = quantity(c);
        match groups.iter_mut().find(|(g, _)| *g == q) {
            Some((_, names)) => names.push(c),
            None => groups.push((q, vec![c])),
        }
    }
    for (q, names) in &groups {
        let mut panel = Panel::new(TIME, with_unit(q.kind, q.unit));
        for name in names {
            if let Some(s) = run.series(name, name) {
                panel = panel.with_series(s);
            }
        }
        panels.push(panel);
    }
    for (q, names) in &groups {
        let mut panel = Panel::new(TIME, with_unit(&format!("{} rate", q.kind), q.rate_unit));
        for name in names {
            let column = format!("{name}_dot");
            if let Some(s) = run.series(&column, &column) {
                panel = panel.with_series(s);
            }
        }
        panels.push(panel);
    }
    if run
        .column("tilt")
        .is_some_and(|v| v.iter().any(|&x| x != 0.0))
        && let Some(s) = run.series("tilt", "tilt")
    {
        panels.push(Panel::new(TIME, "hoop tilt from vertical (rad)").with_series(s));
    }
    if let Some(s) = run.series("energy_rel_err", "|E − E₀| / |E₀|") {
        panels.push(
            Panel::new(TIME, "relative energy error")
                .with_y_scale(Scale::Log)
                .with_series(s),
        );
    }
    StackedFigure {
        title: title.into(),
        subtitle: String::new(),
        panels,
        width: 1100,
        panel_height: 300,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_come_from_coordinate_names() {
        assert_eq!(quantity("alpha").unit, "rad");
        assert_eq!(quantity("theta1").rate_unit, "rad/s");
        assert_eq!(quantity("z").unit, "m");
        assert_eq!(quantity("q0").unit, "");
    }

    #[test]
    fn panels_group_coordinates_by_unit_then_rates_then_energy_error() {
        let columns: Vec<String> = ["t", "phi", "x", "alpha", "phi_dot", "x_dot", "alpha_dot"]
            .iter()
            .map(|s| (*s).to_string())
            .chain(["energy".into(), "energy_rel_err".into(), "tilt".into()])
            .collect();
        let mut values = vec![vec![0.0, 1.0]; columns.len()];
        let run = Run {
            columns: &columns,
            values: &values,
            coordinates: &["phi", "x", "alpha"],
        };
        let f = figure("title", &run);
        let labels: Vec<&str> = f.panels.iter().map(|p| p.y_label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "angle (rad)",
                "position (m)",
                "angle rate (rad/s)",
                "position rate (m/s)",
                "hoop tilt from vertical (rad)",
                "relative energy error"
            ]
        );
        let names: Vec<&str> = f.panels[0]
            .series
            .iter()
            .map(|s| s.label.as_str())
            .collect();
        assert_eq!(names, ["phi", "alpha"]);
        assert_eq!(f.panels[5].y_scale, Scale::Log);
        assert!(f.panels.iter().all(|p| p.x_label == "time t (s)"));
        // A tilt that stays 0 (a vertical hoop) gets no panel.
        values[9] = vec![0.0, 0.0];
        let run = Run {
            columns: &columns,
            values: &values,
            coordinates: &["phi", "x", "alpha"],
        };
        assert_eq!(figure("title", &run).panels.len(), 5);
    }
}
