//! Values of a sweep-file draft that remember where they came from, and their conversion to
//! numbers with errors naming the key.

use super::file_error::{Origin, SweepFileError};
use tumble_scenarios::toml_file::describe;

/// A value and where it came from.
#[derive(Debug, Clone)]
pub(super) struct Src<T> {
    pub(super) value: T,
    pub(super) at: Origin,
}

/// A number as written: a float, an integer, or a value of another type (an error when a
/// number is needed).
#[derive(Debug, Clone)]
pub(super) enum Num {
    Float(f64),
    Int(i64),
    Other(String),
}

impl Num {
    pub(super) fn from_toml(value: &toml::Value) -> Self {
        match value {
            toml::Value::Float(x) => Num::Float(*x),
            toml::Value::Integer(i) => Num::Int(*i),
            other => Num::Other(describe(other)),
        }
    }
}

impl Src<Num> {
    /// As a float (integers exactly representable as one).
    pub(super) fn float(&self, key: &str) -> Result<f64, SweepFileError> {
        match &self.value {
            Num::Float(x) => Ok(*x),
            Num::Int(i) if (*i as f64) as i64 == *i => Ok(*i as f64),
            Num::Int(i) => Err(self.not_a(
                key,
                "a number",
                format!("the integer {i}, which a float cannot hold exactly"),
            )),
            Num::Other(found) => Err(self.not_a(key, "a number", found.clone())),
        }
    }

    /// As a whole number `≥ min` (overrides give floats: they must be whole).
    pub(super) fn whole(
        &self,
        key: &str,
        min: u64,
        expected: &'static str,
    ) -> Result<u64, SweepFileError> {
        let n = match &self.value {
            Num::Int(i) => u64::try_from(*i).ok(),
            Num::Float(x) if x.fract() == 0.0 && *x >= 0.0 && *x < 2f64.powi(64) => Some(*x as u64),
            _ => None,
        };
        match n {
            Some(n) if n >= min => Ok(n),
            _ => Err(self.not_a(
                key,
                expected,
                match &self.value {
                    Num::Float(x) => format!("{x}"),
                    Num::Int(i) => format!("{i}"),
                    Num::Other(found) => found.clone(),
                },
            )),
        }
    }

    pub(super) fn not_a(&self, key: &str, expected: &'static str, found: String) -> SweepFileError {
        SweepFileError::NotANumber {
            at: self.at.clone(),
            key: key.to_string(),
            expected,
            found,
        }
    }
}
