//! The catalogue of built-in scenes as `tumble scenes --json` prints it and `tumble.scenes()`
//! returns it: coordinates, columns, parameters, conserved quantities, oracle, applicable
//! integrators and the default run (the scene's options resolved: a fixed step `default_dt`
//! or a tolerance `default_tol`, depending on the default integrator); and the registry's
//! integrators as `tumble integrators --json` prints them and `tumble.integrators()` returns
//! them, each with the built-in scenes it runs.

use serde::Serialize;
use tumble_integrators::registry::{MethodInfo, methods};
use tumble_scenarios::recommendation::{
    Band, LongRuns, Provenance, SceneMeasurements, measurements,
};
use tumble_scenarios::scenes::builtin;
use tumble_scenarios::{Recommendation, RunOptions, Scene, SceneError};

/// A registry entry with the built-in scenes it runs (`tumble integrators --json`,
/// `tumble.integrators()`).
#[derive(Debug, Clone, Serialize)]
pub struct IntegratorEntry {
    /// The registry's entry: name, order, family, properties, stages, problem kinds, summary.
    #[serde(flatten)]
    pub info: &'static MethodInfo,
    /// The built-in scenes it runs, in `tumble scenes` order.
    pub scenes: Vec<&'static str>,
}

/// Every registry entry with the built-in scenes it runs.
#[must_use]
pub fn integrators() -> Vec<IntegratorEntry> {
    methods()
        .iter()
        .map(|info| IntegratorEntry {
            info,
            scenes: scenes_running(info),
        })
        .collect()
}

/// The built-in scenes `method` runs, in `tumble scenes` order.
#[must_use]
pub fn scenes_running(method: &MethodInfo) -> Vec<&'static str> {
    builtin()
        .iter()
        .map(|s| s.info())
        .filter(|info| info.runs(method.name))
        .map(|info| info.name)
        .collect()
}

/// One parameter of a scene.
#[derive(Debug, Clone, Serialize)]
pub struct Parameter {
    /// Name.
    pub name: &'static str,
    /// Default value.
    pub default: f64,
    /// Unit.
    pub unit: &'static str,
    /// Allowed values, in words.
    pub domain: String,
    /// What it is.
    pub description: &'static str,
}

/// One scene in the catalogue (`tumble scenes --json`, `tumble.scenes()`); field order is the
/// documented key order.
#[derive(Debug, Clone, Serialize)]
pub struct Entry {
    /// Name.
    pub name: &'static str,
    /// One line.
    pub summary: &'static str,
    /// Generalized coordinates.
    pub coordinates: &'static [&'static str],
    /// Trajectory columns.
    pub columns: Vec<String>,
    /// Parameters.
    pub parameters: Vec<Parameter>,
    /// Conserved quantities.
    pub conserved: &'static [&'static str],
    /// The independent truth its runs are checked against.
    pub oracle: &'static str,
    /// Problem kinds it offers integrators.
    pub problems: Vec<&'static str>,
    /// Applicable integrators.
    pub integrators: Vec<&'static str>,
    /// Its symmetric order-2 base methods, which a composition table composes as `TABLE:BASE`.
    pub composition_bases: Vec<&'static str>,
    /// Integrator of the default run.
    pub default_integrator: &'static str,
    /// Error of the default run against the reference.
    pub default_error: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    /// Default fixed step (fixed-step default integrator).
    pub default_dt: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    /// Default tolerance (adaptive default integrator).
    pub default_tol: Option<f64>,
    /// Default horizon (s).
    pub default_t_end: f64,
    /// Which methods to use, by purpose, with the measurements behind them.
    pub recommended: Vec<Recommended>,
    /// How the measurements were made (command, version, date, machine), if they were.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured_by: Option<&'static Provenance>,
    /// The reference the measured errors are taken against.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured_against: Option<&'static str>,
}

/// A scene's recommendation for one purpose with its measurements (the embedded
/// `tumble_scenarios::recommendation::measurements`).
#[derive(Debug, Clone, Serialize)]
pub struct Recommended {
    /// What the run is for.
    pub purpose: &'static str,
    /// The methods, fastest first.
    pub integrators: &'static [&'static str],
    /// The band's finest error, which the first method reaches (an error band).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finest_error: Option<f64>,
    /// Methods measured beside them for comparison.
    pub compared_with: &'static [&'static str],
    /// Why, where it is a property of the method and the model (empty: the measurements say it).
    pub reason: &'static str,
    /// Each method's time to the band's finest error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub to_error: Option<&'static Band>,
    /// Each method's energy error over a long run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub long_run: Option<&'static LongRuns>,
}

/// `scene`'s recommendations joined with its embedded measurements, and those measurements.
fn recommended(scene: &dyn Scene) -> (Vec<Recommended>, Option<&'static SceneMeasurements>) {
    let measured = measurements().ok().and_then(|m| m.scene(scene.info().name));
    let list = scene
        .recommendations()
        .iter()
        .map(|r: &Recommendation| Recommended {
            purpose: r.purpose,
            integrators: r.integrators,
            finest_error: r.finest_error(),
            compared_with: r.compared_with,
            reason: r.reason,
            to_error: measured.and_then(|m| m.band(r.purpose)),
            long_run: measured.and_then(|m| m.long_run(r.purpose)),
        })
        .collect();
    (list, measured)
}

/// The catalogue entry of a scene.
///
/// # Errors
/// The scene's own default options do not resolve (a bug in the scene).
pub fn entry(scene: &dyn Scene) -> Result<Entry, SceneError> {
    let info = scene.info();
    let resolved = RunOptions::default().resolve(info)?;
    let (recommended, measured) = recommended(scene);
    let (default_dt, default_tol) = resolved.step.dt_tol();
    Ok(Entry {
        name: info.name,
        summary: info.summary,
        coordinates: info.coordinates,
        columns: info.columns(),
        parameters: info
            .parameters
            .iter()
            .map(|p| Parameter {
                name: p.name,
                default: p.default,
                unit: p.unit,
                domain: p.domain.to_string(),
                description: p.description,
            })
            .collect(),
        conserved: info.conserved,
        oracle: info.oracle,
        problems: info.problems.iter().map(|k| k.name()).collect(),
        integrators: info.integrators(),
        composition_bases: info.composition_bases(),
        default_integrator: info.default_integrator,
        default_error: info.default_error,
        default_dt,
        default_tol,
        default_t_end: resolved.t_end,
        recommended,
        measured_by: measured.map(|m| &m.provenance),
        measured_against: measured.map(|m| m.reference.as_str()),
    })
}
