//! Diagnostics as observers: conserved quantities watched while integrating.
//!
//! [`RigidBodyMonitor`] (for [`RigidBodyState`] and for [`GroupState<3>`] read as `(R, m)`) and
//! [`CoupledMonitor`] (for [`CoupledState`]) remember the values of the first state they see and
//! keep running maxima of the deviations from them, computed on the fly — no trajectory is
//! stored:
//!
//! - energy `H` (absolute and relative to `|H₀|`);
//! - spatial angular momentum `L = R m` (`|L − L₀|`) and its vertical component
//!   (`|L·e₃ − L₀·e₃|`, conserved in gravity along `e₃`);
//! - the Casimir `|m|` (conserved by the free rigid body's Euler equations);
//! - the orthogonality defect `‖RᵀR − 𝟙‖_F` (its maximum, not a deviation).
//!
//! The monitors never stop a run ([`Flow::Continue`]); a coupled state whose energy cannot be
//! computed (singular kinetic energy) is recorded in [`CoupledMonitor::failure`].

use nalgebra::Vector3;

use crate::driver::{Flow, Observer};
use crate::error::Error;
use crate::rigid::coupled::{CoupledLagrangian, coupled_energy};
use crate::rigid::problem::RigidBody;
use crate::rigid::state::{CoupledState, GroupState, RigidBodyState};

/// Running maxima of the deviations of the invariants from their initial values.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Deviations {
    /// `max |H − H₀|`.
    pub energy: f64,
    /// `max |H − H₀| / |H₀|` (`NaN` when `H₀ = 0`).
    pub energy_relative: f64,
    /// `max |L − L₀|` (space frame).
    pub spatial_momentum: f64,
    /// `max |L·e₃ − L₀·e₃|`.
    pub vertical_momentum: f64,
    /// `max ||m| − |m₀||`.
    pub casimir: f64,
    /// `max ‖RᵀR − 𝟙‖_F`.
    pub orthogonality: f64,
    /// Number of observations.
    pub observations: u64,
}

/// The values every deviation is measured from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Initial {
    /// `H₀`.
    pub energy: f64,
    /// `L₀`.
    pub spatial_momentum: Vector3<f64>,
    /// `|m₀|`.
    pub casimir: f64,
}

impl Deviations {
    fn record(
        &mut self,
        initial: &Initial,
        energy: f64,
        l: &Vector3<f64>,
        casimir: f64,
        defect: f64,
    ) {
        let de = (energy - initial.energy).abs();
        self.energy = self.energy.max(de);
        self.energy_relative = if initial.energy == 0.0 {
            f64::NAN
        } else {
            self.energy / initial.energy.abs()
        };
        self.spatial_momentum = self
            .spatial_momentum
            .max((l - initial.spatial_momentum).norm());
        self.vertical_momentum = self
            .vertical_momentum
            .max((l.z - initial.spatial_momentum.z).abs());
        self.casimir = self.casimir.max((casimir - initial.casimir).abs());
        self.orthogonality = self.orthogonality.max(defect);
        self.observations += 1;
    }
}

/// Watches energy, spatial angular momentum, `|m|` and `‖RᵀR − 𝟙‖` of a [`RigidBody`].
#[derive(Debug, Clone)]
pub struct RigidBodyMonitor<'a, B: ?Sized> {
    problem: &'a B,
    initial: Option<Initial>,
    deviations: Deviations,
}

impl<'a, B: RigidBody + ?Sized> RigidBodyMonitor<'a, B> {
    /// A monitor for `problem`; the first observed state sets the reference values.
    #[must_use]
    pub fn new(problem: &'a B) -> Self {
        Self {
            problem,
            initial: None,
            deviations: Deviations::default(),
        }
    }

    /// The reference values (after the first observation).
    #[must_use]
    pub fn initial(&self) -> Option<Initial> {
        self.initial
    }

    /// The running maxima.
    #[must_use]
    pub fn deviations(&self) -> Deviations {
        self.deviations
    }

    fn watch(&mut self, state: &RigidBodyState) {
        let energy = self.problem.hamiltonian(state);
        let l = state.spatial_momentum();
        let casimir = state.momentum.norm();
        let initial = *self.initial.get_or_insert(Initial {
            energy,
            spatial_momentum: l,
            casimir,
        });
        self.deviations
            .record(&initial, energy, &l, casimir, state.orthogonality_defect());
    }
}

impl<B: RigidBody + ?Sized> Observer<RigidBodyState> for RigidBodyMonitor<'_, B> {
    fn observe(&mut self, _t: f64, state: &RigidBodyState) -> Flow {
        self.watch(state);
        Flow::Continue
    }
}

impl<B: RigidBody + ?Sized> Observer<GroupState<3>> for RigidBodyMonitor<'_, B> {
    fn observe(&mut self, _t: f64, state: &GroupState<3>) -> Flow {
        self.watch(&RigidBodyState::from(*state));
        Flow::Continue
    }
}

/// Watches energy, spatial angular momentum `R Π`, `|Π|` and `‖RᵀR − 𝟙‖` of a
/// [`CoupledLagrangian`] model.
#[derive(Debug, Clone)]
pub struct CoupledMonitor<'a, L: ?Sized, const N: usize> {
    model: &'a L,
    initial: Option<Initial>,
    deviations: Deviations,
    failure: Option<Error>,
}

impl<'a, L: CoupledLagrangian<N> + ?Sized, const N: usize> CoupledMonitor<'a, L, N> {
    /// A monitor for `model`; the first observed state sets the reference values.
    #[must_use]
    pub fn new(model: &'a L) -> Self {
        Self {
            model,
            initial: None,
            deviations: Deviations::default(),
            failure: None,
        }
    }

    /// The reference values (after the first observation).
    #[must_use]
    pub fn initial(&self) -> Option<Initial> {
        self.initial
    }

    /// The running maxima.
    #[must_use]
    pub fn deviations(&self) -> Deviations {
        self.deviations
    }

    /// The first energy evaluation that failed, if any.
    #[must_use]
    pub fn failure(&self) -> Option<&Error> {
        self.failure.as_ref()
    }
}

impl<L: CoupledLagrangian<N> + ?Sized, const N: usize> Observer<CoupledState<N>>
    for CoupledMonitor<'_, L, N>
{
    fn observe(&mut self, _t: f64, state: &CoupledState<N>) -> Flow {
        let energy = match coupled_energy(self.model, state) {
            Ok(e) => e,
            Err(e) => {
                self.failure.get_or_insert(e);
                f64::NAN
            }
        };
        let l = state.spatial_momentum();
        let casimir = state.momentum.norm();
        let initial = *self.initial.get_or_insert(Initial {
            energy,
            spatial_momentum: l,
            casimir,
        });
        self.deviations
            .record(&initial, energy, &l, casimir, state.orthogonality_defect());
        Flow::Continue
    }
}
