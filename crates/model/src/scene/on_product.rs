//! A model with several orientations on SO(3) on the product group `SO(3)ᴹ × ℝʸ`
//! ([`ModelProduct`]): as a vector field ([`ProductVectorField`]) for the Lie-group
//! Runge–Kutta methods (`rkmk4`, `cg3`), and as a Lagrangian by its derivatives
//! ([`ProductLagrangian`]) for the variational LGVI on the product and its compositions
//! (`lgvi`, `lgvi4` … `lgvi10`, [`tumble_integrators::rigid::ProductLgvi`]).
//!
//! The model's first-order system on the state `(q, R₁ … R_M, q̇, ω₁ … ω_M)` (each rotation as
//! nine numbers) has `Ṙₖ = Rₖ hat ωₖ` with `ωₖ` the body angular velocity, a state variable:
//! the field's body velocities are `ξₖ = ωₖ`, and its vector part `y = (q, q̇, ω₁ … ω_M)`
//! (`Y = 2n + 3M` numbers) moves by the same system's `(q̇, q̈, ω̇₁ … ω̇_M)` evaluated at the
//! rotations the method hands it. Nothing is asked of the Lagrangian's form (a time-dependent
//! or rotating-frame model integrates as well); the method keeps each `Rₖ` on SO(3) to
//! round-off, where a vector-space method lets the nine numbers drift off it.
//!
//! The Lagrangian's derivatives are one more tape on the model's graph ([`lagrangian_tape`]):
//! the momenta `p = ∂L/∂v` in the velocities `v = (q̇, ω₁ … ω_M)`, the derivative along the
//! configuration `(∂L/∂q, τ₁(L) … τ_M(L))` with `τₖ` the left-trivialized derivative along
//! `Rₖ` ([`Algebra::rotation_derivative`]), the mass matrix `∂²L/∂v²`, and the momenta's
//! derivatives along the configuration (Newton's matrix of the step), all symbolic.

use std::cell::RefCell;

use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::ProblemKind;
use tumble_integrators::rigid::{
    LagrangianJet, ProductLagrangian, ProductState, ProductVectorField,
};
use tumble_scenarios::scene::run_product_rows;
use tumble_scenarios::{Params, Recorder, RunPlan, RunSummary, SceneError};

use super::ModelScene;
use super::ode::ModelOde;
use crate::expr::tape::Tape;
use crate::file::Model;
use crate::mechanics::{Algebra, Layout};

/// The tape of a model's Lagrangian derivatives on the product (see the module doc): the
/// momenta (`D = dof`), the configuration derivative (`D`), the mass matrix (`D²`, row-major)
/// and `∂p_b/∂η_a` (`D²`, row `b`), in the order of
/// [`tumble_integrators::rigid::LagrangianJet`].
pub(super) fn lagrangian_tape(model: &mut Model) -> Tape {
    let layout = model.layout;
    let (n, dof) = (layout.n, layout.dof());
    let eq = &model.equations;
    let g = &mut model.graph;
    let mut out = eq.momenta.clone();
    out.extend_from_slice(&eq.dl_dq);
    for k in 0..layout.so3 {
        out.extend(Algebra { g: &mut *g }.rotation_derivative(eq.lagrangian, layout, k));
    }
    out.extend_from_slice(&eq.mass);
    for b in 0..dof {
        let p = eq.momenta[b];
        for i in 0..n {
            out.push(g.diff(p, layout.q(i)));
        }
        for k in 0..layout.so3 {
            out.extend(Algebra { g: &mut *g }.rotation_derivative(p, layout, k));
        }
    }
    Tape::with_fixed(g, &out, &|k| layout.is_param(k))
}

/// A model with `M` orientations on SO(3) and a state of `S = 2n + 12M` numbers, at one run's
/// parameters, on `SO(3)ᴹ × ℝʸ`, `Y = 2n + 3M` (see the module doc): a vector field (the
/// model's right-hand side, [`ModelOde`]) and a Lagrangian (its derivatives' tape), both
/// allocation-free.
#[derive(Debug)]
pub struct ModelProduct<'a, const M: usize, const S: usize, const Y: usize> {
    ode: ModelOde<'a>,
    layout: Layout,
    lagrangian: &'a Tape,
    /// `lagrangian`'s workspace, the parameters set and its prelude run.
    work: RefCell<Vec<f64>>,
}

impl<'a, const M: usize, const S: usize, const Y: usize> ModelProduct<'a, M, S, Y> {
    /// The model at one run's parameters (`inputs`), or `None` unless it has `M` orientations
    /// on SO(3), `S` state numbers and `Y` of them beside the rotations.
    fn new(
        ode: ModelOde<'a>,
        layout: Layout,
        lagrangian: &'a Tape,
        inputs: &[f64],
    ) -> Option<Self> {
        if !(layout.so3 == M && layout.state_len() == S && S == Y + 9 * M) {
            return None;
        }
        let mut w = lagrangian.workspace();
        let k = inputs.len().min(w.len());
        w[..k].copy_from_slice(&inputs[..k]);
        lagrangian.run_prelude(&mut w);
        Some(ModelProduct {
            ode,
            layout,
            lagrangian,
            work: RefCell::new(w),
        })
    }

    /// The model's state `(q, R₁ … R_M, q̇, ω₁ … ω_M)` of a point of the product.
    #[must_use]
    pub fn flatten(&self, rotations: &[Matrix3<f64>; M], y: &SVector<f64, Y>) -> SVector<f64, S> {
        let n = self.layout.n;
        let mut z = SVector::<f64, S>::zeros();
        let zs = z.as_mut_slice();
        zs[..n].copy_from_slice(&y.as_slice()[..n]);
        for (k, r) in rotations.iter().enumerate() {
            for a in 0..3 {
                for b in 0..3 {
                    zs[n + 9 * k + 3 * a + b] = r[(a, b)];
                }
            }
        }
        zs[n + 9 * M..].copy_from_slice(&y.as_slice()[n..]);
        z
    }

    /// The point of the product of a model state (the inverse of [`Self::flatten`]).
    #[must_use]
    pub fn split(&self, z: &[f64]) -> ProductState<M, Y> {
        let n = self.layout.n;
        let rotations = std::array::from_fn(|k| Matrix3::from_row_slice(&z[n + 9 * k..][..9]));
        let mut vector = SVector::<f64, Y>::zeros();
        let vs = vector.as_mut_slice();
        vs[..n].copy_from_slice(&z[..n]);
        vs[n..].copy_from_slice(&z[n + 9 * M..S]);
        ProductState { rotations, vector }
    }
}

impl<const M: usize, const S: usize, const Y: usize> ProductVectorField<M, Y>
    for ModelProduct<'_, M, S, Y>
{
    fn eval(
        &self,
        t: f64,
        rotations: &[Matrix3<f64>; M],
        y: &SVector<f64, Y>,
    ) -> ([Vector3<f64>; M], SVector<f64, Y>) {
        let n = self.layout.n;
        let z = self.flatten(rotations, y);
        let mut dz = SVector::<f64, S>::zeros();
        self.ode.rhs_slice(t, z.as_slice(), dz.as_mut_slice());
        let omega_at = 2 * n;
        let xi = std::array::from_fn(|k| {
            Vector3::from_column_slice(&y.as_slice()[omega_at + 3 * k..][..3])
        });
        let mut dy = SVector::<f64, Y>::zeros();
        let ds = dy.as_mut_slice();
        ds[..n].copy_from_slice(&dz.as_slice()[..n]);
        ds[n..].copy_from_slice(&dz.as_slice()[n + 9 * M..]);
        (xi, dy)
    }
}

impl<const M: usize, const S: usize, const Y: usize> ProductLagrangian<M, Y>
    for ModelProduct<'_, M, S, Y>
{
    fn jet(
        &self,
        t: f64,
        rotations: &[Matrix3<f64>; M],
        y: &SVector<f64, Y>,
        out: &mut LagrangianJet,
    ) {
        let z = self.flatten(rotations, y);
        let tape = self.lagrangian;
        let mut w = self.work.borrow_mut();
        // The inputs are time, then the state in order (`Layout`).
        w[0] = t;
        let k = S.min(tape.inputs().saturating_sub(1));
        w[1..=k].copy_from_slice(&z.as_slice()[..k]);
        tape.run(&mut w);
        let d = self.layout.dof();
        for i in 0..d {
            out.momenta[i] = tape.output(&w, i);
            out.force[i] = tape.output(&w, d + i);
        }
        for i in 0..d * d {
            out.mass[i] = tape.output(&w, 2 * d + i);
            out.mixed[i] = tape.output(&w, 2 * d + d * d + i);
        }
    }
}

impl ModelScene {
    /// The model on `SO(3)ᴹ × ℝʸ` at `params` ([`ModelProduct`]): `None` unless it has
    /// `M ≥ 2` orientations on SO(3), `S` state numbers and `Y = S − 9M`.
    #[must_use]
    pub fn product<const M: usize, const S: usize, const Y: usize>(
        &self,
        params: &Params,
    ) -> Option<ModelProduct<'_, M, S, Y>> {
        let lagrangian = self.product_lagrangian.as_ref()?;
        (M >= 2)
            .then(|| {
                ModelProduct::new(
                    self.ode(params),
                    self.model.layout,
                    lagrangian,
                    &self.inputs(params),
                )
            })
            .flatten()
    }

    /// Runs a model of `M ≥ 2` orientations on SO(3) (a state of `S` numbers, `Y = S − 9M` of
    /// them beside the rotations): on the product group where the plan's kind is
    /// [`ProblemKind::ProductVectorField`] or [`ProblemKind::ProductLagrangian`], else as
    /// [`ModelScene::run_flat`].
    pub(super) fn run_multi<const S: usize, const M: usize, const Y: usize>(
        &self,
        params: &Params,
        plan: &RunPlan,
        y0: &[f64],
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        if !matches!(
            plan.kind,
            ProblemKind::ProductVectorField | ProblemKind::ProductLagrangian
        ) {
            return self.run_flat::<S>(params, plan, y0, recorder);
        }
        let field = self
            .product::<M, S, Y>(params)
            .ok_or_else(|| SceneError::ModelRefused {
                model: self.info.name.to_string(),
                message: format!(
                    "a state of {} numbers with {} orientations on SO(3) is not the product \
                     SO(3)^{M} × R^{Y}",
                    self.model.layout.state_len(),
                    self.model.layout.so3
                ),
            })?;
        self.check_conditioning(&field.ode, y0)?;
        let columns = self.info.columns().len();
        let energy = 1 + self.display.len();
        let mut row = self.row_writer::<S>(params);
        let s0 = field.split(y0);
        let rows = |t: f64, s: &ProductState<M, Y>, out: &mut [f64]| {
            row(t, &field.flatten(&s.rotations, &s.vector), out);
        };
        run_product_rows(&field, s0, plan, columns, energy, rows, recorder)
    }
}
