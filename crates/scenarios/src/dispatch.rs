//! Dispatch: from a validated [`RunPlan`] to a stepper on the scene's model.
//!
//! The registry builds a method's stepper ([`tumble_integrators::registry::build`]: one
//! function per [`ProblemKind`], matching every family without a wildcard); this module
//! supplies the receivers that run it on a scene's model with the plan's driver, step
//! control, events and observer. No method is named here: a new table of an existing family
//! (an explicit pair, a Gauss table, a composition) is a registry row and runs on every scene
//! offering its kind; a new family is a compile error in the builders until each kind says
//! what it does with it. A scene states which kinds its model offers
//! ([`crate::SceneInfo::problems`]); the plan carries the kind chosen for the run
//! ([`RunPlan::kind`]). A test runs every scene with every method it derives
//! (`every_scene_runs_every_integrator_it_lists`).
//!
//! | kind | model | methods |
//! |---|---|---|
//! | [`ProblemKind::Ode`] | `y' = f(t, y)` on ℝⁿ (a flattened model) | explicit Runge–Kutta, Gauss–Legendre |
//! | [`ProblemKind::TaylorSeries`] | `y' = f(t, y)` on ℝⁿ computing its Taylor coefficients ([`TaylorSystem`]) | the Taylor methods |
//! | [`ProblemKind::DoubleDoubleTaylorSeries`] | the same, its coefficients also in double-double ([`TaylorSystem::double_double`]) | `taylor-dd` |
//! | [`ProblemKind::RigidBody`] | [`RigidBody`] on SO(3) × ℝ³ | LGVI and its compositions (orders 4–10), principal-axis splittings, exact-flow splitting |
//! | [`ProblemKind::FreeRigidBody`] | [`FreeRigidBody`] | discrete Moser–Veselov, the exact flow |
//! | [`ProblemKind::LieVectorField`] | Euler's equations as a vector field on SO(3) × ℝ³ | RKMK, Crouch–Grossman |
//! | [`ProblemKind::ProductVectorField`] | a vector field on SO(3)ᴹ × ℝⁿ ([`ProductVectorField`]: several orientations) | RKMK, Crouch–Grossman |
//! | [`ProblemKind::ProductLagrangian`] | the same state's Lagrangian by its derivatives ([`ProductLagrangian`]) | the LGVI on the product and its compositions (orders 4–10) |
//! | [`ProblemKind::CoupledRigidBody`] | [`CoupledLagrangian`] on SO(3) × ℝⁿ | the coupled LGVI and its compositions (orders 4–10) |
//! | [`ProblemKind::Separable`] | [`SeparableHamiltonian`] `H = T(p) + V(q)` on ℝ²ᵈ | symplectic Euler, Störmer–Verlet, and the composition tables named alone (orders 4–10), which compose Störmer–Verlet |
//! | [`ProblemKind::Split`] | the same Hamiltonian as its drift and kick ([`HamiltonianSplit`]) | Strang splitting |
//!
//! A `TABLE:BASE` name ([`tumble_integrators::registry::composed`]) is the composition table
//! applied to the base stepper: `lgvi`, `split2` and `split-exact2` on a rigid body, `lgvi` on a
//! coupled one, `gauss2` on a first-order ODE.

use nalgebra::SVector;
use tumble_integrators::registry::build::{self, NoStepper, Receive, ReceiveOde};
use tumble_integrators::rigid::{
    CoupledLagrangian, CoupledState, EulerEquations, FreeRigidBody, GroupState, ProductLagrangian,
    ProductState, ProductVectorField, RigidBody, RigidBodyState,
};
use tumble_integrators::{
    AdaptiveStepper, Counted, DenseOutput, Driver, Event, HamiltonianSplit, Observer, Ode, Order,
    ProblemKind, Report, Restepped, SeparableHamiltonian, State, Stepper, TaylorSystem, Tolerances,
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

/// The error for a plan whose method has no stepper for `kind` (validation chooses a kind the
/// method integrates, so only a scene calling the wrong `run_*` for its plan meets it).
fn no_stepper(plan: &RunPlan, kind: &str) -> SceneError {
    SceneError::UnsupportedIntegrator {
        scene: String::new(),
        name: plan.integrator().to_string(),
        reason: format!("no stepper for it on a {kind} problem"),
        applicable: String::new(),
    }
}

impl From<NoStepper> for SceneError {
    fn from(e: NoStepper) -> Self {
        SceneError::UnsupportedIntegrator {
            scene: String::new(),
            name: e.method.to_string(),
            reason: format!("no stepper for it on a {} problem", e.kind.name()),
            applicable: String::new(),
        }
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

/// Runs an ODE method's stepper over the plan: adaptive with a tolerance, fixed steps (with
/// events and output times on the stepper's interpolant, or on re-stepping for a method
/// without one) with a step.
struct OdeRun<'r, 'e, P, O, const S: usize> {
    problem: &'r P,
    y: &'r mut SVector<f64, S>,
    plan: &'r RunPlan,
    driver: Driver<'r>,
    events: &'r mut [Event<'e, SVector<f64, S>>],
    observer: &'r mut O,
}

type OdeResult<const S: usize> = Result<Report<SVector<f64, S>>, SceneError>;

impl<P, O, const S: usize> OdeRun<'_, '_, P, O, S>
where
    O: Observer<SVector<f64, S>>,
{
    /// Fixed steps on the stepper's own interpolant, where one is needed.
    fn fixed<St: DenseOutput<P, State = SVector<f64, S>>>(self, mut stepper: St) -> OdeResult<S> {
        let h = self.step(false)?;
        let (driver, y, events, observer) = (self.driver, self.y, self.events, self.observer);
        Ok(
            if events.is_empty() && self.plan.times.is_none() && !observer.wants_dense_steps() {
                driver.run_fixed(&mut stepper, self.problem, y, h, observer)?
            } else {
                driver.run_fixed_with_events(&mut stepper, self.problem, y, h, events, observer)?
            },
        )
    }

    /// The plan's fixed step for a method that is (`adaptive`) or is not adaptive; the error
    /// of a plan that gives the other control.
    fn step(&self, adaptive: bool) -> Result<f64, SceneError> {
        match (self.plan.step, adaptive) {
            (StepControl::Fixed(h), false) => Ok(h),
            _ => Err(no_stepper(self.plan, "first-order ODE")),
        }
    }
}

impl<P, O, const S: usize> ReceiveOde<P, SVector<f64, S>> for OdeRun<'_, '_, P, O, S>
where
    O: Observer<SVector<f64, S>>,
{
    type Output = OdeResult<S>;

    fn adaptive<St: AdaptiveStepper<P, State = SVector<f64, S>> + DenseOutput<P>>(
        self,
        mut stepper: St,
    ) -> OdeResult<S> {
        let StepControl::Tolerance(tol) = self.plan.step else {
            return Err(no_stepper(self.plan, "first-order ODE"));
        };
        let tolerances = Tolerances::new(tol, tol)?;
        Ok(self.driver.run_adaptive(
            &mut stepper,
            self.problem,
            self.y,
            &tolerances,
            self.events,
            self.observer,
        )?)
    }

    fn interpolating<St: DenseOutput<P, State = SVector<f64, S>>>(
        self,
        stepper: St,
    ) -> OdeResult<S> {
        self.fixed(stepper)
    }

    fn plain<St: Stepper<P, State = SVector<f64, S>> + Clone>(
        self,
        mut stepper: St,
    ) -> OdeResult<S> {
        // Dense output, where asked for, by re-stepping (no interpolant of its own).
        let h = self.step(false)?;
        if self.events.is_empty() && self.plan.times.is_none() && !self.observer.wants_dense_steps()
        {
            Ok(self
                .driver
                .run_fixed(&mut stepper, self.problem, self.y, h, self.observer)?)
        } else {
            let mut dense = Restepped::new(stepper, interpolation_order(self.plan));
            Ok(self.driver.run_fixed_with_events(
                &mut dense,
                self.problem,
                self.y,
                h,
                self.events,
                self.observer,
            )?)
        }
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
    let counted = Counted::new(ByRef(problem));
    let y0 = *y;
    let run = OdeRun {
        problem: &counted,
        y,
        plan,
        driver: plan.driver()?,
        events,
        observer,
    };
    let report = build::ode(plan.method, &y0, run)??;
    Ok(Outcome {
        t: report.t,
        steps: report.steps,
        evaluations: counted.evaluations().rhs,
        terminated: matches!(report.status, tumble_integrators::Status::Terminated(_)),
    })
}

/// Integrates a first-order system that computes the Taylor coefficients of its solution
/// ([`ProblemKind::TaylorSeries`], [`TaylorSystem`]) from `y` over the plan's horizon with a
/// Taylor method, with `events` (located on the step's Taylor polynomial; a terminal event ends
/// the run). [`Outcome::evaluations`] counts coefficient expansions (one per step, none
/// rejected).
///
/// # Errors
/// Integration failures.
pub fn run_taylor<P, O, const S: usize>(
    problem: &P,
    y: &mut SVector<f64, S>,
    plan: &RunPlan,
    events: &mut [Event<'_, SVector<f64, S>>],
    observer: &mut O,
) -> Result<Outcome, SceneError>
where
    P: TaylorSystem,
    O: Observer<SVector<f64, S>>,
{
    if !matches!(
        plan.kind,
        ProblemKind::TaylorSeries | ProblemKind::DoubleDoubleTaylorSeries
    ) {
        return Err(no_stepper(plan, plan.kind.name()));
    }
    let y0 = *y;
    let run = OdeRun {
        problem,
        y,
        plan,
        driver: plan.driver()?,
        events,
        observer,
    };
    let report = build::taylor(plan.method, &y0, run)??;
    Ok(Outcome {
        t: report.t,
        steps: report.steps,
        evaluations: report.steps + report.rejected,
        terminated: matches!(report.status, tumble_integrators::Status::Terminated(_)),
    })
}

/// Runs a fixed-step stepper on `problem` from `state` over the plan ([`run_fixed`]).
struct FixedRun<'r, P: ?Sized, S, O> {
    problem: &'r P,
    state: &'r mut S,
    plan: &'r RunPlan,
    observer: &'r mut O,
}

impl<P: ?Sized, S: State, O: Observer<S>> Receive<P, S> for FixedRun<'_, P, S, O> {
    type Output = Result<Report<S>, SceneError>;
    fn receive<St: Stepper<P, State = S> + Clone>(self, stepper: St) -> Self::Output {
        run_fixed(stepper, self.problem, self.state, self.plan, self.observer)
    }
}

/// Runs a Lie-group stepper on `GroupState<3>` as a stepper of [`RigidBodyState`]
/// ([`OnRigidBody`]).
struct FixedRunOnGroup<'r, P: ?Sized, O>(FixedRun<'r, P, RigidBodyState, O>);

impl<P: ?Sized, O: Observer<RigidBodyState>> Receive<P, GroupState<3>>
    for FixedRunOnGroup<'_, P, O>
{
    type Output = Result<Report<RigidBodyState>, SceneError>;
    fn receive<St: Stepper<P, State = GroupState<3>> + Clone>(self, stepper: St) -> Self::Output {
        self.0.receive(OnRigidBody(stepper))
    }
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
    let report = match (plan.kind, free) {
        (ProblemKind::RigidBody, _) => {
            let run = FixedRun {
                problem: body,
                state,
                plan,
                observer,
            };
            build::rigid_body(plan.method, run)??
        }
        (ProblemKind::FreeRigidBody, Some(free)) => {
            let run = FixedRun {
                problem: free,
                state,
                plan,
                observer,
            };
            build::free_rigid_body(plan.method, run)??
        }
        (ProblemKind::LieVectorField, _) => {
            let field = EulerEquations(*body);
            let run = FixedRunOnGroup(FixedRun {
                problem: &field,
                state,
                plan,
                observer,
            });
            build::lie_vector_field::<EulerEquations<B>, _, 3>(plan.method, run)??
        }
        (kind, _) => return Err(no_stepper(plan, kind.name())),
    };
    Ok(Outcome {
        t: report.t,
        steps: report.steps,
        evaluations: report.steps,
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
    if plan.kind != ProblemKind::CoupledRigidBody {
        return Err(no_stepper(plan, plan.kind.name()));
    }
    let run = FixedRun {
        problem: model,
        state,
        plan,
        observer,
    };
    let report = build::coupled::<L, _, N>(plan.method, run)??;
    Ok(Outcome {
        t: report.t,
        steps: report.steps,
        evaluations: report.steps,
        terminated: false,
    })
}

/// Integrates a system on the product `SO(3)ᴹ × ℝᴺ` from `state` over the plan's horizon: as
/// its vector field ([`ProblemKind::ProductVectorField`]) or its Lagrangian
/// ([`ProblemKind::ProductLagrangian`]), as the plan's kind says.
///
/// # Errors
/// Integration failures.
pub fn run_product<F, O, const M: usize, const N: usize>(
    system: &F,
    state: &mut ProductState<M, N>,
    plan: &RunPlan,
    observer: &mut O,
) -> Result<Outcome, SceneError>
where
    F: ProductVectorField<M, N> + ProductLagrangian<M, N>,
    O: Observer<ProductState<M, N>>,
{
    let run = FixedRun {
        problem: system,
        state,
        plan,
        observer,
    };
    let report = match plan.kind {
        ProblemKind::ProductVectorField => {
            build::product_vector_field::<F, _, M, N>(plan.method, run)??
        }
        ProblemKind::ProductLagrangian => {
            build::product_lagrangian::<F, _, M, N>(plan.method, run)??
        }
        kind => return Err(no_stepper(plan, kind.name())),
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
    let y0 = *y;
    let (report, evaluations) = match plan.kind {
        ProblemKind::Separable => {
            let counted = Counted::new(model);
            let run = FixedRun {
                problem: &counted,
                state: y,
                plan,
                observer,
            };
            let report = build::separable(plan.method, &y0, run)??;
            (report, counted.evaluations().potential_gradients)
        }
        ProblemKind::Split => {
            let counted = Counted::new(HamiltonianSplit::new(model));
            let run = FixedRun {
                problem: &counted,
                state: y,
                plan,
                observer,
            };
            let report = build::split(plan.method, run)??;
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
        Order::Exact | Order::Variable => u32::MAX,
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
