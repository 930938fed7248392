//! Dense output for any one-step method, by re-stepping.
//!
//! Splitting, composition, variational and Lie-group methods have no continuous extension of
//! their own. [`Restepped`] gives them one: the state at `τ ∈ [t₀, t₀ + h]` is the method's
//! own step of size `τ − t₀` from the state at `t₀`,
//!
//! ```text
//! u(τ) = Φ_{τ − t₀}(y₀),        u(t₀ + h) = y₁ (the step's own result).
//! ```
//!
//! Its properties follow from the method's:
//!
//! - **order**: the local error of `Φ_s` is `O(s^(p+1))` for a method of order `p`, so the
//!   interpolant has order `p` (it is as accurate between steps as the method is at them; an
//!   exact flow interpolates exactly);
//! - **geometry**: `Φ_s` is one of the method's steps, so a method that keeps the rotation on
//!   SO(3) keeps every interpolated rotation on SO(3) — for Lie-group methods this is the
//!   "interpolant that keeps the group" without a separate Lie-algebra construction;
//! - **smoothness**: `s ↦ Φ_s(y₀)` is as smooth as the method's increment function, so root
//!   finding on the interpolant (events, extrema) converges as on any smooth function;
//! - **the step sequence is unchanged**: the partial step is taken by a second copy of the
//!   stepper (the *shadow*) from a saved copy of the state at `t₀`; the stepper that advances
//!   the run never sees it.
//!
//! The price is one step of the method per interpolated point (a Hermite interpolant would be
//! cheaper but of order 3 at most from the two ends' values and derivatives, below the order of
//! every method it would serve here). Nothing is allocated after the first step.
//!
//! A partial step of an implicit method can in principle fail to converge (it never did in the
//! tests: it is shorter than a step that converged); the failure is kept and handed to the
//! driver by [`DenseOutput::take_failure`], which ends the run with it.

use crate::error::Error;
use crate::state::State;
use crate::stepper::{DenseOutput, Stepper};

/// A stepper with dense output by re-stepping (see the [module documentation](self)).
#[derive(Debug, Clone)]
pub struct Restepped<St, S> {
    stepper: St,
    shadow: St,
    start: Option<S>,
    end: Option<S>,
    last: Option<(f64, f64)>,
    order: u32,
    failure: Option<Error>,
}

impl<St: Clone, S> Restepped<St, S> {
    /// Wraps `stepper`, a method of order `order` (the order of the interpolant; give
    /// `u32::MAX` for an exact flow).
    pub fn new(stepper: St, order: u32) -> Self {
        Self {
            shadow: stepper.clone(),
            stepper,
            start: None,
            end: None,
            last: None,
            order,
            failure: None,
        }
    }

    /// The wrapped stepper.
    pub fn inner(&self) -> &St {
        &self.stepper
    }
}

fn keep<S: State>(slot: &mut Option<S>, state: &S) {
    match slot {
        Some(s) => s.copy_from(state),
        None => *slot = Some(state.clone()),
    }
}

impl<P: ?Sized, S: State, St: Stepper<P, State = S> + Clone> Stepper<P> for Restepped<St, S> {
    type State = S;

    fn step(&mut self, problem: &P, t: f64, state: &mut S, h: f64) -> Result<(), Error> {
        self.last = None;
        keep(&mut self.start, state);
        self.stepper.step(problem, t, state, h)?;
        keep(&mut self.end, state);
        self.last = Some((t, h));
        Ok(())
    }

    fn reset(&mut self) {
        self.stepper.reset();
        self.last = None;
    }
}

impl<P: ?Sized, S: State, St: Stepper<P, State = S> + Clone> DenseOutput<P> for Restepped<St, S> {
    fn last_step(&self) -> Option<(f64, f64)> {
        self.last
    }

    fn interpolate(&mut self, problem: &P, t: f64, out: &mut S) {
        let (Some((t0, h)), Some(start), Some(end)) = (self.last, &self.start, &self.end) else {
            return;
        };
        if t == t0 + h {
            out.copy_from(end);
            return;
        }
        out.copy_from(start);
        let s = t - t0;
        if s == 0.0 {
            return;
        }
        self.shadow.reset();
        if let Err(e) = self.shadow.step(problem, t0, out, s) {
            out.copy_from(start);
            self.failure.get_or_insert(e);
        }
    }

    fn dense_order(&self) -> u32 {
        self.order
    }

    fn take_failure(&mut self) -> Option<Error> {
        self.failure.take()
    }
}
