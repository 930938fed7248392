//! Criterion bench of tumble-integrators on Hairer's rigid-body problem
//! `y' = (−2 y₂y₃, 1.25 y₁y₃, −0.5 y₁y₂)`, `y(0) = (1, 0, 0.9)`.
//!
//! - `step/<method>`: time of 1000 fixed steps of size 0.01 (criterion reports it per element:
//!   ns per step). Runge–Kutta and Gauss–Legendre methods integrate the ODE; symplectic
//!   Euler/Verlet-type methods are not applicable to a non-separable system, so the
//!   compositions use Strang splitting of the rigid body into three exact rotations as their
//!   base method (`strang` itself is listed too).
//! - `dop853/<solver>/<tol>`: the whole integration over t ∈ [0, 20] at rtol = atol = tol by
//!   our DOP853 and DP5 and, side by side in the same run, the DOP853 of the
//!   `differential-equations` and `ode_solvers` crates on the same right-hand side. Before
//!   measuring, the bench prints each solver's error against a Gauss–Legendre reference and
//!   its number of steps.
//!
//! - `rigid/<method>`: time of 1000 fixed steps of size 0.01 of every rigid-body method on a
//!   free asymmetric body (principal moments 1, 2, 3 about rotated axes, so `J` is not
//!   diagonal), in ns per step; before measuring, the bench prints each method's error at
//!   t = 100 (10⁴ steps of 0.01) against the exact elliptic-function solution.
//!
//! - `step-overhead/<scene>/<method>`: per-step cost of every explicit Runge–Kutta method on
//!   the flattened `free-hoop` and `free-body` equations against the cost of its right-hand-side
//!   evaluations alone (module [`step_overhead`]).
//!
//! - `lie-gauss-solve/free-hoop/<method>`: where a step of the variational Lie–Gauss methods
//!   goes on `free-hoop` at the step that reaches 1e-8 (module [`lie_gauss_solve`]).
//!
//! Run: `cargo bench --bench integrators` (`-- rigid` for the rigid-body group only,
//! `-- step-overhead` for the per-step overhead, `-- lie-gauss-solve` for the Lie–Gauss
//! solves).

use std::cell::OnceCell;
use std::hint::black_box;

#[path = "groups/lie_gauss_solve.rs"]
mod lie_gauss_solve;
#[path = "groups/step_overhead.rs"]
mod step_overhead;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::SVector;
use tumble_integrators::tables::composition::ALL;
use tumble_integrators::verification::{RigidBodyEuler, RigidBodySplit, max_abs_diff};
use tumble_integrators::{
    Composition, Driver, ExplicitRungeKutta, Gauss, NoObserver, Splitting, SplittingStepper,
    Stepper, Tolerances, gauss2, gauss4, gauss6, gauss8, gauss10, gauss12,
};

type V3 = SVector<f64, 3>;

const STEPS: u64 = 1000;
const H: f64 = 0.01;

fn run_steps<P: ?Sized, St: Stepper<P, State = V3>>(mut st: St, problem: &P) -> V3 {
    let mut y = V3::from(RigidBodyEuler::INITIAL);
    let mut t = 0.0;
    for k in 0..STEPS {
        st.step(problem, t, &mut y, H).expect("step");
        t = (k + 1) as f64 * H;
    }
    y
}

fn bench_steps(c: &mut Criterion) {
    let rb = RigidBodyEuler::default();
    let y0 = V3::from(RigidBodyEuler::INITIAL);
    let mut g = c.benchmark_group("step");
    g.throughput(Throughput::Elements(STEPS));
    g.bench_function("rk4", |b| {
        b.iter(|| run_steps(ExplicitRungeKutta::rk4().stepper(&y0), black_box(&rb)))
    });
    g.bench_function("dp5", |b| {
        b.iter(|| run_steps(ExplicitRungeKutta::dp5().stepper(&y0), black_box(&rb)))
    });
    g.bench_function("dop853", |b| {
        b.iter(|| run_steps(ExplicitRungeKutta::dop853().stepper(&y0), black_box(&rb)))
    });
    fn gauss<const S: usize>(
        g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
        m: Gauss<S>,
    ) {
        let rb = RigidBodyEuler::default();
        let y0 = V3::from(RigidBodyEuler::INITIAL);
        g.bench_function(m.table.name, |b| {
            b.iter(|| run_steps(m.stepper(&y0), black_box(&rb)))
        });
        let name = format!("{}-newton", m.table.name);
        let newton = m.with_newton();
        g.bench_function(&name, |b| {
            b.iter(|| run_steps(newton.stepper(&y0), black_box(&rb)))
        });
    }
    gauss(&mut g, gauss2());
    gauss(&mut g, gauss4());
    gauss(&mut g, gauss6());
    gauss(&mut g, gauss8());
    gauss(&mut g, gauss10());
    gauss(&mut g, gauss12());
    g.bench_function("strang", |b| {
        b.iter(|| {
            run_steps(
                SplittingStepper::<V3>::new(Splitting::Strang),
                black_box(&RigidBodySplit),
            )
        })
    });
    for table in ALL {
        g.bench_function(table.name, |b| {
            b.iter(|| {
                run_steps(
                    Composition::new(table, SplittingStepper::<V3>::new(Splitting::Strang)),
                    black_box(&RigidBodySplit),
                )
            })
        });
    }
    g.finish();
}

struct PeerRigidBody;

impl differential_equations::prelude::ODE<f64, [f64; 3]> for PeerRigidBody {
    fn diff(&self, _t: f64, y: &[f64; 3], dy: &mut [f64; 3]) {
        dy[0] = -2.0 * y[1] * y[2];
        dy[1] = 1.25 * y[0] * y[2];
        dy[2] = -0.5 * y[0] * y[1];
    }
}

impl ode_solvers::System<f64, ode_solvers::Vector3<f64>> for PeerRigidBody {
    fn system(&self, _t: f64, y: &ode_solvers::Vector3<f64>, dy: &mut ode_solvers::Vector3<f64>) {
        dy[0] = -2.0 * y[1] * y[2];
        dy[1] = 1.25 * y[0] * y[2];
        dy[2] = -0.5 * y[0] * y[1];
    }
}

const T_END: f64 = 20.0;

fn ours<const S: usize>(method: ExplicitRungeKutta<S>, tol: f64) -> (V3, u64) {
    let rb = RigidBodyEuler::default();
    let mut y = V3::from(RigidBodyEuler::INITIAL);
    let mut st = method.stepper(&y);
    let r = Driver::new(0.0, T_END)
        .expect("horizon")
        .run_adaptive(
            &mut st,
            &rb,
            &mut y,
            &Tolerances::new(tol, tol).expect("tol"),
            &mut [],
            &mut NoObserver,
        )
        .expect("integration");
    (y, r.steps)
}

fn diffeq(tol: f64) -> ([f64; 3], usize) {
    use differential_equations::prelude::*;
    let sol = IVP::ode(&PeerRigidBody, 0.0, T_END, RigidBodyEuler::INITIAL)
        .method(ExplicitRungeKutta::dop853().rtol(tol).atol(tol))
        .t_eval([T_END])
        .solve()
        .expect("differential-equations DOP853");
    (*sol.y.last().expect("final state"), sol.steps.accepted)
}

fn odesolvers(tol: f64) -> ([f64; 3], usize) {
    let y0 = ode_solvers::Vector3::new(1.0, 0.0, 0.9);
    // Hairer's defaults (safety 0.9, β = 0, factors 0.333 … 6), automatic first step, output
    // at every accepted step (their dense output at dx = t_end returned a wrong end point).
    let mut s = ode_solvers::Dop853::from_param(
        PeerRigidBody,
        0.0,
        T_END,
        T_END,
        y0,
        tol,
        tol,
        0.9,
        0.0,
        0.333,
        6.0,
        T_END,
        0.0,
        100_000,
        1000,
        ode_solvers::OutputType::Sparse,
    );
    let stats = s.integrate().expect("ode_solvers DOP853");
    // The boundary between nalgebra 0.34 (ode_solvers) and 0.35 (ours): plain numbers.
    let y = s.y_out().last().expect("final state");
    ([y[0], y[1], y[2]], stats.accepted_steps as usize)
}

fn bench_peers(c: &mut Criterion) {
    // The errors are computed and printed by the first entry criterion runs, so a filter
    // that excludes the group skips them.
    let report = || {
        let rb = RigidBodyEuler::default();
        let mut reference = V3::from(RigidBodyEuler::INITIAL);
        Driver::new(0.0, T_END)
            .expect("horizon")
            .run_fixed(
                &mut gauss12().stepper(&reference),
                &rb,
                &mut reference,
                T_END / 4000.0,
                &mut NoObserver,
            )
            .expect("reference");
        for tol in [1e-6, 1e-10] {
            let (y, n) = ours(ExplicitRungeKutta::dop853(), tol);
            eprintln!(
                "tol {tol:.0e} tumble dop853:            error {:.2e}, {n} steps",
                max_abs_diff(y.as_slice(), reference.as_slice())
            );
            let (y, n) = ours(ExplicitRungeKutta::dp5(), tol);
            eprintln!(
                "tol {tol:.0e} tumble dp5:               error {:.2e}, {n} steps",
                max_abs_diff(y.as_slice(), reference.as_slice())
            );
            let (y, n) = diffeq(tol);
            eprintln!(
                "tol {tol:.0e} differential-equations:   error {:.2e}, {n} steps",
                max_abs_diff(&y, reference.as_slice())
            );
            let (y, n) = odesolvers(tol);
            eprintln!(
                "tol {tol:.0e} ode_solvers:              error {:.2e}, {n} steps",
                max_abs_diff(&y, reference.as_slice())
            );
        }
    };
    let done = OnceCell::new();
    let mut g = c.benchmark_group("dop853");
    for tol in [1e-6, 1e-10] {
        g.bench_function(format!("tumble/{tol:.0e}"), |b| {
            done.get_or_init(&report);
            b.iter(|| ours(ExplicitRungeKutta::dop853(), black_box(tol)))
        });
        g.bench_function(format!("tumble-dp5/{tol:.0e}"), |b| {
            done.get_or_init(&report);
            b.iter(|| ours(ExplicitRungeKutta::dp5(), black_box(tol)))
        });
        g.bench_function(format!("differential-equations/{tol:.0e}"), |b| {
            done.get_or_init(&report);
            b.iter(|| diffeq(black_box(tol)))
        });
        g.bench_function(format!("ode_solvers/{tol:.0e}"), |b| {
            done.get_or_init(&report);
            b.iter(|| odesolvers(black_box(tol)))
        });
    }
    g.finish();
}

mod rigid {
    use super::*;
    use nalgebra::{Matrix3, Vector3};
    use tumble_integrators::registry::build::{self, Receive};
    use tumble_integrators::registry::find;
    use tumble_integrators::rigid::{EulerEquations, FreeRigidBody, GroupState, RigidBodyState};
    use tumble_integrators::{ProblemKind, State};
    use tumble_kinematics::so3::exp;

    pub const H: f64 = 0.01;

    pub fn body() -> FreeRigidBody {
        let q = exp(&Vector3::new(0.4, 1.1, -0.3));
        let j = q.matrix()
            * Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0))
            * q.matrix().transpose();
        FreeRigidBody::from_inertia(&j).expect("inertia")
    }

    pub fn initial() -> RigidBodyState {
        RigidBodyState::new(
            &exp(&Vector3::new(0.3, -0.2, 0.9)),
            Vector3::new(0.7, -0.3, 1.0),
        )
    }

    /// Takes `n` steps of the stepper it receives from `s0`.
    struct Steps<'a, P: ?Sized, S> {
        problem: &'a P,
        s0: S,
        n: u64,
    }

    impl<P: ?Sized, S: State> Receive<P, S> for Steps<'_, P, S> {
        type Output = S;
        fn receive<St: Stepper<P, State = S> + Clone>(self, mut st: St) -> S {
            let mut s = self.s0;
            for k in 0..self.n {
                st.step(self.problem, k as f64 * H, &mut s, H)
                    .expect("step");
            }
            s
        }
    }

    pub const METHODS: [&str; 10] = [
        "lgvi",
        "dmv",
        "rkmk4",
        "cg3",
        "split2",
        "split4",
        "split6",
        "split8",
        "split-exact2",
        "exact",
    ];

    /// The state after `n` steps of `name` from the initial state (the registry builds the
    /// stepper: on the body, on Euler's equations as a Lie-group vector field, or on the free
    /// body as such).
    pub fn run(name: &str, body: &FreeRigidBody, n: u64) -> RigidBodyState {
        let method = find(name).expect("registered");
        let s0 = initial();
        let kind = method.problems[0];
        match kind {
            ProblemKind::LieVectorField => {
                let field = EulerEquations(body);
                let steps = Steps {
                    problem: &field,
                    s0: GroupState::from(s0),
                    n,
                };
                build::lie_vector_field::<_, _, 3>(method, steps).map(RigidBodyState::from)
            }
            ProblemKind::FreeRigidBody => build::free_rigid_body(
                method,
                Steps {
                    problem: body,
                    s0,
                    n,
                },
            ),
            _ => build::rigid_body(
                method,
                Steps {
                    problem: body,
                    s0,
                    n,
                },
            ),
        }
        .expect("a rigid-body method")
    }
}

fn bench_rigid(c: &mut Criterion) {
    let body = rigid::body();
    let s0 = rigid::initial();
    // Printed by the first entry criterion runs (a filter that excludes the group skips it).
    let report = || {
        let t_end = 100.0;
        let (r, m) = body
            .flow(&s0.rotation3(), &s0.momentum)
            .expect("flow")
            .at(t_end);
        eprintln!(
            "rigid body I = (1, 2, 3) about rotated axes, h = {}, error at t = {t_end} against the exact solution:",
            rigid::H
        );
        for name in rigid::METHODS {
            let s = rigid::run(name, &body, (t_end / rigid::H).round() as u64);
            let err = ((s.momentum - m).norm() / s0.momentum.norm())
                .max((s.rotation - r.matrix()).amax());
            eprintln!(
                "  {name:>12}: error {err:.2e}, ‖RᵀR − 𝟙‖ {:.1e}",
                s.orthogonality_defect()
            );
        }
    };
    let done = OnceCell::new();
    let mut g = c.benchmark_group("rigid");
    g.throughput(Throughput::Elements(STEPS));
    for name in rigid::METHODS {
        g.bench_function(name, |b| {
            done.get_or_init(&report);
            b.iter(|| rigid::run(name, black_box(&body), STEPS))
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    bench_steps,
    bench_peers,
    bench_rigid,
    step_overhead::bench_step_overhead,
    lie_gauss_solve::bench_lie_gauss_solve
);
criterion_main!(benches);
