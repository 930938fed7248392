//! Typed errors of the crate.
//!
//! Three enums, by the stage at which something can go wrong:
//!
//! * [`InertiaError`]: a value is not a physical mass distribution (a non-positive mass, a
//!   non-symmetric or non-realizable tensor, a negative radius, …);
//! * [`MeshError`]: a triangle mesh does not bound a solid (open, non-manifold, inconsistently
//!   oriented, inverted, degenerate faces);
//! * [`LoadError`]: a mesh file cannot be read, or what it contains is not a valid mesh.
//!
//! Every variant says what was wrong and where: the offending value, the face index, the edge
//! (as a pair of vertex indices *and* their coordinates, since vertex numbering after loading need
//! not match the file's), the file. [`LoadError`] names the file and keeps the cause as its
//! [`source`](std::error::Error::source), so print the whole chain (e.g. `anyhow`'s `{:#}`).

use std::fmt;
use std::path::PathBuf;

use nalgebra::{Point3, Vector3};

/// An edge of a triangle mesh: two vertex indices and their positions.
///
/// `from → to` is the direction in which the face that the error refers to traverses the edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    /// Index of the first vertex (0-based, in the mesh's vertex list).
    pub from: usize,
    /// Index of the second vertex.
    pub to: usize,
    /// Position of the first vertex.
    pub from_position: Point3<f64>,
    /// Position of the second vertex.
    pub to_position: Point3<f64>,
}

impl fmt::Display for Edge {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = &self.from_position;
        let q = &self.to_position;
        write!(
            f,
            "edge v{} → v{} ({}, {}, {}) → ({}, {}, {})",
            self.from, self.to, p.x, p.y, p.z, q.x, q.y, q.z
        )
    }
}

/// A value that is not a physical mass distribution.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InertiaError {
    /// The mass is NaN or infinite.
    #[error("mass must be finite, got {mass}")]
    NonFiniteMass {
        /// The offending mass.
        mass: f64,
    },
    /// The mass is zero or negative.
    #[error("mass must be positive, got {mass}")]
    NonPositiveMass {
        /// The offending mass.
        mass: f64,
    },
    /// A component of the centre of mass is NaN or infinite.
    #[error("centre of mass must be finite, got ({}, {}, {})", center.x, center.y, center.z)]
    NonFiniteCenterOfMass {
        /// The offending centre of mass.
        center: Vector3<f64>,
    },
    /// An entry of the inertia tensor is NaN or infinite.
    #[error("inertia tensor entry ({row}, {col}) must be finite, got {value}")]
    NonFiniteInertia {
        /// Row of the entry (0-based).
        row: usize,
        /// Column of the entry (0-based).
        col: usize,
        /// The offending value.
        value: f64,
    },
    /// The inertia tensor is not symmetric beyond round-off.
    #[error(
        "inertia tensor is not symmetric: entry ({row}, {col}) = {upper} but ({col}, {row}) = {lower}"
    )]
    NotSymmetric {
        /// Row of the upper entry (0-based).
        row: usize,
        /// Column of the upper entry (0-based).
        col: usize,
        /// `I[(row, col)]`.
        upper: f64,
        /// `I[(col, row)]`.
        lower: f64,
    },
    /// A principal moment is negative (beyond round-off), or zero where a positive-definite
    /// tensor is required.
    #[error(
        "inertia tensor is not positive definite: principal moments {} {} {}",
        moments.x, moments.y, moments.z
    )]
    NotPositiveDefinite {
        /// The principal moments, ascending.
        moments: Vector3<f64>,
    },
    /// The principal moments violate the triangle inequality `I1 + I2 ≥ I3`, so no mass
    /// distribution has them.
    #[error(
        "principal moments {} {} {} violate the triangle inequality: {} + {} < {}",
        moments.x, moments.y, moments.z, moments.x, moments.y, moments.z
    )]
    TriangleInequality {
        /// The principal moments, ascending (the violated permutation is always `I1 + I2 < I3`).
        moments: Vector3<f64>,
    },
    /// A length (radius, side, …) of a body is out of range (not finite and positive, or
    /// inconsistent with another one).
    #[error("{name} {requirement}, got {value}")]
    InvalidDimension {
        /// Which parameter (e.g. `"radius"`).
        name: &'static str,
        /// The offending value.
        value: f64,
        /// What it must satisfy (e.g. `"must be finite and positive"`).
        requirement: &'static str,
    },
    /// A torus whose tube radius is not smaller than its centre-line radius intersects itself.
    #[error(
        "torus tube radius {minor_radius} must be smaller than its centre-line radius {major_radius}"
    )]
    SelfIntersectingTorus {
        /// Radius of the tube's centre line.
        major_radius: f64,
        /// Radius of the tube.
        minor_radius: f64,
    },
    /// A density is not finite and positive.
    #[error("density must be finite and positive, got {density}")]
    InvalidDensity {
        /// The offending density.
        density: f64,
    },
    /// A point mass has a non-positive or non-finite mass, or a non-finite position.
    #[error("point mass {index}: mass {mass} at ({}, {}, {}) must be positive and finite", position.x, position.y, position.z)]
    InvalidPointMass {
        /// Index of the point mass in the input.
        index: usize,
        /// Its mass.
        mass: f64,
        /// Its position.
        position: Point3<f64>,
    },
    /// Nothing to build a body from (no point masses, no bodies to combine).
    #[error("no bodies or point masses given")]
    Empty,
    /// The symmetric eigendecomposition did not converge (faer reports `NoConvergence`).
    #[error("symmetric eigendecomposition of the inertia tensor did not converge")]
    EigenNoConvergence,
}

/// A triangle mesh that does not bound a solid.
///
/// Vertex and face indices are 0-based positions in the mesh's vertex and face lists; for a mesh
/// loaded from a file, faces are numbered in file order after polygons were split into triangles,
/// and vertices after exactly coincident vertices were merged. Edges also carry their coordinates.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no faces.
    #[error("mesh has no faces")]
    Empty,
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate ({}, {}, {})", position.x, position.y, position.z)]
    NonFiniteVertex {
        /// Index of the vertex.
        vertex: usize,
        /// Its coordinates.
        position: Point3<f64>,
    },
    /// The mesh is so large that its integrals (up to fifth powers of the coordinates)
    /// overflow.
    #[error(
        "mesh is too large: its bounding-box diagonal is {diagonal:e}, above {limit:e}, where \
         the volume and inertia integrals overflow; give the coordinates in a larger unit"
    )]
    TooLarge {
        /// The bounding box's diagonal.
        diagonal: f64,
        /// The largest diagonal accepted.
        limit: f64,
    },
    /// The mesh is so small that its integrals (up to fifth powers of the coordinates)
    /// underflow.
    #[error(
        "mesh is too small: its bounding-box diagonal is {diagonal:e}, below {limit:e}, where \
         the volume and inertia integrals underflow to zero; give the coordinates in a smaller \
         unit (and `units` to match)"
    )]
    TooSmall {
        /// The bounding box's diagonal.
        diagonal: f64,
        /// The smallest diagonal accepted.
        limit: f64,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index}, but the mesh has {vertex_count} vertices")]
    VertexIndexOutOfRange {
        /// Index of the face.
        face: usize,
        /// The offending vertex index.
        index: usize,
        /// Number of vertices in the mesh.
        vertex_count: usize,
    },
    /// A face has (nearly) zero area: a repeated vertex, or three (nearly) collinear vertices.
    #[error(
        "degenerate face {face} (vertices {} {} {}): area {area:.3e} is below the tolerance {tolerance:.3e} \
         (relative tolerance × bounding-box diagonal²)",
        vertices[0], vertices[1], vertices[2]
    )]
    DegenerateFace {
        /// Index of the face.
        face: usize,
        /// Its vertex indices.
        vertices: [usize; 3],
        /// Its area.
        area: f64,
        /// The area below which a face counts as degenerate.
        tolerance: f64,
    },
    /// An edge is used by only one face: the surface has a hole.
    #[error("mesh is open: {edge} belongs to face {face} only (a closed surface needs two)")]
    OpenEdge {
        /// The boundary edge, as face `face` traverses it.
        edge: Edge,
        /// The only face using it.
        face: usize,
    },
    /// An edge is used by more than two faces: the surface is not a 2-manifold there.
    #[error("mesh is non-manifold: {edge} is shared by {} faces ({faces:?}); a closed surface needs exactly two", faces.len())]
    NonManifoldEdge {
        /// The edge, as the first face listed traverses it.
        edge: Edge,
        /// Every face using the edge.
        faces: Vec<usize>,
    },
    /// Two faces traverse a shared edge in the same direction: their normals disagree.
    #[error(
        "mesh is inconsistently oriented: faces {} and {} both traverse {edge} in the same direction",
        faces[0], faces[1]
    )]
    InconsistentOrientation {
        /// The edge, in the direction both faces traverse it.
        edge: Edge,
        /// The two faces.
        faces: [usize; 2],
    },
    /// The mesh is closed and consistently oriented, but its faces point inwards.
    #[error(
        "mesh is inverted: its faces point inwards (signed volume {signed_volume:.6e} < 0); \
         reverse the face winding, or ask for the mesh to be flipped"
    )]
    Inverted {
        /// The (negative) signed volume.
        signed_volume: f64,
    },
    /// The mesh encloses no volume (e.g. a flat, doubly covered surface).
    #[error(
        "mesh encloses no volume: signed volume {signed_volume:.3e} is within the tolerance {tolerance:.3e} of zero"
    )]
    ZeroVolume {
        /// The signed volume.
        signed_volume: f64,
        /// The volume below which the mesh counts as flat.
        tolerance: f64,
    },
    /// A mesh generator was given a parameter outside its range.
    #[error("{parameter} = {value} is invalid: {requirement}")]
    InvalidShape {
        /// Which parameter.
        parameter: &'static str,
        /// Its value.
        value: f64,
        /// What it must satisfy.
        requirement: &'static str,
    },
    /// The relative area tolerance is not finite and non-negative.
    #[error("relative area tolerance must be finite and non-negative, got {value}")]
    InvalidTolerance {
        /// The offending tolerance.
        value: f64,
    },
}

/// A mesh file that cannot be read or does not hold a valid mesh.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file cannot be opened or read.
    #[error("{}: cannot read file", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The file's extension is neither `.obj` nor `.stl`.
    #[error("{}: unknown mesh format (expected a .obj or .stl file)", path.display())]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// `tobj` could not parse the OBJ file.
    #[error("{}: cannot parse OBJ", path.display())]
    Obj {
        /// The file.
        path: PathBuf,
        /// The parser's error.
        #[source]
        source: tobj::LoadError,
    },
    /// A binary STL file whose size does not match the triangle count in its header (84
    /// bytes of header and count, then 50 bytes a triangle).
    #[error(
        "{}: not a whole binary STL file: {}, but the file has {size} bytes; it is truncated \
         or its triangle count is wrong: export it again (or as ASCII STL or OBJ)",
        path.display(),
        match count {
            Some(n) => format!(
                "its header counts {n} triangles, which take 84 + 50 × {n} = {} bytes",
                84 + 50 * u64::from(*n)
            ),
            None => "a binary STL file has at least 84 bytes (header and triangle count)"
                .to_string(),
        }
    )]
    BinaryStlSize {
        /// The file.
        path: PathBuf,
        /// The triangle count in the header, if the file is long enough to hold one.
        count: Option<u32>,
        /// The file's size in bytes.
        size: u64,
    },
    /// `stl_io` could not parse the STL file.
    #[error("{}: cannot parse STL", path.display())]
    Stl {
        /// The file.
        path: PathBuf,
        /// The parser's error.
        #[source]
        source: std::io::Error,
    },
    /// The file parsed, but the mesh in it does not bound a solid.
    #[error("{}: invalid mesh", path.display())]
    Mesh {
        /// The file.
        path: PathBuf,
        /// What is wrong with the mesh.
        #[source]
        source: MeshError,
    },
}
