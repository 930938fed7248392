//! Routing a run: the plan's kind of problem chooses the first-order system, its Taylor
//! series or a Lie-group method ([`super::on_group`]); every route writes the same rows.

use nalgebra::SVector;
use tumble_integrators::ProblemKind;
use tumble_scenarios::scene::{run_taylor_vector, run_vector};
use tumble_scenarios::{Params, Recorder, RunPlan, RunSummary, SceneError};

use super::ModelScene;

/// Whether a kind of problem is one of the Lie-group methods'.
fn on_group(kind: ProblemKind) -> bool {
    matches!(
        kind,
        ProblemKind::RigidBody
            | ProblemKind::FreeRigidBody
            | ProblemKind::LieVectorField
            | ProblemKind::CoupledRigidBody
    )
}

impl ModelScene {
    /// Runs a model of at most one orientation on SO(3) (a state of `S ≤ 18` numbers): on the
    /// group where the plan's method is a Lie-group method, else as [`ModelScene::run_flat`].
    pub(super) fn run<const S: usize>(
        &self,
        params: &Params,
        plan: &RunPlan,
        y0: &[f64],
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        if !on_group(plan.kind) {
            return self.run_flat::<S>(params, plan, y0, recorder);
        }
        let ode = self.ode(params);
        self.check_conditioning(&ode, y0)?;
        let columns = self.info.columns().len();
        let energy = 1 + self.display.len();
        let row = self.row_writer::<S>(params);
        self.run_on_group(params, plan, y0, (columns, energy), row, recorder)
    }

    /// Runs the first-order system `y' = F(t, y)` of the state `(q, R₁ … R_k, q̇, ω₁ … ω_k)`
    /// (each rotation as nine numbers) with the plan's vector-space method: an explicit pair,
    /// Gauss–Legendre and its compositions, or the Taylor methods (`taylor`, and `taylor-dd` in
    /// double-double). A Lie-group method reaching
    /// here (a model with several orientations on SO(3)) is refused with why.
    pub(super) fn run_flat<const S: usize>(
        &self,
        params: &Params,
        plan: &RunPlan,
        y0: &[f64],
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        if on_group(plan.kind) {
            return Err(SceneError::ModelRefused {
                model: self.info.name.to_string(),
                message: format!(
                    "`{}` is a Lie-group method: {}; applicable: {}",
                    plan.integrator(),
                    self.not_on_group.as_deref().unwrap_or_default(),
                    self.info.applicable()
                ),
            });
        }
        let ode = self.ode(params);
        self.check_conditioning(&ode, y0)?;
        let columns = self.info.columns().len();
        let energy = 1 + self.display.len();
        let row = self.row_writer::<S>(params);
        let y = SVector::<f64, S>::from_column_slice(y0);
        if matches!(
            plan.kind,
            ProblemKind::TaylorSeries | ProblemKind::DoubleDoubleTaylorSeries
        ) {
            let taylor = self.taylor(params);
            run_taylor_vector(&taylor, y, plan, columns, energy, row, &mut [], recorder)
        } else {
            run_vector(&ode, y, plan, columns, energy, row, &mut [], recorder)
        }
    }

    /// What writes a row from `(t, y)` at `params`: `t`, the shown state (a quaternion and body
    /// angular velocity for each orientation on SO(3), the coordinates and rates), the energy
    /// function, then the momenta of the cyclic coordinates and the outputs (the energy's
    /// relative error, between them, is the driver's). Its workspace is allocated here, once.
    pub(super) fn row_writer<const S: usize>(
        &self,
        params: &Params,
    ) -> impl FnMut(f64, &SVector<f64, S>, &mut [f64]) + '_ {
        let layout = self.model.layout;
        let state = layout.state_len();
        let shown = self.display.len();
        let mut row_w = self.row.workspace();
        let inputs = self.inputs(params);
        let k = inputs.len().min(row_w.len());
        row_w[..k].copy_from_slice(&inputs[..k]);
        self.row.run_prelude(&mut row_w);
        let row_tape = &self.row;
        let display = &self.display;
        let mut previous = vec![None; layout.so3];
        move |t: f64, y: &SVector<f64, S>, out: &mut [f64]| {
            out[0] = t;
            display.write(layout, y.as_slice(), &mut previous, &mut out[1..=shown]);
            let inputs = row_tape.inputs();
            if inputs > 0 {
                row_w[0] = t;
                let m = (inputs - 1).min(state);
                row_w[1..=m].copy_from_slice(&y.as_slice()[..m]);
            }
            row_tape.run(&mut row_w);
            out[1 + shown] = row_tape.output(&row_w, 0);
            for i in 1..row_tape.outputs() {
                out[2 + shown + i] = row_tape.output(&row_w, i);
            }
        }
    }
}
