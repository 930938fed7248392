//! Explicit Runge–Kutta: one generic stepper walks any [`ExplicitTableau`].
//!
//! A step of size `h` from `(t, y)` computes the stages
//! `kᵢ = f(t + cᵢ h, y + h Σ_{j<i} a_ij k_j)` and `y₁ = y + h Σ bᵢ kᵢ` (with compensated
//! summation of the update). With an embedded pair the scaled error
//! `err = ‖h Σ eᵢ kᵢ‖`, weighted componentwise by `atol + rtol max(|y|, |y₁|)` in the RMS
//! norm, drives the step-size controller ([`crate::control`]).
//!
//! Dense output on `[t, t + h]`, `θ = (τ − t)/h`, `θ' = 1 − θ`:
//!
//! `u(θ) = r₁ + θ(r₂ + θ'(r₃ + θ(r₄ + θ'(r₅ + θ(r₆ + θ'(r₇ + θ r₈))))))`
//!
//! with `r₁ = y`, `r₂ = y₁ − y`, `r₃ = h k₁ − r₂`, `r₄ = r₂ − h f(t+h, y₁) − r₃` (the cubic
//! Hermite interpolant) and `r_{4+m} = h Σᵢ d_{m,i} kᵢ` from the table's dense rows
//! (DP5: Shampine's order-4 output, one row; DOP853: Hairer's order-7 output, four rows and
//! three extra stages, evaluated only when an interpolant is asked for).
//!
//! Tsitouras' and Verner's pairs ([`crate::tables::rk_pairs`]) come with continuous weights
//! instead ([`DenseForm::Polynomial`]):
//!
//! `u(θ) = y + h Σᵢ bᵢ(θ) kᵢ`, `bᵢ(θ) = Σ_{m=1}^{q} d_{m,i} θ^m`,
//!
//! evaluated by Horner's rule in `θ`; `bᵢ(1) = bᵢ`. Verner's interpolants need extra stages
//! (3 for 6(5), 6 for 7(6), 8 for 8(7), 10 for 9(8), one of them `f(t + h, y₁)`), which are
//! again evaluated only when an interpolant is asked for, once per step.
//!
//! # Round-off: stages as differences
//!
//! Sums of stages are evaluated as `Σ_j a_ij k_j = cᵢ k₁ + Σ_{j>1} a_ij (k_j − k₁)` (and
//! likewise `Σ bᵢ kᵢ = k₁ + Σ_{i>1} bᵢ (kᵢ − k₁)`, and the interpolant's weights, which sum
//! to `θ`). In exact arithmetic nothing changes (`Σ_j a_ij = cᵢ`, `Σ bᵢ = 1`); in `f64` the
//! rounded coefficients of pairs with large entries (Verner's 6(5): `|a_ij|` up to 207 and
//! `|bᵢ|` up to 73) no longer satisfy the low-order conditions exactly — with the coefficients
//! rounded to nearest, `Σ bᵢ cᵢ − 1/2` is `−6.5·10⁻¹²` for the 6(5) pair when `cᵢ` are the
//! row sums — which shows as a global error `O(h)` of ~10⁻¹¹ on Kepler's problem. In the
//! difference form the rounded `a_ij` and `bᵢ` multiply only `k_j − k₁ = O(h)`, the row sums
//! are the nodes `cᵢ` exactly, and the defect drops to the rounding of `bᵢ cᵢ` (~10⁻¹⁴).
//!
//! The differences `k_j − k₁` are formed once per stage (workspace `dk`), not once per term:
//! the same roundings as forming them term by term, one subtraction per stage instead of one
//! per nonzero coefficient.
//!
//! For the built-in tables the same sums are unrolled with the coefficients as constants
//! (`kernels`), with the same terms in the same order, so both paths agree bit for bit.
//!
//! # References
//! See [`crate::tables::explicit`] and [`crate::tables::rk_pairs`].

mod kernels;

use crate::control::PiController;
use crate::error::Error;
use crate::problem::Ode;
use crate::state::{VectorState, compensated_add, copy_into};
use crate::stepper::{AdaptiveStepper, DenseOutput, Stepper, Tolerances};
use crate::tables::explicit::{DOP853, DP5, RK4};
use crate::tables::rk_pairs::{TSIT5, VERN6, VERN7, VERN8, VERN9};
use crate::tables::{DenseForm, ErrorEstimator, ExplicitTableau};

/// An explicit Runge–Kutta method: a table and its step-size controller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitRungeKutta<const S: usize> {
    /// The Butcher tableau (with error estimator and dense output).
    pub table: &'static ExplicitTableau<S>,
    /// Step-size controller (unused for fixed steps).
    pub controller: PiController,
}

/// The classical RK4.
pub type Rk4 = ExplicitRungeKutta<5>;
/// Dormand–Prince 5(4).
pub type Dp5 = ExplicitRungeKutta<7>;
/// DOP853.
pub type Dop853 = ExplicitRungeKutta<16>;
/// Tsitouras 5(4).
pub type Tsit5 = ExplicitRungeKutta<7>;
/// Verner's 6(5) pair with its order-6 interpolant (12 rows).
pub type Vern6 = ExplicitRungeKutta<12>;
/// Verner's 7(6) pair with its order-7 interpolant (16 rows).
pub type Vern7 = ExplicitRungeKutta<16>;
/// Verner's 8(7) pair with its order-8 interpolant (21 rows).
pub type Vern8 = ExplicitRungeKutta<21>;
/// Verner's 9(8) pair with its order-9 interpolant (26 rows).
pub type Vern9 = ExplicitRungeKutta<26>;

impl ExplicitRungeKutta<5> {
    /// The classical RK4 (fixed step; cubic Hermite dense output).
    #[must_use]
    pub const fn rk4() -> Self {
        Self {
            table: &RK4,
            controller: PiController::DP5,
        }
    }
}

impl ExplicitRungeKutta<7> {
    /// Dormand–Prince 5(4) with Hairer's PI controller.
    #[must_use]
    pub const fn dp5() -> Self {
        Self {
            table: &DP5,
            controller: PiController::DP5,
        }
    }

    /// Tsitouras 5(4) (FSAL, order-4 dense output) with the PI controller of DP5.
    #[must_use]
    pub const fn tsit5() -> Self {
        Self {
            table: &TSIT5,
            controller: PiController::DP5,
        }
    }
}

impl ExplicitRungeKutta<16> {
    /// DOP853 with Hairer's controller.
    #[must_use]
    pub const fn dop853() -> Self {
        Self {
            table: &DOP853,
            controller: PiController::DOP853,
        }
    }

    /// Verner's "most efficient" 7(6) pair (10 stages, order-7 interpolant).
    #[must_use]
    pub const fn vern7() -> Self {
        Self {
            table: &VERN7,
            controller: PiController::VERNER,
        }
    }
}

impl ExplicitRungeKutta<12> {
    /// Verner's "most efficient" 6(5) pair (9 stages with FSAL, order-6 interpolant).
    #[must_use]
    pub const fn vern6() -> Self {
        Self {
            table: &VERN6,
            controller: PiController::VERNER,
        }
    }
}

impl ExplicitRungeKutta<21> {
    /// Verner's "most efficient" 8(7) pair (13 stages, order-8 interpolant).
    #[must_use]
    pub const fn vern8() -> Self {
        Self {
            table: &VERN8,
            controller: PiController::VERNER,
        }
    }
}

impl ExplicitRungeKutta<26> {
    /// Verner's "most efficient" 9(8) pair (16 stages, order-9 interpolant).
    #[must_use]
    pub const fn vern9() -> Self {
        Self {
            table: &VERN9,
            controller: PiController::VERNER,
        }
    }
}

impl<const S: usize> ExplicitRungeKutta<S> {
    /// Builds the per-run stepper for states shaped like `y0` (allocates the workspace once).
    #[must_use]
    pub fn stepper<Y: VectorState>(&self, y0: &Y) -> ExplicitRkStepper<S, Y> {
        ExplicitRkStepper {
            table: self.table,
            kernel: kernels::Kernel::of(self.table),
            controller: self.controller,
            k: std::array::from_fn(|_| y0.zeros_like()),
            dk: std::array::from_fn(|_| y0.zeros_like()),
            y0: y0.zeros_like(),
            y1: y0.zeros_like(),
            ytmp: y0.zeros_like(),
            scratch: y0.zeros_like(),
            delta: y0.zeros_like(),
            carry: y0.zeros_like(),
            t0: 0.0,
            h: 0.0,
            t1: f64::NAN,
            committed: false,
            dense_ready: false,
            continuing: false,
            k0_y: y0.zeros_like(),
            k0_t: f64::NAN,
            k0_valid: false,
            coef: (0..dense_coefficients(self.table))
                .map(|_| y0.zeros_like())
                .collect(),
        }
    }
}

/// How many vectors the dense output of `table` is a polynomial of (see
/// [`ExplicitRkStepper::interpolate`]): `W_m` of the polynomial form, or `r_0 … r_{n−1}` of
/// DOP853's.
fn dense_coefficients<const S: usize>(table: &ExplicitTableau<S>) -> usize {
    match table.dense_form {
        DenseForm::Polynomial => table.dense.len(),
        _ => 4 + table.dense.len(),
    }
}

/// Workspace of one run of an explicit Runge–Kutta method.
#[derive(Debug, Clone)]
pub struct ExplicitRkStepper<const S: usize, Y> {
    table: &'static ExplicitTableau<S>,
    /// The unrolled stage sums for a built-in table ([`kernels`]), else the generic loops.
    kernel: kernels::Kernel,
    controller: PiController,
    k: [Y; S],
    /// `dk[j] = k[j] − k[0]` for `j ≥ 1`, formed once per stage (module doc: every sum of
    /// stages is taken over these differences).
    dk: [Y; S],
    y0: Y,
    y1: Y,
    ytmp: Y,
    /// Second workspace of the error estimate (DOP853's third-order difference).
    scratch: Y,
    delta: Y,
    carry: Y,
    t0: f64,
    h: f64,
    t1: f64,
    committed: bool,
    dense_ready: bool,
    continuing: bool,
    /// `k[0] = f(k0_t, k0_y)` from a rejected attempt, reusable by the retry.
    k0_y: Y,
    k0_t: f64,
    k0_valid: bool,
    /// The dense output's polynomial coefficients of the last step, formed once per step
    /// (when it is first interpolated) and evaluated by Horner's rule at every time asked.
    coef: Vec<Y>,
}

impl<const S: usize, Y: VectorState> ExplicitRkStepper<S, Y> {
    /// The table this stepper walks.
    pub fn table(&self) -> &'static ExplicitTableau<S> {
        self.table
    }

    /// `ytmp = base + h Σ_{j<i} a_ij k_j` (`base` = `y0` of the last step when `None`),
    /// evaluated as `base + h (cᵢ k₁ + Σ_{1<j<i} a_ij (k_j − k₁))` (module doc).
    fn stage_argument(&mut self, base: Option<&Y>, i: usize, h: f64) {
        let n = self.y0.dim();
        let row = &self.table.a[i];
        let mut ha = [0.0; S];
        for j in 1..i {
            ha[j] = h * row[j];
        }
        let base = base.unwrap_or(&self.y0).as_slice();
        let k0 = self.k[0].as_slice();
        combine(
            &mut self.ytmp.as_mut_slice()[..n],
            Some(base),
            h * self.table.c[i],
            k0,
            &self.dk[1..i],
            &ha[1..i],
        );
    }

    /// `dk[i] = k[i] − k[0]`.
    fn difference(&mut self, i: usize) {
        let n = self.y0.dim();
        let (first, rest) = self.k.split_at(1);
        let k0 = &first[0].as_slice()[..n];
        let ki = &rest[i - 1].as_slice()[..n];
        let d = &mut self.dk[i].as_mut_slice()[..n];
        for m in 0..n {
            d[m] = ki[m] - k0[m];
        }
    }

    /// All stages of one attempt and the increment `delta = h Σ bᵢ kᵢ`.
    fn compute_stages<P: Ode<Y>>(&mut self, problem: &P, t: f64, y: &Y, h: f64) {
        let tab = self.table;
        // The cached f(t, y) of the previous step is the first stage when the caller
        // continues from exactly where the last step ended.
        self.continuing = self.committed
            && crate::state::same_time(t, self.t1)
            && y.as_slice() == self.y1.as_slice()
            && tab.fsal != 0;
        let retry = self.k0_valid && t == self.k0_t && y.as_slice() == self.k0_y.as_slice();
        if self.continuing {
            let (first, rest) = self.k.split_at_mut(1);
            copy_into(&mut first[0], &rest[tab.fsal - 1]);
        } else if !retry {
            problem.rhs(t, y, &mut self.k[0]);
        }
        if !retry {
            copy_into(&mut self.k0_y, y);
            self.k0_t = t;
            self.k0_valid = true;
        }
        self.committed = false;
        self.dense_ready = false;
        let unrolled = kernels::stages(
            self.kernel,
            problem,
            t,
            y,
            h,
            kernels::Work {
                k: &mut self.k,
                dk: &mut self.dk,
                ytmp: &mut self.ytmp,
                delta: &mut self.delta,
            },
        );
        if unrolled {
            return;
        }
        for i in 1..tab.stages {
            self.stage_argument(Some(y), i, h);
            problem.rhs(t + tab.c[i] * h, &self.ytmp, &mut self.k[i]);
            self.difference(i);
        }
        // delta = h Σ bᵢ kᵢ = h (k₁ + Σ_{i>1} bᵢ (kᵢ − k₁)) since Σ bᵢ = 1 (module doc).
        let n = y.dim();
        let mut hb = [0.0; S];
        for j in 1..tab.stages {
            hb[j] = h * tab.b[j];
        }
        combine(
            &mut self.delta.as_mut_slice()[..n],
            None,
            h,
            self.k[0].as_slice(),
            &self.dk[1..tab.stages],
            &hb[1..tab.stages],
        );
    }

    /// The scaled error of the last attempt. The weighted stage sums go into the `ytmp` and
    /// `scratch` workspaces (unrolled for a built-in table, else accumulated stage by stage:
    /// per component the same sum in the same order either way), then their weighted norm.
    fn error_norm(&mut self, y: &Y, h: f64, tol: &Tolerances) -> f64 {
        let (e5w, e3w) = match &self.table.error {
            ErrorEstimator::None => return 0.0,
            ErrorEstimator::Embedded { weights, .. } => (weights, None),
            ErrorEstimator::Dop853 { e5, e3, .. } => (e5, Some(e3)),
        };
        if !kernels::error_sums(self.kernel, &self.k, &mut self.ytmp, &mut self.scratch) {
            let accumulate = |out: &mut Y, weights: &[f64; S], k: &[Y; S]| {
                let out = out.as_mut_slice();
                out.fill(0.0);
                for (&w, kj) in weights.iter().zip(k) {
                    if w != 0.0 {
                        for (o, x) in out.iter_mut().zip(kj.as_slice()) {
                            *o += w * x;
                        }
                    }
                }
            };
            accumulate(&mut self.ytmp, e5w, &self.k);
            if let Some(e3w) = e3w {
                accumulate(&mut self.scratch, e3w, &self.k);
            }
        }
        let n = y.dim();
        let ys = &y.as_slice()[..n];
        let ds = &self.delta.as_slice()[..n];
        let e5 = &self.ytmp.as_slice()[..n];
        let dim = n.max(1) as f64;
        let weight = |i: usize| tol.atol + tol.rtol * ys[i].abs().max((ys[i] + ds[i]).abs());
        if e3w.is_none() {
            let mut sum = 0.0;
            for (i, &ei) in e5.iter().enumerate() {
                let r = h * ei / weight(i);
                sum += r * r;
            }
            return (sum / dim).sqrt();
        }
        let e3 = &self.scratch.as_slice()[..n];
        let (mut s5, mut s3) = (0.0, 0.0);
        for (i, (&x5, &x3)) in e5.iter().zip(e3).enumerate() {
            let sk = weight(i);
            s5 += (x5 / sk) * (x5 / sk);
            s3 += (x3 / sk) * (x3 / sk);
        }
        let mut deno = s5 + 0.01 * s3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        h.abs() * s5 / (dim * deno).sqrt()
    }

    fn commit<P: Ode<Y>>(&mut self, problem: &P, t: f64, y: &mut Y, h: f64) {
        let tab = self.table;
        copy_into(&mut self.y0, y);
        if !self.continuing {
            self.carry.as_mut_slice().fill(0.0);
        }
        for ((yi, di), ci) in y
            .as_mut_slice()
            .iter_mut()
            .zip(self.delta.as_slice())
            .zip(self.carry.as_mut_slice())
        {
            compensated_add(yi, *di, ci);
        }
        copy_into(&mut self.y1, y);
        self.t0 = t;
        self.h = h;
        self.t1 = t + h;
        if tab.fsal >= tab.stages {
            problem.rhs(t + h, y, &mut self.k[tab.fsal]);
            self.difference(tab.fsal);
        }
        self.committed = true;
        self.dense_ready = false;
        self.k0_valid = false;
    }

    fn ensure_dense<P: Ode<Y>>(&mut self, problem: &P) {
        if self.dense_ready {
            return;
        }
        let tab = self.table;
        let (t0, h) = (self.t0, self.h);
        for i in tab.stages..S {
            if i == tab.fsal {
                continue;
            }
            self.stage_argument(None, i, h);
            problem.rhs(t0 + tab.c[i] * h, &self.ytmp, &mut self.k[i]);
            self.difference(i);
        }
        self.dense_coefficients();
        self.dense_ready = true;
    }

    /// Forms [`Self::coef`] from the stages of the last step.
    fn dense_coefficients(&mut self) {
        let tab = self.table;
        let h = self.h;
        let n = self.y0.dim();
        if tab.dense_form == DenseForm::Polynomial {
            // W_m = h Σᵢ d_{m,i} kᵢ; the weights sum to [m = 0], so
            // W_m = h (δ_{m0} k₁ + Σ_{i>1} d_{m,i} (kᵢ − k₁)).
            for (m, row) in tab.dense.iter().enumerate() {
                for i in 0..n {
                    let mut w = if m == 0 { self.k[0].as_slice()[i] } else { 0.0 };
                    for (j, &d) in row.iter().enumerate().skip(1) {
                        if d != 0.0 {
                            w += d * self.dk[j].as_slice()[i];
                        }
                    }
                    self.coef[m].as_mut_slice()[i] = h * w;
                }
            }
            return;
        }
        for i in 0..n {
            let y0 = self.y0.as_slice()[i];
            let r1 = self.y1.as_slice()[i] - y0;
            let r2 = h * self.k[0].as_slice()[i] - r1;
            let r3 = r1 - h * self.k[tab.fsal].as_slice()[i] - r2;
            for (m, r) in [y0, r1, r2, r3].into_iter().enumerate() {
                self.coef[m].as_mut_slice()[i] = r;
            }
            for (m, row) in tab.dense.iter().enumerate() {
                let mut s = 0.0;
                for (j, &d) in row.iter().enumerate() {
                    if d != 0.0 {
                        s += d * self.k[j].as_slice()[i];
                    }
                }
                self.coef[4 + m].as_mut_slice()[i] = h * s;
            }
        }
    }
}

impl<const S: usize, Y: VectorState, P: Ode<Y>> Stepper<P> for ExplicitRkStepper<S, Y> {
    type State = Y;

    fn step(&mut self, problem: &P, t: f64, state: &mut Y, h: f64) -> Result<(), Error> {
        self.compute_stages(problem, t, state, h);
        self.commit(problem, t, state, h);
        Ok(())
    }

    fn reset(&mut self) {
        self.committed = false;
        self.dense_ready = false;
        self.k0_valid = false;
        self.t1 = f64::NAN;
    }
}

impl<const S: usize, Y: VectorState, P: Ode<Y>> AdaptiveStepper<P> for ExplicitRkStepper<S, Y> {
    fn error_order(&self) -> u32 {
        match self.table.error {
            ErrorEstimator::None => self.table.order,
            ErrorEstimator::Embedded { order, .. } | ErrorEstimator::Dop853 { order, .. } => order,
        }
    }

    fn controller(&self) -> PiController {
        self.controller
    }

    fn attempt(
        &mut self,
        problem: &P,
        t: f64,
        state: &Y,
        h: f64,
        tolerances: &Tolerances,
    ) -> Result<f64, Error> {
        self.compute_stages(problem, t, state, h);
        Ok(self.error_norm(state, h, tolerances))
    }

    fn accept(&mut self, problem: &P, t: f64, state: &mut Y, h: f64) {
        self.commit(problem, t, state, h);
    }

    fn initial_step(
        &mut self,
        problem: &P,
        t: f64,
        state: &Y,
        h_max: f64,
        tolerances: &Tolerances,
    ) -> f64 {
        // Hairer–Nørsett–Wanner I, §II.4: h₀ from ‖y‖ and ‖f‖, then one Euler step to
        // estimate the second derivative.
        let n = state.dim().max(1) as f64;
        problem.rhs(t, state, &mut self.k[0]);
        let ys = state.as_slice();
        let sk = |i: usize| tolerances.atol + tolerances.rtol * ys[i].abs();
        let rms = |v: &[f64]| {
            (v.iter()
                .enumerate()
                .map(|(i, x)| (x / sk(i)) * (x / sk(i)))
                .sum::<f64>()
                / n)
                .sqrt()
        };
        let d0 = rms(ys);
        let d1 = rms(self.k[0].as_slice());
        let mut h0 = if d0 < 1e-10 || d1 < 1e-10 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        h0 = h0.min(h_max);
        copy_into(&mut self.ytmp, state);
        for (o, f) in self
            .ytmp
            .as_mut_slice()
            .iter_mut()
            .zip(self.k[0].as_slice())
        {
            *o += h0 * f;
        }
        problem.rhs(t + h0, &self.ytmp, &mut self.k[1]);
        let mut diff = 0.0;
        for i in 0..ys.len() {
            let d = (self.k[1].as_slice()[i] - self.k[0].as_slice()[i]) / sk(i);
            diff += d * d;
        }
        let d2 = (diff / n).sqrt() / h0;
        let order = f64::from(self.table.order);
        let h1 = if d1.max(d2) <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / d1.max(d2)).powf(1.0 / order)
        };
        self.committed = false;
        self.k0_valid = false;
        (100.0 * h0).min(h1).min(h_max)
    }
}

impl<const S: usize, Y: VectorState, P: Ode<Y>> DenseOutput<P> for ExplicitRkStepper<S, Y> {
    fn last_step(&self) -> Option<(f64, f64)> {
        self.committed.then_some((self.t0, self.h))
    }

    fn interpolate(&mut self, problem: &P, t: f64, out: &mut Y) {
        self.ensure_dense(problem);
        let tab = self.table;
        let theta = (t - self.t0) / self.h;
        let o = out.as_mut_slice();
        if tab.dense_form == DenseForm::Polynomial {
            // u(θ) = y + Σ_m θ^(m+1) W_m, by Horner's rule in θ.
            for (i, o) in o.iter_mut().enumerate() {
                let mut acc = 0.0;
                for w in self.coef.iter().rev() {
                    acc = theta * (w.as_slice()[i] + acc);
                }
                *o = self.y0.as_slice()[i] + acc;
            }
            return;
        }
        // DOP853's form: fold from the innermost term; r_m (1-based) is multiplied by θ' when
        // m is even and by θ when m is odd.
        let theta1 = 1.0 - theta;
        let n_r = self.coef.len();
        for (i, o) in o.iter_mut().enumerate() {
            let r = |m: usize| self.coef[m].as_slice()[i];
            let mut acc = r(n_r - 1);
            for m in (1..n_r - 1).rev() {
                let mult = if (m + 1) % 2 == 0 { theta1 } else { theta };
                acc = r(m) + mult * acc;
            }
            *o = r(0) + theta * acc;
        }
    }

    fn dense_order(&self) -> u32 {
        self.table.dense_order
    }
}

/// Width of the register blocks of [`combine`] and of the unrolled kernels.
const LANES: usize = 4;

/// `out = base + (w₀ x₀ + Σ_j w_j x_j)` componentwise, terms with `w_j = 0` left out (`base`
/// zero when `None`). The sum is taken block by block over [`LANES`] components, each block
/// accumulated in registers over all terms and stored once: no component is written and read
/// back within a call, and per component the terms are added in the same order.
#[inline(always)]
fn combine<Y: VectorState>(
    out: &mut [f64],
    base: Option<&[f64]>,
    w0: f64,
    x0: &[f64],
    xs: &[Y],
    ws: &[f64],
) {
    let n = out.len();
    let x0 = &x0[..n];
    let block = |out: &mut [f64], start: usize| {
        let width = out.len();
        let mut acc = [0.0; LANES];
        for l in 0..width {
            acc[l] = w0 * x0[start + l];
        }
        for (x, &w) in xs.iter().zip(ws) {
            if w != 0.0 {
                let x = &x.as_slice()[start..start + width];
                for l in 0..width {
                    acc[l] += w * x[l];
                }
            }
        }
        match base {
            Some(b) => {
                let b = &b[start..start + width];
                for l in 0..width {
                    out[l] = b[l] + acc[l];
                }
            }
            None => out.copy_from_slice(&acc[..width]),
        }
    };
    let mut chunks = out.chunks_exact_mut(LANES);
    let mut start = 0;
    for c in &mut chunks {
        block(c, start);
        start += LANES;
    }
    let rest = chunks.into_remainder();
    if !rest.is_empty() {
        block(rest, start);
    }
}
