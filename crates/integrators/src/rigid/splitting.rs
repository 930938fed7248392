//! Splitting methods for rigid bodies, and the exact free flow as a stepper.
//!
//! # Principal-axis splitting ([`PrincipalAxisSplitting`], `split2`)
//!
//! In the principal frame (`J = Q diag(I₁, I₂, I₃) Qᵀ`, `I₁ ≤ I₂ ≤ I₃`, `m = Q μ`, `R Q = P`)
//! the kinetic energy splits as `T = T₁ + T₂ + T₃`, `Tᵢ = μᵢ²/(2Iᵢ)`. Each `Tᵢ` is integrable:
//! `μᵢ` is constant, and with `θ = τ μᵢ/Iᵢ`
//!
//! ```text
//! μ(τ) = exp(−θ hat eᵢ) μ(0),     P(τ) = P(0) exp(θ hat eᵢ),
//! ```
//!
//! an exact rotation about the principal axis `eᵢ` (two components of `μ` and two columns of
//! `P` turn by `θ`). With a potential, its flow `m ← m + τ M(R)` (`R` fixed) is exact too. The
//! symmetric (Strang) composition
//!
//! ```text
//! Φ_h = V_{h/2} ∘ T₁_{h/2} ∘ T₂_{h/2} ∘ T₃_h ∘ T₂_{h/2} ∘ T₁_{h/2} ∘ V_{h/2}
//! ```
//!
//! (the kick is skipped for torque-free bodies) is explicit, symplectic (each sub-flow is the
//! exact flow of a Hamiltonian on `T*SO(3)`), symmetric and of order 2; every sub-flow is an
//! exact rotation, so `R` stays on `SO(3)`, and `|m|` and `R m` are conserved by the free part.
//! [`split4`], [`split6`], [`split8`] compose it through [`Composition`] with
//! McLachlan's 5-stage order-4 (`MCLACHLAN4`), Kahan & Li's 9-stage order-6 (`KAHAN_LI6`) and
//! 17-stage order-8 (`KAHAN_LI8`) coefficients.
//!
//! # Round-off: the principal frame is kept between steps
//!
//! For a non-diagonal `J` the steppers work on `(P, μ) = (R Q, Qᵀ m)`. Converting back and forth
//! at every step would multiply the state by `Q Qᵀ`, which differs from `𝟙` by a *fixed*
//! rounding pattern, and the error would grow linearly in the number of steps. Instead each
//! stepper keeps the principal-frame state of its last output and, when it is called again with
//! exactly that output (the normal case, also inside a composition), continues from it; a state
//! changed by the caller is converted afresh. Every rotation and kick is applied as an increment
//! (`x + ((c − 1)x + s y)`, `c − 1 = −2 sin²(θ/2)`) summed with Kahan compensation carried in
//! the same cache, so the round-off of long runs stays at the level of a few roundings.
//!
//! # Exact free flow and kicks ([`ExactSplitting`], `split-exact2`)
//!
//! For `H = T + V`: `V_{h/2} ∘ φ^T_h ∘ V_{h/2}` with the exact free-rigid-body flow `φ^T`
//! ([`crate::rigid::ExactFlow`]): order 2, symmetric, symplectic; exact for `V = 0`. The closed
//! form restarted every step with the same `h` multiplies the orientation by nearly the same
//! rotation matrix every step, whose rounding would then accumulate coherently (linearly in the
//! number of steps: 4e-13 after 10⁴ steps of the Simo–Wong top); one Newton–Schulz step
//! `P ← P (3𝟙 − PᵀP)/2` after each flow, which moves `P` only by the size of its defect, keeps
//! `‖PᵀP − 𝟙‖` at ~1e-16.
//!
//! It is a variational integrator: its discrete Lagrangian is the action of the free body along
//! its exact path from `R_k` to `R_{k+1}` (the exact discrete Lagrangian of `T`, which exists
//! for short steps because `T` is positive definite) minus the trapezoidal rule for the
//! potential, `L_d = S_T(R_k, R_{k+1}; h) − (h/2)(V(R_k) + V(R_{k+1}))`. Its discrete Legendre
//! transforms are the half kicks on either side of the free flow (Marsden & West 2001: the
//! exact discrete Lagrangian generates the exact flow, and the trapezoidal rule for the
//! potential gives the kicks of Störmer–Verlet; the LGVI replaces `S_T` by its Moser–Veselov
//! approximation). [`split_exact4`], [`split_exact6`] and [`split_exact8`] compose it with
//! McLachlan's 5-stage order-4 and Kahan & Li's 9-stage order-6 and 17-stage order-8
//! coefficients: explicit, symplectic and variational methods of high order whose error comes
//! only from the potential (a top spinning fast, whose motion is mostly the free rotation, has
//! a small one). Sofroniou & Spaletta's order-10 table composes it too
//! (`sofroniou-spaletta10:split-exact2`), but on the test tops its error reaches the round-off
//! floor while still pre-asymptotic (local orders 12 to 14), so no order-10 name is
//! registered. Every substep restarts the closed form, whose
//! round-off then adds up: over 2²⁰ steps of the heavy top the energy error of `split-exact8`
//! grows like `t^0.7` to 3e-15, where the LGVI compositions stay at 2e-16.
//!
//! # Exact stepper ([`ExactStepper`], `exact`)
//!
//! The exact flow of the free rigid body as a [`Stepper`]: no truncation error at any step.
//!
//! # References
//! - R. I. McLachlan, *Explicit Lie–Poisson integration and the Euler equations*, Phys. Rev.
//!   Lett. 71 (1993) 3043–3046.
//! - J. Touma, J. Wisdom, *Lie–Poisson integrators for rigid body dynamics in the solar
//!   system*, Astron. J. 107 (1994) 1189–1202.
//! - A. Dullweber, B. Leimkuhler, R. McLachlan, *Symplectic splitting methods for rigid body
//!   molecular dynamics*, J. Chem. Phys. 107 (1997) 5840–5851.
//! - J. E. Marsden, M. West, *Discrete mechanics and variational integrators*, Acta Numerica
//!   10 (2001) 357–514.
//! - E. Celledoni, F. Fassò, N. Säfström, A. Zanna, *The exact computation of the free rigid
//!   body motion and its use in splitting methods*, SIAM J. Sci. Comput. 30 (2008) 2084–2112.

use nalgebra::{Matrix3, Rotation3, Vector3};

use crate::rigid::state::compensated_add_all;
use crate::state::{compensated_add, same_time};

use crate::composition::Composition;
use crate::error::{Error, check_step};
use crate::rigid::exact::FreeRigidBody;
use crate::rigid::problem::RigidBody;
use crate::rigid::state::RigidBodyState;
use crate::stepper::Stepper;
use crate::tables::composition::{KAHAN_LI6, KAHAN_LI8, MCLACHLAN4};

/// A state in the principal frame, `(P, μ) = (R Q, Qᵀ m)`, with the Kahan carries of its
/// increments.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Principal {
    pub(crate) p: Matrix3<f64>,
    pub(crate) mu: Vector3<f64>,
    carry_p: Matrix3<f64>,
    carry_mu: Vector3<f64>,
}

impl Principal {
    fn new(p: Matrix3<f64>, mu: Vector3<f64>) -> Self {
        Self {
            p,
            mu,
            ..Self::default()
        }
    }

    /// `P ← P + ΔP`, `μ ← μ + Δμ`, compensated.
    pub(crate) fn add(&mut self, dp: &Matrix3<f64>, dmu: &Vector3<f64>) {
        compensated_add_all(&mut self.p, dp, &mut self.carry_p);
        compensated_add_all(&mut self.mu, dmu, &mut self.carry_mu);
    }

    /// Replaces the state (a closed-form flow, not an increment): the carries restart.
    fn set(&mut self, p: Matrix3<f64>, mu: Vector3<f64>) {
        *self = Self::new(p, mu);
    }
}

/// The principal-frame state of the last output of a stepper (see the module doc).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct PrincipalFrame {
    last: Option<Cached>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct Cached {
    t: f64,
    axes: Matrix3<f64>,
    output: RigidBodyState,
    state: Principal,
}

impl PrincipalFrame {
    /// The principal-frame state of `state` at `t`: the cached one (with its carries) when
    /// `(t, state)` is the last output for the same axes `q`, else `(R Q, Qᵀ m)`.
    pub(crate) fn enter(&self, q: &Matrix3<f64>, t: f64, state: &RigidBodyState) -> Principal {
        match &self.last {
            Some(c) if c.axes == *q && c.output == *state && same_time(c.t, t) => c.state,
            _ => Principal::new(state.rotation * q, q.transpose() * state.momentum),
        }
    }

    /// Writes `(P Qᵀ, Q μ)` into `state` and remembers it as the output at `t`.
    pub(crate) fn leave(
        &mut self,
        q: &Matrix3<f64>,
        t: f64,
        x: Principal,
        state: &mut RigidBodyState,
    ) {
        state.rotation = x.p * q.transpose();
        state.momentum = q * x.mu;
        self.last = Some(Cached {
            t,
            axes: *q,
            output: *state,
            state: x,
        });
    }

    pub(crate) fn reset(&mut self) {
        self.last = None;
    }
}

/// Symmetric splitting into exact principal-axis rotations (and potential kicks): `split2`.
///
/// Implements [`Stepper<B>`] for every [`RigidBody`] `B`, on [`RigidBodyState`]. Holds the
/// principal-frame state of its last step (see the module doc).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PrincipalAxisSplitting {
    frame: PrincipalFrame,
}

impl PrincipalAxisSplitting {
    /// A new stepper.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

/// `split4`: [`PrincipalAxisSplitting`] composed with McLachlan's order-4 coefficients.
#[must_use]
pub fn split4() -> Composition<PrincipalAxisSplitting> {
    Composition::new(&MCLACHLAN4, PrincipalAxisSplitting::new())
}

/// `split6`: [`PrincipalAxisSplitting`] composed with Kahan & Li's order-6 coefficients.
#[must_use]
pub fn split6() -> Composition<PrincipalAxisSplitting> {
    Composition::new(&KAHAN_LI6, PrincipalAxisSplitting::new())
}

/// `split8`: [`PrincipalAxisSplitting`] composed with Kahan & Li's order-8 coefficients.
#[must_use]
pub fn split8() -> Composition<PrincipalAxisSplitting> {
    Composition::new(&KAHAN_LI8, PrincipalAxisSplitting::new())
}

/// `split-exact4`: [`ExactSplitting`] composed with McLachlan's 5-stage order-4 coefficients.
#[must_use]
pub fn split_exact4() -> Composition<ExactSplitting> {
    Composition::new(&MCLACHLAN4, ExactSplitting::new())
}

/// `split-exact6`: [`ExactSplitting`] composed with Kahan & Li's 9-stage order-6 coefficients.
#[must_use]
pub fn split_exact6() -> Composition<ExactSplitting> {
    Composition::new(&KAHAN_LI6, ExactSplitting::new())
}

/// `split-exact8`: [`ExactSplitting`] composed with Kahan & Li's 17-stage order-8 coefficients.
#[must_use]
pub fn split_exact8() -> Composition<ExactSplitting> {
    Composition::new(&KAHAN_LI8, ExactSplitting::new())
}

/// The exact flow of `Tᵢ = μᵢ²/(2Iᵢ)` over time `tau`, in the principal frame.
#[inline]
fn principal_rotation(axis: usize, tau: f64, moments: &Vector3<f64>, x: &mut Principal) {
    let (j, k) = match axis {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let theta = tau * x.mu[axis] / moments[axis];
    let s = theta.sin();
    // c − 1 = −2 sin²(θ/2): the rotation is applied as compensated increments
    // x ← x + ((c − 1)x + s y), which round once per entry in a pattern that changes with the
    // state, instead of rounding c ≈ 1 the same way at every step of a steady rotation (a linear
    // drift of ‖PᵀP − 𝟙‖).
    let half = (0.5 * theta).sin();
    let cm1 = -2.0 * half * half;
    // exp(θ hat eᵢ) maps e_j ↦ c e_j + s e_k and e_k ↦ −s e_j + c e_k; only the entries that
    // change are touched.
    let (mj, mk) = (x.mu[j], x.mu[k]);
    compensated_add(&mut x.mu[j], cm1 * mj + s * mk, &mut x.carry_mu[j]);
    compensated_add(&mut x.mu[k], cm1 * mk - s * mj, &mut x.carry_mu[k]);
    for row in 0..3 {
        let (pj, pk) = (x.p[(row, j)], x.p[(row, k)]);
        compensated_add(
            &mut x.p[(row, j)],
            cm1 * pj + s * pk,
            &mut x.carry_p[(row, j)],
        );
        compensated_add(
            &mut x.p[(row, k)],
            cm1 * pk - s * pj,
            &mut x.carry_p[(row, k)],
        );
    }
}

/// `μ ← μ + τ Qᵀ M(P Qᵀ)`: the kick of the potential over `tau`, in the principal frame.
#[inline]
fn kick<B: RigidBody + ?Sized>(problem: &B, q: &Matrix3<f64>, x: &mut Principal, tau: f64) {
    let rotation = x.p * q.transpose();
    let dmu = q.transpose() * (problem.torque(&rotation) * tau);
    compensated_add_all(&mut x.mu, &dmu, &mut x.carry_mu);
}

impl<B: RigidBody + ?Sized> Stepper<B> for PrincipalAxisSplitting {
    type State = RigidBodyState;

    fn step(
        &mut self,
        problem: &B,
        t: f64,
        state: &mut RigidBodyState,
        h: f64,
    ) -> Result<(), Error> {
        if !h.is_finite() {
            return check_step(h);
        }
        let body = problem.body();
        let moments = body.principal_moments();
        let q = *body.principal_axes().matrix();
        let mut x = self.frame.enter(&q, t, state);
        let kicks = !problem.is_torque_free();
        let half = 0.5 * h;
        if kicks {
            kick(problem, &q, &mut x, half);
        }
        principal_rotation(0, half, &moments, &mut x);
        principal_rotation(1, half, &moments, &mut x);
        principal_rotation(2, h, &moments, &mut x);
        principal_rotation(1, half, &moments, &mut x);
        principal_rotation(0, half, &moments, &mut x);
        if kicks {
            kick(problem, &q, &mut x, half);
        }
        self.frame.leave(&q, t + h, x, state);
        Ok(())
    }

    fn reset(&mut self) {
        self.frame.reset();
    }
}

/// The exact free flow in the principal frame: a body with diagonal inertia (so the closed form
/// adds no frame change of its own), rebuilt only when the moments change; the orientation is
/// re-orthogonalized to round-off after each flow (see [`DiagonalFlow::advance`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct DiagonalFlow {
    body: Option<FreeRigidBody>,
}

impl DiagonalFlow {
    /// Advances `x = (P, μ)` by the exact free flow over `h`.
    fn advance(
        &mut self,
        moments: &Vector3<f64>,
        t: f64,
        h: f64,
        x: &mut Principal,
    ) -> Result<(), Error> {
        let (p, mu) = (&x.p, &x.mu);
        let failure = |p: &Matrix3<f64>, mu: &Vector3<f64>| Error::NonFinite {
            t,
            h,
            state: p.iter().chain(mu.iter()).copied().collect(),
        };
        let body = match self.body {
            Some(b) if b.principal_moments() == *moments => b,
            _ => {
                let b =
                    FreeRigidBody::from_principal_moments(*moments).map_err(|_| failure(p, mu))?;
                self.body = Some(b);
                b
            }
        };
        let flow = body
            .flow(&Rotation3::from_matrix_unchecked(*p), mu)
            .map_err(|_| failure(p, mu))?;
        let (r, m) = flow.at(h);
        // One Newton–Schulz step towards the nearest rotation, P ← P (3𝟙 − PᵀP)/2: it moves P
        // by the size of its defect (~1e-16) and keeps it there. Without it the defect grows
        // linearly: restarted every step with the same h, the closed form multiplies by nearly
        // the same rotation matrix every step and accumulates that matrix's rounding coherently.
        let r = r.into_inner();
        x.set(r * (Matrix3::identity() * 3.0 - r.transpose() * r) * 0.5, m);
        Ok(())
    }
}

/// Strang splitting of `H = T + V` into potential kicks and the exact free flow: `split-exact2`.
///
/// Implements [`Stepper<B>`] for every [`RigidBody`] `B`, on [`RigidBodyState`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ExactSplitting {
    frame: PrincipalFrame,
    flow: DiagonalFlow,
}

impl ExactSplitting {
    /// A new stepper.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl<B: RigidBody + ?Sized> Stepper<B> for ExactSplitting {
    type State = RigidBodyState;

    fn step(
        &mut self,
        problem: &B,
        t: f64,
        state: &mut RigidBodyState,
        h: f64,
    ) -> Result<(), Error> {
        if !h.is_finite() {
            return check_step(h);
        }
        let body = problem.body();
        let moments = body.principal_moments();
        let q = *body.principal_axes().matrix();
        let mut x = self.frame.enter(&q, t, state);
        let kicks = !problem.is_torque_free();
        if kicks {
            kick(problem, &q, &mut x, 0.5 * h);
        }
        self.flow.advance(&moments, t, h, &mut x)?;
        if kicks {
            kick(problem, &q, &mut x, 0.5 * h);
        }
        self.frame.leave(&q, t + h, x, state);
        Ok(())
    }

    fn reset(&mut self) {
        self.frame.reset();
    }
}

/// The exact free-rigid-body flow as a stepper: `exact`.
///
/// Implements [`Stepper<FreeRigidBody>`] on [`RigidBodyState`]. The closed form
/// ([`FreeRigidBody::flow`]) is built once, from the first state of a run, and every step
/// evaluates it at the elapsed time: a run of many steps lands on the same state as one step
/// over the whole horizon, at round-off however it is stepped (rebuilding the flow from each
/// state would re-derive its invariants, frame and phase every step and lose about 1e-12 a
/// step). A step from any other state than the one the stepper produced last (a new run, an
/// event, a changed state) rebuilds it there.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ExactStepper {
    origin: Option<FlowOrigin>,
}

/// The flow of a run, where it started and where the last step left it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FlowOrigin {
    flow: crate::rigid::exact::ExactFlow,
    t0: f64,
    t_last: f64,
    last: RigidBodyState,
}

impl ExactStepper {
    /// A new stepper.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Stepper<FreeRigidBody> for ExactStepper {
    type State = RigidBodyState;

    fn step(
        &mut self,
        body: &FreeRigidBody,
        t: f64,
        state: &mut RigidBodyState,
        h: f64,
    ) -> Result<(), Error> {
        check_step(h)?;
        let continuing = self
            .origin
            .as_ref()
            .is_some_and(|o| same_time(t, o.t_last) && *state == o.last);
        if !continuing {
            let r0 = Rotation3::from_matrix_unchecked(state.rotation);
            self.origin = Some(FlowOrigin {
                flow: body.flow(&r0, &state.momentum)?,
                t0: t,
                t_last: t,
                last: *state,
            });
        }
        let Some(origin) = self.origin.as_mut() else {
            return Ok(());
        };
        let (r, m) = origin.flow.at(t + h - origin.t0);
        state.rotation = *r.matrix();
        state.momentum = m;
        origin.t_last = t + h;
        origin.last = *state;
        Ok(())
    }

    fn reset(&mut self) {
        self.origin = None;
    }
}
