//! A model's first-order system `(q, q̇)' = (q̇, M⁻¹ f)` ([`ModelOde`]): the tape evaluated
//! natively or interpreted, a constant mass matrix inverted once per run, and the refusal of
//! an initial state where the mass matrix is singular or ill-conditioned.

use std::cell::RefCell;

use nalgebra::SVector;
use tumble_integrators::Ode;
use tumble_scenarios::{Params, SceneError};

use super::ModelScene;
use crate::expr::tape::Tape;
use crate::mechanics::Layout;
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
        let layout = self.model.layout;
        self.flow
            .compile(&state_args(&self.flow, layout), layout.state_len())
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
        let inputs = self.inputs(params);
        let prepared = |tape: &Tape| {
            let mut w = tape.workspace();
            let k = inputs.len().min(w.len());
            w[..k].copy_from_slice(&inputs[..k]);
            tape.run_prelude(&mut w);
            w
        };
        let (slots, mass) = (prepared(&self.flow), prepared(&self.rhs));
        let state = layout.state_len();
        // The pivots of a mass matrix of the parameters alone are results of the prelude:
        // checked here once; others after each evaluation.
        let pivots = state..state + layout.dof();
        let (pivots, positive) = if self.constant_mass {
            let positive = pivots.clone().all(|j| self.flow.output(&slots, j) > 0.0);
            (state..state, positive)
        } else {
            (pivots, true)
        };
        ModelOde {
            tape: &self.flow,
            mass: &self.rhs,
            native: match evaluation {
                Evaluation::Native => self.native,
                Evaluation::Interpreted => None,
            },
            layout,
            pivots,
            positive,
            work: RefCell::new(Work { slots, mass }),
        }
    }

    /// The equations at `params` as a system computing its Taylor coefficients (Taylor-mode
    /// automatic differentiation on the tape, [`crate::taylor`]), its storage allocated here:
    /// on the mass-matrix-and-forces tape for a model of scalar coordinates, on the
    /// first-order tape (the state `(q, R, q̇, ω)` as [`ModelScene::ode`]'s) for a model with an
    /// orientation on SO(3).
    #[must_use]
    pub fn taylor(&self, params: &Params) -> ModelTaylor<'_> {
        let layout = self.model.layout;
        if layout.so3 == 0 {
            ModelTaylor::new(&self.rhs, &self.taylor, layout.n, self.inputs(params))
        } else {
            ModelTaylor::first_order(
                &self.flow,
                &self.taylor,
                layout.state_len(),
                layout.dof(),
                self.inputs(params),
            )
        }
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

/// The workspaces of one run's right-hand side and of its mass matrix.
#[derive(Debug)]
struct Work {
    slots: Vec<f64>,
    mass: Vec<f64>,
}

/// How a model's right-hand side is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Evaluation {
    /// The tape compiled to machine code at load ([`tumble_jit`], Cranelift).
    Native,
    /// The tape interpreted instruction by instruction.
    Interpreted,
}

/// The arguments of a model's compiled right-hand side: its state `y`, inputs `1 ..` of the
/// tape (the ones it has).
pub(super) fn state_args(flow: &Tape, layout: Layout) -> Vec<u32> {
    (1..=layout.state_len() as u32)
        .take_while(|&k| (k as usize) < flow.inputs())
        .collect()
}

/// A model's first-order system `(q, q̇)' = (q̇, M⁻¹ f)` at fixed parameters.
#[derive(Debug)]
pub struct ModelOde<'a> {
    /// `y'` then the pivots ([`first_order`]).
    tape: &'a Tape,
    /// Mass matrix then forces.
    mass: &'a Tape,
    native: Option<Native>,
    layout: Layout,
    /// The outputs of `tape` that are pivots to check after each evaluation (none for a
    /// mass matrix of the parameters alone).
    pivots: std::ops::Range<usize>,
    /// Whether the pivots checked once per run were positive.
    positive: bool,
    work: RefCell<Work>,
}

impl ModelOde<'_> {
    /// Outputs `range` of the mass matrix and forces' tape at `(t, y)`.
    fn mass_outputs(&self, t: f64, y: &[f64], range: std::ops::Range<usize>) -> Vec<f64> {
        let w = &mut self.work.borrow_mut().mass;
        let inputs = self.mass.inputs();
        if inputs > 0 {
            w[0] = t;
            let m = (inputs - 1).min(y.len());
            w[1..=m].copy_from_slice(&y[..m]);
        }
        self.mass.run(w);
        range.map(|i| self.mass.output(w, i)).collect()
    }

    /// `M(q, t)` at `(t, y)`, row-major.
    #[must_use]
    pub fn mass_matrix(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let dof = self.layout.dof();
        self.mass_outputs(t, y, 0..dof * dof)
    }

    /// The generalized forces `f` of `M v̇ = f` at `(t, y)` ([`crate::mechanics::Equations`]).
    #[must_use]
    pub fn forces(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let dof = self.layout.dof();
        self.mass_outputs(t, y, dof * dof..dof * dof + dof)
    }

    /// Writes `(q̇, q̈)` for the state `y = (q, q̇)` into `dy`; NaN accelerations where the mass
    /// matrix is not positive definite (the driver then stops with the state).
    pub fn rhs_slice(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let w = &mut self.work.borrow_mut().slots;
        let tape = self.tape;
        let state = self.layout.state_len();
        // Input 0 is time; the state's inputs follow (`state_args`).
        let inputs = tape.inputs();
        if inputs > 0 {
            w[0] = t;
        }
        match self.native {
            Some(f) => f.run(w, y, dy),
            None => {
                let m = inputs.saturating_sub(1).min(state);
                w[1..=m].copy_from_slice(&y[..m]);
                tape.run(w);
                for (i, d) in dy[..state].iter_mut().enumerate() {
                    *d = tape.output(w, i);
                }
            }
        }
        if !self.positive || self.pivots.clone().any(|j| !(tape.output(w, j) > 0.0)) {
            let v = self.layout.velocities_at();
            dy[v..state].fill(f64::NAN);
        }
    }
}

impl<const S: usize> Ode<SVector<f64, S>> for ModelOde<'_> {
    fn rhs(&self, t: f64, y: &SVector<f64, S>, dy: &mut SVector<f64, S>) {
        self.rhs_slice(t, y.as_slice(), dy.as_mut_slice());
    }
}
