//! The T-handle of the `dzhanibekov` scene: a crossbar with a stem, both rectangular blocks.
//!
//! Body frame: the crossbar lies along x, the stem hangs from its middle along −z, both have the
//! same depth along y; the origin is the middle of the line where the stem meets the crossbar.
//!
//! ```text
//!         z
//!         ↑   bar_length (x)
//!   ┌─────┼─────┐  ↑
//!   │     │     │  bar_thickness
//!   └───┐ O ┌───┘  ↓    → x
//!       │   │
//!       │   │  stem_length
//!       └───┘
//!      stem_width
//! ```
//!
//! Two descriptions of the same solid, independent of each other, so that each checks the other:
//! [`THandle::mass_properties`] composes the closed-form box tensors with parallel-axis shifts,
//! and [`THandle::mesh`] builds the exact closed surface of the union (the T profile extruded
//! along y, 16 vertices, 28 triangles, no internal faces). The mirror symmetries `x → −x` and
//! `y → −y` make x, y, z principal axes; the dimensions of [`THandle::STANDARD`] give three
//! well-separated moments (ratio about 1 : 1.63 : 2.44), so spin about the intermediate axis
//! (x, the crossbar) is unstable: the Dzhanibekov effect.

use std::io::{self, Write};

use nalgebra::{Point3, Vector3};

use crate::error::{InertiaError, MeshError};
use crate::mass_properties::MassProperties;
use crate::mesh::{MassSpec, TriangleMesh};

/// Dimensions of a T-handle (m); see the [module docs](self) for the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct THandle {
    /// Length of the crossbar along x.
    pub bar_length: f64,
    /// Thickness of the crossbar along z.
    pub bar_thickness: f64,
    /// Depth of crossbar and stem along y.
    pub depth: f64,
    /// Width of the stem along x (smaller than `bar_length`).
    pub stem_width: f64,
    /// Length of the stem along −z.
    pub stem_length: f64,
}

impl THandle {
    /// The handle of the `dzhanibekov` scene and of `scenes/t-handle.obj`: an 80 mm crossbar of
    /// 20 mm × 20 mm section with a 60 mm stem of the same section.
    pub const STANDARD: Self = Self {
        bar_length: 0.08,
        bar_thickness: 0.02,
        depth: 0.02,
        stem_width: 0.02,
        stem_length: 0.06,
    };

    /// The first invalid dimension, if any: `(name, value, requirement)`.
    fn invalid_dimension(&self) -> Option<(&'static str, f64, &'static str)> {
        let lengths = [
            ("bar length", self.bar_length),
            ("bar thickness", self.bar_thickness),
            ("depth", self.depth),
            ("stem width", self.stem_width),
            ("stem length", self.stem_length),
        ];
        if let Some(&(name, value)) = lengths.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Some((name, value, "must be finite and positive"));
        }
        // A stem as wide as the bar is not a T (and the cap triangulation would degenerate).
        (self.stem_width >= self.bar_length).then_some((
            "stem width",
            self.stem_width,
            "must be smaller than the bar length",
        ))
    }

    fn bar_volume(&self) -> f64 {
        self.bar_length * self.bar_thickness * self.depth
    }

    fn stem_volume(&self) -> f64 {
        self.stem_width * self.stem_length * self.depth
    }

    /// Volume (m³).
    #[must_use]
    pub fn volume(&self) -> f64 {
        self.bar_volume() + self.stem_volume()
    }

    /// Analytic mass properties at uniform density: the two boxes' closed forms
    /// ([`MassProperties::solid_box`]) moved to their centres `(0, 0, t/2)` and `(0, 0, −l/2)`
    /// and combined (parallel-axis theorem).
    ///
    /// # Errors
    /// [`InertiaError`] for invalid dimensions (non-positive, or a stem not narrower than the
    /// bar) or an invalid density or mass.
    pub fn mass_properties(&self, spec: MassSpec) -> Result<MassProperties, InertiaError> {
        if let Some((name, value, requirement)) = self.invalid_dimension() {
            return Err(InertiaError::InvalidDimension {
                name,
                value,
                requirement,
            });
        }
        let density = match spec {
            MassSpec::Density(density) => {
                if !(density.is_finite() && density > 0.0) {
                    return Err(InertiaError::InvalidDensity { density });
                }
                density
            }
            MassSpec::TotalMass(mass) => {
                if !(mass.is_finite() && mass > 0.0) {
                    return Err(InertiaError::NonPositiveMass { mass });
                }
                mass / self.volume()
            }
        };
        let bar = MassProperties::solid_box(
            density * self.bar_volume(),
            &Vector3::new(self.bar_length, self.depth, self.bar_thickness),
        )?
        .translated(&Vector3::new(0.0, 0.0, self.bar_thickness / 2.0));
        let stem = MassProperties::solid_box(
            density * self.stem_volume(),
            &Vector3::new(self.stem_width, self.depth, self.stem_length),
        )?
        .translated(&Vector3::new(0.0, 0.0, -self.stem_length / 2.0));
        bar.combine(&stem)
    }

    /// The closed triangle mesh of the handle's surface.
    ///
    /// The T profile in the x–z plane (8 corners, counter-clockwise seen from −y) is extruded
    /// from `y = −d/2` to `y = d/2`: 8 side rectangles (16 triangles) and two caps of 6 triangles
    /// each. Cap triangles use only the profile's corners, so every edge is shared by exactly two
    /// faces (no T-junctions) and there is no internal face between bar and stem.
    ///
    /// # Errors
    /// [`MeshError::InvalidShape`] for invalid dimensions.
    pub fn mesh(&self) -> Result<TriangleMesh, MeshError> {
        if let Some((parameter, value, requirement)) = self.invalid_dimension() {
            return Err(MeshError::InvalidShape {
                parameter,
                value,
                requirement,
            });
        }
        let (a, t) = (self.bar_length / 2.0, self.bar_thickness);
        let (s, l) = (self.stem_width / 2.0, self.stem_length);
        let profile = [
            (-a, 0.0),
            (-s, 0.0),
            (-s, -l),
            (s, -l),
            (s, 0.0),
            (a, 0.0),
            (a, t),
            (-a, t),
        ];
        let y = self.depth / 2.0;
        // Front cap (y = −d/2): corners 0..8; back cap (y = +d/2): 8..16.
        let mut vertices: Vec<Point3<f64>> = Vec::with_capacity(16);
        for side in [-y, y] {
            vertices.extend(profile.iter().map(|&(x, z)| Point3::new(x, side, z)));
        }
        // The profile is counter-clockwise in (x, z), whose normal x × z = −y points out of
        // the front cap.
        let cap = [
            [0, 1, 7],
            [1, 6, 7],
            [1, 4, 6],
            [4, 5, 6],
            [2, 3, 4],
            [2, 4, 1],
        ];
        let mut faces: Vec<[usize; 3]> = Vec::with_capacity(28);
        faces.extend(cap);
        faces.extend(cap.iter().map(|&[i, j, k]| [i + 8, k + 8, j + 8]));
        for i in 0..8 {
            let j = (i + 1) % 8;
            // The front cap traverses i → j, so the side traverses j → i.
            faces.push([j, i, i + 8]);
            faces.push([j, i + 8, j + 8]);
        }
        TriangleMesh::try_new(vertices, faces)
    }

    /// Writes [`mesh`](Self::mesh) as OBJ with a comment stating the dimensions (this is how
    /// `scenes/t-handle.obj` is made; a test checks that the file matches).
    ///
    /// # Errors
    /// [`io::ErrorKind::InvalidInput`] for invalid dimensions; the writer's I/O errors.
    pub fn write_obj<W: Write>(&self, writer: W) -> io::Result<()> {
        let mesh = self
            .mesh()
            .map_err(|e| io::Error::new(io::ErrorKind::InvalidInput, e))?;
        let comment = format!(
            "T-handle for the dzhanibekov scene, written by tumble_inertia::THandle::write_obj.\n\
             Units: metres. Crossbar {} × {} × {} (x × y × z) on top of the origin;\n\
             stem {} × {} × {} below it. Faces counter-clockwise seen from outside.",
            self.bar_length,
            self.depth,
            self.bar_thickness,
            self.stem_width,
            self.depth,
            self.stem_length
        );
        mesh.write_obj(writer, &comment)
    }
}
