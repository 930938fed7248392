//! Taylor-series methods: the contract a problem offers them ([`TaylorSystem`]).
//!
//! A Taylor method advances `x' = F(t, x)` by the truncated Taylor series of the solution
//! through the current point, `x(t₀ + h) ≈ Σₖ₌₀ᵖ xₖ hᵏ`, whose *normalized* coefficients
//! `xₖ = x⁽ᵏ⁾(t₀)/k!` the problem computes by the recursions of automatic differentiation
//! (Moore 1966; Griewank & Walther 2008, ch. 13; Jorba & Zou 2005, §3): `x₀ = x(t₀)` and
//! `(k+1) xₖ₊₁ = [F(t, x(t))]ₖ`, the `k`-th coefficient of the right-hand side along the series,
//! which depends only on `x₀ … xₖ`. A problem states it can do this by implementing
//! [`TaylorSystem`]; its kind is [`crate::ProblemKind::TaylorSeries`].
//!
//! # References
//! - R. E. Moore, *Interval Analysis*, Prentice-Hall 1966, ch. 11.
//! - A. Griewank, A. Walther, *Evaluating Derivatives*, 2nd ed., SIAM 2008, ch. 13.
//! - À. Jorba, M. Zou, *A software package for the numerical integration of ODEs by means of
//!   high-order Taylor methods*, Experimental Mathematics 14 (2005) 99–117.

/// Why a [`TaylorSystem`] could not give its coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TaylorError {
    /// A coefficient is NaN or infinite (a singularity of the equations at or near the
    /// point, or an overflow).
    #[error("Taylor coefficient of order {order} of component {component} is not finite")]
    NonFinite {
        /// The order `k` of the coefficient.
        order: usize,
        /// The state component `i`.
        component: usize,
    },
    /// The equations cannot be solved for the derivative at the point (a mass matrix that
    /// is not positive definite there).
    #[error("the equations are singular at the point: {reason}")]
    Singular {
        /// What is singular.
        reason: &'static str,
    },
}

/// An ODE `x' = F(t, x)` on ℝⁿ that computes the normalized Taylor coefficients of its
/// solution through a point.
///
/// Implementations keep whatever workspace their recursions need inside (as [`crate::Ode`]
/// implementations do, behind a `RefCell`): [`TaylorSystem::coefficients`] takes `&self` and
/// must not allocate once it has been called with the largest order of a run (a workspace may
/// grow on the first call with a larger order).
pub trait TaylorSystem {
    /// The dimension `n` of the state.
    fn dim(&self) -> usize;

    /// Writes the normalized Taylor coefficients `xₖ = x⁽ᵏ⁾(t₀)/k!`, `k = 0 ..= order`, of the
    /// solution through `(t0, x0)` into `coeffs[k * n + i]` (`coeffs.len() ≥ (order + 1) n`,
    /// a buffer the caller owns; `x0.len() = n`), so that `x(t₀ + h) ≈ Σₖ xₖ hᵏ`. Coefficient
    /// `0` is `x0` itself.
    ///
    /// # Errors
    /// [`TaylorError::NonFinite`] when a coefficient is not finite (the first found, lowest
    /// order first); [`TaylorError::Singular`] when the equations cannot be solved for the
    /// derivatives at the point. The contents of `coeffs` are then unspecified.
    fn coefficients(
        &self,
        t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError>;
}

impl<T: TaylorSystem + ?Sized> TaylorSystem for &T {
    fn dim(&self) -> usize {
        (**self).dim()
    }
    fn coefficients(
        &self,
        t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError> {
        (**self).coefficients(t0, x0, order, coeffs)
    }
}

/// The first non-finite coefficient of `coeffs[..(order + 1) n]`, as the error
/// [`TaylorSystem::coefficients`] returns (a helper for implementations).
///
/// # Errors
/// [`TaylorError::NonFinite`] naming it.
pub fn check_finite(coeffs: &[f64], n: usize, order: usize) -> Result<(), TaylorError> {
    match coeffs[..(order + 1) * n]
        .iter()
        .position(|c| !c.is_finite())
    {
        None => Ok(()),
        Some(at) => Err(TaylorError::NonFinite {
            order: at / n.max(1),
            component: at % n.max(1),
        }),
    }
}
