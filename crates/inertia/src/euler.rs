//! The article's classroom exercise: turn a body by Euler angles and watch its tensor; find the
//! angles that make the off-diagonal terms vanish.
//!
//! Convention (docs/design.md §2): the article's intrinsic ZYZ angles `(φ, θ, ψ)`, active rotation
//! `R = Rz(φ) Ry(θ) Rz(ψ)` from body to space ([`EulerConvention::ARTICLE`] of
//! `tumble-kinematics`; other conventions by name through the `*_with` functions).
//!
//! * [`MassProperties::turned_zyz`]: the body turned by `R` about the frame's origin; its
//!   tensor (about the centre of mass) is `R I Rᵀ`, its centre of mass `R c`.
//! * [`MassProperties::principal_euler_zyz`]: the angles of `Qᵀ`, where `Q`'s columns are the
//!   principal axes ([`PrincipalAxes::axes`](crate::PrincipalAxes)). Turning the body by them
//!   brings its principal axes onto the frame's x, y, z (ascending moments), so
//!   `turned_zyz(principal angles)` has the diagonal tensor `diag(I1, I2, I3)`; on the way
//!   there (e.g. along `t · angles`, `t → 1`) the off-diagonal terms shrink to zero.
//!
//! Euler angles are singular at `θ = 0, π` (gimbal lock: only `φ ± ψ` is determined). A body
//! whose principal axes already lie along the frame's axes is exactly there; the decomposition
//! then carries `gimbal_lock = true` and angles that still reproduce the rotation.

use nalgebra::{Matrix3, Vector3};
use tumble_kinematics::euler::{EulerConvention, EulerDecomposition};

use crate::mass_properties::MassProperties;

/// Frobenius norm of the off-diagonal part of a tensor: zero exactly in a principal frame.
#[must_use]
pub fn off_diagonal_norm(inertia: &Matrix3<f64>) -> f64 {
    let mut off = *inertia;
    off.fill_diagonal(0.0);
    off.norm()
}

impl MassProperties {
    /// The body turned by the article's ZYZ Euler angles `(φ, θ, ψ)` (radians):
    /// `R = Rz(φ) Ry(θ) Rz(ψ)`, tensor `R I Rᵀ`, centre of mass `R c`.
    #[must_use]
    pub fn turned_zyz(&self, angles: &Vector3<f64>) -> Self {
        self.turned_with(&EulerConvention::ARTICLE, angles)
    }

    /// The body turned by Euler angles of any convention (see [`turned_zyz`](Self::turned_zyz)).
    #[must_use]
    pub fn turned_with(&self, convention: &EulerConvention, angles: &Vector3<f64>) -> Self {
        self.rotated(&convention.to_rotation(angles))
    }

    /// The article's ZYZ angles of the turn that brings the principal axes onto the frame's
    /// axes (smallest moment along x), i.e. of `Qᵀ`; with the gimbal-lock flag of the
    /// decomposition.
    ///
    /// ```
    /// use nalgebra::{Matrix3, Point3};
    /// use tumble_inertia::{off_diagonal_norm, MassProperties};
    ///
    /// let i = Matrix3::new(3.0, -0.4, 0.2,
    ///                      -0.4, 2.0, 0.1,
    ///                      0.2, 0.1, 4.0);
    /// let body = MassProperties::try_new(1.0, Point3::origin(), i)?;
    /// let angles = body.principal_euler_zyz().angles;
    /// let turned = body.turned_zyz(&angles);
    /// assert!(off_diagonal_norm(turned.inertia()) < 1e-14);
    /// # Ok::<(), tumble_inertia::InertiaError>(())
    /// ```
    #[must_use]
    pub fn principal_euler_zyz(&self) -> EulerDecomposition<f64> {
        self.principal_euler_with(&EulerConvention::ARTICLE)
    }

    /// As [`principal_euler_zyz`](Self::principal_euler_zyz), in any convention.
    #[must_use]
    pub fn principal_euler_with(&self, convention: &EulerConvention) -> EulerDecomposition<f64> {
        convention.from_rotation(&self.principal().axes.inverse())
    }
}
