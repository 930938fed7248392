//! # tumble-integrators
//!
//! Integrators for tumble's models, with accuracy we can measure: explicit Runge–Kutta with
//! error control (RK4, Dormand–Prince 5(4), DOP853, Tsitouras 5(4) and Verner's "most
//! efficient" 6(5), 7(6), 8(7), 9(8) pairs, all with dense output and event location),
//! symplectic Euler and Störmer–Verlet, symmetric compositions of any symmetric base method
//! (Yoshida 4/6/8, Suzuki 4, McLachlan 4, Kahan–Li 6/8, Sofroniou–Spaletta 10), Gauss–Legendre
//! collocation with 1…6 stages, and, in [`rigid`], methods on `SO(3)` and `SO(3) × ℝⁿ`: the
//! exact free-rigid-body flow, the Lee–Leok–McClamroch Lie group variational integrator (also
//! for bodies coupled to extra coordinates), Runge–Kutta–Munthe-Kaas 4, Crouch–Grossman 3,
//! principal-axis splitting composed to orders 2–8, and discrete Moser–Veselov.
//!
//! ## Design
//!
//! - **Methods as data.** Butcher tableaux and composition coefficients are `const` tables
//!   in [`tables`], one module per family, each citing its source; coefficients are exact
//!   (rationals, or 30-digit literals generated at high precision by
//!   `tools/gen_tables.py`). One generic stepper walks each family's tables
//!   ([`explicit`], [`gauss`], [`composition`]).
//! - **Method, stepper, driver.** A method value holds only its table and tolerances
//!   ([`ExplicitRungeKutta`], [`Gauss`], [`StormerVerlet`]); `method.stepper(&y0)` builds
//!   the workspace of one run (allocated once; nothing is allocated per step). The
//!   [`Driver`] owns the loop: horizon (landing exactly on `t_end`), fixed or adaptive steps,
//!   events, observers every `n` steps, cancellation.
//! - **Problems as capabilities.** [`Ode`] (`y' = f(t, y)` into a buffer, optional
//!   Jacobian), [`SplitOde`] (sub-flows), [`SeparableHamiltonian`] (`∂T/∂p`, `∇V`);
//!   [`Counted`] counts evaluations.
//! - **States.** Steppers are generic over [`VectorState`] (`SVector<f64, N>` on the stack,
//!   `DVector<f64>`, `[f64; N]`). The [`Stepper`] trait itself asks only for [`State`]
//!   (finiteness and a snapshot for errors), so [`Composition`] raises the order of *any*
//!   symmetric base stepper, including Lie-group steps on `SO(3) × ℝⁿ`.
//! - **Round-off.** Fixed-step updates use compensated summation with a carried error term
//!   (Kahan), so long runs follow Brouwer's `√n` law; implicit stages iterate until the
//!   increment stops decreasing rather than to an arbitrary tolerance.
//! - **Errors, not NaN.** Bad parameters and numerical failures are [`Error`] values (with
//!   time and state); the library never prints and does not panic on user input.
//! - **Lie groups.** Rigid-body states keep `R` as a 3×3 matrix and every method moves it by
//!   group operations (exponentials, Cayley maps, exact rotations), applied as compensated
//!   increments `R + R G`; problems are capabilities again ([`rigid::RigidBody`],
//!   [`rigid::LieVectorField`], [`rigid::CoupledLagrangian`]); diagnostics are observers.
//! - **Verification.** [`verification`] is the shared observed-order harness and the exact
//!   test problems.
//! - **Registry.** [`registry`] lists every method as a row holding its family and its table
//!   ([`registry::Stepping`]), from which its order, stages and properties are derived, and
//!   [`registry::build`] makes a row's stepper for a kind of problem: the one place a method
//!   becomes a stepper, matched by family, so a family without a case is a compile error.
//!
//! ## Example
//!
//! ```
//! use nalgebra::SVector;
//! use tumble_integrators::{Driver, HamiltonianOde, NoObserver, gauss6, verification::Kepler};
//!
//! let problem = HamiltonianOde(Kepler);
//! let mut y = SVector::<f64, 4>::from(Kepler::initial(0.6));
//! let mut stepper = gauss6().stepper(&y);
//! let t_end = 2.0 * std::f64::consts::PI;
//! Driver::new(0.0, t_end)?.run_fixed(&mut stepper, &problem, &mut y, t_end / 200.0, &mut NoObserver)?;
//! let exact = Kepler::exact(0.6, t_end);
//! assert!((y[0] - exact[0]).abs() < 1e-6);
//! # Ok::<(), tumble_integrators::Error>(())
//! ```
//!
//! # References
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*,
//!   Springer 1993.
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., Springer
//!   2006.
//! - E. Hairer, R. I. McLachlan, A. Razakarivony, *Achieving Brouwer's law with implicit
//!   Runge–Kutta methods*, BIT 48 (2008) 231–243.

pub mod composition;
pub mod control;
pub mod driver;
pub mod error;
pub mod explicit;
pub mod gauss;
pub mod problem;
pub mod registry;
pub mod restep;
pub mod rigid;
pub mod roots;
pub mod special;
pub mod state;
pub mod stepper;
pub mod symplectic;
pub mod tables;
pub mod taylor;
pub mod verification;

pub use composition::Composition;
pub use control::PiController;
pub use driver::{
    Action, DenseStep, Direction, Driver, Event, EventRecord, Flow, FnObserver, NoObserver,
    Observer, Report, Status,
};
pub use error::Error;
pub use explicit::{
    Dop853, Dp5, ExplicitRkStepper, ExplicitRungeKutta, Rk4, Tsit5, Vern6, Vern7, Vern8, Vern9,
};
pub use gauss::{
    Gauss, GaussStepper, StageSolver, gauss2, gauss4, gauss6, gauss8, gauss10, gauss12,
};
pub use problem::{
    Counted, Evaluations, FnOde, HamiltonianOde, HamiltonianSplit, Ode, SeparableHamiltonian,
    SplitOde,
};
pub use registry::{Family, MethodInfo, Order, ProblemKind, Properties};
pub use restep::Restepped;
pub use state::{State, VectorState};
pub use stepper::{AdaptiveStepper, DenseOutput, Stepper, Tolerances};
pub use symplectic::{
    HamiltonianStepper, Splitting, SplittingStepper, StormerVerlet, SymplecticEuler,
};
pub use taylor::{
    DoubleDouble, DoubleDoubleSystem, DoubleDoubleTaylorStepper, Taylor, TaylorError, TaylorOrder,
    TaylorStepper, TaylorSystem,
};
