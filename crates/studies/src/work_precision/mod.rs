//! Work–precision: the error at the final time against the cost of getting it, for every
//! integrator that runs a scene (docs/design.md §4).
//!
//! For each integrator, a ladder of steps (or tolerances, for the adaptive `dp5`/`dop853`) runs
//! from an error of about `1e-2` down to the round-off floor or a time budget. Each rung records
//! the error of the final state against a [`Reference`], the largest relative energy error over
//! the run, the right-hand-side evaluations and the wall time (the median of several repeats of
//! a run that observes only its first and last state, [`Observe::Ends`], so that the diagnostics
//! a row computes are not charged to the method). Once every ladder has run, [`retime`] times
//! all rungs again in rounds in which the methods take turns, so that the ratios between
//! methods do not depend on which one ran while the machine was slow.
//!
//! # The error
//!
//! The final state is the row `simulate` writes at the final time: the coordinates and their
//! rates (for rotating bodies the unit quaternion and the body angular velocity). Its error is
//! the mixed absolute/relative maximum norm that Runge–Kutta error control uses,
//! `max_i |yᵢ − yᵢ,ref| / (1 + |yᵢ,ref|)`, with each quaternion compared up to its sign
//! (`q` and `−q` are the same rotation; a model with several orientations has one per body).
//!
//! # The reference
//!
//! A scene the Taylor method runs in double-double arithmetic (`taylor-dd`: the rigid bodies,
//! `free-body`, `dzhanibekov`, `heavy-top` and the bodies of scene files): that method at
//! tolerance `1e-30`, whose final state is the solution rounded to `f64`, checked against itself
//! at `1e-26` and against what would otherwise be the reference (below). Otherwise, for
//! `free-body` and `dzhanibekov`: the exact flow (Jacobi elliptic functions and Carlson's
//! `R_J`; `exact` in the registry). Otherwise the highest Gauss–Legendre method the scene takes
//! at a step 16 times below the scene's default, cross-checked against DOP853 at tolerance
//! `1e-13`, and against itself at half the step; for a scene without Gauss–Legendre methods
//! (`coriolis-drop` ends at an event, which needs dense output) DOP853 at `1e-13` is the
//! reference and RK4 at the small step the cross-check. [`Reference::agreement`] says how far
//! the two agree, which bounds what the ladder can resolve.
//!
//! # Submodules
//!
//! Long runs (the energy error over a million steps and more, cost matching) are in `long`;
//! the measurements behind a scene's recommendations ([`measure_recommendations`]) in
//! `recommend`. Their items are re-exported here.

mod long;
mod recommend;
pub mod record;

pub use record::Rung;

use std::time::Instant;

use tumble_integrators::registry::{self, Family, MethodInfo, Order};

use long::power_law;
pub use long::{
    EnergyHistory, LONG_FACTOR, LongRun, cost_distance, cost_per_second, long_run_methods,
    long_runs, matching_step, matching_tolerance,
};
pub use recommend::{cost_at, measure_recommendations};
use tumble_integrators::Flow;
use tumble_scenarios::error::SceneError;
use tumble_scenarios::params::Params;
use tumble_scenarios::scene::{
    Observe, Recorder, RunOptions, RunPlan, RunSummary, Scene, SceneInfo, StepControl,
};

/// Keeps the last row of a run (the final state), overwriting it in place.
#[derive(Debug, Clone, Default)]
pub struct LastRow {
    /// The last row handed over.
    pub last: Vec<f64>,
}

impl Recorder for LastRow {
    fn row(&mut self, values: &[f64]) -> Flow {
        if self.last.len() == values.len() {
            self.last.copy_from_slice(values);
        } else {
            self.last.clear();
            self.last.extend_from_slice(values);
        }
        Flow::Continue
    }
}

pub use tumble_scenarios::scene::FinalState;

/// Runs `scene` and returns its final state and summary.
///
/// # Errors
/// Whatever the run reports.
pub fn final_state(
    scene: &dyn Scene,
    params: &Params,
    plan: &RunPlan,
) -> Result<(FinalState, RunSummary), SceneError> {
    let info = scene.info();
    let mut rec = LastRow::default();
    let summary = scene.simulate(params, plan, &mut rec)?;
    let n = state_len(info);
    let values = rec.last.get(1..=n).map(<[f64]>::to_vec).unwrap_or_default();
    Ok((
        FinalState {
            t: rec.last.first().copied().unwrap_or(f64::NAN),
            values,
        },
        summary,
    ))
}

/// Number of coordinates and rates in a row.
pub(crate) fn state_len(info: &SceneInfo) -> usize {
    let rates = if info.rate_names.is_empty() {
        info.coordinates.len()
    } else {
        info.rate_names.len()
    };
    info.coordinates.len() + rates
}

/// Whether the four coordinates from `i` are a quaternion's `qw, qx, qy, qz`, under a common
/// prefix (a model with several orientations shows each as `NAME_qw` …).
fn is_quaternion(coordinates: &[&str], i: usize) -> bool {
    let Some(w) = coordinates.get(i..i + 4) else {
        return false;
    };
    let Some(prefix) = w[0].strip_suffix("qw") else {
        return false;
    };
    ["qx", "qy", "qz"]
        .iter()
        .zip(&w[1..])
        .all(|(c, name)| name.strip_suffix(c) == Some(prefix))
}

/// The error of `y` against `reference` (module doc): `max |Δᵢ| / (1 + |refᵢ|)`, each
/// quaternion compared up to its own sign, and `∞` when the times differ by more than
/// round-off or a value is not finite.
#[must_use]
pub fn state_error(info: &SceneInfo, y: &FinalState, reference: &FinalState) -> f64 {
    let n = y.values.len();
    if n != reference.values.len() || (y.t - reference.t).abs() > 1e-9 * reference.t.abs().max(1.0)
    {
        return f64::INFINITY;
    }
    let error = |i: usize, sign: f64| {
        let (a, b) = (y.values[i], reference.values[i]);
        let e = (sign * a - b).abs() / (1.0 + b.abs());
        if e.is_nan() { f64::INFINITY } else { e }
    };
    let mut worst = 0.0f64;
    let mut i = 0;
    while i < n {
        if i + 4 <= n && is_quaternion(info.coordinates, i) {
            let block = |sign: f64| (i..i + 4).fold(0.0f64, |m, j| m.max(error(j, sign)));
            worst = worst.max(block(1.0).min(block(-1.0)));
            i += 4;
        } else {
            worst = worst.max(error(i, 1.0));
            i += 1;
        }
    }
    worst
}

/// How the reference was computed.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// The reference's final state.
    pub state: FinalState,
    /// What computed it (`exact`, or `gauss12 dt = 6.25e-4`).
    pub method: String,
    /// What cross-checked it (`dop853 tol = 1e-13`).
    pub check: String,
    /// [`state_error`] of the cross-check against the reference.
    pub agreement: f64,
    /// What the reference was compared with itself (`gauss12 dt = 3.125e-4`); empty for the
    /// exact flow.
    pub self_check: String,
    /// [`state_error`] of that run against the reference.
    pub self_agreement: f64,
}

/// Options of a work–precision study.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    /// Horizon (s).
    pub t_end: f64,
    /// A ladder stops after a run that took longer than this (s) (its rung is kept); a run
    /// still going at [`Config::CUT_FACTOR`] times this is cut (its rung dropped).
    pub max_run_seconds: f64,
    /// Wall-time limit (s) of each run of the reference ([`reference_within`]).
    pub max_reference_seconds: f64,
    /// A ladder stops after a run of more steps than this (a budget that, unlike time, does
    /// not depend on the machine: for tests).
    pub max_steps: u64,
    /// A ladder stops once the error is below this.
    pub error_floor: f64,
    /// Largest error a rung may have to be kept (coarser rungs are skipped).
    pub max_error: f64,
}

impl Config {
    /// [`Config::max_run_seconds`] unless told otherwise (`work-precision --max-seconds`,
    /// Python's `max_seconds`).
    pub const DEFAULT_MAX_RUN_SECONDS: f64 = 0.5;

    /// Each run of the reference is limited to this multiple of [`Config::max_run_seconds`]
    /// ([`Config::max_reference_seconds`] unless told otherwise).
    pub const REFERENCE_FACTOR: f64 = 60.0;

    /// A ladder's run is cut at this multiple of [`Config::max_run_seconds`].
    pub const CUT_FACTOR: f64 = 2.0;

    /// The defaults for `info`: its horizon, 0.5 s per run, errors from `1e-2` down to `1e-14`.
    #[must_use]
    pub fn new(info: &SceneInfo) -> Self {
        Config {
            t_end: info.default_t_end,
            max_run_seconds: Config::DEFAULT_MAX_RUN_SECONDS,
            max_reference_seconds: Config::REFERENCE_FACTOR * Config::DEFAULT_MAX_RUN_SECONDS,
            max_steps: u64::MAX,
            error_floor: 1e-14,
            max_error: 1e-1,
        }
    }
}

/// Above this error a rung is coarse: a failure there does not end the ladder.
const COARSE_ERROR: f64 = 1e-4;

/// A rung that failed (a step too large for an implicit solver to converge, say).
#[derive(Debug, Clone, PartialEq)]
pub struct FailedRung {
    /// Integrator.
    pub integrator: String,
    /// Step or tolerance.
    pub control: StepControl,
    /// Why.
    pub reason: String,
    /// Whether the run was cut at its time limit.
    pub time_limit: bool,
}

/// The ladder of one integrator.
#[derive(Debug, Clone, PartialEq)]
pub struct Ladder {
    /// Integrator.
    pub integrator: String,
    /// Its order (a number, the exact flow, or variable: a Taylor method's).
    pub order: Order,
    /// Rungs from coarse to fine.
    pub rungs: Vec<Rung>,
    /// Rungs that failed.
    pub failures: Vec<FailedRung>,
    /// Why the ladder stopped.
    pub stop: String,
}

/// The validated plan of `integrator` at `control` over `[0, t_end]` on `info`'s scene.
///
/// # Errors
/// An integrator the scene does not take, or an invalid step, tolerance or horizon.
pub fn plan(
    info: &SceneInfo,
    integrator: &str,
    control: StepControl,
    t_end: f64,
    observe: Observe,
) -> Result<RunPlan, SceneError> {
    RunOptions {
        integrator: Some(integrator.to_string()),
        step: Some(control),
        t_end: Some(t_end),
        every: Some(1),
        at: None,
        output_dt: None,
        max_steps: None,
        cancel: None,
        observe,
    }
    .resolve(info)
}

/// A step or tolerance as the study prints it: `dt = 1.000e-2`, `tol = 1.0e-8`.
#[must_use]
pub fn control_words(c: StepControl) -> String {
    match c {
        StepControl::Fixed(h) => format!("dt = {h:.3e}"),
        StepControl::Tolerance(t) => format!("tol = {t:.1e}"),
    }
}

fn describe(integrator: &str, control: StepControl) -> String {
    match control {
        StepControl::Fixed(h) => format!("{integrator} dt = {h:e}"),
        StepControl::Tolerance(tol) => format!("{integrator} tol = {tol:e}"),
    }
}

/// The method of highest order (the exact flow above all) among those that run `info`'s scene
/// and satisfy `pred`; the first in registry order among equals.
#[must_use]
pub fn highest_order(
    info: &SceneInfo,
    pred: impl Fn(&MethodInfo) -> bool,
) -> Option<&'static MethodInfo> {
    let rank = |m: &MethodInfo| m.order.value().unwrap_or(u32::MAX);
    registry::methods()
        .iter()
        .filter(|m| info.kind_for(m).is_some() && pred(m))
        .fold(None, |best: Option<&'static MethodInfo>, m| match best {
            Some(b) if rank(b) >= rank(m) => Some(b),
            _ => Some(m),
        })
}

/// The reference solution of `scene` at `t_end` (module doc).
///
/// # Errors
/// A failing reference run.
pub fn reference(scene: &dyn Scene, params: &Params, t_end: f64) -> Result<Reference, SceneError> {
    reference_within(scene, params, t_end, None)
}

/// [`reference`] with each of its runs limited to `seconds` of wall time (when given).
///
/// # Errors
/// A failing reference run, [`tumble_integrators::Error::TimeLimit`] for one that reached the
/// limit.
pub fn reference_within(
    scene: &dyn Scene,
    params: &Params,
    t_end: f64,
    seconds: Option<f64>,
) -> Result<Reference, SceneError> {
    let info = scene.info();
    let h_small = refine_step(info.default_step / 16.0, t_end);
    let tight = StepControl::Tolerance(1e-13);
    let exact = highest_order(info, |m| m.properties.exact);
    let gauss = highest_order(info, |m| m.family == Family::GaussLegendre && m.order >= 8);
    let adaptive = highest_order(info, |m| m.properties.adaptive);
    let explicit_fixed = highest_order(info, |m| {
        m.family == Family::ExplicitRungeKutta && !m.properties.adaptive
    });
    let missing = |what: &str| SceneError::InvalidOption {
        option: "integrator",
        value: f64::NAN,
        reason: format!("scene `{}` has no {what} for a reference", info.name),
    };
    let adaptive = adaptive.ok_or_else(|| missing("adaptive method"))?.name;
    let (method, control, check, check_control, self_control) = if let Some(e) = exact {
        // One step of the exact flow over the whole horizon.
        (e.name, StepControl::Fixed(t_end), adaptive, tight, None)
    } else if let Some(g) = gauss {
        (
            g.name,
            StepControl::Fixed(h_small),
            adaptive,
            tight,
            Some(StepControl::Fixed(refine_step(h_small / 2.0, t_end))),
        )
    } else {
        (
            adaptive,
            tight,
            explicit_fixed
                .ok_or_else(|| missing("fixed-step Runge–Kutta method"))?
                .name,
            StepControl::Fixed(h_small),
            Some(StepControl::Tolerance(1e-14)),
        )
    };
    let run = |name: &str, c: StepControl| {
        let mut plan = plan(info, name, c, t_end, Observe::Ends)?;
        if let Some(seconds) = seconds.filter(|s| s.is_finite()) {
            plan = plan.with_deadline(seconds);
        }
        final_state(scene, params, &plan).map(|(s, _)| s)
    };
    let checked = run(method, control)?;
    let double_double = registry::find(DOUBLE_DOUBLE_REFERENCE.0)
        .ok()
        .filter(|m| info.kind_for(m).is_some());
    if let Some(dd) = double_double {
        // The double-double Taylor method, checked by what would otherwise be the reference
        // (which stays the reference if it fails, e.g. on the time limit of a long horizon).
        let reference = StepControl::Tolerance(DOUBLE_DOUBLE_REFERENCE.1);
        let again = StepControl::Tolerance(DOUBLE_DOUBLE_REFERENCE.2);
        let runs = run(dd.name, reference).and_then(|s| Ok((s, run(dd.name, again)?)));
        if let Ok((state, repeated)) = runs {
            return Ok(Reference {
                agreement: state_error(info, &checked, &state),
                self_agreement: state_error(info, &repeated, &state),
                state,
                method: describe(dd.name, reference),
                check: if exact.is_some() {
                    "exact flow (one step over the horizon)".to_string()
                } else {
                    describe(method, control)
                },
                self_check: describe(dd.name, again),
            });
        }
    }
    let state = checked;
    let checked = run(check, check_control)?;
    let agreement = state_error(info, &checked, &state);
    let (self_check, self_agreement) = match self_control {
        Some(c) => {
            let again = run(method, c)?;
            (describe(method, c), state_error(info, &again, &state))
        }
        None => (String::new(), 0.0),
    };
    Ok(Reference {
        state,
        method: if exact.is_some() {
            "exact flow (one step over the horizon)".to_string()
        } else {
            describe(method, control)
        },
        check: describe(check, check_control),
        agreement,
        self_check,
        self_agreement,
    })
}

/// The reference method where a scene offers it, its tolerance, and the tolerance of its
/// self-check (module doc).
const DOUBLE_DOUBLE_REFERENCE: (&str, f64, f64) = ("taylor-dd", 1e-30, 1e-26);

/// `h` adjusted down so that a whole number of steps fits the horizon.
pub(crate) fn refine_step(h: f64, t_end: f64) -> f64 {
    let n = (t_end / h).ceil().max(1.0);
    t_end / n
}

/// Median of `values` (sorted in place).
fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// Back-to-back runs of `seconds` each that last at least 5 ms together (a single µs-scale run
/// is at the mercy of a timer tick or a neighbour's burst).
fn batch_for(seconds: f64) -> usize {
    (5e-3 / seconds.max(1e-9)).ceil().clamp(1.0, 1e5) as usize
}

/// The plan of `integrator` over the study's horizon on `info`'s scene, cut at
/// [`Config::CUT_FACTOR`] times the run limit: a ladder's rungs change only its step.
fn ladder_plan(info: &SceneInfo, integrator: &str, config: &Config) -> Result<RunPlan, SceneError> {
    let base = RunOptions {
        integrator: Some(integrator.to_string()),
        t_end: Some(config.t_end),
        ..RunOptions::default()
    }
    .resolve(info)?;
    let limit = config.max_run_seconds * Config::CUT_FACTOR;
    Ok(if limit.is_finite() {
        base.with_deadline(limit)
    } else {
        base
    })
}

/// Runs one rung: a monitored run (error, energy, evaluations), then timed runs that observe
/// only the ends (5 samples of at least 5 ms of back-to-back runs; 3 for runs over 0.1 s).
///
/// # Errors
/// The run's error.
pub fn rung(
    scene: &dyn Scene,
    params: &Params,
    plan: &RunPlan,
    reference: &FinalState,
) -> Result<Rung, SceneError> {
    let info = scene.info();
    let start = Instant::now();
    let (state, summary) = final_state(scene, params, &plan.observing(Observe::EveryStep))?;
    let monitored = start.elapsed().as_secs_f64();
    // Timing: samples of back-to-back runs lasting at least 5 ms each (a single µs-scale run is
    // at the mercy of a timer tick or a neighbour's burst), the median of 5 samples (3 for runs
    // over 0.1 s).
    let batch = batch_for(monitored);
    let samples = if monitored < 0.1 { 5 } else { 3 };
    let quiet = plan.observing(Observe::Ends);
    let mut times = Vec::with_capacity(samples);
    for _ in 0..samples {
        let start = Instant::now();
        for _ in 0..batch {
            let (timed, _) = final_state(scene, params, &quiet)?;
            // Observing only the ends must not change the run (the quaternion's sign, chosen
            // continuous along the observed states, may differ).
            debug_assert!(
                state_error(info, &timed, &state) == 0.0,
                "observing only the ends changed the run: {timed:?} against {state:?}"
            );
        }
        times.push(start.elapsed().as_secs_f64() / batch as f64);
    }
    let repeats = samples * batch;
    let (dt, tol) = plan.step.dt_tol();
    Ok(Rung {
        integrator: plan.integrator().to_string(),
        order: plan.method.order,
        dt,
        tol,
        steps: summary.steps,
        evaluations: summary.evaluations,
        error: state_error(info, &state, reference),
        max_energy_rel_err: summary.max_energy_rel_err,
        wall_time_s: median(&mut times),
        repeats,
    })
}

/// The ratio between successive step counts of a ladder for a method of order `p`: about a
/// factor 4 less error per rung (`2^{2/p}`), between `2^{1/4}` and 2.
fn step_ratio(p: u32) -> f64 {
    2f64.powf((2.0 / f64::from(p.max(1))).clamp(0.25, 1.0))
}

/// Runs the ladder of `integrator` (module doc). `progress` sees each rung as it completes.
///
/// # Errors
/// An integrator that the registry does not know or the scene does not take; failures of single
/// rungs are recorded in [`Ladder::failures`] instead.
pub fn ladder(
    scene: &dyn Scene,
    params: &Params,
    integrator: &str,
    reference: &FinalState,
    config: &Config,
    progress: &mut dyn FnMut(&Rung),
) -> Result<Ladder, SceneError> {
    let info = scene.info();
    // The integrator's plan for this scene, validated once; rungs change only its step.
    let base = ladder_plan(info, integrator, config)?;
    let method = base.method;
    let order = method.order;
    let mut out = Ladder {
        integrator: integrator.to_string(),
        order,
        rungs: Vec::new(),
        failures: Vec::new(),
        stop: String::new(),
    };
    let t_end = config.t_end;
    let run = |control: StepControl, out: &mut Ladder| -> Option<Rung> {
        match base
            .with_step(control)
            .and_then(|plan| rung(scene, params, &plan, reference))
        {
            Ok(r) => Some(r),
            Err(e) => {
                out.failures.push(FailedRung {
                    integrator: integrator.to_string(),
                    control,
                    reason: e.to_string(),
                    time_limit: matches!(
                        e,
                        SceneError::Integration(tumble_integrators::Error::TimeLimit { .. })
                    ),
                });
                None
            }
        }
    };
    let cut = |out: &Ladder| out.failures.last().is_some_and(|f| f.time_limit);
    let p = match order {
        Order::Finite(p) => p,
        // Adaptive: its rungs are tolerances, which need no order.
        Order::Variable => 0,
        Order::Exact => {
            // The exact flow: one rung at the scene's default step.
            let h = refine_step(info.default_step, t_end);
            if let Some(r) = run(StepControl::Fixed(h), &mut out) {
                progress(&r);
                out.rungs.push(r);
            }
            out.stop = if cut(&out) {
                format!(
                    "a run was cut at {} s",
                    config.max_run_seconds * Config::CUT_FACTOR
                )
            } else {
                "exact flow: one rung".into()
            };
            return Ok(out);
        }
    };
    let adaptive = method.properties.adaptive;
    // The last rung of an adaptive method: tolerance 1e-15, or 1e-20 for a Taylor method (its
    // tolerance bounds each step's error against the largest component of the state, so the
    // smaller components need a tighter one to reach the same error; its order grows with it).
    let last_rung = if method.family == Family::Taylor {
        36
    } else {
        26
    };
    // Rung k: a tolerance 10^{-(2 + k/2)}, or n_k = n₀ r^k steps from a start coarse enough.
    let control_at = |k: i32, n0: f64| {
        if adaptive {
            StepControl::Tolerance(10f64.powf(-2.0 - f64::from(k) / 2.0))
        } else {
            let n = (n0 * step_ratio(p).powi(k)).round().max(1.0);
            StepControl::Fixed(t_end / n)
        }
    };
    let mut n0 = (t_end / info.default_step / 8.0).round().max(1.0);
    let mut k = 0;
    if !adaptive {
        // Coarsen until the error exceeds max_error (or the run fails, or one step is left):
        // untimed probes of the error only; the ladder proper starts at the last of them.
        let probe_error = |n: f64| {
            base.with_step(control_at(0, n))
                .and_then(|p| final_state(scene, params, &p.observing(Observe::Ends)))
                .ok()
                .map(|(s, _)| state_error(info, &s, reference))
        };
        while n0 > 1.0 && probe_error(n0).is_some_and(|e| e <= config.max_error) {
            n0 = (n0 / 4.0).ceil();
        }
    }
    let mut best = f64::INFINITY;
    let mut stalled = 0;
    loop {
        let control = control_at(k, n0);
        k += 1;
        if out
            .rungs
            .last()
            .is_some_and(|last| last.control() == Some(control))
        {
            continue;
        }
        let Some(r) = run(control, &mut out) else {
            if cut(&out) {
                out.stop = format!(
                    "a run was cut at {} s",
                    config.max_run_seconds * Config::CUT_FACTOR
                );
                break;
            }
            // A coarse rung may fail where a finer one converges (an implicit solve at a step
            // that turns the body by a radian): the ladder goes on while no rung is accurate.
            if k < 40 && (out.rungs.is_empty() || best > COARSE_ERROR) {
                continue;
            }
            out.stop = "a run failed".into();
            break;
        };
        let (error, seconds, steps) = (r.error, r.wall_time_s, r.steps);
        if error <= config.max_error {
            progress(&r);
            out.rungs.push(r);
        }
        if error < best / 1.5 {
            best = error;
            stalled = 0;
        } else if best < 1e-9 && !adaptive {
            // Not decreasing once small: round-off (a coarse, pre-asymptotic error, or an
            // adaptive method at loose tolerances, may wander for a rung or two).
            stalled += 1;
        }
        if error <= config.error_floor {
            out.stop = format!("error below {:e}", config.error_floor);
            break;
        }
        if stalled >= 3 {
            out.stop = "round-off floor: the error stopped decreasing".into();
            break;
        }
        if seconds > config.max_run_seconds {
            out.stop = format!("a run took longer than {} s", config.max_run_seconds);
            break;
        }
        if steps > config.max_steps {
            out.stop = format!("a run took more than {} steps", config.max_steps);
            break;
        }
        if adaptive && k > last_rung {
            out.stop = format!(
                "tolerance {:.0e} reached",
                10f64.powf(-2.0 - f64::from(last_rung) / 2.0)
            );
            break;
        }
    }
    Ok(out)
}

/// Rounds of [`retime`] that `tumble work-precision` runs.
pub const RETIME_ROUNDS: usize = 5;

/// Times every rung of `ladders` again, the rungs taking turns: `rounds` rounds, in each of
/// which every rung runs one batch of back-to-back runs observing only the ends (as many as
/// last 5 ms by the rung's first timing; one for a run over 5 ms). Each rung's
/// [`Rung::wall_time_s`] becomes the median of its batches' means. A ladder times its rungs one
/// method after another, so a change of the machine's speed during a study (another process's
/// burst on a shared host) falls on some methods and not on others; taken in turns it falls on
/// all of them alike, and the ratios between methods, which a study is read for, hold.
///
/// # Errors
/// A rung's plan or run that fails now although it ran in its ladder.
pub fn retime(
    scene: &dyn Scene,
    params: &Params,
    ladders: &mut [Ladder],
    config: &Config,
    rounds: usize,
) -> Result<(), SceneError> {
    struct Job {
        ladder: usize,
        rung: usize,
        plan: RunPlan,
        batch: usize,
        times: Vec<f64>,
    }
    let info = scene.info();
    let mut jobs = Vec::new();
    for (l, ladder) in ladders.iter().enumerate() {
        if ladder.rungs.is_empty() {
            continue;
        }
        let base = ladder_plan(info, &ladder.integrator, config)?;
        for (r, rung) in ladder.rungs.iter().enumerate() {
            let control = rung.control().ok_or_else(|| SceneError::InvalidOption {
                option: "dt",
                value: rung.dt.unwrap_or(f64::NAN),
                reason: format!(
                    "a rung of {} needs a step or a tolerance, not both or neither",
                    ladder.integrator
                ),
            })?;
            jobs.push(Job {
                ladder: l,
                rung: r,
                plan: base.with_step(control)?.observing(Observe::Ends),
                batch: batch_for(rung.wall_time_s),
                times: Vec::with_capacity(rounds),
            });
        }
    }
    for _ in 0..rounds {
        for job in &mut jobs {
            let start = Instant::now();
            for _ in 0..job.batch {
                final_state(scene, params, &job.plan)?;
            }
            job.times
                .push(start.elapsed().as_secs_f64() / job.batch as f64);
        }
    }
    for mut job in jobs {
        let rung = &mut ladders[job.ladder].rungs[job.rung];
        rung.wall_time_s = median(&mut job.times);
        rung.repeats += rounds * job.batch;
    }
    Ok(())
}

/// The least-squares slope of `log10 error` against `log10 x` over the rungs whose error lies
/// in `[lo, hi]` (`None` with fewer than 3 such rungs).
#[must_use]
pub fn fitted_slope(rungs: &[Rung], x: impl Fn(&Rung) -> f64, lo: f64, hi: f64) -> Option<f64> {
    power_law(
        rungs
            .iter()
            .filter(|r| r.error >= lo && r.error <= hi)
            .map(|r| (x(r), r.error)),
    )
}
