//! What a scene looks like, for `tumble view` and `tumble animate`: the [`Drawing`] a scene
//! declares ([`Scene::drawing`](crate::Scene::drawing): objects made of [`Piece`]s, how each
//! follows the rows, the trail), the pieces of a body's parts, and the parts of a scene file's
//! `[body]` table in the body's own frame (the mass properties come from the same parts,
//! [`body_table`](crate::body_table); this keeps their shapes).

mod pieces;
mod view;

pub use pieces::{Form, Piece, equivalent_box, mesh, parts, reach};
pub use view::{Drawing, Motion, Object, Placed, Trail, pivot};

use std::path::Path;

use nalgebra::Point3;
use serde::Deserialize;
use toml::Spanned;
use tumble_inertia::{Placement, PointMass, Shape, TriangleMesh};

use crate::body_table::{self, Place, RawBody};
use crate::scene_file::SceneFileError;
use crate::scenes;
use crate::toml_file;

/// One source of a body, in the body's own frame (metres).
#[derive(Debug, Clone)]
pub enum Part {
    /// A closed triangle mesh, scaled to metres.
    Mesh(TriangleMesh),
    /// A primitive turned and moved into place.
    Shape(Shape, Placement),
    /// Point masses.
    Points(Vec<PointMass>),
}

/// A body to draw: its parts and the point its orientation turns about (the centre of mass of
/// a free body, the pivot of a top), in the body's own frame.
#[derive(Debug, Clone)]
pub struct BodyDrawing {
    /// The parts.
    pub parts: Vec<Part>,
    /// The fixed point of the motion.
    pub center: Point3<f64>,
}

/// Only the keys the drawing needs; the file was validated by [`crate::scene_file`].
#[derive(Deserialize)]
struct BodyOnly {
    scene: Option<String>,
    body: Option<Spanned<RawBody>>,
}

/// The body of the scene file at `path`, if it has a `[body]` table.
///
/// # Errors
/// The file cannot be read or parsed, or its `[body]` table is invalid (the errors of
/// [`crate::scene_file::SceneFile::load`]).
pub fn of_scene_file(path: &Path) -> Result<Option<BodyDrawing>, SceneFileError> {
    let origin = path.display().to_string();
    let text = toml_file::read(path, "scene")?;
    let raw: BodyOnly = toml_file::parse(&text, &origin)?;
    let (Some(scene), Some(table)) = (raw.scene, raw.body) else {
        return Ok(None);
    };
    let Some(body_scene) = scenes::body::for_scene(&scene) else {
        return Ok(None);
    };
    let place = Place {
        origin: &origin,
        text: &text,
    };
    let body =
        body_table::read(&place, &table, body_scene.0).map_err(|e| SceneFileError::Body {
            at: e.at,
            key: e.key,
            message: e.message,
        })?;
    Ok(Some(BodyDrawing {
        center: body.pivot.unwrap_or(body.props.center_of_mass()),
        parts: body.parts,
    }))
}
