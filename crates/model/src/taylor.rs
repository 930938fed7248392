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
//!
//! A model with orientations on SO(3) has the state `y = (q, R₁ … R_k, q̇, ω₁ … ω_k)` (each
//! rotation matrix by rows) and the first-order tape of `y' = F(t, y)` ([`crate::mechanics::first_order`]:
//! the kinematics `q' = q̇`, `Ṙ = R ω̂`, and `v̇ = M⁻¹ f` by a Cholesky factorization written
//! on the graph). Its coefficients are those of the tape itself: one pass at order `k` gives
//! `[F(t, y(t))]ₖ` and `yₖ₊₁ = [F]ₖ/(k+1)` (Jorba & Zou 2005, §3), the square roots and
//! quotients of the factorization expanded by their own recursions. `R` is then a point of
//! ℝ⁹: the series keeps it on SO(3) to the method's truncation error only, so `RᵀR − I` drifts
//! at the level of the tolerance (the Lie-group methods keep it there to round-off).
//!
//! Both forms also expand in double-double ([`DoubleDoubleSystem`], for `taylor-dd` and the
//! references built on it): the same recursion over [`DoubleDouble`], with the functions of
//! order 0, the parameters' nodes and the factorization of `M₀` in double-double
//! ([`crate::expr::scalar`]): the parameters and the model's constants, as `f64`, are the
//! data, and everything computed from them is computed to about `2⁻¹⁰⁴`.

use std::cell::RefCell;

use tumble_integrators::TaylorSystem;
use tumble_integrators::taylor::{DoubleDouble, DoubleDoubleSystem, TaylorError, check_finite};

use crate::expr::scalar::TapeScalar;
use crate::expr::tape::Tape;
use crate::expr::taylor::{TaylorPlan, TaylorWork};
use crate::mechanics::{cholesky_factor, cholesky_substitute};

/// Which equations a [`ModelTaylor`] expands.
#[derive(Debug, Clone, PartialEq)]
enum Form {
    /// `M(q, t) q̈ = f` of `n` coordinates (the mass-matrix-and-forces tape).
    SecondOrder { n: usize },
    /// `y' = F(t, y)` of a state of length `dim` (the first-order tape), whose outputs
    /// `pivots` are the pivots of the mass matrix's factorization.
    FirstOrder {
        dim: usize,
        pivots: std::ops::Range<usize>,
    },
}

/// The storage of one run's expansions, in the scalar `S`.
#[derive(Debug)]
struct Work<S> {
    series: TaylorWork<S>,
    /// `M₀`, factorized.
    m0: Vec<S>,
    /// The right-hand side of order `k`, then `aₖ`.
    b: Vec<S>,
    /// `aⱼ`, `j < k`, by order.
    acc: Vec<S>,
}

impl<S: TapeScalar> Work<S> {
    /// Storage for orders `0 ..= order` of the tape's expansion, and for the second-order
    /// form's solves of `n` coordinates (`n = 0`: the first-order form).
    fn new(tape: &Tape, plan: &TaylorPlan, fixed: &[f64], n: usize, order: usize) -> Self {
        Work {
            series: TaylorWork::new(tape, plan, fixed, order),
            m0: vec![S::ZERO; n * n],
            b: vec![S::ZERO; n],
            acc: vec![S::ZERO; (order + 1) * n],
        }
    }
}

/// A model's equations at fixed parameters, computing Taylor coefficients of its solution.
#[derive(Debug)]
pub struct ModelTaylor<'a> {
    tape: &'a Tape,
    plan: &'a TaylorPlan,
    form: Form,
    /// The tape's inputs with the parameters set (time, coordinates and rates zero).
    fixed: Vec<f64>,
    work: RefCell<Work<f64>>,
    /// The double-double storage, made at the first double-double expansion.
    work_dd: RefCell<Option<Work<DoubleDouble>>>,
}

/// The order the storage is first sized for (that of the adaptive method at `ε ≈ 10⁻¹⁶`).
const INITIAL_ORDER: usize = 20;

impl<'a> ModelTaylor<'a> {
    /// The system of the mass-matrix-and-forces `tape` (outputs: `M` row-major, then `f`) of a
    /// model with `n` coordinates, its inputs `fixed` (parameters set), storage for
    /// [`INITIAL_ORDER`].
    #[must_use]
    pub fn new(tape: &'a Tape, plan: &'a TaylorPlan, n: usize, fixed: Vec<f64>) -> Self {
        ModelTaylor {
            tape,
            plan,
            form: Form::SecondOrder { n },
            work: RefCell::new(Work::new(tape, plan, &fixed, n, INITIAL_ORDER)),
            work_dd: RefCell::new(None),
            fixed,
        }
    }

    /// The system of the first-order `tape` of a state of length `dim` (outputs: `y'`, then
    /// the mass matrix's `dof` pivots, [`crate::mechanics::first_order`]), its inputs `fixed`
    /// (parameters set), storage for [`INITIAL_ORDER`].
    #[must_use]
    pub fn first_order(
        tape: &'a Tape,
        plan: &'a TaylorPlan,
        dim: usize,
        dof: usize,
        fixed: Vec<f64>,
    ) -> Self {
        ModelTaylor {
            tape,
            plan,
            form: Form::FirstOrder {
                dim,
                pivots: dim..dim + dof,
            },
            work: RefCell::new(Work::new(tape, plan, &fixed, 0, INITIAL_ORDER)),
            work_dd: RefCell::new(None),
            fixed,
        }
    }

    /// Coordinates of the second-order form (0 for the first-order form).
    fn second_order_n(&self) -> usize {
        match self.form {
            Form::SecondOrder { n } => n,
            Form::FirstOrder { .. } => 0,
        }
    }

    /// Sets coefficient `k` of time and of the state's inputs (`coeffs` of order `k`, the
    /// first `dim` of the tape's inputs after time).
    fn set_inputs<S: TapeScalar>(
        &self,
        series: &mut TaylorWork<S>,
        t0: S,
        coeffs: &[S],
        dim: usize,
        k: usize,
    ) {
        let inputs = self.tape.inputs();
        if inputs > 0 {
            let t = match k {
                0 => t0,
                1 => S::of(1.0),
                _ => S::ZERO,
            };
            series.set_input(0, k, t);
        }
        for i in 0..dim.min(inputs.saturating_sub(1)) {
            series.set_input(1 + i, k, coeffs[k * dim + i]);
        }
    }

    /// The coefficients of the solution through `(t0, x0)` to `order`, in the scalar `S`, with
    /// the storage `w` (grown if the order exceeds it).
    fn expand<S: TapeScalar>(
        &self,
        w: &mut Work<S>,
        t0: S,
        x0: &[S],
        order: usize,
        coeffs: &mut [S],
    ) -> Result<(), TaylorError> {
        if order > w.series.max_order() {
            *w = Work::new(
                self.tape,
                self.plan,
                &self.fixed,
                self.second_order_n(),
                order,
            );
        }
        match &self.form {
            Form::SecondOrder { n } => self.second_order_coefficients(w, t0, x0, order, coeffs, *n),
            Form::FirstOrder { dim, pivots } => {
                self.first_order_coefficients(w, t0, x0, order, coeffs, (*dim, pivots.clone()))
            }
        }
    }

    /// The coefficients of `y' = F(t, y)` by the tape of `F` ([`Form::FirstOrder`]).
    fn first_order_coefficients<S: TapeScalar>(
        &self,
        w: &mut Work<S>,
        t0: S,
        x0: &[S],
        order: usize,
        coeffs: &mut [S],
        (dim, pivots): (usize, std::ops::Range<usize>),
    ) -> Result<(), TaylorError> {
        coeffs[..dim].copy_from_slice(&x0[..dim]);
        for k in 0..order {
            self.set_inputs(&mut w.series, t0, coeffs, dim, k);
            w.series.run_order(self.tape, self.plan, k);
            if k == 0
                && pivots
                    .clone()
                    .any(|j| !(w.series.output(self.tape, j, 0).leading() > 0.0))
            {
                return Err(TaylorError::Singular {
                    reason: "the mass matrix is not positive definite",
                });
            }
            let next = S::of((k + 1) as f64);
            for i in 0..dim {
                coeffs[(k + 1) * dim + i] = w.series.output(self.tape, i, k).quotient(next);
            }
        }
        check_finite(coeffs, dim, order)
    }

    /// The coefficients of `q' = q̇`, `M q̈ = f` by the tape of `M` and `f`
    /// ([`Form::SecondOrder`]).
    fn second_order_coefficients<S: TapeScalar>(
        &self,
        w: &mut Work<S>,
        t0: S,
        x0: &[S],
        order: usize,
        coeffs: &mut [S],
        n: usize,
    ) -> Result<(), TaylorError> {
        let dim = 2 * n;
        coeffs[..dim].copy_from_slice(&x0[..dim]);
        for k in 0..order {
            self.set_inputs(&mut w.series, t0, coeffs, dim, k);
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
                        r = r - w.series.output(self.tape, i * n + l, j) * *al;
                    }
                }
                w.b[i] = r;
            }
            cholesky_substitute(&w.m0, &mut w.b, n);
            w.acc[k * n..(k + 1) * n].copy_from_slice(&w.b);
            let next = S::of((k + 1) as f64);
            for i in 0..n {
                coeffs[(k + 1) * dim + n + i] = w.b[i].quotient(next);
                coeffs[(k + 1) * dim + i] = coeffs[k * dim + n + i].quotient(next);
            }
        }
        check_finite(coeffs, dim, order)
    }
}

impl TaylorSystem for ModelTaylor<'_> {
    fn dim(&self) -> usize {
        match self.form {
            Form::SecondOrder { n } => 2 * n,
            Form::FirstOrder { dim, .. } => dim,
        }
    }

    fn coefficients(
        &self,
        t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError> {
        self.expand(&mut self.work.borrow_mut(), t0, x0, order, coeffs)
    }

    fn double_double(&self) -> Option<&dyn DoubleDoubleSystem> {
        Some(self)
    }
}

impl DoubleDoubleSystem for ModelTaylor<'_> {
    fn coefficients_dd(
        &self,
        t0: DoubleDouble,
        x0: &[DoubleDouble],
        order: usize,
        coeffs: &mut [DoubleDouble],
    ) -> Result<(), TaylorError> {
        let mut slot = self.work_dd.borrow_mut();
        let w = slot.get_or_insert_with(|| {
            Work::new(
                self.tape,
                self.plan,
                &self.fixed,
                self.second_order_n(),
                order.max(INITIAL_ORDER),
            )
        });
        self.expand(w, t0, x0, order, coeffs)
    }
}
