//! The Taylor method in double-double arithmetic: `taylor-dd`, the references' method.
//!
//! A double-double is the unevaluated sum `hi + lo` of two `f64` with `|lo| ≤ ulp(hi)/2`, about
//! 106 significant bits; its sums and products are exact transformations of `f64` operations
//! (Dekker 1971; the algorithms and their error bounds, about `u² = 2⁻¹⁰⁶` relative each: Joldeș,
//! Muller & Popescu 2017), here from the `twofloat` crate.
//!
//! [`DoubleDoubleTaylorStepper`] runs in the same driver as every `f64` method: the driver sees
//! the state rounded to `f64`, and the stepper keeps the state in double-double between steps.
//! At every step it checks that the driver's time and state are its own, rounded; when they
//! are not (the first step, or a state changed by an event), it starts again from the driver's
//! `f64` values, which are exact double-doubles. Each step lands exactly on the driver's next
//! time `t + h` (an `f64`): the step it sums is that time minus its own, an exact double-double,
//! so that the state it carries is the solution at the driver's times and at `t_end`, with no
//! drift between the two clocks.
//!
//! Order and step follow Jorba & Zou (2005) as for `taylor` ([`super::jorba_zou_order`],
//! [`super::jorba_zou_step`]), from the tolerance asked (down to `1e-30`); the series is summed
//! by Horner's rule in double-double.
//!
//! # References
//! - T. J. Dekker, *A floating-point technique for extending the available precision*,
//!   Numerische Mathematik 18 (1971) 224–242.
//! - M. Joldeș, J.-M. Muller, V. Popescu, *Tight and rigorous error bounds for basic building
//!   blocks of double-word arithmetic*, ACM TOMS 44 (2017) 15:1–27.
//! - Y. Hida, X. S. Li, D. H. Bailey, *Algorithms for quad-double precision floating point
//!   arithmetic*, ARITH-15 (2001) 155–162 (the division, [`SeriesScalar::quotient`]).

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Mul, Neg, Sub};

use super::{TaylorError, TaylorSystem, jorba_zou_order, jorba_zou_step, jorba_zou_tolerance};

/// A double-double number: `hi + lo`, about 32 significant digits.
pub type DoubleDouble = twofloat::TwoFloat;

/// The scalars a Taylor recursion can be written once for: `f64`, and [`DoubleDouble`].
pub trait SeriesScalar:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
    + AddAssign
{
    /// Zero.
    const ZERO: Self;
    /// The value `x`, exactly.
    fn of(x: f64) -> Self;
    /// Neither NaN nor infinite.
    fn is_finite(self) -> bool;
    /// The value rounded to `f64`.
    fn leading(self) -> f64;
    /// `self / rhs`, correctly rounded in `f64`, to about `2⁻¹⁰⁴` relative in double-double.
    fn quotient(self, rhs: Self) -> Self;
}

impl SeriesScalar for f64 {
    const ZERO: Self = 0.0;
    #[inline]
    fn of(x: f64) -> Self {
        x
    }
    #[inline]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    #[inline]
    fn leading(self) -> f64 {
        self
    }
    #[inline]
    fn quotient(self, rhs: Self) -> Self {
        self / rhs
    }
}

impl SeriesScalar for DoubleDouble {
    const ZERO: Self = DoubleDouble::from_f64(0.0);
    #[inline]
    fn of(x: f64) -> Self {
        DoubleDouble::from_f64(x)
    }
    #[inline]
    fn is_finite(self) -> bool {
        self.hi().is_finite() && self.lo().is_finite()
    }
    #[inline]
    fn leading(self) -> f64 {
        self.hi()
    }
    /// Long division by the leading part, three quotient digits (Hida, Li & Bailey 2001, the
    /// accurate division of QD): `qᵢ = rᵢ.hi / b.hi`, `rᵢ₊₁ = rᵢ − qᵢ b` with exact products,
    /// `a / b ≈ q₀ + q₁ + q₂`. (`twofloat`'s own `TwoFloat / TwoFloat` forms `1 − b.hi t` without a
    /// fused multiply–add and is accurate only to about `1e-17`.)
    fn quotient(self, rhs: Self) -> Self {
        let q0 = self.hi() / rhs.hi();
        let r = self - rhs * q0;
        let q1 = r.hi() / rhs.hi();
        let r = r - rhs * q1;
        let q2 = r.hi() / rhs.hi();
        DoubleDouble::new_add(q0, q1) + q2
    }
}

/// The order of a fixed step of `taylor-dd`: that of `ε = 2⁻¹⁰⁶`, double-double's unit
/// round-off ([`jorba_zou_order`]: `⌈−½ ln 2⁻¹⁰⁶ + 1⌉ = 38`).
pub const DOUBLE_DOUBLE_ORDER: u32 = 38;

/// The workspace of one run of `taylor-dd` on `f64` states `Y` (module doc): the state and
/// the coefficients in double-double, the last step's polynomial rounded to `f64` as its
/// dense output.
#[derive(Debug, Clone)]
pub struct DoubleDoubleTaylorStepper<Y> {
    n: usize,
    /// The state in double-double, at `time`; `None` until the first step.
    state: Vec<DoubleDouble>,
    time: Option<f64>,
    /// Order of the coefficients in `coeffs`, `None` when they are not those of `state`.
    cached: Option<u32>,
    coeffs: Vec<DoubleDouble>,
    /// The step proposed at the cached point.
    proposal: f64,
    /// The last step's coefficients rounded to `f64`, its order, and `(t, h)`.
    dense: Vec<f64>,
    dense_order: u32,
    last: Option<(f64, f64)>,
    order: u32,
    _state: std::marker::PhantomData<Y>,
}

impl<Y: crate::VectorState> DoubleDoubleTaylorStepper<Y> {
    /// The workspace for states shaped like `y0` (buffers for [`DOUBLE_DOUBLE_ORDER`]; they grow
    /// once if a tighter tolerance asks for more).
    #[must_use]
    pub fn new(y0: &Y) -> Self {
        let n = y0.dim();
        let len = (DOUBLE_DOUBLE_ORDER as usize + 1) * n;
        DoubleDoubleTaylorStepper {
            n,
            state: vec![DoubleDouble::ZERO; n],
            time: None,
            cached: None,
            coeffs: vec![DoubleDouble::ZERO; len],
            proposal: f64::INFINITY,
            dense: vec![0.0; len],
            dense_order: DOUBLE_DOUBLE_ORDER,
            last: None,
            order: DOUBLE_DOUBLE_ORDER,
            _state: std::marker::PhantomData,
        }
    }

    /// The state carried, in double-double (the solution at [`Self::time`]).
    #[must_use]
    pub fn state(&self) -> &[DoubleDouble] {
        &self.state
    }

    /// The time of [`Self::state`], `None` before the first step.
    #[must_use]
    pub fn time(&self) -> Option<f64> {
        self.time
    }

    /// The order used at the last point.
    #[must_use]
    pub fn order(&self) -> u32 {
        self.order
    }

    /// Takes the driver's `(t, y)` as the state unless it is the carried state rounded.
    fn sync(&mut self, t: f64, y: &Y) {
        let own = self.time == Some(t)
            && self
                .state
                .iter()
                .zip(y.as_slice())
                .all(|(z, &v)| z.hi() == v);
        if !own {
            for (z, &v) in self.state.iter_mut().zip(y.as_slice()) {
                *z = DoubleDouble::from_f64(v);
            }
            self.time = Some(t);
            self.cached = None;
        }
    }

    /// Coefficients of order `p` of the carried state, unless they are there already.
    fn expand<P: TaylorSystem + ?Sized>(
        &mut self,
        problem: &P,
        t: f64,
        y: &Y,
        p: u32,
        h: f64,
    ) -> Result<(), crate::Error> {
        self.sync(t, y);
        if self.cached == Some(p) {
            return Ok(());
        }
        let len = (p as usize + 1) * self.n;
        if self.coeffs.len() < len {
            self.coeffs.resize(len, DoubleDouble::ZERO);
            self.dense.resize(len, 0.0);
        }
        let fail = |reason| crate::Error::Taylor {
            t,
            h,
            reason,
            state: y.to_vec(),
        };
        let system = problem
            .double_double()
            .ok_or_else(|| fail(TaylorError::NoDoubleDouble))?;
        system
            .coefficients_dd(
                DoubleDouble::from_f64(t),
                &self.state,
                p as usize,
                &mut self.coeffs[..len],
            )
            .map_err(fail)?;
        self.order = p;
        self.cached = Some(p);
        Ok(())
    }

    /// `‖xⱼ‖∞` of the current coefficients (rounded to `f64`).
    fn norm(&self, j: u32) -> f64 {
        let j = j as usize;
        self.coeffs[j * self.n..(j + 1) * self.n]
            .iter()
            .fold(0.0f64, |m, c| m.max(c.hi().abs()))
    }

    /// Order and step of Jorba & Zou at `(t, y)`, coefficients computed and cached.
    fn plan<P: TaylorSystem + ?Sized>(
        &mut self,
        problem: &P,
        t: f64,
        y: &Y,
        tolerances: &crate::Tolerances,
    ) -> Result<f64, crate::Error> {
        let x0 = y.as_slice().iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let (eps, scale) = jorba_zou_tolerance(tolerances.rtol, tolerances.atol, x0);
        let p = jorba_zou_order(eps);
        self.sync(t, y);
        if self.cached == Some(p) {
            return Ok(self.proposal);
        }
        self.expand(problem, t, y, p, f64::NAN)?;
        let h = jorba_zou_step(self.norm(p - 1), self.norm(p), p, scale);
        self.proposal = h;
        Ok(h)
    }

    /// Steps the carried state from its time `t` to the driver's next time `t + h`, and writes
    /// it, rounded, into `y`; the coefficients become the step's dense output.
    fn commit(&mut self, t: f64, y: &mut Y, h: f64) {
        let t_next = t + h;
        // The exact difference of two doubles (Knuth's TwoSum): this step's length.
        let step = DoubleDouble::new_sub(t_next, t);
        let (n, p) = (self.n, self.order as usize);
        for (i, out) in y.as_mut_slice().iter_mut().enumerate() {
            let mut s = self.coeffs[p * n + i];
            for k in (0..p).rev() {
                s = s * step + self.coeffs[k * n + i];
            }
            self.state[i] = s;
            *out = s.hi();
        }
        for (d, c) in self.dense.iter_mut().zip(&self.coeffs[..(p + 1) * n]) {
            *d = c.hi();
        }
        self.dense_order = self.order;
        self.time = Some(t_next);
        self.cached = None;
        self.last = Some((t, h));
    }
}

impl<P: TaylorSystem + ?Sized, Y: crate::VectorState> crate::Stepper<P>
    for DoubleDoubleTaylorStepper<Y>
{
    type State = Y;

    /// A fixed step at [`DOUBLE_DOUBLE_ORDER`].
    fn step(&mut self, problem: &P, t: f64, state: &mut Y, h: f64) -> Result<(), crate::Error> {
        self.expand(problem, t, state, DOUBLE_DOUBLE_ORDER, h)?;
        self.commit(t, state, h);
        Ok(())
    }

    fn reset(&mut self) {
        self.time = None;
        self.cached = None;
    }
}

impl<P: TaylorSystem + ?Sized, Y: crate::VectorState> crate::AdaptiveStepper<P>
    for DoubleDoubleTaylorStepper<Y>
{
    fn error_order(&self) -> u32 {
        self.order
    }

    /// Unused: the method proposes its own steps ([`crate::AdaptiveStepper::proposed_step`]).
    fn controller(&self) -> crate::PiController {
        crate::PiController::DOP853
    }

    /// `(h / h_JZ)^p`, as for `taylor`.
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

impl<P: TaylorSystem + ?Sized, Y: crate::VectorState> crate::DenseOutput<P>
    for DoubleDoubleTaylorStepper<Y>
{
    fn last_step(&self) -> Option<(f64, f64)> {
        self.last
    }

    /// The step's Taylor polynomial, rounded to `f64`, at `t − t₀` (Horner).
    fn interpolate(&mut self, _problem: &P, t: f64, out: &mut Y) {
        if let Some((t0, _)) = self.last {
            let (n, p, dt) = (self.n, self.dense_order as usize, t - t0);
            for (i, o) in out.as_mut_slice().iter_mut().enumerate() {
                let mut s = self.dense[p * n + i];
                for k in (0..p).rev() {
                    s = s * dt + self.dense[k * n + i];
                }
                *o = s;
            }
        }
    }

    fn dense_order(&self) -> u32 {
        self.dense_order
    }
}
