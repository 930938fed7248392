//! Routing a run: the plan's kind of problem chooses the first-order system, its Taylor
//! series or a Lie-group method ([`super::on_group`]); every route writes the same rows.

use nalgebra::SVector;
use tumble_integrators::ProblemKind;
use tumble_scenarios::scene::{run_taylor_vector, run_vector};
use tumble_scenarios::{Params, Recorder, RunPlan, RunSummary, SceneError};

use super::ModelScene;

impl ModelScene {
    pub(super) fn run<const S: usize>(
        &self,
        params: &Params,
        plan: &RunPlan,
        y0: &[f64],
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let ode = self.ode(params);
        self.check_conditioning(&ode, y0)?;
        let layout = self.model.layout;
        let state = layout.state_len();
        let shown = self.display.len();
        let columns = self.info.columns().len();
        let mut row_w = self.row.workspace();
        let inputs = self.inputs(params);
        let k = inputs.len().min(row_w.len());
        row_w[..k].copy_from_slice(&inputs[..k]);
        self.row.run_prelude(&mut row_w);
        let row_tape = &self.row;
        let display = &self.display;
        let mut previous = vec![None; layout.so3];
        let row = move |t: f64, y: &SVector<f64, S>, out: &mut [f64]| {
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
        };
        if matches!(
            plan.kind,
            ProblemKind::RigidBody
                | ProblemKind::FreeRigidBody
                | ProblemKind::LieVectorField
                | ProblemKind::CoupledRigidBody
        ) {
            return self.run_on_group(params, plan, y0, (columns, 1 + shown), row, recorder);
        }
        let y = SVector::<f64, S>::from_column_slice(y0);
        if plan.kind == ProblemKind::TaylorSeries {
            let taylor = self.taylor(params);
            run_taylor_vector(&taylor, y, plan, columns, 1 + shown, row, &mut [], recorder)
        } else {
            run_vector(&ode, y, plan, columns, 1 + shown, row, &mut [], recorder)
        }
    }
}
