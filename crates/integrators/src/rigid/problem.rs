//! Rigid-body problems as small capability traits.
//!
//! # A rigid body in a potential: [`RigidBody`]
//!
//! Constant body inertia `J` (symmetric positive definite, not necessarily diagonal; given by a
//! [`FreeRigidBody`]) and a potential `V(R)`. The equations of motion in the body frame are
//!
//! ```text
//! Ṙ = R hat(Ω),   ṁ = m × Ω + M(R),   Ω = J⁻¹ m,
//! ```
//!
//! with the **moment** `M(R)` of the potential (Lee, Leok & McClamroch 2005):
//! `hat(M) = ∂V/∂Rᵀ R − Rᵀ ∂V/∂R`, where `∂V/∂R` is the matrix `[∂V/∂R_ij]`. Equivalently
//! `M = −∂/∂η V(R exp(hat η))|_{η=0}`: minus the derivative of `V` under a body-frame
//! perturbation of the orientation, i.e. the torque in the body frame. The energy is
//! `H = ½ m·J⁻¹m + V(R)`.
//!
//! *Check on the heavy top.* `V = w e₃ᵀ R ρ` (weight `w = m g`, body vector `ρ` from the fixed
//! point to the centre of mass, gravity along `−e₃` in space): `∂V/∂R = w e₃ ρᵀ`, so
//! `hat(M) = w (ρ vᵀ − v ρᵀ)` with `v = Rᵀe₃`, and `hat(a × b) = b aᵀ − a bᵀ` gives
//! `M = w v × ρ = w (Rᵀe₃) × ρ = ρ × (−w Rᵀe₃)`: the torque `ρ × F` of the weight
//! `F = −w Rᵀe₃` (body components) at `ρ`. (The opposite sign, `w ρ × Rᵀe₃`, does not conserve
//! energy; `tests/integrators/rigid_body_problems.rs` checks both the sign and the energy.)
//!
//! # A vector field on `SO(3) × ℝᴺ`: [`LieVectorField`]
//!
//! `Ṙ = R hat(ξ(t, R, y))`, `ẏ = f(t, R, y)`, the input of the Lie-group Runge–Kutta methods.
//! [`EulerEquations`] views any [`RigidBody`] as such a field with `y = m`.
//!
//! # References
//! - T. Lee, M. Leok, N. H. McClamroch, *A Lie group variational integrator for the attitude
//!   dynamics of a rigid body with applications to the 3D pendulum*, Proc. IEEE CCA 2005,
//!   962–967.
//! - J. C. Simo, K. K. Wong, *Unconditionally stable algorithms for rigid body dynamics that
//!   exactly preserve energy and momentum*, Int. J. Numer. Methods Eng. 31 (1991) 19–52 (the
//!   heavy-top test case).

use nalgebra::{Matrix3, Rotation3, SVector, Vector3};

use crate::error::Error;
use crate::rigid::exact::FreeRigidBody;
use crate::rigid::state::RigidBodyState;

/// A rigid body with constant body inertia in a potential `V(R)`.
pub trait RigidBody {
    /// The body: inertia `J`, principal moments and axes.
    fn body(&self) -> &FreeRigidBody;

    /// `V(R)`.
    fn potential(&self, rotation: &Matrix3<f64>) -> f64;

    /// The body-frame moment `M(R) = −∂/∂η V(R exp(hat η))|₀` (see the module doc).
    fn torque(&self, rotation: &Matrix3<f64>) -> Vector3<f64>;

    /// `true` when `V` is constant (so `M ≡ 0`); methods may then skip the kicks.
    fn is_torque_free(&self) -> bool {
        false
    }

    /// The energy `H = ½ m·J⁻¹m + V(R)` of a state (named so as not to clash with
    /// [`FreeRigidBody::energy`], the kinetic energy of a momentum).
    fn hamiltonian(&self, state: &RigidBodyState) -> f64 {
        self.body().energy(&state.momentum) + self.potential(&state.rotation)
    }
}

impl RigidBody for FreeRigidBody {
    #[inline]
    fn body(&self) -> &FreeRigidBody {
        self
    }
    #[inline]
    fn potential(&self, _rotation: &Matrix3<f64>) -> f64 {
        0.0
    }
    #[inline]
    fn torque(&self, _rotation: &Matrix3<f64>) -> Vector3<f64> {
        Vector3::zeros()
    }
    #[inline]
    fn is_torque_free(&self) -> bool {
        true
    }
}

impl<B: RigidBody + ?Sized> RigidBody for &B {
    #[inline]
    fn body(&self) -> &FreeRigidBody {
        (**self).body()
    }
    #[inline]
    fn potential(&self, rotation: &Matrix3<f64>) -> f64 {
        (**self).potential(rotation)
    }
    #[inline]
    fn torque(&self, rotation: &Matrix3<f64>) -> Vector3<f64> {
        (**self).torque(rotation)
    }
    #[inline]
    fn is_torque_free(&self) -> bool {
        (**self).is_torque_free()
    }
}

/// A heavy top: a rigid body with a fixed point in uniform gravity `−g e₃` (space frame).
///
/// `V(R) = w e₃ᵀ R ρ` with the weight `w = m g` and `ρ` the body-frame vector from the fixed
/// point to the centre of mass; `M(R) = w (Rᵀe₃) × ρ`. The inertia `J` is about the fixed point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyTop {
    body: FreeRigidBody,
    weight: f64,
    center: Vector3<f64>,
}

impl HeavyTop {
    /// A heavy top with inertia `body` about the fixed point, weight `w = m g` and centre of mass
    /// at body position `center`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-finite weight or centre.
    pub fn new(body: FreeRigidBody, weight: f64, center: Vector3<f64>) -> Result<Self, Error> {
        if !weight.is_finite() {
            return Err(Error::InvalidParameter {
                name: "weight",
                value: weight,
                reason: "the weight m g must be finite",
            });
        }
        if let Some(&c) = center.iter().find(|c| !c.is_finite()) {
            return Err(Error::InvalidParameter {
                name: "center",
                value: c,
                reason: "the centre of mass must be finite",
            });
        }
        Ok(Self {
            body,
            weight,
            center,
        })
    }

    /// Simo & Wong's fast top: `J = diag(5, 5, 1)`, `M g l = 20` with the centre of mass on the
    /// symmetry axis at unit distance (`w = 20`, `ρ = e₃`).
    #[must_use]
    pub fn simo_wong() -> Self {
        let body = FreeRigidBody::from_principal_moments(Vector3::new(5.0, 5.0, 1.0))
            .expect("diag(5, 5, 1) is a valid inertia");
        Self {
            body,
            weight: 20.0,
            center: Vector3::z(),
        }
    }

    /// Simo & Wong's initial state: `Λ₀ = exp(hat(0.05, 0, 0))`, body angular velocity
    /// `W₀ = (0, 0, 50)`, so `m₀ = J W₀ = (0, 0, 50)` and `H = 1250 + 20 cos 0.05 ≈ 1269.975`.
    #[must_use]
    pub fn simo_wong_initial() -> RigidBodyState {
        let r0: Rotation3<f64> = tumble_kinematics::so3::exp(&Vector3::new(0.05, 0.0, 0.0));
        RigidBodyState::new(&r0, Vector3::new(0.0, 0.0, 50.0))
    }

    /// The weight `w = m g`.
    #[must_use]
    pub fn weight(&self) -> f64 {
        self.weight
    }

    /// `ρ`: body position of the centre of mass relative to the fixed point.
    #[must_use]
    pub fn center(&self) -> Vector3<f64> {
        self.center
    }
}

impl RigidBody for HeavyTop {
    fn body(&self) -> &FreeRigidBody {
        &self.body
    }
    fn potential(&self, rotation: &Matrix3<f64>) -> f64 {
        self.weight * rotation.row(2).transpose().dot(&self.center)
    }
    fn torque(&self, rotation: &Matrix3<f64>) -> Vector3<f64> {
        // Rᵀe₃ is the third row of R.
        let up = rotation.row(2).transpose();
        up.cross(&self.center) * self.weight
    }
}

/// A vector field on `SO(3) × ℝᴺ`: `Ṙ = R hat(ξ(t, R, y))`, `ẏ = f(t, R, y)` (`ξ` in the body
/// frame, i.e. right-trivialized).
pub trait LieVectorField<const N: usize> {
    /// `(ξ, f)` at `(t, R, y)`. Must not allocate.
    fn eval(
        &self,
        t: f64,
        rotation: &Matrix3<f64>,
        y: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>);
}

impl<const N: usize, F: LieVectorField<N> + ?Sized> LieVectorField<N> for &F {
    fn eval(
        &self,
        t: f64,
        rotation: &Matrix3<f64>,
        y: &SVector<f64, N>,
    ) -> (Vector3<f64>, SVector<f64, N>) {
        (**self).eval(t, rotation, y)
    }
}

/// Euler's equations of a [`RigidBody`] as a [`LieVectorField`] on `SO(3) × ℝ³` with `y = m`:
/// `ξ = Ω = J⁻¹m`, `ṁ = m × Ω + M(R)`.
#[derive(Debug, Clone, Copy)]
pub struct EulerEquations<B>(pub B);

impl<B: RigidBody> LieVectorField<3> for EulerEquations<B> {
    #[inline]
    fn eval(
        &self,
        _t: f64,
        rotation: &Matrix3<f64>,
        m: &Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let omega = self.0.body().omega(m);
        let mut dm = m.cross(&omega);
        if !self.0.is_torque_free() {
            dm += self.0.torque(rotation);
        }
        (omega, dm)
    }
}
