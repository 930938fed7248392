//! Bodies as the viewer draws them: parts (meshes, primitives, point masses) described in
//! JSON for three.js, each in the frame of the object that carries it.

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

/// A primitive: `kind` and its dimensions, centred at `at`, turned by `turn`.
#[must_use]
pub fn primitive(kind: &str, dims: &[f64], at: &Vector3<f64>, turn: &UnitQuaternion<f64>) -> Value {
    json!({
        "kind": kind,
        "dims": dims.iter().map(|&x| r(x)).collect::<Vec<_>>(),
        "position": vec3(at),
        "quaternion": quat(turn),
    })
}

/// A triangle mesh moved by `-center`.
#[must_use]
pub fn mesh(mesh: &TriangleMesh, center: &Point3<f64>) -> Value {
    let positions: Vec<f64> = mesh
        .vertices()
        .iter()
        .flat_map(|p| [r(p.x - center.x), r(p.y - center.y), r(p.z - center.z)])
        .collect();
    let indices: Vec<usize> = mesh.faces().iter().flatten().copied().collect();
    json!({"kind": "mesh", "positions": positions, "indices": indices})
}

/// A `tumble inertia` shape as a primitive: thin bodies (hoop, rod) get a visible thickness.
fn shape(shape: &Shape, placement: &Placement, center: &Point3<f64>) -> Value {
    let at = placement.at - center.coords;
    let turn = EulerConvention::ARTICLE.to_quaternion(&placement.euler);
    match *shape {
        Shape::Box(sides) => primitive("box", &[sides.x, sides.y, sides.z], &at, &turn),
        Shape::Cylinder { radius, height } => primitive("cylinder", &[radius, height], &at, &turn),
        Shape::Sphere { radius } => primitive("sphere", &[radius], &at, &turn),
        Shape::Torus { major, minor } => primitive("torus", &[major, minor], &at, &turn),
        Shape::Hoop { radius } => primitive("torus", &[radius, 0.03 * radius], &at, &turn),
        Shape::Rod { length } => primitive("cylinder", &[0.015 * length, length], &at, &turn),
    }
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
pub fn parts(parts: &[Part], center: &Point3<f64>) -> Vec<Value> {
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
                    out.push(primitive(
                        "sphere",
                        &[radius],
                        &(p.position - center),
                        &UnitQuaternion::identity(),
                    ));
                }
            }
        }
    }
    out
}
