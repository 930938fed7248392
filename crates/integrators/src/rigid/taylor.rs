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

use super::problem::{HeavyTop, RigidBody};
use crate::taylor::{TaylorError, TaylorSystem, check_finite};

/// State components: `R` (9, column-major) and `m` (3).
const N: usize = 12;

/// A heavy top's equations as a [`TaylorSystem`] on ℝ¹² (module doc).
#[derive(Debug, Clone)]
pub struct TaylorHeavyTop {
    /// `J⁻¹`.
    inverse: Matrix3<f64>,
    /// `w ρ`: the weight times the centre of mass from the fixed point (body frame).
    weighted_center: Vector3<f64>,
    /// The coefficients of `ω`, 3 per order (grown once to the largest order asked).
    omega: RefCell<Vec<f64>>,
}

impl TaylorHeavyTop {
    /// The Taylor system of `top`.
    #[must_use]
    pub fn new(top: &HeavyTop) -> Self {
        let inverse = top
            .body()
            .inertia()
            .try_inverse()
            .unwrap_or_else(|| Matrix3::from_element(f64::NAN));
        TaylorHeavyTop {
            inverse,
            weighted_center: top.center() * top.weight(),
            omega: RefCell::new(Vec::new()),
        }
    }
}

/// `Σⱼ₌₀ᵏ aⱼ × bₖ₋ⱼ` for 3-vectors whose coefficient `j` starts at `a(j)`, `b(j)`.
#[inline]
fn cross_series(
    k: usize,
    a: impl Fn(usize) -> [f64; 3],
    b: impl Fn(usize) -> [f64; 3],
) -> [f64; 3] {
    let mut s = [0.0; 3];
    for j in 0..=k {
        let (x, y) = (a(j), b(k - j));
        s[0] += x[1] * y[2] - x[2] * y[1];
        s[1] += x[2] * y[0] - x[0] * y[2];
        s[2] += x[0] * y[1] - x[1] * y[0];
    }
    s
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
        coeffs[..N].copy_from_slice(&x0[..N]);
        let mut omega = self.omega.borrow_mut();
        if omega.len() < 3 * (order + 1) {
            omega.resize(3 * (order + 1), 0.0);
        }
        let (a, wr) = (&self.inverse, &self.weighted_center);
        for k in 0..order {
            // ωₖ = J⁻¹ mₖ.
            let m = |j: usize| {
                let at = j * N + 9;
                Vector3::new(coeffs[at], coeffs[at + 1], coeffs[at + 2])
            };
            let wk = a * m(k);
            omega[3 * k..3 * k + 3].copy_from_slice(wk.as_slice());
            let w = |j: usize| [omega[3 * j], omega[3 * j + 1], omega[3 * j + 2]];
            let scale = 1.0 / (k + 1) as f64;
            let mut next = [0.0; N];
            // Each row of R: (rₐ × ω)ₖ; R[a][b] is component b·3 + a.
            for row in 0..3 {
                let r = |j: usize| {
                    let at = j * N + row;
                    [coeffs[at], coeffs[at + 3], coeffs[at + 6]]
                };
                let s = cross_series(k, r, w);
                for (b, v) in s.iter().enumerate() {
                    next[b * 3 + row] = v * scale;
                }
            }
            // (m × ω)ₖ + w (Rᵀe₃)ₖ × ρ, Rᵀe₃ the third row.
            let mk = |j: usize| {
                let at = j * N + 9;
                [coeffs[at], coeffs[at + 1], coeffs[at + 2]]
            };
            let s = cross_series(k, mk, w);
            let at = k * N + 2;
            let gamma = Vector3::new(coeffs[at], coeffs[at + 3], coeffs[at + 6]);
            let torque = gamma.cross(wr);
            for i in 0..3 {
                next[9 + i] = (s[i] + torque[i]) * scale;
            }
            coeffs[(k + 1) * N..(k + 2) * N].copy_from_slice(&next);
        }
        check_finite(coeffs, N, order)
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
