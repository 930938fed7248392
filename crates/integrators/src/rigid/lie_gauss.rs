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
//! `a′`, `b′` the derivatives in `θ²` (series below `θ = 1`).
//!
//! This is the construction of Bogfjellmo & Marthinsen (symplectic partitioned Runge–Kutta
//! methods in exponential coordinates lifted to `T*G`) for a Gauss–Legendre tableau, derived
//! here from the discrete Lagrangian.
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

use tumble_kinematics::so3::{dexp as dexp_right, dexpinv, exp_quat, hat, log_quat};

use crate::error::{Error, check_step};
use crate::rigid::coupled::{CoupledLagrangian, velocities_of};
use crate::rigid::problem::RigidBody;
use crate::rigid::state::{CoupledState, RigidBodyState, RigidCarry, compensated_add_all};
use crate::stepper::Stepper;
use crate::tables::GaussTableau;
use crate::tables::gauss::{GAUSS4, GAUSS6, GAUSS8, GAUSS10, GAUSS12};

/// Newton iterations allowed per step before [`Error::NoConvergence`].
pub const MAX_ITERATIONS: usize = 40;

/// `sin θ/θ`, `a = (1 − cos θ)/θ²`, `b = (θ − sin θ)/θ³`, `a′`, `b′` (derivatives in `θ²`) and
/// `c = (1 − (θ/2) cot(θ/2))/θ²`, the coefficient of `hat u²` in `J_r(u)⁻¹ = 𝟙 + ½ hat u + c hat u²`.
#[derive(Debug, Clone, Copy)]
struct Coefficients {
    sinc: f64,
    a: f64,
    b: f64,
    da: f64,
    db: f64,
    inv: f64,
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

impl Coefficients {
    /// `J_r(u) = 𝟙 − a hat u + b hat u²`, for the `u` these coefficients are of.
    fn right_jacobian(&self, u: &Vector3<f64>) -> Matrix3<f64> {
        let uh = hat(u);
        Matrix3::identity() - uh * self.a + uh * uh * self.b
    }

    /// At `t = θ²`: the Taylor series below `θ = 1` (no cancellation), closed forms above
    /// (their cancellations cost at most a few units in the 14th digit at `θ = 1`).
    fn new(t: f64) -> Self {
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

/// What a step needs of a model at a stage.
trait StageModel<const N: usize> {
    /// `(Ω, q̇, ∂T/∂q)` at `q` for momenta `(Π, p)`; `None` if the kinetic energy is singular.
    fn velocities(
        &self,
        q: &SVector<f64, N>,
        momentum: &Vector3<f64>,
        p: &SVector<f64, N>,
    ) -> Option<(Vector3<f64>, SVector<f64, N>, SVector<f64, N>)>;

    /// The body-frame moment `M(R, q)` and `∂V/∂q`.
    fn forces(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>);

    /// `true` when `V` is constant.
    fn force_free(&self) -> bool;
}

struct OnBody<'a, B: ?Sized>(&'a B);

impl<B: RigidBody + ?Sized> StageModel<0> for OnBody<'_, B> {
    fn velocities(
        &self,
        _q: &SVector<f64, 0>,
        momentum: &Vector3<f64>,
        _p: &SVector<f64, 0>,
    ) -> Option<(Vector3<f64>, SVector<f64, 0>, SVector<f64, 0>)> {
        Some((
            self.0.body().omega(momentum),
            SVector::zeros(),
            SVector::zeros(),
        ))
    }
    fn forces(
        &self,
        rotation: &Matrix3<f64>,
        _q: &SVector<f64, 0>,
    ) -> (Vector3<f64>, SVector<f64, 0>) {
        (self.0.torque(rotation), SVector::zeros())
    }
    fn force_free(&self) -> bool {
        self.0.is_torque_free()
    }
}

struct OnCoupled<'a, L: ?Sized>(&'a L);

impl<L: CoupledLagrangian<N> + ?Sized, const N: usize> StageModel<N> for OnCoupled<'_, L> {
    fn velocities(
        &self,
        q: &SVector<f64, N>,
        momentum: &Vector3<f64>,
        p: &SVector<f64, N>,
    ) -> Option<(Vector3<f64>, SVector<f64, N>, SVector<f64, N>)> {
        let jet = self.0.kinetic_jet(q);
        let (omega, qdot) = velocities_of(&jet.blocks, q, momentum, p).ok()?;
        let tq = jet.configuration_gradient(&omega, &qdot);
        Some((omega, qdot, tq))
    }
    fn forces(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>) {
        self.0.potential_derivatives(rotation, q)
    }
    fn force_free(&self) -> bool {
        false
    }
}

/// The rates of the chart's canonical equations at a stage: `(u̇, q̇, Ṗ, ṗ)`.
#[derive(Debug, Clone, Copy)]
struct Rates<const N: usize> {
    u: Vector3<f64>,
    q: SVector<f64, N>,
    pu: Vector3<f64>,
    p: SVector<f64, N>,
}

/// `(∂(J_r(u) w)/∂u)ᵀ Π` (module doc).
fn jacobian_derivative_transpose(
    co: &Coefficients,
    u: &Vector3<f64>,
    w: &Vector3<f64>,
    pi: &Vector3<f64>,
) -> Vector3<f64> {
    let uw = u.cross(w);
    let uuw = u.cross(&uw);
    let s = 2.0 * (co.db * uuw.dot(pi) - co.da * uw.dot(pi));
    u * s - w.cross(pi) * co.a + uw.cross(pi) * co.b - w.cross(&u.cross(pi)) * co.b
}

/// `∂(J_r(u) w)/∂u` (module doc).
fn jacobian_derivative(co: &Coefficients, u: &Vector3<f64>, w: &Vector3<f64>) -> Matrix3<f64> {
    let uw = u.cross(w);
    let uuw = u.cross(&uw);
    (uuw * (2.0 * co.db) - uw * (2.0 * co.da)) * u.transpose() + hat(w) * co.a
        - (hat(&uw) + hat(u) * hat(w)) * co.b
}

/// The rates at a stage `(u, q, P, p)` of a step from `R_k = r0`, and the stage's moment rotated
/// into the frame of `R_k` (`E M`).
fn rates<M: StageModel<N>, const N: usize>(
    model: &M,
    r0: &Matrix3<f64>,
    u: &Vector3<f64>,
    q: &SVector<f64, N>,
    pu: &Vector3<f64>,
    p: &SVector<f64, N>,
) -> Option<(Rates<N>, Vector3<f64>)> {
    let co = Coefficients::new(u.norm_squared());
    let uh = hat(u);
    let uh2 = uh * uh;
    let jr = Matrix3::identity() - uh * co.a + uh2 * co.b;
    let jr_inv = Matrix3::identity() + uh * 0.5 + uh2 * co.inv;
    let pi = jr_inv.transpose() * pu;
    let (omega, qdot, tq) = model.velocities(q, &pi, p)?;
    let w = jr_inv * omega;
    let mut dpu = jacobian_derivative_transpose(&co, u, &w, &pi);
    let mut dp = tq;
    let mut moment = Vector3::zeros();
    if !model.force_free() {
        let e = Matrix3::identity() + uh * co.sinc + uh2 * co.a;
        let (m, vq) = model.forces(&(r0 * e), q);
        dpu += jr.transpose() * m;
        dp -= vq;
        moment = e * m;
    }
    Some((
        Rates {
            u: w,
            q: qdot,
            pu: dpu,
            p: dp,
        },
        moment,
    ))
}

/// The result of a step: `E₁ − 𝟙`, `Π_{k+1} − Π_k`, `q_{k+1} − q_k`, `p_{k+1} − p_k`.
struct Increments<const N: usize> {
    rotation: Matrix3<f64>,
    momentum: Vector3<f64>,
    q: SVector<f64, N>,
    p: SVector<f64, N>,
}

/// Why a step failed: `(iterations, last increment)`, or a singular kinetic energy.
enum Failure {
    NoConvergence(usize, f64),
    Singular,
}

type C64 = nalgebra::Complex<f64>;

/// `W_u`, `W_P`, `W_ι`: how `u₁`, `P₁` and the impulse answer a change of `P₀` through the
/// stages, `h Σ bⱼ J₀[•, ·] Yⱼ` ([`solve`]).
#[derive(Debug, Clone, Copy)]
struct Responses {
    u: Matrix3<f64>,
    p: Matrix3<f64>,
    impulse: Matrix3<f64>,
}

/// Flat layout of a chart state or rate `(u, q, P, p)`: `d = 6 + 2N` entries.
fn pack<const N: usize>(r: &Rates<N>, out: &mut [f64]) {
    out[..3].copy_from_slice(r.u.as_slice());
    out[3..3 + N].copy_from_slice(r.q.as_slice());
    out[3 + N..6 + N].copy_from_slice(r.pu.as_slice());
    out[6 + N..6 + 2 * N].copy_from_slice(r.p.as_slice());
}

fn unpack<const N: usize>(x: &[f64]) -> Rates<N> {
    Rates {
        u: Vector3::from_column_slice(&x[..3]),
        q: SVector::from_column_slice(&x[3..3 + N]),
        pu: Vector3::from_column_slice(&x[3 + N..6 + N]),
        p: SVector::from_column_slice(&x[6 + N..6 + 2 * N]),
    }
}

/// The simplified Newton iteration's workspace: the eigendecomposition `A = T Λ T⁻¹` of the
/// tableau (formed once), the Jacobian `J₀` of the chart equations at the step's start, the
/// complex LU factors of `𝟙 − hλₖJ₀` (one `d × d` system per eigenvalue instead of one
/// `sd × sd` system), and `Y = (𝟙 − hA ⊗ J₀)⁻¹ E`, the stages' response to the initial chart
/// momentum `P₀`. Allocated when the stepper is built, never in a step.
#[derive(Debug, Clone)]
struct Newton<const S: usize> {
    d: usize,
    t: [[C64; S]; S],
    t_inv: [[C64; S]; S],
    lambda: [C64; S],
    /// 1 for a real eigenvalue, 2 for the first of a conjugate pair, 0 for the second.
    weight: [f64; S],
    /// `(h, W)` of the factorization held, kept for the next step when it continues.
    w: Option<(f64, Responses)>,
    jac: Vec<f64>,
    /// `G = ∂(E M)/∂z` (3 × d, row-major), the rotated moment's dependence on a stage, and the
    /// rotated moment at the state where `J` was formed.
    moment_jac: Vec<f64>,
    moment_base: Vector3<f64>,
    lu: Vec<C64>,
    pivots: Vec<usize>,
    /// `(𝟙 − hλₖJ)⁻¹`, row-major, real and imaginary parts apart (`S d²` each), formed from
    /// the LU factors: an iteration applies it as one matrix–vector product per eigenvalue,
    /// whose rows are independent, instead of two triangular solves, whose are not.
    inv_re: Vec<f64>,
    inv_im: Vec<f64>,
    /// `T⁻¹ g` of one eigenvalue, real and imaginary parts (`d` each).
    hat_re: Vec<f64>,
    hat_im: Vec<f64>,
    /// `Y`, `S d × 3`, stage-major.
    y: Vec<f64>,
    hat: Vec<C64>,
    /// Stage values, rates, residuals, increments (`S d` each), one flat state (`d`).
    z: Vec<f64>,
    k: Vec<f64>,
    g: Vec<f64>,
    dz: Vec<f64>,
    tmp: Vec<f64>,
    tmp2: Vec<f64>,
    tmp3: Vec<f64>,
    /// The start `z₀` (flat; its `P` block is `Π_k`, not the iterated `P₀`).
    origin: Vec<f64>,
    /// The last step's solution, for the next step's starting guess: its stage values and its
    /// start `z₀` with the solved `P₀` (flat, in the last step's chart), and `(h, u₁)`.
    last_z: Vec<f64>,
    last_origin: Vec<f64>,
    last: Option<(f64, Vector3<f64>)>,
    /// `ℓᵢⱼ`: the Lagrange basis of the nodes `0, c₁ … c_S` at `1 + cᵢ`, the last step's
    /// collocation polynomial carried into this step (`j = 0` the node 0, `j = m` the node `c_m`).
    extrapolation: [[f64; S]; S],
    extrapolation_origin: [f64; S],
    /// The same basis at `1`.
    end: [f64; S],
    end_origin: f64,
}

/// Whether a step of length `h` continues one of length `last` with the same step: equal to a
/// relative 1e-6. A fixed-step run takes `t_{k+1} − t_k` with `t_k = t₀ + k h`, whose rounding
/// moves the length by up to `ulp(t_k)` (relative `1e-10` at `t = 10⁴`, `h = 0.01`); the kept
/// Newton matrix and the carried polynomial are approximations far coarser than that.
fn same_step(last: f64, h: f64) -> bool {
    (h - last).abs() <= 1e-6 * h.abs()
}

/// The Lagrange basis polynomial of node `m` of `0, c₁ … c_S` (node 0 is `0`) at `x`.
fn lagrange<const S: usize>(c: &[f64; S], m: usize, x: f64) -> f64 {
    let node = |j: usize| if j == 0 { 0.0 } else { c[j - 1] };
    (0..=S)
        .filter(|&j| j != m)
        .map(|j| (x - node(j)) / (node(m) - node(j)))
        .product()
}

impl<const S: usize> Newton<S> {
    /// Drops what the next step would carry over from the last: its Newton matrix and its
    /// collocation polynomial.
    fn forget(&mut self) {
        self.w = None;
        self.last = None;
    }

    /// Starting stages for a step of length `h` that continues the last step with the same
    /// `h`: the last step's collocation polynomial (through its start and its stages) at
    /// `1 + cᵢ`, moved into this step's chart — `u` by `log(E₁ᵀ exp(hat u))`, the chart
    /// momentum through the body momentum `Π = J_r(u)⁻ᵀ P` it represents, `P' = J_r(u')ᵀ Π` —
    /// and returns the step's `P₀` guess, the body momentum of that polynomial at `1`. `None`
    /// (and nothing written) when there is no such last step.
    fn predict(&mut self, h: f64, pcol: usize) -> Option<Vector3<f64>> {
        let (h_last, u1) = self.last?;
        if !same_step(h_last, h) {
            return None;
        }
        let d = self.d;
        let back = exp_quat(&u1).inverse();
        let to_chart = |v: &mut [f64]| {
            let u_old = Vector3::new(v[0], v[1], v[2]);
            let p_old = Vector3::new(v[pcol], v[pcol + 1], v[pcol + 2]);
            let pi = dexpinv(&u_old).transpose() * p_old;
            let u_new = log_quat(&(back * exp_quat(&u_old)));
            let p_new = dexp_right(&u_new).transpose() * pi;
            v[..3].copy_from_slice(u_new.as_slice());
            v[pcol..pcol + 3].copy_from_slice(p_new.as_slice());
        };
        for i in 0..S {
            for c in 0..d {
                let mut acc = self.extrapolation_origin[i] * self.last_origin[c];
                for m in 0..S {
                    acc += self.extrapolation[i][m] * self.last_z[m * d + c];
                }
                self.z[i * d + c] = acc;
            }
            to_chart(&mut self.z[i * d..(i + 1) * d]);
        }
        // P₀: the polynomial's body momentum at 1 (in the new chart u = 0, where P = Π).
        let mut end = [0.0; 3];
        let mut u_end = [0.0; 3];
        for (b, (e, ue)) in end.iter_mut().zip(u_end.iter_mut()).enumerate() {
            *e = self.end_origin * self.last_origin[pcol + b];
            *ue = self.end_origin * self.last_origin[b];
            for m in 0..S {
                *e += self.end[m] * self.last_z[m * d + pcol + b];
                *ue += self.end[m] * self.last_z[m * d + b];
            }
        }
        Some(dexpinv(&Vector3::from(u_end)).transpose() * Vector3::from(end))
    }

    fn new(table: &GaussTableau<S>, n: usize) -> Self {
        let d = 6 + 2 * n;
        let a = faer::Mat::<f64>::from_fn(S, S, |i, j| table.a[i][j]);
        // The Gauss–Legendre matrices have S distinct eigenvalues (their reciprocals are the
        // roots of the Padé denominator), so A is diagonalizable. Complex eigenvalues come in
        // conjugate pairs; T is built with conjugate columns for each pair, so that for a real
        // right-hand side the solution of the conjugate system is the conjugate, and only one
        // system per pair is solved (`weight` 2, the other `weight` 0).
        let zero = C64::new(0.0, 0.0);
        let mut t = [[zero; S]; S];
        let mut lambda = [zero; S];
        let mut weight = [0.0; S];
        if let Ok(e) = a.eigen() {
            let mut col = 0;
            for k in 0..S {
                let l = e.S()[k];
                if l.im < -1e-12 || col >= S {
                    continue;
                }
                let complex = l.im > 1e-12;
                for i in 0..S {
                    t[i][col] = e.U()[(i, k)];
                }
                lambda[col] = l;
                weight[col] = if complex { 2.0 } else { 1.0 };
                col += 1;
                if complex && col < S {
                    for i in 0..S {
                        t[i][col] = e.U()[(i, k)].conj();
                    }
                    lambda[col] = l.conj();
                    col += 1;
                }
            }
        }
        let tm = nalgebra::DMatrix::<C64>::from_fn(S, S, |i, j| t[i][j]);
        let ti = tm
            .try_inverse()
            .unwrap_or_else(|| nalgebra::DMatrix::zeros(S, S));
        Self {
            d,
            t,
            t_inv: std::array::from_fn(|i| std::array::from_fn(|j| ti[(i, j)])),
            lambda,
            weight,
            w: None,
            jac: vec![0.0; d * d],
            moment_jac: vec![0.0; 3 * d],
            moment_base: Vector3::zeros(),
            lu: vec![C64::new(0.0, 0.0); S * d * d],
            pivots: vec![0; S * d],
            inv_re: vec![0.0; S * d * d],
            inv_im: vec![0.0; S * d * d],
            hat_re: vec![0.0; d],
            hat_im: vec![0.0; d],
            y: vec![0.0; S * d * 3],
            hat: vec![C64::new(0.0, 0.0); S * d],
            z: vec![0.0; S * d],
            k: vec![0.0; S * d],
            g: vec![0.0; S * d],
            dz: vec![0.0; S * d],
            tmp: vec![0.0; d],
            tmp2: vec![0.0; d],
            tmp3: vec![0.0; d],
            origin: vec![0.0; d],
            last_z: vec![0.0; S * d],
            last_origin: vec![0.0; d],
            last: None,
            extrapolation: std::array::from_fn(|i| {
                std::array::from_fn(|m| lagrange(&table.c, m + 1, 1.0 + table.c[i]))
            }),
            extrapolation_origin: std::array::from_fn(|i| lagrange(&table.c, 0, 1.0 + table.c[i])),
            end: std::array::from_fn(|m| lagrange(&table.c, m + 1, 1.0)),
            end_origin: lagrange(&table.c, 0, 1.0),
        }
    }

    /// Factors `𝟙 − hλₖJ₀` for every eigenvalue (partial pivoting) and forms its inverse from
    /// the factors; `false` if one is singular.
    fn factor(&mut self, h: f64) -> bool {
        let d = self.d;
        for k in 0..S {
            if self.weight[k] == 0.0 {
                continue;
            }
            let m = &mut self.lu[k * d * d..(k + 1) * d * d];
            let piv = &mut self.pivots[k * d..(k + 1) * d];
            let hl = self.lambda[k] * h;
            for i in 0..d {
                for j in 0..d {
                    let id = if i == j { 1.0 } else { 0.0 };
                    m[i * d + j] = C64::new(id, 0.0) - hl * self.jac[i * d + j];
                }
            }
            for col in 0..d {
                let mut p = col;
                for row in col + 1..d {
                    if m[row * d + col].l1_norm() > m[p * d + col].l1_norm() {
                        p = row;
                    }
                }
                piv[col] = p;
                if !(m[p * d + col].l1_norm() > 0.0) {
                    return false;
                }
                if p != col {
                    for j in 0..d {
                        m.swap(p * d + j, col * d + j);
                    }
                }
                let inv = C64::new(1.0, 0.0) / m[col * d + col];
                for row in col + 1..d {
                    let f = m[row * d + col] * inv;
                    m[row * d + col] = f;
                    for j in col + 1..d {
                        let v = m[col * d + j];
                        m[row * d + j] -= f * v;
                    }
                }
            }
            // Column e of the inverse: the permuted unit vector through both triangles.
            let x = &mut self.hat[k * d..(k + 1) * d];
            for e in 0..d {
                x.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
                x[e] = C64::new(1.0, 0.0);
                for col in 0..d {
                    x.swap(col, piv[col]);
                }
                for i in 0..d {
                    let mut acc = x[i];
                    for j in 0..i {
                        acc -= m[i * d + j] * x[j];
                    }
                    x[i] = acc;
                }
                for i in (0..d).rev() {
                    let mut acc = x[i];
                    for j in i + 1..d {
                        acc -= m[i * d + j] * x[j];
                    }
                    x[i] = acc / m[i * d + i];
                }
                for (i, v) in x.iter().enumerate() {
                    self.inv_re[k * d * d + i * d + e] = v.re;
                    self.inv_im[k * d * d + i * d + e] = v.im;
                }
            }
        }
        true
    }

    /// `Y = (𝟙 − hA ⊗ J₀)⁻¹ E`, `E` the unit vectors of the `P` block (`pcol …`) at every stage:
    /// `T⁻¹` maps such a column to `(Σᵢ (T⁻¹)ₖᵢ) e`, so `Y`'s column `c` is
    /// `Yⱼ = Σₖ wₖ Re(Tⱼₖ (Σᵢ (T⁻¹)ₖᵢ) (𝟙 − hλₖJ₀)⁻¹ e_{pcol + c})`, a column of each inverse.
    fn respond_to_momentum(&mut self, pcol: usize) {
        let d = self.d;
        self.y.iter_mut().for_each(|x| *x = 0.0);
        for k in 0..S {
            if self.weight[k] == 0.0 {
                continue;
            }
            let sum: C64 = self.t_inv[k].iter().sum();
            for c in 0..3 {
                for r in 0..d {
                    let at = k * d * d + r * d + pcol + c;
                    let x = sum * C64::new(self.inv_re[at], self.inv_im[at]);
                    for j in 0..S {
                        self.y[(j * d + r) * 3 + c] += self.weight[k] * (self.t[j][k] * x).re;
                    }
                }
            }
        }
    }

    /// `dz = (𝟙 − hA ⊗ J₀)⁻¹ g` (both `S d`, stage-major) through the eigenbasis of `A`:
    /// `dz_i = Σₖ wₖ Re(Tᵢₖ (𝟙 − hλₖJ₀)⁻¹ Σⱼ (T⁻¹)ₖⱼ gⱼ)`.
    fn apply_inverse(&mut self) {
        let d = self.d;
        self.dz.iter_mut().for_each(|x| *x = 0.0);
        for k in 0..S {
            if self.weight[k] == 0.0 {
                continue;
            }
            for c in 0..d {
                let (mut re, mut im) = (0.0, 0.0);
                for i in 0..S {
                    re += self.t_inv[k][i].re * self.g[i * d + c];
                    im += self.t_inv[k][i].im * self.g[i * d + c];
                }
                self.hat_re[c] = re;
                self.hat_im[c] = im;
            }
            let mr = &self.inv_re[k * d * d..(k + 1) * d * d];
            let mi = &self.inv_im[k * d * d..(k + 1) * d * d];
            for c in 0..d {
                let (rr, ri) = (&mr[c * d..(c + 1) * d], &mi[c * d..(c + 1) * d]);
                let (mut xr, mut xi) = (0.0, 0.0);
                for (((a, b), x), y) in rr.iter().zip(ri).zip(&self.hat_re).zip(&self.hat_im) {
                    xr += a * x - b * y;
                    xi += a * y + b * x;
                }
                let w = self.weight[k];
                for i in 0..S {
                    let t = self.t[i][k];
                    self.dz[i * d + c] += w * (t.re * xr - t.im * xi);
                }
            }
        }
    }
}

/// Forms `J = ∂F/∂z` and `G = ∂(E M)/∂z` at the chart state in `newton.tmp` (whose rates and
/// rotated moment are in `newton.tmp2` and `newton.moment_base`) by forward differences, each
/// coordinate stepped by √ε of its scale; inverts `𝟙 − hλₖJ`; forms `Y = (𝟙 − hA ⊗ J)⁻¹ E`
/// column by column; returns `W_u = h Σ bⱼ J[u, ·] Yⱼ`, `W_P = h Σ bⱼ J[P, ·] Yⱼ` and
/// `W_ι = h Σ bⱼ G Yⱼ`.
fn linearize<M: StageModel<N>, const S: usize, const N: usize>(
    table: &GaussTableau<S>,
    newton: &mut Newton<S>,
    model: &M,
    r0: &Matrix3<f64>,
    h: f64,
) -> Result<Responses, Failure> {
    let d = 6 + 2 * N;
    let pcol = 3 + N;
    let scale_p = (pcol..d)
        .map(|c| newton.tmp[c].abs())
        .fold(f64::MIN_POSITIVE, f64::max);
    for c in 0..d {
        let base = newton.tmp[c];
        let typical = if c < 3 {
            1.0
        } else if (3..pcol).contains(&c) {
            base.abs().max(1.0)
        } else {
            base.abs().max(scale_p)
        };
        let step = f64::EPSILON.sqrt() * typical;
        newton.tmp[c] = base + step;
        let z = unpack::<N>(&newton.tmp);
        newton.tmp[c] = base;
        let (kc, mc) = rates(model, r0, &z.u, &z.q, &z.pu, &z.p).ok_or(Failure::Singular)?;
        pack(&kc, &mut newton.tmp3);
        for r in 0..d {
            newton.jac[r * d + c] = (newton.tmp3[r] - newton.tmp2[r]) / step;
        }
        for r in 0..3 {
            newton.moment_jac[r * d + c] = (mc[r] - newton.moment_base[r]) / step;
        }
    }
    if !newton.factor(h) {
        return Err(Failure::Singular);
    }
    newton.respond_to_momentum(pcol);
    let mut w_u = Matrix3::zeros();
    let mut w_p = Matrix3::zeros();
    let mut w_i = Matrix3::zeros();
    for c in 0..3 {
        quadrature(table, &newton.y, h, 3, c, &mut newton.tmp3);
        w_u.set_column(c, &rows3(&newton.jac, 0, &newton.tmp3));
        w_p.set_column(c, &rows3(&newton.jac, pcol, &newton.tmp3));
        w_i.set_column(c, &rows3(&newton.moment_jac, 0, &newton.tmp3));
    }
    let responses = Responses {
        u: w_u,
        p: w_p,
        impulse: w_i,
    };
    newton.w = Some((h, responses));
    Ok(responses)
}

/// `out = h Σⱼ bⱼ xⱼ`, with `xⱼ` column `col` of a stage-major array of `stride` columns: the
/// quadrature of a stage correction, which the rows of the one simplified-Newton Jacobian map
/// to the corrections of `u₁`, `P₁` and the impulse (`h Σⱼ bⱼ J xⱼ = J h Σⱼ bⱼ xⱼ`).
fn quadrature<const S: usize>(
    table: &GaussTableau<S>,
    x: &[f64],
    h: f64,
    stride: usize,
    col: usize,
    out: &mut [f64],
) {
    let d = out.len();
    for (c, o) in out.iter_mut().enumerate() {
        let mut acc = 0.0;
        for j in 0..S {
            acc += table.b[j] * x[(j * d + c) * stride + col];
        }
        *o = h * acc;
    }
}

/// Rows `first … first + 2` of the row-major `rows × d` matrix `m` applied to `v`.
fn rows3(m: &[f64], first: usize, v: &[f64]) -> Vector3<f64> {
    let d = v.len();
    Vector3::from_fn(|r, _| {
        m[(first + r) * d..(first + r + 1) * d]
            .iter()
            .zip(v)
            .map(|(a, b)| a * b)
            .sum()
    })
}

/// One step of the `S`-stage method (module doc) from `(R_k, Π_k, q_k, p_k)`: simplified Newton
/// on the stage values `Zᵢ` and the initial chart momentum `P₀` together.
///
/// The unknowns are the stages `Z` and `P₀`; the equations are the stage equations
/// `G = Z − z₀(P₀) − h (A ⊗ 𝟙) F(Z) = 0` and the transform
/// `r = J_r(u₁)(Π_k + ι) − P₀ − h Σ bⱼ F_P(Zⱼ) = 0`, with `u₁ = h Σ bⱼ F_u(Zⱼ)` and the impulse
/// `ι = h Σ bⱼ Eⱼ M(R_k Eⱼ, Qⱼ)`. Newton's matrix is taken with one Jacobian `J₀ = ∂F/∂z` and
/// one `G₀ = ∂(E M)/∂z` for every stage (forward differences at the stages' mean). Eliminating
/// the stages, `ΔZ = X + Y ΔP₀` with `X = −(𝟙 − hA ⊗ J₀)⁻¹ G` and `Y = (𝟙 − hA ⊗ J₀)⁻¹ E`
/// (`E` the stages' dependence on `P₀`), leaves a 3 × 3 system
/// `(𝟙 − D W_u + W_P − J_r(u₁) W_ι) ΔP₀ = r + D v_u − v_P + J_r(u₁) v_ι`, where
/// `D = ∂(J_r(u₁) m)/∂u₁`, `W_• = h Σ bⱼ J₀[•, ·] Yⱼ` (`G₀` for `ι`) and `v_•` the same of `X`.
#[allow(clippy::too_many_arguments)]
fn solve<M: StageModel<N>, const S: usize, const N: usize>(
    table: &GaussTableau<S>,
    newton: &mut Newton<S>,
    model: &M,
    r0: &Matrix3<f64>,
    pi0: &Vector3<f64>,
    q0: &SVector<f64, N>,
    p0: &SVector<f64, N>,
    h: f64,
    max_iterations: usize,
    reuse: bool,
) -> Result<(Increments<N>, usize), Failure> {
    let d = 6 + 2 * N;
    let pcol = 3 + N;
    let zero = Vector3::zeros();
    let (k0, m0) = rates(model, r0, &zero, q0, pi0, p0).ok_or(Failure::Singular)?;
    newton.moment_base = m0;
    let z0 = Rates {
        u: zero,
        q: *q0,
        pu: *pi0,
        p: *p0,
    };
    pack(&z0, &mut newton.origin);
    pack(&k0, &mut newton.tmp2);
    newton.tmp.copy_from_slice(&newton.origin);
    // A step that continues the last one with the same h starts from the last step's
    // mid-step factorization (simplified Newton across steps); any other starts from J at z₀.
    let (mut w, reused) = match newton.w {
        Some((h_last, w)) if reuse && same_step(h_last, h) => (w, true),
        _ => (linearize(table, newton, model, r0, h)?, false),
    };
    // Linearizations after the start's (or the last step's kept matrix).
    let mut relinearized = 0u32;
    // Start: the last step's collocation polynomial continued, if this step continues it with
    // the same h; else Zᵢ = z₀ + cᵢ h F(z₀).
    let predicted = if reuse { newton.predict(h, pcol) } else { None };
    if predicted.is_none() {
        for i in 0..S {
            for c in 0..d {
                newton.z[i * d + c] = newton.origin[c] + table.c[i] * h * newton.tmp2[c];
            }
        }
    }
    newton.last = None;
    let mut chart_p0 = predicted.unwrap_or(*pi0);
    let mut moments = [Vector3::zeros(); S];
    let mut previous = f64::INFINITY;
    let mut iterations = 0;
    loop {
        iterations += 1;
        for i in 0..S {
            let z = unpack::<N>(&newton.z[i * d..(i + 1) * d]);
            let (ki, mi) = rates(model, r0, &z.u, &z.q, &z.pu, &z.p).ok_or(Failure::Singular)?;
            pack(&ki, &mut newton.k[i * d..(i + 1) * d]);
            moments[i] = mi;
        }
        let mut u1 = Vector3::zeros();
        let mut dpu = Vector3::zeros();
        let mut impulse = Vector3::zeros();
        for i in 0..S {
            let c = h * table.b[i];
            u1 += Vector3::from_column_slice(&newton.k[i * d..i * d + 3]) * c;
            dpu += Vector3::from_column_slice(&newton.k[i * d + pcol..i * d + pcol + 3]) * c;
            impulse += moments[i] * c;
        }
        // The transform as J_r(u₁)(Π_k + impulse) − P₁ = 0 (the same equation times J_r(u₁)),
        // whose derivatives in P₀ and the stages are simple.
        let m = pi0 + impulse;
        let co1 = Coefficients::new(u1.norm_squared());
        let jr1 = co1.right_jacobian(&u1);
        let r = jr1 * m - (chart_p0 + dpu);
        // −G = z₀ + h Σ aᵢⱼ Kⱼ − Zᵢ (z₀ with the current P₀).
        for i in 0..S {
            for c in 0..d {
                let start = if (pcol..pcol + 3).contains(&c) {
                    chart_p0[c - pcol]
                } else {
                    newton.origin[c]
                };
                let mut acc = start - newton.z[i * d + c];
                for j in 0..S {
                    acc += h * table.a[i][j] * newton.k[j * d + c];
                }
                newton.g[i * d + c] = acc;
            }
        }
        newton.apply_inverse();
        quadrature(table, &newton.dz, h, 1, 0, &mut newton.tmp3);
        let v_u = rows3(&newton.jac, 0, &newton.tmp3);
        let v_p = rows3(&newton.jac, pcol, &newton.tmp3);
        let v_i = rows3(&newton.moment_jac, 0, &newton.tmp3);
        let dm = jacobian_derivative(&co1, &u1, &m);
        let Some(schur) = (Matrix3::identity() - dm * w.u + w.p - jr1 * w.impulse).try_inverse()
        else {
            return Err(Failure::Singular);
        };
        let dp0 = schur * (r + dm * v_u - v_p + jr1 * v_i);
        // ΔZ = X + Y ΔP₀, measured block by block against the size of the block's values
        // (floors: the step's own scale, for blocks that are zero at the start).
        let mut change = [0.0f64; 4];
        let mut size = [0.0f64; 4];
        for i in 0..S {
            for c in 0..d {
                let x = i * d + c;
                let delta = newton.dz[x]
                    + newton.y[x * 3] * dp0[0]
                    + newton.y[x * 3 + 1] * dp0[1]
                    + newton.y[x * 3 + 2] * dp0[2];
                newton.z[x] += delta;
                let block = if c < 3 {
                    0
                } else if c < pcol {
                    1
                } else if c < pcol + 3 {
                    2
                } else {
                    3
                };
                change[block] = change[block].max(delta.abs());
                size[block] = size[block].max(newton.z[x].abs());
            }
        }
        chart_p0 += dp0;
        let floors = [
            h.abs() * k0.u.amax(),
            h.abs() * k0.q.amax(),
            pi0.amax(),
            h.abs() * k0.p.amax(),
        ];
        let mut measure = if dp0.amax() == 0.0 {
            0.0
        } else {
            dp0.amax() / pi0.amax().max(f64::MIN_POSITIVE)
        };
        for b in 0..4 {
            if change[b] > 0.0 {
                measure = measure.max(change[b] / size[b].max(floors[b]).max(f64::MIN_POSITIVE));
            }
        }
        if !measure.is_finite() {
            return Err(Failure::NoConvergence(iterations, measure));
        }
        // Round-off reached: the increment is at the last bits, or it stopped decreasing once
        // it was small (the iterates then wander within round-off of the solution). (A stop on
        // the contraction θ seen over two iterations, once θ·increment is below an ulp, saves
        // an iteration but leaves errors near 1e-13: the free body's energy then wanders to
        // 2e-14 over 2·10⁴ steps instead of 6e-16, and the order tests meet that floor.)
        if measure <= 2.0 * f64::EPSILON || (measure >= previous && previous <= 1e-10) {
            break;
        }
        // The contraction of the last iteration (0 at the first, which has no previous one).
        let theta = if previous.is_finite() {
            measure / previous
        } else {
            0.0
        };
        // Within a few ulps and barely contracting (long steps, where the simplified Newton
        // matrix is far from the stages' Jacobians): the iterates creep within round-off of
        // the solution, a few ulps a step; more iterations would not change them beyond that,
        // and without this stop such steps ran into the iteration limit at increments of 3 to 9 ε.
        if measure <= 16.0 * f64::EPSILON && theta > 0.5 {
            break;
        }
        if iterations >= max_iterations {
            return Err(Failure::NoConvergence(iterations, measure));
        }
        // A matrix formed at z₀ is replaced once the stages lie within O(h²) of the solution
        // (after the first iteration) by the Jacobian at their mean Σ bᵢ Zᵢ, the state near
        // mid-step: O(h²) from the average of the stages' Jacobians, against O(h) for the
        // start's. The last step's mid-step matrix is kept while it contracts 20-fold.
        // On a long step the stages move far from where the matrix was formed; while an
        // iteration contracts less than twofold the matrix is formed again at the stages'
        // mean, up to three times a step.
        let first = relinearized == 0
            && ((iterations == 1 && !reused)
                || (iterations >= 2 && theta > 0.05 && measure > 1e-9));
        if first || (relinearized < 3 && iterations >= 2 && theta > 0.5) {
            relinearized += 1;
            for c in 0..d {
                newton.tmp[c] = (0..S).map(|i| table.b[i] * newton.z[i * d + c]).sum();
            }
            let mid = unpack::<N>(&newton.tmp);
            let (km, mm) =
                rates(model, r0, &mid.u, &mid.q, &mid.pu, &mid.p).ok_or(Failure::Singular)?;
            pack(&km, &mut newton.tmp2);
            newton.moment_base = mm;
            w = linearize(table, newton, model, r0, h)?;
        }
        previous = measure;
    }
    let mut u1 = Vector3::zeros();
    let mut impulse = Vector3::zeros();
    let mut dq = SVector::<f64, N>::zeros();
    let mut dp = SVector::<f64, N>::zeros();
    for i in 0..S {
        let c = h * table.b[i];
        let ki = unpack::<N>(&newton.k[i * d..(i + 1) * d]);
        u1 += ki.u * c;
        impulse += moments[i] * c;
        dq += ki.q * c;
        dp += ki.p * c;
    }
    // Kept for the next step's starting guess.
    newton.last_z.copy_from_slice(&newton.z);
    newton.last_origin.copy_from_slice(&newton.origin);
    newton.last_origin[pcol..pcol + 3].copy_from_slice(chart_p0.as_slice());
    newton.last = Some((h, u1));
    // E₁ − 𝟙 from Rodrigues' formula (no rounding of 1 − O(θ²) on the diagonal).
    let co = Coefficients::new(u1.norm_squared());
    let uh = hat(&u1);
    let g = uh * co.sinc + uh * uh * co.a;
    // Π_{k+1} − Π_k = E₁ᵀ (Π_k + impulse) − Π_k = Gᵀ (Π_k + impulse) + impulse.
    let momentum = g.transpose() * (pi0 + impulse) + impulse;
    Ok((
        Increments {
            rotation: g,
            momentum,
            q: dq,
            p: dp,
        },
        iterations,
    ))
}

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
        let (inc, iterations) = solve(
            self.table,
            &mut self.newton,
            &OnBody(problem),
            &state.rotation,
            &state.momentum,
            &none,
            &none,
            h,
            self.max_iterations,
            continues,
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
        let (inc, iterations) = solve(
            self.table,
            &mut self.newton,
            &OnCoupled(model),
            &state.rotation,
            &state.momentum,
            &state.q,
            &state.p,
            h,
            self.max_iterations,
            continues,
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

/// The registered variational Lie–Gauss methods: name, stages. (Any [`GaussTableau`] gives a
/// method, e.g. `LieGauss::new(&GAUSS12)` of order 12, [`lie_gauss12`].)
pub const LIE_GAUSS_METHODS: [(&str, usize); 4] = [
    ("lie-gauss4", 2),
    ("lie-gauss6", 3),
    ("lie-gauss8", 4),
    ("lie-gauss10", 5),
];

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
/// 6 stages, order 12 (not registered: see [`LIE_GAUSS_METHODS`]).
#[must_use]
pub fn lie_gauss12() -> LieGauss<6> {
    LieGauss::new(&GAUSS12)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tumble_kinematics::so3::dexp;

    #[test]
    fn series_and_closed_forms_agree_at_the_switch_and_match_the_definitions() {
        for &theta in &[1e-3, 0.3, 0.999_999, 1.000_001, 1.5, 2.0, 2.5, 3.0] {
            let t: f64 = theta * theta;
            let co = Coefficients::new(t);
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
            let co = Coefficients::new(u.norm_squared());
            let analytic = jacobian_derivative_transpose(&co, &u, &w, &pi);
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
            let dm = jacobian_derivative(&co, &u, &w);
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

    #[test]
    fn eigenbasis_solve_equals_the_dense_solve_of_the_newton_matrix() {
        use crate::tables::gauss::{GAUSS6, GAUSS8, GAUSS10};
        fn check<const S: usize>(table: &GaussTableau<S>) {
            let mut newton = Newton::<S>::new(table, 1);
            let d = newton.d;
            // A Jacobian with rotation-like and dissipative parts.
            for r in 0..d {
                for c in 0..d {
                    newton.jac[r * d + c] = ((r * 7 + c * 3) % 11) as f64 / 5.0 - 1.0;
                }
            }
            let h = 0.3;
            assert!(newton.factor(h));
            for x in 0..S * d {
                newton.g[x] = ((x * 5) % 13) as f64 / 6.0 - 1.0;
            }
            newton.apply_inverse();
            let n = S * d;
            let m = nalgebra::DMatrix::<f64>::from_fn(n, n, |row, col| {
                let (i, a) = (row / d, row % d);
                let (j, b) = (col / d, col % d);
                let id = if row == col { 1.0 } else { 0.0 };
                id - h * table.a[i][j] * newton.jac[a * d + b]
            });
            let g = nalgebra::DVector::from_column_slice(&newton.g);
            let lu = m.lu();
            let x = lu.solve(&g).unwrap();
            let err = (0..n)
                .map(|k| (x[k] - newton.dz[k]).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-12 * x.amax(), "S = {S}: {err:e}");
            // The response to the P block, Y = (𝟙 − hA ⊗ J)⁻¹ E, column by column.
            let pcol = 4;
            newton.respond_to_momentum(pcol);
            for c in 0..3 {
                let e = nalgebra::DVector::from_fn(
                    n,
                    |row, _| {
                        if row % d == pcol + c { 1.0 } else { 0.0 }
                    },
                );
                let y = lu.solve(&e).unwrap();
                let err = (0..n)
                    .map(|k| (y[k] - newton.y[k * 3 + c]).abs())
                    .fold(0.0, f64::max);
                assert!(err < 1e-12 * y.amax(), "S = {S}, Y column {c}: {err:e}");
            }
        }
        check(&GAUSS6);
        check(&GAUSS8);
        check(&GAUSS10);
    }

    #[test]
    fn extrapolation_basis_reproduces_polynomials_of_degree_s() {
        fn check<const S: usize>(table: &GaussTableau<S>) {
            let newton = Newton::<S>::new(table, 0);
            // A polynomial of degree S with coefficients of both signs.
            let p = |x: f64| (0..=S).fold(0.0, |acc, k| acc * x + (0.37 * k as f64 - 0.5));
            let carried = |origin: f64, basis: &[f64; S], x: f64| {
                let v = origin * p(0.0) + (0..S).map(|m| basis[m] * p(table.c[m])).sum::<f64>();
                assert!(
                    (v - p(x)).abs() < 1e-12 * p(x).abs().max(1.0),
                    "S = {S} at {x}"
                );
            };
            for i in 0..S {
                carried(
                    newton.extrapolation_origin[i],
                    &newton.extrapolation[i],
                    1.0 + table.c[i],
                );
            }
            carried(newton.end_origin, &newton.end, 1.0);
        }
        check(&GAUSS4);
        check(&GAUSS6);
        check(&GAUSS8);
        check(&GAUSS10);
    }

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
        let Ok((inc, iterations)) = solve(
            table,
            newton,
            &OnBody(body),
            r,
            pi,
            &none,
            &none,
            h,
            MAX_ITERATIONS,
            reuse,
        ) else {
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
