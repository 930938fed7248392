//! Rotating frames: the transport theorem and the effective (fictitious) forces.
//!
//! # Conventions
//!
//! A frame rotates with angular velocity `ω` relative to an inertial frame; its origin is fixed
//! in the inertial frame (a moving origin adds its own acceleration to the applied force). All
//! vectors here — `ω`, `ω̇`, a position `r`, a velocity `v_r` measured in the rotating frame — are
//! expressed in the **rotating frame's components**, where `ω̇` is the same whichever frame
//! differentiates it (`ω × ω = 0`).
//!
//! * Transport theorem, for any vector `G`: `(dG/dt)_inertial = (dG/dt)_rotating + ω × G`.
//! * Newton's law in the rotating frame: `m a_r = F_eff` with
//!   `F_eff = F − 2m ω × v_r − m ω × (ω × r) − m ω̇ × r`
//!   (Coriolis, centrifugal and Euler forces).
//!
//! Applied to the Earth (angular speed `Ω = 7.292e-5 rad/s`) in a local east-north-up frame at
//! colatitude `θ`, `ω = Ω (0, sin θ, cos θ)` ([`earth_rotation_enu`]). A body dropped from rest
//! from height `h` then lands `x ≈ Ω sin θ (2h)^{3/2} / (3 √g)` to the east (2.2 cm for
//! `h = 100 m` at the equator).
//!
//! # References
//! * Physics 151, lecture 9 (rotating frames, Coriolis effect); Goldstein, Poole & Safko,
//!   *Classical Mechanics*, 3rd ed., §4.9–4.10.

use nalgebra::{RealField, Vector3};

use crate::real;

/// The Earth's sidereal angular speed (rad/s).
pub const EARTH_ANGULAR_SPEED: f64 = 7.292_115e-5;

/// `(dG/dt)_inertial = (dG/dt)_rotating + ω × G`.
#[must_use]
pub fn inertial_rate<T: RealField + Copy>(
    omega: &Vector3<T>,
    g: &Vector3<T>,
    rotating_rate: &Vector3<T>,
) -> Vector3<T> {
    rotating_rate + omega.cross(g)
}

/// `(dG/dt)_rotating = (dG/dt)_inertial − ω × G` (the transport theorem solved the other way).
#[must_use]
pub fn rotating_rate<T: RealField + Copy>(
    omega: &Vector3<T>,
    g: &Vector3<T>,
    inertial_rate: &Vector3<T>,
) -> Vector3<T> {
    inertial_rate - omega.cross(g)
}

/// The Earth's rotation vector in a local east-north-up frame at colatitude `colatitude` (rad):
/// `Ω (0, sin θ, cos θ)`.
#[must_use]
pub fn earth_rotation_enu<T: RealField + Copy>(angular_speed: T, colatitude: T) -> Vector3<T> {
    Vector3::new(T::zero(), colatitude.sin(), colatitude.cos()) * angular_speed
}

/// A frame rotating with angular velocity `omega` and angular acceleration `omega_dot`, both in
/// the rotating frame's components, about an origin fixed in the inertial frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotatingFrame<T: RealField + Copy> {
    /// Angular velocity of the frame (rad/s).
    pub omega: Vector3<T>,
    /// Angular acceleration of the frame (rad/s²).
    pub omega_dot: Vector3<T>,
}

/// The three fictitious forces felt by a particle in a rotating frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FictitiousForces<T: RealField + Copy> {
    /// `−2m ω × v_r`.
    pub coriolis: Vector3<T>,
    /// `−m ω × (ω × r)`.
    pub centrifugal: Vector3<T>,
    /// `−m ω̇ × r`.
    pub euler: Vector3<T>,
}

impl<T: RealField + Copy> FictitiousForces<T> {
    /// Their sum.
    #[must_use]
    pub fn total(&self) -> Vector3<T> {
        self.coriolis + self.centrifugal + self.euler
    }
}

impl<T: RealField + Copy> RotatingFrame<T> {
    /// A frame rotating uniformly (`ω̇ = 0`).
    #[must_use]
    pub fn uniform(omega: Vector3<T>) -> Self {
        RotatingFrame {
            omega,
            omega_dot: Vector3::zeros(),
        }
    }

    /// Velocity in the inertial frame of a point at `r` moving with `v_r` in the rotating frame:
    /// `v = v_r + ω × r`.
    #[must_use]
    pub fn inertial_velocity(&self, r: &Vector3<T>, v_r: &Vector3<T>) -> Vector3<T> {
        inertial_rate(&self.omega, r, v_r)
    }

    /// The Coriolis, centrifugal and Euler forces on a particle of mass `mass` at `r` with
    /// velocity `v_r` relative to the rotating frame.
    #[must_use]
    pub fn fictitious_forces(
        &self,
        mass: T,
        r: &Vector3<T>,
        v_r: &Vector3<T>,
    ) -> FictitiousForces<T> {
        let two: T = real(2.0);
        FictitiousForces {
            coriolis: -(self.omega.cross(v_r) * (two * mass)),
            centrifugal: -(self.omega.cross(&self.omega.cross(r)) * mass),
            euler: -(self.omega_dot.cross(r) * mass),
        }
    }

    /// `F_eff = F − 2m ω × v_r − m ω × (ω × r) − m ω̇ × r`.
    #[must_use]
    pub fn effective_force(
        &self,
        force: &Vector3<T>,
        mass: T,
        r: &Vector3<T>,
        v_r: &Vector3<T>,
    ) -> Vector3<T> {
        force + self.fictitious_forces(mass, r, v_r).total()
    }

    /// Acceleration relative to the rotating frame, `a_r = F_eff / m`, for a force per unit mass
    /// `specific_force = F/m` (so the mass drops out).
    #[must_use]
    pub fn relative_acceleration(
        &self,
        specific_force: &Vector3<T>,
        r: &Vector3<T>,
        v_r: &Vector3<T>,
    ) -> Vector3<T> {
        self.effective_force(specific_force, T::one(), r, v_r)
    }
}

/// Closed-form eastward deflection of a body dropped from rest from height `height` at
/// colatitude `colatitude`, to first order in the angular speed:
/// `x = Ω sin θ (2h)^{3/2} / (3 √g)`.
#[must_use]
pub fn drop_deflection_east(angular_speed: f64, colatitude: f64, height: f64, g: f64) -> f64 {
    angular_speed * colatitude.sin() * (2.0 * height).powf(1.5) / (3.0 * g.sqrt())
}
