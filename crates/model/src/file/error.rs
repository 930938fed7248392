//! What is wrong with a model file: the key, its place and what to write instead.

use tumble_scenarios::toml_file::{Location, TomlFileError};

/// What is wrong with a model file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ModelFileError {
    /// Not readable, not TOML, an unknown key or a value of the wrong type.
    #[error(transparent)]
    File(#[from] TomlFileError),
    /// A key whose value is refused.
    #[error("{at}: `{key}`: {message}{excerpt}")]
    Invalid {
        /// Where.
        at: Location,
        /// The dotted key.
        key: String,
        /// What is wrong and what to write instead.
        message: String,
        /// The offending line with a caret (may be empty).
        excerpt: String,
    },
    /// An expression that does not parse.
    #[error("{at}: `{key}`: {message}\n{excerpt}")]
    Expression {
        /// Where the fault is (in the file).
        at: Location,
        /// The dotted key.
        key: String,
        /// What is wrong.
        message: String,
        /// The expression with a caret under the fault.
        excerpt: String,
    },
}
