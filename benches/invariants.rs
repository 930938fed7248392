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

use tumble_integrators::registry::build::{self, Receive};
use tumble_integrators::registry::{BaseStepper, MethodInfo, Stepping};
use tumble_integrators::rigid::{
    CoupledLagrangian, CoupledMonitor, CoupledState, Deviations, FreeRigidBody, RigidBody,
    RigidBodyMonitor, RigidBodyState,
};
use tumble_integrators::{Driver, ProblemKind, Stepper};
use tumble_scenarios::scenes::find;
use tumble_scenarios::scenes::free_hoop::FreeHoopScene;
use tumble_scenarios::scenes::rigid::HeavyTopScene;

const STEPS: u64 = 1 << 20;

/// The methods of the report, by registry name (the registry builds their steppers).
const METHODS: [&str; 13] = [
    "lgvi",
    "lgvi4",
    "lgvi6",
    "lgvi8",
    "lgvi10",
    "lie-gauss4",
    "lie-gauss6",
    "lie-gauss8",
    "lie-gauss10",
    "split-exact2",
    "split-exact4",
    "split-exact6",
    "split-exact8",
];

/// One run's maxima.
struct Outcome {
    deviations: Deviations,
    l0: f64,
    seconds: f64,
}

/// Runs the stepper it receives on a rigid body for [`STEPS`] steps, monitoring invariants.
struct RigidRun<'a, B> {
    body: &'a B,
    s0: RigidBodyState,
    h: f64,
}

impl<B: RigidBody> Receive<B, RigidBodyState> for RigidRun<'_, B> {
    type Output = Outcome;
    fn receive<St: Stepper<B, State = RigidBodyState> + Clone>(self, mut stepper: St) -> Outcome {
        let mut monitor = RigidBodyMonitor::new(self.body);
        let mut s = self.s0;
        let start = Instant::now();
        Driver::new(0.0, STEPS as f64 * self.h)
            .and_then(|d| d.run_fixed(&mut stepper, self.body, &mut s, self.h, &mut monitor))
            .unwrap_or_else(|e| panic!("run failed: {e}"));
        Outcome {
            deviations: monitor.deviations(),
            l0: self.s0.spatial_momentum().norm(),
            seconds: start.elapsed().as_secs_f64(),
        }
    }
}

/// Runs the stepper it receives on a coupled model for [`STEPS`] steps, monitoring invariants.
struct CoupledRun<'a, L> {
    model: &'a L,
    s0: CoupledState<1>,
    h: f64,
}

impl<L: CoupledLagrangian<1>> Receive<L, CoupledState<1>> for CoupledRun<'_, L> {
    type Output = Outcome;
    fn receive<St: Stepper<L, State = CoupledState<1>> + Clone>(self, mut stepper: St) -> Outcome {
        let mut monitor = CoupledMonitor::new(self.model);
        let mut s = self.s0;
        let start = Instant::now();
        Driver::new(0.0, STEPS as f64 * self.h)
            .and_then(|d| d.run_fixed(&mut stepper, self.model, &mut s, self.h, &mut monitor))
            .unwrap_or_else(|e| panic!("run failed: {e}"));
        Outcome {
            deviations: monitor.deviations(),
            l0: self.s0.spatial_momentum().norm(),
            seconds: start.elapsed().as_secs_f64(),
        }
    }
}

/// The method is the LGVI or a composition of it.
fn is_lgvi(method: &MethodInfo) -> bool {
    match method.stepping {
        Stepping::Lgvi => true,
        Stepping::Composition { base, .. } => base.stepper == BaseStepper::Lgvi,
        _ => false,
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
        for method in METHODS {
            let info = tumble_integrators::registry::find(method).expect("registered");
            let name = format!("{scene}/{method}");
            let coupled = scene == "free-hoop";
            if !wanted(&name)
                || (coupled && !info.problems.contains(&ProblemKind::CoupledRigidBody))
            {
                continue;
            }
            let out = match scene {
                "free-body" => {
                    let (body, s0) = free_body(&params);
                    build::rigid_body(info, RigidRun { body: &body, s0, h })
                }
                "heavy-top" => {
                    let (top, s0) = HeavyTopScene::top_and_state(&params).expect("defaults");
                    build::rigid_body(info, RigidRun { body: &top, s0, h })
                }
                _ => {
                    let (model, s0) = FreeHoopScene::model(&params).expect("defaults");
                    build::coupled::<_, _, 1>(
                        info,
                        CoupledRun {
                            model: &model,
                            s0,
                            h,
                        },
                    )
                }
            }
            .unwrap_or_else(|e| panic!("{name}: {e}"));
            let stages = match info.stepping {
                Stepping::Composition { table, .. } => table.gammas.len(),
                _ => 1,
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
                if is_lgvi(info) {
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
