//! From states to rows: the observer that turns a run's states into the rows a [`Recorder`]
//! receives (cadence, output times from dense output, the relative energy error at every step)
//! and the runners of a scene's model through [`dispatch`].

use nalgebra::SVector;
use tumble_integrators::rigid::{
    CoupledLagrangian, CoupledState, FreeRigidBody, ProductLagrangian, ProductState,
    ProductVectorField, RigidBody, RigidBodyState,
};
use tumble_integrators::{
    DenseStep, Event, Flow, Observer, Ode, SeparableHamiltonian, TaylorSystem,
};

use super::{Recorder, RowsView, RunPlan, RunSummary};
use crate::dispatch;
use crate::error::SceneError;

/// The unit quaternion of a rotation matrix with its sign chosen continuous along a run (`q` and
/// `−q` are the same rotation): the first has `w ≥ 0`, each later one the sign closer to the
/// previous one, so that CSV columns and plots do not jump.
pub fn continuous_quaternion(
    rotation: &nalgebra::Matrix3<f64>,
    previous: &mut Option<nalgebra::Quaternion<f64>>,
) -> nalgebra::Quaternion<f64> {
    let q = tumble_kinematics::so3::rotation_to_quat(&nalgebra::Rotation3::from_matrix_unchecked(
        *rotation,
    ))
    .into_inner();
    let q = match previous {
        Some(p) if p.coords.dot(&q.coords) < 0.0 => -q,
        _ => q,
    };
    *previous = Some(q);
    q
}

/// The energy scale after a row: the largest of the scale so far, `|E₀|` and the row's
/// magnitude (see [`run_vector`]). A NaN magnitude leaves the scale as it was (the row's
/// non-finite value stops the run anyway).
#[must_use]
pub fn energy_scale(scale: f64, e0: f64, magnitude: f64) -> f64 {
    scale.max(e0.abs()).max(magnitude)
}

/// `|E − E₀| / scale`, or `|E − E₀|` when the scale is zero (no energy anywhere yet).
#[must_use]
pub fn relative_energy_error(e: f64, e0: f64, scale: f64) -> f64 {
    let change = (e - e0).abs();
    if scale > 0.0 { change / scale } else { change }
}

/// Observer that turns states (of any type) into rows, tracks the relative energy error at
/// every step, and hands rows to the recorder: every `every`-th step, or (when the plan has
/// output times) at exactly those times, from the method's dense output. The final state is
/// always written, whatever the cadence.
pub(crate) struct RowObserver<'a, S, F> {
    row: F,
    buffer: Vec<f64>,
    energy_column: usize,
    energy0: Option<f64>,
    /// The energy scale: the largest of `|E₀|` and the magnitudes the rows wrote so far.
    energy_scale: f64,
    max_rel: f64,
    every: u64,
    /// Rows at the plan's output times instead of every `every` steps.
    at_times: bool,
    count: u64,
    rows: u64,
    /// The row of the last observed step is in `buffer` and has not been written.
    pending: bool,
    /// Time of the last row written.
    last_written: f64,
    stopped: bool,
    /// The first row with a non-finite value, if any: the run stops there with
    /// [`SceneError::NonFiniteOutput`].
    non_finite: Option<SceneError>,
    /// Rows evaluated inside steps for [`Recorder::dense_rows`].
    dense_buffer: Vec<f64>,
    recorder: &'a mut dyn Recorder,
    state: std::marker::PhantomData<fn(&S)>,
}

impl<'a, S, F: FnMut(f64, &S, &mut [f64])> RowObserver<'a, S, F> {
    /// `row(t, state, out)` fills `columns` values; `energy_column` holds the energy and the
    /// column after it receives the relative energy error.
    pub(crate) fn new(
        columns: usize,
        energy_column: usize,
        plan: &RunPlan,
        row: F,
        recorder: &'a mut dyn Recorder,
    ) -> Self {
        RowObserver {
            row,
            buffer: vec![0.0; columns],
            energy_column,
            energy0: None,
            energy_scale: 0.0,
            max_rel: 0.0,
            every: plan.every,
            at_times: plan.times.is_some(),
            count: 0,
            rows: 0,
            pending: false,
            last_written: f64::NEG_INFINITY,
            stopped: false,
            non_finite: None,
            dense_buffer: vec![0.0; columns],
            recorder,
            state: std::marker::PhantomData,
        }
    }

    /// Fills `buffer` with the row of `(t, state)` and its relative energy error: the change
    /// of the energy since the first row over the energy scale (see [`run_vector`]).
    fn fill(&mut self, t: f64, state: &S) -> f64 {
        if let Some(slot) = self.buffer.get_mut(self.energy_column + 1) {
            *slot = 0.0;
        }
        (self.row)(t, state, &mut self.buffer);
        let e = self.buffer[self.energy_column];
        let e0 = *self.energy0.get_or_insert(e);
        let slot = self.buffer.get_mut(self.energy_column + 1);
        let magnitude = slot.as_deref().copied().unwrap_or(0.0).abs();
        self.energy_scale = energy_scale(self.energy_scale, e0, magnitude);
        let rel = relative_energy_error(e, e0, self.energy_scale);
        if let Some(slot) = slot {
            *slot = rel;
        }
        rel
    }

    /// Whether the row in `buffer` is finite; if not, the run stops with the error kept.
    fn finite(&mut self, t: f64) -> bool {
        let Some(column) = self.buffer.iter().position(|v| !v.is_finite()) else {
            return true;
        };
        self.non_finite = Some(SceneError::NonFiniteOutput {
            t,
            column,
            value: self.buffer[column],
            row: self.buffer.clone(),
        });
        self.stopped = true;
        false
    }

    fn write(&mut self, t: f64) -> Flow {
        self.rows += 1;
        self.last_written = t;
        let flow = self.recorder.row(&self.buffer);
        if flow == Flow::Stop {
            self.stopped = true;
        }
        flow
    }

    /// Writes the final state's row if the cadence skipped it, and returns the run's summary.
    ///
    /// # Errors
    /// [`SceneError::NonFiniteOutput`] if a row was not finite.
    pub(crate) fn summary(
        &mut self,
        outcome: &crate::dispatch::Outcome,
    ) -> Result<RunSummary, SceneError> {
        if let Some(e) = self.non_finite.take() {
            return Err(e);
        }
        let t = outcome.t;
        if self.pending && !self.stopped && t > self.last_written {
            self.write(t);
        }
        Ok(RunSummary {
            t,
            steps: outcome.steps,
            evaluations: outcome.evaluations,
            max_energy_rel_err: self.max_rel,
            rows: self.rows,
            terminated: outcome.terminated,
        })
    }
}

impl<S, F: FnMut(f64, &S, &mut [f64])> Observer<S> for RowObserver<'_, S, F> {
    fn observe(&mut self, t: f64, state: &S) -> Flow {
        let rel = self.fill(t, state);
        if !self.finite(t) {
            return Flow::Stop;
        }
        self.max_rel = self.max_rel.max(rel);
        let due = !self.at_times && self.count.is_multiple_of(self.every);
        self.count += 1;
        if due {
            self.pending = false;
            self.write(t)
        } else {
            self.pending = true;
            Flow::Continue
        }
    }

    fn output(&mut self, t: f64, state: &S) -> Flow {
        self.fill(t, state);
        if !self.finite(t) {
            return Flow::Stop;
        }
        self.write(t)
    }

    fn wants_dense_steps(&self) -> bool {
        self.recorder.wants_dense_rows()
    }

    fn dense_step(&mut self, step: &mut dyn DenseStep<S>) -> Flow {
        let mut view = RowsView {
            step,
            row: &mut self.row,
            buffer: &mut self.dense_buffer,
        };
        self.recorder.dense_rows(&mut view)
    }
}

/// Runs a first-order system ([`ProblemKind::Ode`]) with the plan's method through
/// [`dispatch::run_ode`], turning states into rows (with `events`, only methods with dense
/// output run it; a terminal event ends the run there).
///
/// `row(t, y, out)` writes a row (`t`, coordinates, rates, diagnostics; `out` has `columns`
/// entries); column `energy_column` must hold the energy `E = T + V`, and the one after it
/// the energy's magnitude at that state (below), which the observer replaces with the
/// relative energy error.
///
/// # The energy scale
///
/// `energy_rel_err` is `|E − E₀|` over the energy scale `E_s`: the largest of `|E₀|` and the
/// magnitudes of the rows so far. A row's magnitude is the kinetic energy `T` plus the
/// amplitude of the potential's terms: `m g a` for a bead on a hoop of radius `a`, `m g |ρ|`
/// for a body whose centre of mass is `ρ` from its pivot, `g |z|` and `½|ω × r|²` for a
/// mass in a rotating frame — the sizes of the terms whose round-off the computed `E`
/// carries. Where the energy is zero or nearly so while its terms are not (a bead released
/// level with the hoop's centre, a top released horizontally, a mass dropped from a height of
/// 1e-300 m), dividing by `|E₀|` alone reports round-off as a drift of order one or more;
/// over `E_s` it reads as the round-off it is. Where `E₀` dominates its terms the scale is
/// `|E₀|`, the usual relative error. A row that leaves the magnitude at 0 gets `|E₀|`.
pub fn run_vector<P, F, const S: usize>(
    problem: &P,
    y0: SVector<f64, S>,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    events: &mut [Event<'_, SVector<f64, S>>],
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    P: Ode<SVector<f64, S>>,
    F: FnMut(f64, &SVector<f64, S>, &mut [f64]),
{
    let mut y = y0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_ode(problem, &mut y, plan, events, &mut observer)?;
    observer.summary(&outcome)
}

/// Runs a system that computes its Taylor coefficients ([`ProblemKind::TaylorSeries`]) with the
/// plan's Taylor method through [`dispatch::run_taylor`], turning states into rows as
/// [`run_vector`] does.
#[allow(clippy::too_many_arguments)]
pub fn run_taylor_vector<P, F, const S: usize>(
    problem: &P,
    y0: SVector<f64, S>,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    events: &mut [Event<'_, SVector<f64, S>>],
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    P: TaylorSystem,
    F: FnMut(f64, &SVector<f64, S>, &mut [f64]),
{
    let mut y = y0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_taylor(problem, &mut y, plan, events, &mut observer)?;
    observer.summary(&outcome)
}

/// Runs a separable Hamiltonian ([`ProblemKind::Separable`], or [`ProblemKind::Split`] as its
/// drift and kick) with the plan's method through [`dispatch::run_separable`], from
/// `y0 = (q, p)`, turning states into rows as [`run_vector`] does.
pub fn run_hamiltonian<H, F, const S: usize>(
    model: &H,
    y0: SVector<f64, S>,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    H: SeparableHamiltonian,
    F: FnMut(f64, &SVector<f64, S>, &mut [f64]),
{
    let mut y = y0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_separable(model, &mut y, plan, &mut observer)?;
    observer.summary(&outcome)
}

/// Runs a rigid body on SO(3) ([`ProblemKind::RigidBody`], [`ProblemKind::LieVectorField`],
/// and with `free` — the same body when it is torque-free — [`ProblemKind::FreeRigidBody`])
/// with the plan's method through [`dispatch::run_rigid_body`], from `s0`, turning states into
/// rows as [`run_vector`] does.
///
/// [`ProblemKind::RigidBody`]: tumble_integrators::ProblemKind::RigidBody
/// [`ProblemKind::LieVectorField`]: tumble_integrators::ProblemKind::LieVectorField
/// [`ProblemKind::FreeRigidBody`]: tumble_integrators::ProblemKind::FreeRigidBody
#[allow(clippy::too_many_arguments)]
pub fn run_rigid_rows<B, F>(
    body: &B,
    free: Option<&FreeRigidBody>,
    s0: RigidBodyState,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    B: RigidBody,
    F: FnMut(f64, &RigidBodyState, &mut [f64]),
{
    let mut state = s0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_rigid_body(&body, free, &mut state, plan, &mut observer)?;
    observer.summary(&outcome)
}

/// Runs a rigid body coupled to `N` coordinates ([`ProblemKind::CoupledRigidBody`]) with the
/// plan's method through [`dispatch::run_coupled`], from `s0`, turning states into rows as
/// [`run_vector`] does.
///
/// [`ProblemKind::CoupledRigidBody`]: tumble_integrators::ProblemKind::CoupledRigidBody
pub fn run_coupled_rows<L, F, const N: usize>(
    model: &L,
    s0: CoupledState<N>,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    L: CoupledLagrangian<N>,
    F: FnMut(f64, &CoupledState<N>, &mut [f64]),
{
    let mut state = s0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_coupled(model, &mut state, plan, &mut observer)?;
    observer.summary(&outcome)
}

/// Runs a system on the product `SO(3)ᴹ × ℝᴺ` (its vector field or its Lagrangian) with the
/// plan's method through [`dispatch::run_product`], from `s0`, turning states into rows as
/// [`run_vector`] does.
pub fn run_product_rows<P, F, const M: usize, const N: usize>(
    system: &P,
    s0: ProductState<M, N>,
    plan: &RunPlan,
    columns: usize,
    energy_column: usize,
    row: F,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError>
where
    P: ProductVectorField<M, N> + ProductLagrangian<M, N>,
    F: FnMut(f64, &ProductState<M, N>, &mut [f64]),
{
    let mut state = s0;
    let mut observer = RowObserver::new(columns, energy_column, plan, row, recorder);
    let outcome = dispatch::run_product(system, &mut state, plan, &mut observer)?;
    observer.summary(&outcome)
}
