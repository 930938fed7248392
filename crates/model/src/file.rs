//! Model files (TOML): what a model declares, read and checked before any work, into a
//! [`Model`] whose equations are nodes of one expression graph.
//!
//! # Format
//!
//! ```toml
//! [model]
//! name = "driven-hoop"                       # how `tumble models` and the rows name it
//! summary = "bead on a vertical hoop spun at constant omega about the vertical"
//!
//! [parameters]                               # in this order; `--set NAME=VALUE` changes one
//! M = { default = 1.0, unit = "kg", domain = "positive", description = "hoop mass" }
//! omega = 4.43                               # short form: a default, any finite value
//!
//! [coordinates]                              # generalized coordinates, in state order
//! alpha = { initial = "alpha0", rate = "0" } # initial value and rate: expressions of parameters
//!
//! [definitions]                              # named expressions, each may use the ones before
//! spin = "omega*t"                           # a prescribed angle (a driven hoop)
//!
//! [frames.hoop]                              # an orientation (body → model frame)
//! euler = "zyz"                              # any of the 12 conventions, intrinsic by default
//! angles = ["spin", "pi/2", "0"]             # ... or: rotations = [["z", "phi"], ["x", "theta"]]
//! parent = "ring"                            # optional: turns with another frame (gimbals),
//!                                            # which may be an orientation on SO(3)
//! origin = ["0", "0", "-l"]                  # optional: where it sits, in the parent's axes
//!                                            # from the parent's origin (the model frame's)
//!
//! [frames.body]                              # an orientation integrated on SO(3) (up to 4
//! orientation = "so3"                        # frames): R and ω are state, no gimbal lock
//! angles = ["0", "theta0", "0"]              # the initial orientation (or `rotations`)
//! omega = ["0", "0", "spin0"]                # the initial body angular velocity
//! # expressions read body_R11 … body_R33, and body_omega_x … where rates are in scope
//!
//! [rotating_frame]                           # optional: the model frame turns (the Earth)
//! omega = ["0", "W*sin(colat)", "W*cos(colat)"]
//!
//! [bodies.hoop]                              # a rigid body
//! frame = "hoop"                             # its orientation (none: it does not turn)
//! origin = ["0", "0", "0"]                   # in the model frame, added to its frame's
//! mass = "M"                                 # mass, centre of mass in its frame, inertia about
//! com = ["0", "0", "0"]                      # the centre of mass: 3 principal moments or
//! inertia = ["M*a^2/2", "M*a^2/2", "M*a^2"]  # 6 entries [xx, yy, zz, xy, xz, yz]
//! # geometry = { shape = [{ shape = "hoop:1", mass = 1 }] }  # ... or the [body] vocabulary
//!
//! [points.bead]                              # a point mass
//! mass = "m"
//! frame = "hoop"                             # its position is in this frame (none: the model's)
//! position = ["a*cos(alpha)", "a*sin(alpha)", "0"]
//!
//! [lagrangian]
//! gravity = ["0", "0", "-g"]                 # uniform gravity on every mass (model frame)
//! potential = "0"                            # further potential energy V
//! kinetic = "0"                              # further kinetic energy (may use rates alpha_dot)
//!
//! [outputs]                                  # extra columns (coordinates, rates, t, parameters)
//! height = "-a*cos(alpha)"
//!
//! [run]                                      # defaults of a run
//! integrator = "gauss8"
//! dt = 0.01
//! t_end = 10.0
//! ```
//!
//! Expressions are strings in the language of [`crate::expr::parse`] (numbers are accepted as
//! they are). Names in scope: the parameters; in positions, angles, definitions and the
//! potential also `t`, the coordinates and the definitions; in `lagrangian.kinetic` and `[outputs]` also the
//! rates `NAME_dot`. Every error names the file, line and column, the key, and for an
//! expression the place in it with a caret.

use std::collections::HashMap;
use std::path::Path;

use toml::Spanned;
use tumble_scenarios::toml_file::{self, Location};

mod decl;
mod drawn;
mod error;
mod frames;
mod masses;
mod params;
mod raw;
mod reader;

pub use decl::{Orientation, ParamDef, RunDefaults};
pub use drawn::{DrawnBody, DrawnPoint, ModelDrawing};
pub use error::ModelFileError;
use frames::{Placed, frame_names, read_links, so3_frame};
use masses::{Energy, mass_properties};
use params::read_parameter;

use raw::{RawFile, ordered};
use reader::{Names, Src, check_name, run_defaults};

use crate::expr::{Graph, Id};
use crate::mechanics::{Algebra, Chain, Equations, Layout, V3, equations};
use crate::units;

/// The largest model file read, in bytes.
pub const MAX_FILE_BYTES: usize = 1 << 20;
/// The most generalized coordinates a model may have.
pub const MAX_COORDINATES: usize = 6;
/// The most frames integrated on SO(3) a model may have (each adds twelve numbers to the
/// state: its rotation matrix and its body angular velocity).
pub const MAX_SO3_FRAMES: usize = 4;
/// The most scalar coordinates beside orientations on SO(3).
pub const MAX_COORDINATES_WITH_SO3: usize = 3;
/// The most nodes a model's expressions and derivatives may grow to.
pub const MAX_NODES: usize = 200_000;

/// A model read from a file: its declarations and its equations on one graph.
#[derive(Debug, Clone)]
pub struct Model {
    /// Name.
    pub name: String,
    /// One line: what it is.
    pub summary: String,
    /// Parameters, in order.
    pub params: Vec<ParamDef>,
    /// Scalar coordinates, in state order.
    pub coordinates: Vec<String>,
    /// Orientations integrated on SO(3), in state order after the scalar coordinates.
    pub orientations: Vec<Orientation>,
    /// The graph.
    pub graph: Graph,
    /// The input layout.
    pub layout: Layout,
    /// Equations of motion, energy, momenta.
    pub equations: Equations,
    /// Initial coordinates and rates (expressions of the parameters).
    pub initial: Vec<Id>,
    /// Initial rates.
    pub initial_rates: Vec<Id>,
    /// Extra output columns.
    pub outputs: Vec<(String, Id)>,
    /// Run defaults.
    pub run: RunDefaults,
    /// Where the model came from (a path, or a name given to text).
    pub origin: String,
    /// Its bodies and point masses, to draw them.
    pub drawing: ModelDrawing,
}

impl Model {
    /// Reads the model file at `path`.
    ///
    /// # Errors
    /// As [`Model::parse`]; an unreadable file, or one larger than [`MAX_FILE_BYTES`].
    pub fn load(path: &Path) -> Result<Self, ModelFileError> {
        Self::parse(&read_text(path)?, &path.display().to_string())
    }

    /// Parses model text; `origin` names it in messages and locates the files a `geometry`
    /// table names.
    ///
    /// # Errors
    /// A [`ModelFileError`] naming the key and its place: TOML syntax, unknown keys, an
    /// expression that does not parse, an unknown name (listing those in scope), a duplicate
    /// name, a frame whose parent is unknown or later, a body without mass properties, too many
    /// coordinates, a model too large.
    pub fn parse(text: &str, origin: &str) -> Result<Self, ModelFileError> {
        let src = Src {
            origin,
            text,
            read: std::cell::RefCell::new(Vec::new()),
        };
        if text.len() > MAX_FILE_BYTES {
            return Err(src.invalid(
                &(0..0),
                "model",
                format!(
                    "the text is {} bytes, more than the {MAX_FILE_BYTES} a model may have",
                    text.len()
                ),
            ));
        }
        let raw: RawFile = toml_file::parse(text, origin)?;
        let mut graph = Graph::with_limit(MAX_NODES);
        let mut taken: HashMap<String, String> = HashMap::new();
        let mut claim =
            |src: &Src<'_>, key: &str, name: &Spanned<String>| -> Result<(), ModelFileError> {
                check_name(src, key, name)?;
                if let Some(previous) = taken.insert(name.get_ref().clone(), key.to_string()) {
                    return Err(src.invalid(
                        &name.span(),
                        key,
                        format!("`{}` is already declared as `{previous}`", name.get_ref()),
                    ));
                }
                Ok(())
            };

        // Parameters.
        let mut params = Vec::new();
        for (name, value) in ordered(raw.parameters) {
            let key = format!("parameters.{}", name.get_ref());
            claim(&src, &key, &name)?;
            let def = read_parameter(&src, &key, &name, &value)?;
            if !def.domain.contains(def.default) {
                return Err(src.invalid(
                    &value.span(),
                    &key,
                    format!("the default {} {}", def.default, def.domain.requirement()),
                ));
            }
            params.push(def);
        }

        // Orientations on SO(3): counted first, their inputs come before the rates.
        let mut so3_frames: Vec<(Spanned<String>, Spanned<String>)> = raw
            .frames
            .iter()
            .flatten()
            .filter_map(|(name, f)| f.get_ref().orientation.clone().map(|o| (name.clone(), o)))
            .collect();
        so3_frames.sort_by_key(|(name, _)| name.span().start);
        for (name, o) in &so3_frames {
            if o.get_ref() != "so3" {
                return Err(src.invalid(
                    &o.span(),
                    &format!("frames.{}.orientation", name.get_ref()),
                    format!(
                        "unknown orientation {:?}; write \"so3\" (integrated on the rotation group), or leave it out for a frame given by `angles` or `rotations`",
                        o.get_ref()
                    ),
                ));
            }
        }
        if so3_frames.len() > MAX_SO3_FRAMES {
            let names: Vec<_> = so3_frames
                .iter()
                .map(|(n, _)| format!("`{}`", n.get_ref()))
                .collect();
            return Err(src.invalid(&so3_frames[MAX_SO3_FRAMES].0.span(), "frames", format!("{} frames with orientation = \"so3\" ({}): a model may have at most {MAX_SO3_FRAMES}; give the others by `angles` or `rotations`", names.len(), names.join(", "))));
        }

        // Coordinates.
        let coordinates = ordered(raw.coordinates);
        let max_coordinates = if so3_frames.is_empty() {
            MAX_COORDINATES
        } else {
            MAX_COORDINATES_WITH_SO3
        };
        if coordinates.is_empty() && so3_frames.is_empty() {
            return Err(src.invalid(
                &raw.model.span(),
                "coordinates",
                "a model needs at least one coordinate: [coordinates] NAME = { initial = \"...\" }",
            ));
        }
        if coordinates.len() > max_coordinates {
            return Err(src.invalid(
                &coordinates[max_coordinates].0.span(),
                "coordinates",
                format!(
                    "{} coordinates: a model may have at most {MAX_COORDINATES}, or \
                     {MAX_COORDINATES_WITH_SO3} beside an orientation on SO(3) (or several)",
                    coordinates.len()
                ),
            ));
        }
        let layout = Layout {
            n: coordinates.len(),
            so3: so3_frames.len(),
        };
        let mut scope = Names::new();
        for (j, p) in params.iter().enumerate() {
            let id = graph.input(layout.param(j));
            scope.insert(&p.name, id);
        }
        let param_scope = Names {
            map: scope.map.clone(),
            order: scope.order.clone(),
        };
        let mut initial = Vec::new();
        let mut initial_rates = Vec::new();
        let mut names = Vec::new();
        for (i, (name, c)) in coordinates.iter().enumerate() {
            let key = format!("coordinates.{}", name.get_ref());
            claim(&src, &key, name)?;
            let rate_name = Spanned::new(name.span(), format!("{}_dot", name.get_ref()));
            claim(&src, &key, &rate_name)?;
            let c = c.get_ref();
            initial.push(src.expr(
                &format!("{key}.initial"),
                &c.initial,
                &mut graph,
                &param_scope,
            )?);
            initial_rates.push(match &c.rate {
                Some(r) => src.expr(&format!("{key}.rate"), r, &mut graph, &param_scope)?,
                None => graph.constant(0.0),
            });
            names.push(name.get_ref().clone());
            let q = graph.input(layout.q(i));
            scope.insert(name.get_ref(), q);
        }
        let t = graph.input(Layout::T);
        scope.insert("t", t);

        // Definitions.
        for (name, value) in ordered(raw.definitions) {
            let key = format!("definitions.{}", name.get_ref());
            claim(&src, &key, &name)?;
            let id = src.expr(&key, &value, &mut graph, &scope)?;
            scope.insert(name.get_ref(), id);
        }

        // Rotating frame.
        let mut alg_frame_omega: Option<V3> = None;
        if let Some(r) = &raw.rotating_frame {
            let w = src.vector(
                "rotating_frame.omega",
                &r.get_ref().omega,
                &mut graph,
                &scope,
            )?;
            alg_frame_omega = Some(w);
        }

        // Frames.
        let mut frames: HashMap<String, Placed> = HashMap::new();
        // Each frame's rotations from its root (the model frame, or the orientation on SO(3)
        // that carries it).
        let mut chains: HashMap<String, Chain> = HashMap::new();
        let mut orientations: Vec<Orientation> = Vec::new();
        let zero = graph.constant(0.0);
        for (name, f) in ordered(raw.frames) {
            let key = format!("frames.{}", name.get_ref());
            let f = f.get_ref();
            let offset = match &f.origin {
                Some(o) => src.vector(&format!("{key}.origin"), o, &mut graph, &scope)?,
                None => [zero; 3],
            };
            if f.orientation.is_some() {
                let (r, w) = so3_frame(
                    &src,
                    &key,
                    f,
                    &mut graph,
                    &param_scope,
                    &mut orientations,
                    name.get_ref(),
                    layout,
                )?;
                let mut alg = Algebra { g: &mut graph };
                frames.insert(
                    name.get_ref().clone(),
                    Placed::on_so3(&mut alg, r, w, offset),
                );
                continue;
            }
            if let Some(w) = &f.omega {
                return Err(src.invalid(&w.span(), &format!("{key}.omega"), "is the initial angular velocity of an orientation on SO(3); with `orientation = \"so3\"` it is read, otherwise the angular velocity follows from the angles' rates"));
            }
            let parent = match &f.parent {
                None => None,
                Some(p) => Some(frames.get(p.get_ref()).copied().ok_or_else(|| {
                    src.invalid(
                        &p.span(),
                        &format!("{key}.parent"),
                        format!(
                            "no frame `{}` declared before this one; frames declared before: {}",
                            p.get_ref(),
                            frame_names(&frames)
                        ),
                    )
                })?),
            };
            // A frame carried by an orientation on SO(3) starts its chain there.
            let mut links = f
                .parent
                .as_ref()
                .and_then(|p| chains.get(p.get_ref()))
                .map(|c| c.links.clone())
                .unwrap_or_default();
            match read_links(&src, &key, f, &mut graph, &scope)? {
                Some(own) => links.extend(own),
                None => {
                    return Err(src.invalid(&name.span(), &key, "needs `angles` (three Euler angles, with `euler` naming the convention, ZYZ by default) or `rotations` ([[axis, angle], ...]), one of them"));
                }
            }
            let chain = Chain { links };
            let mut alg = Algebra { g: &mut graph };
            let placed = Placed::chained(&mut alg, parent.as_ref(), &chain, offset, layout);
            frames.insert(name.get_ref().clone(), placed);
            chains.insert(name.get_ref().clone(), chain);
        }
        // The rotation matrix and angular velocity of each orientation on SO(3), by name:
        // `NAME_R13` (row 1, column 3) in positions, the potential and outputs,
        // `NAME_omega_x` where rates are in scope.
        let mut so3_rates = Vec::new();
        for (f, o) in orientations.iter().enumerate() {
            let key = format!("frames.{}", o.name);
            for a in 0..3 {
                for b in 0..3 {
                    let entry = format!("{}_R{}{}", o.name, a + 1, b + 1);
                    claim(&src, &key, &Spanned::new(0..0, entry.clone()))?;
                    let id = graph.input(layout.rot(f, a, b));
                    scope.insert(&entry, id);
                }
            }
            for (c, axis) in ["x", "y", "z"].into_iter().enumerate() {
                let rate = format!("{}_omega_{axis}", o.name);
                claim(&src, &key, &Spanned::new(0..0, rate.clone()))?;
                so3_rates.push((rate, graph.input(layout.omega(f, c))));
            }
        }
        let frame_of = |src: &Src<'_>,
                        key: &str,
                        f: &Option<Spanned<String>>|
         -> Result<Option<Placed>, ModelFileError> {
            match f {
                None => Ok(None),
                Some(name) => frames
                    .get(name.get_ref())
                    .copied()
                    .map(Some)
                    .ok_or_else(|| {
                        src.invalid(
                            &name.span(),
                            key,
                            format!(
                                "no frame `{}`; frames: {}",
                                name.get_ref(),
                                frame_names(&frames)
                            ),
                        )
                    }),
            }
        };

        // Kinetic and potential energy.
        let extra = raw.lagrangian.unwrap_or_default();
        let gravity = match &extra.gravity {
            Some(g) => Some(src.vector("lagrangian.gravity", g, &mut graph, &scope)?),
            None => None,
        };
        let mut energy = Energy {
            kinetic: Vec::new(),
            potential: Vec::new(),
            gravity,
            frame_omega: alg_frame_omega,
            layout,
        };
        let mut drawing = ModelDrawing::default();
        for (name, b) in ordered(raw.bodies) {
            let key = format!("bodies.{}", name.get_ref());
            let b = b.get_ref();
            let frame = frame_of(&src, &format!("{key}.frame"), &b.frame)?;
            let body_origin = match &b.origin {
                Some(o) => src.vector(&format!("{key}.origin"), o, &mut graph, &scope)?,
                None => [zero; 3],
            };
            let (mass, com, inertia, parts) =
                mass_properties(&src, &key, &name, b, &mut graph, &param_scope)?;
            // The body's frame's origin in the model frame: `origin` plus its frame's own.
            let origin = match &frame {
                Some(placed) => {
                    let mut alg = Algebra { g: &mut graph };
                    alg.add3(body_origin, placed.origin)
                }
                None => body_origin,
            };
            drawing.bodies.push(DrawnBody {
                name: name.get_ref().clone(),
                rotation: frame.map(|f| f.rotation),
                origin,
                mass,
                com,
                inertia,
                parts,
            });
            let (rc, omega) = match &frame {
                Some(placed) => {
                    let mut alg = Algebra { g: &mut graph };
                    let rcom = alg.mat_vec(&placed.rotation, com);
                    let rc = alg.add3(origin, rcom);
                    let mut omega = placed.omega;
                    if let Some(wf) = alg_frame_omega {
                        let wb = alg.mat_t_vec(&placed.rotation, wf);
                        omega = alg.add3(omega, wb);
                    }
                    (rc, Some(omega))
                }
                None => {
                    let mut alg = Algebra { g: &mut graph };
                    let rc = alg.add3(origin, com);
                    // A body that does not turn relative to a turning model frame turns with it.
                    (rc, alg_frame_omega)
                }
            };
            let on_so3 = frame.and_then(|placed| {
                let mut alg = Algebra { g: &mut graph };
                let (w, x, root_origin) = placed.in_root(&mut alg, com)?;
                Some((w, x, alg.add3(body_origin, root_origin)))
            });
            energy.translational(&mut graph, mass, rc, on_so3);
            if let Some(w) = omega {
                energy.rotational(&mut graph, &inertia, w);
            }
        }
        for (name, p) in ordered(raw.points) {
            let key = format!("points.{}", name.get_ref());
            let p = p.get_ref();
            let frame = frame_of(&src, &format!("{key}.frame"), &p.frame)?;
            let mass = src.expr(&format!("{key}.mass"), &p.mass, &mut graph, &param_scope)?;
            let local = src.vector(&format!("{key}.position"), &p.position, &mut graph, &scope)?;
            let origin = match &p.origin {
                Some(o) => src.vector(&format!("{key}.origin"), o, &mut graph, &scope)?,
                None => [zero; 3],
            };
            let mut alg = Algebra { g: &mut graph };
            let on_so3 = frame.and_then(|placed| {
                let (w, x, root_origin) = placed.in_root(&mut alg, local)?;
                Some((w, x, alg.add3(origin, root_origin)))
            });
            let r = match &frame {
                Some(placed) => {
                    let turned = alg.mat_vec(&placed.rotation, local);
                    alg.add3(placed.origin, turned)
                }
                None => local,
            };
            let r = alg.add3(origin, r);
            drawing.points.push(DrawnPoint {
                name: name.get_ref().clone(),
                mass,
                position: r,
            });
            energy.translational(&mut graph, mass, r, on_so3);
        }
        if let Some(v) = &extra.potential {
            energy
                .potential
                .push(src.expr("lagrangian.potential", v, &mut graph, &scope)?);
        }
        let mut rate_scope = Names {
            map: scope.map.clone(),
            order: scope.order.clone(),
        };
        for (i, name) in names.iter().enumerate() {
            let id = graph.input(layout.qd(i));
            rate_scope.insert(&format!("{name}_dot"), id);
        }
        for (name, id) in &so3_rates {
            rate_scope.insert(name, *id);
        }
        if let Some(v) = &extra.kinetic {
            energy
                .kinetic
                .push(src.expr("lagrangian.kinetic", v, &mut graph, &rate_scope)?);
        }
        let mut outputs = Vec::new();
        for (name, v) in ordered(raw.outputs) {
            let key = format!("outputs.{}", name.get_ref());
            claim(&src, &key, &name)?;
            outputs.push((
                name.get_ref().clone(),
                src.expr(&key, &v, &mut graph, &rate_scope)?,
            ));
        }

        // Units, where the parameters declare them.
        let dims: Vec<_> = params
            .iter()
            .map(|p| units::parse_unit(&p.unit).ok().flatten())
            .collect();
        {
            let mut inference =
                units::Inference::new(&graph, layout, &dims, &initial, &initial_rates);
            for (key, span, id) in src.read.borrow().iter() {
                inference
                    .check(*id, units::expected(key))
                    .map_err(|message| src.invalid(span, key, message))?;
            }
        }
        let kinetic = graph.sum(&energy.kinetic);
        let potential = graph.sum(&energy.potential);
        let lagrangian = graph.sub(kinetic, potential);
        let equations = equations(&mut graph, lagrangian, layout);
        graph
            .check()
            .map_err(|e| src.invalid(&raw.model.span(), "model", e))?;

        let header = raw.model.into_inner();
        let model_name = header.name.get_ref().clone();
        if model_name.is_empty() || model_name.chars().any(|c| c.is_control()) {
            return Err(src.invalid(
                &header.name.span(),
                "model.name",
                "must be a non-empty name on one line",
            ));
        }
        let run = run_defaults(&src, raw.run.as_ref())?;
        Ok(Model {
            name: model_name,
            summary: header.summary.unwrap_or_default(),
            params,
            coordinates: names,
            orientations,
            graph,
            layout,
            equations,
            initial,
            initial_rates,
            outputs,
            run,
            origin: origin.to_string(),
            drawing,
        })
    }
}

/// The text of the model file at `path`, refused unread when larger than [`MAX_FILE_BYTES`].
///
/// # Errors
/// An unreadable or too large file.
pub fn read_text(path: &Path) -> Result<String, ModelFileError> {
    let size = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    if size > MAX_FILE_BYTES as u64 {
        return Err(ModelFileError::Invalid {
            at: Location {
                origin: path.display().to_string(),
                position: None,
            },
            key: "model".to_string(),
            message: format!(
                "the file is {size} bytes, more than the {MAX_FILE_BYTES} a model may have"
            ),
            excerpt: String::new(),
        });
    }
    Ok(toml_file::read(path, "model")?)
}
