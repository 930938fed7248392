//! The Lie-group variational integrator on the product `SO(3)ᴹ × ℝⁿ` ([`ProductLgvi`]) for a
//! Lagrangian `L(t, q, R₁ … R_M, q̇, ω₁ … ω_M)` given with its derivatives
//! ([`ProductLagrangian`]): several bodies whose kinetic energy couples their rotations (a
//! chain of bodies joined at pivots, where the inertia one body sees depends on the relative
//! rotations), so that no block of `T` is constant and the single body's form
//! `½ ΩᵀJ(q)Ω + ΩᵀB(q)q̇ + ½ q̇ᵀM(q)q̇` ([`crate::rigid::CoupledLagrangian`]) does not hold.
//! Nothing is asked of the Lagrangian's form: it may depend on time and have terms linear in
//! the velocities (a rotating frame), as long as `∂²L/∂v²` is invertible.
//!
//! # The discrete Lagrangian
//!
//! The velocities are left-trivialized, `v = (q̇, ω₁ … ω_M) ∈ ℝᴰ`, `D = n + 3M`, with `ωₖ` the
//! body angular velocity (`Ṙₖ = Rₖ ω̂ₖ`). A step goes from `g₀` to `g₁ = g₀ exp(hξ)`
//! (`q₁ = q₀ + h ξ_q`, `Rₖ₁ = Rₖ₀ exp(h ξ̂ₖ)`) with the trapezoidal discrete Lagrangian
//!
//! ```text
//! L_d(g₀, g₁) = (h/2) [L(t₀, g₀, ξ) + L(t₁, g₁, ξ)],   h ξ = log(g₀⁻¹ g₁),
//! ```
//!
//! (Marsden & West, *Discrete mechanics and variational integrators*, Acta Numerica 10 (2001)
//! 357–514, §2.7 for the trapezoidal rule; on a Lie group in exponential coordinates,
//! Bou-Rabee & Marsden, *Hamilton–Pontryagin integrators on Lie groups, Part I*, Found.
//! Comput. Math. 9 (2009) 197–219). With `p = ∂L/∂v`, `F` the left-trivialized derivative of `L` along the
//! configuration at fixed velocities (`∂L/∂qᵢ`, and `d/dε L(Rₖ exp(ε ê_a))|₀` along each
//! rotation), `P = ½ [p(t₀, g₀, ξ) + p(t₁, g₁, ξ)]`, and on each rotation block the inverse
//! right Jacobian `J_r⁻¹` of SO(3) ([`tumble_kinematics::so3::dexpinv`]; the identity on ℝⁿ),
//! the discrete Legendre transforms are
//!
//! ```text
//! μ₀ = J_r⁻¹(hξ) P − (h/2) F(t₀, g₀, ξ),     μ₁ = J_r⁻¹(−hξ) P + (h/2) F(t₁, g₁, ξ)
//! ```
//!
//! (varying `g₁ → g₁ exp(εη)` changes `hξ` by `J_r⁻¹(hξ) η`, varying `g₀` by `−J_l⁻¹(hξ) η`,
//! and `J_l⁻ᵀ = J_r⁻¹`, `J_r⁻ᵀ = J_r⁻¹(−·)` on SO(3)). A step solves the first for `ξ` by
//! Newton's method, with `μ₀` the momenta at the step's start, and the second gives `μ₁`.
//!
//! **Properties.** The map is symplectic (it is a variational integrator) and symmetric:
//! `L_d(g₀, g₁; h) = −L_d(g₁, g₀; −h)` (with `t₀` and `t₁` exchanged), so its order is even;
//! it is 2, the order to which `L_d` approximates the exact action (Marsden & West,
//! Theorem 2.3.1), and the map is a base of the symmetric compositions (`lgvi4` … `lgvi10`). Where `L` is invariant under
//! turning every rotation by the same `Q` (`Rₖ → Q Rₖ`), `L_d` is too, and the spatial
//! momentum `Σₖ Rₖ μₖ` is conserved exactly (discrete Noether theorem, Marsden & West §1.3.3):
//! for a free body, `R₁ μ₁ = R₀ exp(hξ̂) J_r⁻¹(−hξ) P = R₀ J_r⁻¹(hξ) P = R₀ μ₀`. Every rotation
//! moves by an exponential, so it stays orthogonal to round-off.
//!
//! # The state
//!
//! The stepper advances [`ProductState`]`<M, N>` with the vector part `(q, q̇, ω₁ … ω_M)`
//! (`N = 2n + 3M`), the velocities of the continuous Legendre transform: at each step's start
//! `μ₀ = p(t₀, g₀, v₀)`, and at its end `v₁` solves `p(t₁, g₁, v₁) = μ₁` (Newton's method with
//! the mass matrix; one iteration where `p` is affine in `v`, as for every mechanical
//! Lagrangian). The state is the same as the Lie-group Runge–Kutta methods' on a
//! [`crate::rigid::ProductVectorField`], so a model runs either.
//!
//! # The Newton matrix
//!
//! `∂/∂ξ` of the first equation is
//! `J_r⁻¹(hξ) · ½ [M₀ + M₁ + h K₁ E] − (h/2) diag(P̂ₖ) − (h/2) K₀ᵀ`, with `M = ∂²L/∂v²`,
//! `K = ∂p/∂η` (the momenta's left-trivialized configuration derivative, [`LagrangianJet::mixed`])
//! and `E = diag(𝟙, J_r(hξₖ))` (`∂g₁ = g₁ exp(h E ∂ξ)`); only the second-order terms of `J_r⁻¹`'s
//! own derivative are left out, so the iteration converges fast ([`ProductLgvi::iterations`]).
//! It runs until the increment is below `4ε` of each velocity block (the rates, each angular
//! velocity) or stops shrinking once below `1e-10` of it (round-off).

use faer::Mat;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::{Par, Spec};
use nalgebra::{Matrix3, SVector, Vector3};
use tumble_kinematics::so3::{dexp, dexpinv, exp, hat};

use crate::error::{Error, check_step};
use crate::rigid::product::ProductState;
use crate::state::State;
use crate::stepper::Stepper;

/// The Newton iterations a step may take before it fails with [`Error::NoConvergence`].
const MAX_NEWTON_ITERATIONS: usize = 30;

/// What a [`ProductLagrangian`] writes at a point `(t, g, v)`, for `D = n + 3M` velocities
/// `v = (q̇, ω₁ … ω_M)` and as many configuration directions `η = (δq, η₁ … η_M)`.
#[derive(Debug, Clone, PartialEq)]
pub struct LagrangianJet {
    /// The momenta `p = ∂L/∂v` (`D`).
    pub momenta: Vec<f64>,
    /// `F`, the derivative of `L` along the configuration at fixed velocities (`D`): `∂L/∂qᵢ`,
    /// then for each rotation `d/dε L(Rₖ exp(ε ê_a))|₀`, `a = 1, 2, 3`.
    pub force: Vec<f64>,
    /// The mass matrix `∂²L/∂v²` (`D × D`, row-major).
    pub mass: Vec<f64>,
    /// `∂p_b/∂η_a` in row `b` (the momentum), column `a` (the configuration direction, as in
    /// [`LagrangianJet::force`]), row-major.
    pub mixed: Vec<f64>,
}

impl LagrangianJet {
    /// A jet of `d` velocities, all zero.
    #[must_use]
    pub fn new(d: usize) -> Self {
        Self {
            momenta: vec![0.0; d],
            force: vec![0.0; d],
            mass: vec![0.0; d * d],
            mixed: vec![0.0; d * d],
        }
    }

    fn is_finite(&self) -> bool {
        self.momenta
            .iter()
            .chain(&self.force)
            .chain(&self.mass)
            .chain(&self.mixed)
            .all(|x| x.is_finite())
    }
}

/// A Lagrangian on `SO(3)ᴹ × ℝⁿ`, by its derivatives at a point (see the module doc), for
/// [`ProductLgvi`]. The state's vector part is `y = (q, q̇, ω₁ … ω_M)`, `N = 2n + 3M` numbers.
pub trait ProductLagrangian<const M: usize, const N: usize> {
    /// Writes the momenta, the configuration derivative, the mass matrix and the mixed
    /// derivative at `(t, R₁ … R_M, y)` into `out` (sized by [`LagrangianJet::new`] for
    /// `D = (N + 3M)/2`). Must not allocate: it is called several times a step.
    fn jet(
        &self,
        t: f64,
        rotations: &[Matrix3<f64>; M],
        y: &SVector<f64, N>,
        out: &mut LagrangianJet,
    );
}

impl<const M: usize, const N: usize, L: ProductLagrangian<M, N> + ?Sized> ProductLagrangian<M, N>
    for &L
{
    fn jet(
        &self,
        t: f64,
        rotations: &[Matrix3<f64>; M],
        y: &SVector<f64, N>,
        out: &mut LagrangianJet,
    ) {
        (**self).jet(t, rotations, y, out);
    }
}

/// The LGVI on `SO(3)ᴹ × ℝⁿ` (see the module doc): the trapezoidal discrete Lagrangian in
/// exponential coordinates, order 2, symmetric, symplectic; its workspace allocated once,
/// when it is built.
pub struct ProductLgvi<const M: usize, const N: usize> {
    max_iterations: usize,
    /// At `(t₀, g₀, ξ)` and at `(t₁, g₁, ξ)`.
    start: LagrangianJet,
    end: LagrangianJet,
    /// `μ₀`, then `μ₁`.
    mu: Vec<f64>,
    xi: Vec<f64>,
    /// `P = ½ (p₀ + p₁)`.
    average: Vec<f64>,
    /// Each velocity block's floor in the convergence test ([`Self::increment_size`]).
    floors: Vec<f64>,
    /// Newton iterations of the last step (its velocities' solve not counted).
    iterations: usize,
    matrix: Mat<f64>,
    rhs: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    buf: MemBuffer,
}

impl<const M: usize, const N: usize> std::fmt::Debug for ProductLgvi<M, N> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ProductLgvi")
            .field("max_iterations", &self.max_iterations)
            .finish_non_exhaustive()
    }
}

impl<const M: usize, const N: usize> Clone for ProductLgvi<M, N> {
    fn clone(&self) -> Self {
        Self::new().with_max_iterations(self.max_iterations)
    }
}

impl<const M: usize, const N: usize> Default for ProductLgvi<M, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const M: usize, const N: usize> ProductLgvi<M, N> {
    /// The scalar coordinates: `n = (N − 3M)/2`.
    const COORDINATES: usize = {
        assert!(N >= 3 * M && (N - 3 * M).is_multiple_of(2), "N = 2n + 3M");
        (N - 3 * M) / 2
    };
    /// The velocities: `D = n + 3M`.
    const VELOCITIES: usize = Self::COORDINATES + 3 * M;

    /// The stepper with its workspace.
    #[must_use]
    pub fn new() -> Self {
        let d = Self::VELOCITIES;
        let req = factor::lu_in_place_scratch::<usize, f64>(d, d, Par::Seq, Spec::default())
            .or(solve::solve_in_place_scratch::<usize, f64>(d, 1, Par::Seq));
        Self {
            max_iterations: MAX_NEWTON_ITERATIONS,
            start: LagrangianJet::new(d),
            end: LagrangianJet::new(d),
            mu: vec![0.0; d],
            xi: vec![0.0; d],
            average: vec![0.0; d],
            floors: vec![0.0; M + 1],
            iterations: 0,
            matrix: Mat::zeros(d, d),
            rhs: Mat::zeros(d, 1),
            perm: vec![0; d],
            perm_inv: vec![0; d],
            buf: MemBuffer::new(req),
        }
    }

    /// The same stepper with at most `n` Newton iterations a step (and as many for the
    /// velocities at its end) before [`Error::NoConvergence`].
    #[must_use]
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// The Newton iterations the last step took to solve for `ξ` (a diagnostic: about three
    /// where Newton's matrix is right, many more where it is not).
    #[must_use]
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// The end point `g₁ = g₀ exp(hξ)` with the velocities `ξ`: `(R₁, (q₁, ξ))`.
    fn end_point(
        &self,
        r0: &[Matrix3<f64>; M],
        y0: &SVector<f64, N>,
        h: f64,
    ) -> ([Matrix3<f64>; M], SVector<f64, N>) {
        let n = Self::COORDINATES;
        let mut y1 = *y0;
        for i in 0..n {
            y1[i] = y0[i] + h * self.xi[i];
        }
        y1.as_mut_slice()[n..].copy_from_slice(&self.xi);
        let r1 = std::array::from_fn(|k| r0[k] * exp(&(self.rotation_rate(k) * h)).into_inner());
        (r1, y1)
    }

    /// `ξₖ`, the body velocity of rotation `k`.
    fn rotation_rate(&self, k: usize) -> Vector3<f64> {
        Vector3::from_column_slice(&self.xi[Self::COORDINATES + 3 * k..][..3])
    }

    /// Evaluates the jets at `(t₀, g₀, ξ)` and `(t₁, g₁, ξ)`, and `P`; `None` when a jet is
    /// not finite.
    fn evaluate<L: ProductLagrangian<M, N> + ?Sized>(
        &mut self,
        problem: &L,
        t: f64,
        r0: &[Matrix3<f64>; M],
        y0: &SVector<f64, N>,
        h: f64,
    ) -> Option<([Matrix3<f64>; M], SVector<f64, N>)> {
        let n = Self::COORDINATES;
        let mut at0 = *y0;
        at0.as_mut_slice()[n..].copy_from_slice(&self.xi);
        problem.jet(t, r0, &at0, &mut self.start);
        let (r1, y1) = self.end_point(r0, y0, h);
        problem.jet(t + h, &r1, &y1, &mut self.end);
        for (p, (a, b)) in self
            .average
            .iter_mut()
            .zip(self.start.momenta.iter().zip(&self.end.momenta))
        {
            *p = 0.5 * (a + b);
        }
        (self.start.is_finite() && self.end.is_finite()).then_some((r1, y1))
    }

    /// `−(J_r⁻¹(hξ) P − (h/2) F₀ − μ₀)` into the right-hand side.
    fn residual(&mut self, h: f64) {
        let n = Self::COORDINATES;
        for i in 0..n {
            self.rhs[(i, 0)] = -(self.average[i] - 0.5 * h * self.start.force[i] - self.mu[i]);
        }
        for k in 0..M {
            let at = n + 3 * k;
            let b = dexpinv(&(self.rotation_rate(k) * h));
            let p = Vector3::from_column_slice(&self.average[at..at + 3]);
            let bp = b * p;
            for a in 0..3 {
                self.rhs[(at + a, 0)] =
                    -(bp[a] - 0.5 * h * self.start.force[at + a] - self.mu[at + a]);
            }
        }
    }

    /// Newton's matrix (see the module doc), factored in place. `false` when it is singular.
    fn factor_jacobian(&mut self, h: f64) -> bool {
        let (n, d) = (Self::COORDINATES, Self::VELOCITIES);
        // The columns' map E: the identity on ℝⁿ, J_r(hξₖ) on rotation k.
        let e: [Matrix3<f64>; M] = std::array::from_fn(|k| dexp(&(self.rotation_rate(k) * h)));
        let (s, end) = (&self.start, &self.end);
        // ½ [M₀ + M₁ + h K₁ E].
        for r in 0..d {
            for c in 0..d {
                let k1e = if c < n {
                    end.mixed[r * d + c]
                } else {
                    let (k, j) = ((c - n) / 3, (c - n) % 3);
                    let at = n + 3 * k;
                    (0..3)
                        .map(|a| end.mixed[r * d + at + a] * e[k][(a, j)])
                        .sum()
                };
                self.matrix[(r, c)] = 0.5 * (s.mass[r * d + c] + end.mass[r * d + c] + h * k1e);
            }
        }
        // The rows of each rotation block times J_r⁻¹(hξₖ), less (h/2) P̂ₖ.
        for k in 0..M {
            let at = n + 3 * k;
            let b = dexpinv(&(self.rotation_rate(k) * h));
            let ph = hat(&Vector3::from_column_slice(&self.average[at..at + 3])) * (0.5 * h);
            for c in 0..d {
                let col = Vector3::from_fn(|a, _| self.matrix[(at + a, c)]);
                let bc = b * col;
                for a in 0..3 {
                    let own = if (at..at + 3).contains(&c) {
                        ph[(a, c - at)]
                    } else {
                        0.0
                    };
                    self.matrix[(at + a, c)] = bc[a] - own;
                }
            }
        }
        // Less (h/2) K₀ᵀ.
        for r in 0..d {
            for c in 0..d {
                self.matrix[(r, c)] -= 0.5 * h * s.mixed[c * d + r];
            }
        }
        self.factor(d)
    }

    /// Factors `self.matrix` (`d × d`) in place; `false` when it is singular or not finite.
    fn factor(&mut self, d: usize) -> bool {
        let stack = MemStack::new(&mut self.buf);
        let _ = factor::lu_in_place(
            self.matrix.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            stack,
            Spec::default(),
        );
        (0..d).all(|k| {
            let p = self.matrix[(k, k)];
            p != 0.0 && p.is_finite()
        })
    }

    /// Solves with the factored matrix; the solution (an increment of the velocities)
    /// replaces the right-hand side.
    fn solve(&mut self) {
        let d = Self::VELOCITIES;
        let perm = PermRef::new_checked(&self.perm, &self.perm_inv, d);
        let stack = MemStack::new(&mut self.buf);
        solve::solve_in_place(
            self.matrix.as_ref(),
            self.matrix.as_ref(),
            perm,
            self.rhs.as_mut(),
            Par::Seq,
            stack,
        );
    }

    /// The largest `|x|` over `xs`, NaN when one is NaN.
    fn largest(xs: impl Iterator<Item = f64>) -> f64 {
        xs.fold(0.0f64, |m, x| {
            if x.abs() > m || x.is_nan() {
                x.abs()
            } else {
                m
            }
        })
    }

    /// The velocities' blocks: the rates (`0..n`) and each rotation's angular velocity.
    fn block(b: usize) -> std::ops::Range<usize> {
        let n = Self::COORDINATES;
        if b == 0 {
            0..n
        } else {
            n + 3 * (b - 1)..n + 3 * b
        }
    }

    /// The increment in the right-hand side relative to the velocities `v`, block by block
    /// ([`Self::block`]): each block against the larger of its own size and its floor, so that
    /// a slow block is solved to its own round-off, not to the fastest block's. The floors are
    /// set from the first increment of an iteration (`set_floors`), so that a block at rest
    /// (a body released from rest) is measured against the size of its first change. NaN when
    /// an entry is NaN.
    fn increment_size(&mut self, v: &[f64], set_floors: bool) -> f64 {
        let mut size = 0.0f64;
        for b in 0..=M {
            let range = Self::block(b);
            if range.is_empty() {
                continue;
            }
            let delta = Self::largest(range.clone().map(|i| self.rhs[(i, 0)]));
            let own = Self::largest(v[range].iter().copied());
            if set_floors {
                self.floors[b] = own.max(delta).max(f64::MIN_POSITIVE);
            }
            let relative = delta / own.max(self.floors[b]);
            if relative > size || relative.is_nan() {
                size = relative;
            }
        }
        size
    }
}

impl<const M: usize, const N: usize, L: ProductLagrangian<M, N> + ?Sized> Stepper<L>
    for ProductLgvi<M, N>
{
    type State = ProductState<M, N>;

    fn step(
        &mut self,
        problem: &L,
        t: f64,
        state: &mut ProductState<M, N>,
        h: f64,
    ) -> Result<(), Error> {
        if !(h.is_finite() && h != 0.0) {
            return check_step(h);
        }
        let (n, d) = (Self::COORDINATES, Self::VELOCITIES);
        let failure = |iterations: usize, increment: f64| Error::NoConvergence {
            t,
            h,
            iterations,
            increment,
            state: state.to_vec(),
        };
        let singular = || Error::SingularMatrix {
            t,
            h,
            state: state.to_vec(),
        };
        let r0 = state.rotations;
        let y0 = state.vector;
        // μ₀: the momenta at the step's start. The first guess of ξ is the velocity there.
        let non_finite = || Error::NonFinite {
            t,
            h,
            state: state.to_vec(),
        };
        problem.jet(t, &r0, &y0, &mut self.start);
        if !self.start.is_finite() {
            return Err(non_finite());
        }
        self.mu.copy_from_slice(&self.start.momenta);
        self.xi.copy_from_slice(&y0.as_slice()[n..]);
        let mut previous = f64::INFINITY;
        let mut converged = false;
        let mut iterations = 0;
        while iterations < self.max_iterations {
            iterations += 1;
            self.evaluate(problem, t, &r0, &y0, h)
                .ok_or_else(non_finite)?;
            self.residual(h);
            if !self.factor_jacobian(h) {
                return Err(singular());
            }
            self.solve();
            let xi = std::mem::take(&mut self.xi);
            let size = self.increment_size(&xi, iterations == 1);
            self.xi = xi;
            if !size.is_finite() {
                return Err(failure(iterations, size));
            }
            if size >= previous {
                // Stagnation at round-off: the iterate before this increment stands.
                converged = previous <= 1e-10;
                break;
            }
            for i in 0..d {
                self.xi[i] += self.rhs[(i, 0)];
            }
            previous = size;
            if size <= 4.0 * f64::EPSILON {
                converged = true;
                break;
            }
        }
        self.iterations = iterations;
        if !converged {
            return Err(failure(iterations, previous));
        }
        // μ₁ at the solution.
        let (r1, mut y1) = self
            .evaluate(problem, t, &r0, &y0, h)
            .ok_or_else(non_finite)?;
        for i in 0..n {
            self.mu[i] = self.average[i] + 0.5 * h * self.end.force[i];
        }
        for k in 0..M {
            let at = n + 3 * k;
            let b = dexpinv(&(self.rotation_rate(k) * -h));
            let bp = b * Vector3::from_column_slice(&self.average[at..at + 3]);
            for a in 0..3 {
                self.mu[at + a] = bp[a] + 0.5 * h * self.end.force[at + a];
            }
        }
        // The velocities at g₁: p(t₁, g₁, v₁) = μ₁, from v = ξ (where `end` was evaluated).
        let mut previous = f64::INFINITY;
        let mut converged = false;
        let mut solves = 0;
        while solves < self.max_iterations {
            solves += 1;
            for r in 0..d {
                self.rhs[(r, 0)] = self.mu[r] - self.end.momenta[r];
                for c in 0..d {
                    self.matrix[(r, c)] = self.end.mass[r * d + c];
                }
            }
            if !self.factor(d) {
                return Err(singular());
            }
            self.solve();
            let size = self.increment_size(&y1.as_slice()[n..], solves == 1);
            if !size.is_finite() {
                return Err(failure(solves, size));
            }
            if size >= previous {
                converged = previous <= 1e-10;
                break;
            }
            for i in 0..d {
                y1[n + i] += self.rhs[(i, 0)];
            }
            previous = size;
            if size <= 4.0 * f64::EPSILON {
                converged = true;
                break;
            }
            problem.jet(t + h, &r1, &y1, &mut self.end);
            if !self.end.is_finite() {
                return Err(non_finite());
            }
        }
        if !converged {
            return Err(failure(solves, previous));
        }
        state.rotations = r1;
        state.vector = y1;
        if !state.is_finite() {
            return Err(Error::NonFinite {
                t,
                h,
                state: State::to_vec(&ProductState {
                    rotations: r0,
                    vector: y0,
                }),
            });
        }
        Ok(())
    }
}
