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
//!
//! # Double-double
//! A system that can also compute its coefficients in double-double arithmetic (a value as the
//! unevaluated sum of two `f64`, about 32 significant digits; [`DoubleDouble`]) says so through
//! [`TaylorSystem::double_double`]; the method `taylor-dd` ([`DoubleDoubleTaylorStepper`]) then
//! carries the state in double-double, so that its error is set by its tolerance down to about
//! `1e-30` and not by the round-off of `f64`: the references other methods are measured against.

mod double_double;
mod sums;

pub use double_double::{DoubleDouble, DoubleDoubleTaylorStepper, SeriesScalar};
pub use sums::CrossSums;

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
    /// The method asks for double-double coefficients and the system has none
    /// ([`TaylorSystem::double_double`]).
    #[error("the system computes no Taylor coefficients in double-double arithmetic")]
    NoDoubleDouble,
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

    /// The same system computing its coefficients in double-double arithmetic, when it can
    /// (its kind is then also [`crate::ProblemKind::DoubleDoubleTaylorSeries`]); `None` by
    /// default.
    fn double_double(&self) -> Option<&dyn DoubleDoubleSystem> {
        None
    }
}

/// A [`TaylorSystem`]'s coefficients in double-double arithmetic ([`DoubleDouble`]).
pub trait DoubleDoubleSystem {
    /// As [`TaylorSystem::coefficients`], every value a double-double: the coefficients
    /// `xₖ`, `k = 0 ..= order`, of the solution through `(t0, x0)` into `coeffs[k * n + i]`.
    ///
    /// # Errors
    /// As [`TaylorSystem::coefficients`].
    fn coefficients_dd(
        &self,
        t0: DoubleDouble,
        x0: &[DoubleDouble],
        order: usize,
        coeffs: &mut [DoubleDouble],
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
    fn double_double(&self) -> Option<&dyn DoubleDoubleSystem> {
        (**self).double_double()
    }
}

/// The first non-finite coefficient of `coeffs[..(order + 1) n]`, as the error
/// [`TaylorSystem::coefficients`] returns (a helper for implementations).
///
/// # Errors
/// [`TaylorError::NonFinite`] naming it.
pub fn check_finite<S: SeriesScalar>(
    coeffs: &[S],
    n: usize,
    order: usize,
) -> Result<(), TaylorError> {
    let coeffs = &coeffs[..(order + 1) * n];
    // Branch-free over blocks (vectorizable), the search only when one is not finite.
    let finite = |block: &[S]| block.iter().fold(true, |ok, c| ok & c.is_finite());
    if coeffs.chunks(16).all(finite) {
        return Ok(());
    }
    match coeffs.iter().position(|c| !c.is_finite()) {
        None => Ok(()),
        Some(at) => Err(TaylorError::NonFinite {
            order: at / n.max(1),
            component: at % n.max(1),
        }),
    }
}

/// The step a driver's clock takes from `t` over `h`: `fl(t + h) − t`, exact when
/// `|t| ≥ |h|` (Fast2Sum, Dekker 1971). A Taylor method sums its polynomial there, so that its
/// state belongs to the time the driver records ([`TaylorStepper`]; the map's lanes alike).
#[must_use]
#[inline]
pub fn clock_step(t: f64, h: f64) -> f64 {
    (t + h) - t
}

/// How a Taylor method chooses its order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TaylorOrder {
    /// From the tolerance at each step (Jorba & Zou 2005, §3.2):
    /// `p = ⌈−½ ln ε + 1⌉` with `ε` the absolute or the relative tolerance
    /// ([`jorba_zou_order`]); the step from the last two coefficients ([`jorba_zou_step`]).
    FromTolerance,
    /// A fixed order `p ≥ 1`: with a tolerance, the step of Jorba & Zou at that order; with
    /// fixed steps, the order tests' method.
    Fixed(u32),
}

/// The largest order a Taylor method uses (the order of `ε = 10⁻⁵⁰` is 59).
pub const MAX_ORDER: u32 = 60;

/// The order of a fixed-step run of [`TaylorOrder::FromTolerance`]: that of `ε` = the unit
/// round-off `2⁻⁵³` (19).
pub const ROUND_OFF_ORDER: u32 = 19;

/// The order Jorba & Zou choose for a tolerance `ε`: `⌈−½ ln ε + 1⌉` (their §3.2.2), at least 2
/// and at most [`MAX_ORDER`].
#[must_use]
pub fn jorba_zou_order(eps: f64) -> u32 {
    let p = (-0.5 * eps.ln() + 1.0).ceil();
    if p.is_nan() {
        return 2;
    }
    p.clamp(2.0, f64::from(MAX_ORDER)) as u32
}

/// Which tolerance applies at a point (Jorba & Zou 2005, §3.2.1): the absolute one while
/// `rtol ‖x₀‖∞ ≤ atol`, else the relative one. Returns `(ε, scale)`: the tolerance and the
/// norm the coefficients are measured against (1 for absolute, `‖x₀‖∞` for relative).
#[must_use]
pub fn jorba_zou_tolerance(rtol: f64, atol: f64, x0_norm: f64) -> (f64, f64) {
    if rtol * x0_norm <= atol {
        (atol, 1.0)
    } else {
        (rtol, x0_norm)
    }
}

/// The step Jorba & Zou take at order `p` (2005, §3.2.2): with
/// `ρⱼ = (scale / ‖xⱼ‖∞)^(1/j)` for `j = p − 1, p` (an estimate of the radius of convergence
/// of the series), `h = min(ρ_{p−1}, ρ_p) / e² · exp(−0.7 / (p − 1))`, the last factor their
/// safety factor. `norms[j] = ‖xⱼ‖∞`; a zero coefficient puts no bound (`+∞` when both are
/// zero).
#[must_use]
pub fn jorba_zou_step(norm_pm1: f64, norm_p: f64, p: u32, scale: f64) -> f64 {
    let rho = |norm: f64, j: u32| {
        if norm > 0.0 {
            (scale / norm).powf(1.0 / f64::from(j))
        } else {
            f64::INFINITY
        }
    };
    let rho = rho(norm_pm1, p - 1).min(rho(norm_p, p));
    rho * (-2.0f64).exp() * safety(p)
}

/// The safety factor `exp(−0.7 / (p − 1))` of [`jorba_zou_step`], computed once per order up
/// to [`MAX_ORDER`] (the same value `exp` gives each time).
fn safety(p: u32) -> f64 {
    static FACTORS: std::sync::OnceLock<[f64; MAX_ORDER as usize + 1]> = std::sync::OnceLock::new();
    let of = |p: u32| (-0.7 / (f64::from(p) - 1.0)).exp();
    let table = FACTORS.get_or_init(|| std::array::from_fn(|p| of(p as u32)));
    table.get(p as usize).copied().unwrap_or_else(|| of(p))
}

/// A Taylor-series method: its order rule. [`Taylor::stepper`] builds the workspace of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Taylor {
    /// How the order is chosen.
    pub order: TaylorOrder,
}

impl Taylor {
    /// Order from the tolerance, step from the coefficients (Jorba & Zou 2005).
    #[must_use]
    pub const fn adaptive() -> Self {
        Self {
            order: TaylorOrder::FromTolerance,
        }
    }

    /// A fixed order `p` (at least 1, at most [`MAX_ORDER`]).
    #[must_use]
    pub const fn fixed(p: u32) -> Self {
        Self {
            order: TaylorOrder::Fixed(p),
        }
    }

    /// The stepper for states shaped like `y0`: coefficient buffers for the method's order
    /// (a [`TaylorOrder::FromTolerance`] stepper sizes them for the tolerance at its first
    /// step, once).
    #[must_use]
    pub fn stepper<Y: crate::VectorState>(&self, y0: &Y) -> TaylorStepper<Y> {
        let n = y0.dim();
        let p = match self.order {
            TaylorOrder::Fixed(p) => p.clamp(1, MAX_ORDER),
            TaylorOrder::FromTolerance => ROUND_OFF_ORDER,
        };
        TaylorStepper {
            rule: self.order,
            n,
            order: p,
            coeffs: vec![0.0; (p as usize + 1) * n],
            dense: vec![0.0; (p as usize + 1) * n],
            dense_order: p,
            cached: None,
            key: y0.zeros_like(),
            proposal: f64::INFINITY,
            last: None,
            carry: vec![0.0; n],
            produced: None,
            increment: vec![0.0; n],
            order_of: None,
        }
    }
}

/// The workspace of one run of a [`Taylor`] method on states `Y`: the coefficients at the
/// current point and those of the last step (its dense output), allocated once.
///
/// - **Fixed steps** ([`crate::Stepper::step`]): coefficients at the fixed order (for
///   [`TaylorOrder::FromTolerance`], [`ROUND_OFF_ORDER`]), summed by Horner's rule.
/// - **Adaptive** ([`crate::AdaptiveStepper`]): at each point the order from the tolerance
///   ([`jorba_zou_order`]) and the step from the last two coefficients
///   ([`jorba_zou_step`]), proposed to the driver ([`crate::AdaptiveStepper::proposed_step`]),
///   so no step is rejected; a step the driver shortens (to land on `t_end`, or `h_max`) is
///   accepted as it is.
/// - **Dense output**: the step's Taylor polynomial, of the method's order, at no extra cost;
///   the driver locates events by root-finding on it.
/// - **Compensated steps**: the state is advanced by the step's increment plus the rounding
///   error of the last addition (TwoSum, Knuth 1969), so its round-off does not
///   accumulate from step to step.
#[derive(Debug, Clone)]
pub struct TaylorStepper<Y> {
    rule: TaylorOrder,
    n: usize,
    /// Order of the coefficients in `coeffs`.
    order: u32,
    /// Coefficients at the current point (`cached` says which).
    coeffs: Vec<f64>,
    /// Coefficients of the last committed step.
    dense: Vec<f64>,
    dense_order: u32,
    /// `(t, order)` of the point whose coefficients are in `coeffs` (the state is `key`).
    cached: Option<(f64, u32)>,
    key: Y,
    /// The step proposed at the cached point.
    proposal: f64,
    /// `(t, h)` of the last committed step.
    last: Option<(f64, f64)>,
    /// The rounding error of the last committed state, per component (compensated summation:
    /// [`TaylorStepper::commit`]), valid while the driver hands that state back unchanged.
    carry: Vec<f64>,
    /// The state the last commit wrote (`None` before the first).
    produced: Option<Y>,
    /// The step's increment `Σₖ₌₁ᵖ xₖ hᵏ`.
    increment: Vec<f64>,
    /// The last tolerance met and its order ([`jorba_zou_order`]).
    order_of: Option<(f64, u32)>,
}

impl<Y: crate::VectorState> TaylorStepper<Y> {
    /// The order used at the last point.
    #[must_use]
    pub fn order(&self) -> u32 {
        self.order
    }

    /// Coefficients of order `p` at `(t, y)` into `coeffs`, unless they are there already.
    fn expand<P: TaylorSystem + ?Sized>(
        &mut self,
        problem: &P,
        t: f64,
        y: &Y,
        p: u32,
        h: f64,
    ) -> Result<(), crate::Error> {
        if self.cached == Some((t, p)) && self.key.as_slice() == y.as_slice() {
            return Ok(());
        }
        let len = (p as usize + 1) * self.n;
        if self.coeffs.len() < len {
            self.coeffs.resize(len, 0.0);
        }
        self.cached = None;
        problem
            .coefficients(t, y.as_slice(), p as usize, &mut self.coeffs[..len])
            .map_err(|reason| crate::Error::Taylor {
                t,
                h,
                reason,
                state: y.to_vec(),
            })?;
        self.order = p;
        self.cached = Some((t, p));
        self.key.as_mut_slice().copy_from_slice(y.as_slice());
        Ok(())
    }

    /// `‖xⱼ‖∞` of the current coefficients.
    fn norm(&self, j: u32) -> f64 {
        let j = j as usize;
        self.coeffs[j * self.n..(j + 1) * self.n]
            .iter()
            .fold(0.0f64, |m, c| m.max(c.abs()))
    }

    /// The order and the step of Jorba & Zou at `(t, y)` for `tolerances` (coefficients
    /// computed and cached).
    fn plan<P: TaylorSystem + ?Sized>(
        &mut self,
        problem: &P,
        t: f64,
        y: &Y,
        tolerances: &crate::Tolerances,
    ) -> Result<f64, crate::Error> {
        let x0 = y.as_slice().iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let (eps, scale) = jorba_zou_tolerance(tolerances.rtol, tolerances.atol, x0);
        let p = match self.rule {
            TaylorOrder::FromTolerance => match self.order_of {
                Some((e, p)) if e == eps => p,
                _ => {
                    let p = jorba_zou_order(eps);
                    self.order_of = Some((eps, p));
                    p
                }
            },
            TaylorOrder::Fixed(p) => p.clamp(2, MAX_ORDER),
        };
        if self.cached == Some((t, p)) && self.key.as_slice() == y.as_slice() {
            return Ok(self.proposal);
        }
        self.expand(problem, t, y, p, f64::NAN)?;
        let h = jorba_zou_step(self.norm(p - 1), self.norm(p), p, scale);
        self.proposal = h;
        Ok(h)
    }

    /// `y ← Σₖ xₖ hᵏ` from `coeffs` (Horner; a multiply and an add, not `f64::mul_add`,
    /// a library call on x86-64 without FMA), all components at once order by order: each
    /// component's operations are those of its own Horner sum, in the same order.
    fn sum(coeffs: &[f64], n: usize, p: u32, h: f64, out: &mut [f64]) {
        let p = p as usize;
        let out = &mut out[..n];
        out.copy_from_slice(&coeffs[p * n..(p + 1) * n]);
        for k in (0..p).rev() {
            for (s, c) in out.iter_mut().zip(&coeffs[k * n..(k + 1) * n]) {
                *s = *s * h + c;
            }
        }
    }

    /// Commits the step of size `h` from the cached point: the state at its end, and the
    /// coefficients kept as the step's dense output.
    ///
    /// The polynomial is summed at the step the driver's clock takes, `fl(t + h) − t` (exact
    /// when `|t| ≥ |h|`: Fast2Sum, Dekker 1971), not at `h`: the state then belongs to the time
    /// the driver records, and the rounding of `t + h` (up to half an ulp of `t` per step) does
    /// not accumulate into the solution as a phase error. On a top spinning at 50 rad/s over
    /// 400 steps to `t = 10` that drift alone is about `10⁻¹³` (the time's random walk,
    /// `√400 · 4·10⁻¹⁶ s`, times the spin); heyoka carries its time in double length for the
    /// same reason (Biscani & Izzo 2021, §4).
    ///
    /// The new state is `x₀ + Σₖ₌₁ᵖ xₖ hᵏ` summed with compensation (Kahan 1965; the error of
    /// each addition by TwoSum, Knuth 1969, §4.2.2): the increment (Horner) plus the rounding
    /// error the last step left, added to `x₀`, and the error of that addition kept for the
    /// next step. The state's rounding then does not accumulate from step to step as a random
    /// walk of half an ulp per step; the carry is dropped when the driver hands back a state
    /// other than the one written (an event, a restart).
    fn commit(&mut self, t: f64, y: &mut Y, h: f64) {
        let step = clock_step(t, h);
        let n = self.n;
        let carried = self
            .produced
            .as_ref()
            .is_some_and(|p| p.as_slice() == y.as_slice());
        if !carried {
            self.carry.fill(0.0);
        }
        Self::increment(&self.coeffs, n, self.order, step, &mut self.increment);
        for ((x, d), c) in y
            .as_mut_slice()
            .iter_mut()
            .zip(&self.increment)
            .zip(&mut self.carry)
        {
            let (s, e) = two_sum(*x, d + *c);
            *x = s;
            *c = e;
        }
        match &mut self.produced {
            Some(p) => p.as_mut_slice().copy_from_slice(y.as_slice()),
            None => self.produced = Some(y.clone()),
        }
        std::mem::swap(&mut self.coeffs, &mut self.dense);
        if self.coeffs.len() < self.dense.len() {
            self.coeffs.resize(self.dense.len(), 0.0);
        }
        self.dense_order = self.order;
        self.cached = None;
        self.last = Some((t, h));
    }

    /// `Σₖ₌₁ᵖ xₖ hᵏ` (Horner, all components at once order by order) into `out`.
    fn increment(coeffs: &[f64], n: usize, p: u32, h: f64, out: &mut [f64]) {
        let p = p as usize;
        let out = &mut out[..n];
        out.copy_from_slice(&coeffs[p * n..(p + 1) * n]);
        for k in (1..p).rev() {
            for (s, c) in out.iter_mut().zip(&coeffs[k * n..(k + 1) * n]) {
                *s = *s * h + c;
            }
        }
        for s in out.iter_mut() {
            *s *= h;
        }
    }
}

/// `a + b` and its rounding error, exactly: `s = fl(a + b)`, `a + b = s + e` (TwoSum, Knuth
/// 1969, §4.2.2; no condition on the magnitudes).
#[inline]
#[must_use]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

impl<P: TaylorSystem + ?Sized, Y: crate::VectorState> crate::Stepper<P> for TaylorStepper<Y> {
    type State = Y;

    fn step(&mut self, problem: &P, t: f64, state: &mut Y, h: f64) -> Result<(), crate::Error> {
        let p = match self.rule {
            TaylorOrder::Fixed(p) => p.clamp(1, MAX_ORDER),
            TaylorOrder::FromTolerance => ROUND_OFF_ORDER,
        };
        self.expand(problem, t, state, p, h)?;
        self.commit(t, state, h);
        Ok(())
    }

    fn reset(&mut self) {
        self.cached = None;
        self.produced = None;
    }
}

impl<P: TaylorSystem + ?Sized, Y: crate::VectorState> crate::AdaptiveStepper<P>
    for TaylorStepper<Y>
{
    fn error_order(&self) -> u32 {
        self.order
    }

    /// Unused: the method proposes its own steps ([`crate::AdaptiveStepper::proposed_step`]).
    fn controller(&self) -> crate::PiController {
        crate::PiController::DOP853
    }

    /// `(h / h_JZ)^p`: at most 1 for any step no longer than the one Jorba & Zou's rule gives
    /// at this point.
    fn attempt(
        &mut self,
        problem: &P,
        t: f64,
        state: &Y,
        h: f64,
        tolerances: &crate::Tolerances,
    ) -> Result<f64, crate::Error> {
        let h_jz = self.plan(problem, t, state, tolerances)?;
        Ok((h.abs() / h_jz).powi(self.order as i32))
    }

    fn accept(&mut self, _problem: &P, t: f64, state: &mut Y, h: f64) {
        self.commit(t, state, h);
    }

    fn initial_step(
        &mut self,
        problem: &P,
        t: f64,
        state: &Y,
        h_max: f64,
        tolerances: &crate::Tolerances,
    ) -> f64 {
        // A failure here is met again, with its error, by the first attempt.
        self.plan(problem, t, state, tolerances)
            .map_or(h_max, |h| h.min(h_max))
    }

    fn proposed_step(
        &mut self,
        problem: &P,
        t: f64,
        state: &Y,
        tolerances: &crate::Tolerances,
    ) -> Result<Option<f64>, crate::Error> {
        self.plan(problem, t, state, tolerances).map(Some)
    }
}

impl<P: TaylorSystem + ?Sized, Y: crate::VectorState> crate::DenseOutput<P> for TaylorStepper<Y> {
    fn last_step(&self) -> Option<(f64, f64)> {
        self.last
    }

    /// The step's Taylor polynomial at `t − t₀` (Horner).
    fn interpolate(&mut self, _problem: &P, t: f64, out: &mut Y) {
        if let Some((t0, _)) = self.last {
            Self::sum(
                &self.dense,
                self.n,
                self.dense_order,
                t - t0,
                out.as_mut_slice(),
            );
        }
    }

    fn dense_order(&self) -> u32 {
        self.dense_order
    }
}
