//! Symplectic Euler, Störmer–Verlet, and Strang / Lie–Trotter splitting.
//!
//! For a separable Hamiltonian `H(q, p) = T(p) + V(q)`:
//!
//! - symplectic Euler (order 1): `p₁ = p₀ − h ∇V(q₀)`, `q₁ = q₀ + h ∂T/∂p(p₁)`;
//! - Störmer–Verlet (order 2, symmetric, symplectic; "kick–drift–kick"):
//!   `p_{½} = p₀ − (h/2) ∇V(q₀)`, `q₁ = q₀ + h ∂T/∂p(p_{½})`,
//!   `p₁ = p_{½} − (h/2) ∇V(q₁)`.
//!
//! For a split system `y' = f₁ + … + f_m` with flows `φᵢ`:
//!
//! - Lie–Trotter (order 1): `φ_m^h ∘ … ∘ φ₁^h`;
//! - Strang (order 2, symmetric): `φ₁^{h/2} ∘ … ∘ φ_{m−1}^{h/2} ∘ φ_m^h ∘ φ_{m−1}^{h/2} ∘ … ∘ φ₁^{h/2}`.
//!
//! Symmetric methods of order 2 (Verlet, Strang) are the base methods of
//! [`crate::Composition`]. The Hamiltonian steppers update `q` and `p` with compensated
//! summation; the carried error survives across steps (and across the substeps of a
//! composition) as long as nobody else modifies the state, and `∇V(q₁)` of one step is reused
//! as `∇V(q₀)` of the next ("first same as last").
//!
//! # References
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric numerical integration illustrated by the
//!   Störmer–Verlet method*, Acta Numerica 12 (2003) 399–450.
//! - G. Strang, *On the construction and comparison of difference schemes*, SIAM J. Numer.
//!   Anal. 5 (1968) 506–517.

use crate::error::Error;
use crate::problem::{SeparableHamiltonian, SplitOde};
use crate::state::{State, VectorState, compensated_add, copy_into};
use crate::stepper::Stepper;

/// Which Hamiltonian method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scheme {
    Euler,
    Verlet,
}

/// Symplectic Euler for a separable Hamiltonian (order 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SymplecticEuler {
    /// Turn compensated summation of the updates off (default: on).
    pub uncompensated: bool,
}

/// Störmer–Verlet (velocity Verlet, kick–drift–kick) for a separable Hamiltonian (order 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StormerVerlet {
    /// Turn compensated summation of the updates off (default: on).
    pub uncompensated: bool,
}

impl SymplecticEuler {
    /// Builds the per-run stepper for states shaped like `y0`.
    #[must_use]
    pub fn stepper<Y: VectorState>(&self, y0: &Y) -> HamiltonianStepper<Y> {
        HamiltonianStepper::new(Scheme::Euler, !self.uncompensated, y0)
    }
}

impl StormerVerlet {
    /// Builds the per-run stepper for states shaped like `y0`.
    #[must_use]
    pub fn stepper<Y: VectorState>(&self, y0: &Y) -> HamiltonianStepper<Y> {
        HamiltonianStepper::new(Scheme::Verlet, !self.uncompensated, y0)
    }
}

/// Workspace of symplectic Euler / Störmer–Verlet.
#[derive(Debug, Clone)]
pub struct HamiltonianStepper<Y> {
    scheme: Scheme,
    compensated: bool,
    /// First half: `∇V`; second half: `∂T/∂p`.
    work: Y,
    carry: Y,
    last: Y,
    grad_valid: bool,
    carry_valid: bool,
}

impl<Y: VectorState> HamiltonianStepper<Y> {
    fn new(scheme: Scheme, compensated: bool, y0: &Y) -> Self {
        Self {
            scheme,
            compensated,
            work: y0.zeros_like(),
            carry: y0.zeros_like(),
            last: y0.zeros_like(),
            grad_valid: false,
            carry_valid: false,
        }
    }

    /// `p ← p − s ∇V(q)` with `∇V` already in `work[..d]`.
    fn kick(&mut self, y: &mut Y, d: usize, s: f64) {
        let g = &self.work.as_slice()[..d];
        let (_, p) = y.as_mut_slice().split_at_mut(d);
        let c = &mut self.carry.as_mut_slice()[d..];
        for i in 0..d {
            if self.compensated {
                compensated_add(&mut p[i], -s * g[i], &mut c[i]);
            } else {
                p[i] -= s * g[i];
            }
        }
    }

    /// `q ← q + s ∂T/∂p(p)`.
    fn drift<H: SeparableHamiltonian + ?Sized>(
        &mut self,
        problem: &H,
        y: &mut Y,
        d: usize,
        s: f64,
    ) {
        {
            let (_, p) = y.as_slice().split_at(d);
            let (_, dt) = self.work.as_mut_slice().split_at_mut(d);
            problem.kinetic_gradient(p, dt);
        }
        let dt = &self.work.as_slice()[d..];
        let (q, _) = y.as_mut_slice().split_at_mut(d);
        let c = &mut self.carry.as_mut_slice()[..d];
        for i in 0..d {
            if self.compensated {
                compensated_add(&mut q[i], s * dt[i], &mut c[i]);
            } else {
                q[i] += s * dt[i];
            }
        }
    }

    fn grad_v<H: SeparableHamiltonian + ?Sized>(&mut self, problem: &H, y: &Y, d: usize) {
        let q = &y.as_slice()[..d];
        problem.potential_gradient(q, &mut self.work.as_mut_slice()[..d]);
    }
}

impl<H: SeparableHamiltonian + ?Sized, Y: VectorState> Stepper<H> for HamiltonianStepper<Y> {
    type State = Y;

    fn step(&mut self, problem: &H, _t: f64, state: &mut Y, h: f64) -> Result<(), Error> {
        let d = problem.dof();
        if state.dim() != 2 * d {
            return Err(Error::DimensionMismatch {
                expected: 2 * d,
                found: state.dim(),
            });
        }
        // The Hamiltonian is autonomous: only the state decides whether we continue.
        let continuing = state.as_slice() == self.last.as_slice();
        if !(continuing && self.carry_valid) {
            self.carry.as_mut_slice().fill(0.0);
        }
        match self.scheme {
            Scheme::Euler => {
                self.grad_v(problem, state, d);
                self.kick(state, d, h);
                self.drift(problem, state, d, h);
                self.grad_valid = false;
            }
            Scheme::Verlet => {
                if !(continuing && self.grad_valid) {
                    self.grad_v(problem, state, d);
                }
                self.kick(state, d, 0.5 * h);
                self.drift(problem, state, d, h);
                self.grad_v(problem, state, d);
                self.kick(state, d, 0.5 * h);
                self.grad_valid = true;
            }
        }
        self.carry_valid = true;
        copy_into(&mut self.last, state);
        Ok(())
    }

    fn reset(&mut self) {
        self.grad_valid = false;
        self.carry_valid = false;
    }
}

/// Splitting of a [`SplitOde`] into its exact (or given) sub-flows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Splitting {
    /// Lie–Trotter, order 1.
    LieTrotter,
    /// Strang, order 2, symmetric.
    Strang,
}

/// Stepper of a [`Splitting`]; has no workspace (the flows act in place), so it works for
/// any state type the flows accept.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SplittingStepper<S> {
    /// Which splitting.
    pub splitting: Splitting,
    _state: std::marker::PhantomData<fn() -> S>,
}

impl<S> SplittingStepper<S> {
    /// A splitting stepper for states of type `S`.
    #[must_use]
    pub fn new(splitting: Splitting) -> Self {
        Self {
            splitting,
            _state: std::marker::PhantomData,
        }
    }
}

impl<S: State, P: SplitOde<S> + ?Sized> Stepper<P> for SplittingStepper<S> {
    type State = S;

    fn step(&mut self, problem: &P, t: f64, state: &mut S, h: f64) -> Result<(), Error> {
        let m = problem.parts();
        match self.splitting {
            Splitting::LieTrotter => {
                for part in 0..m {
                    problem.flow(part, t, h, state);
                }
            }
            Splitting::Strang => {
                if m == 1 {
                    problem.flow(0, t, h, state);
                    return Ok(());
                }
                // Non-autonomous parts see the time at which their substep starts.
                let half = 0.5 * h;
                for part in 0..m - 1 {
                    problem.flow(part, t, half, state);
                }
                problem.flow(m - 1, t, h, state);
                for part in (0..m - 1).rev() {
                    problem.flow(part, t + half, half, state);
                }
            }
        }
        Ok(())
    }
}
