//! Variational Lie–Gauss methods: Lie-group variational integrators of any even order on
//! `SO(3) × ℝᴺ`, variational by construction rather than by composition.
//!
//! # The discrete Lagrangian
//!
//! Write the configuration near the start of a step in exponential coordinates centred there,
//! `R(t) = R_k exp(hat u(t))`, `u(0) = 0`. The body velocity is `Ω = J_r(u) u̇` with `J_r` the
//! right Jacobian of `exp` ([`tumble_kinematics::so3::dexp`]), so the Lagrangian in the chart is
//!
//! ```text
//! L̃(u, u̇, q, q̇) = L(R_k exp(hat u), J_r(u) u̇, q, q̇)
//! ```
//!
//! (`L = T − V` of [`crate::rigid::CoupledLagrangian`]; a [`RigidBody`] is the case `N = 0`).
//! In the chart the system is an ordinary Lagrangian system on a vector space, and its
//! `s`-stage Gauss–Legendre discrete Lagrangian (Marsden & West 2001, §2.6)
//!
//! ```text
//! F(u₁, q_k, q_{k+1}) = ext h Σᵢ bᵢ L̃(Uᵢ, U̇ᵢ, Qᵢ, Q̇ᵢ),   Uᵢ = h Σⱼ aᵢⱼ U̇ⱼ,  h Σ bⱼ U̇ⱼ = u₁, …
//! ```
//!
//! defines the discrete Lagrangian on the group `L_d(R_k, q_k, R_{k+1}, q_{k+1}) =
//! F(log(R_kᵀR_{k+1}), q_k, q_{k+1})`, where the chart's centre moves with the first argument.
//! It approximates the exact discrete Lagrangian to `O(h^{2s+1})`, so its discrete
//! Euler–Lagrange map has order `2s` (Marsden & West, Theorem 2.3.1); it is symplectic, and it
//! is symmetric. Because the chart is centred at `R_k`, `L_d` inherits every symmetry of `L`
//! under rotations of space: `L_d(QR_k, q_k, QR_{k+1}, q_{k+1}) = L_d(R_k, …)` whenever
//! `V(QR, q) = V(R, q)`, and the discrete Noether theorem conserves the matching component of
//! the spatial angular momentum `R Π` — all of it for a free body, `e₃ · R Π` for a top or a
//! hoop under gravity along `e₃`.
//!
//! # The one-step map
//!
//! The discrete Legendre transforms (left-trivialized: `R → R exp(hat η)`) are, with `P` the
//! chart momentum conjugate to `u`,
//!
//! ```text
//! Π_{k+1} = J_r(u₁)⁻ᵀ P₁,
//! Π_k     = J_r(u₁)⁻¹ P₁ − h Σᵢ bᵢ Eᵢ M(R_k Eᵢ, Qᵢ),        Eᵢ = exp(hat Uᵢ),
//! ```
//!
//! where the sum is the derivative of `F` with respect to the chart's centre (`M` the body-frame
//! moment of the potential) and `(u₁, P₁)` is the Gauss–Legendre step of the canonical
//! equations of `L̃` from `(0, P₀)`:
//!
//! ```text
//! u̇ = J_r(u)⁻¹ Ω,            Ṗ = (∂(J_r(u) w)/∂u)ᵀ Π + J_r(u)ᵀ M(R_k exp(hat u), q),  w = u̇,
//! q̇,                         ṗ = ∂T/∂q − ∂V/∂q,
//! Π = J_r(u)⁻ᵀ P,            (Ω, q̇) from (Π, p) by the Legendre transform at q.
//! ```
//!
//! The unknown is the chart's initial momentum `P₀` (close to `Π_k`, not equal to it), fixed
//! by the second transform, written `J_r(u₁)(Π_k + h Σ bᵢ Eᵢ Mᵢ) − P₁ = 0`. The stages and `P₀`
//! are solved together by simplified Newton: the matrix `𝟙 − hA ⊗ J` (`J` the Jacobian of the
//! chart equations by forward differences, `d = 6 + 2N`) is applied through the
//! eigendecomposition of the Gauss matrix `A`, one complex `d × d` inverse per conjugate pair
//! of eigenvalues, and `P₀` is eliminated by a 3 × 3 Schur complement that includes the
//! impulse's dependence on the stages (`∂(E M)/∂z`, by the same differences). `J` is taken at
//! the start of a step, then once more at the stages' mean after the first iteration; a step
//! that continues the last with the same `h` starts from the last step's matrix, and from the
//! last step's collocation polynomial continued to the new stage times and moved into the new
//! chart (an `O(h^{s+1})` guess, against `O(h²)` for an Euler start). Iteration runs until the
//! increment reaches round-off. Since `J_r(u)⁻ᵀ = exp(hat u)ᵀ J_r(u)⁻¹`, the update is
//! written `Π_{k+1} = E₁ᵀ (Π_k + h Σ bᵢ Eᵢ Mᵢ)`, `R_{k+1} = R_k E₁`: the spatial momentum
//! changes by exactly the quadrature of the spatial moments `h Σ bᵢ R_k Eᵢ Mᵢ`, whatever the
//! iteration left, and the increments of `R` and `Π` are summed with Kahan compensation.
//!
//! The derivative of the right Jacobian, `∂(J_r(u) w)/∂u`, is in closed form: with
//! `J_r(u) = 𝟙 − a(θ²) hat u + b(θ²) hat u²`, `a = (1 − cos θ)/θ²`, `b = (θ − sin θ)/θ³`,
//!
//! ```text
//! (∂(J_r w)/∂u)ᵀ Π = 2 (b′ (u × (u × w)) − a′ (u × w))·Π u − a w × Π + b (u × w) × Π − b w × (u × Π),
//! ```
//!
//! `a′`, `b′` the derivatives in `θ²` (series below `θ = 1`): the coefficients and both
//! derivatives live beside `dexp` in [`tumble_kinematics::so3::ExpCoefficients`].
//!
//! This is the construction of Bogfjellmo & Marthinsen (symplectic partitioned Runge–Kutta
//! methods in exponential coordinates lifted to `T*G`) for a Gauss–Legendre tableau, derived
//! here from the discrete Lagrangian.
//!
//! # Layout
//!
//! This module holds the steppers ([`LieGauss`], [`CoupledLieGauss`]); `solve` the step's
//! equations and their simplified Newton solution (broken into its start, one correction, the
//! update of the stages, a new linearization and the finish); `newton` the linear algebra of
//! `𝟙 − hA ⊗ J` through the eigenbasis of `A` and the carried collocation polynomial.
//!
//! # References
//! - J. E. Marsden, M. West, *Discrete mechanics and variational integrators*, Acta Numerica 10
//!   (2001) 357–514.
//! - G. Bogfjellmo, H. Marthinsen, *High-order symplectic partitioned Lie group methods*, Found.
//!   Comput. Math. 16 (2016) 493–530.
//! - J. Hall, M. Leok, *Lie group spectral variational integrators*, Found. Comput. Math. 17
//!   (2017) 199–257.
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., Springer
//!   2006, §VI.6 (variational integrators), §VIII.6 (implicit stages solved to round-off).
//! - E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, 2nd ed., Springer 1996,
//!   §IV.8 (simplified Newton through the eigenvalues of `A`).
use nalgebra::{Matrix3, SVector, Vector3};

mod newton;
mod solve;

use crate::error::{Error, check_step};
use crate::rigid::coupled::CoupledLagrangian;
use crate::rigid::problem::RigidBody;
use crate::rigid::state::{CoupledState, RigidBodyState, RigidCarry, compensated_add_all};
use crate::stepper::Stepper;
use crate::tables::GaussTableau;
use crate::tables::gauss::{GAUSS4, GAUSS6, GAUSS8, GAUSS10, GAUSS12};
use newton::Newton;
use solve::{Failure, Iteration, OnBody, OnCoupled, Start, solve};

/// Newton iterations allowed per step before [`Error::NoConvergence`].
pub const MAX_ITERATIONS: usize = 40;

/// The variational Lie–Gauss method with `S` stages (order `2S`) on a [`RigidBody`]
/// (module doc). Implements [`Stepper<B>`] on [`RigidBodyState`].
#[derive(Debug, Clone)]
pub struct LieGauss<const S: usize> {
    table: &'static GaussTableau<S>,
    max_iterations: usize,
    carry: RigidCarry,
    newton: Newton<S>,
    iterations: usize,
}

impl<const S: usize> LieGauss<S> {
    /// The method of a Gauss–Legendre tableau.
    #[must_use]
    pub fn new(table: &'static GaussTableau<S>) -> Self {
        Self {
            table,
            max_iterations: MAX_ITERATIONS,
            carry: RigidCarry::default(),
            newton: Newton::new(table, 0),
            iterations: 0,
        }
    }

    /// The same method allowing `n` Newton iterations per step.
    #[must_use]
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// The Newton iterations of the last step.
    #[must_use]
    pub fn last_iterations(&self) -> usize {
        self.iterations
    }
}

fn no_convergence(failure: Failure, t: f64, h: f64, state: Vec<f64>) -> Error {
    match failure {
        Failure::NoConvergence(iterations, increment) => Error::NoConvergence {
            t,
            h,
            iterations,
            increment,
            state,
        },
        Failure::Singular => Error::SingularMatrix { t, h, state },
    }
}

impl<B: RigidBody + ?Sized, const S: usize> Stepper<B> for LieGauss<S> {
    type State = RigidBodyState;

    fn step(
        &mut self,
        problem: &B,
        t: f64,
        state: &mut RigidBodyState,
        h: f64,
    ) -> Result<(), Error> {
        if !(h.is_finite() && h != 0.0) {
            return check_step(h);
        }
        let continues = self.carry.prepare(t, state);
        let none = SVector::<f64, 0>::zeros();
        let start = Start {
            r0: &state.rotation,
            pi0: &state.momentum,
            q0: &none,
            p0: &none,
            h,
        };
        let iteration = Iteration {
            max_iterations: self.max_iterations,
            reuse: continues,
        };
        let (inc, iterations) = solve(
            self.table,
            &mut self.newton,
            &OnBody(problem),
            &start,
            iteration,
        )
        .map_err(|f| no_convergence(f, t, h, crate::state::State::to_vec(state)))?;
        self.iterations = iterations;
        let d_rotation = state.rotation * inc.rotation;
        self.carry
            .apply_with(t + h, state, &d_rotation, |_| inc.momentum);
        Ok(())
    }

    fn reset(&mut self) {
        self.carry.reset();
        self.newton.forget();
    }
}

/// The variational Lie–Gauss method with `S` stages (order `2S`) on a body coupled to `N`
/// coordinates ([`CoupledLagrangian<N>`]; module doc). Implements [`Stepper<L>`] on
/// [`CoupledState<N>`].
#[derive(Debug, Clone)]
pub struct CoupledLieGauss<const S: usize, const N: usize> {
    table: &'static GaussTableau<S>,
    max_iterations: usize,
    newton: Newton<S>,
    carry_rotation: Matrix3<f64>,
    carry_momentum: Vector3<f64>,
    carry_q: SVector<f64, N>,
    carry_p: SVector<f64, N>,
    last: Option<(f64, CoupledState<N>)>,
    iterations: usize,
}

impl<const S: usize, const N: usize> CoupledLieGauss<S, N> {
    /// The method of a Gauss–Legendre tableau.
    #[must_use]
    pub fn new(table: &'static GaussTableau<S>) -> Self {
        Self {
            table,
            max_iterations: MAX_ITERATIONS,
            newton: Newton::new(table, N),
            carry_rotation: Matrix3::zeros(),
            carry_momentum: Vector3::zeros(),
            carry_q: SVector::zeros(),
            carry_p: SVector::zeros(),
            last: None,
            iterations: 0,
        }
    }

    /// The same method allowing `n` Newton iterations per step.
    #[must_use]
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// The Newton iterations of the last step.
    #[must_use]
    pub fn last_iterations(&self) -> usize {
        self.iterations
    }
}

impl<L: CoupledLagrangian<N> + ?Sized, const S: usize, const N: usize> Stepper<L>
    for CoupledLieGauss<S, N>
{
    type State = CoupledState<N>;

    fn step(
        &mut self,
        model: &L,
        t: f64,
        state: &mut CoupledState<N>,
        h: f64,
    ) -> Result<(), Error> {
        if !(h.is_finite() && h != 0.0) {
            return check_step(h);
        }
        let continues = self
            .last
            .as_ref()
            .is_some_and(|(t1, s1)| crate::state::same_time(*t1, t) && s1 == state);
        if !continues {
            self.carry_rotation = Matrix3::zeros();
            self.carry_momentum = Vector3::zeros();
            self.carry_q = SVector::zeros();
            self.carry_p = SVector::zeros();
        }
        let start = Start {
            r0: &state.rotation,
            pi0: &state.momentum,
            q0: &state.q,
            p0: &state.p,
            h,
        };
        let iteration = Iteration {
            max_iterations: self.max_iterations,
            reuse: continues,
        };
        let (inc, iterations) = solve(
            self.table,
            &mut self.newton,
            &OnCoupled(model),
            &start,
            iteration,
        )
        .map_err(|f| no_convergence(f, t, h, crate::state::State::to_vec(state)))?;
        self.iterations = iterations;
        let d_rotation = state.rotation * inc.rotation;
        compensated_add_all(&mut state.rotation, &d_rotation, &mut self.carry_rotation);
        compensated_add_all(&mut state.momentum, &inc.momentum, &mut self.carry_momentum);
        compensated_add_all(&mut state.q, &inc.q, &mut self.carry_q);
        compensated_add_all(&mut state.p, &inc.p, &mut self.carry_p);
        self.last = Some((t + h, *state));
        Ok(())
    }

    fn reset(&mut self) {
        self.last = None;
        self.newton.forget();
    }
}

/// `lie-gauss4`: 2 stages, order 4.
#[must_use]
pub fn lie_gauss4() -> LieGauss<2> {
    LieGauss::new(&GAUSS4)
}
/// `lie-gauss6`: 3 stages, order 6.
#[must_use]
pub fn lie_gauss6() -> LieGauss<3> {
    LieGauss::new(&GAUSS6)
}
/// `lie-gauss8`: 4 stages, order 8.
#[must_use]
pub fn lie_gauss8() -> LieGauss<4> {
    LieGauss::new(&GAUSS8)
}
/// `lie-gauss10`: 5 stages, order 10.
#[must_use]
pub fn lie_gauss10() -> LieGauss<5> {
    LieGauss::new(&GAUSS10)
}
/// 6 stages, order 12 (not registered: the registry lists `lie-gauss4` … `lie-gauss10`).
#[must_use]
pub fn lie_gauss12() -> LieGauss<6> {
    LieGauss::new(&GAUSS12)
}

#[cfg(test)]
mod tests {
    use super::*;
    use newton::same_step;

    /// The heavy top (`I = (1, 2, 3)`, `m g ℓ = 1.5`) and the start `(R₀, Π₀)` of the
    /// continuation tests.
    fn test_top() -> (crate::rigid::problem::HeavyTop, Matrix3<f64>, Vector3<f64>) {
        use crate::rigid::exact::FreeRigidBody;
        let body = FreeRigidBody::from_principal_moments(Vector3::new(1.0, 2.0, 3.0)).unwrap();
        let top =
            crate::rigid::problem::HeavyTop::new(body, 1.5, Vector3::new(0.1, -0.2, 0.5)).unwrap();
        let r0 = tumble_kinematics::so3::exp(&Vector3::new(0.3, -0.2, 0.4)).into_inner();
        (top, r0, Vector3::new(0.3, -1.0, 2.0))
    }

    /// One step of [`solve`] on a rigid body from `(R, Π)`: the new `(R, Π)` and the step's
    /// iterations.
    fn body_step<B: RigidBody, const S: usize>(
        table: &GaussTableau<S>,
        newton: &mut Newton<S>,
        body: &B,
        (r, pi): (&Matrix3<f64>, &Vector3<f64>),
        h: f64,
        reuse: bool,
    ) -> (Matrix3<f64>, Vector3<f64>, usize) {
        let none = SVector::<f64, 0>::zeros();
        let start = Start {
            r0: r,
            pi0: pi,
            q0: &none,
            p0: &none,
            h,
        };
        let iteration = Iteration {
            max_iterations: MAX_ITERATIONS,
            reuse,
        };
        let Ok((inc, iterations)) = solve(table, newton, &OnBody(body), &start, iteration) else {
            panic!("the step at h = {h} did not converge");
        };
        (r + r * inc.rotation, pi + inc.momentum, iterations)
    }

    /// A fixed-step run's step lengths `t_{k+1} − t_k` differ in their last bits: such a step
    /// still continues the last one — it keeps the last Newton matrix and starts from the
    /// carried polynomial — and costs exactly what a step of the same length does (iterations and
    /// model evaluations), less than a fresh start, which forms its matrix twice.
    #[test]
    fn a_step_whose_length_differs_by_rounding_continues_the_last() {
        use crate::rigid::exact::FreeRigidBody;
        use crate::rigid::problem::HeavyTop;
        use std::cell::Cell;
        struct Counting(HeavyTop, Cell<usize>);
        impl RigidBody for Counting {
            fn body(&self) -> &FreeRigidBody {
                self.0.body()
            }
            fn potential(&self, rotation: &Matrix3<f64>) -> f64 {
                self.0.potential(rotation)
            }
            fn torque(&self, rotation: &Matrix3<f64>) -> Vector3<f64> {
                self.1.set(self.1.get() + 1);
                self.0.torque(rotation)
            }
        }
        let (top, r0, pi0) = test_top();
        let top = Counting(top, Cell::new(0));
        let h = 0.2;
        // The iterations and the model evaluations of a second step of length `h2` after one
        // of `h`.
        let second = |h2: f64, reuse: bool| {
            let mut newton = Newton::<4>::new(&GAUSS8, 0);
            let (r1, pi1, _) = body_step(&GAUSS8, &mut newton, &top, (&r0, &pi0), h, false);
            top.1.set(0);
            let iterations = body_step(&GAUSS8, &mut newton, &top, (&r1, &pi1), h2, reuse).2;
            (iterations, top.1.get())
        };
        assert!(same_step(h, h * (1.0 + 1e-13)) && !same_step(h, h * 1.01));
        let exact = second(h, true);
        let rounded = second(h * (1.0 + 1e-13), true);
        let fresh = second(h, false);
        assert_eq!(
            rounded, exact,
            "(iterations, evaluations): rounded h, same h"
        );
        assert!(
            exact.1 < fresh.1,
            "evaluations: continued {exact:?}, fresh start {fresh:?}"
        );
    }

    /// The starting guess of a continuing step (the last step's collocation polynomial, moved
    /// into the new chart) differs from that step's solution by `O(h^{S+1})`: on a heavy top,
    /// halving `h` divides the difference by `2^{S+1}`.
    #[test]
    fn continued_collocation_polynomial_predicts_the_next_stages_to_order_s_plus_one() {
        use crate::rigid::problem::HeavyTop;
        type Start = (HeavyTop, Matrix3<f64>, Vector3<f64>);
        fn gap<const S: usize>(table: &GaussTableau<S>, (top, r0, pi0): &Start, h: f64) -> f64 {
            let mut newton = Newton::<S>::new(table, 0);
            let (r1, pi1, _) = body_step(table, &mut newton, top, (r0, pi0), h, false);
            let Some(p0_guess) = newton.predict(h, 3) else {
                panic!("no prediction after a step");
            };
            let guess = newton.z.clone();
            let _ = body_step(table, &mut newton, top, (&r1, &pi1), h, false);
            let p0 = Vector3::from_column_slice(&newton.last_origin[3..6]);
            guess
                .iter()
                .zip(&newton.last_z)
                .map(|(a, b)| (a - b).abs())
                .fold((p0_guess - p0).amax(), f64::max)
        }
        fn order<const S: usize>(table: &GaussTableau<S>, start: &Start) {
            let (coarse, fine) = (gap(table, start, 0.1), gap(table, start, 0.05));
            let observed = (coarse / fine).log2();
            assert!(
                (observed - (S + 1) as f64).abs() < 0.5,
                "S = {S}: gaps {coarse:e}, {fine:e}, order {observed}"
            );
        }
        let start = test_top();
        order(&GAUSS4, &start);
        order(&GAUSS6, &start);
        order(&GAUSS8, &start);
    }
}
