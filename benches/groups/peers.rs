//! `peers/<scene>`: tumble's explicit pairs against the peer crates' best methods at final-time
//! errors of 1e-6, 1e-8, 1e-10 and 1e-12, on the flattened equations of `free-hoop` (`ℝ¹⁴`,
//! `t_end = 10`) and `free-body` (`ℝ¹²`, `t_end = 20`) at their default parameters.
//!
//! - Solvers: tumble's `dop853`, `tsit5`, `vern6` … `vern9` (`Driver::run_adaptive`);
//!   `ode_solvers`' `Dop853` and `Dopri5` (Hairer's parameters); `differential-equations`'
//!   `dop853` and Verner's `rkv655e`, `rkv766e`, `rkv877e`, `rkv988e` (the variants with the
//!   fewest interpolation stages). All integrate the same right-hand side
//!   ([`FlatFreeHoop`], [`FlatRigidBody`]) at `rtol = atol = tol`; the peers' wrappers copy
//!   the state into our vector type and the derivative out (about 1–3 ns an evaluation).
//! - Error: `max_i |yᵢ − yᵢ,ref| / (1 + |yᵢ,ref|)` over the flat final state (rotation matrix,
//!   momenta, bead angle and momentum). References: the exact elliptic-function solution for
//!   `free-body`; Gauss–Legendre of order 12 at `h = 10/4000` for `free-hoop` (its agreement with
//!   `h = 10/2000` is printed).
//! - Setting: tolerances `10^(−k/8)`, `k = 32 … 120` (1e-4 … 1e-15). For each target, a solver's
//!   setting is the loosest tolerance whose error, and the errors at the next three finer grid
//!   points, are all at or below the target.
//! - Time: each solver at its setting, the fastest of 21 samples of at least 5 ms, the solvers
//!   taking turns sample by sample (on a shared machine the fastest sample is the least
//!   disturbed by other processes).
//!
//! Printed: per scene and target, every solver's tolerance, steps, RHS evaluations, error and
//! time, then the best of ours, each peer crate's best, and the ratios peer / ours (above 1:
//! ours is faster).

use std::cell::{Cell, OnceCell};
use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::Criterion;
use nalgebra::{Rotation3, SVector, Vector3};
use tumble_integrators::rigid::{FreeRigidBody, RigidBodyState};
use tumble_integrators::{Driver, ExplicitRungeKutta, NoObserver, Ode, Tolerances, gauss12};
use tumble_scenarios::Scene;
use tumble_scenarios::scenes::free_hoop::{self, FlatFreeHoop, FreeHoopScene};
use tumble_scenarios::scenes::rigid::{self, FlatRigidBody};

/// Target errors.
const TARGETS: [f64; 4] = [1e-6, 1e-8, 1e-10, 1e-12];
/// Grid points per decade of tolerance.
const PER_DECADE: i32 = 8;
/// Loosest and tightest grid points (`1e-4`, `1e-15`).
const K_RANGE: (i32, i32) = (4 * PER_DECADE, 15 * PER_DECADE);
/// Finer grid points that must meet the target too.
const CONFIRM: i32 = 3;
/// Timed samples (the fastest is reported).
const SAMPLES: usize = 21;
/// A sample repeats a run until it lasts this long (s).
const MIN_SAMPLE_SECONDS: f64 = 0.005;

/// The solvers.
const SOLVERS: [Solver; 13] = [
    Solver::Ours("dop853"),
    Solver::Ours("tsit5"),
    Solver::Ours("vern6"),
    Solver::Ours("vern7"),
    Solver::Ours("vern8"),
    Solver::Ours("vern9"),
    Solver::OdeSolvers("dop853"),
    Solver::OdeSolvers("dopri5"),
    Solver::DiffEq("dop853"),
    Solver::DiffEq("rkv655e"),
    Solver::DiffEq("rkv766e"),
    Solver::DiffEq("rkv877e"),
    Solver::DiffEq("rkv988e"),
];

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Solver {
    Ours(&'static str),
    OdeSolvers(&'static str),
    DiffEq(&'static str),
}

impl Solver {
    fn crate_name(self) -> &'static str {
        match self {
            Solver::Ours(_) => "tumble",
            Solver::OdeSolvers(_) => "ode_solvers",
            Solver::DiffEq(_) => "differential-equations",
        }
    }

    fn name(self) -> String {
        match self {
            Solver::Ours(m) | Solver::OdeSolvers(m) | Solver::DiffEq(m) => {
                format!("{}-{m}", self.crate_name())
            }
        }
    }
}

/// Our right-hand side in the peers' traits (and counting its evaluations).
struct Peer<'a, P> {
    inner: &'a P,
    calls: &'a Cell<u64>,
}

impl<P> Clone for Peer<'_, P> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<P> Copy for Peer<'_, P> {}

impl<const N: usize, P: Ode<SVector<f64, N>>> Ode<SVector<f64, N>> for Peer<'_, P> {
    fn rhs(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        self.calls.set(self.calls.get() + 1);
        self.inner.rhs(t, y, dy);
    }
}

impl<const N: usize, P: Ode<SVector<f64, N>>> differential_equations::prelude::ODE<f64, [f64; N]>
    for Peer<'_, P>
{
    fn diff(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]) {
        let mut out = SVector::<f64, N>::zeros();
        Ode::rhs(self, t, &SVector::from(*y), &mut out);
        dy.copy_from_slice(out.as_slice());
    }
}

impl<const N: usize, P: Ode<SVector<f64, N>>> ode_solvers::System<f64, ode_solvers::SVector<f64, N>>
    for Peer<'_, P>
{
    fn system(
        &self,
        t: f64,
        y: &ode_solvers::SVector<f64, N>,
        dy: &mut ode_solvers::SVector<f64, N>,
    ) {
        let mut out = SVector::<f64, N>::zeros();
        Ode::rhs(self, t, &SVector::from_column_slice(y.as_slice()), &mut out);
        dy.copy_from_slice(out.as_slice());
    }
}

/// A run's final state and accepted steps.
type Outcome<const N: usize> = Result<(SVector<f64, N>, u64), String>;

fn ours<const S: usize, const N: usize, P: Ode<SVector<f64, N>>>(
    method: ExplicitRungeKutta<S>,
    p: &P,
    y0: &SVector<f64, N>,
    t_end: f64,
    tol: f64,
) -> Outcome<N> {
    let mut y = *y0;
    let mut st = method.stepper(&y);
    let tol = Tolerances::new(tol, tol).map_err(|e| e.to_string())?;
    let report = Driver::new(0.0, t_end)
        .map_err(|e| e.to_string())?
        .max_steps(10_000_000)
        .run_adaptive(&mut st, p, &mut y, &tol, &mut [], &mut NoObserver)
        .map_err(|e| e.to_string())?;
    Ok((y, report.steps))
}

fn diffeq<const N: usize, P: Ode<SVector<f64, N>>>(
    method: &str,
    p: Peer<'_, P>,
    y0: &SVector<f64, N>,
    t_end: f64,
    tol: f64,
) -> Outcome<N> {
    use differential_equations::prelude::*;
    let mut start = [0.0; N];
    start.copy_from_slice(y0.as_slice());
    let ivp = IVP::ode(&p, 0.0, t_end, start);
    macro_rules! solve {
        ($m:ident) => {
            ivp.method(
                ExplicitRungeKutta::$m()
                    .rtol(tol)
                    .atol(tol)
                    .max_steps(10_000_000),
            )
            .t_eval([t_end])
            .solve()
        };
    }
    let sol = match method {
        "dop853" => solve!(dop853),
        "rkv655e" => solve!(rkv655e),
        "rkv766e" => solve!(rkv766e),
        "rkv877e" => solve!(rkv877e),
        "rkv988e" => solve!(rkv988e),
        other => return Err(format!("no method {other}")),
    }
    .map_err(|e| format!("{e:?}"))?;
    let y = sol.y.last().ok_or("no output")?;
    Ok((SVector::from(*y), sol.steps.accepted as u64))
}

fn odesolvers<const N: usize, P: Ode<SVector<f64, N>>>(
    method: &str,
    p: Peer<'_, P>,
    y0: &SVector<f64, N>,
    t_end: f64,
    tol: f64,
) -> Outcome<N> {
    let y0 = ode_solvers::SVector::<f64, N>::from_column_slice(y0.as_slice());
    let sparse = ode_solvers::OutputType::Sparse;
    // Hairer's parameters; output only at t_end (dx = t_end).
    let (y, steps) = match method {
        "dop853" => {
            let mut s = ode_solvers::Dop853::from_param(
                p, 0.0, t_end, t_end, y0, tol, tol, 0.9, 0.0, 0.333, 6.0, t_end, 0.0, 10_000_000,
                1000, sparse,
            );
            let stats = s.integrate().map_err(|e| format!("{e:?}"))?;
            (*s.y_out().last().ok_or("no output")?, stats.accepted_steps)
        }
        "dopri5" => {
            let mut s = ode_solvers::Dopri5::from_param(
                p, 0.0, t_end, t_end, y0, tol, tol, 0.9, 0.04, 0.2, 10.0, t_end, 0.0, 10_000_000,
                1000, sparse,
            );
            let stats = s.integrate().map_err(|e| format!("{e:?}"))?;
            (*s.y_out().last().ok_or("no output")?, stats.accepted_steps)
        }
        other => return Err(format!("no method {other}")),
    };
    Ok((SVector::from_column_slice(y.as_slice()), u64::from(steps)))
}

/// One scene: its right-hand side, initial state, horizon and reference final state.
struct Case<'a, const N: usize, P> {
    name: &'static str,
    problem: &'a P,
    y0: SVector<f64, N>,
    t_end: f64,
    reference: SVector<f64, N>,
}

impl<const N: usize, P: Ode<SVector<f64, N>>> Case<'_, N, P> {
    fn run(&self, solver: Solver, tol: f64, calls: &Cell<u64>) -> Outcome<N> {
        let peer = Peer {
            inner: self.problem,
            calls,
        };
        let (y0, t) = (&self.y0, self.t_end);
        match solver {
            Solver::Ours(m) => match m {
                "dop853" => ours(ExplicitRungeKutta::dop853(), self.problem, y0, t, tol),
                "tsit5" => ours(ExplicitRungeKutta::tsit5(), self.problem, y0, t, tol),
                "vern6" => ours(ExplicitRungeKutta::vern6(), self.problem, y0, t, tol),
                "vern7" => ours(ExplicitRungeKutta::vern7(), self.problem, y0, t, tol),
                "vern8" => ours(ExplicitRungeKutta::vern8(), self.problem, y0, t, tol),
                "vern9" => ours(ExplicitRungeKutta::vern9(), self.problem, y0, t, tol),
                other => Err(format!("no method {other}")),
            },
            Solver::OdeSolvers(m) => odesolvers(m, peer, y0, t, tol),
            Solver::DiffEq(m) => diffeq(m, peer, y0, t, tol),
        }
    }

    fn error(&self, y: &SVector<f64, N>) -> f64 {
        y.iter()
            .zip(self.reference.iter())
            .map(|(a, r)| (a - r).abs() / (1.0 + r.abs()))
            .fold(0.0, f64::max)
    }

    /// Error, steps and evaluations of `solver` at every grid point (`None`: the run failed).
    fn scan(&self, solver: Solver) -> Vec<Option<(f64, u64, u64)>> {
        (K_RANGE.0..=K_RANGE.1)
            .map(|k| {
                let tol = tol_at(k);
                let calls = Cell::new(0);
                // our solvers are counted through the same wrapper as the peers
                let counted = Case {
                    name: self.name,
                    problem: &Peer {
                        inner: self.problem,
                        calls: &calls,
                    },
                    y0: self.y0,
                    t_end: self.t_end,
                    reference: self.reference,
                };
                let (y, steps) = match solver {
                    Solver::Ours(_) => counted.run(solver, tol, &Cell::new(0)),
                    _ => self.run(solver, tol, &calls),
                }
                .ok()?;
                Some((self.error(&y), steps, calls.get()))
            })
            .collect()
    }
}

fn tol_at(k: i32) -> f64 {
    10f64.powf(-f64::from(k) / f64::from(PER_DECADE))
}

/// The loosest grid index meeting `target` with the next [`CONFIRM`] points.
fn choose(scan: &[Option<(f64, u64, u64)>], target: f64) -> Option<usize> {
    let ok = |i: usize| {
        scan.get(i)
            .copied()
            .flatten()
            .is_some_and(|r| r.0 <= target)
    };
    (0..scan.len()).find(|&i| (i..=i + CONFIRM as usize).all(ok))
}

/// The study of one scene: the table per target and the ratios.
fn study<const N: usize, P: Ode<SVector<f64, N>>>(case: &Case<'_, N, P>) {
    let scans: Vec<_> = SOLVERS.iter().map(|&s| case.scan(s)).collect();
    for target in TARGETS {
        let chosen: Vec<Option<usize>> = scans.iter().map(|s| choose(s, target)).collect();
        let calls = Cell::new(0);
        let reps: Vec<u32> = SOLVERS
            .iter()
            .zip(&chosen)
            .map(|(&s, c)| {
                c.map_or(0, |i| {
                    let tol = tol_at(K_RANGE.0 + i as i32);
                    let start = Instant::now();
                    let _ = case.run(s, tol, &calls);
                    let once = start.elapsed().as_secs_f64();
                    (MIN_SAMPLE_SECONDS / once).ceil().clamp(1.0, 100_000.0) as u32
                })
            })
            .collect();
        let mut best = vec![f64::INFINITY; SOLVERS.len()];
        for _ in 0..SAMPLES {
            for (j, (&s, c)) in SOLVERS.iter().zip(&chosen).enumerate() {
                let Some(i) = c else { continue };
                let tol = tol_at(K_RANGE.0 + *i as i32);
                let start = Instant::now();
                for _ in 0..reps[j] {
                    let _ = black_box(case.run(s, black_box(tol), &calls));
                }
                best[j] = best[j].min(start.elapsed().as_secs_f64() / f64::from(reps[j]));
            }
        }
        eprintln!();
        eprintln!(
            "peers/{}: error <= {target:.0e} at t_end = {} (loosest tolerance meeting it with the next {CONFIRM} finer)",
            case.name, case.t_end
        );
        eprintln!(
            "  {:<32} {:>9} {:>8} {:>10} {:>9} {:>10}",
            "solver", "tol", "steps", "RHS evals", "error", "time ms"
        );
        for (j, &s) in SOLVERS.iter().enumerate() {
            match chosen[j] {
                Some(i) => {
                    let (e, steps, evals) = scans[j][i].expect("chosen runs succeeded");
                    eprintln!(
                        "  {:<32} {:>9.2e} {steps:>8} {evals:>10} {e:>9.2e} {:>10.3}",
                        s.name(),
                        tol_at(K_RANGE.0 + i as i32),
                        best[j] * 1e3
                    );
                }
                None => eprintln!("  {:<32} NOT REACHED by tol 1e-15", s.name()),
            }
        }
        let best_of = |crate_name: &str| {
            SOLVERS
                .iter()
                .enumerate()
                .filter(|(j, s)| s.crate_name() == crate_name && best[*j].is_finite())
                .min_by(|a, b| best[a.0].total_cmp(&best[b.0]))
                .map(|(j, s)| (s.name(), best[j]))
        };
        let Some((ours_name, ours_time)) = best_of("tumble") else {
            eprintln!("  no tumble method reached the target");
            continue;
        };
        eprintln!("  best ours: {ours_name}, {:.3} ms", ours_time * 1e3);
        for peer in ["ode_solvers", "differential-equations"] {
            match best_of(peer) {
                Some((name, t)) => eprintln!(
                    "  best {peer}: {name}, {:.3} ms; ratio {peer} / ours = {:.2}",
                    t * 1e3,
                    t / ours_time
                ),
                None => eprintln!("  best {peer}: none reached the target"),
            }
        }
    }
}

/// The `peers` group: `peers/free-hoop` and `peers/free-body` print their study when they run
/// (a filter that excludes them skips it), then criterion times tumble's `vern9` at 1e-10.
pub fn bench_peers(c: &mut Criterion) {
    let mut g = c.benchmark_group("peers");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(1))
        .warm_up_time(Duration::from_millis(300));

    let params = FreeHoopScene.info().default_params();
    let (model, s0) = FreeHoopScene::model(&params).expect("free-hoop model");
    let hoop = FlatFreeHoop::new(model).expect("flat free hoop");
    let y0 = free_hoop::flatten(&s0);
    let done = OnceCell::new();
    g.bench_function("free-hoop", |b| {
        done.get_or_init(|| {
            let gauss = |n: f64| {
                let mut y = y0;
                Driver::new(0.0, 10.0)
                    .and_then(|d| {
                        d.run_fixed(&mut gauss12().stepper(&y), &hoop, &mut y, 10.0 / n, &mut NoObserver)
                    })
                    .expect("Gauss-Legendre reference");
                y
            };
            let reference = gauss(4000.0);
            let case = Case {
                name: "free-hoop",
                problem: &hoop,
                y0,
                t_end: 10.0,
                reference,
            };
            eprintln!(
                "peers/free-hoop: reference Gauss-Legendre 12 at h = 10/4000; agreement with h = 10/2000: {:.1e}",
                case.error(&gauss(2000.0))
            );
            study(&case);
        });
        b.iter(|| ours(ExplicitRungeKutta::vern9(), &hoop, &y0, 10.0, black_box(1e-10)))
    });

    let body = FreeRigidBody::from_principal_moments(Vector3::new(1.0, 2.0, 3.0)).expect("body");
    let m0 = Vector3::new(0.4, -0.8, 0.6);
    let s0 = RigidBodyState::new(&Rotation3::identity(), m0);
    let flat_body = FlatRigidBody(body);
    let y0 = rigid::flatten(&s0);
    let done = OnceCell::new();
    g.bench_function("free-body", |b| {
        done.get_or_init(|| {
            let (r, m) = body
                .flow(&Rotation3::identity(), &m0)
                .expect("exact flow")
                .at(20.0);
            let reference = rigid::flatten(&RigidBodyState::new(&r, m));
            eprintln!("peers/free-body: reference the exact solution");
            study(&Case {
                name: "free-body",
                problem: &flat_body,
                y0,
                t_end: 20.0,
                reference,
            });
        });
        b.iter(|| {
            ours(
                ExplicitRungeKutta::vern9(),
                &flat_body,
                &y0,
                20.0,
                black_box(1e-10),
            )
        })
    });
    g.finish();
}
