//! `simulate`, `work_precision`, and the catalogues of scenes and integrators.
//!
//! A run's record and a study's rows are handed to Python as the JSON of the same types the
//! command line writes (`tumble_studies::record::RunRecord`,
//! `tumble_studies::work_precision::Rung`), so their names cannot drift.

use std::time::Instant;

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tumble_integrators::Flow;
use tumble_output::Provenance;
use tumble_scenarios::scene::{CancelFlag, check_horizon};
use tumble_scenarios::{Recorder, SceneError, StepControl, scenes};
use tumble_studies::catalog;
use tumble_studies::error_estimate::{self, Tap, WrittenRows};
use tumble_studies::record::{Estimated, RunRecord, RunSetup};
use tumble_studies::simulation::{
    DEFAULT_ENERGY_WARN, Interruptible, LoadedScene, Naming, ParamOverride, RunRequest,
    failure_message, flag_words, load_scene, number,
};
use tumble_studies::work_precision::Rung;
use tumble_studies::work_precision::{self as ladders, Config};

use crate::{SimulationError, f64_bytes, interruptible, refused};

/// The rows of a run, column by column.
struct Columns(Vec<Vec<f64>>);

impl Recorder for Columns {
    fn row(&mut self, values: &[f64]) -> Flow {
        for (column, &v) in self.0.iter_mut().zip(values) {
            column.push(v);
        }
        Flow::Continue
    }
}

/// `params` (a dict of parameter names to numbers) as overrides, labelled `params['KEY']`.
fn overrides(params: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<ParamOverride>> {
    let Some(params) = params else {
        return Ok(Vec::new());
    };
    params
        .iter()
        .map(|(k, v)| {
            let key: String = k.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "params: keys are parameter names (str), got {}",
                    type_name(&k)
                ))
            })?;
            let value = number_of(&v).ok_or_else(|| {
                PyTypeError::new_err(format!(
                    "params['{key}']: expected a number, got {}",
                    type_name(&v)
                ))
            })?;
            Ok(ParamOverride {
                label: format!("params['{key}']"),
                key,
                value,
            })
        })
        .collect()
}

/// A Python value as a number: `int` or `float` (or a NumPy scalar), not `bool` or `str`.
pub(crate) fn number_of(v: &Bound<'_, PyAny>) -> Option<f64> {
    if v.is_instance_of::<pyo3::types::PyBool>() || v.is_instance_of::<pyo3::types::PyString>() {
        return None;
    }
    v.extract::<f64>().ok()
}

/// The name of a value's type, for messages.
pub(crate) fn type_name(v: &Bound<'_, PyAny>) -> String {
    v.get_type()
        .name()
        .map_or_else(|_| "?".to_string(), |n| n.to_string())
}

/// The provenance of a call: this extension's version; its build records no git commit.
fn provenance(threads: usize) -> Provenance {
    Provenance::now(env!("CARGO_PKG_VERSION"), "unknown", threads)
}

/// Runs a scene (see the Python docstring of `tumble.simulate`).
#[pyfunction]
#[pyo3(signature = (scene, params=None, integrator=None, dt=None, tol=None, t_end=None, at=None,
    every=None, output_dt=None, max_steps=tumble_studies::simulation::DEFAULT_MAX_STEPS, allow_coarse_step=false, check=true))]
pub(crate) fn simulate<'py>(
    py: Python<'py>,
    scene: &str,
    params: Option<&Bound<'py, PyDict>>,
    integrator: Option<String>,
    dt: Option<f64>,
    tol: Option<f64>,
    t_end: Option<f64>,
    at: Option<Vec<f64>>,
    every: Option<u64>,
    output_dt: Option<f64>,
    max_steps: u64,
    allow_coarse_step: bool,
    check: bool,
) -> PyResult<Bound<'py, PyDict>> {
    if usize::from(every.is_some()) + usize::from(at.is_some()) + usize::from(output_dt.is_some())
        > 1
    {
        return Err(PyValueError::new_err(
            "every, at, output_dt: give at most one (which rows to keep)",
        ));
    }
    let loaded = load_scene(scene, &overrides(params)?).map_err(refused)?;
    let request = RunRequest {
        integrator,
        step: StepControl::from_dt_tol(dt, tol).map_err(refused)?,
        t_end,
        every,
        at,
        output_dt,
        max_steps: Some(max_steps),
        allow_coarse_step,
        cancel: None,
    };
    let plan = loaded.plan(&request, Naming::Python).map_err(refused)?;
    let LoadedScene {
        scene,
        origin,
        params,
        frame,
        ..
    } = loaded;
    let info = scene.info();
    let columns = info.columns();
    let n = columns.len();
    let start = Instant::now();
    let (result, rows, wall_time_s, estimate) = interruptible(
        py,
        |flag| {
            let mut plan = plan.clone();
            plan.cancel = Some(CancelFlag(flag));
            let mut rows = Columns(vec![Vec::new(); n]);
            let mut written = WrittenRows::new(info);
            let result = if check {
                scene.simulate(
                    &params,
                    &plan,
                    &mut Tap {
                        inner: &mut rows,
                        rows: &mut written,
                    },
                )
            } else {
                scene.simulate(&params, &plan, &mut rows)
            };
            let wall_time_s = start.elapsed().as_secs_f64();
            // A cancelled companion is an interrupted call: `interruptible` raises
            // KeyboardInterrupt once the flag is set, whatever this returns.
            let estimate = match &result {
                Ok(summary) if check => {
                    match error_estimate::estimate(scene, &params, &plan, summary, &written) {
                        Ok(e) => Estimated::Done(e),
                        Err(reason) => Estimated::Failed(reason),
                    }
                }
                _ => Estimated::Off,
            };
            (result, rows.0, wall_time_s, estimate)
        },
        |_| Ok(()),
    )?;
    let summary = result.map_err(|e| SimulationError::new_err(failure_message(info, &e)))?;
    let record = RunRecord::new(
        provenance(1),
        &RunSetup {
            info,
            origin: &origin,
            frame: frame.as_deref(),
            params: &params,
            plan: &plan,
        },
        &summary,
        &estimate,
        DEFAULT_ENERGY_WARN,
        String::new(),
        wall_time_s,
    );
    let out = PyDict::new(py);
    out.set_item("record", serde_json::to_string(&record).map_err(refused)?)?;
    // The record's parameters are a map (sorted by name); the scene declares an order, which
    // figures and listings keep.
    let order: Vec<&str> = params.iter().map(|(name, _)| name).collect();
    out.set_item("parameter_order", order)?;
    let data: Vec<f64> = rows.concat();
    out.set_item("data", f64_bytes(py, &data))?;
    out.set_item("coordinates", info.coordinates)?;
    out.set_item("rates", tumble_studies::simulation::rate_columns(info))?;
    Ok(out)
}

/// `tumble scenes --json`, as text.
#[pyfunction]
pub(crate) fn scenes_json() -> PyResult<String> {
    let entries = scenes::builtin()
        .iter()
        .map(|s| catalog::entry(*s))
        .collect::<Result<Vec<_>, _>>()
        .map_err(refused)?;
    serde_json::to_string(&entries).map_err(refused)
}

/// `tumble integrators --json`, as text.
#[pyfunction]
pub(crate) fn integrators_json() -> PyResult<String> {
    serde_json::to_string(&tumble_studies::catalog::integrators()).map_err(refused)
}

/// Work–precision ladders (see the Python docstring of `tumble.work_precision`).
#[pyfunction]
#[pyo3(signature = (scene, params=None, integrators=None, t_end=None, max_seconds=Config::DEFAULT_MAX_RUN_SECONDS))]
pub(crate) fn work_precision<'py>(
    py: Python<'py>,
    scene: &str,
    params: Option<&Bound<'py, PyDict>>,
    integrators: Option<Vec<String>>,
    t_end: Option<f64>,
    max_seconds: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let loaded = load_scene(scene, &overrides(params)?).map_err(refused)?;
    let info = loaded.scene.info();
    let integrators = integrators.unwrap_or_else(|| {
        info.integrators()
            .iter()
            .map(|s| (*s).to_string())
            .collect()
    });
    for name in &integrators {
        if !info.runs(name) {
            return Err(PyValueError::new_err(format!(
                "integrators: `{name}` cannot run scene `{}`; applicable: {}",
                info.name,
                info.integrators().join(", ")
            )));
        }
    }
    if !(max_seconds.is_finite() && max_seconds > 0.0) {
        return Err(PyValueError::new_err(format!(
            "max_seconds={}: must be finite and positive",
            number(max_seconds)
        )));
    }
    let t_end = t_end.or(loaded.run.t_end).unwrap_or(info.default_t_end);
    check_horizon(t_end).map_err(|e| {
        PyValueError::new_err(format!("{}: {}", info.name, flag_words(&e, Naming::Python)))
    })?;
    let mut config = Config::new(info);
    config.t_end = t_end;
    config.max_run_seconds = max_seconds;
    config.max_reference_seconds = Config::REFERENCE_FACTOR * max_seconds;
    let (scene, params) = (loaded.scene, loaded.params);
    let outcome = interruptible(
        py,
        |flag| {
            let scene = Interruptible { scene, flag };
            let reference = ladders::reference_within(
                &scene,
                &params,
                t_end,
                Some(config.max_reference_seconds),
            )
            .map_err(|e| format!("{}: the reference run failed: {e}", info.name))?;
            let mut ladders = Vec::new();
            for name in &integrators {
                let ladder = ladders::ladder(
                    &scene,
                    &params,
                    name,
                    &reference.state,
                    &config,
                    &mut |_| {},
                )
                .map_err(|e: SceneError| format!("{}: {name}: {e}", info.name))?;
                ladders.push(ladder);
            }
            Ok::<_, String>((reference, ladders))
        },
        |_| Ok(()),
    )?;
    let (reference, ladders) = outcome.map_err(SimulationError::new_err)?;
    let out = PyDict::new(py);
    out.set_item("scene", info.name)?;
    out.set_item("t_end", t_end)?;
    out.set_item("reference", &reference.method)?;
    out.set_item("cross_check", &reference.check)?;
    out.set_item("agreement", reference.agreement)?;
    out.set_item("columns", Rung::COLUMNS.to_vec())?;
    let rungs = serde_json::to_string(&Rung::of(&ladders)).map_err(refused)?;
    out.set_item("rungs", rungs)?;
    let stops = PyDict::new(py);
    for l in &ladders {
        stops.set_item(&l.integrator, &l.stop)?;
    }
    out.set_item("stopped", stops)?;
    Ok(out)
}
