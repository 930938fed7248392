//! Problems as small capability traits.
//!
//! - [`Ode`]: a first-order system `y' = f(t, y)`, written into an output buffer (no
//!   allocation), with an optional Jacobian `∂f/∂y` for Newton iterations.
//! - [`SplitOde`]: `y' = f₁(t, y) + … + f_m(t, y)` given by the flows `φᵢʰ` of its parts,
//!   for splitting and composition methods.
//! - [`SeparableHamiltonian`]: `H(q, p) = T(p) + V(q)` given by `∂T/∂p` and `∇V`, for
//!   symplectic Euler and Störmer–Verlet. The state is `y = (q, p)`, coordinates first.
//!   [`HamiltonianOde`] views it as the first-order system `q' = ∂T/∂p`, `p' = −∇V`, and
//!   [`HamiltonianSplit`] as the two exactly solvable flows (drift and kick).
//! - [`Counted`] wraps any of them and counts evaluations, so that no method can forget to.

use std::cell::Cell;

use crate::state::VectorState;

/// A first-order ODE `y' = f(t, y)`.
pub trait Ode<Y: VectorState> {
    /// Writes `f(t, y)` into `dy` (same dimension as `y`). Must not allocate.
    fn rhs(&self, t: f64, y: &Y, dy: &mut Y);

    /// Writes the Jacobian `∂f/∂y (t, y)` into `jac` (row-major, `n × n`) and returns
    /// `true`, or returns `false` when the problem has none (callers then use finite
    /// differences).
    fn jacobian(&self, t: f64, y: &Y, jac: &mut [f64]) -> bool {
        let _ = (t, y, jac);
        false
    }
}

/// A split system `y' = Σᵢ fᵢ(t, y)` given by the flows of its parts.
pub trait SplitOde<Y> {
    /// Number of parts `m ≥ 1`.
    fn parts(&self) -> usize;
    /// Advances `y` by the flow of part `part` (0-based) over `[t, t + h]`; `h` may be
    /// negative (compositions step backwards).
    fn flow(&self, part: usize, t: f64, h: f64, y: &mut Y);
}

/// A separable Hamiltonian `H(q, p) = T(p) + V(q)` with `d` degrees of freedom.
///
/// The state is `y = (q₁ … q_d, p₁ … p_d)`.
pub trait SeparableHamiltonian {
    /// Number of degrees of freedom `d`.
    fn dof(&self) -> usize;
    /// Kinetic energy `T(p)`.
    fn kinetic(&self, p: &[f64]) -> f64;
    /// Potential energy `V(q)`.
    fn potential(&self, q: &[f64]) -> f64;
    /// Writes `∂T/∂p` into `out`.
    fn kinetic_gradient(&self, p: &[f64], out: &mut [f64]);
    /// Writes `∇V(q)` into `out`.
    fn potential_gradient(&self, q: &[f64], out: &mut [f64]);
    /// `H(q, p)` for `y = (q, p)`.
    fn energy(&self, y: &[f64]) -> f64 {
        let d = self.dof();
        self.kinetic(&y[d..2 * d]) + self.potential(&y[..d])
    }
}

/// A [`SeparableHamiltonian`] viewed as the first-order system `q' = ∂T/∂p`, `p' = −∇V(q)`.
#[derive(Debug, Clone, Copy)]
pub struct HamiltonianOde<H>(pub H);

impl<H: SeparableHamiltonian, Y: VectorState> Ode<Y> for HamiltonianOde<H> {
    fn rhs(&self, _t: f64, y: &Y, dy: &mut Y) {
        let d = self.0.dof();
        let (q, p) = y.as_slice().split_at(d);
        let (dq, dp) = dy.as_mut_slice().split_at_mut(d);
        self.0.kinetic_gradient(p, dq);
        self.0.potential_gradient(q, dp);
        for v in dp.iter_mut() {
            *v = -*v;
        }
    }
}

/// A [`SeparableHamiltonian`] as two exact flows: part 0 is the drift
/// `q ← q + h ∂T/∂p(p)`, part 1 the kick `p ← p − h ∇V(q)`. Strang splitting of this
/// pair is Störmer–Verlet. Uses a small scratch buffer of `d` numbers per call.
#[derive(Debug, Clone)]
pub struct HamiltonianSplit<H> {
    /// The Hamiltonian.
    pub hamiltonian: H,
    scratch: std::cell::RefCell<Vec<f64>>,
}

impl<H: SeparableHamiltonian> HamiltonianSplit<H> {
    /// Wraps a Hamiltonian (allocates the scratch buffer once).
    pub fn new(hamiltonian: H) -> Self {
        let d = hamiltonian.dof();
        Self {
            hamiltonian,
            scratch: std::cell::RefCell::new(vec![0.0; d]),
        }
    }
}

impl<H: SeparableHamiltonian, Y: VectorState> SplitOde<Y> for HamiltonianSplit<H> {
    fn parts(&self) -> usize {
        2
    }
    fn flow(&self, part: usize, _t: f64, h: f64, y: &mut Y) {
        let d = self.hamiltonian.dof();
        let mut g = self.scratch.borrow_mut();
        let (q, p) = y.as_mut_slice().split_at_mut(d);
        if part == 0 {
            self.hamiltonian.kinetic_gradient(p, &mut g);
            for (qi, gi) in q.iter_mut().zip(g.iter()) {
                *qi += h * gi;
            }
        } else {
            self.hamiltonian.potential_gradient(q, &mut g);
            for (pi, gi) in p.iter_mut().zip(g.iter()) {
                *pi -= h * gi;
            }
        }
    }
}

/// Wraps a problem and counts its evaluations (right-hand sides, Jacobians, sub-flows,
/// gradients). The counters use [`Cell`], so a `Counted` problem is used through `&self`
/// like any other.
#[derive(Debug, Default)]
pub struct Counted<P> {
    inner: P,
    rhs: Cell<u64>,
    jacobians: Cell<u64>,
    flows: Cell<u64>,
    potential_gradients: Cell<u64>,
    kinetic_gradients: Cell<u64>,
}

/// Evaluation counts of a [`Counted`] problem.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Evaluations {
    /// Right-hand-side evaluations `f(t, y)`.
    pub rhs: u64,
    /// Jacobian evaluations.
    pub jacobians: u64,
    /// Sub-flow evaluations of a split system.
    pub flows: u64,
    /// `∇V` evaluations.
    pub potential_gradients: u64,
    /// `∂T/∂p` evaluations.
    pub kinetic_gradients: u64,
}

impl<P> Counted<P> {
    /// Wraps `inner` with all counters at zero.
    pub fn new(inner: P) -> Self {
        Self {
            inner,
            rhs: Cell::new(0),
            jacobians: Cell::new(0),
            flows: Cell::new(0),
            potential_gradients: Cell::new(0),
            kinetic_gradients: Cell::new(0),
        }
    }
    /// The wrapped problem.
    pub fn inner(&self) -> &P {
        &self.inner
    }
    /// The counts so far.
    pub fn evaluations(&self) -> Evaluations {
        Evaluations {
            rhs: self.rhs.get(),
            jacobians: self.jacobians.get(),
            flows: self.flows.get(),
            potential_gradients: self.potential_gradients.get(),
            kinetic_gradients: self.kinetic_gradients.get(),
        }
    }
    /// Sets every counter back to zero.
    pub fn reset(&self) {
        for c in [
            &self.rhs,
            &self.jacobians,
            &self.flows,
            &self.potential_gradients,
            &self.kinetic_gradients,
        ] {
            c.set(0);
        }
    }
}

fn bump(c: &Cell<u64>) {
    c.set(c.get() + 1);
}

impl<Y: VectorState, P: Ode<Y>> Ode<Y> for Counted<P> {
    fn rhs(&self, t: f64, y: &Y, dy: &mut Y) {
        bump(&self.rhs);
        self.inner.rhs(t, y, dy);
    }
    fn jacobian(&self, t: f64, y: &Y, jac: &mut [f64]) -> bool {
        let has = self.inner.jacobian(t, y, jac);
        if has {
            bump(&self.jacobians);
        }
        has
    }
}

impl<Y, P: SplitOde<Y>> SplitOde<Y> for Counted<P> {
    fn parts(&self) -> usize {
        self.inner.parts()
    }
    fn flow(&self, part: usize, t: f64, h: f64, y: &mut Y) {
        bump(&self.flows);
        self.inner.flow(part, t, h, y);
    }
}

impl<H: SeparableHamiltonian> SeparableHamiltonian for Counted<H> {
    fn dof(&self) -> usize {
        self.inner.dof()
    }
    fn kinetic(&self, p: &[f64]) -> f64 {
        self.inner.kinetic(p)
    }
    fn potential(&self, q: &[f64]) -> f64 {
        self.inner.potential(q)
    }
    fn kinetic_gradient(&self, p: &[f64], out: &mut [f64]) {
        bump(&self.kinetic_gradients);
        self.inner.kinetic_gradient(p, out);
    }
    fn potential_gradient(&self, q: &[f64], out: &mut [f64]) {
        bump(&self.potential_gradients);
        self.inner.potential_gradient(q, out);
    }
}

impl<H: SeparableHamiltonian + ?Sized> SeparableHamiltonian for &H {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn kinetic(&self, p: &[f64]) -> f64 {
        (**self).kinetic(p)
    }
    fn potential(&self, q: &[f64]) -> f64 {
        (**self).potential(q)
    }
    fn kinetic_gradient(&self, p: &[f64], out: &mut [f64]) {
        (**self).kinetic_gradient(p, out)
    }
    fn potential_gradient(&self, q: &[f64], out: &mut [f64]) {
        (**self).potential_gradient(q, out)
    }
}

/// A right-hand side given as a closure `|t, y, dy| …`.
#[derive(Debug, Clone, Copy)]
pub struct FnOde<F>(pub F);

impl<Y: VectorState, F: Fn(f64, &Y, &mut Y)> Ode<Y> for FnOde<F> {
    fn rhs(&self, t: f64, y: &Y, dy: &mut Y) {
        (self.0)(t, y, dy)
    }
}
