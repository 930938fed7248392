//! The scene abstraction: what a built-in scene documents, and how it is run.
//!
//! A [`Scene`] documents its coordinates, parameters (with defaults), conserved quantities and
//! test oracle ([`SceneInfo`]), and runs itself with a chosen integrator, step (or tolerance)
//! and horizon ([`RunOptions`]), handing rows of `t`, coordinates, rates and diagnostics to a
//! [`Recorder`] every `every` steps. Diagnostics (energy and its relative error, angular
//! momentum, hoop tilt) are computed on the fly; no trajectory is stored unless the recorder
//! stores it.

use nalgebra::SVector;
use tumble_integrators::registry::{self, MethodInfo};
use tumble_integrators::{
    DenseStep, Driver, Event, Flow, Observer, Ode, ProblemKind, SeparableHamiltonian, TaylorSystem,
};

use crate::dispatch;
use crate::error::SceneError;
use crate::params::{ParamSpec, Params};

/// What a scene documents.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneInfo {
    /// Name (`driven-hoop`).
    pub name: &'static str,
    /// One line: what it shows.
    pub summary: &'static str,
    /// Generalized coordinates in state order (CSV column names; rates add `_dot`).
    pub coordinates: &'static [&'static str],
    /// Parameters with defaults.
    pub parameters: &'static [ParamSpec],
    /// Conserved quantities.
    pub conserved: &'static [&'static str],
    /// The oracle its tests use.
    pub oracle: &'static str,
    /// The kinds of problem its model offers, most specific first: a method runs the scene
    /// when it integrates one of them (the first it shares is used), see [`Self::integrators`].
    pub problems: &'static [ProblemKind],
    /// Its runs locate events, so a method needs dense output to run it.
    pub needs_dense_output: bool,
    /// Default integrator.
    pub default_integrator: &'static str,
    /// Default fixed step (s) for fixed-step integrators (adaptive ones default to a tolerance of
    /// [`DEFAULT_TOLERANCE`]).
    pub default_step: f64,
    /// The error of the default run (integrator, step or tolerance, horizon) at the default
    /// parameters against the scene's reference, in the work–precision norm (measured by the
    /// test `default_runs_are_accurate`, which keeps this figure honest).
    pub default_error: f64,
    /// Default horizon (s).
    pub default_t_end: f64,
    /// Diagnostic columns after the coordinates and rates.
    pub diagnostics: &'static [&'static str],
    /// Names of the rate columns when they are not the coordinates' derivatives (a rotation is
    /// reported as a quaternion and its rates as the body angular velocity); empty: the
    /// coordinates with `_dot`.
    pub rate_names: &'static [&'static str],
}

impl SceneInfo {
    /// The CSV header: `t`, coordinates, rates (`_dot`, or [`Self::rate_names`]), diagnostics.
    #[must_use]
    pub fn columns(&self) -> Vec<String> {
        std::iter::once("t".to_string())
            .chain(self.coordinates.iter().map(|c| (*c).to_string()))
            .chain(if self.rate_names.is_empty() {
                self.coordinates
                    .iter()
                    .map(|c| format!("{c}_dot"))
                    .collect::<Vec<_>>()
            } else {
                self.rate_names.iter().map(|r| (*r).to_string()).collect()
            })
            .chain(self.diagnostics.iter().map(|d| (*d).to_string()))
            .collect()
    }

    /// The default parameters.
    #[must_use]
    pub fn default_params(&self) -> Params {
        Params::defaults(self.name, self.parameters)
    }

    /// The kind of problem `method` integrates this scene as, or `None` when it cannot run it
    /// (it shares no kind with the scene, or lacks the dense output the scene's events need).
    #[must_use]
    pub fn kind_for(&self, method: &MethodInfo) -> Option<ProblemKind> {
        if self.needs_dense_output && !method.properties.dense_output {
            return None;
        }
        self.problems
            .iter()
            .copied()
            .find(|k| method.problems.contains(k))
    }

    /// Every registry method that runs this scene, in registry order, but for the `TABLE:BASE`
    /// compositions ([`Self::compositions`]; the short names `lgvi4` …, `split4` … are listed).
    #[must_use]
    pub fn integrators(&self) -> Vec<&'static str> {
        registry::methods()
            .iter()
            .filter(|m| registry::composed(m.name).is_none() && self.kind_for(m).is_some())
            .map(|m| m.name)
            .collect()
    }
}

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

/// Receives the rows of a run: `t`, coordinates, rates, diagnostics.
pub trait Recorder {
    /// One row; return [`Flow::Stop`] to end the run early (e.g. after a write error).
    fn row(&mut self, values: &[f64]) -> Flow;

    /// Whether the recorder wants every step's rows as a continuous function of time
    /// ([`Recorder::dense_rows`]; methods with dense output only). The default is no.
    fn wants_dense_rows(&self) -> bool {
        false
    }

    /// The rows of the last step at any time in it, from the method's dense output: called
    /// after each step, before the row of the step's end (when [`Recorder::wants_dense_rows`]
    /// and the method has dense output). The default does nothing.
    fn dense_rows(&mut self, rows: &mut dyn DenseRows) -> Flow {
        let _ = rows;
        Flow::Continue
    }
}

/// The rows of one step at any time in it; see [`Recorder::dense_rows`].
pub trait DenseRows {
    /// `(t₀, t₁)` of the step.
    fn span(&self) -> (f64, f64);
    /// The row at `t ∈ [t₀, t₁]` (`t`, coordinates, rates, diagnostics), from dense output.
    fn row_at(&mut self, t: f64) -> &[f64];
}

/// [`DenseRows`] from a step's dense states and a scene's row function.
struct RowsView<'v, S, F> {
    step: &'v mut dyn DenseStep<S>,
    row: &'v mut F,
    buffer: &'v mut [f64],
}

impl<S, F: FnMut(f64, &S, &mut [f64])> DenseRows for RowsView<'_, S, F> {
    fn span(&self) -> (f64, f64) {
        self.step.span()
    }

    fn row_at(&mut self, t: f64) -> &[f64] {
        let state = self.step.state_at(t);
        (self.row)(t, state, self.buffer);
        self.buffer
    }
}

/// A recorder that keeps nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Discard;

impl Recorder for Discard {
    fn row(&mut self, _values: &[f64]) -> Flow {
        Flow::Continue
    }
}

/// A recorder that keeps every row in memory (for tests and small runs).
#[derive(Debug, Clone, Default)]
pub struct Rows(pub Vec<Vec<f64>>);

impl Recorder for Rows {
    fn row(&mut self, values: &[f64]) -> Flow {
        self.0.push(values.to_vec());
        Flow::Continue
    }
}

/// The final state of a run: its coordinates and rates.
#[derive(Debug, Clone, PartialEq)]
pub struct FinalState {
    /// Time reached.
    pub t: f64,
    /// Coordinates then rates, as the scene's CSV columns after `t`.
    pub values: Vec<f64>,
}

/// Summary of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// Time reached.
    pub t: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations (or steps of a method without one).
    pub evaluations: u64,
    /// Largest relative energy error `|E − E₀|/E_s` over every step.
    pub max_energy_rel_err: f64,
    /// Rows handed to the recorder.
    pub rows: u64,
    /// The run ended at a terminal event of the scene (the Coriolis drop's landing) before
    /// the horizon: its natural end, not a failure.
    pub terminated: bool,
}

/// A guide drawn over the map of a sweep of a scene: a line or curve the scene's physics says
/// the map's features follow.
#[derive(Debug, Clone, PartialEq)]
pub enum Guide {
    /// A vertical line at `x` (a critical value of the map's first axis).
    Vertical {
        /// Where.
        x: f64,
        /// Its label.
        label: String,
    },
    /// A curve through `points` (first axis, second axis).
    Curve {
        /// Its label.
        label: String,
        /// The points, in order.
        points: Vec<(f64, f64)>,
    },
}

/// The largest angle (rad) a fixed step may turn at the initial state's fastest rate
/// ([`Scene::initial_rate`]): about 12 steps a turn.
pub const MAX_ANGLE_PER_STEP: f64 = 0.5;

/// Which methods to use for one purpose on a scene, from measurements of its work–precision
/// (`tumble work-precision SCENE`, and `--long` for long horizons) at its default parameters.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Recommendation {
    /// What the run is for: a band of final-time error over the measured horizon, or a long
    /// horizon where the energy must not drift.
    pub purpose: &'static str,
    /// The methods, fastest first (registry names the scene runs).
    pub integrators: &'static [&'static str],
    /// The finest final-time error of the band at the default parameters and horizon, which
    /// the first method reaches (`None`: a purpose that is not an error band, such as a long
    /// horizon). The test `recommended_methods_reach_their_error_bands` holds it to that.
    pub finest_error: Option<f64>,
    /// The measurement behind it: times or errors of the methods and of DOP853 beside them.
    pub evidence: &'static str,
}

/// `purpose: method, method (evidence)`, the line `tumble scenes` prints.
impl std::fmt::Display for Recommendation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {} ({})",
            self.purpose,
            self.integrators.join(", "),
            self.evidence
        )
    }
}

/// A smaller model of a scene's motion, for runs that need only some of its columns (a sweep
/// whose every metric reads them): fewer numbers integrated for the same motion.
///
/// Its rows hold [`Reduction::columns`] (a subset of the scene's, `t` first, the energy and its
/// relative error among them) with the values the scene's own rows would hold for them; it
/// integrates with the scene's vector-space methods ([`ProblemKind::Ode`]) and runs plans
/// resolved for the scene.
#[derive(Debug)]
pub struct Reduction {
    /// Its name (`euler-poisson`), as a manifest states it.
    pub name: &'static str,
    /// What it integrates, in a line.
    pub summary: &'static str,
    /// The columns of its rows, in the scene's order.
    pub columns: &'static [&'static str],
    /// Runs it, as [`Scene::simulate`] runs the scene (rows of [`Reduction::columns`]).
    pub simulate: fn(&Params, &RunPlan, &mut dyn Recorder) -> Result<RunSummary, SceneError>,
}

impl Reduction {
    /// Whether it can run `plan`: the plan integrates the scene as a first-order system in a
    /// vector space, by a method for ODEs or by the Taylor method (the Lie-group methods
    /// integrate the full rotation).
    #[must_use]
    pub fn runs(&self, plan: &RunPlan) -> bool {
        matches!(plan.kind, ProblemKind::Ode | ProblemKind::TaylorSeries)
    }
}

/// A built-in scene.
pub trait Scene: Sync {
    /// Its documentation.
    fn info(&self) -> &'static SceneInfo;

    /// Runs it with a validated plan (from [`RunOptions::resolve`] on this scene's info).
    ///
    /// # Errors
    /// Invalid parameters, model failures and integration failures, each a [`SceneError`]
    /// saying what and where.
    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError>;

    /// Validates `options` into a plan, then runs it: for callers that hold raw options once
    /// (tests, one-off runs); a study that runs many points resolves once and calls
    /// [`Scene::simulate`].
    ///
    /// # Errors
    /// As [`RunOptions::resolve`] and [`Scene::simulate`].
    fn run(
        &self,
        params: &Params,
        options: &RunOptions,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        self.simulate(params, &options.resolve(self.info())?, recorder)
    }

    /// For a scene of a torque-free body whose flips about the intermediate principal axis can
    /// be counted: that axis in the body frame at `params` (the `flips` metric counts sign
    /// changes of `ω` along it). `None`: the scene has no such axis.
    ///
    /// # Errors
    /// (Inside the `Some`) invalid parameters, or principal moments without a strict middle one.
    fn intermediate_axis(
        &self,
        _params: &Params,
    ) -> Option<Result<nalgebra::Vector3<f64>, SceneError>> {
        None
    }

    /// The fastest angular rate (rad/s) of the initial state at `params` (an upper estimate:
    /// spin and relative rates added), against which a fixed step is judged: a step `h` with
    /// `h · rate` above [`MAX_ANGLE_PER_STEP`] does not resolve the motion
    /// ([`crate::StepResolution`]). `None`: the scene has no such rate. In each parameter, the
    /// others held, the rate must be largest at an end of any interval (built from `|x|`, `x²`,
    /// `1/x` of single parameters and monotone functions of them): a sweep judges only the
    /// corners of its axes.
    ///
    /// # Errors
    /// (Inside the `Some`) a parameter that is missing.
    fn initial_rate(&self, _params: &Params) -> Option<Result<f64, SceneError>> {
        None
    }

    /// Guides for the map of a sweep of this scene over the parameters `axes` (first axis
    /// horizontal, spanning `x_range`), the others fixed at `params`. Empty by default.
    fn map_guides(&self, _params: &Params, _axes: &[&str], _x_range: (f64, f64)) -> Vec<Guide> {
        Vec::new()
    }

    /// A smaller model of the same motion for runs that need only some columns
    /// ([`Reduction`]). `None` by default.
    fn reduction(&self) -> Option<&'static Reduction> {
        None
    }

    /// Which method to use, by purpose (accuracy band, long horizon), from the scene's measured
    /// work–precision. Empty by default (a scene that has not been measured).
    fn recommendations(&self) -> &'static [Recommendation] {
        &[]
    }

    /// Columns whose value the scene fixes by construction, whatever its parameters, each
    /// with the reason (the `tilt` of a hoop held vertical): metrics of them are refused, and
    /// a sweep's default metrics leave them out. Empty by default.
    fn fixed_columns(&self) -> &'static [(&'static str, &'static str)] {
        &[]
    }
}

/// The unit quaternion of a rotation matrix with its sign chosen continuous along a run (`q` and
/// `−q` are the same rotation): the first has `w ≥ 0`, each later one the sign closer to the
/// previous one, so that CSV columns and plots do not jump.
pub fn continuous_quaternion(
    rotation: &nalgebra::Matrix3<f64>,
    previous: &mut Option<nalgebra::Quaternion<f64>>,
) -> nalgebra::Quaternion<f64> {
    let q = tumble_kinematics::so3::rotation_to_quat(&nalgebra::Rotation3::from_matrix_unchecked(
        *rotation,
    ))
    .into_inner();
    let q = match previous {
        Some(p) if p.coords.dot(&q.coords) < 0.0 => -q,
        _ => q,
    };
    *previous = Some(q);
    q
}

/// The energy scale after a row: the largest of the scale so far, `|E₀|` and the row's
/// magnitude (see [`run_vector`]). A NaN magnitude leaves the scale as it was (the row's
/// non-finite value stops the run anyway).
#[must_use]
pub fn energy_scale(scale: f64, e0: f64, magnitude: f64) -> f64 {
    scale.max(e0.abs()).max(magnitude)
}

/// `|E − E₀| / scale`, or `|E − E₀|` when the scale is zero (no energy anywhere yet).
#[must_use]
pub fn relative_energy_error(e: f64, e0: f64, scale: f64) -> f64 {
    let change = (e - e0).abs();
    if scale > 0.0 { change / scale } else { change }
}

/// Observer that turns states (of any type) into rows, tracks the relative energy error at
/// every step, and hands rows to the recorder: every `every`-th step, or (when the plan has
/// output times) at exactly those times, from the method's dense output. The final state is
/// always written, whatever the cadence.
pub(crate) struct RowObserver<'a, S, F> {
    row: F,
    buffer: Vec<f64>,
    energy_column: usize,
    energy0: Option<f64>,
    /// The energy scale: the largest of `|E₀|` and the magnitudes the rows wrote so far.
    energy_scale: f64,
    max_rel: f64,
    every: u64,
    /// Rows at the plan's output times instead of every `every` steps.
    at_times: bool,
    count: u64,
    rows: u64,
    /// The row of the last observed step is in `buffer` and has not been written.
    pending: bool,
    /// Time of the last row written.
    last_written: f64,
    stopped: bool,
    /// The first row with a non-finite value, if any: the run stops there with
    /// [`SceneError::NonFiniteOutput`].
    non_finite: Option<SceneError>,
    /// Rows evaluated inside steps for [`Recorder::dense_rows`].
    dense_buffer: Vec<f64>,
    recorder: &'a mut dyn Recorder,
    state: std::marker::PhantomData<fn(&S)>,
}

impl<'a, S, F: FnMut(f64, &S, &mut [f64])> RowObserver<'a, S, F> {
    /// `row(t, state, out)` fills `columns` values; `energy_column` holds the energy and the
    /// column after it receives the relative energy error.
    pub(crate) fn new(
        columns: usize,
        energy_column: usize,
        plan: &RunPlan,
        row: F,
        recorder: &'a mut dyn Recorder,
    ) -> Self {
        RowObserver {
            row,
            buffer: vec![0.0; columns],
            energy_column,
            energy0: None,
            energy_scale: 0.0,
            max_rel: 0.0,
            every: plan.every,
            at_times: plan.times.is_some(),
            count: 0,
            rows: 0,
            pending: false,
            last_written: f64::NEG_INFINITY,
            stopped: false,
            non_finite: None,
            dense_buffer: vec![0.0; columns],
            recorder,
            state: std::marker::PhantomData,
        }
    }

    /// Fills `buffer` with the row of `(t, state)` and its relative energy error: the change
    /// of the energy since the first row over the energy scale (see [`run_vector`]).
    fn fill(&mut self, t: f64, state: &S) -> f64 {
        if let Some(slot) = self.buffer.get_mut(self.energy_column + 1) {
            *slot = 0.0;
        }
        (self.row)(t, state, &mut self.buffer);
        let e = self.buffer[self.energy_column];
        let e0 = *self.energy0.get_or_insert(e);
        let slot = self.buffer.get_mut(self.energy_column + 1);
        let magnitude = slot.as_deref().copied().unwrap_or(0.0).abs();
        self.energy_scale = energy_scale(self.energy_scale, e0, magnitude);
        let rel = relative_energy_error(e, e0, self.energy_scale);
        if let Some(slot) = slot {
            *slot = rel;
        }
        rel
    }

    /// Whether the row in `buffer` is finite; if not, the run stops with the error kept.
    fn finite(&mut self, t: f64) -> bool {
        let Some(column) = self.buffer.iter().position(|v| !v.is_finite()) else {
            return true;
        };
        self.non_finite = Some(SceneError::NonFiniteOutput {
            t,
            column,
            value: self.buffer[column],
            row: self.buffer.clone(),
        });
        self.stopped = true;
        false
    }

    fn write(&mut self, t: f64) -> Flow {
        self.rows += 1;
        self.last_written = t;
        let flow = self.recorder.row(&self.buffer);
        if flow == Flow::Stop {
            self.stopped = true;
        }
        flow
    }

    /// Writes the final state's row if the cadence skipped it, and returns the run's summary.
    ///
    /// # Errors
    /// [`SceneError::NonFiniteOutput`] if a row was not finite.
    pub(crate) fn summary(
        &mut self,
        outcome: &crate::dispatch::Outcome,
    ) -> Result<RunSummary, SceneError> {
        if let Some(e) = self.non_finite.take() {
            return Err(e);
        }
        let t = outcome.t;
        if self.pending && !self.stopped && t > self.last_written {
            self.write(t);
        }
        Ok(RunSummary {
            t,
            steps: outcome.steps,
            evaluations: outcome.evaluations,
            max_energy_rel_err: self.max_rel,
            rows: self.rows,
            terminated: outcome.terminated,
        })
    }
}

impl<S, F: FnMut(f64, &S, &mut [f64])> Observer<S> for RowObserver<'_, S, F> {
    fn observe(&mut self, t: f64, state: &S) -> Flow {
        let rel = self.fill(t, state);
        if !self.finite(t) {
            return Flow::Stop;
        }
        self.max_rel = self.max_rel.max(rel);
        let due = !self.at_times && self.count.is_multiple_of(self.every);
        self.count += 1;
        if due {
            self.pending = false;
            self.write(t)
        } else {
            self.pending = true;
            Flow::Continue
        }
    }

    fn output(&mut self, t: f64, state: &S) -> Flow {
        self.fill(t, state);
        if !self.finite(t) {
            return Flow::Stop;
        }
        self.write(t)
    }

    fn wants_dense_steps(&self) -> bool {
        self.recorder.wants_dense_rows()
    }

    fn dense_step(&mut self, step: &mut dyn DenseStep<S>) -> Flow {
        let mut view = RowsView {
            step,
            row: &mut self.row,
            buffer: &mut self.dense_buffer,
        };
        self.recorder.dense_rows(&mut view)
    }
}

/// Runs a first-order system ([`ProblemKind::Ode`]) with the plan's method through
/// [`dispatch::run_ode`], turning states into rows (with `events`, only methods with dense
/// output run it; a terminal event ends the run there).
///
/// `row(t, y, out)` writes a row (`t`, coordinates, rates, diagnostics; `out` has `columns`
/// entries); column `energy_column` must hold the energy `E = T + V`, and the one after it
/// the energy's magnitude at that state (below), which the observer replaces with the
/// relative energy error.
///
/// # The energy scale
///
/// `energy_rel_err` is `|E − E₀|` over the energy scale `E_s`: the largest of `|E₀|` and the
/// magnitudes of the rows so far. A row's magnitude is the kinetic energy `T` plus the
/// amplitude of the potential's terms: `m g a` for a bead on a hoop of radius `a`, `m g |ρ|`
/// for a body whose centre of mass is `ρ` from its pivot, `g |z|` and `½|ω × r|²` for a
/// mass in a rotating frame — the sizes of the terms whose round-off the computed `E`
/// carries. Where the energy is zero or nearly so while its terms are not (a bead released
/// level with the hoop's centre, a top released horizontally, a mass dropped from a height of
/// 1e-300 m), dividing by `|E₀|` alone reports round-off as a drift of order one or more;
/// over `E_s` it reads as the round-off it is. Where `E₀` dominates its terms the scale is
/// `|E₀|`, the usual relative error. A row that leaves the magnitude at 0 gets `|E₀|`.
pub fn run_vector<P, F, const S: usize>(
    problem: &P,
    y0: SVector<f64, S>,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    events: &mut [Event<'_, SVector<f64, S>>],
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    P: Ode<SVector<f64, S>>,
    F: FnMut(f64, &SVector<f64, S>, &mut [f64]),
{
    let mut y = y0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_ode(problem, &mut y, plan, events, &mut observer)?;
    observer.summary(&outcome)
}

/// Runs a system that computes its Taylor coefficients ([`ProblemKind::TaylorSeries`]) with the
/// plan's Taylor method through [`dispatch::run_taylor`], turning states into rows as
/// [`run_vector`] does.
#[allow(clippy::too_many_arguments)]
pub fn run_taylor_vector<P, F, const S: usize>(
    problem: &P,
    y0: SVector<f64, S>,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    events: &mut [Event<'_, SVector<f64, S>>],
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    P: TaylorSystem,
    F: FnMut(f64, &SVector<f64, S>, &mut [f64]),
{
    let mut y = y0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_taylor(problem, &mut y, plan, events, &mut observer)?;
    observer.summary(&outcome)
}

/// Runs a separable Hamiltonian ([`ProblemKind::Separable`], or [`ProblemKind::Split`] as its
/// drift and kick) with the plan's method through [`dispatch::run_separable`], from
/// `y0 = (q, p)`, turning states into rows as [`run_vector`] does.
pub fn run_hamiltonian<H, F, const S: usize>(
    model: &H,
    y0: SVector<f64, S>,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    H: SeparableHamiltonian,
    F: FnMut(f64, &SVector<f64, S>, &mut [f64]),
{
    let mut y = y0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_separable(model, &mut y, plan, &mut observer)?;
    observer.summary(&outcome)
}
