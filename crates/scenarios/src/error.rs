//! Errors of the scenarios crate: each says what is wrong and where.

/// A model could not be built or evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A parameter is outside its physical domain.
    #[error("parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// The parameter's name as the scene documents it.
        name: String,
        /// The value given.
        value: f64,
        /// What it must satisfy.
        reason: &'static str,
    },
    /// The mass matrix is singular or too ill-conditioned: a coordinate singularity (gimbal
    /// lock of Euler angles) or a degenerate model.
    #[error(
        "singular mass matrix at t = {t}: condition number {condition:e} exceeds {max_condition:e} \
         (state {state:?}); the coordinates are at or near a singularity"
    )]
    SingularMassMatrix {
        /// Time.
        t: f64,
        /// `λ_max/λ_min` (∞ when not positive definite).
        condition: f64,
        /// The bound it was compared with.
        max_condition: f64,
        /// The state `(q, q̇)`.
        state: Vec<f64>,
    },
    /// The equations produced a non-finite value.
    #[error("non-finite accelerations at t = {t} (state {state:?})")]
    NonFinite {
        /// Time.
        t: f64,
        /// The state `(q, q̇)`.
        state: Vec<f64>,
    },
    /// A state vector of the wrong size.
    #[error("state has {found} components, the model needs {expected}")]
    Dimension {
        /// Required size.
        expected: usize,
        /// Given size.
        found: usize,
    },
}

/// Checks that a parameter is finite and positive.
pub(crate) fn positive(name: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ModelError::InvalidParameter {
            name: name.to_string(),
            value,
            reason: "must be finite and positive",
        })
    }
}

/// Checks that a parameter is finite and not negative.
pub(crate) fn non_negative(name: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ModelError::InvalidParameter {
            name: name.to_string(),
            value,
            reason: "must be finite and not negative",
        })
    }
}

/// Checks that a parameter is finite.
pub(crate) fn finite(name: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ModelError::InvalidParameter {
            name: name.to_string(),
            value,
            reason: "must be finite",
        })
    }
}

/// What can go wrong when a scene is configured or run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// No built-in scene has this name.
    #[error("unknown scene `{name}`; built-in scenes: {known}")]
    UnknownScene {
        /// The name given.
        name: String,
        /// The built-in names.
        known: String,
    },
    /// The scene has no parameter of this name.
    #[error("scene `{scene}` has no parameter `{name}`; its parameters: {known}")]
    UnknownParameter {
        /// The scene.
        scene: String,
        /// The name given.
        name: String,
        /// The scene's parameter names.
        known: String,
    },
    /// A parameter value outside its domain.
    #[error("scene `{scene}`: parameter `{name}` = {value} {requirement}")]
    InvalidParameter {
        /// The scene.
        scene: String,
        /// The parameter.
        name: String,
        /// The value given.
        value: f64,
        /// What the domain requires.
        requirement: &'static str,
    },
    /// The integrator does not exist or does not apply to this scene.
    #[error("integrator `{name}` cannot run scene `{scene}`: {reason}; applicable: {applicable}")]
    UnsupportedIntegrator {
        /// The scene.
        scene: String,
        /// The integrator asked for.
        name: String,
        /// Why not: what the method needs and what the scene offers.
        reason: String,
        /// The integrators that apply.
        applicable: String,
    },
    /// A run option (step, tolerance, horizon, output cadence) is invalid.
    #[error("{option} = {value}: {reason}")]
    InvalidOption {
        /// `dt`, `tol`, `t_end` or `every`.
        option: &'static str,
        /// The value given.
        value: f64,
        /// What it must satisfy.
        reason: String,
    },
    /// The model failed (a singular mass matrix, a non-finite state).
    #[error(transparent)]
    Model(#[from] ModelError),
    /// Mass properties could not be computed (a body's mesh or primitive).
    #[error(transparent)]
    Inertia(#[from] tumble_inertia::InertiaError),
    /// A body's triangle mesh does not bound a solid.
    #[error(transparent)]
    Mesh(#[from] tumble_inertia::MeshError),
    /// The integrator failed (non-convergence, non-finite state), with time and state.
    #[error("integration failed: {0}")]
    Integration(#[from] tumble_integrators::Error),
    /// A row of output (the state, or a quantity derived from it such as the energy) is not
    /// finite: the model's numbers overflowed (parameters of an extreme scale) or the state
    /// blew up. The run stops at that row, which is not handed to the recorder.
    #[error(
        "non-finite output at t = {t}: column {column} of the row is {value} (row {row:?}); \
         the state or a quantity derived from it overflowed (check the parameters' scale)"
    )]
    NonFiniteOutput {
        /// Time of the row.
        t: f64,
        /// Index of the first non-finite column (0 is `t`).
        column: usize,
        /// Its value.
        value: f64,
        /// The whole row.
        row: Vec<f64>,
    },
    /// The run was stopped from outside (a signal) at a step boundary before its horizon.
    #[error("interrupted at t = {t}")]
    Interrupted {
        /// Time reached.
        t: f64,
    },
    /// A model written as text refused its state or parameters before any step (a singular
    /// mass matrix at the initial state, with the coordinate at fault and what to do).
    #[error("model `{model}`: {message}")]
    ModelRefused {
        /// The model's name.
        model: String,
        /// What is wrong and what to do instead.
        message: String,
    },
}
