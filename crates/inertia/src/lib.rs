//! Mass properties of rigid bodies: point masses, primitives with closed forms, and closed
//! triangle meshes, computed once in the body frame.
//!
//! "The article" in these docs is Andy Rundquist's blog post "Rigid bodies, formulation and
//! examples" (Euler angles ZYZ, the bead on a driven, spinning and free hoop); "the lecture" is
//! Harvard Physics 151, lecture 9, "Rigid Body Motion". The repository's `docs/design.md`
//! summarizes what the code takes from them.
//!
//! # Conventions
//!
//! SI units throughout (kg, m, kg·m²). A [`MassProperties`] holds the mass, the centre of mass
//! in the body frame, and the inertia tensor **about the centre of mass** with body-frame
//! components, `I = ∫ (|r|² 𝟙 − r rᵀ) dm`, `r` measured from the centre of mass. Primitives are
//! centred with their symmetry axis along body z. Rotations are active (`R` turns the body;
//! its tensor becomes `R I Rᵀ`). Principal moments are ascending; principal axes are the
//! columns of a proper rotation `Q` with `I = Q diag(I1, I2, I3) Qᵀ`.
//!
//! # Design choices
//!
//! * **Validated values.** [`MassProperties`] keeps its fields private and is only built
//!   through checks: positive finite mass, finite centre, a symmetric tensor whose principal
//!   moments are positive and satisfy the triangle inequality `Iᵢ + Iⱼ ≥ Iₖ` (every
//!   permutation). The check needs the eigendecomposition anyway, so the principal frame is
//!   computed once, on construction. Idealized lower-dimensional parts (a point mass, a thin
//!   rod) have a zero moment; they are accepted only through the explicitly named
//!   [`MassProperties::try_new_idealized`] and the constructors that produce them, never by
//!   loosening [`MassProperties::try_new`]. Tolerances only absorb round-off
//!   ([`REALIZABILITY_TOLERANCE`]); nothing is clamped.
//! * **Meshes are validated before use** ([`TriangleMesh`]): closed, manifold, consistently
//!   and outward oriented, no degenerate faces (relative to the mesh's size). Each failure is
//!   its own [`MeshError`] naming the face or edge. A negative volume is an error, never an
//!   `abs()`; flipping an inverted mesh is an explicit option.
//! * **Accurate integrals.** Mesh integrals are sums over signed tetrahedra (the divergence
//!   theorem; Mirtich 1996, Eberly 2002, Tonon 2004) taken about a point near the solid, in two
//!   passes (centroid, then second moments about it) with compensated summation, so translating
//!   a mesh far from the origin costs no accuracy beyond that of its coordinates. Point-mass
//!   sums and combinations are two-pass for the same reason.
//! * **Eigen with faer.** Principal axes come from faer's self-adjoint eigendecomposition and
//!   are put in a canonical right-handed form, so degenerate moments (spheres, symmetric
//!   cylinders) still give a valid orthonormal frame, and a diagonal tensor gives (a signed
//!   permutation of) the identity.
//! * **Files.** OBJ via `tobj` (read as f64), STL via `stl_io` (ASCII and binary, f32 vertices);
//!   vertices are merged only when exactly equal, so topology is checked on the surface as
//!   stored, never welded by a guessed distance.
//! * **The classroom exercise** (the article's ZYZ Euler angles, from `tumble-kinematics`):
//!   [`MassProperties::turned_zyz`] gives the tensor `R I Rᵀ` of the turned body, and
//!   [`MassProperties::principal_euler_zyz`] the angles that make it diagonal, with the
//!   gimbal-lock flag passed through.
//! * **No printing, no panics on input.** Every fallible function returns a typed error
//!   ([`InertiaError`], [`MeshError`], [`LoadError`]); the `tumble inertia` command prints.
//!
//! # Modules
//!
//! The main types are re-exported at the crate root; the modules hold the details:
//! [`mesh`] (validation and the divergence-theorem integrals), [`primitives`] (closed forms),
//! [`principal`] (eigendecomposition and realizability), [`io`] (OBJ and STL), [`body`] (bodies
//! assembled from meshes in a length unit, point masses and placed primitives), [`shapes`] and
//! [`t_handle`] (generated meshes), [`euler`] (the classroom exercise), [`error`].
//!
//! # Example
//!
//! ```
//! use nalgebra::Vector3;
//! use tumble_inertia::{shapes, MassProperties, MassSpec};
//!
//! // The 12-triangle box mesh agrees with the box formula.
//! let sides = Vector3::new(1.0, 2.0, 3.0);
//! let mesh = shapes::box_mesh(&sides)?;
//! let from_mesh = mesh.mass_properties(MassSpec::TotalMass(6.0))?;
//! let formula = MassProperties::solid_box(6.0, &sides)?;
//! assert!((from_mesh.inertia() - formula.inertia()).norm() < 1e-14);
//! // Principal moments ascending, axes a right-handed rotation.
//! let p = formula.principal();
//! assert!(p.moments[0] <= p.moments[1] && p.moments[1] <= p.moments[2]);
//! assert!((p.axes.matrix().determinant() - 1.0).abs() < 1e-15);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # References
//! - B. Mirtich, "Fast and accurate computation of polyhedral mass properties", *Journal of
//!   Graphics Tools* 1(2) (1996) 31–50.
//! - D. Eberly, "Polyhedral mass properties (revisited)", Geometric Tools (2002, rev. 2009).
//! - F. Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor in terms of its
//!   vertex coordinates", *Journal of Mathematics and Statistics* 1(1) (2004) 8–11.
//! - H. Goldstein, C. Poole, J. Safko, *Classical Mechanics*, 3rd ed. (2002), ch. 5: the
//!   inertia tensor, principal axes, the parallel-axis theorem.

pub mod body;
pub mod error;
pub mod euler;
pub mod io;
mod mass_properties;
pub mod mesh;
pub mod primitives;
pub mod principal;
pub mod shapes;
mod sum;
pub mod t_handle;

pub use body::{BodyError, Placement, Shape, Units, parse_points};
pub use error::{Edge, InertiaError, LoadError, MeshError};
pub use euler::off_diagonal_norm;
pub use io::{MeshFormat, load_mesh, load_obj, load_stl, parse_obj, parse_stl};
pub use mass_properties::{MassProperties, PointMass, parallel_axis_term};
pub use mesh::{MassSpec, TriangleMesh, ValidationOptions};
pub use principal::{
    PrincipalAxes, REALIZABILITY_TOLERANCE, principal_axes, realizable_principal_axes,
};
pub use t_handle::THandle;
