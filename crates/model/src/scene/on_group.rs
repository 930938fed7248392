//! The Lie-group methods on a model with one orientation on SO(3) (a model with several runs
//! the Lie-group Runge–Kutta methods on their product, [`super::on_product`], and the others
//! refuse it, saying why and which methods run it): the kinds of problem it
//! offers (as `free-body`, `heavy-top` or `free-hoop`, and the Taylor series of its
//! first-order system), the model as a rigid body or a rigid
//! body coupled to its scalar coordinates ([`crate::group`]), and the runs of those, whose rows
//! are written from the state `(q, R, q̇, ω)` as for the first-order system.

use nalgebra::{Matrix3, SVector, Vector3};
use tumble_integrators::ProblemKind;
use tumble_integrators::rigid::{
    CoupledState, RigidBodyState, coupled_state_from_velocities, coupled_velocities,
};
use tumble_scenarios::scene::{run_coupled_rows, run_rigid_rows};
use tumble_scenarios::{Params, Recorder, RunPlan, RunSummary, SceneError};

use super::{ModelScene, inputs_at};
use crate::file::Model;
use crate::group::{Group, ModelCoupled, ModelRigidBody};
use tumble_integrators::rigid::RigidBody;

/// The kinds of problem of a model with one orientation on SO(3) and no other coordinate,
/// torque-free: as the built-in `free-body`.
const FREE_BODY: &[ProblemKind] = &[
    ProblemKind::FreeRigidBody,
    ProblemKind::RigidBody,
    ProblemKind::LieVectorField,
    ProblemKind::Ode,
    ProblemKind::TaylorSeries,
    ProblemKind::DoubleDoubleTaylorSeries,
];

/// … in a potential: as the built-in `heavy-top`.
const RIGID_BODY: &[ProblemKind] = &[
    ProblemKind::RigidBody,
    ProblemKind::LieVectorField,
    ProblemKind::Ode,
    ProblemKind::TaylorSeries,
    ProblemKind::DoubleDoubleTaylorSeries,
];

/// … coupled to scalar coordinates: as the built-in `free-hoop`.
const COUPLED: &[ProblemKind] = &[
    ProblemKind::CoupledRigidBody,
    ProblemKind::Ode,
    ProblemKind::TaylorSeries,
    ProblemKind::DoubleDoubleTaylorSeries,
];

/// … with several orientations on SO(3): a vector field on their product, for the Lie-group
/// Runge–Kutta methods, and a Lagrangian on it, for the LGVI and its compositions
/// ([`super::on_product`]).
const PRODUCT: &[ProblemKind] = &[
    ProblemKind::ProductVectorField,
    ProblemKind::ProductLagrangian,
    ProblemKind::Ode,
    ProblemKind::TaylorSeries,
    ProblemKind::DoubleDoubleTaylorSeries,
];

/// … without a Lie-group kind: the first-order system and its Taylor series.
const FLAT: &[ProblemKind] = &[
    ProblemKind::Ode,
    ProblemKind::TaylorSeries,
    ProblemKind::DoubleDoubleTaylorSeries,
];

/// The kinds a model offers at its default parameters, and why the Lie-group methods that do
/// not run it do not (`None` when they all do).
pub(super) fn group_problems(
    model: &Model,
    group: Option<&Group>,
) -> (&'static [ProblemKind], Option<String>) {
    match group_kinds(model, group) {
        Ok(kinds) => (kinds, None),
        Err(why) if model.layout.so3 > 1 => (PRODUCT, Some(why)),
        Err(why) => (FLAT, Some(why)),
    }
}

/// The Lie-group kinds a model with at most one orientation on SO(3) offers at its default
/// parameters, or why it offers none (for several: why only the product's methods run it).
fn group_kinds(model: &Model, group: Option<&Group>) -> Result<&'static [ProblemKind], String> {
    let Some(group) = group else {
        return Err(if model.layout.so3 == 0 {
            "the Lie-group methods need an orientation on SO(3) (a frame with \
             `orientation = \"so3\"`)"
                .into()
        } else {
            let names: Vec<String> = model
                .orientations
                .iter()
                .map(|o| format!("`{}`", o.name))
                .collect();
            format!(
                "model `{}` has {} orientations on SO(3) ({}), a state on their product \
                 SO(3)^{} × R^{}, which Lie–Gauss, the splittings, dmv and the exact flow do \
                 not integrate: they step on one rotation group (SO(3), or SO(3) × R^n beside \
                 scalar coordinates); the LGVI and its compositions (lgvi, lgvi4 … lgvi10), \
                 rkmk4 and cg3 run it on the product, and the vector-space methods (the \
                 explicit pairs, Gauss–Legendre, taylor) each rotation matrix as nine numbers",
                model.name,
                names.len(),
                names.join(", "),
                names.len(),
                2 * model.layout.n + 3 * names.len()
            )
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

impl ModelScene {
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

    /// Runs a Lie-group method ([`crate::group`]) from the state `y0` (coordinates, rotation,
    /// rates, angular velocity), writing rows with `row` from the same state again;
    /// `(columns, energy column)` as for [`tumble_scenarios::scene::run_vector`].
    pub(super) fn run_on_group<const S: usize, F>(
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
