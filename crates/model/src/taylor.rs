//! A model's Taylor coefficients ([`TaylorSystem`]) by Taylor-mode automatic differentiation
//! on its instruction tape ([`crate::expr::taylor`]), for the Taylor methods of
//! `tumble-integrators`.
//!
//! The state is `x = (q, q̇)` and the equations `q' = q̇`, `M(q, t) q̈ = f(q, q̇, t)`. With the
//! coefficients of `q` and `q̇` known to order `k`, one pass over the tape gives coefficient `k`
//! of every entry of `M` and `f`; the coefficient `aₖ` of `q̈` then solves
//! `M₀ aₖ = fₖ − Σⱼ₌₁ᵏ Mⱼ aₖ₋ⱼ` (the Cauchy product of `M q̈ = f` at order `k`), with `M₀`
//! factorized once per expansion (Cholesky), and gives `q̇ₖ₊₁ = aₖ/(k+1)`,
//! `qₖ₊₁ = q̇ₖ/(k+1)`. Time is the series `t₀ + h`. Nothing is allocated per expansion once the
//! storage holds the run's order.

use std::cell::RefCell;

use tumble_integrators::TaylorSystem;
use tumble_integrators::taylor::{TaylorError, check_finite};

use crate::expr::tape::Tape;
use crate::expr::taylor::{TaylorPlan, TaylorWork};
use crate::mechanics::{cholesky_factor, cholesky_substitute};

/// The storage of one run's expansions.
#[derive(Debug)]
struct Work {
    series: TaylorWork,
    /// `M₀`, factorized.
    m0: Vec<f64>,
    /// The right-hand side of order `k`, then `aₖ`.
    b: Vec<f64>,
    /// `aⱼ`, `j < k`, by order.
    acc: Vec<f64>,
}

/// A model's equations at fixed parameters, computing Taylor coefficients of its solution.
#[derive(Debug)]
pub struct ModelTaylor<'a> {
    tape: &'a Tape,
    plan: &'a TaylorPlan,
    n: usize,
    /// The tape's inputs with the parameters set (time, coordinates and rates zero).
    fixed: Vec<f64>,
    work: RefCell<Work>,
}

/// The order the storage is first sized for (that of the adaptive method at `ε ≈ 10⁻¹⁶`).
const INITIAL_ORDER: usize = 20;

impl<'a> ModelTaylor<'a> {
    /// The system of the mass-matrix-and-forces `tape` (outputs: `M` row-major, then `f`) of a
    /// model with `n` coordinates, its inputs `fixed` (parameters set), storage for
    /// [`INITIAL_ORDER`].
    #[must_use]
    pub fn new(tape: &'a Tape, plan: &'a TaylorPlan, n: usize, fixed: Vec<f64>) -> Self {
        let work = Work {
            series: TaylorWork::new(tape, plan, &fixed, INITIAL_ORDER),
            m0: vec![0.0; n * n],
            b: vec![0.0; n],
            acc: vec![0.0; (INITIAL_ORDER + 1) * n],
        };
        ModelTaylor {
            tape,
            plan,
            n,
            fixed,
            work: RefCell::new(work),
        }
    }
}

impl TaylorSystem for ModelTaylor<'_> {
    fn dim(&self) -> usize {
        2 * self.n
    }

    fn coefficients(
        &self,
        t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError> {
        let n = self.n;
        let dim = 2 * n;
        let w = &mut *self.work.borrow_mut();
        if order > w.series.max_order() {
            w.series = TaylorWork::new(self.tape, self.plan, &self.fixed, order);
            w.acc = vec![0.0; (order + 1) * n];
        }
        coeffs[..dim].copy_from_slice(&x0[..dim]);
        let inputs = self.tape.inputs();
        for k in 0..order {
            if inputs > 0 {
                let t = match k {
                    0 => t0,
                    1 => 1.0,
                    _ => 0.0,
                };
                w.series.set_input(0, k, t);
            }
            for i in 0..dim.min(inputs.saturating_sub(1)) {
                w.series.set_input(1 + i, k, coeffs[k * dim + i]);
            }
            w.series.run_order(self.tape, self.plan, k);
            if k == 0 {
                for i in 0..n * n {
                    w.m0[i] = w.series.output(self.tape, i, 0);
                }
                if !(cholesky_factor(&mut w.m0, n) > 0.0) {
                    return Err(TaylorError::Singular {
                        reason: "the mass matrix is not positive definite",
                    });
                }
            }
            for i in 0..n {
                let mut r = w.series.output(self.tape, n * n + i, k);
                for j in 1..=k {
                    let a = &w.acc[(k - j) * n..(k - j + 1) * n];
                    for (l, al) in a.iter().enumerate() {
                        r -= w.series.output(self.tape, i * n + l, j) * al;
                    }
                }
                w.b[i] = r;
            }
            cholesky_substitute(&w.m0, &mut w.b, n);
            w.acc[k * n..(k + 1) * n].copy_from_slice(&w.b);
            let next = (k + 1) as f64;
            for i in 0..n {
                coeffs[(k + 1) * dim + n + i] = w.b[i] / next;
                coeffs[(k + 1) * dim + i] = coeffs[k * dim + n + i] / next;
            }
        }
        check_finite(coeffs, dim, order)
    }
}
