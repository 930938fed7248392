//! Invariants of the variational Lie-group methods over 2²⁰ ≈ 10⁶ steps, checked in release mode
//! (a report with assertions, not a timed test: `cargo test` stays fast).
//!
//! For every variational Lie-group method — `lgvi`, its compositions `lgvi4` … `lgvi10`, and the
//! variational Lie–Gauss methods `lie-gauss4` … `lie-gauss10`, and on the rigid bodies the
//! kicks around the exact free flow, `split-exact2` and its compositions `split-exact4` …
//! `split-exact8` — at each scene's default step from its default parameters:
//!
//! - `free-body`: `‖RᵀR − 𝟙‖_F`, the spatial angular momentum `|L − L₀|/|L₀|` and, for the
//!   LGVI and its compositions, the energy (the torque-free LGVI is the discrete Moser–Veselov
//!   map: it conserves `½ m·J⁻¹m` exactly; the energy error of the Lie–Gauss methods and of
//!   `split-exact`, which restarts the closed form every substep, is reported);
//! - `heavy-top` (Simo & Wong's fast top): `‖RᵀR − 𝟙‖_F` and the vertical angular momentum
//!   `|ΔL·e₃|/|L₀|` (gravity's symmetry, conserved by the discrete Noether theorem); the energy
//!   error is reported (bounded, not conserved);
//! - `free-hoop` (the coupled methods): `‖RᵀR − 𝟙‖_F` and `|ΔL·e₃|/|L₀|`.
//!
//! Each conserved quantity must stay within `10 ε √N`, `N` the number of base steps taken (a
//! random walk of round-off, one rounding pattern per base step: 2²⁰ steps times the
//! composition's stages, 2²⁰ for a Lie–Gauss method, 2.3e-12 for `lgvi`, 6.8e-12 for the 9
//! stages of `lgvi6`), and the free body's energy too; the run fails otherwise. A table of the maxima and the wall time of each
//! run is printed.
//!
//! Run: `cargo bench --bench invariants` (all: about a minute on a 2-core machine, most of it
//! the free hoop's `lgvi8` and `lgvi10`, whose coupled LGVI costs about 0.6 µs a substep and
//! whose compositions take 15 and 35 substeps a step),
//! or with a filter on `scene/method`: `cargo bench --bench invariants -- free-body`.

use std::time::Instant;

use nalgebra::{Matrix3, Vector3};

use tumble_integrators::rigid::{
    CoupledLgvi, CoupledLieGauss, CoupledMonitor, CoupledState, Deviations, ExactSplitting,
    FreeRigidBody, LGVI_COMPOSITIONS, LIE_GAUSS_METHODS, Lgvi, LieGauss, RigidBody,
    RigidBodyMonitor, RigidBodyState,
};
use tumble_integrators::tables::composition::{KAHAN_LI6, KAHAN_LI8, MCLACHLAN4};
use tumble_integrators::tables::gauss::{GAUSS4, GAUSS6, GAUSS8, GAUSS10};
use tumble_integrators::tables::{CompositionTable, GaussTableau};
use tumble_integrators::{Composition, Driver, Stepper};
use tumble_scenarios::scenes::find;
use tumble_scenarios::scenes::free_hoop::FreeHoopScene;
use tumble_scenarios::scenes::rigid::HeavyTopScene;

const STEPS: u64 = 1 << 20;

/// One run's maxima.
struct Outcome {
    deviations: Deviations,
    l0: f64,
    seconds: f64,
}

fn rigid<B: RigidBody, St: Stepper<B, State = RigidBodyState>>(
    body: &B,
    s0: RigidBodyState,
    mut stepper: St,
    h: f64,
) -> Outcome {
    let mut monitor = RigidBodyMonitor::new(body);
    let mut s = s0;
    let start = Instant::now();
    Driver::new(0.0, STEPS as f64 * h)
        .and_then(|d| d.run_fixed(&mut stepper, body, &mut s, h, &mut monitor))
        .unwrap_or_else(|e| panic!("run failed: {e}"));
    Outcome {
        deviations: monitor.deviations(),
        l0: s0.spatial_momentum().norm(),
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// A method of the report.
#[derive(Clone, Copy)]
enum Method {
    /// The LGVI (`None`) or its composition by a table of [`LGVI_COMPOSITIONS`].
    Lgvi(Option<&'static CompositionTable>),
    /// The variational Lie–Gauss method with this many stages.
    LieGauss(usize),
    /// `split-exact2` (`None`) or its composition `split-exact4` … `split-exact8` (rigid
    /// bodies only).
    SplitExact(Option<&'static CompositionTable>),
}

/// Every method of the report, by registry name.
fn methods() -> impl Iterator<Item = (&'static str, Method)> {
    std::iter::once(("lgvi", Method::Lgvi(None)))
        .chain(
            LGVI_COMPOSITIONS
                .iter()
                .map(|(n, t)| (*n, Method::Lgvi(Some(*t)))),
        )
        .chain(
            LIE_GAUSS_METHODS
                .iter()
                .map(|(n, s)| (*n, Method::LieGauss(*s))),
        )
        .chain([
            ("split-exact2", Method::SplitExact(None)),
            ("split-exact4", Method::SplitExact(Some(&MCLACHLAN4))),
            ("split-exact6", Method::SplitExact(Some(&KAHAN_LI6))),
            ("split-exact8", Method::SplitExact(Some(&KAHAN_LI8))),
        ])
}

/// Runs the Lie–Gauss method of `S` stages on a coupled model.
fn coupled_lie_gauss<const S: usize>(
    table: &'static GaussTableau<S>,
    model: &tumble_scenarios::scenes::free_hoop::FreeHoop,
    s: &mut CoupledState<1>,
    h: f64,
    monitor: &mut CoupledMonitor<'_, tumble_scenarios::scenes::free_hoop::FreeHoop, 1>,
) -> Result<(), tumble_integrators::Error> {
    Driver::new(0.0, STEPS as f64 * h)?
        .run_fixed(
            &mut CoupledLieGauss::<S, 1>::new(table),
            model,
            s,
            h,
            monitor,
        )
        .map(|_| ())
}

/// Runs the method on a rigid body.
fn rigid_method<B: RigidBody>(body: &B, s0: RigidBodyState, method: Method, h: f64) -> Outcome {
    match method {
        Method::Lgvi(None) => rigid(body, s0, Lgvi::new(), h),
        Method::Lgvi(Some(t)) => rigid(body, s0, Composition::new(t, Lgvi::new()), h),
        Method::LieGauss(2) => rigid(body, s0, LieGauss::new(&GAUSS4), h),
        Method::LieGauss(3) => rigid(body, s0, LieGauss::new(&GAUSS6), h),
        Method::LieGauss(4) => rigid(body, s0, LieGauss::new(&GAUSS8), h),
        Method::LieGauss(_) => rigid(body, s0, LieGauss::new(&GAUSS10), h),
        Method::SplitExact(None) => rigid(body, s0, ExactSplitting::new(), h),
        Method::SplitExact(Some(t)) => {
            rigid(body, s0, Composition::new(t, ExactSplitting::new()), h)
        }
    }
}

fn main() {
    let filter: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let wanted = |name: &str| filter.is_empty() || filter.iter().any(|f| name.contains(f.as_str()));
    println!(
        "{STEPS} steps at each scene's default step; bound 10 eps sqrt(N), N = steps x stages\n\
         {:<20} {:>10} {:>12} {:>12} {:>12} {:>10} {:>8}",
        "scene/method", "|RtR-1|", "|dL|/|L0|", "|dLz|/|L0|", "|dH|/|H0|", "seconds", "bound"
    );
    let mut failures = Vec::new();
    for scene in ["free-body", "heavy-top", "free-hoop"] {
        let info = find(scene).expect("built-in scene").info();
        let params = info.default_params();
        let h = info.default_step;
        for (method, kind) in methods() {
            let name = format!("{scene}/{method}");
            if !wanted(&name) || (scene == "free-hoop" && matches!(kind, Method::SplitExact(_))) {
                continue;
            }
            let out = match scene {
                "free-body" => {
                    let (body, s0) = free_body(&params);
                    rigid_method(&body, s0, kind, h)
                }
                "heavy-top" => {
                    let (top, s0) = HeavyTopScene::top_and_state(&params).expect("defaults");
                    rigid_method(&top, s0, kind, h)
                }
                _ => {
                    let (model, s0) = FreeHoopScene::model(&params).expect("defaults");
                    let mut monitor = CoupledMonitor::new(&model);
                    let mut s = s0;
                    let start = Instant::now();
                    let driver = Driver::new(0.0, STEPS as f64 * h).expect("horizon");
                    let run = match kind {
                        Method::Lgvi(None) => driver
                            .run_fixed(
                                &mut CoupledLgvi::<1>::new(),
                                &model,
                                &mut s,
                                h,
                                &mut monitor,
                            )
                            .map(|_| ()),
                        Method::Lgvi(Some(t)) => driver
                            .run_fixed(
                                &mut Composition::new(t, CoupledLgvi::<1>::new()),
                                &model,
                                &mut s,
                                h,
                                &mut monitor,
                            )
                            .map(|_| ()),
                        Method::LieGauss(2) => {
                            coupled_lie_gauss(&GAUSS4, &model, &mut s, h, &mut monitor)
                        }
                        Method::LieGauss(3) => {
                            coupled_lie_gauss(&GAUSS6, &model, &mut s, h, &mut monitor)
                        }
                        Method::LieGauss(4) => {
                            coupled_lie_gauss(&GAUSS8, &model, &mut s, h, &mut monitor)
                        }
                        Method::LieGauss(_) => {
                            coupled_lie_gauss(&GAUSS10, &model, &mut s, h, &mut monitor)
                        }
                        Method::SplitExact(_) => {
                            unreachable!("split-exact is skipped on free-hoop")
                        }
                    };
                    run.unwrap_or_else(|e| panic!("{name}: run failed: {e}"));
                    Outcome {
                        deviations: monitor.deviations(),
                        l0: s0.spatial_momentum().norm(),
                        seconds: start.elapsed().as_secs_f64(),
                    }
                }
            };
            let stages = match kind {
                Method::Lgvi(table) | Method::SplitExact(table) => {
                    table.map_or(1, |t| t.gammas.len())
                }
                Method::LieGauss(_) => 1,
            };
            let bound = 10.0 * f64::EPSILON * ((STEPS as usize * stages) as f64).sqrt();
            let d = out.deviations;
            let momentum = d.spatial_momentum / out.l0;
            let vertical = d.vertical_momentum / out.l0;
            println!(
                "{name:<20} {:>10.2e} {:>12.2e} {:>12.2e} {:>12.2e} {:>10.2} {:>8.1e}",
                d.orthogonality, momentum, vertical, d.energy_relative, out.seconds, bound
            );
            let mut check = |what: &str, value: f64| {
                if !(value <= bound) {
                    failures.push(format!("{name}: {what} = {value:e} above {bound:e}"));
                }
            };
            check("|RtR - 1|", d.orthogonality);
            check("|dLz|/|L0|", vertical);
            if scene == "free-body" {
                check("|dL|/|L0|", momentum);
                if matches!(kind, Method::Lgvi(_)) {
                    check("|dH|/|H0|", d.energy_relative);
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "invariants not at round-off:\n{}",
        failures.join("\n")
    );
}

/// The free body of the `free-body` scene: principal moments `I1..I3` along the axes, initial
/// body momentum `m1..m3`, identity orientation.
fn free_body(params: &tumble_scenarios::Params) -> (FreeRigidBody, RigidBodyState) {
    let get = |k| params.get(k).expect("default parameter");
    let inertia = Matrix3::from_diagonal(&Vector3::new(get("I1"), get("I2"), get("I3")));
    let body = FreeRigidBody::from_inertia(&inertia).expect("positive moments");
    let m0 = Vector3::new(get("m1"), get("m2"), get("m3"));
    (
        body,
        RigidBodyState::new(&nalgebra::Rotation3::identity(), m0),
    )
}
