//! Methods made for rotating bodies, and the exact free-rigid-body flow that measures them.
//!
//! Conventions: `R` maps body to space components (active rotation); `m`, `Π` are body-frame
//! angular momenta and `L = R m` the spatial one; `hat(ω) v = ω × v`; gravity is `−g e₃` in
//! space.
//!
//! | module | what | registry |
//! |---|---|---|
//! | [`exact`] | the exact free-rigid-body flow (Jacobi elliptic functions, Carlson `R_J`) | `exact` ([`ExactStepper`]) |
//! | [`state`] | [`RigidBodyState`] `(R, m)`, [`GroupState`] `(R, y) ∈ SO(3) × ℝᴺ`, [`CoupledState`] `(R, Π, q, p)` | |
//! | [`problem`] | [`RigidBody`] (inertia `J`, potential `V(R)`, moment `M(R)`), [`HeavyTop`], [`LieVectorField`], [`EulerEquations`] | |
//! | [`lgvi`] | Lee–Leok–McClamroch Lie group variational integrator, Newton on the Cayley vector | `lgvi` |
//! | [`coupled`] | bodies coupled to `N` coordinates: [`CoupledLagrangian`], variational [`CoupledLgvi`], [`CoupledVectorField`] | |
//! | [`lie_gauss`] | variational Lie–Gauss methods: Gauss–Legendre discrete Lagrangian in exponential coordinates, any even order, on rigid and coupled bodies ([`LieGauss`], [`CoupledLieGauss`]) | `lie-gauss4` … `lie-gauss10` |
//! | [`lie_rk`] | Runge–Kutta–Munthe-Kaas and Crouch–Grossman on `SO(3) × ℝᴺ` and on `SO(3)ᴹ × ℝᴺ` | `rkmk4`, `cg3` |
//! | [`product`] | [`ProductState`] `(R₁ … R_M, y)`, [`ProductVectorField`] on `SO(3)ᴹ × ℝᴺ` | |
//! | [`product_lgvi`] | the LGVI on `SO(3)ᴹ × ℝⁿ` for any Lagrangian ([`ProductLagrangian`], [`ProductLgvi`]): trapezoidal discrete Lagrangian in exponential coordinates | `lgvi`, `lgvi4` … `lgvi10` |
//! | [`splitting`] | principal-axis rotations + kicks (Strang, composed to 4/6/8), kicks + exact free flow (Strang, composed to 4/6/8) | `split2` … `split8`, `split-exact2` … `split-exact8` |
//! | [`dmv`] | discrete Moser–Veselov | `dmv` |
//! | [`diagnostics`] | observers: energy, `R m`, `|m|`, `‖RᵀR − 𝟙‖` | |
//!
//! # Which method for which problem
//!
//! - A [`RigidBody`] (any `J`, any potential `V(R)`) on [`RigidBodyState`]: [`Lgvi`], [`LieGauss`],
//!   [`PrincipalAxisSplitting`] and its compositions [`split4`], [`split6`], [`split8`],
//!   [`ExactSplitting`] and its compositions [`split_exact4`], [`split_exact6`], [`split_exact8`]; through [`EulerEquations`] on [`GroupState<3>`]: [`rkmk4`], [`cg3`].
//! - The free body ([`FreeRigidBody`]): additionally [`Dmv`] and [`ExactStepper`].
//! - A body coupled to `N` coordinates: implement [`CoupledLagrangian<N>`] once; then
//!   [`CoupledLgvi<N>`] and [`CoupledLieGauss`] integrate [`CoupledState<N>`] variationally, and
//!   [`CoupledVectorField`] on [`GroupState<Y>`] (`Y = 3 + 2N`) feeds `rkmk4` and `cg3`.
//! - Any vector field on `SO(3) × ℝᴺ`: implement [`LieVectorField<N>`]; use [`rkmk4`], [`cg3`].
//! - Several orientations (`SO(3)ᴹ × ℝᴺ`, e.g. bodies joined by ball joints): implement
//!   [`ProductVectorField<M, N>`]; use [`product_rkmk4`], [`product_cg3`]. Given the
//!   Lagrangian's derivatives ([`ProductLagrangian<M, N>`]), [`ProductLgvi`] integrates the same
//!   state variationally.
//!
//! Every symmetric order-2 stepper here composes to higher order with
//! [`crate::Composition`] (e.g. `Composition::new(&YOSHIDA6, Lgvi::default())`).
//!
//! # Example
//!
//! ```
//! use nalgebra::Vector3;
//! use tumble_integrators::rigid::{FreeRigidBody, Lgvi, RigidBodyMonitor, RigidBodyState};
//! use tumble_integrators::Driver;
//! use tumble_kinematics::so3::exp;
//!
//! let body = FreeRigidBody::from_principal_moments(Vector3::new(1.0, 2.0, 3.0))?;
//! let r0 = exp(&Vector3::new(0.3, -0.2, 0.9));
//! let mut state = RigidBodyState::new(&r0, Vector3::new(0.2, 0.3, 1.0));
//! let mut monitor = RigidBodyMonitor::new(&body);
//! Driver::new(0.0, 10.0)?.run_fixed(&mut Lgvi::default(), &body, &mut state, 0.01, &mut monitor)?;
//! let exact = body.flow(&r0, &Vector3::new(0.2, 0.3, 1.0))?.at(10.0);
//! assert!((state.momentum - exact.1).norm() < 1e-3);
//! assert!(monitor.deviations().spatial_momentum < 1e-13);
//! # Ok::<(), tumble_integrators::Error>(())
//! ```

pub mod coupled;
pub mod diagnostics;
pub mod dmv;
pub mod exact;
pub mod lgvi;
pub mod lie_gauss;
pub mod lie_rk;
pub mod problem;
pub mod product;
pub mod product_lgvi;
pub mod splitting;
pub mod state;
pub mod taylor;

pub use coupled::{
    CoupledLagrangian, CoupledLgvi, CoupledVectorField, KineticBlocks, KineticJet, Scalar,
    coupled_energy, coupled_kinetic_gradient, coupled_lgvi4, coupled_lgvi6, coupled_lgvi8,
    coupled_lgvi10, coupled_potential_gradient, coupled_state_from_velocities, coupled_torque,
    coupled_velocities,
};
pub use diagnostics::{CoupledMonitor, Deviations, Initial, RigidBodyMonitor};
pub use dmv::Dmv;
pub use exact::{ExactFlow, FreeRigidBody};
pub use lgvi::{Lgvi, lgvi4, lgvi6, lgvi8, lgvi10};
pub use lie_gauss::{
    CoupledLieGauss, LieGauss, lie_gauss4, lie_gauss6, lie_gauss8, lie_gauss10, lie_gauss12,
};
pub use lie_rk::{
    CROUCH_GROSSMAN3, CrouchGrossman, LieRkTableau, ProductCrouchGrossman, ProductRkmk, RKMK4,
    Rkmk, cg3, product_cg3, product_rkmk4, rkmk4,
};
pub use problem::{EulerEquations, HeavyTop, LieVectorField, RigidBody};
pub use product::{ProductState, ProductVectorField};
pub use product_lgvi::{LagrangianJet, ProductLagrangian, ProductLgvi};
pub use splitting::{
    ExactSplitting, ExactStepper, PrincipalAxisSplitting, split_exact4, split_exact6, split_exact8,
    split4, split6, split8,
};
pub use state::{CoupledState, GroupState, RigidBodyState};
pub use taylor::TaylorHeavyTop;
