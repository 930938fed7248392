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
    DoubleDouble, DoubleDoubleSystem, SeriesScalar, TaylorError, TaylorSystem, check_finite,
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
    /// The coefficients of `ω`, 3 per order (grown once to the largest order asked).
    omega: RefCell<Vec<f64>>,
    omega_dd: RefCell<Vec<DoubleDouble>>,
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
            omega: RefCell::new(Vec::new()),
            omega_dd: RefCell::new(Vec::new()),
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

/// `Σⱼ₌₀ᵏ aⱼ × bₖ₋ⱼ` for 3-vectors whose coefficient `j` starts at `a(j)`, `b(j)`.
#[inline]
fn cross_series<S: SeriesScalar>(
    k: usize,
    a: impl Fn(usize) -> [S; 3],
    b: impl Fn(usize) -> [S; 3],
) -> [S; 3] {
    let mut s = [S::ZERO; 3];
    for j in 0..=k {
        let (x, y) = (a(j), b(k - j));
        s[0] += x[1] * y[2] - x[2] * y[1];
        s[1] += x[2] * y[0] - x[0] * y[2];
        s[2] += x[0] * y[1] - x[1] * y[0];
    }
    s
}

/// The recursion of the module doc in any scalar: coefficients `0 ..= order` of the solution
/// through `x0` into `coeffs`.
fn expand<S: SeriesScalar>(
    c: &Constants<S>,
    omega: &mut Vec<S>,
    x0: &[S],
    order: usize,
    coeffs: &mut [S],
) -> Result<(), TaylorError> {
    coeffs[..N].copy_from_slice(&x0[..N]);
    if omega.len() < 3 * (order + 1) {
        omega.resize(3 * (order + 1), S::ZERO);
    }
    let (a, wr) = (&c.inverse, &c.weighted_center);
    for k in 0..order {
        // ωₖ = J⁻¹ mₖ (a row of J⁻¹ times mₖ, summed left to right).
        let at = k * N + 9;
        let mk = [coeffs[at], coeffs[at + 1], coeffs[at + 2]];
        for (i, row) in a.iter().enumerate() {
            omega[3 * k + i] = row[0] * mk[0] + row[1] * mk[1] + row[2] * mk[2];
        }
        let w = |j: usize| [omega[3 * j], omega[3 * j + 1], omega[3 * j + 2]];
        let scale = S::of(1.0).quotient(S::of((k + 1) as f64));
        let mut next = [S::ZERO; N];
        // Each row of R: (rₐ × ω)ₖ; R[a][b] is component b·3 + a.
        for row in 0..3 {
            let r = |j: usize| {
                let at = j * N + row;
                [coeffs[at], coeffs[at + 3], coeffs[at + 6]]
            };
            let s = cross_series(k, r, w);
            for (b, v) in s.iter().enumerate() {
                next[b * 3 + row] = *v * scale;
            }
        }
        // (m × ω)ₖ + w (Rᵀe₃)ₖ × ρ, Rᵀe₃ the third row.
        let m = |j: usize| {
            let at = j * N + 9;
            [coeffs[at], coeffs[at + 1], coeffs[at + 2]]
        };
        let s = cross_series(k, m, w);
        let at = k * N + 2;
        let g = [coeffs[at], coeffs[at + 3], coeffs[at + 6]];
        let torque = [
            g[1] * wr[2] - g[2] * wr[1],
            g[2] * wr[0] - g[0] * wr[2],
            g[0] * wr[1] - g[1] * wr[0],
        ];
        for i in 0..3 {
            next[9 + i] = (s[i] + torque[i]) * scale;
        }
        coeffs[(k + 1) * N..(k + 2) * N].copy_from_slice(&next);
    }
    check_finite(coeffs, N, order)
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
        expand(
            &self.double,
            &mut self.omega.borrow_mut(),
            x0,
            order,
            coeffs,
        )
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
            &mut self.omega_dd.borrow_mut(),
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
