//! The data of a run for the viewer: the bodies (parts in their own frames), their poses in the
//! lab at every frame, the angular velocity and angular momentum in the lab, the point the
//! trail follows, and every column of the scene's rows, as `f32` arrays.

use anyhow::{Result, bail};
use nalgebra::{Matrix3, Point3, Quaternion, UnitQuaternion, Vector3};
use serde_json::{Value, json};
use tumble_inertia::{MassSpec, THandle};
use tumble_kinematics::EulerConvention;
use tumble_model::ModelScene;
use tumble_scenarios::Params;
use tumble_scenarios::drawing::{BodyDrawing, Part};

use super::geometry::{self, Form, Piece};
use super::{f32_base64, round_sig};

/// How an object's pose follows the rows.
#[derive(Debug, Clone, Copy)]
enum Pose {
    /// Fixed at the origin.
    Fixed,
    /// Turned by the rows' quaternion `qw … qz`.
    Quaternion,
    /// A hoop in a vertical plane at azimuth φ (the `phi` column, or `omega t` when driven).
    VerticalPlane { omega: Option<f64> },
    /// The bead: on the free hoop (body x-y plane, angle `alpha`) at radius `a`.
    BeadFree { a: f64 },
    /// The bead on a vertical hoop at azimuth φ, `alpha` from the bottom.
    BeadVertical { a: f64, omega: Option<f64> },
    /// A model's body (by index), placed by the model's expressions.
    ModelBody(usize),
    /// A model's point mass (by index), placed by the model's expressions.
    ModelPoint(usize),
}

/// One drawn object.
struct Object {
    name: &'static str,
    colour: &'static str,
    parts: Vec<Piece>,
    pose: Pose,
    /// Draw the object's own axes (the body frame).
    axes: bool,
}

/// What the trail follows.
#[derive(Debug, Clone, Copy)]
enum Trail {
    /// A point of an object (by index), in its own frame.
    Tip(usize, Vector3<f64>),
    /// An object's position (by index): the bead, a model's first point mass.
    Object(usize),
}

/// A scene's drawing: its objects, what the trail follows, its size, and for a model the
/// scene and parameters that place its objects.
pub struct Drawing {
    objects: Vec<Object>,
    trail: Trail,
    reach: f64,
    model: Option<(&'static ModelScene, Params)>,
}

fn identity() -> UnitQuaternion<f64> {
    UnitQuaternion::identity()
}

fn pivot(reach: f64) -> Object {
    Object {
        name: "pivot",
        colour: "#555555",
        parts: vec![Piece::centred(Form::Sphere(0.025 * reach))],
        pose: Pose::Fixed,
        axes: false,
    }
}

fn bead(a: f64, pose: Pose) -> Object {
    Object {
        name: "bead",
        colour: "#d55e00",
        parts: vec![Piece::centred(Form::Sphere(0.06 * a))],
        pose,
        axes: false,
    }
}

fn body(parts: Vec<Piece>) -> Object {
    Object {
        name: "body",
        colour: "#0072b2",
        parts,
        pose: Pose::Quaternion,
        axes: true,
    }
}

impl Drawing {
    /// A hoop of radius `a` posed by `hoop`, its bead posed by `bead`, the trail on the bead.
    fn hoop(a: f64, hoop: Pose, bead_pose: Pose) -> Self {
        Drawing {
            objects: vec![
                Object {
                    name: "hoop",
                    colour: "#0072b2",
                    parts: vec![Piece::centred(Form::Torus {
                        major: a,
                        minor: 0.025 * a,
                    })],
                    pose: hoop,
                    axes: true,
                },
                bead(a, bead_pose),
                pivot(a),
            ],
            trail: Trail::Object(1),
            model: None,
            reach: a,
        }
    }

    /// The drawing of a scene file's `[body]`: its parts about its fixed point, the trail on
    /// the intermediate principal axis (the flip axis of the Dzhanibekov effect; for a top, the
    /// axis it spins about wobbles with it).
    #[must_use]
    pub fn of_body(drawing: &BodyDrawing, params: &Params) -> Self {
        let reach = geometry::reach(&drawing.parts, &drawing.center).max(1e-9);
        let axes = ["frame_phi", "frame_theta", "frame_psi"].map(|k| params.get(k).unwrap_or(0.0));
        let q = EulerConvention::ARTICLE.to_rotation(&Vector3::from(axes));
        let tip = q.matrix().column(1).into_owned() * 1.15 * reach;
        Drawing {
            objects: vec![
                body(geometry::parts(&drawing.parts, &drawing.center)),
                pivot(reach),
            ],
            trail: Trail::Tip(0, tip),
            model: None,
            reach,
        }
    }

    /// The drawing of a model: its bodies (their `geometry`, or the uniform box with their
    /// mass and principal moments, at their centre of mass along their principal axes), its
    /// point masses as spheres sized by the cube root of their mass, and the origin; placed at
    /// each row by the model's own expressions. The trail follows the first point mass, or
    /// the heaviest turning body's z axis.
    #[must_use]
    pub fn of_model(scene: &'static ModelScene, params: &Params) -> Self {
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
                Some(parts) => geometry::parts(parts, &Point3::origin()),
                None => vec![equivalent_box(b)],
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
            .map(|(k, parts)| Object {
                name: "body",
                colour: palette[k % palette.len()],
                parts,
                pose: Pose::ModelBody(k),
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
                parts: vec![Piece::centred(Form::Sphere(0.06 * reach * size.max(0.3)))],
                pose: Pose::ModelPoint(k),
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
            model: Some((scene, params.clone())),
        }
    }

    /// The drawing of a built-in scene.
    ///
    /// # Errors
    /// A scene with no 3D view (the Coriolis drop), a missing parameter.
    pub fn of_builtin(name: &str, params: &Params) -> Result<Self> {
        let get = |p: &str| params.get(p);
        Ok(match name {
            "free-hoop" => {
                let a = get("a")?;
                Drawing::hoop(a, Pose::Quaternion, Pose::BeadFree { a })
            }
            "spinning-hoop" | "driven-hoop" => {
                let a = get("a")?;
                let omega = (name == "driven-hoop").then(|| get("omega")).transpose()?;
                Drawing::hoop(
                    a,
                    Pose::VerticalPlane { omega },
                    Pose::BeadVertical { a, omega },
                )
            }
            "free-body" => {
                let half = geometry::equivalent_box([get("I1")?, get("I2")?, get("I3")?]);
                let sides = half.map(|v| 2.0 * v);
                let reach = 0.5 * Vector3::from(sides).norm();
                Drawing {
                    objects: vec![body(vec![Piece::centred(Form::Box(sides))]), pivot(reach)],
                    trail: Trail::Tip(0, Vector3::new(0.0, 0.6 * sides[1].max(0.6), 0.0)),
                    model: None,
                    reach,
                }
            }
            "dzhanibekov" => {
                let mesh = THandle::STANDARD.mesh()?;
                let props = THandle::STANDARD.mass_properties(MassSpec::TotalMass(1.0))?;
                let body_drawing = BodyDrawing {
                    parts: vec![Part::Mesh(mesh)],
                    center: props.center_of_mass(),
                };
                let reach = geometry::reach(&body_drawing.parts, &body_drawing.center);
                // The trail follows the intermediate principal axis, the one the handle flips about.
                Drawing {
                    objects: vec![
                        body(geometry::parts(&body_drawing.parts, &body_drawing.center)),
                        pivot(reach),
                    ],
                    trail: Trail::Tip(
                        0,
                        props.principal().axes.matrix().column(1).into_owned() * 1.15 * reach,
                    ),
                    reach,
                    model: None,
                }
            }
            "heavy-top" => {
                // The symmetric top: its axis along body z from the pivot and a disk at its end.
                let z = |h: f64| Vector3::new(0.0, 0.0, h);
                let upright = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.0);
                Drawing {
                    objects: vec![
                        body(vec![
                            Piece::new(
                                Form::Cylinder {
                                    radius: 0.02,
                                    height: 1.0,
                                },
                                z(0.5),
                                upright,
                            ),
                            Piece::new(
                                Form::Cylinder {
                                    radius: 0.4,
                                    height: 0.06,
                                },
                                z(1.0),
                                upright,
                            ),
                        ]),
                        pivot(1.0),
                    ],
                    trail: Trail::Tip(0, z(1.1)),
                    model: None,
                    reach: 1.1,
                }
            }
            other => bail!(
                "`{other}` has no 3D view: view draws free-hoop, spinning-hoop, driven-hoop, \
                 free-body, dzhanibekov, heavy-top and scene files with a [body] table"
            ),
        })
    }

    /// The scene's size (metres): the camera and the arrows are scaled by it.
    #[must_use]
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// The objects drawn: colour (`#rrggbb`), pieces in the object's frame, and whether its
    /// own axes (the body frame) are drawn.
    pub fn objects(&self) -> impl Iterator<Item = (&'static str, &[Piece], bool)> {
        self.objects
            .iter()
            .map(|o| (o.colour, o.parts.as_slice(), o.axes))
    }

    /// The poses of every object at every row, the trail and the vectors.
    ///
    /// # Errors
    /// Rows without the columns the drawing needs.
    pub fn frames(&self, columns: &[String], rows: &[Vec<f64>]) -> Result<Frames> {
        let col = |name: &str| columns.iter().position(|c| c == name);
        let need = |name: &str| {
            col(name).ok_or_else(|| anyhow::anyhow!("the rows have no `{name}` column"))
        };
        let n = rows.len();
        let orientation = |row: &[f64]| -> Result<UnitQuaternion<f64>> {
            let [w, x, y, z] = ["qw", "qx", "qy", "qz"].map(|c| need(c).map(|k| row[k]));
            Ok(UnitQuaternion::from_quaternion(Quaternion::new(
                w?, x?, y?, z?,
            )))
        };
        let azimuth = |row: &[f64], omega: Option<f64>| -> Result<f64> {
            Ok(match omega {
                Some(w) => w * row[0],
                None => row[need("phi")?],
            })
        };
        let model_poses = match &self.model {
            Some((scene, params)) => {
                let poses = scene.poses(params, rows);
                if poses.len() != n {
                    bail!("the rows do not hold the model's coordinates and rates");
                }
                poses
            }
            None => Vec::new(),
        };
        let mut positions: Vec<Vec<Vector3<f64>>> = Vec::new();
        let mut turns: Vec<Vec<UnitQuaternion<f64>>> = Vec::new();
        for object in &self.objects {
            let mut p = Vec::with_capacity(n);
            let mut q = Vec::with_capacity(n);
            for (i, row) in rows.iter().enumerate() {
                let (at, turn) = match object.pose {
                    Pose::ModelBody(k) => {
                        let (r, origin) = model_poses[i].bodies[k];
                        let m = Matrix3::from_fn(|a, b| r[a][b]);
                        (
                            Vector3::from(origin),
                            UnitQuaternion::from_matrix_eps(&m, 1e-12, 100, identity()),
                        )
                    }
                    Pose::ModelPoint(k) => (Vector3::from(model_poses[i].points[k]), identity()),
                    Pose::Fixed => (Vector3::zeros(), identity()),
                    Pose::Quaternion => (Vector3::zeros(), orientation(row)?),
                    Pose::VerticalPlane { omega } => {
                        let phi = azimuth(row, omega)?;
                        // The hoop's plane: its x axis horizontal at azimuth φ, its normal
                        // horizontal; the torus (in its x-y plane) turned up by π/2 about x.
                        let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi)
                            * UnitQuaternion::from_axis_angle(
                                &Vector3::x_axis(),
                                std::f64::consts::FRAC_PI_2,
                            );
                        (Vector3::zeros(), turn)
                    }
                    Pose::BeadFree { a } => {
                        let alpha = row[need("alpha")?];
                        let at =
                            orientation(row)? * Vector3::new(a * alpha.cos(), a * alpha.sin(), 0.0);
                        (at, identity())
                    }
                    Pose::BeadVertical { a, omega } => {
                        let (phi, alpha) = (azimuth(row, omega)?, row[need("alpha")?]);
                        let at = Vector3::new(
                            a * alpha.sin() * phi.cos(),
                            a * alpha.sin() * phi.sin(),
                            -a * alpha.cos(),
                        );
                        (at, identity())
                    }
                };
                p.push(at);
                q.push(turn);
            }
            positions.push(p);
            turns.push(q);
        }
        // The trail: a point of the body, or the bead.
        let trail: Vec<Vector3<f64>> = match self.trail {
            Trail::Tip(k, tip) => turns[k]
                .iter()
                .zip(&positions[k])
                .map(|(q, p)| p + q * tip)
                .collect(),
            Trail::Object(k) => positions[k].clone(),
        };
        // Angular velocity (lab) and angular momentum (lab), when the rows give them.
        let omega: Option<Vec<Vector3<f64>>> = if let (Some(x), Some(y), Some(z)) =
            (col("omega_x"), col("omega_y"), col("omega_z"))
        {
            Some(
                rows.iter()
                    .zip(&turns[0])
                    .map(|(row, q)| q * Vector3::new(row[x], row[y], row[z]))
                    .collect(),
            )
        } else {
            match self.objects[0].pose {
                Pose::VerticalPlane { omega: Some(w) } => Some(vec![Vector3::new(0.0, 0.0, w); n]),
                Pose::VerticalPlane { omega: None } => {
                    let k = need("phi_dot")?;
                    Some(rows.iter().map(|r| Vector3::new(0.0, 0.0, r[k])).collect())
                }
                _ => None,
            }
        };
        let momentum: Option<Vec<Vector3<f64>>> =
            if let (Some(x), Some(y), Some(z)) = (col("Lx"), col("Ly"), col("Lz")) {
                Some(
                    rows.iter()
                        .map(|r| Vector3::new(r[x], r[y], r[z]))
                        .collect(),
                )
            } else {
                None
            };
        let vectors = [
            ("omega", "ω (angular velocity)", "#cc79a7", omega),
            ("L", "L (angular momentum)", "#009e73", momentum),
        ]
        .into_iter()
        .filter_map(|(name, label, colour, series)| {
            let series = series?;
            let largest = series.iter().map(Vector3::norm).fold(0.0, f64::max);
            // The longest arrow of the run reaches 1.3 times the body.
            let scale = if largest > 0.0 {
                1.3 * self.reach / largest
            } else {
                0.0
            };
            Some(Vector {
                name,
                label,
                colour,
                scale,
                series,
            })
        })
        .collect();
        Ok(Frames {
            positions,
            turns,
            trail,
            vectors,
        })
    }

    /// The page data of `rows` (the scene's `columns`, `t` first).
    ///
    /// # Errors
    /// Rows without the columns the drawing needs.
    pub fn data(&self, columns: &[String], rows: &[Vec<f64>]) -> Result<Value> {
        let frames = self.frames(columns, rows)?;
        let mut arrays: Vec<(String, usize, Vec<f32>)> = Vec::new();
        let vectors3 = |v: &[Vector3<f64>]| -> Vec<f32> {
            v.iter()
                .flat_map(|v| [v.x, v.y, v.z])
                .map(|x| x as f32)
                .collect()
        };
        let mut object_json = Vec::new();
        for (k, object) in self.objects.iter().enumerate() {
            object_json.push(json!({
                "name": object.name,
                "colour": object.colour,
                "parts": object.parts.iter().map(Piece::json).collect::<Vec<_>>(),
                "axes": object.axes,
                "position": format!("{k}.p"),
                "quaternion": format!("{k}.q"),
            }));
            arrays.push((format!("{k}.p"), 3, vectors3(&frames.positions[k])));
            arrays.push((
                format!("{k}.q"),
                4,
                frames.turns[k]
                    .iter()
                    .flat_map(|u| [u.i, u.j, u.k, u.w])
                    .map(|x| x as f32)
                    .collect(),
            ));
        }
        arrays.push(("trail".into(), 3, vectors3(&frames.trail)));
        let mut vectors = Vec::new();
        for v in &frames.vectors {
            vectors.push(json!({
                "name": v.name, "label": v.label, "colour": v.colour,
                "scale": round_sig(v.scale, 6), "array": v.name,
            }));
            arrays.push((v.name.to_string(), 3, vectors3(&v.series)));
        }
        // Every column of the rows.
        for (k, name) in columns.iter().enumerate() {
            arrays.push((
                format!("col:{name}"),
                1,
                rows.iter().map(|r| r[k] as f32).collect(),
            ));
        }
        let mut flat: Vec<f32> = Vec::new();
        let mut layout = Vec::new();
        for (name, width, values) in &arrays {
            layout.push(json!({"name": name, "width": width, "offset": flat.len()}));
            flat.extend_from_slice(values);
        }
        if flat.iter().any(|x| !x.is_finite()) {
            bail!("a value of the run does not fit a 32-bit float (the page stores them so)");
        }
        Ok(json!({
            "frames": rows.len(),
            "columns": columns,
            "objects": object_json,
            "vectors": vectors,
            "reach": round_sig(self.reach, 6),
            "layout": layout,
            "data": f32_base64(&flat),
        }))
    }
}

/// A vector drawn as an arrow from the origin: its series in the lab and its scale (metres per
/// unit: the longest arrow of the run reaches 1.3 times the scene).
pub struct Vector {
    /// Key (`omega`, `L`).
    pub name: &'static str,
    /// Legend text.
    pub label: &'static str,
    /// Colour, `#rrggbb`.
    pub colour: &'static str,
    /// Metres per unit of the vector.
    pub scale: f64,
    /// The vector at every row.
    pub series: Vec<Vector3<f64>>,
}

/// The poses of a drawing's objects at every row (in the order of [`Drawing::objects`]), the
/// trail point at every row, and the vectors.
pub struct Frames {
    /// Position of each object at each row.
    pub positions: Vec<Vec<Vector3<f64>>>,
    /// Orientation of each object at each row.
    pub turns: Vec<Vec<UnitQuaternion<f64>>>,
    /// The point the trail follows, at each row.
    pub trail: Vec<Vector3<f64>>,
    /// ω and L, where the rows give them.
    pub vectors: Vec<Vector>,
}

/// A body known by its mass and inertia, drawn at its centre of mass along its principal
/// axes: a flat body symmetric about its largest axis (`I₃ = I₁ + I₂`, `I₁ = I₂`: a ring, the
/// gimbals) as the hoop with its largest moment (radius `√(I₃/m)`), any other as the uniform
/// box with its principal moments (full sides `s₁² = 6 (I₂ + I₃ − I₁) / m`, …); a box with no
/// extent along an axis gets 2 % of its largest side there, a body with no inertia a small
/// sphere.
fn equivalent_box(b: &tumble_model::drawing::BodyShape) -> Piece {
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
    use tumble_model::drawing::BodyShape;

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
        let piece = equivalent_box(&shape(
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
        let piece = equivalent_box(&shape(
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
