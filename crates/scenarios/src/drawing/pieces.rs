//! The pieces a drawn object is made of (boxes, cylinders, spheres, tori, triangle meshes),
//! each placed in its object's frame, and the pieces of a body's [`Part`]s.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use tumble_inertia::{Placement, Shape, TriangleMesh};
use tumble_kinematics::EulerConvention;

use super::Part;

/// The shape of a piece, in its own frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Form {
    /// A box of these sides along x, y, z, centred.
    Box([f64; 3]),
    /// A cylinder of this radius and height along z, centred.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Height along z.
        height: f64,
    },
    /// A sphere of this radius.
    Sphere(f64),
    /// A torus in the x-y plane about z.
    Torus {
        /// Radius of the centre-line circle.
        major: f64,
        /// Radius of the tube.
        minor: f64,
    },
    /// A closed triangle mesh (flat faces).
    Mesh {
        /// Vertices.
        vertices: Vec<[f64; 3]>,
        /// Triangles by vertex index.
        faces: Vec<[usize; 3]>,
    },
}

/// A piece of an object: a form centred at `at` and turned by `turn` in the object's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// The shape.
    pub form: Form,
    /// Where its centre sits in the object's frame.
    pub at: Vector3<f64>,
    /// How it is turned in the object's frame.
    pub turn: UnitQuaternion<f64>,
}

impl Piece {
    /// A piece of `form` at `at`, turned by `turn`.
    #[must_use]
    pub fn new(form: Form, at: Vector3<f64>, turn: UnitQuaternion<f64>) -> Self {
        Piece { form, at, turn }
    }

    /// A piece of `form` at the origin of its object, not turned.
    #[must_use]
    pub fn centred(form: Form) -> Self {
        Self::new(form, Vector3::zeros(), UnitQuaternion::identity())
    }

    /// How far the piece reaches from its object's origin.
    #[must_use]
    pub fn reach(&self) -> f64 {
        let size = match &self.form {
            Form::Box(sides) => 0.5 * Vector3::from(*sides).norm(),
            Form::Cylinder { radius, height } => radius.hypot(0.5 * height),
            Form::Sphere(radius) => *radius,
            Form::Torus { major, minor } => major + minor,
            Form::Mesh { vertices, .. } => {
                return vertices
                    .iter()
                    .map(|v| (self.at + self.turn * Vector3::from(*v)).norm())
                    .fold(0.0, f64::max);
            }
        };
        self.at.norm() + size
    }
}

/// A triangle mesh moved by `-center`.
#[must_use]
pub fn mesh(mesh: &TriangleMesh, center: &Point3<f64>) -> Piece {
    Piece::centred(Form::Mesh {
        vertices: mesh
            .vertices()
            .iter()
            .map(|p| [p.x - center.x, p.y - center.y, p.z - center.z])
            .collect(),
        faces: mesh.faces().to_vec(),
    })
}

/// A `tumble inertia` shape as a piece: thin bodies (hoop, rod) get a visible thickness.
fn shape(shape: &Shape, placement: &Placement, center: &Point3<f64>) -> Piece {
    let at = placement.at - center.coords;
    let turn = EulerConvention::ARTICLE.to_quaternion(&placement.euler);
    let form = match *shape {
        Shape::Box(sides) => Form::Box([sides.x, sides.y, sides.z]),
        Shape::Cylinder { radius, height } => Form::Cylinder { radius, height },
        Shape::Sphere { radius } => Form::Sphere(radius),
        Shape::Torus { major, minor } => Form::Torus { major, minor },
        Shape::Hoop { radius } => Form::Torus {
            major: radius,
            minor: 0.03 * radius,
        },
        Shape::Rod { length } => Form::Cylinder {
            radius: 0.015 * length,
            height: length,
        },
    };
    Piece::new(form, at, turn)
}

/// The half-sides of the uniform box with principal moments `moments` (side² ∝ I₂ + I₃ − I₁,
/// …), scaled so that the longest is 1: how a body known only by its moments is drawn.
#[must_use]
pub fn equivalent_box(moments: [f64; 3]) -> [f64; 3] {
    let [i1, i2, i3] = moments;
    let sq = [i2 + i3 - i1, i1 + i3 - i2, i1 + i2 - i3].map(|v| v.max(0.0).sqrt());
    let top = sq
        .iter()
        .copied()
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    sq.map(|v| v / top)
}

/// How far the parts reach from `center` (metres): the camera and the arrows are scaled by it.
#[must_use]
pub fn reach(parts: &[Part], center: &Point3<f64>) -> f64 {
    let mut far: f64 = 0.0;
    for part in parts {
        match part {
            Part::Mesh(m) => {
                for p in m.vertices() {
                    far = far.max((p - center).norm());
                }
            }
            Part::Points(points) => {
                for p in points {
                    far = far.max((p.position - center).norm());
                }
            }
            Part::Shape(s, placement) => {
                let size = match *s {
                    Shape::Box(v) => 0.5 * v.norm(),
                    Shape::Cylinder { radius, height } => radius.hypot(0.5 * height),
                    Shape::Sphere { radius } | Shape::Hoop { radius } => radius,
                    Shape::Torus { major, minor } => major + minor,
                    Shape::Rod { length } => 0.5 * length,
                };
                far = far.max((placement.at - center.coords).norm() + size);
            }
        }
    }
    far
}

/// The parts of a body about `center` (its fixed point), with point masses as spheres sized by
/// the cube root of their mass (the heaviest `0.06 reach` across).
#[must_use]
pub fn parts(parts: &[Part], center: &Point3<f64>) -> Vec<Piece> {
    let span = reach(parts, center).max(f64::MIN_POSITIVE);
    let heaviest = parts
        .iter()
        .flat_map(|p| match p {
            Part::Points(points) => points.iter().map(|q| q.mass).collect(),
            _ => Vec::new(),
        })
        .fold(0.0, f64::max);
    let mut out = Vec::new();
    for part in parts {
        match part {
            Part::Mesh(m) => out.push(mesh(m, center)),
            Part::Shape(s, placement) => out.push(shape(s, placement, center)),
            Part::Points(points) => {
                for p in points {
                    let radius = 0.06 * span * (p.mass / heaviest).cbrt();
                    out.push(Piece::new(
                        Form::Sphere(radius),
                        p.position - center,
                        UnitQuaternion::identity(),
                    ));
                }
            }
        }
    }
    out
}
