//! [`MassProperties`]: construction, validation and the operations on it (shift, rotate,
//! combine).

use nalgebra::{Matrix3, Point3, Rotation3, Vector3};

use crate::error::InertiaError;
use crate::principal::{Definiteness, PrincipalAxes, realizable_principal_axes_with};
use crate::sum::MomentSums;

/// Mass, centre of mass and inertia tensor of a rigid body, in its body frame.
///
/// * `mass` `M > 0` (kg);
/// * `center_of_mass` `c` (m), a point of the body frame;
/// * `inertia` `I = ∫ (|r|² 𝟙 − r rᵀ) dm` with `r = x − c`: the tensor **about the centre of
///   mass**, with components in the body frame (kg·m²).
///
/// Kinetic energy of rotation is `T = ½ ω·(I ω)` with `ω` in the body frame, and `I` is
/// constant there: compute it once (docs/design.md §1).
///
/// # Invariants
///
/// Every value of this type is a physical mass distribution: `M` positive and finite, `c` finite,
/// `I` finite and symmetric, its principal moments non-negative and obeying the triangle
/// inequality `Iᵢ + Iⱼ ≥ Iₖ` (see [`realizable_principal_axes`](crate::realizable_principal_axes)
/// for the round-off tolerance). Values from [`try_new`](Self::try_new) and from every solid
/// body (meshes, solid primitives) are moreover positive definite. Only idealized
/// lower-dimensional bodies, built with [`try_new_idealized`](Self::try_new_idealized) (a point
/// mass, a thin rod, collinear point masses), may have a zero principal moment; such a body is a
/// valid *part* of a rigid body, and [`is_positive_definite`](Self::is_positive_definite) tells
/// whether it can also be one on its own.
///
/// Fields are private so that the invariants hold; the principal axes are computed once, on
/// construction, as part of the validation.
///
/// ```
/// use nalgebra::{Point3, Vector3};
/// use tumble_inertia::MassProperties;
///
/// let ball = MassProperties::solid_sphere(2.0, 0.5)?;
/// // Shift the ball so its centre is at (1, 0, 0): the tensor about the origin grows by M·1².
/// let moved = ball.translated(&Vector3::new(1.0, 0.0, 0.0));
/// let about_origin = moved.inertia_about(&Point3::origin());
/// assert!((about_origin[(1, 1)] - (0.2 + 2.0)).abs() < 1e-15);
/// // ... and shifting back recovers the tensor about the centre of mass.
/// let back = MassProperties::try_from_inertia_about(2.0, Point3::new(1.0, 0.0, 0.0),
///                                                 &Point3::origin(), &about_origin)?;
/// assert!((back.inertia() - ball.inertia()).norm() < 1e-15);
/// # Ok::<(), tumble_inertia::InertiaError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct MassProperties {
    mass: f64,
    center_of_mass: Point3<f64>,
    inertia: Matrix3<f64>,
    principal: PrincipalAxes,
}

/// A point mass: `mass` (kg) at `position` (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointMass {
    /// Mass, positive.
    pub mass: f64,
    /// Position in the body frame.
    pub position: Point3<f64>,
}

impl PointMass {
    /// A point mass `mass` at `position`.
    #[must_use]
    pub fn new(mass: f64, position: Point3<f64>) -> Self {
        Self { mass, position }
    }
}

/// The parallel-axis term `M (|d|² 𝟙 − d dᵀ)`: the inertia about a point `O` of a point mass `M`
/// at `O + d`.
///
/// `I_O = I_cm + parallel_axis_term(M, c − O)` (Steiner's theorem; docs/design.md §1).
#[must_use]
pub fn parallel_axis_term(mass: f64, offset: &Vector3<f64>) -> Matrix3<f64> {
    (Matrix3::identity() * offset.norm_squared() - offset * offset.transpose()) * mass
}

/// `(A + Aᵀ)/2`: removes the round-off asymmetry of a tensor this crate computed itself
/// (`R I Rᵀ`, sums of products); never applied to values a caller supplies, which are checked.
pub(crate) fn symmetrized(a: &Matrix3<f64>) -> Matrix3<f64> {
    (a + a.transpose()) * 0.5
}

impl MassProperties {
    /// A rigid body from its mass, centre of mass and inertia about the centre of mass (body
    /// frame), checked to be physical and **positive definite**.
    ///
    /// # Errors
    /// [`InertiaError`] naming the first problem found: a non-finite or non-positive mass, a
    /// non-finite centre of mass, a non-finite or non-symmetric tensor (beyond round-off), a zero
    /// or negative principal moment, or moments that violate the triangle inequality.
    pub fn try_new(
        mass: f64,
        center_of_mass: Point3<f64>,
        inertia: Matrix3<f64>,
    ) -> Result<Self, InertiaError> {
        Self::validated(mass, center_of_mass, inertia, Definiteness::Positive)
    }

    /// Like [`try_new`](Self::try_new), but accepts zero principal moments: idealized
    /// lower-dimensional bodies (a point mass has no inertia about its centre, a thin rod none
    /// about its axis). Negative moments and triangle-inequality violations are still errors.
    ///
    /// # Errors
    /// As [`try_new`](Self::try_new), except that a zero principal moment is accepted.
    pub fn try_new_idealized(
        mass: f64,
        center_of_mass: Point3<f64>,
        inertia: Matrix3<f64>,
    ) -> Result<Self, InertiaError> {
        Self::validated(mass, center_of_mass, inertia, Definiteness::SemiDefinite)
    }

    pub(crate) fn validated(
        mass: f64,
        center_of_mass: Point3<f64>,
        inertia: Matrix3<f64>,
        definiteness: Definiteness,
    ) -> Result<Self, InertiaError> {
        if !mass.is_finite() {
            return Err(InertiaError::NonFiniteMass { mass });
        }
        if mass <= 0.0 {
            return Err(InertiaError::NonPositiveMass { mass });
        }
        if !center_of_mass.iter().all(|x| x.is_finite()) {
            return Err(InertiaError::NonFiniteCenterOfMass {
                center: center_of_mass.coords,
            });
        }
        let principal = realizable_principal_axes_with(&inertia, definiteness)?;
        Ok(Self {
            mass,
            center_of_mass,
            inertia: symmetrized(&inertia),
            principal,
        })
    }

    /// A body whose tensor is known about a point `point` other than the centre of mass: the
    /// parallel-axis theorem run backwards, `I_cm = I_O − M (|d|² 𝟙 − d dᵀ)` with
    /// `d = center_of_mass − point`.
    ///
    /// # Errors
    /// As [`try_new`](Self::try_new); in particular a tensor about `point` that is too small for
    /// a body of this mass centred there gives a non-positive-definite `I_cm`.
    pub fn try_from_inertia_about(
        mass: f64,
        center_of_mass: Point3<f64>,
        point: &Point3<f64>,
        inertia_about_point: &Matrix3<f64>,
    ) -> Result<Self, InertiaError> {
        let shift = parallel_axis_term(mass, &(center_of_mass - point));
        Self::try_new(mass, center_of_mass, inertia_about_point - shift)
    }

    /// The mass properties of a set of point masses.
    ///
    /// Two passes with compensated summation: the centre of mass first, then the tensor about it
    /// (`Σ mᵢ (|rᵢ|² 𝟙 − rᵢ rᵢᵀ)`, `rᵢ = pᵢ − c`), so no large terms cancel.
    ///
    /// A single point, or collinear points, have a zero principal moment: the result is an
    /// idealized body (see [`try_new_idealized`](Self::try_new_idealized)).
    ///
    /// # Errors
    /// [`InertiaError::Empty`] for no points; [`InertiaError::InvalidPointMass`] for a mass that
    /// is not positive and finite or a position that is not finite.
    pub fn from_point_masses(points: &[PointMass]) -> Result<Self, InertiaError> {
        if points.is_empty() {
            return Err(InertiaError::Empty);
        }
        let mut sums = MomentSums::default();
        for (index, p) in points.iter().enumerate() {
            let finite = p.mass.is_finite() && p.position.iter().all(|x| x.is_finite());
            if !finite || p.mass <= 0.0 {
                return Err(InertiaError::InvalidPointMass {
                    index,
                    mass: p.mass,
                    position: p.position,
                });
            }
            sums.add_zeroth(p.mass);
            sums.add_first(&(p.position.coords * p.mass));
        }
        let mass = sums.zeroth();
        let center = Point3::from(sums.first() / mass);
        let mut second = MomentSums::default();
        for p in points {
            second.add_second(&parallel_axis_term(p.mass, &(p.position - center)));
        }
        Self::validated(mass, center, second.second(), Definiteness::SemiDefinite)
    }

    /// Mass (kg).
    #[must_use]
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Centre of mass in the body frame (m).
    #[must_use]
    pub fn center_of_mass(&self) -> Point3<f64> {
        self.center_of_mass
    }

    /// Inertia tensor about the centre of mass, body-frame components (kg·m²).
    #[must_use]
    pub fn inertia(&self) -> &Matrix3<f64> {
        &self.inertia
    }

    /// Principal moments (ascending) and principal axes (a right-handed rotation whose columns
    /// are the axes), computed on construction.
    #[must_use]
    pub fn principal(&self) -> &PrincipalAxes {
        &self.principal
    }

    /// Whether every principal moment is positive beyond round-off (false only for idealized
    /// lower-dimensional bodies: a point mass, a thin rod, collinear point masses).
    #[must_use]
    pub fn is_positive_definite(&self) -> bool {
        crate::principal::is_positive_definite(&self.principal.moments)
    }

    /// The tensor about an arbitrary point `point` (body frame): the parallel-axis theorem
    /// `I_O = I_cm + M (|d|² 𝟙 − d dᵀ)` with `d = c − O` (docs/design.md §1).
    #[must_use]
    pub fn inertia_about(&self, point: &Point3<f64>) -> Matrix3<f64> {
        self.inertia + parallel_axis_term(self.mass, &(self.center_of_mass - point))
    }

    /// The same body moved rigidly by `offset`: the centre of mass moves, the tensor about it
    /// does not change.
    #[must_use]
    pub fn translated(&self, offset: &Vector3<f64>) -> Self {
        Self {
            center_of_mass: self.center_of_mass + offset,
            ..self.clone()
        }
    }

    /// The same body turned by the active rotation `rotation` about the frame's origin: the
    /// centre of mass goes to `R c` and the tensor to `R I Rᵀ` (its principal axes to `R Q`, its
    /// moments unchanged).
    #[must_use]
    pub fn rotated(&self, rotation: &Rotation3<f64>) -> Self {
        let r = rotation.matrix();
        Self {
            mass: self.mass,
            center_of_mass: rotation * self.center_of_mass,
            inertia: symmetrized(&(r * self.inertia * r.transpose())),
            principal: PrincipalAxes {
                moments: self.principal.moments,
                axes: rotation * self.principal.axes,
            },
        }
    }

    /// The rigid union of two bodies (both given in the same frame): masses add, the centre of
    /// mass is the mass-weighted mean, and each tensor is shifted to the common centre by the
    /// parallel-axis theorem before adding.
    ///
    /// # Errors
    /// Only [`InertiaError::EigenNoConvergence`] if the eigensolver fails, which it does not for
    /// finite symmetric 3×3 input.
    pub fn combine(&self, other: &Self) -> Result<Self, InertiaError> {
        Self::combine_all([self, other])
    }

    /// The rigid union of any number of bodies (see [`combine`](Self::combine)).
    ///
    /// The result is positive definite if any part is, or if the parts' centres are not
    /// collinear; otherwise (e.g. two point masses) it is an idealized body.
    ///
    /// # Errors
    /// [`InertiaError::Empty`] for no bodies; [`InertiaError::EigenNoConvergence`] as above.
    pub fn combine_all<'a>(
        bodies: impl IntoIterator<Item = &'a MassProperties>,
    ) -> Result<Self, InertiaError> {
        let bodies: Vec<&MassProperties> = bodies.into_iter().collect();
        if bodies.is_empty() {
            return Err(InertiaError::Empty);
        }
        let mut sums = MomentSums::default();
        for b in &bodies {
            sums.add_zeroth(b.mass);
            sums.add_first(&(b.center_of_mass.coords * b.mass));
        }
        let mass = sums.zeroth();
        let center = Point3::from(sums.first() / mass);
        let mut second = MomentSums::default();
        for b in &bodies {
            second.add_second(&b.inertia_about(&center));
        }
        Self::validated(mass, center, second.second(), Definiteness::SemiDefinite)
    }
}
