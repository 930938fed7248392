//! The stepper traits: what a driver (or a composition) asks of a method.
//!
//! A *method* (a table plus its tolerances, e.g. [`crate::Dop853`], [`crate::Gauss`]) holds
//! no run-time state; `method.stepper(&y0)` builds a *stepper*: the method's table together
//! with the workspace of one run (stage vectors, carried compensation terms, cached
//! derivatives). Steppers allocate only when they are built, never per step.
//!
//! [`Stepper`] is deliberately small — one step of a given size from a given time — and
//! places no bound on the state beyond [`State`], so that a composition can raise the order
//! of any symmetric base method, including Lie-group and splitting steps whose state is not
//! a vector space.

use crate::error::Error;
use crate::state::State;

/// One step of a one-step method.
pub trait Stepper<P: ?Sized> {
    /// What the stepper advances.
    type State: State;

    /// Advances `state` from `t` to `t + h`. `h` may be negative when the stepper is used
    /// inside a composition with negative coefficients.
    ///
    /// Steppers may cache data of their last step (the derivative at its end, the carried
    /// compensation term, the stage values used to extrapolate starting values); they use
    /// a cache only when `t` and `state` are exactly what their last step produced, so a
    /// caller that modifies the state between steps gets a correct (uncached) step.
    ///
    /// # Errors
    /// Numerical failures of the step (non-convergence of implicit stages, a singular
    /// Newton matrix), with the time and the state at the start of the step.
    fn step(&mut self, problem: &P, t: f64, state: &mut Self::State, h: f64) -> Result<(), Error>;

    /// Forgets every cached value (called by drivers when they change the state).
    fn reset(&mut self) {}
}

/// A stepper with an error estimate, for adaptive step-size control.
pub trait AdaptiveStepper<P: ?Sized>: Stepper<P> {
    /// The order `q` used in the controller's exponent `1/q` (the lower order of the
    /// embedded pair plus one).
    fn error_order(&self) -> u32;

    /// The step-size controller's parameters.
    fn controller(&self) -> crate::control::PiController;

    /// Computes a step of size `h` from `(t, state)` without committing it and returns the
    /// scaled error norm (accept when `≤ 1`).
    ///
    /// # Errors
    /// Numerical failures of the step.
    fn attempt(
        &mut self,
        problem: &P,
        t: f64,
        state: &Self::State,
        h: f64,
        tolerances: &Tolerances,
    ) -> Result<f64, Error>;

    /// Commits the last attempt: `state` becomes the solution at `t + h`.
    fn accept(&mut self, problem: &P, t: f64, state: &mut Self::State, h: f64);

    /// A starting step size for `(t, state)` and the tolerances (Hairer's `hinit`).
    fn initial_step(
        &mut self,
        problem: &P,
        t: f64,
        state: &Self::State,
        h_max: f64,
        tolerances: &Tolerances,
    ) -> f64;

    /// The step the method chooses itself at `(t, state)` for `tolerances`, called by the
    /// driver after each accepted or rejected attempt: `Some(h)` replaces the step-size
    /// controller (a Taylor method's step comes from the coefficients at the point,
    /// [`crate::taylor`]), and the driver then lands on `t_end` without stretching the last
    /// step. The default is `None`: the controller chooses from the error estimate.
    ///
    /// # Errors
    /// Numerical failures at the point.
    fn proposed_step(
        &mut self,
        problem: &P,
        t: f64,
        state: &Self::State,
        tolerances: &Tolerances,
    ) -> Result<Option<f64>, Error> {
        let _ = (problem, t, state, tolerances);
        Ok(None)
    }
}

/// A stepper that can evaluate a continuous extension of its last step.
pub trait DenseOutput<P: ?Sized>: Stepper<P> {
    /// `(t, h)` of the last committed step, if any.
    fn last_step(&self) -> Option<(f64, f64)>;

    /// Writes the interpolant of the last committed step at time `t` into `out`.
    fn interpolate(&mut self, problem: &P, t: f64, out: &mut Self::State);

    /// Order of the interpolant (its error is `O(h^(order+1))` locally).
    fn dense_order(&self) -> u32;

    /// A failure of an interpolation since the last call, if any. Interpolants that take a
    /// partial step of the method ([`crate::restep::Restepped`]) can fail as a step can; the
    /// driver ends the run with the error. The default (interpolants that cannot fail) is
    /// `None`.
    fn take_failure(&mut self) -> Option<crate::error::Error> {
        None
    }
}

/// Relative and absolute tolerances of adaptive methods: component `i` is weighted by
/// `atol + rtol · max(|y₀ᵢ|, |y₁ᵢ|)`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Tolerances {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
}

impl Tolerances {
    /// Validated tolerances.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless both are finite and positive.
    pub fn new(rtol: f64, atol: f64) -> Result<Self, Error> {
        for (name, v) in [("rtol", rtol), ("atol", atol)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::InvalidParameter {
                    name,
                    value: v,
                    reason: "tolerances must be finite and positive",
                });
            }
        }
        Ok(Self { rtol, atol })
    }
}
