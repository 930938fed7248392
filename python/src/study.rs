//! `sweep`: a parameter sweep from a sweep file or a dict, into a folder, back as columns.

use std::path::PathBuf;
use std::sync::Mutex;

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use tumble_output::Destination;
use tumble_output::table::Values;
use tumble_scenarios::scene::CancelFlag;
use tumble_studies::simulation::{Naming, check_sweep_resolution};
use tumble_studies::sweep::{self as sweeps, Progress, RESULTS, RunConfig, Shard, SweepDefinition};

use crate::run::type_name;
use crate::{SimulationError, f64_bytes, interruptible, refused, value_error};

/// A Python value of a sweep dict as TOML; `key` is its dotted path, for messages.
fn toml_value(key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return v.extract::<i64>().map(toml::Value::Integer).map_err(|_| {
            PyValueError::new_err(format!("{key}: the integer does not fit in 64 bits"))
        });
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return toml_table(key, d).map(toml::Value::Table);
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v
            .try_iter()?
            .enumerate()
            .map(|(i, item)| toml_value(&format!("{key}[{i}]"), &item?))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // NumPy scalars and other numbers.
    if let Ok(x) = v.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    Err(PyTypeError::new_err(format!(
        "{key}: a sweep or model dict holds numbers, text, booleans, lists and tables (dicts); \
         got {}",
        type_name(v)
    )))
}

/// A key as TOML writes it: bare when it can be, else quoted.
fn toml_key(name: &str) -> String {
    if !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        name.to_string()
    } else {
        toml::Value::String(name.to_string()).to_string()
    }
}

/// Writes the dict `d` at the dotted table `path` (its TOML keys `keys`) into `out`, in the
/// dict's order: values as `key = value` (a dict of plain values inline), then dicts that hold
/// dicts as `[path.key]` tables. The root's dicts are all tables.
fn emit_table(
    path: &str,
    keys: &[String],
    d: &Bound<'_, PyDict>,
    out: &mut String,
) -> PyResult<()> {
    let mut tables = Vec::new();
    for (k, v) in d.iter() {
        let name: String = k.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "{}: keys are names (str), got {}",
                if path.is_empty() { "model" } else { path },
                type_name(&k)
            ))
        })?;
        let dotted = if path.is_empty() {
            name.clone()
        } else {
            format!("{path}.{name}")
        };
        if let Ok(sub) = v.cast::<PyDict>()
            && (path.is_empty() || sub.values().iter().any(|x| x.is_instance_of::<PyDict>()))
        {
            tables.push((dotted, name, sub.clone()));
            continue;
        }
        let value = toml_value(&dotted, &v)?;
        out.push_str(&format!("{} = {value}\n", toml_key(&name)));
    }
    for (dotted, name, sub) in tables {
        let mut inner = keys.to_vec();
        inner.push(toml_key(&name));
        out.push_str(&format!("\n[{}]\n", inner.join(".")));
        emit_table(&dotted, &inner, &sub, out)?;
    }
    Ok(())
}

/// The TOML text of a dict laid out like a TOML file (a model file), its keys in the dict's
/// order (a model's coordinates are its state in the order written): what `tumble.model_text`
/// returns.
#[pyfunction]
pub(crate) fn toml_text(table: &Bound<'_, PyDict>) -> PyResult<String> {
    let mut out = String::new();
    emit_table("", &[], table, &mut out)?;
    Ok(out)
}

/// A dict of a sweep as a TOML table.
fn toml_table(prefix: &str, d: &Bound<'_, PyDict>) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (k, v) in d.iter() {
        let name: String = k.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "{}: keys are names (str), got {}",
                if prefix.is_empty() { "sweep" } else { prefix },
                type_name(&k)
            ))
        })?;
        let key = if prefix.is_empty() {
            name.clone()
        } else {
            format!("{prefix}.{name}")
        };
        table.insert(name, toml_value(&key, &v)?);
    }
    Ok(table)
}

/// The sweep `definition` names: a sweep file's path, or a dict laid out as a sweep file.
fn definition(definition: &Bound<'_, PyAny>) -> PyResult<SweepDefinition> {
    if let Ok(d) = definition.cast::<PyDict>() {
        let text = toml::to_string(&toml_table("", d)?).map_err(refused)?;
        return SweepDefinition::parse(&text, "sweep dict", &[]).map_err(refused);
    }
    let path: PathBuf = definition.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "definition: expected a sweep file's path or a dict, got {}",
            type_name(definition)
        ))
    })?;
    SweepDefinition::load(&path, &[]).map_err(refused)
}

/// The result columns as `{name: (kind, payload)}`: `f64` and `i64` as native bytes (an
/// undefined metric as NaN), text as a list.
fn columns<'py>(
    py: Python<'py>,
    def: &SweepDefinition,
    rows: &[sweeps::PointRow],
) -> PyResult<Bound<'py, PyList>> {
    let table = sweeps::results_table(def, rows, Vec::new());
    let out = PyList::empty(py);
    for c in table.columns {
        let (kind, payload): (&str, Bound<'py, PyAny>) = match c.values {
            Values::F64(v) => ("f64", f64_bytes(py, &v).into_any()),
            Values::OptionalF64(v) => {
                let v: Vec<f64> = v.iter().map(|x| x.unwrap_or(f64::NAN)).collect();
                ("f64", f64_bytes(py, &v).into_any())
            }
            Values::I64(v) => {
                let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_ne_bytes()).collect();
                ("i64", pyo3::types::PyBytes::new(py, &bytes).into_any())
            }
            Values::Text(v) => ("str", PyList::new(py, v)?.into_any()),
        };
        out.append((c.name, kind, payload))?;
    }
    Ok(out)
}

/// Runs a sweep (see the Python docstring of `tumble.sweep`).
#[pyfunction]
#[pyo3(signature = (spec, threads=None, output=None, resume=false, allow_coarse_step=false,
    progress=None))]
pub(crate) fn sweep<'py>(
    py: Python<'py>,
    spec: &Bound<'py, PyAny>,
    threads: Option<usize>,
    output: Option<PathBuf>,
    resume: bool,
    allow_coarse_step: bool,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let def = definition(spec)?;
    if !allow_coarse_step {
        check_sweep_resolution(&def, Naming::Python).map_err(refused)?;
    }
    let threads = match threads {
        Some(0) => {
            return Err(PyValueError::new_err(
                "threads=0: at least one worker thread is needed",
            ));
        }
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, usize::from),
    };
    if resume && output.is_none() {
        return Err(PyValueError::new_err(
            "resume=True: give the output folder of the sweep to resume",
        ));
    }
    // Without an output folder the sweep's journal goes to a temporary folder, removed after.
    let scratch = match &output {
        Some(_) => None,
        None => Some(tempfile::tempdir().map_err(refused)?),
    };
    let dir = output
        .clone()
        .or_else(|| scratch.as_ref().map(|d| d.path().to_path_buf()))
        .unwrap_or_default();
    std::fs::create_dir_all(&dir)
        .map_err(|e| value_error(format!("{}: cannot create the folder: {e}", dir.display())))?;
    let results = Destination::check(&dir.join(RESULTS)).map_err(refused)?;
    let since = format!("{:?}", std::time::SystemTime::now());
    let _lock = tumble_output::FolderLock::acquire(&dir, &since, "tumble.sweep (Python)", false)
        .map_err(refused)?;

    let latest: Mutex<Option<Progress>> = Mutex::new(None);
    let mut shown: Option<Progress> = None;
    let report = interruptible(
        py,
        |flag| {
            let config = RunConfig {
                threads,
                shard: Shard::ALL,
                resume,
                cancel: Some(flag),
            };
            let mut cancellable = def.clone();
            cancellable.plan.cancel = Some(CancelFlag(flag));
            let mut on_progress = |p: &Progress| {
                if let Ok(mut l) = latest.lock() {
                    *l = Some(*p);
                }
            };
            sweeps::run(&cancellable, &dir, &config, &mut on_progress)
        },
        |_| {
            let now = latest.lock().ok().and_then(|l| *l);
            if let (Some(p), Some(callback)) = (now, &progress)
                && shown != now
            {
                shown = now;
                callback.call1((p.finished, p.total, p.failed))?;
            }
            Ok(())
        },
    )?;
    let report = report.map_err(|e| SimulationError::new_err(crate::message(&e)))?;
    if !report.complete() {
        return Err(SimulationError::new_err(format!(
            "{}: the sweep stopped with {} of {} points finished; run it again with resume=True",
            dir.display(),
            report.rows.len(),
            report.total
        )));
    }
    if output.is_some() {
        let csv = sweeps::results_csv(&def, &report.rows).map_err(refused)?;
        results.write_all(&csv).map_err(refused)?;
    }
    let out = PyDict::new(py);
    out.set_item("columns", columns(py, &def, &report.rows)?)?;
    out.set_item("scene", def.scene.info().name)?;
    out.set_item("origin", &def.origin)?;
    out.set_item("integrator", def.plan.integrator())?;
    out.set_item("points", report.total)?;
    out.set_item("computed", report.computed)?;
    out.set_item("resumed", report.resumed)?;
    out.set_item("failed", report.failures().count())?;
    out.set_item("threads", report.threads)?;
    out.set_item("seconds", report.elapsed.as_secs_f64())?;
    out.set_item("definition", def.to_toml())?;
    out.set_item("version", env!("CARGO_PKG_VERSION"))?;
    Ok(out)
}
