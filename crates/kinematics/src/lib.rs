//! # tumble-kinematics
//!
//! The geometry every tumble model stands on: rotations (SO(3) and its Lie algebra), Euler angles
//! in all twelve sequences, angular velocity from Euler rates and back, and the kinematics of
//! rotating frames.
//!
//! "The article" in these docs is Andy Rundquist's blog post "Rigid bodies, formulation and
//! examples" (Euler angles ZYZ, the bead on a driven, spinning and free hoop); "the lecture" is
//! Harvard Physics 151, lecture 9, "Rigid Body Motion". The repository's `docs/design.md`
//! summarizes what the code takes from them.
//!
//! ## Design choices
//!
//! * **Types are nalgebra's.** Rotations are [`nalgebra::Rotation3`] or
//!   [`nalgebra::UnitQuaternion`] (Hamilton product, components `w, i, j, k`), vectors are
//!   [`nalgebra::Vector3`]. Nothing here wraps them in new types.
//! * **Active rotations, body to space.** A rotation `R` maps the body-frame components of a
//!   vector to its space-frame (lab) components: `v_space = R v_body`. The body's angular velocity
//!   is `ω_space = vee(Ṙ Rᵀ)` in the space frame and `ω_body = vee(Rᵀ Ṙ) = Rᵀ ω_space` in the
//!   body frame.
//! * **Generic over the scalar.** Every function that a model may differentiate (`hat`, `exp`,
//!   Euler-angle rotations, angular velocity, rotating-frame forces) takes any
//!   `T: nalgebra::RealField + Copy`, so that dual numbers from `num-dual` flow through it and
//!   equations of motion can be formed by automatic differentiation. Small-angle branches are
//!   Taylor series in `θ²`, so derivatives stay finite at the identity.
//! * **Accuracy at the edges.** `log` uses the `atan2` form on the quaternion (accurate near 0 and
//!   near π); nalgebra's `scaled_axis`/`angle` are avoided because they lose tiny angles and are
//!   unstable near π. Euler-angle extraction works on the quaternion with `atan2` and `hypot` only
//!   (Bernardes & Viollet 2022), so it never produces NaN; at gimbal lock the returned angles
//!   still reproduce the rotation and a flag says that the first and third angles are not
//!   individually determined.
//! * **Singularities are reported, not hidden.** Euler rates from an angular velocity at gimbal
//!   lock, or the inverse Cayley map at a rotation by π, are typed errors ([`KinematicsError`]).
//!   The library never prints and never panics on user input.
//!
//! ## Modules
//! * [`so3`]: `hat`, `vee`, `exp`, `log`, Cayley map, right/left Jacobians (`dexp`, `dexpinv`).
//! * [`euler`]: the twelve Euler sequences, intrinsic and extrinsic, to and from rotations and
//!   quaternions; angular velocity in the space and body frames; Euler rates from angular velocity.
//! * [`frames`]: the transport theorem and the effective force in a rotating frame.
//!
//! ## Example
//!
//! The body-frame angular velocity from ZXZ Euler angles and rates (Goldstein's convention)
//! agrees with the textbook components (Goldstein, *Classical Mechanics*, 3rd ed., eq. 4.87,
//! with the rates `φ̇, θ̇, ψ̇`), and the angles come back from the rotation they build:
//!
//! ```
//! use nalgebra::Vector3;
//! use tumble_kinematics::{EulerConvention, EulerSequence, RotationKind};
//!
//! let zxz = EulerConvention { sequence: EulerSequence::ZXZ, kind: RotationKind::Intrinsic };
//! let (phi, theta, psi) = (0.3_f64, 1.1_f64, -0.7_f64);
//! let (phi_dot, theta_dot, psi_dot) = (0.5, -0.2, 4.0);
//! let angles = Vector3::new(phi, theta, psi);
//! let omega = zxz.omega_body(&angles, &Vector3::new(phi_dot, theta_dot, psi_dot));
//! let goldstein = Vector3::new(
//!     phi_dot * theta.sin() * psi.sin() + theta_dot * psi.cos(),
//!     phi_dot * theta.sin() * psi.cos() - theta_dot * psi.sin(),
//!     phi_dot * theta.cos() + psi_dot,
//! );
//! assert!((omega - goldstein).norm() < 1e-15);
//!
//! let back = zxz.from_rotation(&zxz.to_rotation(&angles));
//! assert!((back.angles - angles).norm() < 1e-14 && !back.gimbal_lock);
//! ```

pub mod angle;
pub mod euler;
pub mod frames;
pub mod so3;

pub use euler::{Axis, EulerConvention, EulerDecomposition, EulerSequence, RotationKind};
pub use frames::{FictitiousForces, RotatingFrame};

use nalgebra::RealField;

/// Errors of the kinematics crate: each says what is singular and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum KinematicsError {
    /// Euler rates cannot be recovered from an angular velocity at (or too near) gimbal lock.
    #[error(
        "Euler rates are singular for {convention} at middle angle {middle_angle} rad: \
         det E = {determinant:e}, smaller in magnitude than the tolerance {tolerance:e} \
         (gimbal lock at {singular_at})"
    )]
    EulerRateSingular {
        /// The convention, e.g. `intrinsic ZYZ`.
        convention: EulerConvention,
        /// The middle angle (θ).
        middle_angle: f64,
        /// The determinant of the rate matrix (`±sin θ` or `±cos θ`).
        determinant: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
        /// Where the singularity lies, e.g. `θ = 0 or π`.
        singular_at: &'static str,
    },
    /// The inverse Cayley map does not exist for a rotation by π.
    #[error(
        "inverse Cayley map is singular: 1 + tr R = {one_plus_trace:e} (rotation angle at or near π)"
    )]
    CayleySingular {
        /// `1 + tr R`, which vanishes for rotations by π.
        one_plus_trace: f64,
    },
    /// A string did not name an Euler sequence.
    #[error(
        "unknown Euler sequence `{0}`: expected three axis letters from x, y, z with no two \
         neighbours equal (e.g. zyz, zxz, zyx, xyz)"
    )]
    UnknownSequence(String),
}

/// `x` as the scalar type `T` (exact for the constants used in this crate).
#[inline]
pub(crate) fn real<T: RealField>(x: f64) -> T {
    nalgebra::convert(x)
}

/// The real part of a scalar as `f64` (for error messages).
#[inline]
pub(crate) fn to_f64<T: RealField>(x: T) -> f64 {
    x.to_subset().unwrap_or(f64::NAN)
}
