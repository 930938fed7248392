//! Bodies as the viewer and `tumble animate` draw them: pieces (meshes, primitives, point
//! masses), each in the frame of the object that carries it — described in JSON for three.js
//! ([`Piece::json`]) and as shaded triangles for the software renderer ([`Piece::triangles`]),
//! so that the page and the animation draw the same scene.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use serde_json::{Value, json};
use tumble_inertia::{Placement, Shape, TriangleMesh};
use tumble_kinematics::EulerConvention;
use tumble_scenarios::drawing::Part;

use super::round_sig;

/// Significant digits of the geometry's coordinates (far below a pixel).
const DIGITS: i32 = 6;

fn r(x: f64) -> f64 {
    round_sig(x, DIGITS)
}

fn vec3(v: &Vector3<f64>) -> Value {
    json!([r(v.x), r(v.y), r(v.z)])
}

/// three.js's quaternion order: x, y, z, w.
fn quat(q: &UnitQuaternion<f64>) -> Value {
    json!([r(q.i), r(q.j), r(q.k), r(q.w)])
}

/// The shape of a piece, in its own frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Form {
    /// A box of these sides along x, y, z, centred.
    Box([f64; 3]),
    /// A cylinder of this radius and height along z, centred.
    Cylinder { radius: f64, height: f64 },
    /// A sphere.
    Sphere(f64),
    /// A torus in the x-y plane about z.
    Torus { major: f64, minor: f64 },
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

/// A triangle with a normal at each corner (for smooth shading; equal for flat faces).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle {
    /// Corners.
    pub corners: [Vector3<f64>; 3],
    /// Unit outward normals at the corners.
    pub normals: [Vector3<f64>; 3],
}

/// Segments of round forms: as three.js draws them in the page (`common.js`).
const SPHERE_SEGMENTS: (usize, usize) = (32, 16);
const TORUS_SEGMENTS: (usize, usize) = (128, 24);
const CYLINDER_SEGMENTS: usize = 48;

/// Triangles of a `(u, v)` grid on a surface `point(u, v) -> (position, normal)`, `u` and `v`
/// in [0, 1], both closed or open as the surface is.
fn grid(
    (nu, nv): (usize, usize),
    point: &dyn Fn(f64, f64) -> (Vector3<f64>, Vector3<f64>),
    out: &mut Vec<Triangle>,
) {
    let at = |i: usize, j: usize| point(i as f64 / nu as f64, j as f64 / nv as f64);
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            out.push(Triangle {
                corners: [a.0, b.0, c.0],
                normals: [a.1, b.1, c.1],
            });
            out.push(Triangle {
                corners: [a.0, c.0, d.0],
                normals: [a.1, c.1, d.1],
            });
        }
    }
}

/// A flat face's triangle (its normal from its corners, pointing away from the centre).
fn flat(corners: [Vector3<f64>; 3]) -> Triangle {
    let n = (corners[1] - corners[0]).cross(&(corners[2] - corners[0]));
    let n = n.try_normalize(0.0).unwrap_or_else(Vector3::z);
    Triangle {
        corners,
        normals: [n; 3],
    }
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

    /// The piece for three.js (see `assets/viewer/common.js`, `part`).
    #[must_use]
    pub fn json(&self) -> Value {
        let placed = |kind: &str, dims: &[f64]| {
            json!({
                "kind": kind,
                "dims": dims.iter().map(|&x| r(x)).collect::<Vec<_>>(),
                "position": vec3(&self.at),
                "quaternion": quat(&self.turn),
            })
        };
        match &self.form {
            Form::Box(sides) => placed("box", sides),
            Form::Cylinder { radius, height } => placed("cylinder", &[*radius, *height]),
            Form::Sphere(radius) => placed("sphere", &[*radius]),
            Form::Torus { major, minor } => placed("torus", &[*major, *minor]),
            Form::Mesh { vertices, faces } => {
                let place = |v: &[f64; 3]| self.at + self.turn * Vector3::from(*v);
                let positions: Vec<f64> = vertices
                    .iter()
                    .flat_map(|v| {
                        let p = place(v);
                        [r(p.x), r(p.y), r(p.z)]
                    })
                    .collect();
                let indices: Vec<usize> = faces.iter().flatten().copied().collect();
                json!({"kind": "mesh", "positions": positions, "indices": indices})
            }
        }
    }

    /// The piece's surface as triangles in the object's frame, appended to `out`.
    pub fn triangles(&self, out: &mut Vec<Triangle>) {
        let start = out.len();
        let tau = std::f64::consts::TAU;
        match &self.form {
            Form::Sphere(radius) => grid(
                SPHERE_SEGMENTS,
                &|u, v| {
                    let (phi, theta) = (tau * u, std::f64::consts::PI * v);
                    let n = Vector3::new(
                        theta.sin() * phi.cos(),
                        theta.sin() * phi.sin(),
                        theta.cos(),
                    );
                    (n * *radius, n)
                },
                out,
            ),
            Form::Torus { major, minor } => grid(
                TORUS_SEGMENTS,
                &|u, v| {
                    let (phi, theta) = (tau * u, tau * v);
                    let radial = Vector3::new(phi.cos(), phi.sin(), 0.0);
                    let n = radial * theta.cos() + Vector3::z() * theta.sin();
                    (radial * *major + n * *minor, n)
                },
                out,
            ),
            Form::Cylinder { radius, height } => {
                let h = 0.5 * height;
                grid(
                    (CYLINDER_SEGMENTS, 1),
                    &|u, v| {
                        let n = Vector3::new((tau * u).cos(), (tau * u).sin(), 0.0);
                        (n * *radius + Vector3::z() * (h * (2.0 * v - 1.0)), n)
                    },
                    out,
                );
                for (z, sign) in [(h, 1.0), (-h, -1.0)] {
                    let centre = Vector3::new(0.0, 0.0, z);
                    for k in 0..CYLINDER_SEGMENTS {
                        let rim = |k: usize| {
                            let s = tau * k as f64 / CYLINDER_SEGMENTS as f64;
                            Vector3::new(radius * s.cos(), radius * s.sin(), z)
                        };
                        let (a, b) = if sign > 0.0 {
                            (rim(k), rim(k + 1))
                        } else {
                            (rim(k + 1), rim(k))
                        };
                        out.push(Triangle {
                            corners: [centre, a, b],
                            normals: [Vector3::z() * sign; 3],
                        });
                    }
                }
            }
            Form::Box(sides) => {
                let h = Vector3::from(*sides) * 0.5;
                // Each face: its normal axis k and side (the normals are given, so the
                // corners' order does not matter: nothing is culled).
                for k in 0..3 {
                    for sign in [1.0, -1.0] {
                        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                        let corner = |a: f64, b: f64| {
                            let mut p = Vector3::zeros();
                            p[k] = sign * h[k];
                            p[i] = a * h[i];
                            p[j] = sign * b * h[j];
                            p
                        };
                        let quad = [
                            corner(-1.0, -1.0),
                            corner(1.0, -1.0),
                            corner(1.0, 1.0),
                            corner(-1.0, 1.0),
                        ];
                        let mut n = Vector3::zeros();
                        n[k] = sign;
                        for tri in [[0, 1, 2], [0, 2, 3]] {
                            out.push(Triangle {
                                corners: tri.map(|c| quad[c]),
                                normals: [n; 3],
                            });
                        }
                    }
                }
            }
            Form::Mesh { vertices, faces } => {
                for f in faces {
                    if f.iter().all(|&i| i < vertices.len()) {
                        out.push(flat(f.map(|i| Vector3::from(vertices[i]))));
                    }
                }
            }
        }
        for t in &mut out[start..] {
            t.corners = t.corners.map(|c| self.at + self.turn * c);
            t.normals = t.normals.map(|n| self.turn * n);
        }
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
