//! What a model file declares to draw: its bodies and point masses as nodes of its graph.

use tumble_scenarios::drawing::Part;

use crate::expr::Id;
use crate::mechanics::{M3, V3};

/// A model's bodies and point masses as nodes of its graph: where they are and what they
/// look like, to draw them (`tumble view`, `tumble animate`).
#[derive(Debug, Clone, Default)]
pub struct ModelDrawing {
    /// Rigid bodies, in the file's order.
    pub bodies: Vec<DrawnBody>,
    /// Point masses, in the file's order.
    pub points: Vec<DrawnPoint>,
}

/// A rigid body of a model.
#[derive(Debug, Clone)]
pub struct DrawnBody {
    /// Its name in the file.
    pub name: String,
    /// Its orientation (body frame → model frame, by rows); `None`: it does not turn.
    pub rotation: Option<M3>,
    /// Its frame's origin in the model frame.
    pub origin: V3,
    /// Mass (of the parameters).
    pub mass: Id,
    /// Centre of mass in its frame (of the parameters).
    pub com: V3,
    /// Inertia tensor about the centre of mass, in its frame (of the parameters).
    pub inertia: M3,
    /// The parts of a body given by the `[body]` vocabulary (`geometry`), in its frame.
    pub parts: Option<Vec<Part>>,
}

/// A point mass of a model.
#[derive(Debug, Clone)]
pub struct DrawnPoint {
    /// Its name in the file.
    pub name: String,
    /// Mass (of the parameters).
    pub mass: Id,
    /// Position in the model frame.
    pub position: V3,
}
