//! `tumble._tumble`: the native half of the `tumble` Python package.
//!
//! Every function calls the library code the command line calls (`tumble_studies::simulation`
//! to turn arguments into a validated run plan, the scenes' `simulate`, `tumble_studies::sweep`,
//! `tumble_studies::work_precision`, `tumble_inertia`), so a run from Python takes the same steps
//! and gives the same numbers, bit for bit, and a refused input the same reason. The Python half
//! (`pysrc/tumble/__init__.py`) turns the raw results into NumPy arrays and DataFrames.
//!
//! Long work runs on a worker thread with the GIL released ([`interruptible`]); the calling
//! thread wakes every [`POLL`] to let Python handle signals, so Ctrl-C raises
//! `KeyboardInterrupt` within about that time, after stopping the run at its next step.
//!
//! Errors: an input refused before any work raises `ValueError` (or `TypeError` for a value of
//! the wrong type), naming the argument or key; a run that fails raises
//! `tumble.SimulationError` with the command line's message (the time and state included).
//!
//! # Example
//!
//! Built and installed by `pip install ./python` (maturin); then, in Python, the spinning hoop's
//! `L_z` is conserved along the run, and the same run from the command line has the same
//! numbers to the last bit (`python/tests/test_simulate.py`):
//!
//! ```python
//! import numpy as np, tumble
//!
//! run = tumble.simulate("spinning-hoop", t_end=2.0)
//! assert np.allclose(run["Lz"], run["Lz"][0], rtol=1e-12, atol=0)
//! print(run.integrator, run.steps, run.max_energy_rel_err)
//! ```

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

mod body;
mod plot;
mod run;
mod study;

create_exception!(
    _tumble,
    SimulationError,
    PyRuntimeError,
    "A run that failed: a model or integration error, with the time and state it carries."
);

/// How often a waiting call lets Python handle signals (Ctrl-C) and report progress.
const POLL: Duration = Duration::from_millis(20);

/// A refused input as `ValueError`, with this message.
pub(crate) fn value_error(message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// A library error's message with its causes, `error: cause: cause`, as the command line
/// prints it.
pub(crate) fn message(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(cause) = source {
        text.push_str(": ");
        text.push_str(&cause.to_string());
        source = cause.source();
    }
    text
}

/// A library error refusing an input, as `ValueError` with the command line's message.
pub(crate) fn refused(e: impl std::error::Error) -> PyErr {
    PyValueError::new_err(message(&e))
}

/// `values` as native-endian bytes, for `numpy.frombuffer`.
pub(crate) fn f64_bytes<'py>(py: Python<'py>, values: &[f64]) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_ne_bytes()).collect();
    PyBytes::new(py, &bytes)
}

/// Runs `work` on a worker thread with the GIL released, while this thread wakes every
/// [`POLL`] to run Python's signal handlers and `tick` (progress). When either raises (Ctrl-C
/// raises `KeyboardInterrupt`), the flag `work` was given is set — the scenes and the sweep
/// engine poll it before every step and stop at the next one — the worker is joined and the
/// error returned.
///
/// The flag is a fresh one per call (so concurrent calls do not stop each other), leaked
/// because the scenes' cancel flag is a `&'static AtomicBool`: one byte a call.
pub(crate) fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&'static AtomicBool) -> T + Send,
    mut tick: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<T> {
    let flag: &'static AtomicBool = Box::leak(Box::new(AtomicBool::new(false)));
    std::thread::scope(|scope| {
        let (done, mut waiting) = mpsc::channel::<()>();
        let worker = scope.spawn(move || {
            let out = work(flag);
            let _ = done.send(());
            out
        });
        loop {
            let (state, rx) = py.detach(move || (waiting.recv_timeout(POLL), waiting));
            waiting = rx;
            if state != Err(RecvTimeoutError::Timeout) {
                break;
            }
            if let Err(e) = py.check_signals().and_then(|()| tick(py)) {
                flag.store(true, Ordering::Relaxed);
                let _ = py.detach(move || worker.join());
                return Err(e);
            }
        }
        let out = py.detach(move || worker.join());
        tick(py)?;
        out.map_err(|panic| {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| (*s).to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic without a message".to_string());
            PyRuntimeError::new_err(format!("internal error (a bug in tumble): {what}"))
        })
    })
}

/// The native module.
#[pymodule]
fn _tumble(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SimulationError", m.py().get_type::<SimulationError>())?;
    m.add_function(wrap_pyfunction!(run::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(plot::plot, m)?)?;
    m.add_function(wrap_pyfunction!(plot::plot_run, m)?)?;
    m.add_function(wrap_pyfunction!(run::work_precision, m)?)?;
    m.add_function(wrap_pyfunction!(run::scenes_json, m)?)?;
    m.add_function(wrap_pyfunction!(run::integrators_json, m)?)?;
    m.add_function(wrap_pyfunction!(study::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(study::toml_text, m)?)?;
    m.add_function(wrap_pyfunction!(body::inertia, m)?)?;
    Ok(())
}
