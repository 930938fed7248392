//! The discrete Moser–Veselov algorithm for the free rigid body.
//!
//! # Method
//!
//! Moser & Veselov (1991) discretize the free rigid body by the discrete Lagrangian
//! `L(Q_k, Q_{k+1}) = (1/h) tr(Q_k D Q_{k+1}ᵀ)` on `SO(3)`, with `D = diag(d₁, d₂, d₃)`,
//! `dᵢ = ½ (I_j + I_k − I_i)` in the principal frame (`D = ½ tr(I) 𝟙 − I`). In angular-momentum
//! form (Hairer, Lubich & Wanner, *Geometric Numerical Integration*, §VII.5.3) one step is
//!
//! ```text
//! h hat(m_k) = F_k D − D F_kᵀ,    m_{k+1} = F_kᵀ m_k,    R_{k+1} = R_k F_k,
//! ```
//!
//! with `F_k` the relative rotation (HLW's `Ω_kᵀ`), `m` the body angular momentum in the
//! principal frame. Writing `F` through its unit quaternion `(e₀, e)`,
//! `F = 𝟙 + 2e₀ hat(e) + 2 hat(e)²`, the first equation becomes
//!
//! ```text
//! h m_k = 2 (e₀ I e + e × I e),     e₀ = √(1 − |e|²),
//! ```
//!
//! which HLW solve by the fixed-point iteration `e ← I⁻¹ (h m_k/2 − e × I e)/e₀` from
//! `e = h I⁻¹ m_k/2` (a contraction with factor `O(h |Ω| I_max/I_min)`), iterated here until the
//! increment stops decreasing; `I` is diagonal, so each sweep costs a few multiplications.
//! Non-convergence is [`Error::NoConvergence`].
//!
//! # Relation to the LGVI, and order
//!
//! With `V = 0` the Lee–Leok–McClamroch LGVI ([`crate::rigid::Lgvi`]) is this map (their `J_d`
//! is `D` in the body frame); this module computes it by an independent route (principal frame,
//! quaternion, fixed point) and the tests check that the two agree to round-off. The DMV map is
//! integrable and is the exact time-`h` flow of a modified rigid body (McLachlan & Zanna 2005),
//! whose vector field differs from Euler's by `O(h²)`; with `m_k ≈ m(t_k)` and
//! `R_k ≈ R(t_k)` it is a method of order 2 in both the momentum and the rotation (it is
//! equivalent to RATTLE applied to the constrained formulation), measured by
//! `tests/integrators/rigid_body_orders.rs`. Higher accuracy needs the modified moments of
//! inertia and preprocessed initial data of Hairer & Vilmart (2006); they are not needed for
//! order 2 and not implemented here.
//!
//! # References
//! - J. Moser, A. P. Veselov, *Discrete versions of some classical integrable systems and
//!   factorization of matrix polynomials*, Comm. Math. Phys. 139 (1991) 217–243.
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., Springer
//!   2006, §VII.5.
//! - R. I. McLachlan, A. Zanna, *The discrete Moser–Veselov algorithm for the free rigid body,
//!   revisited*, Found. Comput. Math. 5 (2005) 87–123.
//! - E. Hairer, G. Vilmart, *Preprocessed discrete Moser–Veselov algorithm for the full dynamics
//!   of a rigid body*, J. Phys. A 39 (2006) 13225–13235.

use nalgebra::{Matrix3, Vector3};

use crate::error::{Error, check_step};
use crate::rigid::exact::FreeRigidBody;
use crate::rigid::splitting::PrincipalFrame;
use crate::rigid::state::RigidBodyState;
use crate::stepper::Stepper;

/// Default iteration limit of the fixed-point solve.
pub const MAX_FIXED_POINT_ITERATIONS: usize = 100;

/// The discrete Moser–Veselov algorithm (order 2, symplectic, symmetric, integrable).
///
/// Implements [`Stepper<FreeRigidBody>`] on [`RigidBodyState`]. Like the splittings it keeps the
/// principal-frame state of its last output, so a non-diagonal `J` adds no systematic round-off
/// (see [`crate::rigid::splitting`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dmv {
    /// Fixed-point sweeps allowed per step before [`Error::NoConvergence`].
    pub max_iterations: usize,
    frame: PrincipalFrame,
}

impl Default for Dmv {
    fn default() -> Self {
        Self {
            max_iterations: MAX_FIXED_POINT_ITERATIONS,
            frame: PrincipalFrame::default(),
        }
    }
}

impl Dmv {
    /// The default stepper (at most [`MAX_FIXED_POINT_ITERATIONS`] sweeps per step).
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

/// `F − 𝟙 = 2e₀ hat(e) + 2 hat(e)²` for the unit quaternion `(e₀, e)`, without the identity: the
/// update `P ← P + P (F − 𝟙)` (compensated) then rounds once per entry of `P`, in a pattern that
/// changes with `P`, instead of rounding `1 − 2(e_y² + e_z²)` the same way at every step of a
/// steady rotation, which would make `‖PᵀP − 𝟙‖` grow linearly.
fn quaternion_increment(e0: f64, e: &Vector3<f64>) -> Matrix3<f64> {
    let (x, y, z) = (e.x, e.y, e.z);
    Matrix3::new(
        -2.0 * (y * y + z * z),
        2.0 * (x * y - e0 * z),
        2.0 * (x * z + e0 * y),
        2.0 * (x * y + e0 * z),
        -2.0 * (x * x + z * z),
        2.0 * (y * z - e0 * x),
        2.0 * (x * z - e0 * y),
        2.0 * (y * z + e0 * x),
        -2.0 * (x * x + y * y),
    )
}

impl Stepper<FreeRigidBody> for Dmv {
    type State = RigidBodyState;

    fn step(
        &mut self,
        body: &FreeRigidBody,
        t: f64,
        state: &mut RigidBodyState,
        h: f64,
    ) -> Result<(), Error> {
        if !(h.is_finite() && h != 0.0) {
            return check_step(h);
        }
        let i = body.principal_moments();
        let q = *body.principal_axes().matrix();
        let mut x = self.frame.enter(&q, t, state);
        let m = x.mu;
        let half = m * (0.5 * h);
        let mut e = half.component_div(&i);
        let mut previous = f64::INFINITY;
        let mut converged = false;
        let mut sweeps = 0;
        let mut e0 = 1.0;
        while sweeps < self.max_iterations {
            sweeps += 1;
            let n2 = e.norm_squared();
            if n2 >= 1.0 {
                break;
            }
            e0 = (1.0 - n2).sqrt();
            let next = (half - e.cross(&i.component_mul(&e))).component_div(&i) / e0;
            let size = (next - e).amax();
            if !size.is_finite() {
                break;
            }
            if size >= previous {
                converged = previous <= 1e-10 * e.amax().max(f64::MIN_POSITIVE);
                break;
            }
            e = next;
            if size <= 2.0 * f64::EPSILON * e.amax() || size == 0.0 {
                e0 = (1.0 - e.norm_squared()).sqrt();
                converged = true;
                break;
            }
            previous = size;
        }
        if !converged {
            return Err(Error::NoConvergence {
                t,
                h,
                iterations: sweeps,
                increment: previous,
                state: crate::state::State::to_vec(state),
            });
        }
        let g = quaternion_increment(e0, &e);
        // In the principal frame P_{k+1} = P_k F, μ_{k+1} = Fᵀ μ_k (as increments, F = 𝟙 + G);
        // back to the body frame: R = P Qᵀ, m = Q μ.
        let dp = x.p * g;
        x.add(&dp, &(g.transpose() * m));
        self.frame.leave(&q, t + h, x, state);
        Ok(())
    }

    fn reset(&mut self) {
        self.frame.reset();
    }
}
