//! Work–precision benches of the built-in scenes (docs/design.md §4).
//!
//! - `scene-step/<scene>/<integrator>`: the cost of one step of every integrator a scene takes,
//!   run through `Scene::simulate` exactly as the command line runs it. Fixed-step methods take
//!   200 steps of the scene's `default_step`; adaptive ones (`dp5`, `dop853`) run the same
//!   horizon (200 · `default_step`) at tolerance `1e-8`. The run observes only its first and
//!   last state ([`Observe::Ends`]), so the per-step diagnostics of a row (energy, angular
//!   momentum, the exact solution's error) are not charged to the method. Criterion reports
//!   time per step (throughput = the run's accepted steps, from `RunSummary::steps`).
//!   `coriolis-drop` ends at its landing event, so its adaptive runs take fewer steps.
//!
//! - `free-hoop-1e-8/<solver>`: speed at a fixed error against the peer crates. On `free-hoop`
//!   (default parameters, `t_end = 10` s), each solver is run at the cheapest setting that
//!   brings the error at the final time to `1e-8` or below, and the wall times are compared: the
//!   project's best method against the best peer-crate DOP853 (`differential-equations`, `ode_solvers`),
//!   which integrate exactly the same right-hand side ([`FlatFreeHoop`], 14 dimensions, wrapped
//!   in their ODE traits; the wrappers only copy the 14 numbers in and out).
//!
//!   * Ours run through `Scene::simulate` with [`Observe::Ends`]: `dop853` and `vern8`
//!     (rtol = atol = tol), `gauss6` … `gauss12`, `rk4`, the coupled Lie-group variational
//!     integrator `lgvi` and its eighth-order composition `lgvi8`, and the variational
//!     Lie–Gauss methods `lie-gauss6` … `lie-gauss10` (`n` fixed steps of `t_end / n`). The
//!     solvers take turns in the timing, so the ratios between them (the variational methods
//!     against DOP853, say) hold even when the machine's speed drifts. Peers run `t_end` at
//!     rtol = atol = tol from the flattened initial state, with their default step control.
//!   * The error is the project's work–precision metric
//!     ([`tumble_studies::work_precision::state_error`]): `max |yᵢ − yᵢ,ref| / (1 + |yᵢ,ref|)`
//!     over the coordinates and rates the scene writes (quaternion `qw, qx, qy, qz` compared up
//!     to sign, `alpha`, body `omega`, `alpha_dot`); a peer's final flat state is converted by
//!     [`free_hoop::final_state`], the same row code the scene uses. The reference is
//!     [`work_precision::reference`]: Gauss–Legendre `s = 6` at a small step, cross-checked
//!     against DOP853 at `1e-13` (the agreement is printed; it bounds what `1e-8` can mean).
//!   * Settings, the same rule for every solver: a grid, tolerances `10^(−k/8)` or step counts
//!     `n = round(2^(k/8))` (ratio `2^(1/8)` ≈ 1.09). The search goes finer by a factor 10
//!     (tolerances) or 2 (steps) until the error is ≤ `1e-8`, then scans that octave or decade
//!     on the fine grid and keeps the coarsest grid point whose error, and that of the next
//!     three finer points, are all ≤ `1e-8` (the error is not exactly monotone in the setting).
//!     A run that fails (an implicit solve that does not converge at a large step) counts as
//!     not meeting the target. The grid ends at tolerance `1e-15` and at 2²⁰ steps (and, as a
//!     safety net, after a single run longer than 30 s): a run that met the target without
//!     three finer grid points to confirm it is kept and marked `met, not confirmed` (this is
//!     `lgvi`, order 2, which needs about 10⁶ steps); a solver with no such run is marked
//!     `NOT REACHED` and criterion times its finest run.
//!   * Before criterion measures, the bench prints a table (solver, setting, steps, right-hand
//!     side evaluations, error, error one grid point coarser, wall time) and then the best of
//!     ours, the best peer and `ratio best-peer / best-ours` (above 1: ours is faster). The
//!     wall time, by `std::time::Instant`, is the median of 11 samples (3 for a run over 1 s),
//!     a sample being the mean of enough back-to-back runs to last 20 ms; the solvers take
//!     turns sample by sample, so that load from other processes falls on all of them alike.
//!     Criterion then measures every solver at its chosen setting. The search runs once, when
//!     the first benchmark of the group runs, so a filter that excludes the group skips it.
//!
//! - `peers/<scene>`: tumble's explicit pairs against the best methods of the peer crates at
//!   errors 1e-6 … 1e-12 on `free-hoop` and `free-body` (module [`peers`]).
//!
//! Run: `cargo bench --bench work_precision` (`-- free-hoop-1e-8` for the second group only,
//! `-- scene-step` for the first, `-- peers` for the peer comparison; a bare `-- free-hoop`
//! also matches `scene-step/free-hoop/…` and `peers/free-hoop`).

#[path = "groups/peers.rs"]
mod peers;

use std::cell::OnceCell;
use std::collections::BTreeMap;
use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use tumble_integrators::{Ode, registry};
use tumble_scenarios::scene::Discard;
use tumble_scenarios::scenes::free_hoop::{
    self, Flat, FlatFreeHoop, FreeHoop, FreeHoopScene, flatten,
};
use tumble_scenarios::{Observe, Params, Scene, StepControl};
use tumble_studies::work_precision::{self, FinalState, Reference, state_error};

// ---------------------------------------------------------------------------------------------
// scene-step

/// Fixed steps per run (and the horizon in units of the scene's default step).
const SCENE_STEPS: u32 = 200;
/// Tolerance of the adaptive methods in `scene-step`.
const SCENE_TOL: f64 = 1e-8;

/// Whether the registry marks `integrator` adaptive (`dp5`, `dop853`).
fn is_adaptive(integrator: &str) -> Result<bool, String> {
    registry::find(integrator)
        .map(|m| m.properties.adaptive)
        .map_err(|e| e.to_string())
}

fn bench_scene_steps(c: &mut Criterion) {
    let mut g = c.benchmark_group("scene-step");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(1))
        .warm_up_time(Duration::from_millis(500));
    for &scene in tumble_scenarios::scenes::builtin() {
        let info = scene.info();
        let params = info.default_params();
        for integrator in info.integrators() {
            let id = format!("{}/{integrator}", info.name);
            let step = match is_adaptive(integrator) {
                Ok(true) => StepControl::Tolerance(SCENE_TOL),
                Ok(false) => StepControl::Fixed(info.default_step),
                Err(e) => {
                    eprintln!("scene-step/{id}: skipped: {e}");
                    continue;
                }
            };
            let plan = match work_precision::plan(
                info,
                integrator,
                step,
                f64::from(SCENE_STEPS) * info.default_step,
                Observe::Ends,
            ) {
                Ok(plan) => plan,
                Err(e) => {
                    eprintln!("scene-step/{id}: skipped: {e}");
                    continue;
                }
            };
            // One run for the step count (and to skip a pair that fails).
            let steps = match scene.simulate(&params, &plan, &mut Discard) {
                Ok(summary) => summary.steps,
                Err(e) => {
                    eprintln!("scene-step/{id}: skipped, the run failed: {e}");
                    continue;
                }
            };
            g.throughput(Throughput::Elements(steps.max(1)));
            g.bench_function(&id, |b| {
                b.iter(|| {
                    scene
                        .simulate(black_box(&params), &plan, &mut Discard)
                        .expect("scene run")
                })
            });
        }
    }
    g.finish();
}

// ---------------------------------------------------------------------------------------------
// free-hoop-1e-8

/// Horizon of the acceptance test (s).
const HOOP_T_END: f64 = 10.0;
/// Target error at the final time.
const TARGET: f64 = 1e-8;
/// Timed samples per solver (the median is reported); [`LONG_SAMPLES`] for runs over 1 s.
const TIMED_RUNS: usize = 11;
/// Timed samples of a solver whose run takes more than 1 s.
const LONG_SAMPLES: usize = 3;
/// A timed sample repeats a short run until it lasts this long (s).
const MIN_SAMPLE_SECONDS: f64 = 0.02;
/// Finer grid points that must meet the target too.
const CONFIRM: i32 = 3;
/// Grid points per factor 10 (tolerances) or 2 (steps).
const PER_OCTAVE: i32 = 8;
/// Most fixed steps the search tries (2²⁰).
const MAX_STEPS_K: i32 = 20 * PER_OCTAVE;
/// Smallest tolerance the search tries (`1e-15`).
const MIN_TOL_K: i32 = 15 * PER_OCTAVE;
/// A safety net: a single run longer than this ends the search (s).
const MAX_RUN_SECONDS: f64 = 30.0;
/// Our candidate methods.
const OURS: [&str; 12] = [
    "dop853",
    "vern8",
    "gauss6",
    "gauss8",
    "gauss10",
    "gauss12",
    "rk4",
    "lgvi",
    "lgvi8",
    "lie-gauss6",
    "lie-gauss8",
    "lie-gauss10",
];

/// The free hoop's right-hand side in the peer crates' traits.
#[derive(Debug, Clone, Copy)]
struct PeerHoop(FlatFreeHoop);

/// `ode_solvers` state (its nalgebra is 0.34, ours 0.35: plain numbers cross the boundary).
type PeerVector = ode_solvers::SVector<f64, 14>;

impl differential_equations::prelude::ODE<f64, [f64; 14]> for PeerHoop {
    fn diff(&self, t: f64, y: &[f64; 14], dy: &mut [f64; 14]) {
        let mut out = Flat::zeros();
        self.0.rhs(t, &Flat::from(*y), &mut out);
        dy.copy_from_slice(out.as_slice());
    }
}

impl ode_solvers::System<f64, PeerVector> for PeerHoop {
    fn system(&self, t: f64, y: &PeerVector, dy: &mut PeerVector) {
        let mut out = Flat::zeros();
        self.0
            .rhs(t, &Flat::from_column_slice(y.as_slice()), &mut out);
        dy.copy_from_slice(out.as_slice());
    }
}

/// A solver of the acceptance test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Solver {
    /// One of [`OURS`], through `Scene::simulate`.
    Ours(&'static str),
    /// DOP853 of `differential-equations`.
    DiffEq,
    /// DOP853 of `ode_solvers`.
    OdeSolvers,
}

impl Solver {
    fn all() -> Vec<Solver> {
        OURS.iter()
            .map(|&m| Solver::Ours(m))
            .chain([Solver::DiffEq, Solver::OdeSolvers])
            .collect()
    }

    fn name(self) -> String {
        match self {
            Solver::Ours(m) => format!("tumble-{m}"),
            Solver::DiffEq => "differential-equations-dop853".into(),
            Solver::OdeSolvers => "ode_solvers-dop853".into(),
        }
    }

    fn is_peer(self) -> bool {
        !matches!(self, Solver::Ours(_))
    }

    fn adaptive(self) -> bool {
        match self {
            Solver::Ours(m) => is_adaptive(m).expect("our methods are in the registry"),
            Solver::DiffEq | Solver::OdeSolvers => true,
        }
    }
}

/// A point of the search grid.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Setting {
    /// rtol = atol.
    Tol(f64),
    /// Fixed steps of `t_end / n`.
    Steps(u64),
}

impl Setting {
    /// Grid point `k`: `10^(−k/8)` or `round(2^(k/8))` steps.
    fn at(adaptive: bool, k: i32) -> Setting {
        let x = f64::from(k) / f64::from(PER_OCTAVE);
        if adaptive {
            Setting::Tol(10f64.powf(-x))
        } else {
            Setting::Steps(2f64.powf(x).round().max(1.0) as u64)
        }
    }

    fn control(self) -> StepControl {
        match self {
            Setting::Tol(tol) => StepControl::Tolerance(tol),
            Setting::Steps(n) => StepControl::Fixed(HOOP_T_END / n as f64),
        }
    }

    fn describe(self) -> String {
        match self {
            Setting::Tol(tol) => format!("tol {tol:.2e}"),
            Setting::Steps(n) => format!("n {n} (h {:.2e})", HOOP_T_END / n as f64),
        }
    }
}

/// A run's final state and cost.
#[derive(Debug, Clone)]
struct Outcome {
    state: FinalState,
    steps: u64,
    evaluations: u64,
}

/// One run of the search.
#[derive(Debug, Clone)]
struct Trial {
    setting: Setting,
    /// `(error, steps, evaluations)`, or why the run failed.
    result: Result<(f64, u64, u64), String>,
}

impl Trial {
    fn passes(&self) -> bool {
        self.result.as_ref().is_ok_and(|r| r.0 <= TARGET)
    }

    fn error(&self) -> Option<f64> {
        self.result.as_ref().ok().map(|r| r.0)
    }
}

/// A solver's chosen setting and its timing.
#[derive(Debug, Clone)]
struct Choice {
    solver: Solver,
    /// The chosen run; when the target was not reached, the finest run that succeeded.
    trial: Option<Trial>,
    /// The chosen run meets the target.
    reached: bool,
    /// The chosen run meets the target but the search stopped before confirming it (the
    /// finer points unchecked, or a cheaper point in its octave not scanned).
    unconfirmed: bool,
    /// The next coarser grid point's run.
    coarser: Option<Trial>,
    /// Median wall time of a run ([`Hoop::time_all`]) (s).
    seconds: f64,
    /// Why the search stopped without reaching the target.
    note: String,
}

/// The free hoop at its default parameters and its reference.
struct Hoop {
    params: Params,
    model: FreeHoop,
    peer: PeerHoop,
    y0: Flat,
    reference: Reference,
}

impl Hoop {
    fn new() -> Hoop {
        let scene = FreeHoopScene;
        let params = scene.info().default_params();
        let (model, s0) = FreeHoopScene::model(&params).expect("free-hoop model");
        let peer = PeerHoop(FlatFreeHoop::new(model).expect("flat free hoop"));
        let reference =
            work_precision::reference(&scene, &params, HOOP_T_END).expect("free-hoop reference");
        Hoop {
            params,
            model,
            peer,
            y0: flatten(&s0),
            reference,
        }
    }

    fn run(&self, solver: Solver, setting: Setting) -> Result<Outcome, String> {
        match (solver, setting) {
            (Solver::Ours(m), _) => self.ours(m, setting),
            (Solver::DiffEq, Setting::Tol(tol)) => self.diffeq(tol),
            (Solver::OdeSolvers, Setting::Tol(tol)) => self.odesolvers(tol),
            (_, Setting::Steps(_)) => Err("a peer DOP853 takes a tolerance".into()),
        }
    }

    fn ours(&self, method: &str, setting: Setting) -> Result<Outcome, String> {
        let plan = work_precision::plan(
            FreeHoopScene.info(),
            method,
            setting.control(),
            HOOP_T_END,
            Observe::Ends,
        )
        .map_err(|e| e.to_string())?;
        let (state, summary) = work_precision::final_state(&FreeHoopScene, &self.params, &plan)
            .map_err(|e| e.to_string())?;
        Ok(Outcome {
            state,
            steps: summary.steps,
            evaluations: summary.evaluations,
        })
    }

    fn diffeq(&self, tol: f64) -> Result<Outcome, String> {
        use differential_equations::prelude::*;
        let mut y0 = [0.0; 14];
        y0.copy_from_slice(self.y0.as_slice());
        let sol = IVP::ode(&self.peer, 0.0, HOOP_T_END, y0)
            .method(ExplicitRungeKutta::dop853().rtol(tol).atol(tol))
            .t_eval([HOOP_T_END])
            .solve()
            .map_err(|e| format!("differential-equations DOP853: {e:?}"))?;
        let (Some(&t), Some(y)) = (sol.t.last(), sol.y.last()) else {
            return Err("differential-equations DOP853: no output".into());
        };
        Ok(Outcome {
            state: free_hoop::final_state(&self.model, t, &Flat::from(*y)),
            steps: sol.steps.accepted as u64,
            evaluations: sol.evals.function as u64,
        })
    }

    fn odesolvers(&self, tol: f64) -> Result<Outcome, String> {
        let y0 = PeerVector::from_column_slice(self.y0.as_slice());
        // Hairer's defaults (safety 0.9, β = 0, factors 0.333 … 6), automatic first step,
        // output at every accepted step (as in benches/integrators.rs).
        let mut s = ode_solvers::Dop853::from_param(
            self.peer,
            0.0,
            HOOP_T_END,
            HOOP_T_END,
            y0,
            tol,
            tol,
            0.9,
            0.0,
            0.333,
            6.0,
            HOOP_T_END,
            0.0,
            10_000_000,
            1000,
            ode_solvers::OutputType::Sparse,
        );
        let stats = s
            .integrate()
            .map_err(|e| format!("ode_solvers DOP853: {e:?}"))?;
        let (Some(&t), Some(y)) = (s.x_out().last(), s.y_out().last()) else {
            return Err("ode_solvers DOP853: no output".into());
        };
        Ok(Outcome {
            state: free_hoop::final_state(&self.model, t, &Flat::from_column_slice(y.as_slice())),
            steps: u64::from(stats.accepted_steps),
            evaluations: u64::from(stats.num_eval),
        })
    }

    /// One run's error and cost, and its wall time (s).
    fn trial(&self, solver: Solver, setting: Setting) -> (Trial, f64) {
        let start = Instant::now();
        let outcome = self.run(solver, setting);
        let seconds = start.elapsed().as_secs_f64();
        let info = FreeHoopScene.info();
        let result = outcome.map(|o| {
            (
                state_error(info, &o.state, &self.reference.state),
                o.steps,
                o.evaluations,
            )
        });
        (Trial { setting, result }, seconds)
    }

    /// Wall time of `reps` back-to-back runs, per run (s).
    fn time(&self, solver: Solver, setting: Setting, reps: u32) -> f64 {
        let start = Instant::now();
        for _ in 0..reps {
            let _ = black_box(self.run(solver, black_box(setting)));
        }
        start.elapsed().as_secs_f64() / f64::from(reps)
    }

    /// Sets each choice's time: the median of [`TIMED_RUNS`] samples ([`LONG_SAMPLES`] for a
    /// run over 1 s), a sample being the mean of enough back-to-back runs to last
    /// [`MIN_SAMPLE_SECONDS`]. The solvers take turns, one sample each per round, so that load
    /// from other processes falls on all of them alike.
    fn time_all(&self, choices: &mut [Choice]) {
        let plans: Vec<Option<(Setting, u32, usize)>> = choices
            .iter()
            .map(|c| {
                let setting = c.trial.as_ref()?.setting;
                let once = self.time(c.solver, setting, 1);
                let reps = (MIN_SAMPLE_SECONDS / once).ceil().clamp(1.0, 10_000.0) as u32;
                let samples = if once > 1.0 { LONG_SAMPLES } else { TIMED_RUNS };
                Some((setting, reps, samples))
            })
            .collect();
        let mut samples: Vec<Vec<f64>> = vec![Vec::new(); choices.len()];
        for round in 0..TIMED_RUNS {
            for (i, c) in choices.iter().enumerate() {
                if let Some((setting, reps, n)) = plans[i]
                    && round < n
                {
                    samples[i].push(self.time(c.solver, setting, reps));
                }
            }
        }
        for (c, mut s) in choices.iter_mut().zip(samples) {
            s.sort_by(f64::total_cmp);
            c.seconds = s.get(s.len() / 2).copied().unwrap_or(f64::NAN);
        }
    }

    /// The search of the module doc for `solver`.
    fn choose(&self, solver: Solver) -> Choice {
        let adaptive = solver.adaptive();
        // Grid bounds: tolerances 1e-1 … 1e-15, steps 1 … 2^20; the search starts at 1e-3 or
        // 16 steps.
        let (k_min, k_start, k_max) = if adaptive {
            (PER_OCTAVE, 3 * PER_OCTAVE, MIN_TOL_K)
        } else {
            (0, 4 * PER_OCTAVE, MAX_STEPS_K)
        };
        let mut trials: BTreeMap<i32, Trial> = BTreeMap::new();
        let mut stopped: Option<String> = None;
        // Whether grid point k meets the target; `None`: not run (beyond the grid or the time
        // budget).
        let mut passes = |k: i32| -> Option<bool> {
            if let Some(t) = trials.get(&k) {
                return Some(t.passes());
            }
            if k < k_min || k > k_max {
                stopped.get_or_insert_with(|| {
                    format!(
                        "grid ends at {}",
                        Setting::at(adaptive, k.clamp(k_min, k_max)).describe()
                    )
                });
                return None;
            }
            if stopped.is_some() {
                return None;
            }
            let (trial, seconds) = self.trial(solver, Setting::at(adaptive, k));
            if seconds > MAX_RUN_SECONDS {
                stopped = Some(format!(
                    "a run ({}) took {seconds:.1} s",
                    trial.setting.describe()
                ));
            }
            let ok = trial.passes();
            trials.insert(k, trial);
            Some(ok)
        };
        let chosen = 'search: {
            // Finer by octaves until the target is met.
            let mut k = k_start;
            loop {
                match passes(k) {
                    Some(true) => break,
                    Some(false) => k += PER_OCTAVE,
                    None => break 'search None,
                }
            }
            // Coarser by octaves while it is still met.
            while k - PER_OCTAVE >= k_min && passes(k - PER_OCTAVE) == Some(true) {
                k -= PER_OCTAVE;
            }
            // The coarsest fine-grid point after the last failing octave that meets the target
            // together with the next CONFIRM finer points.
            let from = if k - PER_OCTAVE >= k_min {
                k - PER_OCTAVE + 1
            } else {
                k_min
            };
            for j in from..=k_max {
                let mut all = true;
                for i in j..=j + CONFIRM {
                    match passes(i) {
                        Some(true) => {}
                        Some(false) => {
                            all = false;
                            break;
                        }
                        None => break 'search None,
                    }
                }
                if all {
                    break 'search Some(j);
                }
            }
            None
        };
        // Without a confirmed choice: the coarsest run that met the target anyway (the search
        // ran out of time after it), else the finest run that succeeded.
        let (trial, reached, unconfirmed, coarser) = match chosen {
            Some(j) => (
                trials.get(&j).cloned(),
                true,
                false,
                trials.get(&(j - 1)).cloned(),
            ),
            None => match trials.iter().find(|(_, t)| t.passes()) {
                Some((&j, t)) => (Some(t.clone()), true, true, trials.get(&(j - 1)).cloned()),
                None => (
                    trials.values().rev().find(|t| t.result.is_ok()).cloned(),
                    false,
                    false,
                    None,
                ),
            },
        };
        Choice {
            solver,
            trial,
            reached,
            unconfirmed,
            coarser,
            seconds: f64::NAN,
            note: stopped.unwrap_or_default(),
        }
    }
}

/// The table, the best of ours and of the peers, and their ratio.
fn report(hoop: &Hoop, choices: &[Choice]) {
    let r = &hoop.reference;
    eprintln!();
    eprintln!(
        "free-hoop (default parameters), t_end = {HOOP_T_END} s: cheapest setting with final-time error <= {TARGET:e}"
    );
    eprintln!("  reference: {}", r.method);
    eprintln!(
        "  cross-check {}: agreement {:.2e}; self-check {}: {:.2e}",
        r.check, r.agreement, r.self_check, r.self_agreement
    );
    eprintln!(
        "  {:<30} {:<22} {:>9} {:>11} {:>9} {:>9} {:>11}",
        "solver", "setting", "steps", "RHS evals", "error", "coarser", "median ms"
    );
    for c in choices {
        let name = c.solver.name();
        let Some(t) = &c.trial else {
            eprintln!("  {name:<30} no successful run ({})", c.note);
            continue;
        };
        let (error, steps, evaluations) = t.result.clone().expect("successful trial");
        let coarser = c
            .coarser
            .as_ref()
            .map_or("-".to_string(), |t| match t.error() {
                Some(e) => format!("{e:.2e}"),
                None => "failed".to_string(),
            });
        eprintln!(
            "  {name:<30} {:<22} {steps:>9} {evaluations:>11} {error:>9.2e} {coarser:>9} {:>11.3}{}",
            t.setting.describe(),
            c.seconds * 1e3,
            if !c.reached {
                format!("  NOT REACHED ({})", c.note)
            } else if c.unconfirmed {
                format!("  met, not confirmed ({})", c.note)
            } else {
                String::new()
            }
        );
    }
    eprintln!(
        "  (the variational methods lgvi, lgvi8 and lie-gauss* have no right-hand side: their \"RHS evals\" are their steps; \"coarser\" is the error one grid point coarser)"
    );
    let best = |peer: bool| {
        choices
            .iter()
            .filter(|c| c.reached && c.solver.is_peer() == peer)
            .min_by(|a, b| a.seconds.total_cmp(&b.seconds))
    };
    let describe = |c: Option<&Choice>| match c {
        Some(c) => format!(
            "{} ({}), {:.3} ms",
            c.solver.name(),
            c.trial
                .as_ref()
                .map_or(String::new(), |t| t.setting.describe()),
            c.seconds * 1e3
        ),
        None => "none reached the target".into(),
    };
    let (ours, peer) = (best(false), best(true));
    eprintln!("best ours: {}", describe(ours));
    eprintln!("best peer: {}", describe(peer));
    if let (Some(o), Some(p)) = (ours, peer) {
        let ratio = p.seconds / o.seconds;
        eprintln!(
            "ratio best-peer / best-ours = {ratio:.3} ({})",
            if ratio > 1.0 {
                "ours is faster"
            } else {
                "ours is SLOWER than the best peer"
            }
        );
    }
    // Each of ours against our DOP853, from the same interleaved samples.
    if let Some(dop) = choices
        .iter()
        .find(|c| c.reached && c.solver == Solver::Ours("dop853"))
    {
        let ratios: Vec<String> = choices
            .iter()
            .filter(|c| c.reached && !c.solver.is_peer() && c.solver != Solver::Ours("dop853"))
            .map(|c| format!("{} {:.2}", c.solver.name(), c.seconds / dop.seconds))
            .collect();
        eprintln!("time / ours dop853: {}", ratios.join(", "));
    }
    eprintln!();
}

fn bench_free_hoop(c: &mut Criterion) {
    let solvers = Solver::all();
    // The search and the table run when the first benchmark of the group does (a filter that
    // excludes the group skips them).
    let cell: OnceCell<(Hoop, Vec<Choice>)> = OnceCell::new();
    let study = || {
        cell.get_or_init(|| {
            let hoop = Hoop::new();
            let mut choices: Vec<Choice> = solvers.iter().map(|&s| hoop.choose(s)).collect();
            hoop.time_all(&mut choices);
            report(&hoop, &choices);
            (hoop, choices)
        })
    };
    let mut g = c.benchmark_group("free-hoop-1e-8");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    for (i, &solver) in solvers.iter().enumerate() {
        g.bench_function(solver.name(), |b| {
            let (hoop, choices) = study();
            let choice = &choices[i];
            let Some(trial) = &choice.trial else {
                eprintln!("{}: no successful run to measure", solver.name());
                b.iter(|| ());
                return;
            };
            if !choice.reached {
                eprintln!(
                    "{}: target not reached; measuring its finest run ({})",
                    solver.name(),
                    trial.setting.describe()
                );
            }
            let setting = trial.setting;
            b.iter(|| hoop.run(solver, black_box(setting)).expect("run"));
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    bench_scene_steps,
    bench_free_hoop,
    peers::bench_peers
);
criterion_main!(benches);
