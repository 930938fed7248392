//! Composition of any base stepper: `Ψ_h = Φ_{γ_m h} ∘ … ∘ Φ_{γ₁ h}`.
//!
//! With a symmetric base method `Φ` of order 2 (Störmer–Verlet, Strang splitting, the
//! implicit midpoint rule, a Lie-group variational step, …) and the symmetric coefficient
//! tables of [`crate::tables::composition`], the composition is symmetric and has the
//! table's order. Substep `i` starts at `t + γ₁h + … + γ_{i−1}h` (times go backwards during
//! negative substeps).
//!
//! [`Composition`] is generic over the base [`Stepper`] and over its state type: it asks
//! nothing of the state, so states that are not vector spaces (`SO(3) × ℝⁿ`) compose the
//! same way.
//!
//! # Adding a base method
//! Implement [`Stepper`] for it (any `State`, any problem type `P`); then
//! `Composition::new(&YOSHIDA6, base)` is a 6th-order method if the base is symmetric of
//! order 2.

use crate::error::Error;
use crate::stepper::Stepper;
use crate::tables::CompositionTable;

/// A composition method: coefficient table plus base stepper.
#[derive(Debug, Clone)]
pub struct Composition<B> {
    table: &'static CompositionTable,
    base: B,
}

impl<B> Composition<B> {
    /// Composes `base` with the coefficients of `table`.
    pub fn new(table: &'static CompositionTable, base: B) -> Self {
        Self { table, base }
    }
    /// The coefficient table.
    pub fn table(&self) -> &'static CompositionTable {
        self.table
    }
    /// The base stepper.
    pub fn base(&self) -> &B {
        &self.base
    }
    /// The base stepper, mutable.
    pub fn base_mut(&mut self) -> &mut B {
        &mut self.base
    }
}

impl<P: ?Sized, B: Stepper<P>> Stepper<P> for Composition<B> {
    type State = B::State;

    fn step(&mut self, problem: &P, t: f64, state: &mut B::State, h: f64) -> Result<(), Error> {
        // τ advances by the same expression the base uses for the end of its step, so a
        // base that caches data of its last step recognises the continuation.
        let mut tau = t;
        for &gamma in self.table.gammas {
            let sub = gamma * h;
            self.base.step(problem, tau, state, sub)?;
            tau += sub;
        }
        Ok(())
    }

    fn reset(&mut self) {
        self.base.reset();
    }
}
