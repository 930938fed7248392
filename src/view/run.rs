//! The data of a run for the viewer: the bodies (parts in their own frames), their poses in the
//! lab at every frame, the angular velocity and angular momentum in the lab, the point the
//! trail follows, and every column of the scene's rows, as `f32` arrays.

use anyhow::{Result, bail};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde_json::{Value, json};
use tumble_inertia::{MassSpec, THandle};
use tumble_kinematics::EulerConvention;
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

/// A scene's drawing: its objects, the body point the trail follows (in the body frame of the
/// first object, or the bead), and its size.
pub struct Drawing {
    objects: Vec<Object>,
    /// The trail follows this point of the first object; `None`: it follows the second (the
    /// bead).
    tip: Option<Vector3<f64>>,
    reach: f64,
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
            tip: None,
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
            tip: Some(tip),
            reach,
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
                    tip: Some(Vector3::new(0.0, 0.6 * sides[1].max(0.6), 0.0)),
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
                    tip: Some(
                        props.principal().axes.matrix().column(1).into_owned() * 1.15 * reach,
                    ),
                    reach,
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
                    tip: Some(z(1.1)),
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
        let mut positions: Vec<Vec<Vector3<f64>>> = Vec::new();
        let mut turns: Vec<Vec<UnitQuaternion<f64>>> = Vec::new();
        for object in &self.objects {
            let mut p = Vec::with_capacity(n);
            let mut q = Vec::with_capacity(n);
            for row in rows {
                let (at, turn) = match object.pose {
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
        let trail: Vec<Vector3<f64>> = match self.tip {
            Some(tip) => turns[0].iter().map(|q| q * tip).collect(),
            None => positions[1].clone(),
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
