//! Metrics of one sweep point, computed by a [`Recorder`] while the scene integrates: nothing
//! of the trajectory is kept but the current step.
//!
//! # Column metrics, for any column of any scene
//!
//! `max:COL`, `min:COL`, `final:COL`, `mean:COL` (time average), `first_time:COL>VALUE` and
//! `first_time:COL<VALUE` (the first time the column exceeds or falls below the value; empty
//! when it never does). They are located on the method's dense output, not on the steps (see
//! [`super::column`]: extremes by Brent's method on the dense output, crossings by the Illinois
//! method, the average by adaptive Clenshaw–Curtis quadrature of each step). The hoop scenes' names are
//! aliases: `max_tilt` is `max:tilt`, `final_tilt` is `final:tilt`, `time_tilt_exceeds` is
//! `first_time:tilt>THRESHOLD` with `metrics.tilt_threshold`.
//!
//! # Other metrics
//!
//! * `max_energy_rel_err`: the run's largest `|E − E₀|/E_s` over every step.
//! * `flips` (`free-body`, `dzhanibekov`): the number of sign changes of `ω · e₂`, the body
//!   angular velocity's component on the intermediate principal axis — each is one flip of
//!   the body (the T-handle's half turn) — as in the scenes' flip-period test.
//!
//! A row with a non-finite value stops the run: the point fails with the time and column.

use std::fmt;

use nalgebra::Vector3;
use tumble_integrators::Flow;

use tumble_scenarios::error::SceneError;
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{DenseRows, Recorder, Scene};

pub use super::column::ColumnOp;
use super::column::{ColumnTracker, lobatto_nodes};

/// A quantity recorded for every point of a sweep.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Metric {
    /// Largest tilt of the hoop over the horizon (rad): `max:tilt`.
    MaxTilt,
    /// Tilt at the end of the horizon (rad): `final:tilt`.
    FinalTilt,
    /// First time the tilt exceeds the threshold (s): `first_time:tilt>THRESHOLD`.
    TimeTiltExceeds,
    /// Largest relative energy error over every step.
    MaxEnergyRelErr,
    /// Sign changes of the body angular velocity on the intermediate principal axis.
    Flips,
    /// A metric of one column (`max:COL`, …).
    Column {
        /// What is computed.
        op: ColumnOp,
        /// The column's name.
        column: String,
    },
}

impl Metric {
    /// The named metrics, in the order the documentation lists them.
    pub const ALL: [Metric; 5] = [
        Metric::MaxTilt,
        Metric::FinalTilt,
        Metric::TimeTiltExceeds,
        Metric::MaxEnergyRelErr,
        Metric::Flips,
    ];

    /// The forms of a column metric, for messages.
    pub const COLUMN_FORMS: &'static str =
        "max:COL, min:COL, final:COL, mean:COL, first_time:COL>VALUE, first_time:COL<VALUE";

    /// Its name in sweep files and CSV headers.
    #[must_use]
    pub fn name(&self) -> String {
        match self {
            Metric::MaxTilt => "max_tilt".into(),
            Metric::FinalTilt => "final_tilt".into(),
            Metric::TimeTiltExceeds => "time_tilt_exceeds".into(),
            Metric::MaxEnergyRelErr => "max_energy_rel_err".into(),
            Metric::Flips => "flips".into(),
            Metric::Column { op, column } => match op {
                ColumnOp::Max => format!("max:{column}"),
                ColumnOp::Min => format!("min:{column}"),
                ColumnOp::Final => format!("final:{column}"),
                ColumnOp::Mean => format!("mean:{column}"),
                ColumnOp::FirstTime { above, value } => {
                    format!(
                        "first_time:{column}{}{value}",
                        if *above { ">" } else { "<" }
                    )
                }
            },
        }
    }

    /// Its SI unit (empty when dimensionless or unknown).
    #[must_use]
    pub fn unit(&self) -> &'static str {
        match self {
            Metric::MaxTilt | Metric::FinalTilt => "rad",
            Metric::TimeTiltExceeds
            | Metric::Column {
                op: ColumnOp::FirstTime { .. },
                ..
            } => "s",
            Metric::Column { column, .. } if column == "tilt" => "rad",
            _ => "",
        }
    }

    /// What it is, in a few words (plot labels).
    #[must_use]
    pub fn description(&self) -> String {
        match self {
            Metric::MaxTilt => "maximum tilt".into(),
            Metric::FinalTilt => "final tilt".into(),
            Metric::TimeTiltExceeds => "time the tilt first exceeds the threshold".into(),
            Metric::MaxEnergyRelErr => "maximum relative energy error".into(),
            Metric::Flips => "number of flips".into(),
            Metric::Column { op, column } => match op {
                ColumnOp::Max => format!("maximum {column}"),
                ColumnOp::Min => format!("minimum {column}"),
                ColumnOp::Final => format!("final {column}"),
                ColumnOp::Mean => format!("time-averaged {column}"),
                ColumnOp::FirstTime { above, value } => format!(
                    "time {column} first {} {value}",
                    if *above { "exceeds" } else { "falls below" }
                ),
            },
        }
    }

    /// The metric called `name`: a named metric or a column metric.
    ///
    /// # Errors
    /// What is wrong with the name (an unknown form, an empty column, a value that is not a
    /// finite number).
    pub fn parse(name: &str) -> Result<Metric, String> {
        if let Some(m) = Metric::ALL.into_iter().find(|m| m.name() == name) {
            return Ok(m);
        }
        let unknown = || {
            format!(
                "unknown metric `{name}`; metrics: {}, or a column metric ({})",
                Metric::ALL.map(|m| m.name()).join(", "),
                Metric::COLUMN_FORMS
            )
        };
        let Some((form, rest)) = name.split_once(':') else {
            return Err(unknown());
        };
        let (op, column) = match form {
            "max" => (ColumnOp::Max, rest),
            "min" => (ColumnOp::Min, rest),
            "final" => (ColumnOp::Final, rest),
            "mean" => (ColumnOp::Mean, rest),
            "first_time" => {
                let Some(i) = rest.find(['>', '<']) else {
                    return Err(format!(
                        "`{name}`: a crossing needs `>` or `<` and a value, e.g.                          `first_time:{rest}>0.5`"
                    ));
                };
                let (column, value) = (&rest[..i], &rest[i + 1..]);
                let v: f64 = value.trim().parse().map_err(|_| {
                    format!("`{name}`: the crossing value `{value}` is not a number")
                })?;
                if !v.is_finite() {
                    return Err(format!(
                        "`{name}`: the crossing value must be finite, not {value}"
                    ));
                }
                (
                    ColumnOp::FirstTime {
                        above: rest.as_bytes()[i] == b'>',
                        value: v,
                    },
                    column,
                )
            }
            _ => return Err(unknown()),
        };
        if column.is_empty() {
            return Err(format!("`{name}`: name a column after `{form}:`"));
        }
        Ok(Metric::Column {
            op,
            column: column.to_owned(),
        })
    }

    /// The column metric this is (aliases resolved; `threshold` is `metrics.tilt_threshold`).
    #[must_use]
    pub fn as_column(&self, threshold: Option<f64>) -> Option<(ColumnOp, &str)> {
        match self {
            Metric::MaxTilt => Some((ColumnOp::Max, "tilt")),
            Metric::FinalTilt => Some((ColumnOp::Final, "tilt")),
            Metric::TimeTiltExceeds => Some((
                ColumnOp::FirstTime {
                    above: true,
                    value: threshold.unwrap_or(f64::NAN),
                },
                "tilt",
            )),
            Metric::Column { op, column } => Some((*op, column)),
            Metric::MaxEnergyRelErr | Metric::Flips => None,
        }
    }

    /// Whether its values are whole numbers (written without a decimal point).
    #[must_use]
    pub fn is_count(&self) -> bool {
        matches!(self, Metric::Flips)
    }

    /// The column a plot of it draws against (the tilt for the hoop names).
    #[must_use]
    pub fn needs_tilt(&self) -> bool {
        matches!(
            self,
            Metric::MaxTilt | Metric::FinalTilt | Metric::TimeTiltExceeds
        )
    }

    /// Why the metric does not apply to `scene`, or `None` when it does.
    #[must_use]
    pub fn not_applicable(&self, scene: &dyn Scene) -> Option<String> {
        let info = scene.info();
        let columns = info.columns();
        let column = match self {
            Metric::Column { column, .. } => Some(column.as_str()),
            m if m.needs_tilt() => Some("tilt"),
            _ => None,
        };
        if let Some((fixed, why)) = scene
            .fixed_columns()
            .iter()
            .find(|(c, _)| Some(*c) == column)
        {
            return Some(format!(
                "`{}`: in scene `{}`, {why}; `{fixed}` has nothing to measure",
                self.name(),
                info.name
            ));
        }
        if self.needs_tilt() && !columns.iter().any(|c| c == "tilt") {
            return Some(format!(
                "`{}` needs a hoop scene (a `tilt` column); scene `{}` has none",
                self.name(),
                info.name
            ));
        }
        if let Metric::Column { op, column } = self {
            if column == "t" || !columns.iter().any(|c| c == column) {
                return Some(format!(
                    "`{}`: scene `{}` has no column `{column}`; its columns: {}",
                    self.name(),
                    info.name,
                    columns[1..].join(", ")
                ));
            }
            if let ColumnOp::FirstTime { value, .. } = op
                && column == "tilt"
                && !(*value > 0.0 && *value < std::f64::consts::FRAC_PI_2)
            {
                return Some(format!(
                    "`{}`: a tilt is asin|n_z|, in [0, pi/2]; cross a value strictly between",
                    self.name()
                ));
            }
        }
        if *self == Metric::Flips && scene.intermediate_axis(&info.default_params()).is_none() {
            let bodies: Vec<&str> = tumble_scenarios::scenes::builtin()
                .iter()
                .filter(|s| s.intermediate_axis(&s.info().default_params()).is_some())
                .map(|s| s.info().name)
                .collect();
            return Some(format!(
                "`flips` applies to the torque-free bodies ({}), not to scene `{}`",
                bodies.join(", "),
                info.name
            ));
        }
        None
    }
}

impl fmt::Display for Metric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

/// Counts sign changes of `ω · e₂`.
struct FlipCounter {
    axis: Vector3<f64>,
    omega_column: usize,
    sign: Option<f64>,
    flips: u64,
}

impl FlipCounter {
    fn push(&mut self, row: &[f64]) {
        let w = Vector3::new(
            row[self.omega_column],
            row[self.omega_column + 1],
            row[self.omega_column + 2],
        );
        let d = w.dot(&self.axis);
        if d != 0.0 {
            let sign = d.signum();
            if self.sign.is_some_and(|s| s != sign) {
                self.flips += 1;
            }
            self.sign = Some(sign);
        }
    }
}

/// Computes a point's metrics from the rows of its run.
pub(crate) struct MetricRecorder {
    columns: Vec<String>,
    /// One tracker per column metric, with the metric's index.
    trackers: Vec<(usize, ColumnTracker)>,
    /// Node values of the current step, one array per tracker (allocated once).
    nodes: Vec<[f64; 5]>,
    flips: Option<FlipCounter>,
    /// Why the run was stopped (a non-finite value).
    failure: Option<String>,
}

impl MetricRecorder {
    /// A recorder for `metrics` of `scene` run with `params`, whose rows hold `columns` (the
    /// scene's, or its reduction's).
    ///
    /// # Errors
    /// The parameters of a torque-free body without a defined intermediate axis (`flips`); a
    /// column the rows do not have.
    pub(crate) fn new(
        scene: &dyn Scene,
        columns: Vec<String>,
        params: &Params,
        metrics: &[Metric],
        tilt_threshold: Option<f64>,
    ) -> Result<Self, SceneError> {
        let info = scene.info();
        let find = |name: &str| columns.iter().position(|c| c == name);
        let mut trackers = Vec::new();
        for (i, m) in metrics.iter().enumerate() {
            if let Some((op, column)) = m.as_column(tilt_threshold) {
                let j = find(column).ok_or_else(|| SceneError::InvalidOption {
                    option: "metrics",
                    value: f64::NAN,
                    reason: format!("scene `{}` has no column `{column}`", info.name),
                })?;
                trackers.push((i, ColumnTracker::new(j, op, column == "tilt")));
            }
        }
        let flips = if metrics.contains(&Metric::Flips) {
            Some(FlipCounter {
                axis: scene.intermediate_axis(params).ok_or_else(|| {
                    SceneError::InvalidOption {
                        option: "flips",
                        value: f64::NAN,
                        reason: format!("scene `{}` has no intermediate axis", info.name),
                    }
                })??,
                omega_column: find("omega_x").ok_or_else(|| SceneError::InvalidOption {
                    option: "flips",
                    value: f64::NAN,
                    reason: format!("scene `{}` has no omega_x column", info.name),
                })?,
                sign: None,
                flips: 0,
            })
        } else {
            None
        };
        Ok(MetricRecorder {
            columns,
            nodes: vec![[0.0; 5]; trackers.len()],
            trackers,
            flips,
            failure: None,
        })
    }

    /// Why the run stopped early, if it did.
    pub(crate) fn failure(&self) -> Option<&str> {
        self.failure.as_deref()
    }

    /// The value of `metric` after the run (`None`: not defined, e.g. a threshold never
    /// crossed). `max_energy_rel_err` is the run summary's.
    pub(crate) fn finish(
        &mut self,
        metrics: &[Metric],
        max_energy_rel_err: f64,
    ) -> Vec<Option<f64>> {
        metrics
            .iter()
            .enumerate()
            .map(|(i, m)| match m {
                Metric::MaxEnergyRelErr => Some(max_energy_rel_err),
                Metric::Flips => self.flips.as_ref().map(|f| f.flips as f64),
                _ => self
                    .trackers
                    .iter()
                    .find(|(k, _)| *k == i)
                    .and_then(|(_, t)| t.finish()),
            })
            .collect()
    }
}

impl Recorder for MetricRecorder {
    fn wants_dense_rows(&self) -> bool {
        !self.trackers.is_empty()
    }

    fn dense_rows(&mut self, rows: &mut dyn DenseRows) -> Flow {
        let (t0, t1) = rows.span();
        let times = lobatto_nodes(t0, t1);
        for (k, &t) in times.iter().enumerate() {
            let row = rows.row_at(t);
            for ((_, tracker), nodes) in self.trackers.iter().zip(self.nodes.iter_mut()) {
                nodes[k] = row[tracker.column()];
            }
        }
        for ((_, tracker), nodes) in self.trackers.iter_mut().zip(&self.nodes) {
            tracker.step(&times, nodes, rows);
        }
        Flow::Continue
    }

    fn row(&mut self, values: &[f64]) -> Flow {
        if let Some(j) = values.iter().position(|v| !v.is_finite()) {
            self.failure = Some(format!(
                "non-finite state at t = {}: {} = {}",
                values[0],
                self.columns.get(j).map_or("?", String::as_str),
                values[j]
            ));
            return Flow::Stop;
        }
        for (_, tracker) in &mut self.trackers {
            tracker.row(values);
        }
        if let Some(flips) = &mut self.flips {
            flips.push(values);
        }
        Flow::Continue
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metric_names_round_trip() {
        for m in Metric::ALL {
            assert_eq!(Metric::parse(&m.name()), Ok(m));
        }
        for name in [
            "max:alpha",
            "min:omega_z",
            "final:x",
            "mean:energy",
            "first_time:tilt>0.5",
            "first_time:z<-1.25",
        ] {
            assert_eq!(Metric::parse(name).map(|m| m.name()), Ok(name.to_owned()));
        }
    }

    #[test]
    fn malformed_metric_names_are_refused_with_the_reason() {
        for (name, says) in [
            ("tilt", "unknown metric"),
            ("peak:alpha", "unknown metric"),
            ("max:", "name a column"),
            ("first_time:tilt", "needs `>` or `<`"),
            ("first_time:tilt>abc", "not a number"),
            ("first_time:tilt>inf", "must be finite"),
        ] {
            let e = Metric::parse(name).unwrap_err();
            assert!(e.contains(says), "{name}: {e}");
        }
    }
}
