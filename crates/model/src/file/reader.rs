//! Reading a model file's values: the names in scope of an expression, the text being read
//! (numbers, expressions and vectors placed in it for messages), parameter domains, axes,
//! names, and the `[run]` defaults.

use std::collections::HashMap;

use toml::Spanned;
use tumble_scenarios::params::Domain;
use tumble_scenarios::toml_file::{self, Location};
use tumble_scenarios::{RunOptions, StepControl};

use super::raw::RawRun;
use super::{ModelFileError, RunDefaults};
use crate::expr::parse::{ParseError, Scope, parse};
use crate::expr::{Graph, Id};
use crate::mechanics::V3;

/// Names visible to an expression.
pub(super) struct Names {
    pub(super) map: HashMap<String, Id>,
    pub(super) order: Vec<String>,
}

impl Names {
    pub(super) fn new() -> Self {
        Names {
            map: HashMap::new(),
            order: Vec::new(),
        }
    }

    pub(super) fn insert(&mut self, name: &str, id: Id) {
        if self.map.insert(name.to_string(), id).is_none() {
            self.order.push(name.to_string());
        }
    }
}

impl Scope for Names {
    fn resolve(&self, name: &str, _graph: &mut Graph) -> Option<Id> {
        self.map.get(name).copied()
    }
    fn names(&self) -> Vec<String> {
        self.order.clone()
    }
}

/// The text being read, to place errors.
pub(super) struct Src<'a> {
    pub(super) origin: &'a str,
    pub(super) text: &'a str,
    /// Every expression read: its key, place and node (checked for units at the end).
    pub(super) read: std::cell::RefCell<Vec<(String, std::ops::Range<usize>, Id)>>,
}

impl Src<'_> {
    pub(super) fn invalid(
        &self,
        span: &std::ops::Range<usize>,
        key: &str,
        message: impl ToString,
    ) -> ModelFileError {
        let at = Location::at(self.origin, self.text, span.start);
        ModelFileError::Invalid {
            excerpt: toml_file::excerpt(self.text, &at),
            at,
            key: key.to_string(),
            message: message.to_string(),
        }
    }

    /// A number (or an angle such as `"pi/2"`).
    pub(super) fn number(
        &self,
        key: &str,
        value: &Spanned<toml::Value>,
    ) -> Result<f64, ModelFileError> {
        let x = toml_file::number_or_angle(value.get_ref()).map_err(|found| {
            self.invalid(
                &value.span(),
                key,
                format!("must be a number, found {found}"),
            )
        })?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.invalid(&value.span(), key, format!("must be finite, found {x}")))
        }
    }

    /// An expression: a number, or a string in the expression language.
    pub(super) fn expr(
        &self,
        key: &str,
        value: &Spanned<toml::Value>,
        graph: &mut Graph,
        scope: &Names,
    ) -> Result<Id, ModelFileError> {
        let span = value.span();
        let id = match value.get_ref() {
            toml::Value::Float(x) if x.is_finite() => graph.constant(*x),
            toml::Value::Integer(i) => graph.constant(*i as f64),
            toml::Value::String(s) => {
                parse(s, graph, scope).map_err(|e| self.expression(key, &span, s, &e))?
            }
            other => Err(self.invalid(
                &span,
                key,
                format!(
                    "must be an expression (a string such as \"m*g*l\") or a number, found {}",
                    toml_file::describe(other)
                ),
            ))?,
        };
        self.read.borrow_mut().push((key.to_string(), span, id));
        Ok(id)
    }

    pub(super) fn expression(
        &self,
        key: &str,
        span: &std::ops::Range<usize>,
        s: &str,
        e: &ParseError,
    ) -> ModelFileError {
        // The string's text starts after its opening quote(s); escapes may shift the column.
        let raw = &self.text[span.start.min(self.text.len())..];
        let quote = if raw.starts_with("\"\"\"") || raw.starts_with("'''") {
            3
        } else {
            1
        };
        let at = Location::at(self.origin, self.text, span.start + quote + e.offset);
        ModelFileError::Expression {
            at,
            key: key.to_string(),
            message: e.message.clone(),
            excerpt: e.excerpt(s),
        }
    }

    pub(super) fn vector(
        &self,
        key: &str,
        value: &Spanned<Vec<Spanned<toml::Value>>>,
        graph: &mut Graph,
        scope: &Names,
    ) -> Result<V3, ModelFileError> {
        let list = value.get_ref();
        if list.len() != 3 {
            return Err(self.invalid(
                &value.span(),
                key,
                format!("must be three expressions [x, y, z], found {}", list.len()),
            ));
        }
        let mut out = [Id(0); 3];
        for (i, v) in list.iter().enumerate() {
            out[i] = self.expr(&format!("{key}[{}]", i + 1), v, graph, scope)?;
        }
        Ok(out)
    }
}

pub(super) fn domain(name: &str) -> Option<Domain> {
    Some(match name {
        "positive" => Domain::Positive,
        "non-negative" => Domain::NonNegative,
        "finite" => Domain::Finite,
        "non-zero" => Domain::NonZero,
        _ => return None,
    })
}

pub(super) fn axis(name: &str) -> Option<usize> {
    match name {
        "x" | "X" => Some(0),
        "y" | "Y" => Some(1),
        "z" | "Z" => Some(2),
        _ => None,
    }
}

/// A name that expressions can use: letters, digits and `_`, not starting with a digit, and not
/// a built-in name.
pub(super) fn check_name(
    src: &Src<'_>,
    key: &str,
    name: &Spanned<String>,
) -> Result<(), ModelFileError> {
    let s = name.get_ref();
    let ok = s
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !ok {
        return Err(src.invalid(
            &name.span(),
            key,
            format!("`{s}` cannot be used in expressions: use letters, digits and `_`, starting with a letter"),
        ));
    }
    let builtin = s == "t"
        || s == "pi"
        || s == "atan2"
        || s == "pow"
        || crate::expr::Fun::ALL.iter().any(|(n, _)| *n == s);
    if builtin {
        return Err(src.invalid(
            &name.span(),
            key,
            format!("`{s}` is a built-in name; choose another"),
        ));
    }
    Ok(())
}

pub(super) fn run_defaults(
    src: &Src<'_>,
    run: Option<&Spanned<RawRun>>,
) -> Result<RunDefaults, ModelFileError> {
    let mut options = RunOptions::default();
    let mut out = RunDefaults {
        integrator: "gauss8".to_string(),
        dt: 0.01,
        t_end: 10.0,
        options: RunOptions::default(),
    };
    if let Some(run) = run {
        let r = run.get_ref();
        if let Some(name) = &r.integrator {
            out.integrator.clone_from(name);
        }
        match (&r.dt, &r.tol) {
            (Some(dt), None) => {
                out.dt = src.number("run.dt", dt)?;
                if !(out.dt > 0.0) {
                    return Err(src.invalid(&dt.span(), "run.dt", "must be positive"));
                }
                options.step = Some(StepControl::Fixed(out.dt));
            }
            (None, Some(tol)) => {
                let x = src.number("run.tol", tol)?;
                if !(x > 0.0) {
                    return Err(src.invalid(&tol.span(), "run.tol", "must be positive"));
                }
                options.step = Some(StepControl::Tolerance(x));
            }
            (Some(_), Some(tol)) => {
                return Err(src.invalid(&tol.span(), "run.tol", "`run.dt` and `run.tol` are both given; a run has a fixed step or a tolerance, not both"));
            }
            (None, None) => {}
        }
        if let Some(t) = &r.t_end {
            out.t_end = src.number("run.t_end", t)?;
            if !(out.t_end > 0.0) {
                return Err(src.invalid(&t.span(), "run.t_end", "must be positive"));
            }
        }
    }
    out.options = options;
    Ok(out)
}
