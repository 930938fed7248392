//! The `simulate --plot` figure: a scene's coordinates, their rates and the relative energy
//! error against time.
//!
//! Panels, top to bottom: one per kind of coordinate (angles in rad, positions in m,
//! quaternion components, others without a unit), one per kind of rate (rad/s, m/s, the body
//! angular velocity of a rotation), the hoop's tilt when the run has a `tilt` column that is
//! not identically zero (a hoop that stays vertical has nothing to show), and, on logarithmic
//! axes, the relative energy error `|E − E₀|/E_s` (`energy_rel_err`) and the error against an
//! exact solution (`exact_err`) when the run has those columns.
//!
//! Scenes name their coordinates and rates but not their units, so the unit is read from the
//! name ([`quantity`], [`rate_quantity`]): Greek angle names (`alpha`, `phi`, `theta`, `psi`,
//! …) are angles in radians, `x`, `y`, `z` (and `r`, `s`) lengths in metres, `qw`, `qx`, `qy`,
//! `qz` components of a unit quaternion; a rate `<name>_dot` has the unit of `<name>` per
//! second, `omega_x` (any `omega_*`) is an angular velocity in rad/s.

use tumble_scenarios::StepControl;
use tumble_scenarios::display::symbol;
use tumble_studies::simulation::number;

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
    } else if matches!(stem.as_str(), "qw" | "qx" | "qy" | "qz") {
        Quantity {
            kind: "orientation quaternion",
            unit: "",
            rate_unit: "1/s",
        }
    } else {
        Quantity {
            kind: "coordinate",
            unit: "",
            rate_unit: "",
        }
    }
}

/// The quantity a rate column named `name` measures, as `(kind, unit)`: `<coordinate>_dot` is
/// the coordinate's rate, `omega_*` an angular velocity.
#[must_use]
pub fn rate_quantity(name: &str) -> (String, &'static str) {
    if let Some(coordinate) = name.strip_suffix("_dot") {
        let q = quantity(coordinate);
        (format!("{} rate", q.kind), q.rate_unit)
    } else if name == "omega" || name.starts_with("omega_") {
        ("angular velocity".to_string(), "rad/s")
    } else {
        ("rate".to_string(), "")
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
    /// The scene's coordinates.
    pub coordinates: &'a [String],
    /// The scene's rate columns (`<coordinate>_dot`, or named rates such as `omega_x`).
    pub rates: &'a [String],
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
    // Group coordinates, then rates, by quantity, keeping the scene's order.
    let mut groups: Vec<(String, Vec<&str>)> = Vec::new();
    let mut add = |label: String, name| match groups.iter_mut().find(|(g, _)| *g == label) {
        Some((_, names)) => names.push(name),
        None => groups.push((label, vec![name])),
    };
    for c in run.coordinates {
        let q = quantity(c);
        add(with_unit(q.kind, q.unit), c);
    }
    for r in run.rates {
        let (kind, unit) = rate_quantity(r);
        add(with_unit(&kind, unit), r.as_str());
    }
    for (label, names) in &groups {
        let mut panel = Panel::new(TIME, label.as_str());
        for name in names {
            if let Some(s) = run.series(name, &symbol(name)) {
                panel = panel.with_series(s);
            }
        }
        if !panel.series.is_empty() {
            panels.push(panel);
        }
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
    if let Some(s) = run.series("exact_err", &symbol("exact_err")) {
        panels.push(
            Panel::new(TIME, "error against the exact solution")
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

/// A finished run, as its figure reads it: what the scene declares (its name, coordinates and
/// rate columns), how the run was made (integrator, step control, parameters in the scene's
/// order) and its rows, column by column. `simulate --plot`, `tumble plot FILE.csv` and
/// Python's `Simulation.plot` build one and draw [`RunResult::figure`].
#[derive(Debug, Clone, PartialEq)]
pub struct RunResult {
    /// The scene's name.
    pub scene: String,
    /// The scene's coordinates, in its order.
    pub coordinates: Vec<String>,
    /// The scene's rate columns (`<coordinate>_dot`, or named rates such as `omega_x`).
    pub rates: Vec<String>,
    /// The integrator's name.
    pub integrator: String,
    /// Its step control.
    pub step: StepControl,
    /// The scene's parameters and their values, in the scene's order.
    pub parameters: Vec<(String, f64)>,
    /// Column names, as in the CSV header; the first is `t`.
    pub columns: Vec<String>,
    /// `values[j][i]`: column `j` at row `i`.
    pub values: Vec<Vec<f64>>,
}

impl RunResult {
    /// A run of scene `info` with `params`: the declaration taken from `info`.
    #[must_use]
    pub fn of_scene(
        info: &tumble_scenarios::SceneInfo,
        integrator: &str,
        step: StepControl,
        params: &tumble_scenarios::Params,
        columns: Vec<String>,
        values: Vec<Vec<f64>>,
    ) -> Self {
        RunResult {
            scene: info.name.to_string(),
            coordinates: info.coordinates.iter().map(|c| (*c).to_string()).collect(),
            rates: tumble_studies::simulation::rate_columns(info),
            integrator: integrator.to_string(),
            step,
            parameters: params.iter().map(|(k, v)| (k.to_string(), v)).collect(),
            columns,
            values,
        }
    }

    /// The `simulate --plot` figure: the title names the scene, the integrator and the step
    /// control, the subtitle the parameters.
    #[must_use]
    pub fn figure(&self) -> StackedFigure {
        let run = Run {
            columns: &self.columns,
            values: &self.values,
            coordinates: &self.coordinates,
            rates: &self.rates,
        };
        let mut figure = figure(
            format!(
                "{} — {}, {}",
                self.scene,
                self.integrator,
                step_words(self.step)
            ),
            &run,
        );
        figure.subtitle =
            super::labels::parameters(self.parameters.iter().map(|(k, v)| (k.as_str(), *v)));
        figure
    }
}

/// A step control in the words of a run's title: `fixed step dt = 0.001 s`, `tolerance 1e-10`.
#[must_use]
pub fn step_words(step: StepControl) -> String {
    match step {
        StepControl::Fixed(h) => format!("fixed step dt = {h} s"),
        StepControl::Tolerance(tol) => format!("tolerance {}", number(tol)),
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
        assert_eq!(quantity("q0").kind, "coordinate");
        assert_eq!(quantity("qx").kind, "orientation quaternion");
        assert_eq!(
            rate_quantity("alpha_dot"),
            ("angle rate".to_string(), "rad/s")
        );
        assert_eq!(
            rate_quantity("omega_y"),
            ("angular velocity".to_string(), "rad/s")
        );
    }

    #[test]
    fn quaternion_scenes_get_orientation_and_angular_velocity_panels() {
        let columns: Vec<String> = [
            "t",
            "qw",
            "qx",
            "qy",
            "qz",
            "alpha",
            "omega_x",
            "omega_y",
            "omega_z",
            "alpha_dot",
            "exact_err",
        ]
        .map(String::from)
        .into();
        let values = vec![vec![0.0, 1.0]; columns.len()];
        let rates: Vec<String> = ["omega_x", "omega_y", "omega_z", "alpha_dot"]
            .map(String::from)
            .into();
        let run = Run {
            columns: &columns,
            values: &values,
            coordinates: &["qw", "qx", "qy", "qz", "alpha"].map(String::from),
            rates: &rates,
        };
        let f = figure("free", &run);
        let labels: Vec<&str> = f.panels.iter().map(|p| p.y_label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "orientation quaternion",
                "angle (rad)",
                "angular velocity (rad/s)",
                "angle rate (rad/s)",
                "error against the exact solution"
            ]
        );
        assert_eq!(f.panels[0].series.len(), 4);
        assert_eq!(f.panels[2].series.len(), 3);
    }

    #[test]
    fn panels_group_coordinates_by_unit_then_rates_then_energy_error() {
        let columns: Vec<String> = ["t", "phi", "x", "alpha", "phi_dot", "x_dot", "alpha_dot"]
            .iter()
            .map(|s| (*s).to_string())
            .chain(["energy".into(), "energy_rel_err".into(), "tilt".into()])
            .collect();
        let mut values = vec![vec![0.0, 1.0]; columns.len()];
        let rates: Vec<String> = ["phi_dot", "x_dot", "alpha_dot"].map(String::from).into();
        let run = Run {
            columns: &columns,
            values: &values,
            coordinates: &["phi", "x", "alpha"].map(String::from),
            rates: &rates,
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
        assert_eq!(names, ["φ", "α"]);
        assert_eq!(f.panels[5].y_scale, Scale::Log);
        assert!(f.panels.iter().all(|p| p.x_label == "time t (s)"));
        let names: Vec<&str> = f.panels[2]
            .series
            .iter()
            .map(|s| s.label.as_str())
            .collect();
        assert_eq!(names, ["φ\u{307}", "α\u{307}"]);
        // A tilt that stays 0 (a vertical hoop) gets no panel.
        values[9] = vec![0.0, 0.0];
        let run = Run {
            columns: &columns,
            values: &values,
            coordinates: &["phi", "x", "alpha"].map(String::from),
            rates: &rates,
        };
        assert_eq!(figure("title", &run).panels.len(), 5);
    }
}
