//! What a model file declares beside its equations: parameters, run defaults and the frames
//! integrated on SO(3).

use tumble_scenarios::RunOptions;
use tumble_scenarios::params::Domain;

use crate::mechanics::{M3, V3};

/// A declared parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamDef {
    /// Name.
    pub name: String,
    /// Default value.
    pub default: f64,
    /// Unit (may be empty).
    pub unit: String,
    /// Allowed values.
    pub domain: Domain,
    /// What it is.
    pub description: String,
}

/// Run defaults of a model file.
#[derive(Debug, Clone, PartialEq)]
pub struct RunDefaults {
    /// Integrator.
    pub integrator: String,
    /// Fixed step (s).
    pub dt: f64,
    /// Horizon (s).
    pub t_end: f64,
    /// The file's own `[run]` options (for the caller to lay its own over).
    pub options: RunOptions,
}

/// A frame whose orientation is integrated on SO(3) (`orientation = "so3"`): its rotation
/// matrix and body angular velocity are state, not functions of coordinates.
#[derive(Debug, Clone)]
pub struct Orientation {
    /// The frame's name.
    pub name: String,
    /// The initial rotation (body → model frame, by rows), of the parameters.
    pub initial_rotation: M3,
    /// The initial angular velocity in the body frame, of the parameters.
    pub initial_omega: V3,
}
