//! A model as a scene: [`ModelScene`] implements [`tumble_scenarios::Scene`], so that every
//! command, sweep and study that runs a built-in scene runs a model file, with the methods of
//! the first-order kind ([`ProblemKind::Ode`]: the explicit pairs, `rk4`, Gauss–Legendre and
//! its compositions) and the Taylor methods ([`ProblemKind::TaylorSeries`]: coefficients by
//! automatic differentiation on the tape, [`crate::taylor`]).
//!
//! The state is `(q, q̇)`; each evaluation of the right-hand side runs one instruction tape
//! ([`crate::expr::tape`]) in a workspace allocated once per run: the forces, the kinematics
//! and the solve of `M q̈ = f` by Cholesky written out on the graph
//! ([`crate::mechanics::first_order`]; a mass matrix of the parameters alone is inverted in
//! the tape's prelude, once per run), compiled to native code where the machine has a code
//! generator, reading the state and writing its derivative directly.
//!
//! Rows: `t`, the coordinates, their rates, `energy` (the energy function
//! `h = Σ q̇ᵢ ∂L/∂q̇ᵢ − L`: the energy, or the Jacobi integral of a driven or rotating model),
//! `energy_rel_err`, the momentum `p_NAME` of each cyclic coordinate, then the model's outputs.
//!
//! [`Scene::info`] returns `&'static SceneInfo`: a model's info (and the names in it) is leaked
//! once per distinct model text loaded ([`load`] and [`from_text`] keep one scene per text), so
//! that a model is a scene like any other for as long as the program runs.

use std::cell::RefCell;
use std::collections::HashMap;
use std::path::Path;
use std::sync::{Mutex, OnceLock};

use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::rigid::{
    CoupledState, RigidBody, RigidBodyState, coupled_state_from_velocities, coupled_velocities,
};
use tumble_integrators::{Ode, ProblemKind};
use tumble_scenarios::scene::{
    continuous_quaternion, run_coupled_rows, run_rigid_rows, run_taylor_vector, run_vector,
};
use tumble_scenarios::{
    ParamSpec, Params, Recorder, RunPlan, RunSummary, Scene, SceneError, SceneInfo,
};

use crate::expr::tape::Tape;
use crate::expr::taylor::TaylorPlan;
use crate::file::{Model, ModelFileError};
use crate::group::{Group, ModelCoupled, ModelRigidBody};
use crate::mechanics::{Layout, first_order};
use crate::taylor::ModelTaylor;
use tumble_jit::{JitError, Native};

/// The largest condition number of the mass matrix accepted at the initial state.
pub const MAX_CONDITION: f64 = 1e10;

/// A model file as a scene.
#[derive(Debug)]
pub struct ModelScene {
    info: &'static SceneInfo,
    model: Model,
    /// Mass matrix (row-major) then forces: the Taylor recursions' tape, and the mass matrix
    /// of [`ModelOde::mass_matrix`].
    rhs: Tape,
    /// The first-order right-hand side `y'` (the state's length), then the pivots of the
    /// mass matrix's Cholesky factorization ([`first_order`]).
    flow: Tape,
    /// `flow`'s body as native code, where the machine has a code generator: the state as its
    /// arguments, `y'` as its results, the pivots stored in the workspace.
    native: Option<Native>,
    /// Whether the mass matrix depends on the parameters only (a body on SO(3) with no
    /// coordinates: its inertia): then it is factored once per run, in `flow`'s prelude.
    constant_mass: bool,
    /// Energy, momenta of the cyclic coordinates, outputs.
    row: Tape,
    /// Initial coordinates then rates (of the parameters).
    init: Tape,
    /// Every momentum (for [`ModelScene::momenta`]).
    momenta: Tape,
    /// The series recursions of `rhs` ([`crate::taylor`]); none for a model with an
    /// orientation on SO(3), whose kinematics `Ṙ = R ω̂` the recursions do not cover.
    taylor: Option<TaylorPlan>,
    /// Names of the displayed coordinates and rates (quaternions and body angular velocities
    /// for the orientations on SO(3), then the scalar coordinates and their rates).
    display: Display,
    /// The tapes of the Lie-group methods ([`crate::group`]), for a model with one orientation
    /// on SO(3).
    group: Option<Group>,
    /// Why the Lie-group methods are not offered, when they are not.
    not_on_group: Option<String>,
}

/// The kinds of problem of a model with one orientation on SO(3) and no other coordinate,
/// torque-free: as the built-in `free-body`.
const FREE_BODY: &[ProblemKind] = &[
    ProblemKind::FreeRigidBody,
    ProblemKind::RigidBody,
    ProblemKind::LieVectorField,
    ProblemKind::Ode,
];

/// … in a potential: as the built-in `heavy-top`.
const RIGID_BODY: &[ProblemKind] = &[
    ProblemKind::RigidBody,
    ProblemKind::LieVectorField,
    ProblemKind::Ode,
];

/// … coupled to scalar coordinates: as the built-in `free-hoop`.
const COUPLED: &[ProblemKind] = &[ProblemKind::CoupledRigidBody, ProblemKind::Ode];

/// The inputs of a model's tapes at `values` (the parameters in order): time, coordinates and
/// rates zero.
fn inputs_at(model: &Model, values: impl Iterator<Item = f64>) -> Vec<f64> {
    let layout = model.layout;
    let mut inputs = vec![0.0; layout.param(model.params.len()) as usize];
    for (j, value) in values.enumerate() {
        inputs[layout.param(j) as usize] = value;
    }
    inputs
}

/// The Lie-group kinds a model offers at its default parameters, or why it offers none.
fn group_problems(model: &Model, group: Option<&Group>) -> Result<&'static [ProblemKind], String> {
    let Some(group) = group else {
        return Err(if model.layout.so3 == 0 {
            "the Lie-group methods need an orientation on SO(3) (a frame with \
             `orientation = \"so3\"`)"
                .into()
        } else {
            "the Lie-group methods take one orientation on SO(3)".into()
        });
    };
    let template = inputs_at(model, model.params.iter().map(|p| p.default));
    if let Some(why) = group.misfit(&template) {
        return Err(format!("the Lie-group methods do not apply: {why}"));
    }
    if model.layout.n > 0 {
        return Ok(COUPLED);
    }
    let body = ModelRigidBody::new(group, &template)
        .map_err(|why| format!("the Lie-group methods do not apply: {why}"))?;
    Ok(if body.is_free() {
        FREE_BODY
    } else {
        RIGID_BODY
    })
}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

impl ModelScene {
    /// The scene of a parsed model.
    #[must_use]
    pub fn new(mut model: Model) -> Self {
        let group = (model.layout.so3 == 1).then(|| Group::new(&mut model));
        let on_group = group_problems(&model, group.as_ref());
        let layout = model.layout;
        let n = layout.n;
        let fixed = move |k: u32| layout.is_param(k);
        let constant_mass = model
            .equations
            .mass
            .iter()
            .all(|&id| !model.graph.depends_on(id, &|k| !layout.is_param(k)));
        let system = first_order(&mut model.graph, &model.equations, layout, constant_mass);
        let mut flow_out = system.derivative;
        flow_out.extend(system.pivots);
        let flow = Tape::with_fixed(&model.graph, &flow_out, &fixed);
        let native = flow
            .compile(&state_args(&flow, layout), layout.state_len())
            .ok();
        let eq = &model.equations;
        let (cyclic, autonomous) = symmetries(&model);
        let mut outputs = eq.mass.clone();
        outputs.extend_from_slice(&eq.force);
        let rhs = Tape::with_fixed(&model.graph, &outputs, &fixed);
        let taylor = (layout.so3 == 0).then(|| TaylorPlan::new(&rhs, 1 + 2 * n));
        let display = Display::of(&model);
        let mut row_out = vec![eq.energy];
        let mut diagnostics = vec![leak("energy".into()), leak("energy_rel_err".into())];
        let mut conserved = Vec::new();
        if autonomous {
            conserved.push(leak(
                "energy function h = sum(q_dot dL/dq_dot) - L (energy, or Jacobi integral)".into(),
            ));
        }
        for i in 0..n {
            if cyclic[i] {
                row_out.push(eq.momenta[i]);
                let name = format!("p_{}", model.coordinates[i]);
                conserved.push(leak(format!(
                    "{name} (momentum of the cyclic coordinate {}, at the default parameters)",
                    model.coordinates[i]
                )));
                diagnostics.push(leak(name));
            }
        }
        for (name, id) in &model.outputs {
            row_out.push(*id);
            diagnostics.push(leak(name.clone()));
        }
        let row = Tape::with_fixed(&model.graph, &row_out, &fixed);
        // The initial state in state order: coordinates, rotations, rates, angular velocities.
        let mut init_out = model.initial.clone();
        for o in &model.orientations {
            init_out.extend(o.initial_rotation.iter().flatten());
        }
        init_out.extend_from_slice(&model.initial_rates);
        for o in &model.orientations {
            init_out.extend_from_slice(&o.initial_omega);
        }
        let init = Tape::new(&model.graph, &init_out);
        let momenta = Tape::new(&model.graph, &eq.momenta);
        let parameters: Vec<ParamSpec> = model
            .params
            .iter()
            .map(|p| ParamSpec {
                name: leak(p.name.clone()),
                default: p.default,
                unit: leak(p.unit.clone()),
                description: leak(p.description.clone()),
                domain: p.domain,
            })
            .collect();
        let coordinates: Vec<&'static str> = display
            .coordinates
            .iter()
            .map(|c| leak(c.clone()))
            .collect();
        let rate_names: Vec<&'static str> = display.rates.iter().map(|c| leak(c.clone())).collect();
        let info = Box::leak(Box::new(SceneInfo {
            name: leak(model.name.clone()),
            summary: leak(if model.summary.is_empty() {
                format!("model file {}", model.origin)
            } else {
                model.summary.clone()
            }),
            coordinates: Box::leak(coordinates.into_boxed_slice()),
            parameters: Box::leak(parameters.into_boxed_slice()),
            conserved: Box::leak(conserved.into_boxed_slice()),
            oracle: leak(format!("model file {}", model.origin)),
            problems: match (&on_group, &taylor) {
                (Ok(kinds), _) => kinds,
                (Err(_), Some(_)) => &[ProblemKind::Ode, ProblemKind::TaylorSeries],
                (Err(_), None) => &[ProblemKind::Ode],
            },
            needs_dense_output: false,
            default_integrator: leak(model.run.integrator.clone()),
            default_step: model.run.dt,
            // Not measured: a model has no reference solution of its own.
            default_error: f64::NAN,
            default_t_end: model.run.t_end,
            diagnostics: Box::leak(diagnostics.into_boxed_slice()),
            rate_names: if layout.so3 == 0 {
                &[]
            } else {
                Box::leak(rate_names.into_boxed_slice())
            },
            not_on_group: on_group.as_ref().err().map_or("", |why| leak(why.clone())),
        }));
        ModelScene {
            info,
            model,
            rhs,
            flow,
            native,
            constant_mass,
            row,
            init,
            momenta,
            taylor,
            display,
            group,
            not_on_group: on_group.err(),
        }
    }

    /// The model as a rigid body at `params` ([`ModelRigidBody`]): `None` unless its only
    /// coordinate is an orientation on SO(3) and the Lie-group methods apply.
    #[must_use]
    pub fn rigid_body(&self, params: &Params) -> Option<ModelRigidBody<'_>> {
        let group = self.group.as_ref()?;
        let template = self.inputs(params);
        if self.model.layout.n != 0 || group.misfit(&template).is_some() {
            return None;
        }
        ModelRigidBody::new(group, &template).ok()
    }

    /// The model as a rigid body coupled to its `N` scalar coordinates at `params`
    /// ([`ModelCoupled`]): `None` unless it has `N` of them beside one orientation on SO(3)
    /// and the Lie-group methods apply.
    #[must_use]
    pub fn coupled<const N: usize>(&self, params: &Params) -> Option<ModelCoupled<'_, N>> {
        let group = self.group.as_ref()?;
        let template = self.inputs(params);
        if N == 0 || self.model.layout.n != N || group.misfit(&template).is_some() {
            return None;
        }
        Some(ModelCoupled::new(group, &template))
    }

    /// Why the Lie-group methods (LGVI, Lie–Gauss, RKMK, …) do not run this model, or `None`
    /// when they do.
    #[must_use]
    pub fn not_on_group(&self) -> Option<&str> {
        self.not_on_group.as_deref()
    }

    /// The model.
    #[must_use]
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Instructions per right-hand-side evaluation (the body of its tape).
    #[must_use]
    pub fn rhs_instructions(&self) -> usize {
        self.flow.len()
    }

    /// The inputs of the model's tapes at `params`: time, coordinates and rates zero.
    fn inputs(&self, params: &Params) -> Vec<f64> {
        inputs_at(&self.model, params.iter().map(|(_, value)| value))
    }

    /// The initial state `(q, q̇)` at `params`.
    #[must_use]
    pub fn initial_state(&self, params: &Params) -> Vec<f64> {
        let mut w = self.init.workspace();
        self.init.run_all(&mut w, &self.inputs(params));
        (0..self.init.outputs())
            .map(|i| self.init.output(&w, i))
            .collect()
    }

    /// The momenta `∂L/∂q̇` at `(t, q, q̇)` and `params`.
    #[must_use]
    pub fn momenta(&self, params: &Params, t: f64, state: &[f64]) -> Vec<f64> {
        let mut inputs = self.inputs(params);
        inputs[0] = t;
        inputs[1..=state.len()].copy_from_slice(state);
        let mut w = self.momenta.workspace();
        self.momenta.run_all(&mut w, &inputs);
        (0..self.momenta.outputs())
            .map(|i| self.momenta.output(&w, i))
            .collect()
    }

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
    fn check_conditioning(&self, ode: &ModelOde<'_>, y: &[f64]) -> Result<(), SceneError> {
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

    fn run<const S: usize>(
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
        match (plan.kind, self.taylor(params)) {
            (ProblemKind::TaylorSeries, Some(taylor)) => {
                run_taylor_vector(&taylor, y, plan, columns, 1 + shown, row, &mut [], recorder)
            }
            _ => run_vector(&ode, y, plan, columns, 1 + shown, row, &mut [], recorder),
        }
    }

    /// Runs a Lie-group method ([`crate::group`]) from the state `y0` (coordinates, rotation,
    /// rates, angular velocity), writing rows with `row` from the same state again;
    /// `(columns, energy column)` as for [`run_vector`].
    fn run_on_group<const S: usize, F>(
        &self,
        params: &Params,
        plan: &RunPlan,
        y0: &[f64],
        (columns, energy): (usize, usize),
        mut row: F,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError>
    where
        F: FnMut(f64, &SVector<f64, S>, &mut [f64]),
    {
        let refuse = |message: String| SceneError::ModelRefused {
            model: self.info.name.to_string(),
            message,
        };
        let group = self
            .group
            .as_ref()
            .ok_or_else(|| refuse(self.not_on_group.clone().unwrap_or_default()))?;
        let template = self.inputs(params);
        if let Some(why) = group.misfit(&template) {
            return Err(refuse(format!(
                "`{}` is a Lie-group method, which does not apply at these parameters: {why}; \
                 use gauss8 or an explicit pair (vern9)",
                plan.integrator()
            )));
        }
        let layout = self.model.layout;
        let v = layout.velocities_at();
        let rotation = |y: &[f64], n: usize| Matrix3::from_row_slice(&y[n..n + 9]);
        match layout.n {
            0 => {
                let body = ModelRigidBody::new(group, &template).map_err(refuse)?;
                if plan.kind == ProblemKind::FreeRigidBody && !body.is_free() {
                    return Err(refuse(format!(
                        "`{}` integrates a torque-free body, and the potential does not vanish \
                         at these parameters; use lgvi, its compositions or rkmk4",
                        plan.integrator()
                    )));
                }
                let omega = Vector3::from_column_slice(&y0[v..v + 3]);
                let s0 = RigidBodyState {
                    rotation: rotation(y0, 0),
                    momentum: body.body().inertia() * omega,
                };
                let free = body.is_free().then(|| *body.body());
                let mut y = SVector::<f64, S>::zeros();
                let rows = |t: f64, s: &RigidBodyState, out: &mut [f64]| {
                    set_rotation(y.as_mut_slice(), 0, &s.rotation);
                    let omega = body.body().omega(&s.momentum);
                    y.as_mut_slice()[v..v + 3].copy_from_slice(omega.as_slice());
                    row(t, &y, out);
                };
                run_rigid_rows(
                    &body,
                    free.as_ref(),
                    s0,
                    plan,
                    columns,
                    energy,
                    rows,
                    recorder,
                )
            }
            1 => {
                run_coupled::<1, S, F>(group, &template, y0, plan, (columns, energy), row, recorder)
            }
            2 => {
                run_coupled::<2, S, F>(group, &template, y0, plan, (columns, energy), row, recorder)
            }
            _ => {
                run_coupled::<3, S, F>(group, &template, y0, plan, (columns, energy), row, recorder)
            }
        }
    }

    /// The state `(t, y)` of a row of this scene's CSV (`t`, the displayed coordinates and
    /// rates first): quaternions become rotation matrices again.
    #[must_use]
    pub fn state_of_row(&self, row: &[f64]) -> Vec<f64> {
        let layout = self.model.layout;
        let mut out = vec![0.0; 1 + layout.state_len()];
        out[0] = row[0];
        self.display.read(layout, &row[1..], &mut out[1..]);
        out
    }
}

/// Writes `rotation` by rows into `y` from index `at`.
fn set_rotation(y: &mut [f64], at: usize, rotation: &Matrix3<f64>) {
    for a in 0..3 {
        for b in 0..3 {
            y[at + 3 * a + b] = rotation[(a, b)];
        }
    }
}

/// Runs a model with `N` scalar coordinates beside its orientation on SO(3) as a coupled rigid
/// body ([`ModelCoupled`]) from `y0`, rows as in [`ModelScene::run_on_group`].
fn run_coupled<const N: usize, const S: usize, F>(
    group: &Group,
    template: &[f64],
    y0: &[f64],
    plan: &RunPlan,
    (columns, energy): (usize, usize),
    mut row: F,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    F: FnMut(f64, &SVector<f64, S>, &mut [f64]),
{
    let model = ModelCoupled::<N>::new(group, template);
    let v = N + 9;
    let s0 = coupled_state_from_velocities(
        &model,
        &Matrix3::from_row_slice(&y0[N..N + 9]),
        &Vector3::from_column_slice(&y0[v + N..v + N + 3]),
        &SVector::from_column_slice(&y0[..N]),
        &SVector::from_column_slice(&y0[v..v + N]),
    );
    let mut y = SVector::<f64, S>::zeros();
    let rows = |t: f64, s: &CoupledState<N>, out: &mut [f64]| {
        let (omega, qdot) = coupled_velocities(&model, &s.q, &s.momentum, &s.p)
            .unwrap_or((Vector3::repeat(f64::NAN), SVector::repeat(f64::NAN)));
        let ys = y.as_mut_slice();
        ys[..N].copy_from_slice(s.q.as_slice());
        set_rotation(ys, N, &s.rotation);
        ys[v..v + N].copy_from_slice(qdot.as_slice());
        ys[v + N..v + N + 3].copy_from_slice(omega.as_slice());
        row(t, &y, out);
    };
    run_coupled_rows(&model, s0, plan, columns, energy, rows, recorder)
}

/// How a model's state is shown in its rows: each orientation on SO(3) as a unit quaternion
/// (sign continuous along the run) and its body angular velocity, the scalar coordinates and
/// rates as they are.
#[derive(Debug, Clone)]
struct Display {
    coordinates: Vec<String>,
    rates: Vec<String>,
}

impl Display {
    fn of(model: &Model) -> Self {
        let single = model.orientations.len() == 1;
        let prefix = |name: &str| {
            if single {
                String::new()
            } else {
                format!("{name}_")
            }
        };
        let mut coordinates = Vec::new();
        let mut rates = Vec::new();
        for o in &model.orientations {
            let p = prefix(&o.name);
            coordinates.extend(["qw", "qx", "qy", "qz"].map(|c| format!("{p}{c}")));
            rates.extend(["omega_x", "omega_y", "omega_z"].map(|c| format!("{p}{c}")));
        }
        coordinates.extend(model.coordinates.iter().cloned());
        rates.extend(model.coordinates.iter().map(|c| format!("{c}_dot")));
        Display { coordinates, rates }
    }

    /// Number of values shown.
    fn len(&self) -> usize {
        self.coordinates.len() + self.rates.len()
    }

    /// Writes the shown values of the state `y` into `out`.
    fn write(
        &self,
        layout: Layout,
        y: &[f64],
        previous: &mut [Option<nalgebra::Quaternion<f64>>],
        out: &mut [f64],
    ) {
        let (n, k, v) = (layout.n, layout.so3, layout.velocities_at());
        for f in 0..k {
            let r = nalgebra::Matrix3::from_row_slice(&y[n + 9 * f..n + 9 * f + 9]);
            let q = continuous_quaternion(&r, &mut previous[f]);
            out[4 * f..4 * f + 4].copy_from_slice(&[q.w, q.i, q.j, q.k]);
        }
        out[4 * k..4 * k + n].copy_from_slice(&y[..n]);
        let base = 4 * k + n;
        out[base..base + 3 * k].copy_from_slice(&y[v + n..v + n + 3 * k]);
        out[base + 3 * k..base + 3 * k + n].copy_from_slice(&y[v..v + n]);
    }

    /// The state `y` of shown values (the inverse of [`Display::write`]).
    fn read(&self, layout: Layout, shown: &[f64], y: &mut [f64]) {
        let (n, k, v) = (layout.n, layout.so3, layout.velocities_at());
        for f in 0..k {
            let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                shown[4 * f],
                shown[4 * f + 1],
                shown[4 * f + 2],
                shown[4 * f + 3],
            ));
            let r = q.to_rotation_matrix();
            for a in 0..3 {
                for b in 0..3 {
                    y[n + 9 * f + 3 * a + b] = r[(a, b)];
                }
            }
        }
        y[..n].copy_from_slice(&shown[4 * k..4 * k + n]);
        let base = 4 * k + n;
        y[v + n..v + n + 3 * k].copy_from_slice(&shown[base..base + 3 * k]);
        y[v..v + n].copy_from_slice(&shown[base + 3 * k..base + 3 * k + n]);
    }
}

/// Which coordinates are cyclic and whether the Lagrangian is autonomous, by evaluating
/// `∂L/∂qᵢ` and `∂L/∂t` at sample states (coordinates and rates in ±1.5, `t` in [0, 3]) at the
/// default parameters: a derivative that vanishes symbolically, or to round-off
/// (`≤ 1e-12 · (1 + |L|)`) at every sample (where it cancels only after simplification, as
/// `sin² + cos²` does), marks a symmetry. The samples are fixed, so the answer is reproducible.
fn symmetries(model: &Model) -> (Vec<bool>, bool) {
    let eq = &model.equations;
    let n = model.layout.n;
    let mut outputs = eq.dl_dq.clone();
    outputs.push(eq.dl_dt);
    outputs.push(eq.lagrangian);
    let tape = Tape::new(&model.graph, &outputs);
    let mut w = tape.workspace();
    let mut inputs = vec![0.0; model.layout.param(model.params.len()) as usize];
    for (j, p) in model.params.iter().enumerate() {
        inputs[model.layout.param(j) as usize] = p.default;
    }
    let mut cyclic: Vec<bool> = eq.dl_dq.iter().map(|_| true).collect();
    let mut autonomous = true;
    // A fixed low-discrepancy sequence (golden-ratio steps) over the state.
    let mut x = std::f64::consts::FRAC_1_PI;
    let mut next = || {
        x = (x + 0.618_033_988_749_894_9).fract();
        x
    };
    for _ in 0..8 {
        inputs[0] = 3.0 * next();
        for k in 0..model.layout.state_len() {
            inputs[1 + k] = 3.0 * next() - 1.5;
        }
        tape.run_all(&mut w, &inputs);
        let scale = 1e-12 * (1.0 + tape.output(&w, n + 1).abs());
        for i in 0..n {
            let d = tape.output(&w, i);
            cyclic[i] &= d.abs() <= scale;
        }
        autonomous &= tape.output(&w, n).abs() <= scale;
    }
    (cyclic, autonomous)
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
fn state_args(flow: &Tape, layout: Layout) -> Vec<u32> {
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

impl Scene for ModelScene {
    fn info(&self) -> &'static SceneInfo {
        self.info
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let y0 = self.initial_state(params);
        if let Some(i) = y0.iter().position(|x| !x.is_finite()) {
            let layout = self.model.layout;
            let (n, v) = (layout.n, layout.velocities_at());
            let orientation = |k: usize| &self.model.orientations[k].name;
            let what = if i < n {
                format!("the initial value of `{}`", self.model.coordinates[i])
            } else if i < v {
                format!(
                    "the initial orientation of frame `{}`",
                    orientation((i - n) / 9)
                )
            } else if i < v + n {
                format!("the initial rate of `{}`", self.model.coordinates[i - v])
            } else {
                format!(
                    "the initial angular velocity of frame `{}`",
                    orientation((i - v - n) / 3)
                )
            };
            return Err(SceneError::ModelRefused {
                model: self.info.name.to_string(),
                message: format!("{what} is {} at these parameters", y0[i]),
            });
        }
        // One size per state length (at most 6 coordinates, or 3 beside an orientation).
        match self.model.layout.state_len() {
            2 => self.run::<2>(params, plan, &y0, recorder),
            4 => self.run::<4>(params, plan, &y0, recorder),
            6 => self.run::<6>(params, plan, &y0, recorder),
            8 => self.run::<8>(params, plan, &y0, recorder),
            10 => self.run::<10>(params, plan, &y0, recorder),
            12 => self.run::<12>(params, plan, &y0, recorder),
            14 => self.run::<14>(params, plan, &y0, recorder),
            16 => self.run::<16>(params, plan, &y0, recorder),
            _ => self.run::<18>(params, plan, &y0, recorder),
        }
    }
}

/// Models loaded so far, one scene per (origin, text).
fn cache() -> &'static Mutex<HashMap<(String, String), &'static ModelScene>> {
    static CACHE: OnceLock<Mutex<HashMap<(String, String), &'static ModelScene>>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// The scene of model text (named `origin` in messages; files it names are relative to
/// `origin`'s directory). The same text and origin give the same scene.
///
/// # Errors
/// As [`Model::parse`].
pub fn from_text(text: &str, origin: &str) -> Result<&'static ModelScene, ModelFileError> {
    let key = (origin.to_string(), text.to_string());
    if let Some(scene) = cache().lock().map_err(|_| poisoned(origin))?.get(&key) {
        return Ok(scene);
    }
    let scene: &'static ModelScene =
        Box::leak(Box::new(ModelScene::new(Model::parse(text, origin)?)));
    cache()
        .lock()
        .map_err(|_| poisoned(origin))?
        .insert(key, scene);
    Ok(scene)
}

fn poisoned(origin: &str) -> ModelFileError {
    ModelFileError::Invalid {
        at: tumble_scenarios::toml_file::Location {
            origin: origin.to_string(),
            position: None,
        },
        key: "model".to_string(),
        message: "an earlier load of a model panicked".to_string(),
        excerpt: String::new(),
    }
}

/// The scene of the model file at `path`.
///
/// # Errors
/// As [`Model::load`].
pub fn load(path: &Path) -> Result<&'static ModelScene, ModelFileError> {
    let text = crate::file::read_text(path)?;
    from_text(&text, &path.display().to_string())
}

/// Whether TOML text is a model file (it has a `[model]` table) rather than a scene file.
#[must_use]
pub fn is_model_text(text: &str) -> bool {
    text.lines().any(|l| {
        let l = l.trim();
        l == "[model]"
            || l.starts_with("[model]")
            || l.starts_with("model.")
            || l.starts_with("model =")
    })
}

/// Whether the file at `path` is a model file ([`is_model_text`]).
#[must_use]
pub fn is_model_file(path: &Path) -> bool {
    std::fs::read_to_string(path).is_ok_and(|t| is_model_text(&t))
}
