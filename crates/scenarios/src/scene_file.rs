//! Scene files (TOML): a built-in model kind, its parameters and run defaults, validated with
//! the line of every offending key.
//!
//! # Format
//!
//! ```toml
//! # The model kind: one of the built-in scenes (`tumble scenes` lists them).
//! scene = "spinning-hoop"
//!
//! # Parameters of that scene; any omitted one keeps its default. Values are numbers
//! # (integers are taken as exact floats) or angle expressions as strings, with the grammar
//! # of `--set` (`"pi/2"`, `"-3pi/4"`, `"2*pi"`); `inf` and `nan` are rejected like any value
//! # outside the parameter's domain.
//! [parameters]
//! M = 1.0
//! a = 0.4
//! m = 0.2
//! omega0 = 5.0
//! alpha0 = 3.1
//!
//! # Optional run defaults; the command line overrides each of them.
//! [run]
//! integrator = "gauss8"   # from the scene's applicable integrators
//! dt = 0.001              # fixed step (s) ...
//! # tol = 1e-10           # ... or the tolerance of an adaptive integrator, not both
//! t_end = 5.0             # horizon (s)
//! every = 10              # record every 10th step
//! # at = [0.5, 1.0, 2.5]  # ... or rows at these times (dense output), or
//! # output_dt = 0.1       # ... every 0.1 s; the final state is always written
//! ```
//!
//! Top-level keys are `scene`, `parameters`, `run` and `body`; `[run]` takes `integrator`,
//! `dt`, `tol`, `t_end`, `every`, `at` and `output_dt`. Any other key is an error.
//!
//! # Rigid bodies: the `[body]` table
//!
//! The rigid-body scenes `free-body`, `dzhanibekov` and `heavy-top` take a body of the user's
//! own from a `[body]` table: a mesh (relative to the scene file, with its units and its mass
//! or density), point masses and placed primitives, all combined (the format is in
//! [`body_table`](crate::body_table)); the heavy top also names its pivot. The scene then
//! becomes its body variant ([`scenes::body`](crate::scenes::body)): the body's parameters
//! (principal moments, principal axes, for the top its mass and centre of mass) come from the
//! table, and the initial orientation (`phi0, theta0, psi0`) and angular velocity (`omega_x0,
//! omega_y0, omega_z0`) are given in `[parameters]` **in the body's own frame** (the mesh file's
//! coordinates), the frame the rows report. Other scenes refuse a `[body]` table
//! ([`SceneFileError::BodyNotApplicable`]).
//!
//! # Validation
//!
//! Everything is checked when the file is read, before any work: TOML syntax and unknown keys
//! (the TOML parser's message with its line and column), a missing or unknown `scene`, unknown
//! parameters and values outside their domain (negative mass, `nan`, `inf`), values of the
//! wrong type, and the `[run]` table as a whole (step or tolerance against the integrator,
//! step against the horizon) through [`RunOptions::resolve`]. Each error is a
//! [`SceneFileError`] carrying a [`Location`] (`file:line:column` of the offending key) and the
//! key's name.

use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::body_table::{self, RawBody};
use crate::error::SceneError;
use crate::params::Params;
use crate::scene::{RunOptions, Scene, StepControl};
use crate::scenes;
pub use crate::toml_file::Location;
use crate::toml_file::{self, TomlFileError, describe};

/// What can be wrong with a scene file. Every variant carries the location of the offending
/// key, but a file that cannot be read or names no scene ([`TomlFileError`]).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneFileError {
    /// Not readable, not TOML, an unknown key, a value of the wrong type, no scene named.
    #[error(transparent)]
    File(#[from] TomlFileError),
    /// The scene, a parameter or a run option was rejected by the scene: unknown scene,
    /// unknown parameter, value outside its domain, unsupported integrator, invalid step,
    /// tolerance, horizon or cadence.
    #[error("{at}: `{key}`: {error}")]
    Scene {
        /// Where the key is.
        at: Location,
        /// The dotted key (`scene`, `parameters.M`, `run.dt`).
        key: String,
        /// What the scene said (part of this error's message, so not a `source`; boxed to
        /// keep the error small).
        error: Box<SceneError>,
    },
    /// A value that must be a number is something else.
    #[error("{at}: `{key}` must be a number, found {found}")]
    NotANumber {
        /// Where the key is.
        at: Location,
        /// The dotted key.
        key: String,
        /// What was found, described (`a string "heavy"`, `an array`).
        found: String,
    },
    /// `run.every` is not a whole number of at least 1.
    #[error("{at}: `run.every` must be a whole number >= 1, found {found}")]
    InvalidEvery {
        /// Where the key is.
        at: Location,
        /// The value found, as written.
        found: String,
    },
    /// `[run]` gives both `dt` and `tol`.
    #[error(
        "{at}: `run.dt` and `run.tol` are both given; a run has a fixed step or a tolerance, \
         not both"
    )]
    StepAndTolerance {
        /// Where the second of the two is.
        at: Location,
    },
    /// `[run]` chooses the rows two ways (`every`, `at`, `output_dt`: one of them at most).
    #[error(
        "{at}: `run.{second}` and `run.{first}` both choose which rows are written; give one \
         of them"
    )]
    RowsTwoWays {
        /// Where the second of the two is.
        at: Location,
        /// The key written first.
        first: &'static str,
        /// The key written second.
        second: &'static str,
    },
    /// A `[body]` table that cannot be read or gives no usable body: a mesh that is not a
    /// closed surface, a negative mass, no points, a zero principal moment.
    #[error("{at}: `{key}`: {message}")]
    Body {
        /// Where the key is.
        at: Location,
        /// The dotted key (`body.mesh`, `body.shape[1].mass`, `body`).
        key: String,
        /// What is wrong.
        message: String,
    },
    /// A `[body]` table in a file whose scene does not take a body from a scene file.
    #[error(
        "{at}: `body`: scene `{scene}` does not take its body from a scene file; a [body] \
         table is for the rigid-body scenes free-body, dzhanibekov and heavy-top"
    )]
    BodyNotApplicable {
        /// Where the table is.
        at: Location,
        /// The scene named by the file.
        scene: String,
    },
}

impl SceneFileError {
    /// The location of the offending key, when the error has one.
    #[must_use]
    pub fn location(&self) -> Option<&Location> {
        match self {
            SceneFileError::File(e) => e.location(),
            SceneFileError::Scene { at, .. }
            | SceneFileError::NotANumber { at, .. }
            | SceneFileError::InvalidEvery { at, .. }
            | SceneFileError::StepAndTolerance { at }
            | SceneFileError::RowsTwoWays { at, .. }
            | SceneFileError::Body { at, .. }
            | SceneFileError::BodyNotApplicable { at, .. } => Some(at),
        }
    }
}

/// The file as TOML gives it, before validation.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    scene: Option<Spanned<String>>,
    parameters: Option<BTreeMap<Spanned<String>, Spanned<toml::Value>>>,
    run: Option<Spanned<RawRun>>,
    body: Option<Spanned<RawBody>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRun {
    integrator: Option<Spanned<String>>,
    dt: Option<Spanned<toml::Value>>,
    tol: Option<Spanned<toml::Value>>,
    t_end: Option<Spanned<toml::Value>>,
    every: Option<Spanned<toml::Value>>,
    at: Option<Spanned<Vec<Spanned<toml::Value>>>>,
    output_dt: Option<Spanned<toml::Value>>,
}

/// A validated scene file: the scene it names, its parameters (the scene's defaults with the
/// file's values set) and its run defaults.
#[derive(Clone)]
pub struct SceneFile {
    /// The file's path as given, or the name given to parsed text.
    pub origin: String,
    /// The built-in scene (model kind) the file names.
    pub scene: &'static dyn Scene,
    /// Parameter values: the scene's defaults, overridden by `[parameters]`.
    pub params: Params,
    /// Run defaults from `[run]`; `None` fields take the scene's defaults.
    pub run: RunOptions,
    /// For a scene with a `[body]` table: the frame its rows report (the body's own frame), in
    /// words, for the run's records; `None` for the built-in bodies.
    pub frame: Option<String>,
}

impl fmt::Debug for SceneFile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SceneFile")
            .field("origin", &self.origin)
            .field("scene", &self.scene.info().name)
            .field("params", &self.params)
            .field("run", &self.run)
            .finish()
    }
}

/// Parsing state: the text and its origin, to place spans.
struct Source<'a> {
    origin: &'a str,
    text: &'a str,
}

impl Source<'_> {
    fn at(&self, span: &Range<usize>) -> Location {
        Location::at(self.origin, self.text, span.start)
    }

    /// A number: a float, or an integer exactly representable as one.
    fn number(
        &self,
        key: &str,
        key_span: &Range<usize>,
        value: &Spanned<toml::Value>,
    ) -> Result<f64, SceneFileError> {
        toml_file::number_or_angle(value.get_ref()).map_err(|found| SceneFileError::NotANumber {
            at: self.at(key_span),
            key: key.to_string(),
            found,
        })
    }
}

impl SceneFile {
    /// Reads and validates the scene file at `path`.
    ///
    /// # Errors
    /// [`TomlFileError::Read`] if the file cannot be read, otherwise as [`SceneFile::parse`].
    pub fn load(path: &Path) -> Result<Self, SceneFileError> {
        let text = toml_file::read(path, "scene")?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parses and validates scene-file text; `origin` names it in error messages (a path).
    ///
    /// # Errors
    /// A [`SceneFileError`] naming the key and its line: TOML syntax, unknown keys, wrong
    /// types, a missing or unknown scene, unknown parameters, values outside their domain,
    /// invalid run options, a `[body]` table for a scene that takes none.
    pub fn parse(text: &str, origin: &str) -> Result<Self, SceneFileError> {
        let src = Source { origin, text };
        let raw: RawFile = toml_file::parse(text, origin)?;

        let Some(scene_name) = raw.scene else {
            return Err(TomlFileError::missing_scene(origin).into());
        };
        let scene = scenes::find(scene_name.get_ref()).map_err(|error| SceneFileError::Scene {
            at: src.at(&scene_name.span()),
            key: "scene".to_string(),
            error: Box::new(error),
        })?;
        let info = scene.info();

        let (scene, mut params, frame) = match &raw.body {
            None => (scene, info.default_params(), None),
            Some(table) => {
                let Some(body_scene) = scenes::body::for_scene(info.name) else {
                    return Err(SceneFileError::BodyNotApplicable {
                        at: src.at(&table.span()),
                        scene: info.name.to_string(),
                    });
                };
                let place = body_table::Place { origin, text };
                let body = body_table::read(&place, table, body_scene.0).map_err(|e| {
                    SceneFileError::Body {
                        at: e.at,
                        key: e.key,
                        message: e.message,
                    }
                })?;
                let mut params = body_scene.info().default_params();
                body_table::set_params(&body, &mut params).map_err(|message| {
                    SceneFileError::Body {
                        at: src.at(&table.span()),
                        key: "body".to_string(),
                        message,
                    }
                })?;
                let frame = format!(
                    "the [body] table's own frame ({}): orientation qw..qz of that frame, \
                     omega_x..omega_z components in it; the model runs in the principal frame",
                    table_sources(table.get_ref())
                );
                let scene: &'static dyn Scene = body_scene;
                (scene, params, Some(frame))
            }
        };
        // Parameters, in the order they appear in the file.
        let mut entries: Vec<_> = raw.parameters.unwrap_or_default().into_iter().collect();
        entries.sort_by_key(|(k, _)| k.span().start);
        for (name, value) in &entries {
            let key = format!("parameters.{}", name.get_ref());
            if frame.is_some() && scenes::body::BODY_PARAMETERS.contains(&name.get_ref().as_str()) {
                return Err(SceneFileError::Body {
                    at: src.at(&name.span()),
                    key,
                    message: "is computed from the [body] table; change the body instead".into(),
                });
            }
            let x = src.number(&key, &name.span(), value)?;
            params
                .set(name.get_ref(), x)
                .map_err(|error| SceneFileError::Scene {
                    at: src.at(&name.span()),
                    key,
                    error: Box::new(error),
                })?;
        }

        let run = match raw.run {
            Some(run) => src.run_options(scene, run)?,
            None => RunOptions::default(),
        };

        Ok(SceneFile {
            origin: origin.to_string(),
            scene,
            params,
            run,
            frame,
        })
    }
}

/// The sources a `[body]` table names, for the description of its frame.
fn table_sources(body: &body_table::RawBody) -> String {
    body.describe()
}

impl Source<'_> {
    /// Builds the `[run]` options and validates them as a whole against the scene.
    fn run_options(
        &self,
        scene: &dyn Scene,
        run: Spanned<RawRun>,
    ) -> Result<RunOptions, SceneFileError> {
        let table_span = run.span();
        let run = run.into_inner();
        let number = |key: &str, value: &Option<Spanned<toml::Value>>| {
            value
                .as_ref()
                .map(|v| self.number(&format!("run.{key}"), &v.span(), v))
                .transpose()
        };
        let dt = number("dt", &run.dt)?;
        let tol = number("tol", &run.tol)?;
        let t_end = number("t_end", &run.t_end)?;
        let step = match (dt, tol) {
            (Some(_), Some(_)) => {
                let later = match (&run.dt, &run.tol) {
                    (Some(a), Some(b)) => a.span().start.max(b.span().start),
                    _ => table_span.start,
                };
                return Err(SceneFileError::StepAndTolerance {
                    at: Location::at(self.origin, self.text, later),
                });
            }
            (Some(h), None) => Some(StepControl::Fixed(h)),
            (None, Some(tol)) => Some(StepControl::Tolerance(tol)),
            (None, None) => None,
        };
        let every = match &run.every {
            None => None,
            Some(v) => match v.get_ref() {
                toml::Value::Integer(n) if *n >= 1 => Some(n.unsigned_abs()),
                other => {
                    return Err(SceneFileError::InvalidEvery {
                        at: self.at(&v.span()),
                        found: describe(other),
                    });
                }
            },
        };
        // As on the command line, the rows are chosen one way: every n-th step, at given times,
        // or every output_dt.
        let mut row_keys: Vec<(&'static str, std::ops::Range<usize>)> = [
            ("every", run.every.as_ref().map(Spanned::span)),
            ("at", run.at.as_ref().map(Spanned::span)),
            ("output_dt", run.output_dt.as_ref().map(Spanned::span)),
        ]
        .into_iter()
        .filter_map(|(k, s)| s.map(|s| (k, s)))
        .collect();
        row_keys.sort_by_key(|(_, s)| s.start);
        if let [(first, _), (second, span), ..] = row_keys.as_slice() {
            return Err(SceneFileError::RowsTwoWays {
                at: self.at(span),
                first,
                second,
            });
        }
        let output_dt = number("output_dt", &run.output_dt)?;
        let at = match &run.at {
            None => None,
            Some(list) => Some(
                list.get_ref()
                    .iter()
                    .map(|v| self.number("run.at", &v.span(), v))
                    .collect::<Result<Vec<f64>, _>>()?,
            ),
        };
        let options = RunOptions {
            integrator: run.integrator.as_ref().map(|s| s.get_ref().clone()),
            step,
            t_end,
            every,
            at,
            output_dt,
            max_steps: None,
            cancel: None,
            observe: crate::scene::Observe::EveryStep,
        };
        // Validate the table as a whole and point at the key the scene complains about.
        if let Err(error) = options.resolve(scene.info()) {
            let (key, span) = match &error {
                SceneError::UnsupportedIntegrator { .. } => {
                    ("integrator", run.integrator.as_ref().map(Spanned::span))
                }
                SceneError::InvalidOption { option, .. } => {
                    let span = match *option {
                        "dt" => run.dt.as_ref().map(Spanned::span),
                        "tol" => run.tol.as_ref().map(Spanned::span),
                        "t_end" => run.t_end.as_ref().map(Spanned::span),
                        "every" => run.every.as_ref().map(Spanned::span),
                        "at" => run.at.as_ref().map(Spanned::span),
                        "output_dt" => run.output_dt.as_ref().map(Spanned::span),
                        _ => None,
                    };
                    (*option, span)
                }
                _ => ("run", None),
            };
            let key = if key == "run" {
                key.to_string()
            } else {
                format!("run.{key}")
            };
            return Err(SceneFileError::Scene {
                at: self.at(&span.unwrap_or(table_span)),
                key,
                error: Box::new(error),
            });
        }
        Ok(options)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<SceneFile, SceneFileError> {
        SceneFile::parse(text, "test.toml")
    }

    fn line_of(e: &SceneFileError) -> usize {
        e.location()
            .and_then(Location::line)
            .unwrap_or_else(|| panic!("no line in {e}"))
    }

    #[test]
    fn a_complete_file_sets_parameters_and_run_options() {
        let f = parse(
            "scene = \"spinning-hoop\"\n\
             [parameters]\n\
             M = 1\n\
             a = 0.4\n\
             omega0 = 5.0\n\
             [run]\n\
             integrator = \"gauss6\"\n\
             dt = 0.001\n\
             t_end = 2\n\
             every = 10\n",
        )
        .unwrap();
        assert_eq!(f.scene.info().name, "spinning-hoop");
        assert_eq!(f.params.get("M").unwrap(), 1.0);
        assert_eq!(f.params.get("a").unwrap(), 0.4);
        assert_eq!(f.params.get("omega0").unwrap(), 5.0);
        // Untouched parameters keep the scene's defaults.
        let defaults = f.scene.info().default_params();
        assert_eq!(f.params.get("g").unwrap(), defaults.get("g").unwrap());
        assert_eq!(
            f.run,
            RunOptions {
                integrator: Some("gauss6".into()),
                step: Some(StepControl::Fixed(0.001)),
                t_end: Some(2.0),
                every: Some(10),
                at: None,
                output_dt: None,
                max_steps: None,
                cancel: None,
                observe: crate::scene::Observe::EveryStep,
            }
        );
    }

    #[test]
    fn a_file_with_only_the_scene_takes_every_default() {
        let f = parse("scene = \"driven-hoop\"\n").unwrap();
        assert_eq!(f.params, f.scene.info().default_params());
        assert_eq!(f.run, RunOptions::default());
    }

    #[test]
    fn malformed_toml_names_its_line() {
        let e = parse("scene = \"driven-hoop\"\n[parameters]\nM = = 1\n").unwrap_err();
        assert!(
            matches!(e, SceneFileError::File(TomlFileError::Syntax { .. })),
            "{e}"
        );
        assert_eq!(line_of(&e), 3, "{e}");
        assert!(e.to_string().starts_with("test.toml:3:"), "{e}");
        assert!(e.to_string().contains("M = = 1"), "excerpt missing: {e}");
    }

    #[test]
    fn unknown_keys_are_errors_with_their_line() {
        let e = parse("scene = \"driven-hoop\"\n\nspeed = 3\n").unwrap_err();
        assert_eq!(line_of(&e), 3, "{e}");
        assert!(e.to_string().contains("speed"), "{e}");
        let e = parse("scene = \"driven-hoop\"\n[run]\nt_end = 1\nstep = 0.1\n").unwrap_err();
        assert_eq!(line_of(&e), 4, "{e}");
        assert!(e.to_string().contains("step"), "{e}");
    }

    #[test]
    fn missing_and_unknown_scenes_are_errors() {
        let e = parse("[parameters]\nM = 1\n").unwrap_err();
        assert!(
            matches!(e, SceneFileError::File(TomlFileError::MissingScene { .. })),
            "{e}"
        );
        assert!(e.to_string().contains("driven-hoop"), "{e}");
        let e = parse("# a comment\nscene = \"warp-drive\"\n").unwrap_err();
        assert!(
            matches!(&e, SceneFileError::Scene { error, .. }
                if matches!(**error, SceneError::UnknownScene { .. })),
            "{e}"
        );
        assert_eq!(line_of(&e), 2);
        assert!(e.to_string().contains("warp-drive"), "{e}");
    }

    #[test]
    fn unknown_parameters_name_the_key_the_line_and_the_known_ones() {
        let e = parse("scene = \"driven-hoop\"\n[parameters]\nM = 1\nmass = 2\n").unwrap_err();
        assert_eq!(line_of(&e), 4, "{e}");
        let msg = e.to_string();
        assert!(msg.contains("parameters.mass"), "{msg}");
        assert!(msg.contains("omega"), "known names missing: {msg}");
    }

    #[test]
    fn non_physical_and_non_finite_values_are_rejected() {
        for (value, what) in [
            ("-1.0", "positive"),
            ("0", "positive"),
            ("inf", "finite"),
            ("nan", "finite"),
            ("-inf", "finite"),
        ] {
            let text = format!("scene = \"driven-hoop\"\n[parameters]\n\nM = {value}\n");
            let e = parse(&text).unwrap_err();
            assert_eq!(line_of(&e), 4, "{e}");
            assert!(e.to_string().contains("parameters.M"), "{e}");
            assert!(e.to_string().contains(what), "{value}: {e}");
        }
        let e = parse("scene = \"driven-hoop\"\n[parameters]\nomega = nan\n").unwrap_err();
        assert!(e.to_string().contains("must be finite"), "{e}");
    }

    #[test]
    fn parameters_take_angle_expressions_as_strings_like_set() {
        let file =
            parse("scene = \"free-hoop\"\n[parameters]\ntheta0 = \"pi/2\"\nalpha0 = \"-3pi/4\"\n")
                .unwrap();
        assert_eq!(
            file.params.get("theta0").unwrap(),
            std::f64::consts::PI / 2.0
        );
        assert_eq!(
            file.params.get("alpha0").unwrap(),
            -3.0 * std::f64::consts::PI / 4.0
        );
        let e = parse("scene = \"free-hoop\"\n[parameters]\n\ntheta0 = \"2**pi\"\n").unwrap_err();
        assert!(matches!(e, SceneFileError::NotANumber { .. }), "{e}");
        assert_eq!(line_of(&e), 4, "{e}");
        let message = e.to_string();
        assert!(message.contains("parameters.theta0"), "{message}");
        assert!(message.contains("2**pi"), "{message}");
        assert!(message.contains("angle expressions such as"), "{message}");
        // The value still goes through the parameter's domain check.
        let e = parse("scene = \"free-hoop\"\n[parameters]\na = \"-pi\"\n").unwrap_err();
        assert!(e.to_string().contains("parameters.a"), "{e}");
    }

    #[test]
    fn values_of_the_wrong_type_are_rejected() {
        let e = parse("scene = \"driven-hoop\"\n[parameters]\nM = \"heavy\"\n").unwrap_err();
        assert!(matches!(e, SceneFileError::NotANumber { .. }), "{e}");
        assert_eq!(line_of(&e), 3);
        assert!(e.to_string().contains("heavy"), "{e}");
        let e = parse("scene = 3\n").unwrap_err();
        assert!(
            matches!(e, SceneFileError::File(TomlFileError::Syntax { .. })),
            "{e}"
        );
        assert_eq!(line_of(&e), 1);
        let e = parse("scene = \"driven-hoop\"\n[parameters]\nM = 9007199254740993\n").unwrap_err();
        assert!(matches!(e, SceneFileError::NotANumber { .. }), "{e}");
    }

    #[test]
    fn run_options_are_validated_with_the_line_of_the_key() {
        let cases = [
            ("dt = 0.0", "run.dt"),
            ("dt = -0.01", "run.dt"),
            ("dt = nan", "run.dt"),
            ("t_end = 1.0\ndt = 2.0", "run.dt"),
            ("tol = 0.0\nintegrator = \"dp5\"", "run.tol"),
            ("integrator = \"rk4\"\ntol = 1e-8", "run.tol"),
            ("integrator = \"nope\"", "run.integrator"),
            ("t_end = -1", "run.t_end"),
            ("every = 0", "every"),
            ("every = 2.5", "every"),
            ("dt = 0.01\ntol = 1e-9", "run.dt"),
            ("dt = \"small\"", "run.dt"),
        ];
        for (run, key) in cases {
            let text = format!("scene = \"driven-hoop\"\n[run]\n{run}\n");
            let e = parse(&text).unwrap_err();
            let msg = e.to_string();
            assert!(msg.contains(key), "{run:?}: {msg}");
            let line = line_of(&e);
            assert!((3..=4).contains(&line), "{run:?}: line {line}: {msg}");
        }
        // The key the scene complains about is the one located: `dt` on line 4.
        let e = parse("scene = \"driven-hoop\"\n[run]\nt_end = 1.0\ndt = 2.0\n").unwrap_err();
        assert_eq!(line_of(&e), 4, "{e}");
    }

    #[test]
    fn a_body_table_is_reserved_for_rigid_body_scenes() {
        let e = parse("scene = \"driven-hoop\"\n[body]\nmesh = \"t-handle.obj\"\n").unwrap_err();
        assert!(matches!(e, SceneFileError::BodyNotApplicable { .. }), "{e}");
        assert!(e.to_string().contains("driven-hoop"), "{e}");
    }

    #[test]
    fn locations_count_lines_and_characters() {
        let text = "a\nβγ = 1\n";
        let at = Location::at("f", text, text.find('=').unwrap());
        assert_eq!(at.position, Some((2, 4)));
        assert_eq!(at.to_string(), "f:2:4");
    }
}
