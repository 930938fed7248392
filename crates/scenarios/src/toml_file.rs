//! What scene files and sweep files share: reading the text, parsing it into raw tables with
//! every syntax error placed at its `file:line:column` and shown with a caret, the
//! [`Location`] of a key, the description of a TOML value for messages, and the errors common
//! to both ([`TomlFileError`]).

use std::fmt;
use std::path::{Path, PathBuf};
use tumble_kinematics::angle::{ACCEPTED, parse_angle};

use serde::de::DeserializeOwned;

use crate::scenes;

/// Where in a file something is: its origin (a path, or a name given to text) and, when
/// known, the 1-based line and column.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file's path as given, or the name given to parsed text.
    pub origin: String,
    /// 1-based `(line, column)`; `None` when the parser could not place the error.
    pub position: Option<(usize, usize)>,
}

impl Location {
    /// The location of byte offset `offset` in `text`.
    #[must_use]
    pub fn at(origin: &str, text: &str, offset: usize) -> Self {
        let offset = offset.min(text.len());
        let before = &text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before[line_start..].chars().count() + 1;
        Location {
            origin: origin.to_string(),
            position: Some((line, column)),
        }
    }

    /// The 1-based line, when known.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        self.position.map(|(line, _)| line)
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.position {
            Some((line, column)) => write!(f, "{}:{line}:{column}", self.origin),
            None => f.write_str(&self.origin),
        }
    }
}

/// What can be wrong with a scene or sweep file before its keys are validated.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TomlFileError {
    /// The file could not be read.
    #[error("{}: cannot read the {kind} file: {source}", path.display())]
    Read {
        /// `scene` or `sweep`.
        kind: &'static str,
        /// The path given.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not UTF-8 text (TOML files are UTF-8).
    #[error(
        "{}: the {kind} file is not UTF-8 text: byte 0x{byte:02X} at line {line}, column {column} \
         (byte offset {offset}); save it as UTF-8",
        path.display()
    )]
    NotUtf8 {
        /// `scene` or `sweep`.
        kind: &'static str,
        /// The path given.
        path: PathBuf,
        /// The first byte that is not part of a UTF-8 character.
        byte: u8,
        /// Its offset in the file.
        offset: usize,
        /// Its line, from 1.
        line: usize,
        /// Its column in characters, from 1.
        column: usize,
    },
    /// Not valid TOML, an unknown key, a duplicate key or a value of the wrong type: the TOML
    /// parser's message (it names the key), followed by the offending line.
    #[error("{at}: {message}{excerpt}")]
    Syntax {
        /// Where.
        at: Location,
        /// The parser's message.
        message: String,
        /// The offending line, indented, with a caret under the column (empty when unplaced).
        excerpt: String,
    },
    /// The file does not name its scene.
    #[error("{origin}: missing `scene = \"NAME\"` (the model kind); built-in scenes: {known}")]
    MissingScene {
        /// The file.
        origin: String,
        /// The built-in scene names.
        known: String,
    },
}

impl TomlFileError {
    /// The location of the offending text, when the error has one.
    #[must_use]
    pub fn location(&self) -> Option<&Location> {
        match self {
            TomlFileError::Syntax { at, .. } => Some(at),
            TomlFileError::Read { .. }
            | TomlFileError::NotUtf8 { .. }
            | TomlFileError::MissingScene { .. } => None,
        }
    }

    /// The error for a file `origin` that names no scene.
    #[must_use]
    pub fn missing_scene(origin: &str) -> Self {
        TomlFileError::MissingScene {
            origin: origin.to_string(),
            known: scenes::builtin()
                .iter()
                .map(|s| s.info().name)
                .collect::<Vec<_>>()
                .join(", "),
        }
    }
}

/// Reads the `kind` file (`scene`, `sweep`) at `path`.
///
/// # Errors
/// [`TomlFileError::Read`] with the system's reason, [`TomlFileError::NotUtf8`] with the place
/// of the first byte that is not UTF-8.
pub fn read(path: &Path, kind: &'static str) -> Result<String, TomlFileError> {
    let bytes = std::fs::read(path).map_err(|source| TomlFileError::Read {
        kind,
        path: path.to_path_buf(),
        source,
    })?;
    String::from_utf8(bytes).map_err(|e| {
        let bytes = e.as_bytes();
        let offset = e.utf8_error().valid_up_to();
        // The valid prefix is UTF-8: its lines and characters place the bad byte.
        let before = std::str::from_utf8(&bytes[..offset]).unwrap_or_default();
        let line = before.matches('\n').count() + 1;
        let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        TomlFileError::NotUtf8 {
            kind,
            path: path.to_path_buf(),
            byte: bytes[offset],
            offset,
            line,
            column,
        }
    })
}

/// Parses `text` (named `origin` in messages) into raw tables `T`.
///
/// # Errors
/// [`TomlFileError::Syntax`], placed and with the offending line.
pub fn parse<T: DeserializeOwned>(text: &str, origin: &str) -> Result<T, TomlFileError> {
    toml::from_str(text).map_err(|e| {
        let at = match e.span() {
            Some(span) => Location::at(origin, text, span.start),
            None => Location {
                origin: origin.to_string(),
                position: None,
            },
        };
        TomlFileError::Syntax {
            excerpt: excerpt(text, &at),
            at,
            message: e.message().trim_end().to_string(),
        }
    })
}

/// A TOML value read as a number: a float, an integer a float holds exactly, or a string holding
/// an angle expression with the grammar of `--set` ([`parse_angle`]: `"pi/2"`, `"-3pi/4"`).
///
/// # Errors
/// What was found instead, described for a "must be a number, found …" message.
pub fn number_or_angle(value: &toml::Value) -> Result<f64, String> {
    match value {
        toml::Value::Float(x) => Ok(*x),
        toml::Value::Integer(i) if (*i as f64) as i64 == *i => Ok(*i as f64),
        toml::Value::Integer(i) => Err(format!(
            "the integer {i}, which a float cannot hold exactly"
        )),
        toml::Value::String(s) => parse_angle(s)
            .ok_or_else(|| format!("{}, which is not a number ({ACCEPTED})", describe(value))),
        other => Err(describe(other)),
    }
}

/// Describes a TOML value for an error message.
#[must_use]
pub fn describe(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) if s.chars().count() > 60 => {
            let head: String = s.chars().take(40).collect();
            format!(
                "a string of {} characters starting {head:?}…",
                s.chars().count()
            )
        }
        toml::Value::String(s) => format!("a string {s:?}"),
        toml::Value::Integer(i) => format!("the integer {i}"),
        toml::Value::Float(x) => format!("the float {x}"),
        toml::Value::Boolean(b) => format!("the boolean {b}"),
        toml::Value::Datetime(d) => format!("the date-time {d}"),
        toml::Value::Array(_) => "an array".to_string(),
        toml::Value::Table(_) => "a table".to_string(),
    }
}

/// A line of `text` with a caret under `at`'s column, indented, or empty when unplaced.
#[must_use]
pub fn excerpt(text: &str, at: &Location) -> String {
    let Some((line, column)) = at.position else {
        return String::new();
    };
    let Some(source) = text.lines().nth(line - 1) else {
        return String::new();
    };
    // A long line is cut to a window around the column (a 200 kB line is not echoed whole).
    const WINDOW: usize = 60;
    let chars: Vec<char> = source.chars().collect();
    let col = column.saturating_sub(1).min(chars.len());
    let (from, to) = if chars.len() <= 2 * WINDOW {
        (0, chars.len())
    } else {
        let from = col.saturating_sub(WINDOW);
        (from, (col + WINDOW).min(chars.len()))
    };
    let head = if from > 0 { "…" } else { "" };
    let tail = if to < chars.len() { "…" } else { "" };
    let shown: String = chars[from..to].iter().collect();
    format!(
        "\n    {line:>4} | {head}{shown}{tail}\n         | {}^",
        " ".repeat(col - from + head.chars().count())
    )
}
