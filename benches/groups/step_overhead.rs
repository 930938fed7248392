//! `step-overhead/<scene>/…`: the cost of one step of each explicit Runge–Kutta method against
//! the cost of its right-hand-side evaluations alone, on the flattened equations of
//! `free-hoop` (`ℝ¹⁴`) and `free-body` (`ℝ¹²`) at their default parameters.
//!
//! - `rhs`: one evaluation of the right-hand side, at each of the states a run passes through
//!   in turn (passed through `black_box`): independent evaluations, which the processor
//!   overlaps (throughput);
//! - `rhs-chained`: the same evaluations, each argument depending on the previous result
//!   through one multiply–add, as the stages of a step do (latency; [`rhs_chained`]);
//! - `<method>`: one step of `h` = the scene's default step (0.01), 1000 steps from the initial
//!   state through `Stepper::step` (fixed steps, the FSAL stage reused), and
//!   `<method>-adaptive`: `attempt` + `accept`, the step of an adaptive run including its
//!   error estimate and norm (always accepted here; the step is fixed so that both count the
//!   same evaluations).
//!
//! Before criterion measures, a table is printed: evaluations per step (counted by a
//! wrapper), ns per step, and `overhead = step time / (evaluations × RHS time) − 1`, against
//! both RHS times. The stages of an explicit step are sequential, so the chained time is the
//! floor a step's evaluations can reach; the independent time is the lower figure a
//! right-hand side shows on its own. The times
//! are the fastest of 21 samples of at least 5 ms each, the entries taking turns sample by
//! sample: on a shared machine the fastest sample is the one least disturbed by other
//! processes (medians moved by up to a factor 2 between two runs under a load of 5–8 on 2
//! cores).

use std::cell::{Cell, OnceCell};
use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkGroup, Criterion, Throughput, measurement::WallTime};
use nalgebra::{Rotation3, SVector, Vector3};
use tumble_integrators::registry::{self, Stepping, build, build::ReceiveOde};
use tumble_integrators::rigid::{FreeRigidBody, RigidBodyState};
use tumble_integrators::{
    AdaptiveStepper, DenseOutput, ExplicitRungeKutta, Ode, Stepper, Tolerances,
};
use tumble_scenarios::Scene;
use tumble_scenarios::scenes::free_hoop::{self, FlatFreeHoop, FreeHoopScene};
use tumble_scenarios::scenes::rigid::{self, FlatRigidBody};

/// Steps per timed run.
const STEPS: u32 = 1000;
/// Step size (the default step of both scenes).
const H: f64 = 0.01;
/// Samples per entry (the fastest is reported).
const SAMPLES: usize = 21;
/// A sample repeats its run until it lasts this long (s).
const MIN_SAMPLE_SECONDS: f64 = 0.005;

/// The methods measured: every explicit Runge–Kutta method of the registry, and whether it
/// has an embedded error estimate.
pub fn methods() -> Vec<(&'static str, bool)> {
    registry::methods()
        .iter()
        .filter(|m| matches!(m.stepping, Stepping::Explicit(_)))
        .map(|m| (m.name, m.properties.adaptive))
        .collect()
}

/// `problem` counting its evaluations.
struct Counting<'a, P> {
    inner: &'a P,
    calls: Cell<u64>,
}

impl<const N: usize, P: Ode<SVector<f64, N>>> Ode<SVector<f64, N>> for Counting<'_, P> {
    fn rhs(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        self.calls.set(self.calls.get() + 1);
        self.inner.rhs(t, y, dy);
    }
}

/// Runs `STEPS` steps of the stepper the registry builds from `y0`; `adaptive`: through
/// `attempt` + `accept`.
struct Steps<'a, P, const N: usize> {
    problem: &'a P,
    y0: &'a SVector<f64, N>,
    adaptive: bool,
}

impl<P: Ode<SVector<f64, N>>, const N: usize> ReceiveOde<P, SVector<f64, N>> for Steps<'_, P, N> {
    type Output = SVector<f64, N>;
    fn adaptive<St: AdaptiveStepper<P, State = SVector<f64, N>> + DenseOutput<P>>(
        self,
        mut st: St,
    ) -> Self::Output {
        let mut y = *self.y0;
        let tol = Tolerances::new(1.0, 1.0).expect("tolerances");
        let mut t = 0.0;
        for k in 0..STEPS {
            if self.adaptive {
                let err = st.attempt(self.problem, t, &y, H, &tol).expect("attempt");
                black_box(err);
                st.accept(self.problem, t, &mut y, H);
            } else {
                st.step(self.problem, t, &mut y, H).expect("step");
            }
            t = f64::from(k + 1) * H;
        }
        y
    }
    fn interpolating<St: DenseOutput<P, State = SVector<f64, N>>>(self, st: St) -> Self::Output {
        fixed_steps(st, self.problem, self.y0)
    }
    fn plain<St: Stepper<P, State = SVector<f64, N>> + Clone>(self, st: St) -> Self::Output {
        fixed_steps(st, self.problem, self.y0)
    }
}

/// `STEPS` fixed steps of `st` from `y0`.
fn fixed_steps<const N: usize, P, St: Stepper<P, State = SVector<f64, N>>>(
    mut st: St,
    problem: &P,
    y0: &SVector<f64, N>,
) -> SVector<f64, N> {
    let mut y = *y0;
    for k in 0..STEPS {
        st.step(problem, f64::from(k) * H, &mut y, H).expect("step");
    }
    y
}

/// Runs `STEPS` steps of the registry's method `name` (see [`methods`]).
fn run_named<const N: usize, P: Ode<SVector<f64, N>>>(
    name: &str,
    problem: &P,
    y0: &SVector<f64, N>,
    adaptive: bool,
) -> SVector<f64, N> {
    let method = registry::find(name).expect("a registry method");
    build::ode(
        method,
        y0,
        Steps {
            problem,
            y0,
            adaptive,
        },
    )
    .expect("an explicit method")
}

/// The `STEPS + 1` states of an RK4 run of `STEPS` steps from `y0` (the states the timed
/// steps pass through, to a step's local error).
fn trajectory<const N: usize, P: Ode<SVector<f64, N>>>(
    problem: &P,
    y0: &SVector<f64, N>,
) -> Vec<SVector<f64, N>> {
    let mut y = *y0;
    let mut st = ExplicitRungeKutta::rk4().stepper(&y);
    let mut out = vec![y];
    for k in 0..STEPS {
        st.step(problem, f64::from(k) * H, &mut y, H).expect("step");
        out.push(y);
    }
    out
}

/// `STEPS` evaluations of the right-hand side, one at each state along the trajectory (the
/// cost of an evaluation depends on the state: at the initial state of `free-hoop` it is
/// about half of that along the run).
fn rhs_only<const N: usize, P: Ode<SVector<f64, N>>>(problem: &P, states: &[SVector<f64, N>]) {
    let mut dy = SVector::<f64, N>::zeros();
    for (k, y) in states.iter().take(STEPS as usize).enumerate() {
        problem.rhs(k as f64 * H, black_box(y), &mut dy);
        black_box(&mut dy);
    }
}

/// The same `STEPS` evaluations in a dependent chain: each argument is the trajectory's state
/// plus `0 ×` the previous result, so an evaluation cannot start before the previous one has
/// finished (`0 × x` is not folded away in floating point). The stages of an explicit
/// Runge–Kutta step form such a chain (stage `i` needs `kᵢ₋₁`), with one multiply–add between
/// evaluations at least, which this chain has too: its time per evaluation is the latency
/// of an evaluation, where [`rhs_only`] measures its throughput (consecutive evaluations
/// overlap in the processor).
fn rhs_chained<const N: usize, P: Ode<SVector<f64, N>>>(problem: &P, states: &[SVector<f64, N>]) {
    let mut dy = SVector::<f64, N>::zeros();
    for (k, y) in states.iter().take(STEPS as usize).enumerate() {
        let arg = black_box(y) + 0.0 * dy;
        problem.rhs(k as f64 * H, &arg, &mut dy);
    }
    black_box(&mut dy);
}

/// One timed entry: a label, evaluations per step, and the run.
pub struct Entry<'a> {
    pub label: String,
    pub evaluations: f64,
    pub run: Box<dyn Fn() + 'a>,
}

/// Fastest time of `run` per call (s), with every entry sampled in turns.
pub fn time_all(entries: &[Entry<'_>]) -> Vec<f64> {
    let reps: Vec<u32> = entries
        .iter()
        .map(|e| {
            let start = Instant::now();
            (e.run)();
            let once = start.elapsed().as_secs_f64();
            (MIN_SAMPLE_SECONDS / once).ceil().clamp(1.0, 100_000.0) as u32
        })
        .collect();
    let mut samples = vec![Vec::with_capacity(SAMPLES); entries.len()];
    for _ in 0..SAMPLES {
        for (i, e) in entries.iter().enumerate() {
            let start = Instant::now();
            for _ in 0..reps[i] {
                (e.run)();
            }
            samples[i].push(start.elapsed().as_secs_f64() / f64::from(reps[i]));
        }
    }
    samples
        .into_iter()
        .map(|mut s| {
            s.sort_by(f64::total_cmp);
            s[0]
        })
        .collect()
}

/// The table for one scene, then the criterion entries.
fn scene<const N: usize, P: Ode<SVector<f64, N>>>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    scene: &str,
    problem: &P,
    y0: &SVector<f64, N>,
) {
    let states = trajectory(problem, y0);
    let mut entries = vec![
        Entry {
            label: "rhs".into(),
            evaluations: 1.0,
            run: Box::new(|| rhs_only(problem, &states)),
        },
        Entry {
            label: "rhs-chained".into(),
            evaluations: 1.0,
            run: Box::new(|| rhs_chained(problem, &states)),
        },
    ];
    for (name, embedded) in methods() {
        for adaptive in [false, true] {
            if adaptive && !embedded {
                continue;
            }
            let counting = Counting {
                inner: problem,
                calls: Cell::new(0),
            };
            run_named(name, &counting, y0, adaptive);
            entries.push(Entry {
                label: if adaptive {
                    format!("{name}-adaptive")
                } else {
                    name.to_string()
                },
                evaluations: counting.calls.get() as f64 / f64::from(STEPS),
                run: Box::new(move || {
                    black_box(run_named(name, problem, y0, adaptive));
                }),
            });
        }
    }
    // The table is measured and printed by the first of this scene's entries that criterion
    // runs, so a filter that excludes them all skips it.
    let report = || {
        let times = time_all(&entries);
        let per = |i: usize| times[i] / f64::from(STEPS);
        let (rhs, chained) = (per(0), per(1));
        eprintln!();
        eprintln!(
            "step-overhead/{scene} (dimension {N}, h = {H}, {STEPS} steps a run): RHS {:.1} ns \
             independent, {:.1} ns chained",
            rhs * 1e9,
            chained * 1e9
        );
        eprintln!(
            "  {:<18} {:>10} {:>11} {:>14} {:>9} {:>14} {:>9}",
            "method", "RHS/step", "ns/step", "ns of RHS", "overhead", "ns chained", "overhead"
        );
        for (i, e) in entries.iter().enumerate().skip(2) {
            let rhs_part = e.evaluations * rhs;
            let chained_part = e.evaluations * chained;
            eprintln!(
                "  {:<18} {:>10.2} {:>11.1} {:>14.1} {:>8.1}% {:>14.1} {:>8.1}%",
                e.label,
                e.evaluations,
                per(i) * 1e9,
                rhs_part * 1e9,
                (per(i) / rhs_part - 1.0) * 100.0,
                chained_part * 1e9,
                (per(i) / chained_part - 1.0) * 100.0
            );
        }
    };
    let done = OnceCell::new();
    g.throughput(Throughput::Elements(u64::from(STEPS)));
    for e in &entries {
        g.bench_function(format!("{scene}/{}", e.label), |b| {
            done.get_or_init(&report);
            b.iter(|| (e.run)());
        });
    }
}

/// The `step-overhead` group.
pub fn bench_step_overhead(c: &mut Criterion) {
    let mut g = c.benchmark_group("step-overhead");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(1))
        .warm_up_time(Duration::from_millis(300));
    let params = FreeHoopScene.info().default_params();
    let (model, s0) = FreeHoopScene::model(&params).expect("free-hoop model");
    let hoop = FlatFreeHoop::new(model).expect("flat free hoop");
    scene(&mut g, "free-hoop", &hoop, &free_hoop::flatten(&s0));
    let body =
        FreeRigidBody::from_principal_moments(Vector3::new(1.0, 2.0, 3.0)).expect("free body");
    let s0 = RigidBodyState::new(&Rotation3::identity(), Vector3::new(0.4, -0.8, 0.6));
    scene(
        &mut g,
        "free-body",
        &FlatRigidBody(body),
        &rigid::flatten(&s0),
    );
    g.finish();
}
