//! Scene parameters: named, documented, with defaults and a domain, validated on every change.

use std::fmt;

use crate::error::SceneError;

/// The values a parameter may take.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Domain {
    /// Finite and `> 0` (masses, lengths).
    Positive,
    /// Finite and `≥ 0` (gravity, a massless bead).
    NonNegative,
    /// Any finite value (angles, rates).
    Finite,
    /// Finite and not zero (a spin that sets the whole motion).
    NonZero,
}

impl Domain {
    /// Whether `value` lies in the domain.
    #[must_use]
    pub fn contains(self, value: f64) -> bool {
        value.is_finite()
            && match self {
                Domain::Positive => value > 0.0,
                Domain::NonNegative => value >= 0.0,
                Domain::Finite => true,
                Domain::NonZero => value != 0.0,
            }
    }

    /// What the domain requires, in words.
    #[must_use]
    pub fn requirement(self) -> &'static str {
        match self {
            Domain::Positive => "must be finite and positive",
            Domain::NonNegative => "must be finite and not negative",
            Domain::Finite => "must be finite",
            Domain::NonZero => "must be finite and not zero",
        }
    }
}

impl fmt::Display for Domain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Domain::Positive => "> 0",
            Domain::NonNegative => ">= 0",
            Domain::Finite => "finite",
            Domain::NonZero => "!= 0",
        })
    }
}

/// One documented parameter of a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamSpec {
    /// Name as used in scene files, `--set` and CSV manifests (e.g. `omega0`).
    pub name: &'static str,
    /// Default value.
    pub default: f64,
    /// SI unit (`kg`, `m`, `rad/s`, …; empty for dimensionless).
    pub unit: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Allowed values.
    pub domain: Domain,
}

/// A scene's parameter values, always valid for its specs.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    scene: &'static str,
    specs: &'static [ParamSpec],
    values: Vec<f64>,
}

impl Params {
    /// The defaults of `specs` for scene `scene`.
    #[must_use]
    pub fn defaults(scene: &'static str, specs: &'static [ParamSpec]) -> Self {
        Params {
            scene,
            specs,
            values: specs.iter().map(|s| s.default).collect(),
        }
    }

    /// Sets `name` to `value`.
    ///
    /// # Errors
    /// [`SceneError::UnknownParameter`] (listing the known names) or
    /// [`SceneError::InvalidParameter`] (saying what the domain requires).
    pub fn set(&mut self, name: &str, value: f64) -> Result<(), SceneError> {
        let i = self.index(name)?;
        let spec = &self.specs[i];
        if !spec.domain.contains(value) {
            return Err(SceneError::InvalidParameter {
                scene: self.scene.to_string(),
                name: spec.name.to_string(),
                value,
                requirement: spec.domain.requirement(),
            });
        }
        self.values[i] = value;
        Ok(())
    }

    /// The value of `name`.
    ///
    /// # Errors
    /// [`SceneError::UnknownParameter`] if the scene has no such parameter.
    pub fn get(&self, name: &str) -> Result<f64, SceneError> {
        self.index(name).map(|i| self.values[i])
    }

    /// `(name, value)` in the order the scene documents them.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.specs
            .iter()
            .map(|s| s.name)
            .zip(self.values.iter().copied())
    }

    /// The specs.
    #[must_use]
    pub fn specs(&self) -> &'static [ParamSpec] {
        self.specs
    }

    fn index(&self, name: &str) -> Result<usize, SceneError> {
        self.specs
            .iter()
            .position(|s| s.name == name)
            .ok_or_else(|| SceneError::UnknownParameter {
                scene: self.scene.to_string(),
                name: name.to_string(),
                known: self
                    .specs
                    .iter()
                    .map(|s| s.name)
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}
