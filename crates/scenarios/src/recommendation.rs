//! Which method for what on a built-in scene, and the measurements behind it.
//!
//! A scene declares its [`Recommendation`]s in code: the purpose, the methods, what is measured
//! ([`Measure`]: the time to a final-time error, or the energy error of a long run), the methods
//! measured beside them for comparison, and the reason when it is a property of the method and
//! the model rather than a measurement (an exact flow, a conserved momentum map).
//!
//! The numbers are data: `tumble work-precision SCENE --recommend FILE` measures them and
//! writes them, with the command, date, version and machine that produced them
//! ([`Provenance`]), into `data/recommendations.toml` in this crate, which is embedded at build
//! time ([`measurements`]) and printed by `tumble scenes`. The test
//! `embedded_measurements_cover_every_recommendation` holds the file to the scenes'
//! recommendations.

use std::sync::LazyLock;

use serde::{Deserialize, Serialize};

/// Which methods to use for one purpose on a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Recommendation {
    /// What the run is for: a band of final-time error over the default horizon, or a long
    /// horizon where the energy must not drift.
    pub purpose: &'static str,
    /// The methods, fastest first (registry names the scene runs).
    pub integrators: &'static [&'static str],
    /// What is measured for it.
    pub measure: Measure,
    /// Methods measured beside [`Recommendation::integrators`] for comparison (registry names
    /// the scene runs).
    pub compared_with: &'static [&'static str],
    /// Why, where it is a property of the method and the model rather than a measurement
    /// (empty when the measurements say it all).
    pub reason: &'static str,
}

/// What a [`Recommendation`] is measured by.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measure {
    /// The wall time each method takes to reach this final-time error over the scene's default
    /// horizon at its default parameters (the band's finest error, which the first method
    /// reaches: the test `recommended_methods_reach_their_error_bands` holds it to that).
    ToError(f64),
    /// The relative energy error of each method over a long run at the scene's default step
    /// (an adaptive method at [`LONG_RUN_TOLERANCE`]).
    LongRun,
    /// Nothing: the reason says why (a closed-form solution).
    Nothing,
}

/// The tolerance of an adaptive method in a [`Measure::LongRun`].
pub const LONG_RUN_TOLERANCE: f64 = 1e-13;

impl Recommendation {
    /// The band's finest error ([`Measure::ToError`]), if it is an error band.
    #[must_use]
    pub fn finest_error(&self) -> Option<f64> {
        match self.measure {
            Measure::ToError(e) => Some(e),
            Measure::LongRun | Measure::Nothing => None,
        }
    }

    /// The methods measured for it: its own, then those compared with them.
    pub fn measured_methods(&self) -> impl Iterator<Item = &'static str> {
        let (own, compared) = (self.integrators, self.compared_with);
        own.iter().chain(compared).copied()
    }
}

/// The measurements behind the built-in scenes' recommendations, as written by
/// `tumble work-precision SCENE --recommend FILE`: one entry per measured scene, in the order
/// of `scenes::builtin()`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Measurements {
    /// The scenes.
    #[serde(default, rename = "scene")]
    pub scenes: Vec<SceneMeasurements>,
}

/// The measurements of one scene at its default parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneMeasurements {
    /// The scene.
    pub name: String,
    /// What measured them, where and when.
    pub provenance: Provenance,
    /// Horizon of the error bands (s): the scene's default.
    pub t_end: f64,
    /// The reference the final-time errors are measured against (`exact`, `gauss12 dt = …`).
    pub reference: String,
    /// The error bands, in the order of the scene's recommendations.
    #[serde(default, rename = "band")]
    pub bands: Vec<Band>,
    /// The long runs, in the order of the scene's recommendations.
    #[serde(default, rename = "long")]
    pub long_runs: Vec<LongRuns>,
}

/// How a measurement was made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    /// The command line.
    pub command: String,
    /// `tumble` version.
    pub tumble_version: String,
    /// Git commit the binary was built from (`-dirty` with uncommitted changes).
    pub git_commit: String,
    /// When the command started (UTC, RFC 3339).
    pub date: String,
    /// CPU model.
    pub cpu: String,
    /// Logical cores the machine offered the process.
    pub cores: usize,
    /// The one-minute load average when the measurement started (Linux; a load near or above
    /// `cores` means other work shared the machine).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub load_average: Option<f64>,
}

/// The time each method takes to reach a final-time error.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Band {
    /// The recommendation's purpose.
    pub purpose: String,
    /// The error reached.
    pub target_error: f64,
    /// The recommended methods, then those compared with them.
    #[serde(rename = "method")]
    pub methods: Vec<TimeToError>,
}

/// One method of a [`Band`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeToError {
    /// The method.
    pub integrator: String,
    /// Wall time (s) to the target error, interpolated log–log between the ladder's rungs
    /// (none: the ladder never reached it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seconds: Option<f64>,
    /// Right-hand-side evaluations to the target error, interpolated likewise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub evaluations: Option<f64>,
    /// The smallest final-time error of its ladder.
    pub best_error: f64,
}

/// The energy error of each method over a long run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LongRuns {
    /// The recommendation's purpose.
    pub purpose: String,
    /// Steps of the scene's default step: the horizon is `steps × dt`.
    pub steps: u64,
    /// The scene's default step (s).
    pub dt: f64,
    /// The recommended methods, then those compared with them.
    #[serde(rename = "method")]
    pub methods: Vec<LongRun>,
}

/// One method of [`LongRuns`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LongRun {
    /// The method.
    pub integrator: String,
    /// Its step (`dt = 1.000e-2`) or tolerance (`tol = 1.0e-13`).
    pub control: String,
    /// The largest relative energy error over the run (none: the run failed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_energy_rel_err: Option<f64>,
    /// The exponent `a` of the error's growth as `t^a` over the last decades (none: too few
    /// points, or an error at round-off throughout).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub growth: Option<f64>,
    /// Wall time of the run (s).
    pub seconds: f64,
    /// Why it failed, if it did.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failed: Option<String>,
}

/// The measurements file, as embedded at build time.
pub const MEASUREMENTS_TOML: &str = include_str!("../data/recommendations.toml");

static EMBEDDED: LazyLock<Result<Measurements, String>> =
    LazyLock::new(|| Measurements::parse(MEASUREMENTS_TOML));

/// The embedded measurements ([`MEASUREMENTS_TOML`]); an error if the file does not parse,
/// which the test `embedded_measurements_cover_every_recommendation` rules out.
///
/// # Errors
/// The embedded file does not parse (its message).
pub fn measurements() -> Result<&'static Measurements, &'static str> {
    EMBEDDED.as_ref().map_err(String::as_str)
}

impl Measurements {
    /// Parses a measurements file.
    ///
    /// # Errors
    /// Not TOML of this layout (the parser's message).
    pub fn parse(text: &str) -> Result<Self, String> {
        toml::from_str(text).map_err(|e| e.to_string())
    }

    /// The file's text.
    ///
    /// # Errors
    /// A value TOML cannot hold (the serializer's message).
    pub fn to_toml(&self) -> Result<String, String> {
        toml::to_string_pretty(self).map_err(|e| e.to_string())
    }

    /// The measurements of the scene `name`.
    #[must_use]
    pub fn scene(&self, name: &str) -> Option<&SceneMeasurements> {
        self.scenes.iter().find(|s| s.name == name)
    }

    /// Puts `scene` in place of the entry of the same name, or adds it; the entries are then
    /// ordered as `order` names them (names it does not list last, in their order).
    pub fn replace(&mut self, scene: SceneMeasurements, order: &[&str]) {
        match self.scenes.iter_mut().find(|s| s.name == scene.name) {
            Some(old) => *old = scene,
            None => self.scenes.push(scene),
        }
        let rank = |name: &str| order.iter().position(|n| *n == name).unwrap_or(order.len());
        self.scenes.sort_by_key(|s| rank(&s.name));
    }
}

impl SceneMeasurements {
    /// The error band measured for `purpose`.
    #[must_use]
    pub fn band(&self, purpose: &str) -> Option<&Band> {
        self.bands.iter().find(|b| b.purpose == purpose)
    }

    /// The long runs measured for `purpose`.
    #[must_use]
    pub fn long_run(&self, purpose: &str) -> Option<&LongRuns> {
        self.long_runs.iter().find(|l| l.purpose == purpose)
    }
}
