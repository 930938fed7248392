//! States: what a stepper advances.
//!
//! [`State`] is the minimum a driver needs of any state — a finiteness check and a flat
//! snapshot for error reports — and is all that compositions require, so that states that
//! are not vector spaces (a rotation matrix with momenta, `SO(3) × ℝⁿ`) can be stepped
//! through the same machinery.
//!
//! [`VectorState`] adds the flat `f64` storage that Runge–Kutta, Störmer–Verlet and
//! Gauss–Legendre steppers need: `y ← y + h Σ bᵢ kᵢ` is written once, on slices, for
//! `SVector<f64, N>` (no heap, no allocation per step), `DVector<f64>` and `[f64; N]`.
//!
//! # Compensated summation
//!
//! [`compensated_add`] implements Kahan's compensated summation for a state update
//! `y ← y + δ` with a carried error term `e` (Kahan 1965; Møller 1965):
//! `δ' = δ + e`, `y' = y + δ'`, `e = (y − y') + δ'`. Over `n` steps the round-off in `y`
//! then grows like `ε √n` instead of `ε n` (Brouwer's law).
//!
//! # References
//! - W. Kahan, *Further remarks on reducing truncation errors*, Comm. ACM 8 (1965) 40.
//! - E. Hairer, R. I. McLachlan, A. Razakarivony, *Achieving Brouwer's law with implicit
//!   Runge–Kutta methods*, BIT 48 (2008) 231–243.

use nalgebra::{DVector, SVector};

/// Anything a [`Stepper`](crate::Stepper) can advance and a driver can watch.
pub trait State: Clone {
    /// `true` when every number in the state is finite (no NaN, no ±∞).
    fn is_finite(&self) -> bool;
    /// The state's numbers, flattened, for error reports (allocates; only on failure paths).
    fn to_vec(&self) -> Vec<f64>;
    /// Overwrites `self` with `other` (same dimension). Drivers keep the state at the start of
    /// each step this way, to report it if the step fails; heap-backed states override it so
    /// that no step allocates.
    fn copy_from(&mut self, other: &Self) {
        *self = other.clone();
    }
}

/// A state stored as a flat array of `f64`: the vector-space operations of Runge–Kutta
/// methods are written on its slice.
pub trait VectorState: State {
    /// The components.
    fn as_slice(&self) -> &[f64];
    /// The components, mutable.
    fn as_mut_slice(&mut self) -> &mut [f64];
    /// A zero state of the same dimension (used to build workspaces, once per run).
    #[must_use]
    fn zeros_like(&self) -> Self;
    /// Number of components.
    fn dim(&self) -> usize {
        self.as_slice().len()
    }
}

impl<const N: usize> State for SVector<f64, N> {
    fn is_finite(&self) -> bool {
        self.iter().all(|x| x.is_finite())
    }
    fn to_vec(&self) -> Vec<f64> {
        self.as_slice().to_vec()
    }
}

impl<const N: usize> VectorState for SVector<f64, N> {
    #[inline]
    fn as_slice(&self) -> &[f64] {
        nalgebra::Matrix::as_slice(self)
    }
    #[inline]
    fn as_mut_slice(&mut self) -> &mut [f64] {
        nalgebra::Matrix::as_mut_slice(self)
    }
    fn zeros_like(&self) -> Self {
        Self::zeros()
    }
    /// `N`, a constant: loops over `0..dim()` compile to fixed-length code.
    #[inline]
    fn dim(&self) -> usize {
        N
    }
}

impl State for DVector<f64> {
    fn is_finite(&self) -> bool {
        self.iter().all(|x| x.is_finite())
    }
    fn to_vec(&self) -> Vec<f64> {
        self.as_slice().to_vec()
    }
    fn copy_from(&mut self, other: &Self) {
        if self.len() == other.len() {
            self.copy_from_slice(other.as_slice());
        } else {
            *self = other.clone();
        }
    }
}

impl VectorState for DVector<f64> {
    fn as_slice(&self) -> &[f64] {
        nalgebra::Matrix::as_slice(self)
    }
    fn as_mut_slice(&mut self) -> &mut [f64] {
        nalgebra::Matrix::as_mut_slice(self)
    }
    fn zeros_like(&self) -> Self {
        DVector::zeros(self.len())
    }
}

impl<const N: usize> State for [f64; N] {
    fn is_finite(&self) -> bool {
        self.iter().all(|x| x.is_finite())
    }
    fn to_vec(&self) -> Vec<f64> {
        self.as_slice().to_vec()
    }
}

impl<const N: usize> VectorState for [f64; N] {
    #[inline]
    fn as_slice(&self) -> &[f64] {
        self
    }
    #[inline]
    fn as_mut_slice(&mut self) -> &mut [f64] {
        self
    }
    fn zeros_like(&self) -> Self {
        [0.0; N]
    }
    #[inline]
    fn dim(&self) -> usize {
        N
    }
}

/// `y ← y + δ` with Kahan compensation: `carry` holds the rounding error of the previous
/// updates and is updated in place.
#[inline]
pub fn compensated_add(y: &mut f64, delta: f64, carry: &mut f64) {
    let d = delta + *carry;
    let new = *y + d;
    *carry = (*y - new) + d;
    *y = new;
}

/// Copy `src` into `dst` (same dimension).
#[inline]
pub(crate) fn copy_into<Y: VectorState>(dst: &mut Y, src: &Y) {
    dst.as_mut_slice().copy_from_slice(src.as_slice());
}

/// Max-norm of a slice.
#[inline]
pub(crate) fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// `true` when two times agree to a few ulps (a driver's `t₀ + k h` against a stepper's
/// `t + h`): used to decide whether data cached at the end of the last step still apply.
#[inline]
pub(crate) fn same_time(a: f64, b: f64) -> bool {
    (a - b).abs() <= 8.0 * f64::EPSILON * a.abs().max(b.abs())
}
