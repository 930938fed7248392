//! Command-line overrides of a sweep definition's keys (`--set KEY=VALUE`), applied to the
//! draft before validation.

/// A command-line override of one key of a sweep definition (`--set KEY=VALUE`).
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    /// The key: a scene parameter (`omega0` or `parameters.omega0`), `run.integrator`,
    /// `run.dt` or `run.tol` (each clears the other), `run.t_end`, `metrics.tilt_threshold`,
    /// `random.samples`, `random.seed`, or `axes.NAME.count`, `axes.NAME.start`,
    /// `axes.NAME.end`, `axes.NAME.spacing` (`linear`, `log`), `axes.NAME.values` (a list),
    /// `refine.levels`, `refine.metric` (a name), `refine.threshold`.
    pub key: String,
    /// The value.
    pub value: OverrideValue,
    /// As typed, for messages (`run.dt=5e-3`).
    pub text: String,
}

/// The value of an [`Override`].
#[derive(Debug, Clone, PartialEq)]
pub enum OverrideValue {
    /// A number (or an angle expression, evaluated).
    Number(f64),
    /// A name (`run.integrator`, `axes.NAME.spacing`).
    Text(String),
    /// A list of numbers (`axes.NAME.values=[0.5, 1, pi/2]`).
    List(Vec<f64>),
}

impl Override {
    /// Whether `key` takes a name rather than a number.
    #[must_use]
    pub fn takes_text(key: &str) -> bool {
        key == "run.integrator"
            || key == "refine.metric"
            || (key.starts_with("axes.") && key.ends_with(".spacing"))
    }

    /// Whether `key` takes a list of numbers.
    #[must_use]
    pub fn takes_list(key: &str) -> bool {
        key.starts_with("axes.") && key.ends_with(".values")
    }
}
