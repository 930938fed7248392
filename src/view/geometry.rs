//! Bodies as the viewer and `tumble animate` draw them: the pieces a scene declares
//! ([`tumble_scenarios::drawing`]), described in JSON for three.js ([`Render::json`]) and as
//! shaded triangles for the software renderer ([`Render::triangles`]), so that the page and the
//! animation draw the same scene.

use nalgebra::{UnitQuaternion, Vector3};
use serde_json::{Value, json};
pub use tumble_scenarios::drawing::{Form, Piece, parts, reach};

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

/// How a piece is drawn: for three.js and for the software renderer.
pub trait Render {
    /// The piece for three.js (see `assets/viewer/common.js`, `part`).
    fn json(&self) -> Value;
    /// The piece's surface as triangles in the object's frame, appended to `out`.
    fn triangles(&self, out: &mut Vec<Triangle>);
}

impl Render for Piece {
    fn json(&self) -> Value {
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

    fn triangles(&self, out: &mut Vec<Triangle>) {
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
