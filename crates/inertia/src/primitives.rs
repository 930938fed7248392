//! Closed-form mass properties of uniform primitives.
//!
//! Every primitive is centred at the origin of its body frame (which is its centre of mass) and,
//! where it has a symmetry axis, that axis is body **z**; the tensors are therefore diagonal,
//! `diag(I_x, I_y, I_z)`. Move or turn them with [`MassProperties::translated`] and
//! [`MassProperties::rotated`], and assemble bodies with [`MassProperties::combine_all`].
//!
//! The formulas are the standard ones (each follows from `I_z = ∫ (x² + y²) dm` in the
//! coordinates natural to the shape); the crate's tests check each of them against an
//! independent construction (point masses or a fine mesh) and measure the convergence rate.
//!
//! # References
//! - H. Goldstein, C. Poole, J. Safko, *Classical Mechanics*, 3rd ed., Addison-Wesley (2002),
//!   §5.3 (the inertia tensor) and the usual table of moments of uniform bodies.
//! - E. W. Weisstein, "Torus", *MathWorld* (the solid torus' moments).

use nalgebra::{Matrix3, Point3, Vector3};

use crate::error::InertiaError;
use crate::mass_properties::MassProperties;
use crate::principal::Definiteness;

/// `Ok(value)` if `value` is finite and positive, else [`InertiaError::InvalidDimension`].
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, InertiaError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(InertiaError::InvalidDimension {
            name,
            value,
            requirement: "must be finite and positive",
        })
    }
}

/// `Ok(mass)` if finite and positive, else the matching [`InertiaError`].
fn positive_mass(mass: f64) -> Result<f64, InertiaError> {
    if !mass.is_finite() {
        Err(InertiaError::NonFiniteMass { mass })
    } else if mass <= 0.0 {
        Err(InertiaError::NonPositiveMass { mass })
    } else {
        Ok(mass)
    }
}

fn centred(
    mass: f64,
    moments: Vector3<f64>,
    definiteness: Definiteness,
) -> Result<MassProperties, InertiaError> {
    MassProperties::validated(
        mass,
        Point3::origin(),
        Matrix3::from_diagonal(&moments),
        definiteness,
    )
}

impl MassProperties {
    /// A thin hoop (ring) of mass `M` and radius `R` in the body x–y plane, normal along z:
    /// `diag(MR²/2, MR²/2, MR²)`.
    ///
    /// All the mass is at distance `R` from z, and by symmetry `I_x = I_y = I_z / 2` (the
    /// perpendicular-axis theorem for a planar body: `I_x + I_y = I_z`).
    ///
    /// # Errors
    /// [`InertiaError`] for a mass or radius that is not finite and positive.
    pub fn thin_hoop(mass: f64, radius: f64) -> Result<Self, InertiaError> {
        let m = positive_mass(mass)?;
        let r2 = positive("radius", radius)?.powi(2);
        centred(
            m,
            Vector3::new(m * r2 / 2.0, m * r2 / 2.0, m * r2),
            Definiteness::Positive,
        )
    }

    /// A thin uniform disk of mass `M` and radius `R` in the body x–y plane, normal along z:
    /// `diag(MR²/4, MR²/4, MR²/2)`.
    ///
    /// # Errors
    /// [`InertiaError`] for a mass or radius that is not finite and positive.
    pub fn thin_disk(mass: f64, radius: f64) -> Result<Self, InertiaError> {
        let m = positive_mass(mass)?;
        let r2 = positive("radius", radius)?.powi(2);
        centred(
            m,
            Vector3::new(m * r2 / 4.0, m * r2 / 4.0, m * r2 / 2.0),
            Definiteness::Positive,
        )
    }

    /// A solid uniform cylinder (or thick disk) of mass `M`, radius `R` and height `h`, axis
    /// along body z, centred: `I_x = I_y = M (3R² + h²)/12`, `I_z = MR²/2`.
    ///
    /// # Errors
    /// [`InertiaError`] for a mass, radius or height that is not finite and positive.
    pub fn solid_cylinder(mass: f64, radius: f64, height: f64) -> Result<Self, InertiaError> {
        let m = positive_mass(mass)?;
        let r2 = positive("radius", radius)?.powi(2);
        let h2 = positive("height", height)?.powi(2);
        let transverse = m * (3.0 * r2 + h2) / 12.0;
        centred(
            m,
            Vector3::new(transverse, transverse, m * r2 / 2.0),
            Definiteness::Positive,
        )
    }

    /// A thin uniform rod of mass `M` and length `L` along body z, centred:
    /// `diag(ML²/12, ML²/12, 0)`.
    ///
    /// An idealized one-dimensional body: its moment about its own axis is zero, so it is not
    /// positive definite on its own (see [`MassProperties::try_new_idealized`]); it is a valid
    /// part of a composite body.
    ///
    /// # Errors
    /// [`InertiaError`] for a mass or length that is not finite and positive.
    pub fn thin_rod(mass: f64, length: f64) -> Result<Self, InertiaError> {
        let m = positive_mass(mass)?;
        let l2 = positive("length", length)?.powi(2);
        centred(
            m,
            Vector3::new(m * l2 / 12.0, m * l2 / 12.0, 0.0),
            Definiteness::SemiDefinite,
        )
    }

    /// A solid uniform sphere (ball) of mass `M` and radius `R`: `(2/5) MR² 𝟙`.
    ///
    /// # Errors
    /// [`InertiaError`] for a mass or radius that is not finite and positive.
    pub fn solid_sphere(mass: f64, radius: f64) -> Result<Self, InertiaError> {
        let m = positive_mass(mass)?;
        let r2 = positive("radius", radius)?.powi(2);
        centred(
            m,
            Vector3::repeat(2.0 * m * r2 / 5.0),
            Definiteness::Positive,
        )
    }

    /// A hollow sphere (thin uniform spherical shell) of mass `M` and radius `R`: `(2/3) MR² 𝟙`.
    ///
    /// # Errors
    /// [`InertiaError`] for a mass or radius that is not finite and positive.
    pub fn hollow_sphere(mass: f64, radius: f64) -> Result<Self, InertiaError> {
        let m = positive_mass(mass)?;
        let r2 = positive("radius", radius)?.powi(2);
        centred(
            m,
            Vector3::repeat(2.0 * m * r2 / 3.0),
            Definiteness::Positive,
        )
    }

    /// A solid uniform box of mass `M` with side lengths `(a, b, c)` along body x, y, z,
    /// centred: `diag(M(b² + c²)/12, M(a² + c²)/12, M(a² + b²)/12)`.
    ///
    /// # Errors
    /// [`InertiaError`] for a mass or side that is not finite and positive.
    pub fn solid_box(mass: f64, sides: &Vector3<f64>) -> Result<Self, InertiaError> {
        let m = positive_mass(mass)?;
        let a2 = positive("box side x", sides.x)?.powi(2);
        let b2 = positive("box side y", sides.y)?.powi(2);
        let c2 = positive("box side z", sides.z)?.powi(2);
        centred(
            m,
            Vector3::new(m * (b2 + c2), m * (a2 + c2), m * (a2 + b2)) / 12.0,
            Definiteness::Positive,
        )
    }

    /// A solid uniform torus of mass `M`: tube radius `r` (minor) around a centre-line circle of
    /// radius `R` (major) in the body x–y plane, symmetry axis z, centred:
    /// `I_z = M (R² + 3r²/4)`, `I_x = I_y = M (R²/2 + 5r²/8)`.
    ///
    /// (In tube coordinates `x = (R + ρ cos α) cos φ`, …, `dV = ρ (R + ρ cos α) dρ dα dφ`;
    /// integrating `x² + y²` and `z²` over `ρ ≤ r` gives `V = 2π²Rr²`, `∫(x²+y²) dV / V = R² +
    /// 3r²/4` and `∫ z² dV / V = r²/4`.)
    ///
    /// # Errors
    /// [`InertiaError`] for a mass or radius that is not finite and positive, and
    /// [`InertiaError::SelfIntersectingTorus`] for `r > R`.
    pub fn solid_torus(
        mass: f64,
        major_radius: f64,
        minor_radius: f64,
    ) -> Result<Self, InertiaError> {
        let m = positive_mass(mass)?;
        let big = positive("major radius", major_radius)?;
        let small = positive("minor radius", minor_radius)?;
        if small > big {
            return Err(InertiaError::SelfIntersectingTorus {
                major_radius,
                minor_radius,
            });
        }
        let (big2, small2) = (big * big, small * small);
        let transverse = m * (big2 / 2.0 + 5.0 * small2 / 8.0);
        centred(
            m,
            Vector3::new(transverse, transverse, m * (big2 + 3.0 * small2 / 4.0)),
            Definiteness::Positive,
        )
    }
}
