//! What can be wrong with a sweep file or an override, and where a value came from.

use std::fmt;

use tumble_scenarios::error::SceneError;
use tumble_scenarios::toml_file::{Location, TomlFileError};

/// Where a value of a sweep definition came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Origin {
    /// A key of the file (or of the built-in definition's text).
    File(Location),
    /// A command-line override, as typed (`--set run.dt=0.005`).
    Override(String),
}

impl Origin {
    /// The 1-based line in the file, when the value came from one.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        match self {
            Origin::File(at) => at.line(),
            Origin::Override(_) => None,
        }
    }
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::File(at) => at.fmt(f),
            Origin::Override(text) => write!(f, "--set {text}"),
        }
    }
}

/// What can be wrong with a sweep file or an override; every variant names the key and where
/// it is, but a file that cannot be read or names no scene ([`TomlFileError`]) and
/// [`SweepFileError::NoAxes`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepFileError {
    /// Not readable, not TOML, an unknown key, a value of the wrong type, no scene named.
    #[error(transparent)]
    File(#[from] TomlFileError),
    /// The scene rejected a key: unknown scene or parameter, a value outside its domain, an
    /// integrator that cannot run it, an invalid step, tolerance or horizon.
    #[error("{at}: `{key}`: {error}")]
    Scene {
        /// Where.
        at: Origin,
        /// The dotted key (`scene`, `parameters.M`, `run.dt`, `axes.omega0.range`).
        key: String,
        /// What the scene said (boxed to keep the error small).
        error: Box<SceneError>,
    },
    /// A value that must be a number (or a whole number) is something else.
    #[error("{at}: `{key}` must be {expected}, found {found}")]
    NotANumber {
        /// Where.
        at: Origin,
        /// The dotted key.
        key: String,
        /// `a number`, `a whole number >= 1`, …
        expected: &'static str,
        /// What was found, described.
        found: String,
    },
    /// A key whose value is not allowed: a bad range, count, spacing or threshold, a
    /// parameter both fixed and swept, an axis given twice, conflicting keys, an unknown
    /// override key.
    #[error("{at}: `{key}`: {reason}")]
    Invalid {
        /// Where.
        at: Origin,
        /// The dotted key.
        key: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// A metric name that does not exist or does not apply to the scene.
    #[error("{at}: `metrics.record`: {reason}")]
    Metric {
        /// Where the name is.
        at: Origin,
        /// What is wrong (the metric, the scene, the known metrics).
        reason: String,
    },
    /// The file sweeps nothing.
    #[error(
        "{origin}: no [[axes]]: a sweep needs at least one axis (a parameter with `values` or \
         a `range`)"
    )]
    NoAxes {
        /// The file.
        origin: String,
    },
}

impl SweepFileError {
    /// Where the offending key is, when it has a place.
    #[must_use]
    pub fn origin(&self) -> Option<Origin> {
        match self {
            SweepFileError::File(e) => e.location().cloned().map(Origin::File),
            SweepFileError::Scene { at, .. }
            | SweepFileError::NotANumber { at, .. }
            | SweepFileError::Invalid { at, .. }
            | SweepFileError::Metric { at, .. } => Some(at.clone()),
            SweepFileError::NoAxes { .. } => None,
        }
    }

    /// The 1-based line of the offending key, when it is in a file.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        self.origin().and_then(|o| o.line())
    }
}
