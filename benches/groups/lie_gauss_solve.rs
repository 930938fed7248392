//! `lie-gauss-solve/free-hoop/<method>`: where a step of the variational Lie–Gauss methods goes
//! on `free-hoop` (the body coupled to the bead, default parameters), at the fixed step each
//! method needs to reach a final-time error of 1e-8 at t = 10 s (`tumble work-precision
//! free-hoop`: 893, 138, 53 and 30 steps for `lie-gauss4` … `lie-gauss10`).
//!
//! Before criterion measures the runs, a table is printed per method: the simplified-Newton
//! iterations per step (mean, fewest, most), the model evaluations per step (the kinetic jet,
//! counted by a wrapper: one per stage and iteration, `d = 8` more per Jacobian), the time per
//! step, and the share of that time the model's own evaluations take (kinetic jet and
//! potential derivatives, timed alone at the run's states). The rest is the solver: the chart
//! maps (`exp`, `J_r⁻¹` and its derivative) around each evaluation, the finite-difference
//! Jacobian and its factorizations, and the eigenbasis solves of every iteration. Times are
//! the fastest of 21 samples of at least 5 ms, the evaluation and the methods taking turns
//! (the sampling of `step-overhead`).

use std::cell::{Cell, OnceCell};
use std::hint::black_box;
use std::time::Duration;

use criterion::Criterion;
use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::Stepper;
use tumble_integrators::rigid::coupled::{CoupledLagrangian, KineticBlocks, KineticJet, Scalar};
use tumble_integrators::rigid::{CoupledLieGauss, CoupledState};
use tumble_integrators::tables::GaussTableau;
use tumble_integrators::tables::gauss::{GAUSS4, GAUSS6, GAUSS8, GAUSS10};
use tumble_scenarios::Scene;
use tumble_scenarios::scenes::free_hoop::{FreeHoop, FreeHoopScene};

use crate::step_overhead::{Entry, time_all};

/// Horizon (s).
const T_END: f64 = 10.0;

/// The model counting its kinetic jets (one per stage rate).
struct Counting {
    inner: FreeHoop,
    jets: Cell<u64>,
}

impl CoupledLagrangian<1> for Counting {
    fn kinetic<D: Scalar>(&self, q: &SVector<D, 1>) -> KineticBlocks<D, 1> {
        self.inner.kinetic(q)
    }
    fn potential<D: Scalar>(&self, rotation: &Matrix3<D>, q: &SVector<D, 1>) -> D {
        self.inner.potential(rotation, q)
    }
    fn kinetic_jet(&self, q: &SVector<f64, 1>) -> KineticJet<1> {
        self.jets.set(self.jets.get() + 1);
        self.inner.kinetic_jet(q)
    }
    fn kinetic_hessian(&self, q: &SVector<f64, 1>) -> [[KineticBlocks<f64, 1>; 1]; 1] {
        self.inner.kinetic_hessian(q)
    }
    fn potential_derivatives(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, 1>,
    ) -> (Vector3<f64>, SVector<f64, 1>) {
        self.inner.potential_derivatives(rotation, q)
    }
}

/// What a run reports after each step: its Newton iterations and the state reached.
type Seen<'a> = &'a mut dyn FnMut(usize, &CoupledState<1>);

/// `steps` steps of the `S`-stage method from the scene's initial state, reporting each step
/// to `seen`.
fn run<const S: usize, L: CoupledLagrangian<1>>(
    table: &'static GaussTableau<S>,
    model: &L,
    s0: &CoupledState<1>,
    steps: u32,
    seen: Seen<'_>,
) -> CoupledState<1> {
    let h = T_END / f64::from(steps);
    let mut st = CoupledLieGauss::<S, 1>::new(table);
    let mut s = *s0;
    for k in 0..steps {
        st.step(model, f64::from(k) * h, &mut s, h)
            .expect("lie-gauss step");
        seen(st.last_iterations(), &s);
    }
    s
}

/// Runs method `index` (0 … 3: `lie-gauss4` … `lie-gauss10`).
fn run_index<L: CoupledLagrangian<1>>(
    index: usize,
    model: &L,
    s0: &CoupledState<1>,
    steps: u32,
    seen: Seen<'_>,
) -> CoupledState<1> {
    match index {
        0 => run(&GAUSS4, model, s0, steps, seen),
        1 => run(&GAUSS6, model, s0, steps, seen),
        2 => run(&GAUSS8, model, s0, steps, seen),
        _ => run(&GAUSS10, model, s0, steps, seen),
    }
}

/// The methods and their steps to 1e-8.
const METHODS: [(&str, u32); 4] = [
    ("lie-gauss4", 893),
    ("lie-gauss6", 138),
    ("lie-gauss8", 53),
    ("lie-gauss10", 30),
];

pub fn bench_lie_gauss_solve(c: &mut Criterion) {
    let params = FreeHoopScene.info().default_params();
    let (model, s0) = FreeHoopScene::model(&params).expect("free-hoop model");
    // The model's own work per stage rate, timed alone at the states of a lie-gauss6 run.
    let mut states = Vec::new();
    run_index(1, &model, &s0, METHODS[1].1, &mut |_, s| states.push(*s));
    // Iterations and evaluations per step, counted once.
    let counts: Vec<(f64, usize, usize, f64)> = METHODS
        .iter()
        .enumerate()
        .map(|(index, &(_, steps))| {
            let counting = Counting {
                inner: model,
                jets: Cell::new(0),
            };
            let (mut total, mut fewest, mut most) = (0usize, usize::MAX, 0usize);
            run_index(index, &counting, &s0, steps, &mut |i, _| {
                total += i;
                fewest = fewest.min(i);
                most = most.max(i);
            });
            let n = f64::from(steps);
            (
                total as f64 / n,
                fewest,
                most,
                counting.jets.get() as f64 / n,
            )
        })
        .collect();
    // The evaluation and the runs, timed in turns.
    let mut entries = vec![Entry {
        label: "model evaluation".to_string(),
        evaluations: 1.0,
        run: Box::new(|| {
            for s in &states {
                let jet = model.kinetic_jet(black_box(&s.q));
                let (m, vq) = model.potential_derivatives(black_box(&s.rotation), &s.q);
                black_box((jet.blocks.rotational[(0, 0)], m, vq));
            }
        }),
    }];
    for (index, (&(name, steps), count)) in METHODS.iter().zip(&counts).enumerate() {
        let (model, s0) = (&model, &s0);
        entries.push(Entry {
            label: name.to_string(),
            evaluations: count.3,
            run: Box::new(move || {
                black_box(run_index(index, model, s0, steps, &mut |_, _| {}));
            }),
        });
    }
    // Measured and printed by the first entry criterion runs, so a filter that excludes
    // the group skips it.
    let report = || {
        let times = time_all(&entries);
        let evaluation = times[0] / states.len() as f64;
        println!(
            "lie-gauss-solve/free-hoop: model evaluation (kinetic jet + potential derivatives) {:.1} ns",
            evaluation * 1e9
        );
        println!(
            "  {:<12} {:>6} {:>12} {:>10} {:>12} {:>12}",
            "method", "steps", "iterations", "evals/step", "µs/step", "model share"
        );
        for (index, (&(name, steps), &(mean, fewest, most, per_step))) in
            METHODS.iter().zip(&counts).enumerate()
        {
            let time = times[1 + index] / f64::from(steps);
            let iterations = format!("{mean:.1} ({fewest}–{most})");
            println!(
                "  {:<12} {:>6} {:>12} {:>10.1} {:>12.1} {:>11.1} %",
                name,
                steps,
                iterations,
                per_step,
                time * 1e6,
                100.0 * per_step * evaluation / time
            );
        }
    };
    let done = OnceCell::new();
    let mut g = c.benchmark_group("lie-gauss-solve/free-hoop");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    for (index, &(name, steps)) in METHODS.iter().enumerate() {
        g.bench_function(name, |b| {
            done.get_or_init(&report);
            b.iter(|| run_index(index, &model, &s0, steps, &mut |_, _| {}));
        });
    }
    g.finish();
}
