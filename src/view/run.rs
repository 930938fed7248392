//! The data of a run for the viewer: the bodies (parts in their own frames), their poses in the
//! lab at every frame, the angular velocity and angular momentum in the lab, the point the
//! trail follows, and every column of the scene's rows, as `f32` arrays. What is drawn is what
//! the scene declares ([`Scene::drawing`]; a scene file's `[body]` its own parts).

use anyhow::{Result, bail};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use serde_json::{Value, json};
use tumble_scenarios::drawing::{self as declared, BodyDrawing, Motion, Trail};
use tumble_scenarios::{Params, Scene, scenes};

use super::geometry::{Piece, Render};
use super::{f32_base64, round_sig};

/// A scene's drawing ([`declared::Drawing`]) and, for a scene that places its objects itself
/// (a model), the scene and parameters that place them.
pub struct Drawing {
    declared: declared::Drawing,
    placer: Option<(&'static dyn Scene, Params)>,
}

fn identity() -> UnitQuaternion<f64> {
    UnitQuaternion::identity()
}

impl Drawing {
    /// The drawing of a scene file's `[body]` ([`declared::Drawing::of_body`]).
    #[must_use]
    pub fn of_body(drawing: &BodyDrawing, params: &Params) -> Self {
        Drawing {
            declared: declared::Drawing::of_body(drawing, params),
            placer: None,
        }
    }

    /// The drawing `scene` declares at `params` ([`Scene::drawing`]).
    ///
    /// # Errors
    /// A scene with no 3D view (the Coriolis drop), invalid parameters.
    pub fn of_scene(scene: &'static dyn Scene, params: &Params) -> Result<Self> {
        let name = scene.info().name;
        let Some(declared) = scene.drawing(params) else {
            let drawn: Vec<&str> = scenes::builtin()
                .iter()
                .filter(|s| s.drawing(&s.info().default_params()).is_some())
                .map(|s| s.info().name)
                .collect();
            bail!(
                "`{name}` has no 3D view: view draws {}, model files and scene files with a \
                 [body] table",
                drawn.join(", ")
            );
        };
        let declared = declared.map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
        let placer = declared.is_placed().then(|| (scene, params.clone()));
        Ok(Drawing { declared, placer })
    }

    /// The scene's size (metres): the camera and the arrows are scaled by it.
    #[must_use]
    pub fn reach(&self) -> f64 {
        self.declared.reach
    }

    /// The objects drawn: colour (`#rrggbb`), pieces in the object's frame, and whether its
    /// own axes (the body frame) are drawn.
    pub fn objects(&self) -> impl Iterator<Item = (&'static str, &[Piece], bool)> {
        self.declared
            .objects
            .iter()
            .map(|o| (o.colour, o.pieces.as_slice(), o.axes))
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
        let placed = match &self.placer {
            Some((scene, params)) => {
                let placed = scene.placements(params, rows);
                if placed.len() != n {
                    bail!("the rows do not hold the scene's coordinates and rates");
                }
                placed
            }
            None => Vec::new(),
        };
        let mut positions: Vec<Vec<Vector3<f64>>> = Vec::new();
        let mut turns: Vec<Vec<UnitQuaternion<f64>>> = Vec::new();
        for object in &self.declared.objects {
            let mut p = Vec::with_capacity(n);
            let mut q = Vec::with_capacity(n);
            for (i, row) in rows.iter().enumerate() {
                let (at, turn) = match object.motion {
                    Motion::PlacedBody(k) => {
                        let (r, origin) = placed[i].bodies[k];
                        let m = Matrix3::from_fn(|a, b| r[a][b]);
                        (
                            Vector3::from(origin),
                            UnitQuaternion::from_matrix_eps(&m, 1e-12, 100, identity()),
                        )
                    }
                    Motion::PlacedPoint(k) => (Vector3::from(placed[i].points[k]), identity()),
                    Motion::Fixed => (Vector3::zeros(), identity()),
                    Motion::Quaternion => (Vector3::zeros(), orientation(row)?),
                    Motion::VerticalPlane { omega } => {
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
                    Motion::BeadFree { a } => {
                        let alpha = row[need("alpha")?];
                        let at =
                            orientation(row)? * Vector3::new(a * alpha.cos(), a * alpha.sin(), 0.0);
                        (at, identity())
                    }
                    Motion::BeadVertical { a, omega } => {
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
        let trail: Vec<Vector3<f64>> = match self.declared.trail {
            Trail::Tip(k, tip) => turns[k]
                .iter()
                .zip(&positions[k])
                .map(|(q, p)| p + q * tip)
                .collect(),
            Trail::Object(k) => positions[k].clone(),
        };
        // Angular velocity (lab) and angular momentum (lab), when the rows give them.
        let omega: Option<Vec<Vector3<f64>>> =
            if let (Some(x), Some(y), Some(z)) = (col("omega_x"), col("omega_y"), col("omega_z")) {
                Some(
                    rows.iter()
                        .zip(&turns[0])
                        .map(|(row, q)| q * Vector3::new(row[x], row[y], row[z]))
                        .collect(),
                )
            } else {
                match self.declared.objects[0].motion {
                    Motion::VerticalPlane { omega: Some(w) } => {
                        Some(vec![Vector3::new(0.0, 0.0, w); n])
                    }
                    Motion::VerticalPlane { omega: None } => {
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
                1.3 * self.declared.reach / largest
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
        for (k, object) in self.declared.objects.iter().enumerate() {
            object_json.push(json!({
                "name": object.name,
                "colour": object.colour,
                "parts": object.pieces.iter().map(Render::json).collect::<Vec<_>>(),
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
            "reach": round_sig(self.declared.reach, 6),
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
