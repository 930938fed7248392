//! Values of a sweep-file draft that remember where they came from, and their conversion to
//! numbers with errors naming the key.

use super::file_error::{Origin, SweepFileError};
use tumble_scenarios::toml_file::{describe, number_or_angle};

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
            // Angle expressions as strings, with the grammar and the words of `--set`.
            toml::Value::String(_) => match number_or_angle(value) {
                Ok(x) => Num::Float(x),
                Err(found) => Num::Other(found),
            },
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

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::super::SweepDefinition;

    const FILE: &str = r#"
scene = "free-hoop"

[parameters]
a = 1.0
theta0 = "pi/2"

[run]
integrator = "gauss8"
dt = 0.01
t_end = 0.5

[[axes]]
parameter = "alpha0"
values = ["-3pi/4", 0.5, "2*pi/3"]
"#;

    #[test]
    fn sweep_files_take_angle_expressions_as_strings_like_set() {
        let def = SweepDefinition::parse(FILE, "angles.sweep.toml", &[]).unwrap();
        assert_eq!(def.params.get("theta0").unwrap(), PI / 2.0);
        let alphas: Vec<f64> = (0..3).map(|k| def.point(k)[0]).collect();
        assert_eq!(alphas, vec![-3.0 * PI / 4.0, 0.5, 2.0 * PI / 3.0]);
    }

    #[test]
    fn a_string_that_is_no_angle_expression_is_refused_with_its_key_and_line() {
        let text = FILE.replace("\"pi/2\"", "\"pi/2x\"");
        let e = SweepDefinition::parse(&text, "angles.sweep.toml", &[]).unwrap_err();
        let message = e.to_string();
        assert!(message.contains("angles.sweep.toml:6"), "{message}");
        assert!(message.contains("theta0"), "{message}");
        assert!(message.contains("pi/2x"), "{message}");
        assert!(message.contains("angle expressions such as"), "{message}");
    }
}
