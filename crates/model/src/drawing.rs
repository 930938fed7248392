//! What `tumble view` and `tumble animate` draw of a model ([`ModelScene::view`], the model's
//! [`Scene::drawing`](tumble_scenarios::Scene::drawing)): its bodies (their `geometry`, or the
//! body with their mass properties) and point masses at the run's parameters, and where they
//! are at each row of a run ([`ModelScene::poses`]). The positions and orientations are the
//! model's own expressions ([`crate::file::ModelDrawing`]), evaluated on an instruction tape
//! from the rows' time, coordinates and rates.

use nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3};
use tumble_scenarios::Params;
use tumble_scenarios::drawing::{
    Drawing, Form, Motion, Object, Part, Piece, Placed, Trail, parts, pivot,
};

use crate::expr::Id;
use crate::expr::tape::Tape;
use crate::scene::ModelScene;

/// A body's mass properties at a run's parameters, in its own frame.
#[derive(Debug, Clone)]
pub struct BodyShape {
    /// Its name in the file.
    pub name: String,
    /// Mass.
    pub mass: f64,
    /// Centre of mass.
    pub com: [f64; 3],
    /// Inertia tensor about the centre of mass.
    pub inertia: [[f64; 3]; 3],
    /// Its parts, when the file gives its geometry.
    pub parts: Option<Vec<Part>>,
}

/// A point mass at a run's parameters.
#[derive(Debug, Clone)]
pub struct PointShape {
    /// Its name in the file.
    pub name: String,
    /// Mass.
    pub mass: f64,
}

/// A model's bodies and point masses at a run's parameters.
#[derive(Debug, Clone)]
pub struct Shapes {
    /// Bodies, in the file's order.
    pub bodies: Vec<BodyShape>,
    /// Point masses, in the file's order.
    pub points: Vec<PointShape>,
}

impl ModelScene {
    /// The inputs of a tape at `params`, time, coordinates and rates zero.
    fn parameter_inputs(&self, params: &Params) -> Vec<f64> {
        let layout = self.model().layout;
        let mut inputs = vec![0.0; layout.param(self.model().params.len()) as usize];
        for (j, (_, value)) in params.iter().enumerate() {
            inputs[layout.param(j) as usize] = value;
        }
        inputs
    }

    /// The bodies' and point masses' mass properties at `params`.
    #[must_use]
    pub fn shapes(&self, params: &Params) -> Shapes {
        let drawing = &self.model().drawing;
        let mut outputs: Vec<Id> = Vec::new();
        for b in &drawing.bodies {
            outputs.push(b.mass);
            outputs.extend_from_slice(&b.com);
            outputs.extend(b.inertia.iter().flatten());
        }
        outputs.extend(drawing.points.iter().map(|p| p.mass));
        let tape = Tape::new(&self.model().graph, &outputs);
        let mut w = tape.workspace();
        tape.run_all(&mut w, &self.parameter_inputs(params));
        let mut k = 0;
        let mut next = || {
            k += 1;
            tape.output(&w, k - 1)
        };
        let bodies = drawing
            .bodies
            .iter()
            .map(|b| BodyShape {
                name: b.name.clone(),
                mass: next(),
                com: [next(), next(), next()],
                inertia: [
                    [next(), next(), next()],
                    [next(), next(), next()],
                    [next(), next(), next()],
                ],
                parts: b.parts.clone(),
            })
            .collect();
        let points = drawing
            .points
            .iter()
            .map(|p| PointShape {
                name: p.name.clone(),
                mass: next(),
            })
            .collect();
        Shapes { bodies, points }
    }

    /// Where every body and point mass is at each of `rows` (the scene's rows: `t`, the
    /// coordinates, their rates, then the rest) at `params`. Rows shorter than `1 + 2n` give
    /// no pose.
    #[must_use]
    pub fn poses(&self, params: &Params, rows: &[Vec<f64>]) -> Vec<Placed> {
        let model = self.model();
        let (layout, drawing) = (model.layout, &model.drawing);
        let mut outputs: Vec<Id> = Vec::new();
        for b in &drawing.bodies {
            if let Some(r) = &b.rotation {
                outputs.extend(r.iter().flatten());
            }
            outputs.extend_from_slice(&b.origin);
        }
        for p in &drawing.points {
            outputs.extend_from_slice(&p.position);
        }
        let fixed = move |k: u32| layout.is_param(k);
        let tape = Tape::with_fixed(&model.graph, &outputs, &fixed);
        let mut w = tape.workspace();
        let inputs = self.parameter_inputs(params);
        let set = inputs.len().min(tape.inputs()).min(w.len());
        w[..set].copy_from_slice(&inputs[..set]);
        tape.run_prelude(&mut w);
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        // `t`, then each orientation's quaternion and angular velocity, the coordinates, rates.
        let shown = 1 + 2 * layout.n + 7 * layout.so3;
        rows.iter()
            .filter(|row| row.len() >= shown)
            .map(|row| {
                // Time and the state are inputs 0 ..= state_len; a row shows orientations on
                // SO(3) as quaternions.
                let state = self.state_of_row(row);
                let varying = state.len().min(set);
                w[..varying].copy_from_slice(&state[..varying]);
                tape.run(&mut w);
                let mut k = 0;
                let mut next = || {
                    k += 1;
                    tape.output(&w, k - 1)
                };
                let bodies = drawing
                    .bodies
                    .iter()
                    .map(|b| {
                        let r = if b.rotation.is_some() {
                            [0, 1, 2].map(|_| [next(), next(), next()])
                        } else {
                            identity
                        };
                        (r, [next(), next(), next()])
                    })
                    .collect();
                let points = drawing
                    .points
                    .iter()
                    .map(|_| [next(), next(), next()])
                    .collect();
                Placed { bodies, points }
            })
            .collect()
    }

    /// The drawing of a model: its bodies (their `geometry`, or the uniform box with their
    /// mass and principal moments, at their centre of mass along their principal axes), its
    /// point masses as spheres sized by the cube root of their mass, and the origin; placed at
    /// each row by the model's own expressions. The trail follows the first point mass, or
    /// the heaviest turning body's z axis.
    #[must_use]
    pub fn view(&self, params: &Params) -> Drawing {
        let scene = self;
        let shapes = scene.shapes(params);
        let state = scene.initial_state(params);
        let mut row = vec![0.0];
        row.extend_from_slice(&state);
        let start = scene.poses(params, &[row]).pop();
        // The size: the parts' reach about each body's frame origin, the points' distance.
        let mut pieces: Vec<Vec<Piece>> = Vec::new();
        let mut reach: f64 = 0.0;
        for (k, b) in shapes.bodies.iter().enumerate() {
            let own = match &b.parts {
                Some(own) => parts(own, &Point3::origin()),
                None => vec![equivalent_body(b)],
            };
            let far = own.iter().map(Piece::reach).fold(0.0, f64::max);
            let at = start
                .as_ref()
                .map_or(0.0, |p| Vector3::from(p.bodies[k].1).norm());
            reach = reach.max(at + far);
            pieces.push(own);
        }
        for (k, _) in shapes.points.iter().enumerate() {
            let at = start
                .as_ref()
                .map_or(0.0, |p| Vector3::from(p.points[k]).norm());
            reach = reach.max(at);
        }
        let reach = if reach > 0.0 { reach } else { 1.0 };
        let palette = ["#0072b2", "#56b4e9", "#999999", "#f0e442"];
        let heaviest = shapes
            .bodies
            .iter()
            .enumerate()
            .filter(|(k, _)| scene.model().drawing.bodies[*k].rotation.is_some())
            .max_by(|a, b| a.1.mass.total_cmp(&b.1.mass))
            .map(|(k, _)| k);
        let mut objects: Vec<Object> = pieces
            .into_iter()
            .enumerate()
            .map(|(k, pieces)| Object {
                name: "body",
                colour: palette[k % palette.len()],
                pieces,
                motion: Motion::PlacedBody(k),
                axes: Some(k) == heaviest,
            })
            .collect();
        let bodies = objects.len();
        let heaviest_point = shapes.points.iter().map(|p| p.mass).fold(0.0, f64::max);
        for (k, p) in shapes.points.iter().enumerate() {
            let size = if heaviest_point > 0.0 {
                (p.mass / heaviest_point).max(0.0).cbrt()
            } else {
                1.0
            };
            objects.push(Object {
                name: "point",
                colour: "#d55e00",
                pieces: vec![Piece::centred(Form::Sphere(0.06 * reach * size.max(0.3)))],
                motion: Motion::PlacedPoint(k),
                axes: false,
            });
        }
        let trail = if shapes.points.is_empty() {
            Trail::Tip(heaviest.unwrap_or(0), Vector3::new(0.0, 0.0, 1.15 * reach))
        } else {
            Trail::Object(bodies)
        };
        objects.push(pivot(reach));
        Drawing {
            objects,
            trail,
            reach,
        }
    }
}

/// A body known by its mass and inertia, drawn at its centre of mass along its principal
/// axes: a flat body symmetric about its largest axis (`I₃ = I₁ + I₂`, `I₁ = I₂`: a ring, the
/// gimbals) as the hoop with its largest moment (radius `√(I₃/m)`), any other as the uniform
/// box with its principal moments (full sides `s₁² = 6 (I₂ + I₃ − I₁) / m`, …); a box with no
/// extent along an axis gets 2 % of its largest side there, a body with no inertia a small
/// sphere.
fn equivalent_body(b: &BodyShape) -> Piece {
    let inertia = Matrix3::from_fn(|i, j| b.inertia[i][j]);
    let eigen = nalgebra::SymmetricEigen::new(inertia);
    let mut l = eigen.eigenvalues;
    let mut axes = eigen.eigenvectors;
    // The largest moment last, its axis the piece's z.
    let top = (0..3).max_by(|&i, &j| l[i].total_cmp(&l[j])).unwrap_or(2);
    if top != 2 {
        l.swap_rows(top, 2);
        axes.swap_columns(top, 2);
    }
    if axes.determinant() < 0.0 {
        axes.column_mut(0).neg_mut();
    }
    let com = Vector3::from(b.com);
    let flat = (l[2] - l[0] - l[1]).abs() <= 1e-9 * l[2];
    let round = (l[0] - l[1]).abs() <= 1e-9 * l[2];
    if b.mass > 0.0 && l[2] > 0.0 && flat && round {
        let major = (l[2] / b.mass).sqrt();
        let turn = UnitQuaternion::from_matrix_eps(&axes, 1e-12, 100, UnitQuaternion::identity());
        return Piece::new(
            Form::Torus {
                major,
                minor: 0.03 * major,
            },
            com,
            turn,
        );
    }
    let sides = if b.mass > 0.0 {
        [0, 1, 2].map(|i| {
            (6.0 * (l[(i + 1) % 3] + l[(i + 2) % 3] - l[i]) / b.mass)
                .max(0.0)
                .sqrt()
        })
    } else {
        [0.0; 3]
    };
    let largest = sides.iter().copied().fold(0.0, f64::max);
    if !(largest > 0.0 && largest.is_finite()) {
        return Piece::new(Form::Sphere(0.05), com, UnitQuaternion::identity());
    }
    let turn = UnitQuaternion::from_matrix_eps(&axes, 1e-12, 100, UnitQuaternion::identity());
    Piece::new(Form::Box(sides.map(|s| s.max(0.02 * largest))), com, turn)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(mass: f64, inertia: [[f64; 3]; 3]) -> BodyShape {
        BodyShape {
            name: "b".into(),
            mass,
            com: [0.1, 0.2, 0.3],
            inertia,
            parts: None,
        }
    }

    #[test]
    fn a_body_known_by_its_moments_is_drawn_as_the_uniform_box_that_has_them() {
        // A uniform box of sides (a, b, c) and mass m: I₁ = m (b² + c²)/12, … (any textbook).
        let (m, a, b, c) = (2.0, 0.3, 0.5, 0.9);
        let diag = [
            m * (b * b + c * c) / 12.0,
            m * (a * a + c * c) / 12.0,
            m * (a * a + b * b) / 12.0,
        ];
        let piece = equivalent_body(&shape(
            m,
            [
                [diag[0], 0.0, 0.0],
                [0.0, diag[1], 0.0],
                [0.0, 0.0, diag[2]],
            ],
        ));
        let Form::Box(sides) = piece.form else {
            panic!("{piece:?}")
        };
        // The largest moment's axis is the piece's z: the sides in the frame of the moments.
        let world: Vec<f64> = (0..3)
            .map(|k| (piece.turn * Vector3::ith(k, sides[k])).abs().max())
            .collect();
        let mut got = world.clone();
        got.sort_by(f64::total_cmp);
        for (g, e) in got.iter().zip([a, b, c]) {
            assert!((g - e).abs() < 1e-12, "{world:?}");
        }
        assert_eq!(piece.at, Vector3::new(0.1, 0.2, 0.3));
    }

    #[test]
    fn a_flat_round_body_is_drawn_as_the_ring_with_its_largest_moment() {
        // A ring of radius R and mass m: I₃ = m R², I₁ = I₂ = m R²/2, here about x.
        let (m, r) = (0.4, 0.7);
        let i = m * r * r;
        let piece = equivalent_body(&shape(
            m,
            [[i, 0.0, 0.0], [0.0, i / 2.0, 0.0], [0.0, 0.0, i / 2.0]],
        ));
        let Form::Torus { major, .. } = piece.form else {
            panic!("{piece:?}")
        };
        assert!((major - r).abs() < 1e-12);
        // Its normal (the piece's z) along the largest moment's axis, x.
        let normal = piece.turn * Vector3::z();
        assert!((normal.x.abs() - 1.0).abs() < 1e-12, "{normal:?}");
    }
}
