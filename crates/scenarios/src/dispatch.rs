//! Dispatch: from a validated [`RunPlan`] to a stepper on the scene's model.
//!
//! This is the one place where a method's registry name becomes a stepper type. Everything
//! else asks the registry ([`tumble_integrators::registry`]) what a method *is* — adaptive,
//! with dense output, which [`ProblemKind`]s it integrates — and a scene states which kinds its
//! model offers ([`crate::SceneInfo::problems`]); the plan carries the kind chosen for the run
//! ([`RunPlan::kind`]). Adding a method means a registry entry and an arm here for each kind it
//! integrates; every scene offering one of those kinds can then run it, with no list to edit.
//! A test runs every scene with every method it derives (`every_scene_runs_every_integrator_it_lists`),
//! so a registry claim without an arm here fails.
//!
//! | kind | model | methods |
//! |---|---|---|
//! | [`ProblemKind::Ode`] | `y' = f(t, y)` on ℝⁿ (a flattened model) | explicit Runge–Kutta, Gauss–Legendre |
//! | [`ProblemKind::RigidBody`] | [`RigidBody`] on SO(3) × ℝ³ | LGVI and its compositions (orders 4–10), principal-axis splittings, exact-flow splitting |
//! | [`ProblemKind::FreeRigidBody`] | [`FreeRigidBody`] | discrete Moser–Veselov, the exact flow |
//! | [`ProblemKind::LieVectorField`] | Euler's equations as a vector field on SO(3) × ℝ³ | RKMK, Crouch–Grossman |
//! | [`ProblemKind::CoupledRigidBody`] | [`CoupledLagrangian`] on SO(3) × ℝⁿ | the coupled LGVI and its compositions (orders 4–10) |
//! | [`ProblemKind::Separable`] | [`SeparableHamiltonian`] `H = T(p) + V(q)` on ℝ²ᵈ | symplectic Euler, Störmer–Verlet, and the composition tables named alone (orders 4–10), which compose Störmer–Verlet |
//! | [`ProblemKind::Split`] | the same Hamiltonian as its drift and kick ([`HamiltonianSplit`]) | Strang splitting |
//!
//! A `TABLE:BASE` name ([`registry::composed`]) is the composition table applied to the base
//! stepper, built here from the table and the base's arm: `lgvi` and `split2` on a rigid body,
//! `lgvi` on a coupled one, `gauss2` on a first-order ODE.

use nalgebra::SVector;
use tumble_integrators::registry;
use tumble_integrators::rigid::{
    CoupledLagrangian, CoupledLgvi, CoupledLieGauss, CoupledState, Dmv, EulerEquations,
    ExactSplitting, ExactStepper, FreeRigidBody, GroupState, Lgvi, PrincipalAxisSplitting,
    RigidBody, RigidBodyState, cg3, coupled_lgvi4, coupled_lgvi6, coupled_lgvi8, coupled_lgvi10,
    lgvi4, lgvi6, lgvi8, lgvi10, lie_gauss4, lie_gauss6, lie_gauss8, lie_gauss10, rkmk4,
    split_exact4, split_exact6, split_exact8, split4, split6, split8,
};
use tumble_integrators::tables::{composition, gauss};
use tumble_integrators::{
    Composition, Counted, Event, ExplicitRungeKutta, HamiltonianSplit, Observer, Ode, Order,
    ProblemKind, Report, Restepped, SeparableHamiltonian, Splitting, SplittingStepper, State,
    Stepper, StormerVerlet, SymplecticEuler, Tolerances, gauss2, gauss4, gauss6, gauss8, gauss10,
    gauss12,
};

use crate::error::SceneError;
use crate::scene::{RunPlan, StepControl};

/// How a dispatched run ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// Time reached.
    pub t: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations (steps, for methods without a right-hand side).
    pub evaluations: u64,
    /// The run ended at a terminal event of the scene (a landing), not at the horizon.
    pub terminated: bool,
}

/// The error for a plan whose method has no stepper for `kind` (a registry entry without its
/// arm here; the dispatch test catches it).
fn no_stepper(plan: &RunPlan, kind: &str) -> SceneError {
    SceneError::UnsupportedIntegrator {
        scene: String::new(),
        name: plan.integrator().to_string(),
        reason: format!("no stepper for it on a {kind} problem"),
        applicable: String::new(),
    }
}

/// The fixed step of a plan (validation guarantees it for a non-adaptive method).
fn fixed_step(plan: &RunPlan) -> Result<f64, SceneError> {
    match plan.step {
        StepControl::Fixed(h) => Ok(h),
        StepControl::Tolerance(tol) => Err(SceneError::InvalidOption {
            option: "tol",
            value: tol,
            reason: format!(
                "`{}` has a fixed step: give a step instead",
                plan.integrator()
            ),
        }),
    }
}

/// Integrates a first-order system `y' = f(t, y)` ([`ProblemKind::Ode`]) from `y` over the
/// plan's horizon, with `events` (located on dense output; a terminal event ends the run).
///
/// # Errors
/// Integration failures; a method without dense output asked to locate events.
pub fn run_ode<P, O, const S: usize>(
    problem: &P,
    y: &mut SVector<f64, S>,
    plan: &RunPlan,
    events: &mut [Event<'_, SVector<f64, S>>],
    observer: &mut O,
) -> Result<Outcome, SceneError>
where
    P: Ode<SVector<f64, S>>,
    O: Observer<SVector<f64, S>>,
{
    let counted = tumble_integrators::Counted::new(ByRef(problem));
    let driver = plan.driver()?;
    let name = plan.integrator();
    let report = match plan.step {
        StepControl::Tolerance(tol) => {
            let tolerances = Tolerances::new(tol, tol)?;
            macro_rules! adaptive {
                ($stepper:expr) => {{
                    let mut stepper = $stepper;
                    driver.run_adaptive(&mut stepper, &counted, y, &tolerances, events, observer)?
                }};
            }
            match name {
                "dp5" => adaptive!(ExplicitRungeKutta::dp5().stepper(y)),
                "dop853" => adaptive!(ExplicitRungeKutta::dop853().stepper(y)),
                "tsit5" => adaptive!(ExplicitRungeKutta::tsit5().stepper(y)),
                "vern6" => adaptive!(ExplicitRungeKutta::vern6().stepper(y)),
                "vern7" => adaptive!(ExplicitRungeKutta::vern7().stepper(y)),
                "vern8" => adaptive!(ExplicitRungeKutta::vern8().stepper(y)),
                "vern9" => adaptive!(ExplicitRungeKutta::vern9().stepper(y)),
                _ => return Err(no_stepper(plan, "first-order ODE")),
            }
        }
        StepControl::Fixed(h) => {
            macro_rules! fixed {
                ($stepper:expr) => {{
                    let mut stepper = $stepper;
                    if events.is_empty() && plan.times.is_none() && !observer.wants_dense_steps() {
                        driver.run_fixed(&mut stepper, &counted, y, h, observer)?
                    } else {
                        driver.run_fixed_with_events(
                            &mut stepper,
                            &counted,
                            y,
                            h,
                            events,
                            observer,
                        )?
                    }
                }};
            }
            match (name, registry::composed(name)) {
                (_, Some((table, base))) if base.name == "gauss2" => {
                    // Dense output, where asked for, by re-stepping (a composition has no
                    // interpolant of its own).
                    let mut stepper = Composition::new(table, gauss2().stepper(y));
                    if events.is_empty() && plan.times.is_none() && !observer.wants_dense_steps() {
                        driver.run_fixed(&mut stepper, &counted, y, h, observer)?
                    } else {
                        let mut dense = Restepped::new(stepper, interpolation_order(plan));
                        driver
                            .run_fixed_with_events(&mut dense, &counted, y, h, events, observer)?
                    }
                }
                ("rk4", _) => fixed!(ExplicitRungeKutta::rk4().stepper(y)),
                ("gauss2", _) => fixed!(gauss2().stepper(y)),
                ("gauss4", _) => fixed!(gauss4().stepper(y)),
                ("gauss6", _) => fixed!(gauss6().stepper(y)),
                ("gauss8", _) => fixed!(gauss8().stepper(y)),
                ("gauss10", _) => fixed!(gauss10().stepper(y)),
                ("gauss12", _) => fixed!(gauss12().stepper(y)),
                _ => return Err(no_stepper(plan, "first-order ODE")),
            }
        }
    };
    Ok(Outcome {
        t: report.t,
        steps: report.steps,
        evaluations: counted.evaluations().rhs,
        terminated: matches!(report.status, tumble_integrators::Status::Terminated(_)),
    })
}

/// Integrates a rigid body on SO(3) × ℝ³ ([`ProblemKind::RigidBody`],
/// [`ProblemKind::LieVectorField`], and with `free` — the same body as a [`FreeRigidBody`] when
/// it is torque-free — [`ProblemKind::FreeRigidBody`]) from `state` over the plan's horizon.
///
/// # Errors
/// Integration failures.
pub fn run_rigid_body<B, O>(
    body: &B,
    free: Option<&FreeRigidBody>,
    state: &mut RigidBodyState,
    plan: &RunPlan,
    observer: &mut O,
) -> Result<Outcome, SceneError>
where
    B: RigidBody + Copy,
    O: Observer<RigidBodyState>,
{
    macro_rules! on {
        ($problem:expr, $stepper:expr) => {{
            let report = run_fixed($stepper, $problem, state, plan, observer)?;
            (report.t, report.steps)
        }};
    }
    let (t, steps) = if let Some((table, base)) = registry::composed(plan.integrator()) {
        match (plan.kind, base.name) {
            (ProblemKind::RigidBody, "lgvi") => on!(body, Composition::new(table, Lgvi::new())),
            (ProblemKind::RigidBody, "split2") => {
                on!(body, Composition::new(table, PrincipalAxisSplitting::new()))
            }
            (ProblemKind::RigidBody, "split-exact2") => {
                on!(body, Composition::new(table, ExactSplitting::new()))
            }
            (kind, _) => return Err(no_stepper(plan, kind.name())),
        }
    } else {
        match (plan.kind, plan.integrator(), free) {
            (ProblemKind::RigidBody, "lgvi", _) => on!(body, Lgvi::new()),
            (ProblemKind::RigidBody, "lgvi4", _) => on!(body, lgvi4()),
            (ProblemKind::RigidBody, "lgvi6", _) => on!(body, lgvi6()),
            (ProblemKind::RigidBody, "lgvi8", _) => on!(body, lgvi8()),
            (ProblemKind::RigidBody, "lgvi10", _) => on!(body, lgvi10()),
            (ProblemKind::RigidBody, "lie-gauss4", _) => on!(body, lie_gauss4()),
            (ProblemKind::RigidBody, "lie-gauss6", _) => on!(body, lie_gauss6()),
            (ProblemKind::RigidBody, "lie-gauss8", _) => on!(body, lie_gauss8()),
            (ProblemKind::RigidBody, "lie-gauss10", _) => on!(body, lie_gauss10()),
            (ProblemKind::RigidBody, "split2", _) => on!(body, PrincipalAxisSplitting::new()),
            (ProblemKind::RigidBody, "split4", _) => on!(body, split4()),
            (ProblemKind::RigidBody, "split6", _) => on!(body, split6()),
            (ProblemKind::RigidBody, "split8", _) => on!(body, split8()),
            (ProblemKind::RigidBody, "split-exact2", _) => on!(body, ExactSplitting::new()),
            (ProblemKind::RigidBody, "split-exact4", _) => on!(body, split_exact4()),
            (ProblemKind::RigidBody, "split-exact6", _) => on!(body, split_exact6()),
            (ProblemKind::RigidBody, "split-exact8", _) => on!(body, split_exact8()),
            (ProblemKind::FreeRigidBody, "dmv", Some(free)) => on!(free, Dmv::new()),
            (ProblemKind::FreeRigidBody, "exact", Some(free)) => on!(free, ExactStepper::new()),
            (ProblemKind::LieVectorField, "rkmk4", _) => {
                on!(&EulerEquations(*body), OnRigidBody(rkmk4::<3>()))
            }
            (ProblemKind::LieVectorField, "cg3", _) => {
                on!(&EulerEquations(*body), OnRigidBody(cg3::<3>()))
            }
            (kind, _, _) => return Err(no_stepper(plan, kind.name())),
        }
    };
    Ok(Outcome {
        t,
        steps,
        evaluations: steps,
        terminated: false,
    })
}

/// Integrates a rigid body coupled to `N` coordinates ([`ProblemKind::CoupledRigidBody`]) from
/// `state` over the plan's horizon.
///
/// # Errors
/// Integration failures.
pub fn run_coupled<L, O, const N: usize>(
    model: &L,
    state: &mut CoupledState<N>,
    plan: &RunPlan,
    observer: &mut O,
) -> Result<Outcome, SceneError>
where
    L: CoupledLagrangian<N>,
    O: Observer<CoupledState<N>>,
{
    macro_rules! on {
        ($stepper:expr) => {
            run_fixed($stepper, model, state, plan, observer)?
        };
    }
    let composed = registry::composed(plan.integrator()).map(|(table, base)| (table, base.name));
    let report = match (plan.kind, plan.integrator(), composed) {
        (ProblemKind::CoupledRigidBody, _, Some((table, "lgvi"))) => {
            on!(Composition::new(table, CoupledLgvi::<N>::new()))
        }
        (ProblemKind::CoupledRigidBody, "lgvi", _) => on!(CoupledLgvi::<N>::new()),
        (ProblemKind::CoupledRigidBody, "lgvi4", _) => on!(coupled_lgvi4::<N>()),
        (ProblemKind::CoupledRigidBody, "lgvi6", _) => on!(coupled_lgvi6::<N>()),
        (ProblemKind::CoupledRigidBody, "lgvi8", _) => on!(coupled_lgvi8::<N>()),
        (ProblemKind::CoupledRigidBody, "lgvi10", _) => on!(coupled_lgvi10::<N>()),
        (ProblemKind::CoupledRigidBody, "lie-gauss4", _) => {
            on!(CoupledLieGauss::<2, N>::new(&gauss::GAUSS4))
        }
        (ProblemKind::CoupledRigidBody, "lie-gauss6", _) => {
            on!(CoupledLieGauss::<3, N>::new(&gauss::GAUSS6))
        }
        (ProblemKind::CoupledRigidBody, "lie-gauss8", _) => {
            on!(CoupledLieGauss::<4, N>::new(&gauss::GAUSS8))
        }
        (ProblemKind::CoupledRigidBody, "lie-gauss10", _) => {
            on!(CoupledLieGauss::<5, N>::new(&gauss::GAUSS10))
        }
        (kind, _, _) => return Err(no_stepper(plan, kind.name())),
    };
    Ok(Outcome {
        t: report.t,
        steps: report.steps,
        evaluations: report.steps,
        terminated: false,
    })
}

/// Integrates a separable Hamiltonian `H = T(p) + V(q)` from `y = (q, p)` over the plan's
/// horizon: as [`ProblemKind::Separable`] with symplectic Euler, Störmer–Verlet or a composition
/// table named alone (which composes Störmer–Verlet), or as [`ProblemKind::Split`] — the drift
/// and kick of [`HamiltonianSplit`] — with Strang splitting. Output at chosen times and dense
/// rows re-step the method ([`Restepped`]). [`Outcome::evaluations`] counts `∇V` evaluations
/// (Störmer–Verlet reuses the last one of a step as the first of the next), or sub-flows of
/// the split.
///
/// # Errors
/// Integration failures.
pub fn run_separable<H, O, const S: usize>(
    model: &H,
    y: &mut SVector<f64, S>,
    plan: &RunPlan,
    observer: &mut O,
) -> Result<Outcome, SceneError>
where
    H: SeparableHamiltonian,
    O: Observer<SVector<f64, S>>,
{
    let name = plan.integrator();
    let (report, evaluations) = match plan.kind {
        ProblemKind::Separable => {
            let counted = Counted::new(model);
            let table = composition::ALL.into_iter().find(|t| t.name == name);
            let report = match (name, table) {
                ("symplectic-euler", _) => run_fixed(
                    SymplecticEuler::default().stepper(y),
                    &counted,
                    y,
                    plan,
                    observer,
                )?,
                ("verlet", _) => run_fixed(
                    StormerVerlet::default().stepper(y),
                    &counted,
                    y,
                    plan,
                    observer,
                )?,
                (_, Some(table)) => run_fixed(
                    Composition::new(table, StormerVerlet::default().stepper(y)),
                    &counted,
                    y,
                    plan,
                    observer,
                )?,
                _ => return Err(no_stepper(plan, "separable Hamiltonian")),
            };
            (report, counted.evaluations().potential_gradients)
        }
        ProblemKind::Split => {
            let counted = Counted::new(HamiltonianSplit::new(model));
            let report = match name {
                "strang" => run_fixed(
                    SplittingStepper::new(Splitting::Strang),
                    &counted,
                    y,
                    plan,
                    observer,
                )?,
                _ => return Err(no_stepper(plan, "split")),
            };
            (report, counted.evaluations().flows)
        }
        kind => return Err(no_stepper(plan, kind.name())),
    };
    Ok(Outcome {
        t: report.t,
        steps: report.steps,
        evaluations,
        terminated: false,
    })
}

/// Runs a fixed-step method without an interpolant of its own over the plan: plainly, or
/// wrapped in [`Restepped`] when the plan asks for output times or the observer for dense
/// steps (the one place the rigid-body, coupled and separable runs make that choice).
fn run_fixed<P: ?Sized, S: State, St: Stepper<P, State = S> + Clone, O: Observer<S>>(
    mut stepper: St,
    problem: &P,
    state: &mut S,
    plan: &RunPlan,
    observer: &mut O,
) -> Result<Report<S>, SceneError> {
    let h = fixed_step(plan)?;
    let driver = plan.driver()?;
    Ok(if plan.times.is_some() || observer.wants_dense_steps() {
        let mut dense = Restepped::new(stepper, interpolation_order(plan));
        driver.run_fixed_with_events(&mut dense, problem, state, h, &mut [], observer)?
    } else {
        driver.run_fixed(&mut stepper, problem, state, h, observer)?
    })
}

/// The order of a re-stepped dense output ([`Restepped`]): the method's own (an exact flow
/// interpolates exactly).
fn interpolation_order(plan: &RunPlan) -> u32 {
    match plan.method.order {
        Order::Finite(p) => p,
        Order::Exact => u32::MAX,
    }
}

/// A Lie-group method on `GroupState<3>` stepping a [`RigidBodyState`] (the same numbers: the
/// rotation and the body momentum).
#[derive(Clone)]
struct OnRigidBody<St>(St);

impl<P: ?Sized, St: Stepper<P, State = GroupState<3>>> Stepper<P> for OnRigidBody<St> {
    type State = RigidBodyState;

    fn step(
        &mut self,
        problem: &P,
        t: f64,
        state: &mut RigidBodyState,
        h: f64,
    ) -> Result<(), tumble_integrators::Error> {
        let mut g = GroupState {
            rotation: state.rotation,
            vector: state.momentum,
        };
        let stepped = self.0.step(problem, t, &mut g, h);
        *state = RigidBodyState {
            rotation: g.rotation,
            momentum: g.vector,
        };
        stepped
    }

    fn reset(&mut self) {
        self.0.reset();
    }
}

/// A problem used through a reference (the integrators' traits are implemented for owned
/// problems).
struct ByRef<'a, P>(&'a P);

impl<P: Ode<SVector<f64, S>>, const S: usize> Ode<SVector<f64, S>> for ByRef<'_, P> {
    fn rhs(&self, t: f64, y: &SVector<f64, S>, dy: &mut SVector<f64, S>) {
        self.0.rhs(t, y, dy);
    }
    fn jacobian(&self, t: f64, y: &SVector<f64, S>, jac: &mut [f64]) -> bool {
        self.0.jacobian(t, y, jac)
    }
}
