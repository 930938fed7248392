//! One simulation, from what a caller asks for to a validated run plan, in the words of the
//! caller: the command line (`tumble simulate`, `work-precision`, `animate`) and the Python
//! package take the same path, so both refuse the same inputs with the same reasons and run
//! the same steps.
//!
//! [`load_scene`] finds a built-in scene or reads a scene file and applies parameter
//! overrides; [`LoadedScene::plan`] lays a [`RunRequest`] over the file's `[run]` options,
//! resolves the plan against the scene and refuses a fixed step that does not resolve the
//! initial rotation ([`StepResolution`]). Messages name options as the caller does
//! ([`Naming`]: `--t-end` on the command line, `t_end` from Python); [`failure_message`] names
//! the state a failed run carries by the scene's coordinates and rates.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use nalgebra::Vector3;
use tumble_scenarios::drawing::{Drawing, Placed};
use tumble_scenarios::scene::{CancelFlag, MAX_ANGLE_PER_STEP};

use crate::sweep::{SweepDefinition, coarsest_point};
use tumble_scenarios::scene_file::SceneFile;
use tumble_scenarios::{
    Guide, ModelError, Params, Recorder, RunOptions, RunPlan, RunSummary, Scene, SceneError,
    SceneInfo, StepControl, StepResolution, scenes,
};

/// An input refused before any work, with the whole message.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct Refused(pub String);

/// How the caller names run options in messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Naming {
    /// Command-line flags: `--t-end 5`, `--integrator dop853`.
    Cli,
    /// Python keyword arguments: `t_end=5`, `integrator='dop853'`.
    Python,
}

impl Naming {
    /// The option `name` (a [`RunOptions`] field) as the caller spells it.
    #[must_use]
    pub fn option(self, name: &str) -> String {
        match self {
            Naming::Cli => format!("--{}", name.replace('_', "-")),
            Naming::Python => name.to_string(),
        }
    }

    /// The option `name` given `value`: `--dt 0.1` or `dt=0.1`.
    #[must_use]
    pub fn assign(self, name: &str, value: &str) -> String {
        match self {
            Naming::Cli => format!("{} {value}", self.option(name)),
            Naming::Python => format!("{name}={value}"),
        }
    }

    /// The flag or keyword that runs a coarse step anyway.
    fn allow_coarse_step(self) -> &'static str {
        match self {
            Naming::Cli => "pass --allow-coarse-step",
            Naming::Python => "pass allow_coarse_step=True",
        }
    }

    /// The adaptive integrator to suggest.
    fn adaptive(self) -> &'static str {
        match self {
            Naming::Cli => "--integrator dop853",
            Naming::Python => "integrator='dop853'",
        }
    }
}

/// Whether SCENE names a file rather than a built-in scene: it ends in `.toml` or names an
/// existing file.
#[must_use]
pub fn is_scene_file(arg: &str) -> bool {
    Path::new(arg)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
        || Path::new(arg).is_file()
}

/// The `origin` of a built-in scene ([`LoadedScene::origin`]; a file's is its path).
pub const BUILT_IN: &str = "builtin";

/// A scene as the caller names it, with its parameters and the file's run options.
pub struct LoadedScene {
    /// The scene.
    pub scene: &'static dyn Scene,
    /// Where it came from: [`BUILT_IN`] or the scene file's path.
    pub origin: String,
    /// Its parameters: defaults, then the file's values, then the overrides.
    pub params: Params,
    /// The scene file's `[run]` options (none for a built-in scene).
    pub run: RunOptions,
    /// The frame the rows report when the scene file has a `[body]` table.
    pub frame: Option<String>,
}

/// One parameter override: how the caller wrote it (for messages), the key and the value.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamOverride {
    /// The override as written (`--set omega0=5`, `params['omega0']=5`).
    pub label: String,
    /// The parameter.
    pub key: String,
    /// Its value.
    pub value: f64,
}

/// The scene `arg` names (a built-in scene, a TOML scene file or model file when
/// [`is_scene_file`], or model text: several lines with a `[model]` table) with `overrides`
/// applied in order.
///
/// # Errors
/// An unknown scene (listing the built-in ones), an unreadable or invalid scene file, an
/// unknown parameter or a value outside its domain (after the override's label).
pub fn load_scene(arg: &str, overrides: &[ParamOverride]) -> Result<LoadedScene, Refused> {
    // Model text (Python passes a model as a string): several lines with a [model] table.
    let text = arg.contains('\n') && tumble_model::is_model_text(arg);
    let (scene, origin, mut params, run, frame) =
        if text || (is_scene_file(arg) && tumble_model::is_model_file(Path::new(arg))) {
            let (scene, origin) = if text {
                (
                    tumble_model::from_text(arg, "model text"),
                    "model text".to_string(),
                )
            } else {
                (tumble_model::load(Path::new(arg)), arg.to_string())
            };
            let scene = scene.map_err(|e| Refused(e.to_string()))?;
            let run = scene.model().run.options.clone();
            let scene: &'static dyn Scene = scene;
            (scene, origin, scene.info().default_params(), run, None)
        } else if is_scene_file(arg) {
            let file = SceneFile::load(Path::new(arg)).map_err(|e| Refused(e.to_string()))?;
            (file.scene, file.origin, file.params, file.run, file.frame)
        } else {
            let scene = scenes::find(arg).map_err(|e| match e {
                SceneError::UnknownScene { name, known } => Refused(format!(
                    "unknown scene `{name}` (and no file of that name); built-in scenes: {known}; \
                 a scene file must end in .toml"
                )),
                other => Refused(other.to_string()),
            })?;
            let params = scene.info().default_params();
            (
                scene,
                BUILT_IN.to_string(),
                params,
                RunOptions::default(),
                None,
            )
        };
    for o in overrides {
        params
            .set(&o.key, o.value)
            .map_err(|e| Refused(format!("{}: {e}", o.label)))?;
    }
    Ok(LoadedScene {
        scene,
        origin,
        params,
        run,
        frame,
    })
}

/// What the caller asks of a run, over the scene file's `[run]` options (`None`: keep the
/// file's, else the scene's default).
#[derive(Debug, Clone, Default)]
pub struct RunRequest {
    /// Integrator name.
    pub integrator: Option<String>,
    /// Fixed step or tolerance.
    pub step: Option<StepControl>,
    /// Horizon.
    pub t_end: Option<f64>,
    /// Write every N-th step (clears the file's output times).
    pub every: Option<u64>,
    /// Write rows at these times (clears the file's `output_dt`).
    pub at: Option<Vec<f64>>,
    /// Write rows every DT seconds (clears the file's `at`).
    pub output_dt: Option<f64>,
    /// Step budget.
    pub max_steps: Option<u64>,
    /// Run a fixed step that does not resolve the initial rotation anyway.
    pub allow_coarse_step: bool,
    /// The flag that stops the run at its next step.
    pub cancel: Option<CancelFlag>,
}

/// The most steps a run takes unless told otherwise (`simulate --max-steps`, Python's
/// `max_steps`): a guard against a step size that would never reach the horizon.
pub const DEFAULT_MAX_STEPS: u64 = 1_000_000_000;

/// A run's largest relative energy error above which its record sets `energy_warning`
/// (`simulate --energy-warn`): the step does not resolve the motion.
pub const DEFAULT_ENERGY_WARN: f64 = 1e-6;

/// The frame of a run's orientation and angular-velocity columns when its scene file names
/// none: the words a run's record (`FILE.csv.json`, Python's `Simulation.frame`) gives.
pub const BODY_FRAME: &str = "the scene's body frame (docs/design.md, section 3)";

impl LoadedScene {
    /// The frame the rows report, in words: the `[body]` table's, else [`BODY_FRAME`].
    #[must_use]
    pub fn frame_words(&self) -> String {
        self.frame.clone().unwrap_or_else(|| BODY_FRAME.to_string())
    }

    /// The run options: the file's, with `request` laid over them.
    #[must_use]
    pub fn options(&self, request: &RunRequest) -> RunOptions {
        let mut options = self.run.clone();
        if let Some(name) = &request.integrator {
            options.integrator = Some(name.clone());
        }
        if request.step.is_some() {
            options.step = request.step;
        }
        if request.t_end.is_some() {
            options.t_end = request.t_end;
        }
        if request.every.is_some() {
            options.every = request.every;
            options.at = None;
            options.output_dt = None;
        }
        if let Some(times) = &request.at {
            options.at = Some(times.clone());
            options.output_dt = None;
        }
        if request.output_dt.is_some() {
            options.output_dt = request.output_dt;
            options.at = None;
        }
        if request.max_steps.is_some() {
            options.max_steps = request.max_steps;
        }
        if request.cancel.is_some() {
            options.cancel = request.cancel;
        }
        options
    }

    /// The validated plan of `request` on this scene.
    ///
    /// # Errors
    /// An invalid option (named as `naming` names it) or a fixed step that does not resolve
    /// the initial rotation (unless `request.allow_coarse_step`).
    pub fn plan(&self, request: &RunRequest, naming: Naming) -> Result<RunPlan, Refused> {
        let info = self.scene.info();
        let plan = self
            .options(request)
            .resolve(info)
            .map_err(|e| Refused(format!("{}: {}", info.name, flag_words(&e, naming))))?;
        if !request.allow_coarse_step {
            check_resolution(self.scene, &self.params, &plan, naming)?;
        }
        Ok(plan)
    }
}

/// Refuses a fixed step that does not resolve the initial state's fastest rotation (the rule
/// of [`StepResolution`], shared with sweeps), with the bound and a step that resolves it.
///
/// # Errors
/// The step is too coarse, or the rate cannot be computed.
pub fn check_resolution(
    scene: &dyn Scene,
    params: &Params,
    plan: &RunPlan,
    naming: Naming,
) -> Result<(), Refused> {
    let info = scene.info();
    let Some(r) = StepResolution::of(scene, params, plan)
        .map_err(|e| Refused(format!("{}: {e}", info.name)))?
    else {
        return Ok(());
    };
    if r.resolved() {
        return Ok(());
    }
    Err(Refused(format!(
        "{}: dt = {} does not resolve the initial rotation: {}; give {} (or an adaptive \
         integrator, {}), or {} to run anyway",
        info.name,
        number(r.dt),
        rate_words(&r),
        r.suggested_step().map_or_else(
            || "parameters with a finite rate".to_string(),
            |h| format!("{} or smaller", naming.assign("dt", &number(h)))
        ),
        naming.adaptive(),
        naming.allow_coarse_step(),
    )))
}

/// Refuses a sweep whose fixed step does not resolve the fastest initial rotation at one of
/// its points (the rule of [`check_resolution`], judged at the corners of the axes:
/// [`crate::sweep::coarsest_point`]), naming the point and a step that resolves every point.
///
/// # Errors
/// The step is too coarse somewhere, or a rate cannot be computed.
pub fn check_sweep_resolution(def: &SweepDefinition, naming: Naming) -> Result<(), Refused> {
    let Some(point) = coarsest_point(def).map_err(|e| Refused(format!("{}: {e}", def.origin)))?
    else {
        return Ok(());
    };
    let r = &point.resolution;
    if r.resolved() {
        return Ok(());
    }
    let step = |h: f64| match naming {
        Naming::Cli => format!("--set run.dt={} or smaller", number(h)),
        Naming::Python => format!("run.dt = {} or smaller", number(h)),
    };
    Err(Refused(format!(
        "{}: run.dt = {} does not resolve the initial rotation at {} ({}): {}; give {} (the \
         largest rate of the sweep is there), or an adaptive integrator (run.integrator = \
         \"dop853\" with run.tol), or {} to run anyway",
        def.origin,
        number(r.dt),
        point.index.map_or_else(
            || "a corner of the axes".to_string(),
            |i| format!("point {i}")
        ),
        point.describe(def),
        rate_words(r),
        r.suggested_step()
            .map_or_else(|| "axis values with a finite rate".to_string(), step),
        naming.allow_coarse_step(),
    )))
}

/// `|ω| ≈ R rad/s turns A rad a step, above the bound h·|ω| ≤ 0.5`.
#[must_use]
pub fn rate_words(r: &StepResolution) -> String {
    format!(
        "|ω| ≈ {} rad/s turns {} rad a step, above the bound h·|ω| ≤ {MAX_ANGLE_PER_STEP}",
        significant(r.rate),
        significant(r.angle())
    )
}

/// `x` to three significant digits (in exponent form outside `[1e-3, 1e7)`).
fn significant(x: f64) -> String {
    if (1e-3..1e7).contains(&x.abs()) {
        format!("{}", format!("{x:.2e}").parse::<f64>().unwrap_or(x))
    } else {
        format!("{x:.2e}")
    }
}

/// A run-option error in the caller's words (`--dt` or `dt` for `dt`).
#[must_use]
pub fn flag_words(e: &SceneError, naming: Naming) -> String {
    match e {
        SceneError::InvalidOption {
            option,
            value,
            reason,
        } => {
            if !matches!(
                *option,
                "t_end" | "dt" | "tol" | "every" | "at" | "output_dt"
            ) {
                return e.to_string();
            }
            if value.is_nan() && matches!(*option, "at" | "output_dt") {
                format!("{}: {reason}", naming.option(option))
            } else {
                format!("{}: {reason}", naming.assign(option, &number(*value)))
            }
        }
        SceneError::UnsupportedIntegrator { .. } => {
            format!("{}: {e}", naming.option("integrator"))
        }
        _ => e.to_string(),
    }
}

/// A number as a person would type it: plain, or in exponent form when very small or large.
#[must_use]
pub fn number(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The state a failure carries, if any.
fn failure_state(e: &SceneError) -> Option<&[f64]> {
    use tumble_integrators::Error as I;
    match e {
        SceneError::Model(
            ModelError::SingularMassMatrix { state, .. } | ModelError::NonFinite { state, .. },
        )
        | SceneError::Integration(
            I::NonFinite { state, .. }
            | I::NoConvergence { state, .. }
            | I::SingularMatrix { state, .. }
            | I::StepSizeUnderflow { state, .. }
            | I::TooManySteps { state, .. }
            | I::TimeLimit { state, .. },
        ) => Some(state),
        _ => None,
    }
}

/// The names of a scene's rate columns: `<coordinate>_dot`, or the scene's own rate names
/// (a rotation's body angular velocity).
#[must_use]
pub fn rate_columns(info: &SceneInfo) -> Vec<String> {
    if info.rate_names.is_empty() {
        info.coordinates
            .iter()
            .map(|c| format!("{c}_dot"))
            .collect()
    } else {
        info.rate_names.iter().map(|r| (*r).to_string()).collect()
    }
}

/// `name = value, …` for values with one name each.
fn named(names: &[String], values: &[f64]) -> String {
    let parts: Vec<String> = names
        .iter()
        .zip(values)
        .map(|(n, v)| format!("{n} = {}", number(*v)))
        .collect();
    parts.join(", ")
}

/// A run failure with the state it carries, named by the scene's coordinates and rates when
/// the state has one value for each.
#[must_use]
pub fn failure_message(info: &SceneInfo, e: &SceneError) -> String {
    if let SceneError::NonFiniteOutput {
        t,
        column,
        value,
        row,
    } = e
    {
        let columns = info.columns();
        let name = columns.get(*column).map_or("?", String::as_str);
        let mut msg = format!(
            "{}: non-finite output at t = {}: {name} = {value}; the state or a quantity derived \
             from it overflowed (check the parameters' scale)",
            info.name,
            number(*t)
        );
        if columns.len() == row.len() {
            msg += &format!("\n  row: {}", named(&columns, row));
        }
        return msg;
    }
    let mut msg = format!("{}: {e}", info.name);
    if let Some(state) = failure_state(e) {
        let names: Vec<String> = info
            .coordinates
            .iter()
            .map(|c| (*c).to_string())
            .chain(rate_columns(info))
            .collect();
        if names.len() == state.len() {
            msg += &format!("\n  state: {}", named(&names, state));
        } else {
            let values: Vec<String> = state.iter().map(|v| number(*v)).collect();
            msg += &format!("\n  state: [{}]", values.join(", "));
        }
    }
    msg
}

/// A scene whose runs stop at a step boundary once `flag` is set (by a signal handler, or a
/// caller that was interrupted): each run polls the flag ([`RunPlan::cancel`]) and a run it
/// stopped is an error ([`SceneError::Interrupted`]), so that a study built on the scene
/// (work–precision ladders, its reference) never takes a cut run for a finished one and ends
/// at once.
pub struct Interruptible {
    /// The scene.
    pub scene: &'static dyn Scene,
    /// The flag that stops it.
    pub flag: &'static AtomicBool,
}

impl Scene for Interruptible {
    fn info(&self) -> &'static SceneInfo {
        self.scene.info()
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let stopped = || self.flag.load(Ordering::Relaxed);
        if stopped() {
            return Err(SceneError::Interrupted { t: 0.0 });
        }
        let watched;
        let plan = if plan.cancel.is_some() {
            plan
        } else {
            watched = RunPlan {
                cancel: Some(CancelFlag(self.flag)),
                ..plan.clone()
            };
            &watched
        };
        let summary = self.scene.simulate(params, plan, recorder)?;
        if stopped() && !(summary.t >= plan.t_end || summary.terminated) {
            return Err(SceneError::Interrupted { t: summary.t });
        }
        Ok(summary)
    }

    fn intermediate_axis(&self, params: &Params) -> Option<Result<Vector3<f64>, SceneError>> {
        self.scene.intermediate_axis(params)
    }

    fn initial_rate(&self, params: &Params) -> Option<Result<f64, SceneError>> {
        self.scene.initial_rate(params)
    }

    fn map_guides(&self, params: &Params, axes: &[&str], x_range: (f64, f64)) -> Vec<Guide> {
        self.scene.map_guides(params, axes, x_range)
    }

    fn recommendations(&self) -> &'static [tumble_scenarios::Recommendation] {
        self.scene.recommendations()
    }

    fn fixed_columns(&self) -> &'static [(&'static str, &'static str)] {
        self.scene.fixed_columns()
    }

    fn drawing(&self, params: &Params) -> Option<Result<Drawing, SceneError>> {
        self.scene.drawing(params)
    }

    fn placements(&self, params: &Params, rows: &[Vec<f64>]) -> Vec<Placed> {
        self.scene.placements(params, rows)
    }
}
