//! The right Jacobian of `exp` as coefficients in `θ² = |u|²`, and the derivatives of
//! `J_r(u) w` in `u`, for integrators that work in exponential coordinates (the variational
//! Lie–Gauss methods of `tumble-integrators`).
//!
//! `J_r(u) = 𝟙 − a(θ²) hat u + b(θ²) hat u²` ([`super::dexp`]) with `a = (1 − cos θ)/θ²`,
//! `b = (θ − sin θ)/θ³`; `exp(hat u) = 𝟙 + sinc θ hat u + a hat u²`;
//! `J_r(u)⁻¹ = 𝟙 + ½ hat u + c hat u²`, `c = (1 − (θ/2) cot(θ/2))/θ²`. The derivative of
//! `J_r(u) w` in `u` is in closed form, with `a′`, `b′` the derivatives in `θ²`:
//!
//! ```text
//! (∂(J_r w)/∂u)ᵀ Π = 2 (b′ (u × (u × w)) − a′ (u × w))·Π u − a w × Π + b (u × w) × Π − b w × (u × Π).
//! ```
//!
//! Below `θ = 1` every coefficient is a Taylor series in `θ²` (no cancellation), above it the
//! closed form. These are `f64` only: the generic functions of [`super`] serve dual numbers.
//!
//! # References
//! - J. Solà, J. Deray, D. Atchuthan, "A micro Lie theory for state estimation in robotics",
//!   arXiv:1812.01537 (2018).
//! - G. Bogfjellmo, H. Marthinsen, *High-order symplectic partitioned Lie group methods*, Found.
//!   Comput. Math. 16 (2016) 493–530.

use nalgebra::{Matrix3, Vector3};

use super::hat;

/// `sin θ/θ`, `a = (1 − cos θ)/θ²`, `b = (θ − sin θ)/θ³`, `a′`, `b′` (derivatives in `θ²`) and
/// `c = (1 − (θ/2) cot(θ/2))/θ²`, the coefficient of `hat u²` in `J_r(u)⁻¹ = 𝟙 + ½ hat u + c hat u²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExpCoefficients {
    /// `sin θ/θ`.
    pub sinc: f64,
    /// `(1 − cos θ)/θ²`.
    pub a: f64,
    /// `(θ − sin θ)/θ³`.
    pub b: f64,
    /// `a′`, the derivative of `a` in `θ²`.
    pub da: f64,
    /// `b′`, the derivative of `b` in `θ²`.
    pub db: f64,
    /// `c = (1 − (θ/2) cot(θ/2))/θ²`.
    pub inv: f64,
}

/// `|B₂ₙ|/(2n)!` for `n = 1 … SERIES_TERMS` (Bernoulli numbers `B₂ … B₂₄`): the series
/// `c = Σ |B₂ₙ|/(2n)! θ^{2n−2}` of `(1 − (θ/2) cot(θ/2))/θ²` (radius `θ = 2π`).
const INV: [f64; SERIES_TERMS] = {
    let bernoulli = [
        1.0 / 6.0,
        1.0 / 30.0,
        1.0 / 42.0,
        1.0 / 30.0,
        5.0 / 66.0,
        691.0 / 2730.0,
        7.0 / 6.0,
        3617.0 / 510.0,
        43867.0 / 798.0,
        174_611.0 / 330.0,
        854_513.0 / 138.0,
        236_364_091.0 / 2730.0,
    ];
    let mut c = [0.0; SERIES_TERMS];
    let mut n = 0;
    while n < SERIES_TERMS {
        let mut factorial = 1.0;
        let mut i = 2;
        while i <= 2 * (n + 1) {
            factorial *= i as f64;
            i += 1;
        }
        c[n] = bernoulli[n] / factorial;
        n += 1;
    }
    c
};

/// Terms of the Taylor series in `t = θ²` used below `θ = 1`: enough for round-off there
/// (the first term left out is below 1/25! relative).
const SERIES_TERMS: usize = 12;

/// `c_j = s (j + 1)ᵈ (−1)^(j+d) / (2j + m + 2d)!` for `j = 0 … SERIES_TERMS − 1`: with `d = 0`
/// the series of `Σ (−t)ʲ/(2j + m)!`, with `d = 1` that of its derivative in `t`.
const fn series(m: usize, derivative: bool) -> [f64; SERIES_TERMS] {
    let mut c = [0.0; SERIES_TERMS];
    let mut j = 0;
    while j < SERIES_TERMS {
        let d = if derivative { 1 } else { 0 };
        let n = 2 * j + m + 2 * d;
        let mut factorial = 1.0;
        let mut i = 2;
        while i <= n {
            factorial *= i as f64;
            i += 1;
        }
        let sign = if (j + d) % 2 == 0 { 1.0 } else { -1.0 };
        let weight = if derivative { (j + 1) as f64 } else { 1.0 };
        c[j] = sign * weight / factorial;
        j += 1;
    }
    c
}

const SINC: [f64; SERIES_TERMS] = series(1, false);
const A: [f64; SERIES_TERMS] = series(2, false);
const B: [f64; SERIES_TERMS] = series(3, false);
const DA: [f64; SERIES_TERMS] = series(2, true);
const DB: [f64; SERIES_TERMS] = series(3, true);

fn horner(c: &[f64; SERIES_TERMS], t: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ci| acc * t + ci)
}

impl ExpCoefficients {
    /// `J_r(u) = 𝟙 − a hat u + b hat u²`, for the `u` these coefficients are of.
    #[must_use]
    pub fn right_jacobian(&self, u: &Vector3<f64>) -> Matrix3<f64> {
        let uh = hat(u);
        Matrix3::identity() - uh * self.a + uh * uh * self.b
    }

    /// At `t = θ²`: the Taylor series below `θ = 1` (no cancellation), closed forms above
    /// (their cancellations cost at most a few units in the 14th digit at `θ = 1`).
    #[must_use]
    pub fn new(t: f64) -> Self {
        if t < 1.0 {
            Self {
                sinc: horner(&SINC, t),
                a: horner(&A, t),
                b: horner(&B, t),
                da: horner(&DA, t),
                db: horner(&DB, t),
                inv: horner(&INV, t),
            }
        } else {
            let theta = t.sqrt();
            let (s, c) = theta.sin_cos();
            let one_c = 1.0 - c;
            let th_s = theta - s;
            // (θ/2) cot(θ/2) = θ sin θ / (2 (1 − cos θ)).
            let half_cot = theta * s / (2.0 * one_c);
            Self {
                sinc: s / theta,
                a: one_c / t,
                b: th_s / (theta * t),
                da: (theta * s - 2.0 * one_c) / (2.0 * t * t),
                db: (theta * one_c - 3.0 * th_s) / (2.0 * theta * t * t),
                inv: (1.0 - half_cot) / t,
            }
        }
    }
}

/// `(∂(J_r(u) w)/∂u)ᵀ Π` (module doc), with `co` the coefficients of `u`.
#[must_use]
pub fn right_jacobian_derivative_transpose(
    co: &ExpCoefficients,
    u: &Vector3<f64>,
    w: &Vector3<f64>,
    pi: &Vector3<f64>,
) -> Vector3<f64> {
    let uw = u.cross(w);
    let uuw = u.cross(&uw);
    let s = 2.0 * (co.db * uuw.dot(pi) - co.da * uw.dot(pi));
    u * s - w.cross(pi) * co.a + uw.cross(pi) * co.b - w.cross(&u.cross(pi)) * co.b
}

/// `∂(J_r(u) w)/∂u` (module doc), with `co` the coefficients of `u`.
#[must_use]
pub fn right_jacobian_derivative(
    co: &ExpCoefficients,
    u: &Vector3<f64>,
    w: &Vector3<f64>,
) -> Matrix3<f64> {
    let uw = u.cross(w);
    let uuw = u.cross(&uw);
    (uuw * (2.0 * co.db) - uw * (2.0 * co.da)) * u.transpose() + hat(w) * co.a
        - (hat(&uw) + hat(u) * hat(w)) * co.b
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::so3::dexp;

    #[test]
    fn series_and_closed_forms_agree_at_the_switch_and_match_the_definitions() {
        for &theta in &[1e-3, 0.3, 0.999_999, 1.000_001, 1.5, 2.0, 2.5, 3.0] {
            let t: f64 = theta * theta;
            let co = ExpCoefficients::new(t);
            let (s, c) = theta.sin_cos();
            assert!((co.sinc - s / theta).abs() < 1e-15, "sinc at {theta}");
            let inv = 1.0 / t - (theta / 2.0).cos() / (theta / 2.0).sin() / (2.0 * theta);
            assert!(
                (co.inv - inv).abs() < 1e-13 / t.min(1.0),
                "J_r⁻¹ coefficient at {theta}"
            );
            let u = Vector3::new(0.6, -0.48, 0.64) * theta;
            let uh = hat(&u);
            let jr_inv = Matrix3::identity() + uh * 0.5 + uh * uh * co.inv;
            assert!(
                (jr_inv * dexp(&u) - Matrix3::identity()).amax() < 1e-14,
                "J_r⁻¹ J_r at {theta}"
            );
            assert!(
                (co.a - (1.0 - c) / t).abs() < 1e-13 / t.min(1.0),
                "a at {theta}"
            );
            let b = (theta - s) / (theta * t);
            assert!(
                (co.b - b).abs() < 1e-12 / (t * theta).min(1.0),
                "b at {theta}"
            );
            // Derivatives in t against central differences of the closed forms (θ ≥ 0.3).
            if theta >= 0.3 {
                let e = 1e-6;
                let f = |t: f64| {
                    let th = t.sqrt();
                    ((1.0 - th.cos()) / t, (th - th.sin()) / (th * t))
                };
                let (ap, bp) = f(t + e);
                let (am, bm) = f(t - e);
                assert!(
                    (co.da - (ap - am) / (2.0 * e)).abs() < 1e-8,
                    "a' at {theta}"
                );
                assert!(
                    (co.db - (bp - bm) / (2.0 * e)).abs() < 1e-8,
                    "b' at {theta}"
                );
            }
        }
    }

    #[test]
    fn right_jacobian_derivative_matches_central_differences() {
        let w = Vector3::new(0.3, -1.1, 0.7);
        let pi = Vector3::new(-0.4, 0.9, 2.0);
        for u in [
            Vector3::new(1e-4, 2e-4, -1e-4),
            Vector3::new(0.2, -0.1, 0.3),
            Vector3::new(1.5, 0.9, -1.2),
        ] {
            let co = ExpCoefficients::new(u.norm_squared());
            let analytic = right_jacobian_derivative_transpose(&co, &u, &w, &pi);
            let e = 1e-6;
            let numeric = Vector3::from_fn(|i, _| {
                let mut d = Vector3::zeros();
                d[i] = e;
                ((dexp(&(u + d)) * w).dot(&pi) - (dexp(&(u - d)) * w).dot(&pi)) / (2.0 * e)
            });
            assert!(
                (analytic - numeric).amax() < 1e-8,
                "u = {u:?}: {analytic:?} vs {numeric:?}"
            );
            // The matrix form, column by column.
            let dm = right_jacobian_derivative(&co, &u, &w);
            for i in 0..3 {
                let mut d = Vector3::zeros();
                d[i] = e;
                let col = (dexp(&(u + d)) * w - dexp(&(u - d)) * w) / (2.0 * e);
                assert!((dm.column(i) - col).amax() < 1e-8, "u = {u:?}, column {i}");
            }
            // The Jacobian the step uses is so3::dexp's.
            assert!((co.right_jacobian(&u) - dexp(&u)).amax() < 1e-14);
        }
    }
}
