//! [`PlotError`]: why a figure could not be read, drawn or written. Each message names the
//! file or the choice it is about and what was wrong with it; the underlying error (an I/O,
//! JSON or CSV error) is its [`std::error::Error::source`].

use std::path::PathBuf;

use tumble_output::OutputError;
use tumble_scenarios::SceneError;
use tumble_studies::sweep::SweepError;

/// Why a figure could not be read, drawn or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlotError {
    /// A result file that cannot be read.
    #[error("{}: cannot read it", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// A JSON record that is not one tumble wrote (a field missing or of the wrong kind).
    #[error("{}: not a record tumble wrote", path.display())]
    Record {
        /// The record.
        path: PathBuf,
        /// What serde found wrong.
        #[source]
        source: serde_json::Error,
    },
    /// A CSV file that cannot be read, or a row of it that is not what tumble writes.
    #[error("{}: {}", path.display(), row.map_or_else(|| "cannot read it".to_string(), |r| format!("row {r}")))]
    Csv {
        /// The file.
        path: PathBuf,
        /// The row (the header is row 1), when one row is at fault.
        row: Option<usize>,
        /// What the CSV reader found wrong.
        #[source]
        source: csv::Error,
    },
    /// A result whose content is not what tumble writes, or that has no figure.
    #[error("{}: {problem}", path.display())]
    Content {
        /// The file or folder.
        path: PathBuf,
        /// What is wrong with it, and what would do.
        problem: String,
    },
    /// A record naming a scene or parameter this build does not know.
    #[error("{}: {what}", path.display())]
    Scene {
        /// The record.
        path: PathBuf,
        /// What it names (`scene`, `parameter omega0`, `case NAME`).
        what: String,
        /// Why the scene refused it.
        #[source]
        source: Box<SceneError>,
    },
    /// A choice (an option, a flag, a keyword) that the result or the figure refuses.
    #[error("{given}: {expected}")]
    Choice {
        /// What was given (`--font-size 300`, `columns x`, `metric m`).
        given: String,
        /// What to give instead, or why it cannot be.
        expected: String,
    },
    /// A figure larger than [`crate::options::MAX_SIDE_PIXELS`] a side or
    /// [`crate::options::MAX_PIXELS`] in all.
    #[error(
        "the figure would be {width} x {height} pixels; figures are limited to {} pixels a side \
         and {} megapixels: use a smaller --figure-size or --dpi",
        crate::options::MAX_SIDE_PIXELS,
        crate::options::MAX_PIXELS / 1e6
    )]
    TooLarge {
        /// Device pixels across.
        width: u32,
        /// Device pixels down.
        height: u32,
    },
    /// Drawing, rasterising or converting the figure failed (a backend, SVG or PDF error).
    #[error("{0}")]
    Draw(String),
    /// The figure could not be drawn into this file.
    #[error("cannot draw {}", path.display())]
    Drawing {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: Box<PlotError>,
    },
    /// The figure could not be written.
    #[error("cannot write {}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// An output path that is refused or cannot be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A sweep folder that cannot be read.
    #[error(transparent)]
    Sweep(Box<SweepError>),
}

impl From<SweepError> for PlotError {
    fn from(e: SweepError) -> Self {
        PlotError::Sweep(Box::new(e))
    }
}

impl PlotError {
    /// [`PlotError::Content`] of `path`.
    pub(crate) fn content(path: &std::path::Path, problem: impl Into<String>) -> Self {
        PlotError::Content {
            path: path.to_path_buf(),
            problem: problem.into(),
        }
    }

    /// [`PlotError::Choice`].
    pub(crate) fn choice(given: impl Into<String>, expected: impl Into<String>) -> Self {
        PlotError::Choice {
            given: given.into(),
            expected: expected.into(),
        }
    }
}

/// What the figure code returns.
pub type Result<T, E = PlotError> = std::result::Result<T, E>;
