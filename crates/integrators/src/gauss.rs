//! Gauss–Legendre collocation, `s = 1 … 6` stages, order `2s`.
//!
//! With `Zᵢ = Yᵢ − y₀` the stage equations are
//!
//! `Zᵢ = h Σⱼ a_ij f(t₀ + cⱼ h, y₀ + Zⱼ)`, and `y₁ = y₀ + h Σᵢ bᵢ f(t₀ + cᵢ h, y₀ + Zᵢ)`.
//!
//! Two stage solvers:
//!
//! - **Fixed-point iteration** `Z ← h (A ⊗ I) F(Z)`, iterated *until the increment stops
//!   decreasing* (Hairer's `gni_irk2` criterion) at round-off level (`≤ 10⁴ ε (‖y‖ + ‖Z‖)`):
//!   the iteration then sits at round-off, and no accuracy tolerance has to be chosen. (A
//!   non-monotone increment above that level is a slow contraction, and the iteration goes
//!   on.) Starting values come from the collocation polynomial of
//!   the previous step, `u(t₀ + θh) − y₀ = Σⱼ ℓⱼ(θ) Zⱼ` (Lagrange basis on `{0, c₁, …, c_s}`),
//!   extrapolated to the new stage times.
//! - **Simplified Newton** with `M = I − h A ⊗ J`, `J = ∂f/∂y(t₀, y₀)` (from the problem or by
//!   forward differences), factored once per step by faer's partial-pivoting LU, for
//!   problems where the fixed-point map does not contract (stiff or large `h L`).
//!
//! The update `y₁ = y₀ + δ` uses compensated summation with a carried error term, so that the
//! round-off error of long runs grows like `√n` (Brouwer's law) — the recipe of
//! Hairer–McLachlan–Razakarivony. Iterations that stop decreasing while the increment is
//! still large, or exhaust `max_iterations`, are an [`Error::NoConvergence`] carrying the
//! time and the state.
//!
//! Dense output ([`DenseOutput`]) is the last step's collocation polynomial
//! `u(t₀ + θh) = y₀ + Σⱼ ℓⱼ(θ) Zⱼ`, of order `s` (error `O(h^{s+1})` on the step), so events,
//! output at chosen times and the sweep metrics work with Gauss–Legendre as with DOP853.
//!
//! # References
//! - E. Hairer, R. I. McLachlan, A. Razakarivony, *Achieving Brouwer's law with implicit
//!   Runge–Kutta methods*, BIT 48 (2008) 231–243.
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, §VIII.6 (starting
//!   values, fixed-point versus Newton iteration).

use faer::Mat;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::{Par, Spec};

use crate::error::Error;
use crate::problem::Ode;
use crate::state::{State, VectorState, compensated_add, copy_into, max_abs, same_time};
use crate::stepper::{DenseOutput, Stepper};
use crate::tables::GaussTableau;
use crate::tables::gauss::{GAUSS2, GAUSS4, GAUSS6, GAUSS8, GAUSS10, GAUSS12};

/// How the stage equations are solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StageSolver {
    /// Fixed-point iteration until the increment stops decreasing at round-off level.
    FixedPoint,
    /// Simplified Newton with a faer LU of `I − h A ⊗ J`.
    Newton,
}

/// A Gauss–Legendre method: table, stage solver, iteration limit, compensated summation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gauss<const S: usize> {
    /// The collocation table.
    pub table: &'static GaussTableau<S>,
    /// Stage solver.
    pub solver: StageSolver,
    /// Upper bound on the iterations of one step.
    pub max_iterations: usize,
    /// Compensated summation of the update (on by default).
    pub compensated: bool,
}

impl<const S: usize> Gauss<S> {
    /// The method of `table` with fixed-point iteration and compensated summation.
    #[must_use]
    pub const fn new(table: &'static GaussTableau<S>) -> Self {
        Self {
            table,
            solver: StageSolver::FixedPoint,
            max_iterations: 100,
            compensated: true,
        }
    }
    /// Same method, stages solved by simplified Newton.
    #[must_use]
    pub const fn with_newton(mut self) -> Self {
        self.solver = StageSolver::Newton;
        self
    }
    /// Same method, update summed without compensation (to show the difference).
    #[must_use]
    pub const fn uncompensated(mut self) -> Self {
        self.compensated = false;
        self
    }

    /// Builds the per-run stepper for states shaped like `y0` (allocates once).
    #[must_use]
    pub fn stepper<Y: VectorState>(&self, y0: &Y) -> GaussStepper<S, Y> {
        let n = y0.dim();
        let newton = (self.solver == StageSolver::Newton).then(|| NewtonWork::new(n, S));
        GaussStepper {
            method: *self,
            z: std::array::from_fn(|_| y0.zeros_like()),
            znew: std::array::from_fn(|_| y0.zeros_like()),
            f: std::array::from_fn(|_| y0.zeros_like()),
            ytmp: y0.zeros_like(),
            f0: y0.zeros_like(),
            carry: y0.zeros_like(),
            last: y0.zeros_like(),
            start: y0.zeros_like(),
            t_start: f64::NAN,
            t_last: f64::NAN,
            h_last: 0.0,
            have_last: false,
            newton,
            iterations: 0,
        }
    }
}

/// Gauss–Legendre, 1 stage (implicit midpoint rule), order 2.
pub const fn gauss2() -> Gauss<1> {
    Gauss::new(&GAUSS2)
}
/// Gauss–Legendre, 2 stages, order 4.
pub const fn gauss4() -> Gauss<2> {
    Gauss::new(&GAUSS4)
}
/// Gauss–Legendre, 3 stages, order 6.
pub const fn gauss6() -> Gauss<3> {
    Gauss::new(&GAUSS6)
}
/// Gauss–Legendre, 4 stages, order 8.
pub const fn gauss8() -> Gauss<4> {
    Gauss::new(&GAUSS8)
}
/// Gauss–Legendre, 5 stages, order 10.
pub const fn gauss10() -> Gauss<5> {
    Gauss::new(&GAUSS10)
}
/// Gauss–Legendre, 6 stages, order 12.
pub const fn gauss12() -> Gauss<6> {
    Gauss::new(&GAUSS12)
}

/// Dense workspace of the simplified Newton iteration.
struct NewtonWork {
    n: usize,
    jac: Vec<f64>,
    m: Mat<f64>,
    rhs: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    buf: MemBuffer,
}

impl std::fmt::Debug for NewtonWork {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NewtonWork")
            .field("n", &self.n)
            .finish_non_exhaustive()
    }
}

impl Clone for NewtonWork {
    fn clone(&self) -> Self {
        Self::new(self.n, self.m.nrows() / self.n.max(1))
    }
}

impl NewtonWork {
    fn new(n: usize, s: usize) -> Self {
        let big = n * s;
        let req =
            factor::lu_in_place_scratch::<usize, f64>(big, big, Par::Seq, Spec::default()).or(
                solve::solve_in_place_scratch::<usize, f64>(big, 1, Par::Seq),
            );
        Self {
            n,
            jac: vec![0.0; n * n],
            m: Mat::zeros(big, big),
            rhs: Mat::zeros(big, 1),
            perm: vec![0; big],
            perm_inv: vec![0; big],
            buf: MemBuffer::new(req),
        }
    }
}

/// Workspace of one run of a Gauss–Legendre method.
#[derive(Debug, Clone)]
pub struct GaussStepper<const S: usize, Y> {
    method: Gauss<S>,
    z: [Y; S],
    znew: [Y; S],
    f: [Y; S],
    ytmp: Y,
    f0: Y,
    carry: Y,
    last: Y,
    /// The state at the start of the last step (the collocation polynomial's `u(t₀)`).
    start: Y,
    t_start: f64,
    t_last: f64,
    h_last: f64,
    have_last: bool,
    newton: Option<NewtonWork>,
    iterations: usize,
}

/// Lagrange basis polynomial `ℓⱼ` (j = 1..s) on the nodes `{0, c₁, …, c_s}` at `θ`.
fn lagrange<const S: usize>(c: &[f64; S], j: usize, theta: f64) -> f64 {
    let cj = c[j];
    let mut v = theta / cj; // the node 0
    for (k, &ck) in c.iter().enumerate() {
        if k != j {
            v *= (theta - ck) / (cj - ck);
        }
    }
    v
}

impl<const S: usize, Y: VectorState> GaussStepper<S, Y> {
    /// Iterations used by the last step.
    pub fn last_iterations(&self) -> usize {
        self.iterations
    }

    /// `F_j = f(t + c_j h, y + Z_j)` for all stages.
    fn eval_stages<P: Ode<Y> + ?Sized>(&mut self, problem: &P, t: f64, y: &Y, h: f64) {
        let c = &self.method.table.c;
        for j in 0..S {
            copy_into(&mut self.ytmp, y);
            for (o, zj) in self
                .ytmp
                .as_mut_slice()
                .iter_mut()
                .zip(self.z[j].as_slice())
            {
                *o += zj;
            }
            problem.rhs(t + c[j] * h, &self.ytmp, &mut self.f[j]);
        }
    }

    /// Starting values: extrapolated collocation polynomial, or `Zᵢ = cᵢ h f(t, y)`.
    fn starting_values<P: Ode<Y> + ?Sized>(
        &mut self,
        problem: &P,
        t: f64,
        y: &Y,
        h: f64,
        continuing: bool,
    ) {
        let c = self.method.table.c;
        if continuing && self.h_last != 0.0 {
            let r = h / self.h_last;
            for i in 0..S {
                let theta = 1.0 + r * c[i];
                let zi = self.znew[i].as_mut_slice();
                zi.fill(0.0);
                for j in 0..S {
                    let w = lagrange(&c, j, theta) - lagrange(&c, j, 1.0);
                    for (o, zj) in zi.iter_mut().zip(self.z[j].as_slice()) {
                        *o += w * zj;
                    }
                }
            }
            std::mem::swap(&mut self.z, &mut self.znew);
        } else {
            problem.rhs(t, y, &mut self.f0);
            for i in 0..S {
                let s = c[i] * h;
                for (o, f) in self.z[i].as_mut_slice().iter_mut().zip(self.f0.as_slice()) {
                    *o = s * f;
                }
            }
        }
    }

    fn scale(&self, y: &Y) -> f64 {
        let mut zmax = 0.0_f64;
        for z in &self.z {
            zmax = zmax.max(max_abs(z.as_slice()));
        }
        max_abs(y.as_slice()) + zmax
    }

    /// Decides after an iteration with increment `dyno` (previous `prev`, smallest so far
    /// `best`): `Some(true)` converged, `Some(false)` failed, `None` go on.
    ///
    /// Converged when the increment is zero, or stops decreasing at round-off level
    /// (`≤ 10⁴ ε (‖y‖ + ‖Z‖)`). An increment that stops decreasing above that level is a
    /// non-monotone phase of a slow contraction, and the iteration goes on; one that grows
    /// a million-fold above the best seen (or is not finite) diverges.
    fn verdict(&self, dyno: f64, prev: f64, best: f64, y: &Y) -> Option<bool> {
        if dyno == 0.0 {
            return Some(true);
        }
        if !dyno.is_finite() || dyno > 1e6 * best {
            return Some(false);
        }
        if dyno >= prev && dyno <= 1e4 * f64::EPSILON * self.scale(y) {
            return Some(true);
        }
        None
    }

    fn fixed_point<P: Ode<Y> + ?Sized>(
        &mut self,
        problem: &P,
        t: f64,
        y: &Y,
        h: f64,
    ) -> Result<(), Error> {
        let a = &self.method.table.a;
        let mut prev = f64::INFINITY;
        let mut best = f64::INFINITY;
        for iter in 1..=self.method.max_iterations {
            self.iterations = iter;
            self.eval_stages(problem, t, y, h);
            let mut dyno = 0.0_f64;
            for i in 0..S {
                let zi = self.znew[i].as_mut_slice();
                zi.fill(0.0);
                for j in 0..S {
                    let ha = h * a[i][j];
                    for (o, fj) in zi.iter_mut().zip(self.f[j].as_slice()) {
                        *o += ha * fj;
                    }
                }
                for (zn, zo) in zi.iter().zip(self.z[i].as_slice()) {
                    dyno = dyno.max((zn - zo).abs());
                }
            }
            std::mem::swap(&mut self.z, &mut self.znew);
            match self.verdict(dyno, prev, best, y) {
                Some(true) => return Ok(()),
                Some(false) => return Err(no_convergence(t, h, iter, dyno, y)),
                None => {
                    prev = dyno;
                    best = best.min(dyno);
                }
            }
        }
        Err(no_convergence(t, h, self.method.max_iterations, prev, y))
    }

    fn jacobian<P: Ode<Y> + ?Sized>(&mut self, problem: &P, t: f64, y: &Y) {
        let work = self
            .newton
            .as_mut()
            .expect("Newton workspace exists for the Newton solver");
        let n = work.n;
        if problem.jacobian(t, y, &mut work.jac) {
            return;
        }
        // Forward differences, column by column.
        problem.rhs(t, y, &mut self.f0);
        copy_into(&mut self.ytmp, y);
        for col in 0..n {
            let yc = y.as_slice()[col];
            let delta = f64::EPSILON.sqrt() * yc.abs().max(1e-5);
            self.ytmp.as_mut_slice()[col] = yc + delta;
            let dx = self.ytmp.as_slice()[col] - yc;
            problem.rhs(t, &self.ytmp, &mut self.znew[0]);
            for row in 0..n {
                work.jac[row * n + col] =
                    (self.znew[0].as_slice()[row] - self.f0.as_slice()[row]) / dx;
            }
            self.ytmp.as_mut_slice()[col] = yc;
        }
    }

    fn newton<P: Ode<Y> + ?Sized>(
        &mut self,
        problem: &P,
        t: f64,
        y: &Y,
        h: f64,
    ) -> Result<(), Error> {
        self.jacobian(problem, t, y);
        let a = self.method.table.a;
        {
            let work = self.newton.as_mut().expect("Newton workspace");
            let n = work.n;
            for i in 0..S {
                for j in 0..S {
                    let ha = h * a[i][j];
                    for r in 0..n {
                        for c in 0..n {
                            let id = if i == j && r == c { 1.0 } else { 0.0 };
                            work.m[(i * n + r, j * n + c)] = id - ha * work.jac[r * n + c];
                        }
                    }
                }
            }
            let stack = MemStack::new(&mut work.buf);
            let _ = factor::lu_in_place(
                work.m.as_mut(),
                &mut work.perm,
                &mut work.perm_inv,
                Par::Seq,
                stack,
                Spec::default(),
            );
            let singular = (0..n * S).any(|k| {
                let d = work.m[(k, k)];
                d == 0.0 || !d.is_finite()
            });
            if singular {
                return Err(Error::SingularMatrix {
                    t,
                    h,
                    state: y.to_vec(),
                });
            }
        }
        let mut prev = f64::INFINITY;
        let mut best = f64::INFINITY;
        for iter in 1..=self.method.max_iterations {
            self.iterations = iter;
            self.eval_stages(problem, t, y, h);
            let work = self.newton.as_mut().expect("Newton workspace");
            let n = work.n;
            // rhs = −G(Z) = −(Zᵢ − h Σⱼ a_ij Fⱼ)
            for i in 0..S {
                for r in 0..n {
                    let mut g = self.z[i].as_slice()[r];
                    for j in 0..S {
                        g -= h * a[i][j] * self.f[j].as_slice()[r];
                    }
                    work.rhs[(i * n + r, 0)] = -g;
                }
            }
            let perm = PermRef::new_checked(&work.perm, &work.perm_inv, n * S);
            let stack = MemStack::new(&mut work.buf);
            solve::solve_in_place(
                work.m.as_ref(),
                work.m.as_ref(),
                perm,
                work.rhs.as_mut(),
                Par::Seq,
                stack,
            );
            let mut dyno = 0.0_f64;
            for i in 0..S {
                for (r, z) in self.z[i].as_mut_slice().iter_mut().enumerate() {
                    let dz = work.rhs[(i * n + r, 0)];
                    *z += dz;
                    dyno = dyno.max(dz.abs());
                }
            }
            match self.verdict(dyno, prev, best, y) {
                Some(true) => return Ok(()),
                Some(false) => return Err(no_convergence(t, h, iter, dyno, y)),
                None => {
                    prev = dyno;
                    best = best.min(dyno);
                }
            }
        }
        Err(no_convergence(t, h, self.method.max_iterations, prev, y))
    }
}

fn no_convergence<Y: State>(t: f64, h: f64, iterations: usize, increment: f64, y: &Y) -> Error {
    Error::NoConvergence {
        t,
        h,
        iterations,
        increment,
        state: y.to_vec(),
    }
}

impl<const S: usize, Y: VectorState, P: Ode<Y> + ?Sized> Stepper<P> for GaussStepper<S, Y> {
    type State = Y;

    fn step(&mut self, problem: &P, t: f64, state: &mut Y, h: f64) -> Result<(), Error> {
        let continuing =
            self.have_last && same_time(t, self.t_last) && state.as_slice() == self.last.as_slice();
        if !continuing {
            self.carry.as_mut_slice().fill(0.0);
        }
        self.starting_values(problem, t, state, h, continuing);
        copy_into(&mut self.start, state);
        let solved = match self.method.solver {
            StageSolver::FixedPoint => self.fixed_point(problem, t, state, h),
            StageSolver::Newton => self.newton(problem, t, state, h),
        };
        if let Err(e) = solved {
            self.have_last = false;
            return Err(e);
        }
        // y₁ = y₀ + h Σ bᵢ Fᵢ, with the F of the last iteration.
        let b = &self.method.table.b;
        let compensated = self.method.compensated;
        let n = state.dim();
        for r in 0..n {
            let mut delta = 0.0;
            for i in 0..S {
                delta += b[i] * self.f[i].as_slice()[r];
            }
            delta *= h;
            let yr = &mut state.as_mut_slice()[r];
            if compensated {
                compensated_add(yr, delta, &mut self.carry.as_mut_slice()[r]);
            } else {
                *yr += delta;
            }
        }
        copy_into(&mut self.last, state);
        self.t_start = t;
        self.t_last = t + h;
        self.h_last = h;
        self.have_last = true;
        Ok(())
    }

    fn reset(&mut self) {
        self.have_last = false;
        self.t_last = f64::NAN;
    }
}

/// The collocation polynomial of the last step: `u(t₀ + θh) = y₀ + Σⱼ ℓⱼ(θ) Zⱼ` with `ℓⱼ` the
/// Lagrange basis on the nodes `{0, c₁, …, c_s}` (`u(cⱼ) = y₀ + Zⱼ`, the stage values). Its
/// error is `O(h^{s+1})` uniformly on the step (Hairer, Nørsett & Wanner, *Solving ODEs I*,
/// Thm. II.7.10), so its order as an interpolant is `s`; at `θ = 1` it is the step's result up
/// to round-off.
impl<const S: usize, Y: VectorState, P: Ode<Y> + ?Sized> DenseOutput<P> for GaussStepper<S, Y> {
    fn last_step(&self) -> Option<(f64, f64)> {
        self.have_last.then_some((self.t_start, self.h_last))
    }

    fn interpolate(&mut self, _problem: &P, t: f64, out: &mut Y) {
        let theta = (t - self.t_start) / self.h_last;
        if theta == 1.0 {
            copy_into(out, &self.last);
            return;
        }
        copy_into(out, &self.start);
        let c = &self.method.table.c;
        for j in 0..S {
            let w = lagrange(c, j, theta);
            for (o, zj) in out.as_mut_slice().iter_mut().zip(self.z[j].as_slice()) {
                *o += w * zj;
            }
        }
    }

    fn dense_order(&self) -> u32 {
        S as u32
    }
}
