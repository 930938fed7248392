//! The heavy top: a rigid body on a fixed pivot in uniform gravity.
//!
//! # Euler-angle model (AD twin)
//!
//! Coordinates `(φ, θ, ψ)`, the article's convention `R = R_z(φ) R_y(θ) R_z(ψ)`; body inertia `J`
//! about the pivot (any symmetric positive-definite tensor), mass `m`, centre of mass at body
//! vector `χ` from the pivot, gravity `(0, 0, −g)`:
//! `L = ½ ω'·(J ω') − m g (R χ)_z`, `ω'` the body angular velocity from the Euler rates.
//! For the symmetric (Lagrange) top `J = diag(I₁, I₁, I₃)`, `χ = l e₃` this is Goldstein's
//! `L = ½ I₁ (θ̇² + φ̇² sin²θ) + ½ I₃ (ψ̇ + φ̇ cos θ)² − m g l cos θ`, with `p_φ`, `p_ψ` and the
//! energy conserved. Singular at `θ = 0, π` (the symmetry axis vertical).

use nalgebra::{Matrix3, RealField, SVector, Vector3};
use tumble_kinematics::EulerConvention;

use crate::lagrangian::Lagrangian;

/// The heavy top in Euler angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyTopEuler {
    /// Body inertia about the pivot (kg·m²).
    pub inertia: Matrix3<f64>,
    /// `m g` (N).
    pub weight: f64,
    /// Centre of mass in the body frame, from the pivot (m).
    pub center_of_mass: Vector3<f64>,
}

impl Lagrangian<3> for HeavyTopEuler {
    fn lagrangian<D: RealField + Copy>(&self, _t: D, q: &SVector<D, 3>, qd: &SVector<D, 3>) -> D {
        let conv = EulerConvention::ARTICLE;
        let angles = Vector3::new(q[0], q[1], q[2]);
        let w = conv.omega_body(&angles, &Vector3::new(qd[0], qd[1], qd[2]));
        let j: Matrix3<D> = self.inertia.map(nalgebra::convert);
        let chi: Vector3<D> = self.center_of_mass.map(nalgebra::convert);
        let z = (conv.to_rotation(&angles) * chi).z;
        w.dot(&(j * w)) * nalgebra::convert::<f64, D>(0.5)
            - z * nalgebra::convert::<f64, D>(self.weight)
    }
}
