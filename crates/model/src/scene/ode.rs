//! A model's first-order system `(q, q̇)' = (q̇, M⁻¹ f)` ([`ModelOde`]): the tape evaluated
//! natively or interpreted, a constant mass matrix inverted once per run, and the refusal of
//! an initial state where the mass matrix is singular or ill-conditioned.

use std::cell::RefCell;

use nalgebra::SVector;
use tumble_integrators::Ode;
use tumble_scenarios::{Params, SceneError};

use super::ModelScene;
use crate::expr::tape::Tape;
use crate::mechanics::{Layout, cholesky_factor, cholesky_solve, cholesky_substitute};
use crate::taylor::ModelTaylor;
use tumble_jit::{JitError, Native};

/// The largest condition number of the mass matrix accepted at the initial state.
pub const MAX_CONDITION: f64 = 1e10;
impl ModelScene {
    /// How [`ModelScene::ode`] evaluates the right-hand side: natively where the machine has
    /// a code generator (x86-64, AArch64, RISC-V 64, s390x), else by interpretation.
    #[must_use]
    pub fn evaluation(&self) -> Evaluation {
        if self.native.is_some() {
            Evaluation::Native
        } else {
            Evaluation::Interpreted
        }
    }

    /// Compiles the right-hand side's tape again (what loading the model did once), for
    /// timing the compilation.
    ///
    /// # Errors
    /// [`JitError`] where the machine has no code generator.
    pub fn compile_rhs(&self) -> Result<Native, JitError> {
        self.rhs.compile()
    }

    /// The right-hand side at `params`, its workspace allocated here once, evaluated as
    /// [`ModelScene::evaluation`] says.
    #[must_use]
    pub fn ode(&self, params: &Params) -> ModelOde<'_> {
        self.ode_with(params, self.evaluation())
    }

    /// The right-hand side at `params` evaluated by interpretation or native code (native
    /// falls back to interpretation where the machine has no code generator). Both give the
    /// same bits.
    #[must_use]
    pub fn ode_with(&self, params: &Params, evaluation: Evaluation) -> ModelOde<'_> {
        let layout = self.model.layout;
        let dof = layout.dof();
        let mut slots = self.rhs.workspace();
        let inputs = self.inputs(params);
        let k = inputs.len().min(slots.len());
        slots[..k].copy_from_slice(&inputs[..k]);
        self.rhs.run_prelude(&mut slots);
        // A mass matrix of the parameters alone is in the prelude's results: inverted here
        // once (Cholesky, column by column), each evaluation then multiplies by the inverse.
        let mut m = vec![0.0; dof * dof];
        let mut factored = false;
        if self.constant_mass {
            let mut l = vec![0.0; dof * dof];
            for (i, x) in l.iter_mut().enumerate() {
                *x = self.rhs.output(&slots, i);
            }
            if cholesky_factor(&mut l, dof) > 0.0 {
                let mut e = vec![0.0; dof];
                for j in 0..dof {
                    e.fill(0.0);
                    e[j] = 1.0;
                    cholesky_substitute(&l, &mut e, dof);
                    for i in 0..dof {
                        m[i * dof + j] = e[i];
                    }
                }
                factored = true;
            }
        }
        ModelOde {
            tape: &self.rhs,
            native: match evaluation {
                Evaluation::Native => self.native,
                Evaluation::Interpreted => None,
            },
            layout,
            work: RefCell::new(Work {
                slots,
                m,
                b: vec![0.0; dof],
                factored,
            }),
        }
    }

    /// The equations at `params` as a system computing its Taylor coefficients (Taylor-mode
    /// automatic differentiation on the tape, [`crate::taylor`]), its storage allocated here.
    /// `None` for a model with an orientation on SO(3).
    #[must_use]
    pub fn taylor(&self, params: &Params) -> Option<ModelTaylor<'_>> {
        let plan = self.taylor.as_ref()?;
        Some(ModelTaylor::new(
            &self.rhs,
            plan,
            self.model.layout.n,
            self.inputs(params),
        ))
    }

    /// Refuses an initial state where the mass matrix is singular or ill-conditioned, naming
    /// the coordinate along which it degenerates.
    pub(super) fn check_conditioning(
        &self,
        ode: &ModelOde<'_>,
        y: &[f64],
    ) -> Result<(), SceneError> {
        let n = self.model.layout.dof();
        let m = ode.mass_matrix(0.0, y);
        let matrix = nalgebra::DMatrix::from_row_slice(n, n, &m);
        let eigen = nalgebra::SymmetricEigen::new(matrix);
        let (mut lo, mut hi) = (0, 0);
        for i in 0..n {
            if eigen.eigenvalues[i] < eigen.eigenvalues[lo] {
                lo = i;
            }
            if eigen.eigenvalues[i] > eigen.eigenvalues[hi] {
                hi = i;
            }
        }
        let (min, max) = (eigen.eigenvalues[lo], eigen.eigenvalues[hi]);
        let condition = if min > 0.0 { max / min } else { f64::INFINITY };
        if condition.is_finite() && condition <= MAX_CONDITION && max > 0.0 {
            return Ok(());
        }
        // The coordinate at fault: the one whose change most lifts the smallest eigenvalue
        // (at gimbal lock the middle Euler angle, not the two angles that turn alike).
        let v: Vec<f64> = eigen.eigenvectors.column(lo).iter().copied().collect();
        let quadratic = |y: &[f64]| {
            let m = ode.mass_matrix(0.0, y);
            (0..n)
                .map(|i| (0..n).map(|j| v[i] * m[i * n + j] * v[j]).sum::<f64>())
                .sum::<f64>()
        };
        let base = quadratic(y);
        let lift = |k: usize| {
            let mut z = y.to_vec();
            let mut best = 0.0f64;
            for h in [1e-3, -1e-3] {
                z[k] = y[k] + h;
                best = best.max((quadratic(&z) - base).abs());
            }
            best
        };
        // Only a scalar coordinate can be at fault: the angular velocities enter the mass
        // matrix through the inertia, which does not depend on the orientation.
        let fault = (0..self.model.layout.n).max_by(|&a, &b| lift(a).total_cmp(&lift(b)));
        let Some(fault) = fault else {
            return Err(SceneError::ModelRefused {
                model: self.info.name.to_string(),
                message: format!(
                    "the mass matrix is singular at the initial state (condition number \
                     {condition:e}, above {MAX_CONDITION:e}): a body turning on SO(3) needs \
                     an inertia with three positive principal moments"
                ),
            });
        };
        Err(SceneError::ModelRefused {
            model: self.info.name.to_string(),
            message: format!(
                "the mass matrix is singular at the initial state (condition number {condition:e}, \
                 above {MAX_CONDITION:e}); the coordinate at fault is `{}` (moving it \
                 lifts the degenerate direction), at {} = {}. Euler angles lock where their middle angle \
                 makes the first and third axes one (theta = 0 or pi for ZYZ): start away from \
                 it, or choose a convention whose singularity the motion avoids; a coordinate \
                 that carries no mass or inertia also makes M singular",
                self.model.coordinates[fault], self.model.coordinates[fault], y[fault]
            ),
        })
    }
}

/// The workspace of one run's right-hand side.
#[derive(Debug)]
struct Work {
    slots: Vec<f64>,
    m: Vec<f64>,
    b: Vec<f64>,
    /// `m` holds the inverse of a mass matrix that does not change during the run.
    factored: bool,
}

/// How a model's right-hand side is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Evaluation {
    /// The tape compiled to machine code at load ([`tumble_jit`], Cranelift).
    Native,
    /// The tape interpreted instruction by instruction.
    Interpreted,
}

/// A model's first-order system `(q, q̇)' = (q̇, M⁻¹ f)` at fixed parameters.
#[derive(Debug)]
pub struct ModelOde<'a> {
    tape: &'a Tape,
    native: Option<Native>,
    layout: Layout,
    work: RefCell<Work>,
}

impl ModelOde<'_> {
    fn evaluate(&self, t: f64, y: &[f64], w: &mut Work) {
        let inputs = self.tape.inputs();
        if inputs > 0 {
            w.slots[0] = t;
            let m = (inputs - 1).min(y.len());
            w.slots[1..=m].copy_from_slice(&y[..m]);
        }
        match self.native {
            Some(f) => f.run(&mut w.slots),
            None => self.tape.run(&mut w.slots),
        }
    }

    /// `M(q, t)` at `(t, y)`, row-major.
    #[must_use]
    pub fn mass_matrix(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let w = &mut *self.work.borrow_mut();
        self.evaluate(t, y, w);
        let dof = self.layout.dof();
        (0..dof * dof)
            .map(|i| self.tape.output(&w.slots, i))
            .collect()
    }

    /// Writes `(q̇, q̈)` for the state `y = (q, q̇)` into `dy`; NaN accelerations where the mass
    /// matrix is not positive definite (the driver then stops with the state).
    pub fn rhs_slice(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let layout = self.layout;
        let (n, dof, v) = (layout.n, layout.dof(), layout.velocities_at());
        let w = &mut *self.work.borrow_mut();
        self.evaluate(t, y, w);
        let Work {
            slots,
            m,
            b,
            factored,
        } = w;
        for i in 0..dof {
            b[i] = self.tape.output(slots, dof * dof + i);
        }
        // Kinematics: q' = q̇, and R' = R ω̂ for each orientation on SO(3).
        dy[..n].copy_from_slice(&y[v..v + n]);
        for f in 0..layout.so3 {
            let r = n + 9 * f;
            let o = v + n + 3 * f;
            let (wx, wy, wz) = (y[o], y[o + 1], y[o + 2]);
            for a in 0..3 {
                let (r0, r1, r2) = (y[r + 3 * a], y[r + 3 * a + 1], y[r + 3 * a + 2]);
                dy[r + 3 * a] = r1 * wz - r2 * wy;
                dy[r + 3 * a + 1] = r2 * wx - r0 * wz;
                dy[r + 3 * a + 2] = r0 * wy - r1 * wx;
            }
        }
        if *factored {
            for i in 0..dof {
                let row = &m[i * dof..(i + 1) * dof];
                dy[v + i] = row.iter().zip(b.iter()).map(|(a, x)| a * x).sum();
            }
            return;
        }
        for i in 0..dof * dof {
            m[i] = self.tape.output(slots, i);
        }
        if cholesky_solve(m, b, dof) > 0.0 {
            dy[v..v + dof].copy_from_slice(b);
        } else {
            dy[v..v + dof].fill(f64::NAN);
        }
    }
}

impl<const S: usize> Ode<SVector<f64, S>> for ModelOde<'_> {
    fn rhs(&self, t: f64, y: &SVector<f64, S>, dy: &mut SVector<f64, S>) {
        self.rhs_slice(t, y.as_slice(), dy.as_mut_slice());
    }
}
