//! The Taylor coefficients of `driven-hoop` and `spinning-hoop`, by the recursions of automatic
//! differentiation written out for their equations (Moore 1966; Jorba & Zou 2005, §3):
//!
//! - `sin α`, `cos α` along the series: `k sₖ = Σⱼ₌₁ᵏ j αⱼ cₖ₋ⱼ`, `k cₖ = −Σⱼ₌₁ᵏ j αⱼ sₖ₋ⱼ`;
//! - products by Cauchy sums, `(a b)ₖ = Σⱼ aⱼ bₖ₋ⱼ`, and a quotient `u = n / d` by
//!   `uₖ = (nₖ − Σⱼ₌₁ᵏ dⱼ uₖ₋ⱼ) / d₀`;
//! - `(k + 1) xₖ₊₁ = [F(x)]ₖ`.
//!
//! `driven-hoop`, state `(α, α̇)`: `α̈ = ω² (sin α cos α) − (g/a) sin α`.
//! `spinning-hoop`, state `(φ, α, φ̇, α̇)`: `φ̈ = −2 m a² (sin α cos α) α̇ φ̇ / (Ma²/2 + m a² sin²α)`,
//! `α̈ = (sin α cos α) φ̇² − (g/a) sin α` (the right-hand sides of [`DrivenHoop`] and
//! [`SpinningHoop`]).

use std::cell::RefCell;

use tumble_integrators::TaylorSystem;
use tumble_integrators::taylor::{TaylorError, check_finite};

use super::{DrivenHoop, SpinningHoop};
use crate::scenes::cauchy;

/// Series of one run, each `len` coefficients long (grown once to the largest order).
#[derive(Debug, Default)]
struct Series {
    len: usize,
    /// The state's series, component by component, then the auxiliary ones.
    data: Vec<f64>,
}

impl Series {
    /// Room for `count` series of order `order`, zeroed where they grow.
    fn reserve(&mut self, count: usize, order: usize) -> usize {
        if self.len < order + 1 {
            self.len = order + 1;
            self.data = vec![0.0; count * self.len];
        }
        self.len
    }
}

/// Order `k` of `sin α` and `cos α` into `s[k]`, `c[k]` from `α`'s orders `1 ..= k` and their
/// lower orders (`k ≥ 1`).
#[inline]
fn sin_cos_at(alpha: &[f64], s: &mut [f64], c: &mut [f64], k: usize) {
    let (mut ss, mut cc) = (0.0, 0.0);
    for j in 1..=k {
        let u = j as f64 * alpha[j];
        ss += u * c[k - j];
        cc += u * s[k - j];
    }
    let inv = 1.0 / k as f64;
    s[k] = ss * inv;
    c[k] = -cc * inv;
}

/// `driven-hoop`'s equations as a [`TaylorSystem`] on `(α, α̇)` (module doc).
#[derive(Debug)]
pub struct TaylorDrivenHoop {
    omega2: f64,
    g_over_a: f64,
    series: RefCell<Series>,
}

impl TaylorDrivenHoop {
    /// The Taylor system of `hoop`.
    #[must_use]
    pub fn new(hoop: &DrivenHoop) -> Self {
        Self {
            omega2: hoop.omega * hoop.omega,
            g_over_a: hoop.hoop.gravity / hoop.hoop.radius,
            series: RefCell::default(),
        }
    }
}

impl TaylorSystem for TaylorDrivenHoop {
    fn dim(&self) -> usize {
        2
    }

    fn coefficients(
        &self,
        _t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError> {
        let mut series = self.series.borrow_mut();
        let len = series.reserve(4, order);
        let (alpha, rest) = series.data.split_at_mut(len);
        let (v, rest) = rest.split_at_mut(len);
        let (s, c) = rest.split_at_mut(len);
        (alpha[0], v[0]) = (x0[0], x0[1]);
        (s[0], c[0]) = x0[0].sin_cos();
        for k in 0..order {
            if k > 0 {
                sin_cos_at(alpha, s, c, k);
            }
            let scale = 1.0 / (k + 1) as f64;
            alpha[k + 1] = v[k] * scale;
            v[k + 1] = (self.omega2 * cauchy(s, c, k) - self.g_over_a * s[k]) * scale;
        }
        for k in 0..=order {
            coeffs[2 * k] = alpha[k];
            coeffs[2 * k + 1] = v[k];
        }
        check_finite(coeffs, 2, order)
    }
}

/// `spinning-hoop`'s equations as a [`TaylorSystem`] on `(φ, α, φ̇, α̇)` (module doc).
#[derive(Debug)]
pub struct TaylorSpinningHoop {
    /// `m a²`, `M a²/2`, `g/a`.
    ma2: f64,
    diameter_moment: f64,
    g_over_a: f64,
    series: RefCell<Series>,
}

impl TaylorSpinningHoop {
    /// The Taylor system of `hoop`.
    #[must_use]
    pub fn new(hoop: &SpinningHoop) -> Self {
        let p = &hoop.hoop;
        Self {
            ma2: p.bead_mass * p.radius * p.radius,
            diameter_moment: p.diameter_moment(),
            g_over_a: p.gravity / p.radius,
            series: RefCell::default(),
        }
    }
}

impl TaylorSystem for TaylorSpinningHoop {
    fn dim(&self) -> usize {
        4
    }

    fn coefficients(
        &self,
        _t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError> {
        let mut series = self.series.borrow_mut();
        let len = series.reserve(11, order);
        let mut parts = series.data.chunks_exact_mut(len);
        let mut next = || parts.next().expect("eleven series were reserved");
        let (phi, alpha, wp, wa) = (next(), next(), next(), next());
        // sin α, cos α, P = sin α cos α, Q = Ma²/2 + m a² sin²α, N = P α̇, U = −2 m a² N φ̇ / Q,
        // W = φ̇².
        let (s, c, pc, q, n, u, w2) = (next(), next(), next(), next(), next(), next(), next());
        (phi[0], alpha[0], wp[0], wa[0]) = (x0[0], x0[1], x0[2], x0[3]);
        (s[0], c[0]) = x0[1].sin_cos();
        for k in 0..order {
            if k > 0 {
                sin_cos_at(alpha, s, c, k);
            }
            pc[k] = cauchy(s, c, k);
            q[k] = self.ma2 * cauchy(s, s, k) + if k == 0 { self.diameter_moment } else { 0.0 };
            n[k] = cauchy(pc, wa, k);
            let numerator = -2.0 * self.ma2 * cauchy(n, wp, k);
            let lower: f64 = (1..=k).map(|j| q[j] * u[k - j]).sum();
            u[k] = (numerator - lower) / q[0];
            let scale = 1.0 / (k + 1) as f64;
            phi[k + 1] = wp[k] * scale;
            alpha[k + 1] = wa[k] * scale;
            wp[k + 1] = u[k] * scale;
            w2[k] = cauchy(wp, wp, k);
            wa[k + 1] = (cauchy(pc, w2, k) - self.g_over_a * s[k]) * scale;
        }
        for k in 0..=order {
            coeffs[4 * k..4 * k + 4].copy_from_slice(&[phi[k], alpha[k], wp[k], wa[k]]);
        }
        check_finite(coeffs, 4, order)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::hoop::HoopParams;
    use crate::scenes::taylor_check::check;
    use nalgebra::SVector;
    use tumble_integrators::Ode;

    fn hoop() -> HoopParams {
        HoopParams::new(1.0, 0.2, 0.4, 9.81).unwrap()
    }

    #[test]
    fn driven_hoop_coefficients_follow_its_right_hand_side_and_flow() {
        let model = DrivenHoop::new(hoop(), 7.0).unwrap();
        let f = |y: &SVector<f64, 2>| {
            let mut dy = SVector::zeros();
            model.rhs(0.0, y, &mut dy);
            dy
        };
        check(
            &TaylorDrivenHoop::new(&model),
            f,
            SVector::from([0.7, -1.3]),
        );
    }

    #[test]
    fn spinning_hoop_coefficients_follow_its_right_hand_side_and_flow() {
        let model = SpinningHoop { hoop: hoop() };
        let f = |y: &SVector<f64, 4>| {
            let mut dy = SVector::zeros();
            model.rhs(0.0, y, &mut dy);
            dy
        };
        check(
            &TaylorSpinningHoop::new(&model),
            f,
            SVector::from([0.3, 2.1, 5.0, -0.8]),
        );
    }
}
