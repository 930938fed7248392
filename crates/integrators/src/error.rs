//! Errors of the integrators: bad parameters are rejected before any step is taken;
//! numerical failures carry the time and the state at which they happened.

/// Everything that can go wrong in this crate.
///
/// Parameter errors name the parameter and the offending value; numerical failures carry
/// the time `t` at the start of the failing step and the state there (flattened), so the
/// caller can report or resume.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is outside its domain (zero, negative or NaN step, tolerance ≤ 0, …).
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Name of the parameter.
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// The step is larger than the interval to integrate.
    #[error("step {h} is larger than the horizon [{t0}, {t_end}]")]
    StepLargerThanHorizon {
        /// Requested step.
        h: f64,
        /// Start of the interval.
        t0: f64,
        /// End of the interval.
        t_end: f64,
    },
    /// Dimensions of two states (or of a state and a problem) differ.
    #[error("dimension mismatch: expected {expected}, found {found}")]
    DimensionMismatch {
        /// Expected dimension.
        expected: usize,
        /// Dimension found.
        found: usize,
    },
    /// The state became non-finite (NaN or ±∞) during the step starting at `t`.
    #[error("non-finite state after the step from t = {t} with h = {h}")]
    NonFinite {
        /// Time at the start of the step.
        t: f64,
        /// Step size.
        h: f64,
        /// State at the start of the step.
        state: Vec<f64>,
    },
    /// The implicit stage equations did not converge.
    #[error(
        "stage iteration did not converge at t = {t} (h = {h}) after {iterations} iterations; last increment {increment:e}"
    )]
    NoConvergence {
        /// Time at the start of the step.
        t: f64,
        /// Step size.
        h: f64,
        /// Iterations done.
        iterations: usize,
        /// Norm of the last increment.
        increment: f64,
        /// State at the start of the step.
        state: Vec<f64>,
    },
    /// The Newton matrix `I − h A ⊗ J` is singular (or not finite).
    #[error("singular Newton matrix at t = {t} (h = {h})")]
    SingularMatrix {
        /// Time at the start of the step.
        t: f64,
        /// Step size.
        h: f64,
        /// State at the start of the step.
        state: Vec<f64>,
    },
    /// The adaptive step size fell below what `t` can resolve.
    #[error("step size underflow at t = {t}: h = {h:e}")]
    StepSizeUnderflow {
        /// Time reached.
        t: f64,
        /// The step size that was too small.
        h: f64,
        /// State at `t`.
        state: Vec<f64>,
    },
    /// More steps than allowed were needed.
    #[error("maximum number of steps ({max_steps}) reached at t = {t}")]
    TooManySteps {
        /// Time reached.
        t: f64,
        /// The limit.
        max_steps: u64,
        /// State at `t`.
        state: Vec<f64>,
    },
    /// The run reached its wall-clock deadline ([`crate::driver::Driver::deadline`]).
    #[error("time limit of {seconds} s reached at t = {t}")]
    TimeLimit {
        /// Time reached.
        t: f64,
        /// The limit (s of wall time).
        seconds: f64,
        /// State at `t`.
        state: Vec<f64>,
    },
    /// A problem could not give the Taylor coefficients of its solution at `t`
    /// ([`crate::TaylorSystem`]).
    #[error("Taylor coefficients at t = {t} (h = {h}): {reason}")]
    Taylor {
        /// Time of the point.
        t: f64,
        /// The step about to be taken (NaN when not yet chosen).
        h: f64,
        /// What went wrong.
        reason: crate::taylor::TaylorError,
        /// State at `t`.
        state: Vec<f64>,
    },
    /// A name that the registry does not know.
    #[error("unknown integrator `{0}`")]
    UnknownMethod(String),
    /// A method asked to integrate a kind of problem it has no stepper for.
    #[error(transparent)]
    NoStepper(#[from] crate::registry::build::NoStepper),
}

/// Checks that a step size is finite and positive.
pub(crate) fn check_step(h: f64) -> Result<(), Error> {
    if h.is_finite() && h > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidParameter {
            name: "h",
            value: h,
            reason: "the step must be finite and positive",
        })
    }
}
