//! A rigid body coupled to `N` vector-space coordinates (`SO(3) × ℝᴺ`): the model interface, a
//! variational integrator built from a discrete Lagrangian, and the continuous equations as a
//! [`LieVectorField`] for the Lie-group Runge–Kutta methods.
//!
//! # The model ([`CoupledLagrangian`])
//!
//! A body with a fixed point (or a free body's rotation about its centre of mass) whose
//! configuration is `(R, q) ∈ SO(3) × ℝᴺ` — a bead on a hoop (`q = α`), a mass on a spring along
//! a body axis, a rotor — with the Lagrangian
//!
//! ```text
//! L(R, Ω, q, q̇) = ½ Ωᵀ J(q) Ω + Ωᵀ B(q) q̇ + ½ q̇ᵀ M(q) q̇ − V(R, q),
//! ```
//!
//! `Ω` the body angular velocity (`Ṙ = R hat Ω`). A scene implements the two methods of
//! [`CoupledLagrangian`] once, generic over the scalar ([`Scalar`]: `f64` and the dual numbers
//! of `num-dual`); every derivative the integrators need (`∂T/∂q`, the moment
//! `M = −∂V/∂η` of `V(R exp(hat η), q)`, `∂V/∂q`, the Newton Jacobian) is then computed by
//! automatic differentiation, exactly. For a point mass `μ` at body position `r(q)` moving with
//! the body: `J = μ(|r|² 𝟙 − r rᵀ)`, `B = μ hat(r) ∂r/∂q`, `M = μ (∂r/∂q)ᵀ ∂r/∂q`.
//!
//! The momenta are `Π = ∂L/∂Ω = J Ω + B q̇` (body frame; `R Π` is the spatial angular momentum
//! about the fixed point) and `p = ∂L/∂q̇ = Bᵀ Ω + M q̇`, and the energy is
//! `H = ½ (Ω·Π + q̇·p) + V`. The state is [`CoupledState`] `(R, Π, q, p)`.
//!
//! # The variational integrator ([`CoupledLgvi`])
//!
//! Discrete Lagrangian (midpoint in the kinetic energy, trapezoid in the potential), with the
//! relative rotation `F_k = R_kᵀ R_{k+1} = cay(w)` and the discrete body velocity `ξ = w/h`:
//!
//! ```text
//! L_d = h T(ξ, q̄, v) − (h/2) (V(R_k, q_k) + V(R_{k+1}, q_{k+1})),
//! q̄ = (q_k + q_{k+1})/2,   v = (q_{k+1} − q_k)/h.
//! ```
//!
//! Perturbing `R_{k+1} → R_{k+1} exp(hat η)` moves `w` by `A_R(w) η`, perturbing
//! `R_k → R_k exp(hat η)` moves it by `−A_L(w) η`, with
//! `A_R(w) = 𝟙 + ½ hat w + ¼ w wᵀ` and `A_L(w) = A_R(w)ᵀ` (the inverse trivialized tangents of
//! the Cayley map). The discrete Legendre transforms `Π_k = −D_{R_k} L_d`,
//! `p_k = −∂L_d/∂q_k`, `Π_{k+1} = D_{R_{k+1}} L_d`, `p_{k+1} = ∂L_d/∂q_{k+1}` (left-trivialized)
//! then give the one-step map `(R_k, Π_k, q_k, p_k) ↦ (R_{k+1}, Π_{k+1}, q_{k+1}, p_{k+1})`:
//!
//! ```text
//! 0 = Π_k + (h/2) M(R_k, q_k) − A_R(w) T_ξ,
//! 0 = p_k − (h/2) V_q(R_k, q_k) + (h/2) T_q − T_v,                (solve for w, q_{k+1})
//! R_{k+1} = R_k cay(w),
//! Π_{k+1} = A_L(w) T_ξ + (h/2) M(R_{k+1}, q_{k+1}),
//! p_{k+1} = T_v + (h/2) T_q − (h/2) V_q(R_{k+1}, q_{k+1}),
//! ```
//!
//! with `T_ξ, T_q, T_v` the partial derivatives of `T` at `(ξ, q̄, v)`. The `3 + N` equations are
//! solved for `(w, d = q_{k+1} − q_k)` by a simplified Newton method in plain `f64`, from what
//! the model gives of its kinetic energy: the blocks and their first derivatives
//! ([`CoupledLagrangian::kinetic_jet`]) for the residuals, and their second derivatives
//! ([`CoupledLagrangian::kinetic_hessian`]) for the Newton matrix, which is exact at the first
//! iterate (see `StepData::jacobian`), factored once by block elimination (a 3×3 inverse and
//! the inverse of the `N×N` Schur complement, on the stack) and reused until an iteration
//! shrinks the increment less than fourfold (or lets it grow: then the step is retaken with a
//! fresh matrix). The defaults of those methods differentiate the model automatically
//! (dual and hyper-dual numbers); a model may give closed forms instead. The starting guess is
//! the explicit `w = hΩ_k`, `d = h q̇_k`. Iteration stops
//! when the increment is at round-off or stops decreasing; otherwise
//! [`Error::NoConvergence`]. The moment and `∂V/∂q` at the end of a step
//! ([`CoupledLagrangian::potential_derivatives`]) are reused at the start of the next when it
//! continues the last one. Solving for
//! the increment `d` rather than `q_{k+1}` keeps `v = d/h` free of cancellation when `q` is large
//! (an angle that winds up: with `q ≈ 40` the difference `q_{k+1} − q_k` would lose three digits,
//! enough to break the conservation of `L·e₃` at the 1e-14 level per step).
//!
//! The map is symplectic and symmetric (the discrete Lagrangian is self-adjoint), hence of order
//! 2 and composable to higher order with [`crate::Composition`]. If `V` is invariant under
//! rotations about the space axis `e` (`V(exp(θ hat e) R, q) = V(R, q)`, e.g. gravity along `e`),
//! so is `L_d`, and the discrete Noether theorem conserves `e · R_k Π_k` exactly (to round-off).
//! For `N = 0` and constant `J` it is a Cayley-based relative of the LGVI of
//! [`crate::rigid::Lgvi`] (the two discrete kinetic energies differ by `O(h³)`).
//!
//! # The continuous equations ([`CoupledVectorField`])
//!
//! `Ṙ = R hat Ω`, `Π̇ = Π × Ω + M(R, q)`, `q̇`, `ṗ = ∂T/∂q|_{Ω,q̇} − ∂V/∂q`, with `(Ω, q̇)` from
//! the momenta by the Legendre transform; as a [`LieVectorField`] on `SO(3) × ℝʸ` with
//! `y = (Π, q, p)`, `Y = 3 + 2N` (checked when the field is built), integrable by `rkmk4`, `cg3`
//! (see [`CoupledState::to_group`]) or, flattened, by any vector-space method.
//!
//! # References
//! - J. E. Marsden, M. West, *Discrete mechanics and variational integrators*, Acta Numerica 10
//!   (2001) 357–514.
//! - T. Lee, M. Leok, N. H. McClamroch, *Lie group variational integrators for the full body
//!   problem*, Comput. Methods Appl. Mech. Eng. 196 (2007) 2907–2924.
//! - N. Bou-Rabee, J. E. Marsden, *Hamilton–Pontryagin integrators on Lie groups*, Found.
//!   Comput. Math. 9 (2009) 197–219 (Cayley-map discretizations).
//! - M. Kobilarov, J. E. Marsden, *Discrete geometric optimal control on Lie groups*, IEEE
//!   Trans. Robotics 27 (2011) 641–655 (the trivialized tangents of the Cayley map).
//!
//! # Layout
//!
//! `model` holds the trait and what is computed from a model (derivatives by dual numbers, the
//! Legendre transform, energy); `lgvi` the variational integrator; `field` the vector field.

mod field;
mod lgvi;
mod model;

pub use field::CoupledVectorField;
pub use lgvi::{CoupledLgvi, coupled_lgvi4, coupled_lgvi6, coupled_lgvi8, coupled_lgvi10};
pub(crate) use model::velocities_of;
pub use model::{
    CoupledLagrangian, KineticBlocks, KineticJet, Scalar, coupled_energy, coupled_kinetic_gradient,
    coupled_potential_gradient, coupled_state_from_velocities, coupled_torque, coupled_velocities,
};
