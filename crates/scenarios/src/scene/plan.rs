//! How a scene is run: the options a caller gives ([`RunOptions`]: integrator, step or
//! tolerance, horizon, cadence, output times) and the plan they resolve to against a scene
//! ([`RunPlan`]: the method's registry entry, the kind of problem chosen, the driver's
//! settings), with the checks of the step and the horizon.

use tumble_integrators::registry::{self, MethodInfo};
use tumble_integrators::{Driver, ProblemKind};

use super::SceneInfo;
use crate::error::SceneError;

/// The tolerance of an adaptive method when none is given: every built-in scene's default run
/// is then within 1e-9 of its reference at its default horizon (`default_runs_are_accurate`).
pub const DEFAULT_TOLERANCE: f64 = 1e-12;

/// Fixed step or error tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepControl {
    /// Fixed step `h` (s).
    Fixed(f64),
    /// Adaptive step with `rtol = atol = tol`.
    Tolerance(f64),
}

impl StepControl {
    /// `(dt, tol)` as records, manifests and keyword arguments name them: the fixed step or the
    /// tolerance, the other `None`.
    #[must_use]
    pub const fn dt_tol(self) -> (Option<f64>, Option<f64>) {
        match self {
            StepControl::Fixed(h) => (Some(h), None),
            StepControl::Tolerance(t) => (None, Some(t)),
        }
    }

    /// The step control of `dt` (a fixed step) or `tol` (a tolerance), the inverse of
    /// [`StepControl::dt_tol`]: `None` when neither is given.
    ///
    /// # Errors
    /// [`DtAndTol`] when both are given.
    pub const fn from_dt_tol(dt: Option<f64>, tol: Option<f64>) -> Result<Option<Self>, DtAndTol> {
        match (dt, tol) {
            (Some(_), Some(_)) => Err(DtAndTol),
            (Some(h), None) => Ok(Some(StepControl::Fixed(h))),
            (None, Some(t)) => Ok(Some(StepControl::Tolerance(t))),
            (None, None) => Ok(None),
        }
    }
}

/// Both a fixed step and a tolerance were given where one of them is expected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("dt and tol: give one (a fixed step, or a tolerance for an adaptive integrator)")]
pub struct DtAndTol;

/// Which states a run observes: computes a row of (coordinates, rates, diagnostics) for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Observe {
    /// Every step: rows every `every` steps, and the energy error over every step (the default).
    #[default]
    EveryStep,
    /// Only the initial and the final state, for timing a method (the work–precision report):
    /// the diagnostics of a row (energy, angular momentum, the exact solution's error) can
    /// cost as much as a step. [`RunSummary::max_energy_rel_err`] is then the error at the
    /// final time only.
    Ends,
}

/// How to run a scene; `None` fields take the scene's defaults.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunOptions {
    /// Integrator name from the registry.
    pub integrator: Option<String>,
    /// Step or tolerance.
    pub step: Option<StepControl>,
    /// Horizon (s).
    pub t_end: Option<f64>,
    /// Record every `every`-th step (≥ 1).
    pub every: Option<u64>,
    /// Rows at these times instead (from dense output), plus the final state.
    pub at: Option<Vec<f64>>,
    /// Rows every `output_dt` seconds from 0 instead (from dense output), plus the final state.
    pub output_dt: Option<f64>,
    /// Stop with [`tumble_integrators::Error::TooManySteps`] after this many steps.
    pub max_steps: Option<u64>,
    /// End the run early (status cancelled, `RunSummary::t` short of the horizon) once set.
    pub cancel: Option<CancelFlag>,
    /// Which states are observed.
    pub observe: Observe,
}

/// A flag that ends runs early when set (by a signal handler, a user interface), polled before
/// every step. Plans compare equal when they watch the same flag.
#[derive(Debug, Clone, Copy)]
pub struct CancelFlag(pub &'static std::sync::atomic::AtomicBool);

impl PartialEq for CancelFlag {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self.0, other.0)
    }
}

/// A validated run: the method (from the registry) and the kind of problem it integrates the
/// scene as, the step or tolerance, the horizon and the output cadence. Built once by
/// [`RunOptions::resolve`] and passed forward by reference; nothing validates it again.
#[derive(Debug, Clone, PartialEq)]
pub struct RunPlan {
    /// The method.
    pub method: &'static MethodInfo,
    /// The kind of problem the method integrates the scene as.
    pub kind: ProblemKind,
    /// Step or tolerance.
    pub step: StepControl,
    /// Horizon (s).
    pub t_end: f64,
    /// Output cadence.
    pub every: u64,
    /// Output times (rows there instead of every `every` steps), increasing, in `[0, t_end]`.
    pub times: Option<Vec<f64>>,
    /// Most steps a run may take.
    pub max_steps: u64,
    /// Ends the run early once set.
    pub cancel: Option<CancelFlag>,
    /// Wall-clock limit (s) of one run: beyond it the run fails with
    /// [`tumble_integrators::Error::TimeLimit`].
    pub deadline: Option<f64>,
    /// Which states are observed.
    pub observe: Observe,
}

impl RunPlan {
    /// The method's registry name.
    #[must_use]
    pub fn integrator(&self) -> &'static str {
        self.method.name
    }

    /// The same plan with another step or tolerance, checked as [`RunOptions::resolve`] checks
    /// one (a ladder's rungs).
    ///
    /// # Errors
    /// [`SceneError::InvalidOption`] for a step or tolerance the method cannot take.
    pub fn with_step(&self, step: StepControl) -> Result<Self, SceneError> {
        check_step(self.method, step, self.t_end)?;
        Ok(Self {
            step,
            ..self.clone()
        })
    }

    /// The same plan with each run limited to `seconds` of wall time.
    #[must_use]
    pub fn with_deadline(&self, seconds: f64) -> Self {
        Self {
            deadline: Some(seconds),
            ..self.clone()
        }
    }

    /// The same plan observing only the initial and final states.
    #[must_use]
    pub fn observing(&self, observe: Observe) -> Self {
        Self {
            observe,
            ..self.clone()
        }
    }

    /// The driver over `[0, t_end]` that calls the observer at every step, or (with
    /// [`Observe::Ends`]) only at the start and the end.
    pub(crate) fn driver(&self) -> Result<Driver<'_>, SceneError> {
        let mut driver = Driver::new(0.0, self.t_end)?.max_steps(self.max_steps);
        if let Some(CancelFlag(flag)) = self.cancel {
            driver = driver.cancel_flag(flag);
        }
        if let Some(seconds) = self.deadline {
            driver = driver.deadline(seconds)?;
        }
        if let Some(times) = &self.times {
            driver = driver.output_at(times)?;
        }
        Ok(match self.observe {
            Observe::EveryStep => driver,
            Observe::Ends => driver.every(u64::MAX)?,
        })
    }
}

impl RunOptions {
    /// Fills in `info`'s defaults and validates: the one place run options become a
    /// [`RunPlan`].
    ///
    /// # Errors
    /// [`SceneError::UnsupportedIntegrator`] or [`SceneError::InvalidOption`] for a
    /// non-positive, non-finite or larger-than-the-horizon step, a non-positive tolerance or
    /// horizon, or `every = 0`.
    pub fn resolve(&self, info: &SceneInfo) -> Result<RunPlan, SceneError> {
        let name = self
            .integrator
            .as_deref()
            .unwrap_or(info.default_integrator);
        let unsupported = || info.unsupported(name);
        let method = registry::find(name).map_err(|_| unsupported())?;
        let kind = info.kind_for(method).ok_or_else(unsupported)?;
        let adaptive = method.properties.adaptive;
        let t_end = self.t_end.unwrap_or(info.default_t_end);
        check_horizon(t_end)?;
        let step = match self.step {
            Some(s) => s,
            None if adaptive => StepControl::Tolerance(DEFAULT_TOLERANCE),
            None => StepControl::Fixed(info.default_step),
        };
        check_step(method, step, t_end)?;
        let every = self.every.unwrap_or(1);
        if every == 0 {
            return Err(SceneError::InvalidOption {
                option: "every",
                value: 0.0,
                reason: "must be at least 1".into(),
            });
        }
        let times = self.output_times(t_end)?;
        if times.is_some() && !method.properties.dense_output {
            let dense: Vec<&str> = info
                .integrators()
                .into_iter()
                .filter(|n| registry::find(n).is_ok_and(|m| m.properties.dense_output))
                .collect();
            return Err(SceneError::InvalidOption {
                option: if self.at.is_some() { "at" } else { "output_dt" },
                value: f64::NAN,
                reason: format!(
                    "`{}` has no dense output to give rows at chosen times; methods with dense \
                     output that run `{}`: {}",
                    method.name,
                    info.name,
                    dense.join(", ")
                ),
            });
        }
        Ok(RunPlan {
            method,
            kind,
            step,
            t_end,
            every,
            times,
            max_steps: self.max_steps.unwrap_or(u64::MAX),
            cancel: self.cancel,
            deadline: None,
            observe: self.observe,
        })
    }
}

impl RunOptions {
    /// The output times of `at` or `output_dt` over `[0, t_end]`, checked.
    fn output_times(&self, t_end: f64) -> Result<Option<Vec<f64>>, SceneError> {
        let bad = |option: &'static str, value: f64, reason: String| SceneError::InvalidOption {
            option,
            value,
            reason,
        };
        match (&self.at, self.output_dt) {
            (Some(_), Some(dt)) => Err(bad(
                "output_dt",
                dt,
                "`at` and `output_dt` are both given; choose one".into(),
            )),
            (Some(times), None) => {
                if times.is_empty() {
                    return Err(bad("at", f64::NAN, "no times given".into()));
                }
                let mut previous = f64::NEG_INFINITY;
                for &t in times {
                    if !(t.is_finite() && (0.0..=t_end).contains(&t)) {
                        return Err(bad("at", t, format!("outside [0, t_end = {t_end}]")));
                    }
                    if t == previous {
                        return Err(bad("at", t, "given twice".into()));
                    }
                    if t < previous {
                        return Err(bad(
                            "at",
                            t,
                            format!("comes after {previous}: times must increase"),
                        ));
                    }
                    previous = t;
                }
                Ok(Some(times.clone()))
            }
            (None, Some(dt)) => {
                if !(dt.is_finite() && dt > 0.0 && dt <= t_end) {
                    return Err(bad(
                        "output_dt",
                        dt,
                        format!("must be positive and at most the horizon t_end = {t_end}"),
                    ));
                }
                let n = (t_end / dt * (1.0 + 1e-12)).floor();
                if n > 1e8 {
                    return Err(bad(
                        "output_dt",
                        dt,
                        format!("{n:e} rows: more than 10^8; give a larger interval"),
                    ));
                }
                // k·dt, not repeated sums (no accumulated rounding); the final state is
                // written anyway.
                Ok(Some(
                    (0..=n as u64).map(|k| (k as f64 * dt).min(t_end)).collect(),
                ))
            }
            (None, None) => Ok(None),
        }
    }
}

/// Checks a horizon: finite and positive.
///
/// # Errors
/// [`SceneError::InvalidOption`] naming `t_end`.
pub fn check_horizon(t_end: f64) -> Result<(), SceneError> {
    if t_end.is_finite() && t_end > 0.0 {
        Ok(())
    } else {
        Err(SceneError::InvalidOption {
            option: "t_end",
            value: t_end,
            reason: "the horizon must be finite and positive".into(),
        })
    }
}

/// Checks a step or tolerance for `method` over `[0, t_end]`: finite and positive, a step no
/// larger than the horizon, a tolerance only for an adaptive method and a step only for a
/// fixed-step one.
fn check_step(method: &MethodInfo, step: StepControl, t_end: f64) -> Result<(), SceneError> {
    let integrator = method.name;
    let adaptive = method.properties.adaptive;
    match step {
        StepControl::Fixed(h) => {
            if !(h.is_finite() && h > 0.0) {
                return Err(SceneError::InvalidOption {
                    option: "dt",
                    value: h,
                    reason: "the step must be finite and positive".into(),
                });
            }
            if t_end / h > 1e15 {
                return Err(SceneError::InvalidOption {
                    option: "dt",
                    value: h,
                    reason: format!(
                        "{:.1e} steps over the horizon t_end = {t_end}: more than 10^15",
                        t_end / h
                    ),
                });
            }
            if h > t_end {
                return Err(SceneError::InvalidOption {
                    option: "dt",
                    value: h,
                    reason: format!("the step is larger than the horizon t_end = {t_end}"),
                });
            }
            if adaptive {
                return Err(SceneError::InvalidOption {
                    option: "dt",
                    value: h,
                    reason: format!("`{integrator}` is adaptive: give a tolerance instead"),
                });
            }
        }
        StepControl::Tolerance(tol) => {
            if !(tol > 0.0 && tol < 1.0) {
                return Err(SceneError::InvalidOption {
                    option: "tol",
                    value: tol,
                    reason: "the tolerance must lie strictly between 0 and 1 (it bounds the \
                             relative and absolute error of each step)"
                        .into(),
                });
            }
            if !adaptive {
                return Err(SceneError::InvalidOption {
                    option: "tol",
                    value: tol,
                    reason: format!("`{integrator}` has a fixed step: give a step instead"),
                });
            }
        }
    }
    Ok(())
}
