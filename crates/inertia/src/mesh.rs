//! Closed triangle meshes: validation and volume integrals by the divergence theorem.
//!
//! # The integrals
//!
//! For a closed, outward-oriented surface with triangles `(a, b, c)` (counter-clockwise seen
//! from outside), the divergence theorem turns each volume integral `∫ f dV` into a surface
//! integral; for polynomial `f` up to degree 2 the result is a sum over faces of the integral
//! over the *signed tetrahedron* spanned by a reference point `p` and the face (Mirtich 1996
//! evaluates the same surface integrals by projection, Eberly 2002 by direct subexpressions; the
//! tetrahedron form is Tonon 2004's). With `a, b, c` taken relative to `p`, `D = a·(b × c)` and
//! `s = a + b + c`, the tetrahedron contributes
//!
//! ```text
//! ∫ dV      = D / 6
//! ∫ x dV    = D / 24 · s
//! ∫ x xᵀ dV = D / 120 · (a aᵀ + b bᵀ + c cᵀ + s sᵀ)
//! ```
//!
//! (the second-moment line is Tonon's closed form, written as a matrix: its diagonal entries are
//! `D/60 (Σ xᵢ² + Σ_{i<j} xᵢ xⱼ)` and its off-diagonal ones `D/120 (2 Σ xᵢ yᵢ + Σ_{i≠j} xᵢ yⱼ)`,
//! summing over the tetrahedron's vertices, the one at `p` being zero). Tetrahedra of faces
//! seen from `p` from the back have `D < 0` and cancel what lies outside the solid, so `p` need
//! not be inside, but the sum cancels least when it is near the solid: the integrals are
//! computed in two passes, volume and centroid about the bounding-box centre, then the second
//! moments about the centroid itself, with compensated sums. The result is exact for the
//! polyhedron up to round-off, and invariant under translating the mesh up to the round-off of
//! the translated coordinates.
//!
//! # Validation
//!
//! In this order, each failure a [`MeshError`] naming the face or edge: at least one face;
//! vertex indices in range; finite coordinates; no degenerate face (area below
//! `relative_area_tolerance × d²`, `d` the bounding box' diagonal, so the test is independent of
//! units and of where the mesh sits); every undirected edge used by exactly two faces (more:
//! [`MeshError::NonManifoldEdge`]; one: [`MeshError::OpenEdge`]), the two traversing it in
//! opposite directions ([`MeshError::InconsistentOrientation`]); a positive signed volume
//! ([`MeshError::Inverted`], [`MeshError::ZeroVolume`]). An inverted mesh is flipped only if
//! [`ValidationOptions::flip_inverted`] asks for it.
//!
//! # References
//! - B. Mirtich, "Fast and accurate computation of polyhedral mass properties", *Journal of
//!   Graphics Tools* 1(2) (1996) 31–50.
//! - D. Eberly, "Polyhedral mass properties (revisited)", Geometric Tools (2002, rev. 2009).
//! - F. Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor in terms of its
//!   vertex coordinates", *Journal of Mathematics and Statistics* 1(1) (2004) 8–11.

use std::collections::HashMap;
use std::io::{self, Write};

use nalgebra::{Isometry3, Matrix3, Point3, Vector3};

use crate::error::{Edge, InertiaError, MeshError};
use crate::mass_properties::MassProperties;
use crate::principal::Definiteness;
use crate::sum::MomentSums;

/// The largest bounding-box diagonal of a mesh: the inertia integrals take fifth powers of the
/// coordinates, which overflow beyond about 1e61.
pub const MAX_DIAGONAL: f64 = 1e60;

/// The smallest bounding-box diagonal of a mesh: below about 1e-61 the fifth powers of the
/// coordinates underflow (and the degeneracy tests' tolerances with them).
pub const MIN_DIAGONAL: f64 = 1e-60;

/// How the mass of a solid is given: a uniform density, or the total mass (the density is then
/// `M / V`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MassSpec {
    /// Uniform density ρ (kg/m³).
    Density(f64),
    /// Total mass M (kg), spread uniformly.
    TotalMass(f64),
}

/// Options of [`TriangleMesh::try_new_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValidationOptions {
    /// A face is degenerate if its area is below this times the square of the mesh's
    /// bounding-box diagonal (and a mesh is flat if `|V|` is below it times the diagonal
    /// cubed). Default `1e-12`: far above the round-off of a computed area (`~ε d²`), far below
    /// any face a real mesh has (a mesh with 10⁸ faces has mean face area ~10⁻⁸ d²).
    pub relative_area_tolerance: f64,
    /// Reverse every face of a mesh whose signed volume is negative instead of returning
    /// [`MeshError::Inverted`]. Default `false`: an inverted mesh is usually a modelling error
    /// that the user should hear about; ask for the flip explicitly.
    pub flip_inverted: bool,
}

impl Default for ValidationOptions {
    fn default() -> Self {
        Self {
            relative_area_tolerance: 1e-12,
            flip_inverted: false,
        }
    }
}

/// A validated closed, consistently and outward oriented triangle mesh, with its volume
/// integrals.
///
/// Faces are triples of vertex indices, counter-clockwise seen from outside (outward normals by
/// the right-hand rule). Construction validates the mesh (see the [module docs](self)) and
/// computes the volume, centroid and second moment once; [`mass_properties`](Self::mass_properties)
/// then only scales them.
///
/// ```
/// use nalgebra::{Point3, Vector3};
/// use tumble_inertia::{MassProperties, MassSpec, TriangleMesh};
///
/// // A tetrahedron with outward faces.
/// let v = vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
///              Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0)];
/// let f = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
/// let mesh = TriangleMesh::try_new(v, f)?;
/// assert!((mesh.volume() - 1.0 / 6.0).abs() < 1e-16);
/// let body = mesh.mass_properties(MassSpec::TotalMass(3.0))?;
/// assert!((body.center_of_mass() - Point3::new(0.25, 0.25, 0.25)).norm() < 1e-16);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct TriangleMesh {
    vertices: Vec<Point3<f64>>,
    faces: Vec<[usize; 3]>,
    volume: f64,
    centroid: Point3<f64>,
    /// `∫ (x − c)(x − c)ᵀ dV`, the geometric covariance about the centroid.
    covariance: Matrix3<f64>,
    flipped: bool,
}

impl TriangleMesh {
    /// A validated mesh with the default [`ValidationOptions`].
    ///
    /// # Errors
    /// A [`MeshError`] naming the first problem found (see the [module docs](self)).
    pub fn try_new(vertices: Vec<Point3<f64>>, faces: Vec<[usize; 3]>) -> Result<Self, MeshError> {
        Self::try_new_with(vertices, faces, &ValidationOptions::default())
    }

    /// A validated mesh.
    ///
    /// # Errors
    /// [`MeshError::TooLarge`] for a bounding-box diagonal above [`MAX_DIAGONAL`],
    /// [`MeshError::TooSmall`] below [`MIN_DIAGONAL`];
    /// A [`MeshError`] naming the first problem found (see the [module docs](self));
    /// [`MeshError::InvalidTolerance`] for a negative or non-finite tolerance.
    pub fn try_new_with(
        vertices: Vec<Point3<f64>>,
        mut faces: Vec<[usize; 3]>,
        options: &ValidationOptions,
    ) -> Result<Self, MeshError> {
        let tolerance = options.relative_area_tolerance;
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(MeshError::InvalidTolerance { value: tolerance });
        }
        check_indices_and_coordinates(&vertices, &faces)?;
        let (lower, upper) = bounding_box(&vertices, &faces);
        let diagonal = (upper - lower).norm();
        if !(diagonal <= MAX_DIAGONAL) {
            return Err(MeshError::TooLarge {
                diagonal,
                limit: MAX_DIAGONAL,
            });
        }
        if diagonal < MIN_DIAGONAL {
            return Err(MeshError::TooSmall {
                diagonal,
                limit: MIN_DIAGONAL,
            });
        }
        check_face_areas(&vertices, &faces, tolerance * diagonal * diagonal)?;
        check_edges(&vertices, &faces)?;

        let reference = Point3::from((lower.coords + upper.coords) * 0.5);
        let (mut volume, mut centroid) = volume_and_centroid(&vertices, &faces, &reference);
        let volume_tolerance = tolerance * diagonal.powi(3);
        if volume.abs() <= volume_tolerance {
            return Err(MeshError::ZeroVolume {
                signed_volume: volume,
                tolerance: volume_tolerance,
            });
        }
        let mut flipped = false;
        if volume < 0.0 {
            if !options.flip_inverted {
                return Err(MeshError::Inverted {
                    signed_volume: volume,
                });
            }
            for face in &mut faces {
                face.swap(1, 2);
            }
            flipped = true;
            (volume, centroid) = volume_and_centroid(&vertices, &faces, &reference);
        }
        let covariance = second_moment(&vertices, &faces, &centroid);
        Ok(Self {
            vertices,
            faces,
            volume,
            centroid,
            covariance,
            flipped,
        })
    }

    /// The vertices.
    #[must_use]
    pub fn vertices(&self) -> &[Point3<f64>] {
        &self.vertices
    }

    /// The faces: vertex index triples, counter-clockwise seen from outside.
    #[must_use]
    pub fn faces(&self) -> &[[usize; 3]] {
        &self.faces
    }

    /// Enclosed volume (positive; m³).
    #[must_use]
    pub fn volume(&self) -> f64 {
        self.volume
    }

    /// Centroid of the enclosed volume (the centre of mass at uniform density).
    #[must_use]
    pub fn centroid(&self) -> Point3<f64> {
        self.centroid
    }

    /// Whether validation reversed the faces of an inverted mesh (only with
    /// [`ValidationOptions::flip_inverted`]).
    #[must_use]
    pub fn was_flipped(&self) -> bool {
        self.flipped
    }

    /// Mass properties of the solid at uniform density: `M = ρV`, the centre of mass at the
    /// centroid, `I = ρ (tr(C) 𝟙 − C)` with `C = ∫ (x − c)(x − c)ᵀ dV`.
    ///
    /// With [`MassSpec::TotalMass`], `ρ = M/V` and the mass is `M` exactly.
    ///
    /// # Errors
    /// [`InertiaError::InvalidDensity`] or a mass error for a non-positive or non-finite
    /// density or mass; a realizability error if the mesh's components combine to a
    /// non-physical tensor (possible only for overlapping or nested shells).
    pub fn mass_properties(&self, spec: MassSpec) -> Result<MassProperties, InertiaError> {
        let (density, mass) = match spec {
            MassSpec::Density(density) => {
                if !(density.is_finite() && density > 0.0) {
                    return Err(InertiaError::InvalidDensity { density });
                }
                (density, density * self.volume)
            }
            MassSpec::TotalMass(mass) => {
                if !mass.is_finite() {
                    return Err(InertiaError::NonFiniteMass { mass });
                }
                if mass <= 0.0 {
                    return Err(InertiaError::NonPositiveMass { mass });
                }
                (mass / self.volume, mass)
            }
        };
        let c = &self.covariance;
        let inertia = (Matrix3::identity() * c.trace() - c) * density;
        MassProperties::validated(mass, self.centroid, inertia, Definiteness::Positive)
    }

    /// The mesh moved rigidly by `isometry` (re-validated, integrals recomputed).
    ///
    /// # Errors
    /// Only if the moved coordinates overflow, or round-off makes a face degenerate that was
    /// barely above the tolerance.
    pub fn transformed(&self, isometry: &Isometry3<f64>) -> Result<Self, MeshError> {
        let vertices = self.vertices.iter().map(|v| isometry * v).collect();
        Self::try_new(vertices, self.faces.clone())
    }

    /// The mesh with every coordinate multiplied by `factor` (a change of length unit, e.g.
    /// `1e-3` for a file in millimetres), re-validated: volume scales by `factor³`, the
    /// centroid by `factor`, second moments by `factor⁵`.
    ///
    /// # Errors
    /// [`MeshError::InvalidShape`] for a factor that is not finite and positive; otherwise as
    /// [`transformed`](Self::transformed).
    pub fn scaled(&self, factor: f64) -> Result<Self, MeshError> {
        if !(factor.is_finite() && factor > 0.0) {
            return Err(MeshError::InvalidShape {
                parameter: "scale factor",
                value: factor,
                requirement: "must be finite and positive",
            });
        }
        let vertices = self.vertices.iter().map(|v| v * factor).collect();
        Self::try_new(vertices, self.faces.clone())
    }

    /// Axis-aligned bounding box of the vertices used by faces: `(min, max)`.
    #[must_use]
    pub fn bounding_box(&self) -> (Point3<f64>, Point3<f64>) {
        bounding_box(&self.vertices, &self.faces)
    }

    /// Writes the mesh as Wavefront OBJ: `comment` lines (prefixed `# `), then `v x y z` lines
    /// (shortest decimal that reads back to the same `f64`), then `f i j k` lines (1-based).
    ///
    /// # Errors
    /// The writer's I/O errors.
    pub fn write_obj<W: Write>(&self, mut writer: W, comment: &str) -> io::Result<()> {
        for line in comment.lines() {
            writeln!(writer, "# {line}")?;
        }
        for v in &self.vertices {
            // `+ 0.0` turns −0.0 into 0.0, so no "-0" appears in the file.
            writeln!(writer, "v {} {} {}", v.x + 0.0, v.y + 0.0, v.z + 0.0)?;
        }
        for f in &self.faces {
            writeln!(writer, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1)?;
        }
        Ok(())
    }
}

fn check_indices_and_coordinates(
    vertices: &[Point3<f64>],
    faces: &[[usize; 3]],
) -> Result<(), MeshError> {
    if faces.is_empty() {
        return Err(MeshError::Empty);
    }
    for (face, f) in faces.iter().enumerate() {
        for &index in f {
            if index >= vertices.len() {
                return Err(MeshError::VertexIndexOutOfRange {
                    face,
                    index,
                    vertex_count: vertices.len(),
                });
            }
            let position = vertices[index];
            if !position.iter().all(|x| x.is_finite()) {
                return Err(MeshError::NonFiniteVertex {
                    vertex: index,
                    position,
                });
            }
        }
    }
    Ok(())
}

fn bounding_box(vertices: &[Point3<f64>], faces: &[[usize; 3]]) -> (Point3<f64>, Point3<f64>) {
    let first = faces
        .first()
        .map_or_else(Point3::origin, |f| vertices[f[0]]);
    faces.iter().flatten().fold((first, first), |(lo, hi), &i| {
        (lo.inf(&vertices[i]), hi.sup(&vertices[i]))
    })
}

fn check_face_areas(
    vertices: &[Point3<f64>],
    faces: &[[usize; 3]],
    tolerance: f64,
) -> Result<(), MeshError> {
    for (face, f) in faces.iter().enumerate() {
        let [a, b, c] = f.map(|i| vertices[i]);
        let area = 0.5 * (b - a).cross(&(c - a)).norm();
        // A repeated vertex index is degenerate whatever the tolerance (its area is exactly 0).
        if area <= tolerance || f[0] == f[1] || f[1] == f[2] || f[2] == f[0] {
            return Err(MeshError::DegenerateFace {
                face,
                vertices: *f,
                area,
                tolerance,
            });
        }
    }
    Ok(())
}

/// Faces using an undirected edge, each with the direction it traverses the edge in.
#[derive(Default)]
struct EdgeUse {
    /// `(face, from, to)`.
    uses: Vec<(usize, usize, usize)>,
}

fn edge(vertices: &[Point3<f64>], from: usize, to: usize) -> Edge {
    Edge {
        from,
        to,
        from_position: vertices[from],
        to_position: vertices[to],
    }
}

fn check_edges(vertices: &[Point3<f64>], faces: &[[usize; 3]]) -> Result<(), MeshError> {
    // Edges in order of first appearance (face order, then edge order within the face), so that
    // the edge reported is the first offending one in the file, deterministically.
    let mut order: Vec<(usize, usize)> = Vec::with_capacity(faces.len() * 3 / 2);
    let mut uses: HashMap<(usize, usize), EdgeUse> = HashMap::with_capacity(faces.len() * 3 / 2);
    for (face, f) in faces.iter().enumerate() {
        for k in 0..3 {
            let (from, to) = (f[k], f[(k + 1) % 3]);
            let key = (from.min(to), from.max(to));
            let entry = uses.entry(key).or_insert_with(|| {
                order.push(key);
                EdgeUse::default()
            });
            entry.uses.push((face, from, to));
        }
    }
    // The most severe problem first: a non-manifold edge also makes "open" and "orientation"
    // meaningless around it.
    for key in &order {
        let u = &uses[key].uses;
        if u.len() > 2 {
            let (_, from, to) = u[0];
            return Err(MeshError::NonManifoldEdge {
                edge: edge(vertices, from, to),
                faces: u.iter().map(|&(face, _, _)| face).collect(),
            });
        }
    }
    for key in &order {
        let u = &uses[key].uses;
        if u.len() == 1 {
            let (face, from, to) = u[0];
            return Err(MeshError::OpenEdge {
                edge: edge(vertices, from, to),
                face,
            });
        }
    }
    for key in &order {
        let u = &uses[key].uses;
        let ((f0, from0, to0), (f1, from1, _)) = (u[0], u[1]);
        if from0 == from1 {
            return Err(MeshError::InconsistentOrientation {
                edge: edge(vertices, from0, to0),
                faces: [f0, f1],
            });
        }
    }
    Ok(())
}

/// Signed volume and centroid, from tetrahedra reaching back to `reference`.
fn volume_and_centroid(
    vertices: &[Point3<f64>],
    faces: &[[usize; 3]],
    reference: &Point3<f64>,
) -> (f64, Point3<f64>) {
    let mut sums = MomentSums::default();
    for f in faces {
        let [a, b, c] = f.map(|i| vertices[i] - reference);
        let d = a.dot(&b.cross(&c));
        sums.add_zeroth(d / 6.0);
        sums.add_first(&((a + b + c) * (d / 24.0)));
    }
    let volume = sums.zeroth();
    (volume, reference + sums.first() / volume)
}

/// `∫ (x − p)(x − p)ᵀ dV` (Tonon's tetrahedron formula, summed over faces).
fn second_moment(
    vertices: &[Point3<f64>],
    faces: &[[usize; 3]],
    reference: &Point3<f64>,
) -> Matrix3<f64> {
    let mut sums = MomentSums::default();
    for f in faces {
        let [a, b, c] = f.map(|i| vertices[i] - reference);
        let d = a.dot(&b.cross(&c));
        let s: Vector3<f64> = a + b + c;
        let m = a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose();
        sums.add_second(&(m * (d / 120.0)));
    }
    sums.second()
}
