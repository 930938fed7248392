//! The Taylor coefficients of a heavy top (or a torque-free body, weight zero), written out by
//! hand: Euler's equations with the orientation as a matrix, `x = (R, m)` on ℝ¹² (`R` column by
//! column, then the body angular momentum `m`),
//!
//! `Ṙ = R hat(ω)` (each row `rₐ` of `R`: `ṙₐ = rₐ × ω`), `ṁ = m × ω + w (Rᵀe₃) × ρ`,
//! `ω = J⁻¹ m`,
//!
//! a polynomial system: the normalized coefficients follow from Cauchy products alone
//! (`(a b)ₖ = Σⱼ aⱼ bₖ₋ⱼ`; Moore 1966; Jorba & Zou 2005, §3), `ωₖ = J⁻¹ mₖ` and
//! `(Rᵀe₃)ₖ` (the third row of `Rₖ`) being linear. 24 products per order: the cost of an
//! expansion of order `p` is about `12 p²` multiply–adds, with no right-hand side evaluated.
//! The same layout as the scenes' flattened rigid body, so rows and errors are unchanged.

use std::cell::RefCell;

use nalgebra::{Matrix3, Vector3};

use super::FreeRigidBody;
use super::problem::{HeavyTop, RigidBody};
use crate::taylor::{
    CrossSums, DoubleDouble, DoubleDoubleSystem, SeriesScalar, TaylorError, TaylorSystem,
    check_finite,
};

/// State components: `R` (9, column-major) and `m` (3).
const N: usize = 12;

/// The top's constants in one scalar type: `J⁻¹` by rows, and `w ρ`.
#[derive(Debug, Clone)]
struct Constants<S> {
    inverse: [[S; 3]; 3],
    weighted_center: [S; 3],
}

/// A heavy top's equations as a [`TaylorSystem`] on ℝ¹² (module doc), in `f64` and in
/// double-double ([`DoubleDoubleSystem`]).
#[derive(Debug, Clone)]
pub struct TaylorHeavyTop {
    double: Constants<f64>,
    /// `J⁻¹` and `w ρ` of the same `f64` inertia, weight and centre, in double-double.
    double_double: Constants<DoubleDouble>,
    /// The recursion's series (grown once to the largest order asked).
    work: RefCell<CrossSums<f64, N>>,
    work_dd: RefCell<CrossSums<DoubleDouble, N>>,
    arch: pulp::Arch,
}

impl TaylorHeavyTop {
    /// The Taylor system of `top`.
    #[must_use]
    pub fn new(top: &HeavyTop) -> Self {
        Self::with(&top.body().inertia(), top.weight(), &top.center())
    }

    /// The Taylor system of a torque-free body (weight zero).
    #[must_use]
    pub fn free(body: &FreeRigidBody) -> Self {
        Self::with(&body.inertia(), 0.0, &Vector3::zeros())
    }

    fn with(inertia: &Matrix3<f64>, weight: f64, center: &Vector3<f64>) -> Self {
        let inverse = inertia
            .try_inverse()
            .unwrap_or_else(|| Matrix3::from_element(f64::NAN));
        TaylorHeavyTop {
            double: Constants {
                inverse: std::array::from_fn(|i| std::array::from_fn(|j| inverse[(i, j)])),
                weighted_center: std::array::from_fn(|i| center[i] * weight),
            },
            double_double: Constants {
                inverse: inverse_dd(inertia),
                weighted_center: std::array::from_fn(|i| DoubleDouble::new_mul(center[i], weight)),
            },
            work: RefCell::new(CrossSums::default()),
            work_dd: RefCell::new(CrossSums::default()),
            arch: pulp::Arch::new(),
        }
    }
}

/// The inverse of an `f64` matrix in double-double (cofactors over the determinant); NaN when
/// it is singular.
fn inverse_dd(m: &Matrix3<f64>) -> [[DoubleDouble; 3]; 3] {
    let a = |i: usize, j: usize| DoubleDouble::from_f64(m[(i, j)]);
    // cofactor (i, j) of m: the minor with row i and column j struck out, signed.
    let cof = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        a(r0, c0) * a(r1, c1) - a(r0, c1) * a(r1, c0)
    };
    let det = a(0, 0) * cof(0, 0) + a(0, 1) * cof(0, 1) + a(0, 2) * cof(0, 2);
    if det.hi() == 0.0 || !det.hi().is_finite() {
        return [[DoubleDouble::from_f64(f64::NAN); 3]; 3];
    }
    // (m⁻¹)ᵢⱼ = cofⱼᵢ / det.
    std::array::from_fn(|i| std::array::from_fn(|j| cof(j, i).quotient(det)))
}

/// The output component `i` of the twelve products `(rₐ × ω)ᵦ` (`i = 3b + a`, the layout of
/// `R`) and `(m × ω)ᵦ` (`i = 9 + b`), each `uᵦ₊₁ wᵦ₊₂ − uᵦ₊₂ wᵦ₊₁`: where in a state
/// `(R column-major, m, …)` its two `u` factors are, and which components of `ω` multiply
/// them (the lanes of a [`CrossSums`]).
#[derive(Debug, Clone, Copy)]
pub struct CrossPattern {
    /// The index of `uᵦ₊₁` in the state.
    pub first: [usize; N],
    /// The index of `uᵦ₊₂` in the state.
    pub second: [usize; N],
    /// The component of `ω` that multiplies `uᵦ₊₁`.
    pub w_first: [usize; N],
    /// The component of `ω` that multiplies `uᵦ₊₂`.
    pub w_second: [usize; N],
}

/// [`CrossPattern`] of `Ṙ = R hat(ω)` (row by row, `ṙₐ = rₐ × ω`) and `m × ω`.
pub const PATTERN: CrossPattern = {
    let mut p = CrossPattern {
        first: [0; N],
        second: [0; N],
        w_first: [0; N],
        w_second: [0; N],
    };
    let mut i = 0;
    while i < N {
        // (base, stride): rows of R are strided by 3 (column-major), m is contiguous.
        let (b, base, stride) = if i < 9 {
            (i / 3, i % 3, 3)
        } else {
            (i - 9, 9, 1)
        };
        p.first[i] = base + stride * ((b + 1) % 3);
        p.second[i] = base + stride * ((b + 2) % 3);
        p.w_first[i] = (b + 2) % 3;
        p.w_second[i] = (b + 1) % 3;
        i += 1;
    }
    p
};

/// The recursion of the module doc in any scalar: coefficients `0 ..= order` of the solution
/// through `x0` into `coeffs`.
///
/// Order `k` accumulates all twelve Cauchy sums at once, `(rₐ × ω)ₖ = Σⱼ rₐ,ⱼ × ωₖ₋ⱼ` for the
/// three rows `rₐ` of `R` and `(m × ω)ₖ`, each term in the form of a cross product's
/// component, `uᵦ₊₁ wᵦ₊₂ − uᵦ₊₂ wᵦ₊₁`: the terms `j = 1 … k − 1` first
/// ([`CrossSums::middle`]), then those that hold order `k` ([`CrossSums::finish_with`]).
#[inline(always)]
fn expand<S: SeriesScalar>(
    c: &Constants<S>,
    work: &mut CrossSums<S, N>,
    x0: &[S],
    order: usize,
    coeffs: &mut [S],
) -> Result<(), TaylorError> {
    coeffs[..N].copy_from_slice(&x0[..N]);
    work.reserve(order);
    let (a, wr) = (&c.inverse, &c.weighted_center);
    for k in 0..order {
        let x = &coeffs[k * N..(k + 1) * N];
        // The terms of orders below k first, then the end terms from the order-k factors.
        let middle = work.middle(k);
        // ωₖ = J⁻¹ mₖ (a row of J⁻¹ times mₖ, summed left to right).
        let omega: [S; 3] =
            std::array::from_fn(|i| a[i][0] * x[9] + a[i][1] * x[10] + a[i][2] * x[11]);
        let factors = [
            PATTERN.first.map(|i| x[i]),
            PATTERN.second.map(|i| x[i]),
            PATTERN.w_first.map(|i| omega[i]),
            PATTERN.w_second.map(|i| omega[i]),
        ];
        let [f1, f2, f3, f4] = &factors;
        let sums = work.finish_with(k, 0, middle, [f1, f2, f3, f4]);
        let [f1, f2, f3, f4] = factors;
        work.set(k, f1, f2, f3, f4);
        // + w (Rᵀe₃)ₖ × ρ, Rᵀe₃ the third row.
        let g = [x[2], x[5], x[8]];
        let torque = [
            g[1] * wr[2] - g[2] * wr[1],
            g[2] * wr[0] - g[0] * wr[2],
            g[0] * wr[1] - g[1] * wr[0],
        ];
        let scale = S::of(1.0).quotient(S::of((k + 1) as f64));
        let next = &mut coeffs[(k + 1) * N..(k + 2) * N];
        for i in 0..9 {
            next[i] = sums[i] * scale;
        }
        for i in 0..3 {
            next[9 + i] = (sums[9 + i] + torque[i]) * scale;
        }
    }
    check_finite(coeffs, N, order)
}

/// [`expand`] in `f64`, compiled for the instruction set `pulp` finds at run time (inlined
/// into its target-feature function, so that the element-wise sums use the widest vectors;
/// the operations and their order are those of the baseline, so the result is the same bit
/// for bit).
struct Expand<'a> {
    c: &'a Constants<f64>,
    work: &'a mut CrossSums<f64, N>,
    x0: &'a [f64],
    order: usize,
    coeffs: &'a mut [f64],
}

impl pulp::WithSimd for Expand<'_> {
    type Output = Result<(), TaylorError>;
    #[inline(always)]
    fn with_simd<V: pulp::Simd>(self, _: V) -> Self::Output {
        expand(self.c, self.work, self.x0, self.order, self.coeffs)
    }
}

impl TaylorSystem for TaylorHeavyTop {
    fn dim(&self) -> usize {
        N
    }

    fn coefficients(
        &self,
        _t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError> {
        self.arch.dispatch(Expand {
            c: &self.double,
            work: &mut self.work.borrow_mut(),
            x0,
            order,
            coeffs,
        })
    }

    fn double_double(&self) -> Option<&dyn DoubleDoubleSystem> {
        Some(self)
    }
}

impl DoubleDoubleSystem for TaylorHeavyTop {
    fn coefficients_dd(
        &self,
        _t0: DoubleDouble,
        x0: &[DoubleDouble],
        order: usize,
        coeffs: &mut [DoubleDouble],
    ) -> Result<(), TaylorError> {
        expand(
            &self.double_double,
            &mut self.work_dd.borrow_mut(),
            x0,
            order,
            coeffs,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rigid::EulerEquations;
    use crate::rigid::problem::LieVectorField;
    use tumble_kinematics::so3::hat;

    /// The first coefficient is the right-hand side: `x₁ = F(x₀)`, against Euler's equations as
    /// the other methods evaluate them; the second is `½ dF/dt` along the flow, against a
    /// central difference of `F` along a tiny step.
    #[test]
    fn the_series_starts_with_the_right_hand_side_and_its_derivative() {
        let top = HeavyTop::simo_wong();
        let s0 = HeavyTop::simo_wong_initial();
        let mut x0 = [0.0; N];
        x0[..9].copy_from_slice(s0.rotation.as_slice());
        x0[9..].copy_from_slice(s0.momentum.as_slice());
        let f = |x: &[f64; N]| -> [f64; N] {
            let r = Matrix3::from_column_slice(&x[..9]);
            let m = Vector3::new(x[9], x[10], x[11]);
            let (omega, dm) = EulerEquations(&top).eval(0.0, &r, &m);
            let rd = r * hat(&omega);
            let mut out = [0.0; N];
            out[..9].copy_from_slice(rd.as_slice());
            out[9..].copy_from_slice(dm.as_slice());
            out
        };
        let system = TaylorHeavyTop::new(&top);
        let mut c = vec![0.0; 3 * N];
        system.coefficients(0.0, &x0, 2, &mut c).unwrap();
        let f0 = f(&x0);
        for i in 0..N {
            assert!(
                (c[N + i] - f0[i]).abs() <= 1e-13 * (1.0 + f0[i].abs()),
                "x1[{i}]"
            );
        }
        let h = 1e-6;
        let shifted = |s: f64| {
            let mut x = x0;
            for i in 0..N {
                x[i] += s * f0[i];
            }
            f(&x)
        };
        let (fp, fm) = (shifted(h), shifted(-h));
        for i in 0..N {
            let x2 = (fp[i] - fm[i]) / (2.0 * h) / 2.0;
            assert!(
                (c[2 * N + i] - x2).abs() <= 1e-5 * (1.0 + x2.abs()),
                "x2[{i}]: {} vs {x2}",
                c[2 * N + i]
            );
        }
    }
}
