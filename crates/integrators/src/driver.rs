//! The driver: one loop for every method.
//!
//! [`Driver`] owns the horizon `[t₀, t_end]`, the step policy (fixed `h`, or adaptive with
//! [`Tolerances`]), events, observers and cancellation; steppers only step.
//!
//! - **Fixed steps** ([`Driver::run_fixed`]): times `t_k = t₀ + k h` (no accumulated
//!   rounding); the last step is shortened so that the run ends exactly at `t_end` (when
//!   `(t_end − t₀)/h` is an integer up to 1e-9 relative, all steps are `h`).
//! - **Adaptive steps** ([`Driver::run_adaptive`]): PI control, the last step lands exactly
//!   on `t_end`, failures below the resolvable step are [`Error::StepSizeUnderflow`].
//! - **Events**: a function `g(t, y)` whose sign change (in the given [`Direction`]) is
//!   located on the stepper's dense output by the Illinois variant of regula falsi, to a
//!   bracket of a few ulps in `t`; the event then [`Action::Continue`]s (recorded in the
//!   report) or [`Action::Terminate`]s the run with the state at the event.
//! - **Observers** ([`Observer`]) are called at `t₀`, every `n`-th step, and at the end;
//!   the default does nothing and nothing is stored unless an observer stores it.
//! - **Cancellation**: a callback polled before every step; a cancelled run returns
//!   [`Status::Cancelled`] with the last completed state. A wall-clock deadline
//!   ([`Driver::deadline`]) ends a run with [`Error::TimeLimit`].
//!
//! Every step's result is checked: a non-finite state is [`Error::NonFinite`] with the time
//! and the state before the step.

mod events;

use events::{AfterStep, EventHook, EventTracker, NoEvents};

use crate::error::{Error, check_step};
use crate::state::State;
use crate::stepper::{AdaptiveStepper, DenseOutput, Stepper, Tolerances};

/// What an observer asks the driver to do next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Go on.
    Continue,
    /// Stop the run here (status [`Status::Stopped`]).
    Stop,
}

/// Watches the run: called at the start, every `n` steps, and at the end; and at the output
/// times asked for with [`Driver::output_at`].
pub trait Observer<S> {
    /// Called with the current time and state; the default does nothing.
    fn observe(&mut self, t: f64, state: &S) -> Flow {
        let _ = (t, state);
        Flow::Continue
    }

    /// Called at each output time of [`Driver::output_at`], in order, with the state there
    /// from the stepper's dense output (the step's own state when a step ends exactly there).
    /// The step sequence is the same with or without output times. The default does nothing.
    fn output(&mut self, t: f64, state: &S) -> Flow {
        let _ = (t, state);
        Flow::Continue
    }

    /// Whether this observer wants [`Observer::dense_step`] after every step (runs with dense
    /// output only). The default is no.
    fn wants_dense_steps(&self) -> bool {
        false
    }

    /// Called after every step of a run with dense output (when
    /// [`Observer::wants_dense_steps`]), before [`Observer::observe`] sees the step's end: the
    /// continuous extension of the step, to evaluate anywhere on it. The default does nothing.
    fn dense_step(&mut self, step: &mut dyn DenseStep<S>) -> Flow {
        let _ = step;
        Flow::Continue
    }
}

/// The continuous extension of the last step, as [`Observer::dense_step`] sees it.
pub trait DenseStep<S> {
    /// `(t₀, t₁)` of the step.
    fn span(&self) -> (f64, f64);
    /// The state at `t ∈ [t₀, t₁]` from the stepper's dense output (at `t₁`, the step's own
    /// result).
    fn state_at(&mut self, t: f64) -> &S;
}

/// The observer that does nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoObserver;

impl<S> Observer<S> for NoObserver {}

/// An observer from a closure `|t, state| -> Flow`.
pub struct FnObserver<F>(pub F);

impl<S, F: FnMut(f64, &S) -> Flow> Observer<S> for FnObserver<F> {
    fn observe(&mut self, t: f64, state: &S) -> Flow {
        (self.0)(t, state)
    }
}

/// Which sign changes of an event function count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// From negative to non-negative.
    Rising,
    /// From positive to non-positive.
    Falling,
    /// Either.
    Either,
}

/// What happens at an event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Record it and go on.
    Continue,
    /// Record it and end the run at the event.
    Terminate,
}

/// An event function `g(t, y)`.
pub type EventFunction<'a, S> = Box<dyn Fn(f64, &S) -> f64 + 'a>;

/// An event: a root of `g(t, y)`.
pub struct Event<'a, S> {
    /// The event function.
    pub function: EventFunction<'a, S>,
    /// Which crossings count.
    pub direction: Direction,
    /// What to do at a crossing.
    pub action: Action,
}

impl<'a, S> Event<'a, S> {
    /// An event from a closure.
    pub fn new(
        function: impl Fn(f64, &S) -> f64 + 'a,
        direction: Direction,
        action: Action,
    ) -> Self {
        Self {
            function: Box::new(function),
            direction,
            action,
        }
    }
}

/// An event that happened.
#[derive(Debug, Clone, PartialEq)]
pub struct EventRecord<S> {
    /// Index of the event in the list given to the driver.
    pub index: usize,
    /// Time of the root.
    pub t: f64,
    /// State at the root (from the dense output).
    pub state: S,
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// Reached `t_end`.
    Completed,
    /// A terminal event fired (index of the event).
    Terminated(usize),
    /// The cancellation callback returned `true`.
    Cancelled,
    /// An observer returned [`Flow::Stop`].
    Stopped,
}

/// Summary of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Report<S> {
    /// Time reached (the state passed in holds the state there).
    pub t: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts (adaptive runs).
    pub rejected: u64,
    /// How the run ended.
    pub status: Status,
    /// Events that happened, in time order.
    pub events: Vec<EventRecord<S>>,
}

/// The integration loop's settings: horizon, observer cadence, cancellation, step limits.
pub struct Driver<'a> {
    t0: f64,
    t_end: f64,
    every: u64,
    max_steps: u64,
    h_max: f64,
    cancel: Option<&'a dyn Fn() -> bool>,
    cancel_flag: Option<&'a std::sync::atomic::AtomicBool>,
    deadline: Option<(std::time::Instant, f64)>,
    outputs: &'a [f64],
}

impl<'a> Driver<'a> {
    /// A driver for `[t0, t_end]` (forward in time, `t_end > t0`).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for non-finite times or `t_end ≤ t0`.
    pub fn new(t0: f64, t_end: f64) -> Result<Self, Error> {
        if !t0.is_finite() {
            return Err(Error::InvalidParameter {
                name: "t0",
                value: t0,
                reason: "must be finite",
            });
        }
        if !(t_end.is_finite() && t_end > t0) {
            return Err(Error::InvalidParameter {
                name: "t_end",
                value: t_end,
                reason: "must be finite and greater than t0",
            });
        }
        Ok(Self {
            t0,
            t_end,
            every: 1,
            max_steps: u64::MAX,
            h_max: t_end - t0,
            cancel: None,
            cancel_flag: None,
            deadline: None,
            outputs: &[],
        })
    }

    /// Call the observer every `n ≥ 1` steps (default 1).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `n = 0`.
    pub fn every(mut self, n: u64) -> Result<Self, Error> {
        if n == 0 {
            return Err(Error::InvalidParameter {
                name: "every",
                value: 0.0,
                reason: "must be at least 1",
            });
        }
        self.every = n;
        Ok(self)
    }

    /// Give up (with [`Error::TooManySteps`]) after this many steps.
    #[must_use]
    pub fn max_steps(mut self, n: u64) -> Self {
        self.max_steps = n;
        self
    }

    /// Largest step of adaptive runs.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless finite and positive.
    pub fn h_max(mut self, h_max: f64) -> Result<Self, Error> {
        check_step(h_max).map_err(|_| Error::InvalidParameter {
            name: "h_max",
            value: h_max,
            reason: "must be finite and positive",
        })?;
        self.h_max = h_max;
        Ok(self)
    }

    /// Also observe the states at `times` ([`Observer::output`]), from the stepper's dense
    /// output: only runs with dense output take them ([`Driver::run_fixed_with_events`],
    /// [`Driver::run_adaptive`]).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a time that is not finite, outside `[t₀, t_end]`, or not
    /// after the one before it.
    pub fn output_at(mut self, times: &'a [f64]) -> Result<Self, Error> {
        let mut previous = f64::NEG_INFINITY;
        for &t in times {
            if !(t.is_finite() && t >= self.t0 && t <= self.t_end) {
                return Err(Error::InvalidParameter {
                    name: "output time",
                    value: t,
                    reason: "must lie in [t0, t_end]",
                });
            }
            if !(t > previous) {
                return Err(Error::InvalidParameter {
                    name: "output time",
                    value: t,
                    reason: "output times must increase strictly",
                });
            }
            previous = t;
        }
        self.outputs = times;
        Ok(self)
    }

    /// Poll `cancel` before every step; `true` ends the run with [`Status::Cancelled`].
    #[must_use]
    pub fn cancel(mut self, cancel: &'a dyn Fn() -> bool) -> Self {
        self.cancel = Some(cancel);
        self
    }

    /// End the run with [`Status::Cancelled`] once `flag` is set (polled before every step;
    /// e.g. set by a signal handler).
    #[must_use]
    pub fn cancel_flag(mut self, flag: &'a std::sync::atomic::AtomicBool) -> Self {
        self.cancel_flag = Some(flag);
        self
    }

    /// Give up (with [`Error::TimeLimit`]) once `seconds` of wall time have passed since this
    /// call (the clock is read every [`Driver::CLOCK_EVERY`] steps).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `seconds` is finite and positive.
    pub fn deadline(mut self, seconds: f64) -> Result<Self, Error> {
        if !(seconds.is_finite() && seconds > 0.0) {
            return Err(Error::InvalidParameter {
                name: "deadline",
                value: seconds,
                reason: "must be finite and positive",
            });
        }
        let now = std::time::Instant::now();
        let at = now
            .checked_add(std::time::Duration::from_secs_f64(seconds.min(1e9)))
            .unwrap_or(now);
        self.deadline = Some((at, seconds));
        Ok(self)
    }

    /// Steps between two readings of the clock for [`Driver::deadline`].
    pub const CLOCK_EVERY: u64 = 32;

    /// [`Error::TimeLimit`] at `(t, state)` if the deadline has passed (checked every
    /// [`Driver::CLOCK_EVERY`] steps).
    fn check_deadline<S: State>(&self, step: u64, t: f64, state: &S) -> Result<(), Error> {
        match self.deadline {
            Some((at, seconds))
                if step.is_multiple_of(Self::CLOCK_EVERY) && std::time::Instant::now() >= at =>
            {
                Err(Error::TimeLimit {
                    t,
                    seconds,
                    state: state.to_vec(),
                })
            }
            _ => Ok(()),
        }
    }

    fn cancelled(&self) -> bool {
        self.cancel.is_some_and(|c| c())
            || self
                .cancel_flag
                .is_some_and(|f| f.load(std::sync::atomic::Ordering::Relaxed))
    }

    /// Number of fixed steps and whether the last one is shorter.
    fn fixed_steps(&self, h: f64) -> Result<u64, Error> {
        check_step(h)?;
        let span = self.t_end - self.t0;
        if h > span * (1.0 + 1e-12) {
            return Err(Error::StepLargerThanHorizon {
                h,
                t0: self.t0,
                t_end: self.t_end,
            });
        }
        let r = span / h;
        let rounded = r.round();
        let n = if (r - rounded).abs() <= 1e-9 * r {
            rounded
        } else {
            r.ceil()
        };
        if n > 1e15 {
            return Err(Error::InvalidParameter {
                name: "h",
                value: h,
                reason: "too small for the horizon (more than 1e15 steps)",
            });
        }
        Ok(n as u64)
    }

    /// Integrates with fixed steps `h` (any [`Stepper`], no events).
    ///
    /// # Errors
    /// Parameter errors (`h` not positive or larger than the horizon), the stepper's
    /// numerical errors, [`Error::NonFinite`], [`Error::TooManySteps`].
    pub fn run_fixed<P: ?Sized, St: Stepper<P>, O: Observer<St::State>>(
        &self,
        stepper: &mut St,
        problem: &P,
        state: &mut St::State,
        h: f64,
        observer: &mut O,
    ) -> Result<Report<St::State>, Error> {
        if let Some(&t) = self.outputs.first() {
            return Err(Error::InvalidParameter {
                name: "output time",
                value: t,
                reason: "output at chosen times needs a stepper with dense output \
                         (run_fixed_with_events)",
            });
        }
        self.fixed_loop(
            stepper,
            problem,
            state,
            h,
            observer,
            None::<&mut NoEvents<'_, St::State>>,
        )
    }

    /// Integrates with fixed steps `h` and locates `events` on the stepper's dense output.
    ///
    /// # Errors
    /// As [`Driver::run_fixed`].
    pub fn run_fixed_with_events<P: ?Sized, St, O>(
        &self,
        stepper: &mut St,
        problem: &P,
        state: &mut St::State,
        h: f64,
        events: &mut [Event<'_, St::State>],
        observer: &mut O,
    ) -> Result<Report<St::State>, Error>
    where
        St: DenseOutput<P>,
        O: Observer<St::State>,
    {
        let mut tracker = EventTracker::new(events, self.outputs);
        self.fixed_loop(stepper, problem, state, h, observer, Some(&mut tracker))
    }

    fn fixed_loop<P: ?Sized, St: Stepper<P>, O: Observer<St::State>, E: EventHook<P, St>>(
        &self,
        stepper: &mut St,
        problem: &P,
        state: &mut St::State,
        h: f64,
        observer: &mut O,
        mut events: Option<&mut E>,
    ) -> Result<Report<St::State>, Error> {
        let n = self.fixed_steps(h)?;
        let mut report = Report {
            t: self.t0,
            steps: 0,
            rejected: 0,
            status: Status::Completed,
            events: Vec::new(),
        };
        if let Some(ev) = events.as_deref_mut()
            && ev.start(self.t0, state, observer) == Flow::Stop
        {
            report.status = Status::Stopped;
            return Ok(report);
        }
        if observer.observe(self.t0, state) == Flow::Stop {
            report.status = Status::Stopped;
            return Ok(report);
        }
        let mut t = self.t0;
        // The state at the start of the current step, for the error report if it fails
        // (allocated once per run).
        let mut before = state.clone();
        for k in 0..n {
            if self.cancelled() {
                report.status = Status::Cancelled;
                return Ok(report);
            }
            self.check_deadline(k, t, state)?;
            if k >= self.max_steps {
                return Err(Error::TooManySteps {
                    t,
                    max_steps: self.max_steps,
                    state: state.to_vec(),
                });
            }
            let t_next = if k + 1 == n {
                self.t_end
            } else {
                self.t0 + (k + 1) as f64 * h
            };
            let hk = t_next - t;
            before.copy_from(state);
            stepper.step(problem, t, state, hk)?;
            if !state.is_finite() {
                return Err(Error::NonFinite {
                    t,
                    h: hk,
                    state: before.to_vec(),
                });
            }
            report.steps += 1;
            if let Some(ev) = events.as_deref_mut() {
                let after = ev.after_step(stepper, problem, t_next, state, &mut report, observer);
                if ends_run(after, t_next, &mut report, stepper, state, observer)? {
                    return Ok(report);
                }
            }
            t = t_next;
            report.t = t;
            let last = k + 1 == n;
            if (report.steps % self.every == 0 || last) && observer.observe(t, state) == Flow::Stop
            {
                report.status = Status::Stopped;
                return Ok(report);
            }
        }
        Ok(report)
    }

    /// Integrates adaptively with the given tolerances, locating `events` on the dense
    /// output.
    ///
    /// # Errors
    /// Parameter errors, the stepper's numerical errors, [`Error::NonFinite`],
    /// [`Error::StepSizeUnderflow`], [`Error::TooManySteps`].
    pub fn run_adaptive<P: ?Sized, St, O>(
        &self,
        stepper: &mut St,
        problem: &P,
        state: &mut St::State,
        tolerances: &Tolerances,
        events: &mut [Event<'_, St::State>],
        observer: &mut O,
    ) -> Result<Report<St::State>, Error>
    where
        St: AdaptiveStepper<P> + DenseOutput<P>,
        O: Observer<St::State>,
    {
        let tol = Tolerances::new(tolerances.rtol, tolerances.atol)?;
        let mut tracker = EventTracker::new(events, self.outputs);
        let mut report = Report {
            t: self.t0,
            steps: 0,
            rejected: 0,
            status: Status::Completed,
            events: Vec::new(),
        };
        if EventHook::<P, St>::start(&mut tracker, self.t0, state, observer) == Flow::Stop {
            report.status = Status::Stopped;
            return Ok(report);
        }
        if observer.observe(self.t0, state) == Flow::Stop {
            report.status = Status::Stopped;
            return Ok(report);
        }
        let q = stepper.error_order();
        let controller = stepper.controller();
        let mut t = self.t0;
        let mut before = state.clone();
        let mut h = stepper.initial_step(problem, t, state, self.h_max, &tol);
        // A method that proposes its own steps lands on t_end without stretching the last one.
        let mut stretch = match stepper.proposed_step(problem, t, state, &tol)? {
            Some(proposed) => {
                h = proposed.min(self.h_max);
                1.0
            }
            None => 1.01,
        };
        let mut err_prev = 1e-4_f64;
        let mut after_reject = false;
        let mut attempts: u64 = 0;
        while t < self.t_end {
            if self.cancelled() {
                report.status = Status::Cancelled;
                return Ok(report);
            }
            self.check_deadline(attempts, t, state)?;
            if report.steps >= self.max_steps {
                return Err(Error::TooManySteps {
                    t,
                    max_steps: self.max_steps,
                    state: state.to_vec(),
                });
            }
            attempts += 1;
            if attempts > self.max_steps.saturating_mul(4).max(1_000_000_000) {
                return Err(Error::TooManySteps {
                    t,
                    max_steps: self.max_steps,
                    state: state.to_vec(),
                });
            }
            if h < 16.0 * f64::EPSILON * t.abs().max(1.0) {
                return Err(Error::StepSizeUnderflow {
                    t,
                    h,
                    state: state.to_vec(),
                });
            }
            h = h.min(self.h_max);
            let last = t + stretch * h >= self.t_end;
            if last {
                h = self.t_end - t;
            }
            let err = stepper.attempt(problem, t, state, h, &tol)?;
            if err.is_finite() && err <= 1.0 {
                let t_next = if last { self.t_end } else { t + h };
                before.copy_from(state);
                stepper.accept(problem, t, state, h);
                if !state.is_finite() {
                    return Err(Error::NonFinite {
                        t,
                        h,
                        state: before.to_vec(),
                    });
                }
                report.steps += 1;
                let after =
                    tracker.after_step(stepper, problem, t_next, state, &mut report, observer);
                if ends_run(after, t_next, &mut report, stepper, state, observer)? {
                    return Ok(report);
                }
                t = t_next;
                report.t = t;
                if (report.steps % self.every == 0 || t >= self.t_end)
                    && observer.observe(t, state) == Flow::Stop
                {
                    report.status = Status::Stopped;
                    return Ok(report);
                }
                if let Some(proposed) = stepper.proposed_step(problem, t, state, &tol)? {
                    h = proposed;
                    stretch = 1.0;
                } else {
                    let fac = controller.accepted_factor(err, err_prev, q, after_reject);
                    h *= fac;
                }
                err_prev = err.max(1e-4);
                after_reject = false;
            } else {
                report.rejected += 1;
                after_reject = true;
                h = match stepper.proposed_step(problem, t, state, &tol)? {
                    Some(proposed) if proposed < h => proposed,
                    _ => h * controller.rejected_factor(err, q),
                };
            }
        }
        Ok(report)
    }
}

/// Applies what the events and outputs of a step to `t_next` decided: `true` when the run ends
/// there (a terminal event, with the state at the event observed; or an observer's stop).
fn ends_run<P: ?Sized, St: Stepper<P>, O: Observer<St::State>>(
    after: AfterStep,
    t_next: f64,
    report: &mut Report<St::State>,
    stepper: &mut St,
    state: &St::State,
    observer: &mut O,
) -> Result<bool, Error> {
    Ok(match after {
        AfterStep::Go => false,
        AfterStep::Terminated(t_stop) => {
            report.t = t_stop;
            observer.observe(t_stop, state);
            stepper.reset();
            true
        }
        AfterStep::Stopped => {
            report.t = t_next;
            report.status = Status::Stopped;
            true
        }
        AfterStep::Failed(e) => return Err(e),
    })
}
