//! The scene abstraction: what a built-in scene documents, and how it is run.
//!
//! A [`Scene`] documents its coordinates, parameters (with defaults), conserved quantities and
//! test oracle ([`SceneInfo`]), and runs itself with a chosen integrator, step (or tolerance)
//! and horizon ([`RunOptions`]), handing rows of `t`, coordinates, rates and diagnostics to a
//! [`Recorder`] every `every` steps. Diagnostics (energy and its relative error, angular
//! momentum, hoop tilt) are computed on the fly; no trajectory is stored unless the recorder
//! stores it.

use tumble_integrators::registry::{self, MethodInfo};
use tumble_integrators::{DenseStep, Flow, ProblemKind};

use crate::drawing::{Drawing, Placed};
use crate::error::SceneError;
use crate::params::{ParamSpec, Params};
pub use crate::recommendation::Recommendation;
pub use crate::scenes::euler_poisson::lanes::TiltRun;

mod plan;
mod rows;

pub use plan::{
    CancelFlag, DEFAULT_TOLERANCE, DtAndTol, Observe, RunOptions, RunPlan, StepControl,
    check_horizon,
};
pub(crate) use rows::RowObserver;
pub use rows::{
    continuous_quaternion, energy_scale, relative_energy_error, run_coupled_rows, run_hamiltonian,
    run_product_rows, run_rigid_rows, run_taylor_vector, run_vector,
};

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
    /// Why its model offers none of the Lie-group kinds of problem (rigid-body,
    /// free-rigid-body, lie-vector-field, coupled-rigid-body), or only the product's
    /// (product-vector-field): added to the refusal of a method that needs one (a model without
    /// an orientation on SO(3), or with several); empty where nothing needs saying.
    pub not_on_group: &'static str,
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
pub(crate) struct RowsView<'v, S, F> {
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
    /// Runs many points at once for the tilt metrics alone, when it can.
    pub lanes: Option<TiltLanes>,
}

/// Many runs of a [`Reduction`] at once, several per instruction, for the tilt metrics alone
/// (the hoop-tilt map's): each run's result is the same whatever the other runs are.
#[derive(Debug)]
pub struct TiltLanes {
    /// Runs per batch.
    pub width: usize,
    /// Whether [`TiltLanes::run`] runs a plan.
    pub runs: fn(&RunPlan) -> bool,
    /// Runs every point (parameters) with a plan; the threshold (rad) is the tilt whose first
    /// crossing is reported.
    #[allow(clippy::type_complexity)]
    pub run: fn(&[Params], &RunPlan, Option<f64>) -> Vec<Result<TiltRun, SceneError>>,
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

    /// What `tumble view` and `tumble animate` draw of this scene at `params`: its objects,
    /// how each follows the rows, the trail and the size ([`Drawing`]). `None` by default: the
    /// scene has no 3D view.
    ///
    /// # Errors
    /// (Inside the `Some`) invalid parameters.
    fn drawing(&self, _params: &Params) -> Option<Result<Drawing, SceneError>> {
        None
    }

    /// Where the bodies and point masses that this scene places itself
    /// ([`Motion::PlacedBody`](crate::drawing::Motion::PlacedBody), …) are at each of `rows`
    /// (the scene's rows at `params`); rows that do not hold the scene's state give none.
    /// Empty by default.
    fn placements(&self, _params: &Params, _rows: &[Vec<f64>]) -> Vec<Placed> {
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
