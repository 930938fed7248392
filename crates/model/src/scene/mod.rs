//! A model as a scene: [`ModelScene`] implements [`tumble_scenarios::Scene`], so that every
//! command, sweep and study that runs a built-in scene runs a model file, with the methods of
//! the first-order kind ([`tumble_integrators::ProblemKind::Ode`]: the explicit pairs, `rk4`, Gauss–Legendre and
//! its compositions) and the Taylor methods ([`tumble_integrators::ProblemKind::TaylorSeries`]: coefficients by
//! automatic differentiation on the tape, [`crate::taylor`]; on a model with orientations on
//! SO(3), up to [`crate::file::MAX_SO3_FRAMES`], on the tape of its first-order system, each
//! rotation matrix a point of ℝ⁹; `taylor-dd` the same in double-double,
//! [`tumble_integrators::ProblemKind::DoubleDoubleTaylorSeries`]).
//!
//! The state is `(q, q̇)`; each evaluation of the right-hand side runs one instruction tape
//! ([`crate::expr::tape`]) in a workspace allocated once per run: the forces, the kinematics
//! and the solve of `M q̈ = f` by Cholesky written out on the graph
//! ([`crate::mechanics::first_order`]; a mass matrix of the parameters alone is inverted in
//! the tape's prelude, once per run), compiled to native code where the machine has a code
//! generator, reading the state and writing its derivative directly.
//!
//! Rows: `t`, the coordinates, their rates, `energy` (the energy function
//! `h = Σ q̇ᵢ ∂L/∂q̇ᵢ − L`: the energy, or the Jacobi integral of a driven or rotating model),
//! `energy_rel_err`, the momentum `p_NAME` of each cyclic coordinate, the conserved components
//! `Lx`, `Ly`, `Lz` of the spatial angular momentum of a model on SO(3) ([`spatial_momentum`];
//! as the built-in rigid scenes name them, and left out where the model has an output of that
//! name), then the model's outputs.
//!
//! [`Scene::info`] returns `&'static SceneInfo`: a model's info (and the names in it) is leaked
//! once per distinct model text loaded ([`load`] and [`from_text`] keep one scene per text), so
//! that a model is a scene like any other for as long as the program runs.
//!
//! The module's parts: this file builds a model's [`SceneInfo`] and tapes and answers
//! [`Scene`]; [`ode`] is the first-order right-hand side `M q̈ = f` ([`ModelOde`]) and the
//! conditioning check; [`run`] routes a run to the method's kind of problem; `on_group` runs
//! the Lie-group methods on a model with one orientation on SO(3) (the kinds it offers, the
//! rigid and coupled bodies); `on_product` runs a model with several on their product
//! `SO(3)ᴹ × ℝʸ` with the Lie-group Runge–Kutta methods ([`ModelProduct`]; the other Lie-group
//! methods step on one rotation group and refuse it); `display` shows a state in rows (quaternions) and reads it back.

use std::collections::HashMap;
use std::path::Path;
use std::sync::{Mutex, OnceLock};

use tumble_scenarios::drawing::{Drawing, Placed};
use tumble_scenarios::{
    ParamSpec, Params, Recorder, RunPlan, RunSummary, Scene, SceneError, SceneInfo,
};

use crate::expr::Id;
use crate::expr::tape::Tape;
use crate::expr::taylor::TaylorPlan;
use crate::file::{Model, ModelFileError};
use crate::group::{Group, Samples};
use crate::mechanics::{Algebra, first_order};
use tumble_jit::Native;

mod display;
mod ode;
mod on_group;
mod on_product;
mod run;

use display::Display;
use ode::state_args;
pub use ode::{Evaluation, MAX_CONDITION, ModelOde};
use on_group::group_problems;
pub use on_product::ModelProduct;

/// A model file as a scene.
#[derive(Debug)]
pub struct ModelScene {
    info: &'static SceneInfo,
    model: Model,
    /// Mass matrix (row-major) then forces: the Taylor recursions' tape, and the mass matrix
    /// of [`ModelOde::mass_matrix`].
    rhs: Tape,
    /// The first-order right-hand side `y'` (the state's length), then the pivots of the
    /// mass matrix's Cholesky factorization ([`first_order`]).
    flow: Tape,
    /// `flow`'s body as native code, where the machine has a code generator: the state as its
    /// arguments, `y'` as its results, the pivots stored in the workspace.
    native: Option<Native>,
    /// Whether the mass matrix depends on the parameters only (a body on SO(3) with no
    /// coordinates: its inertia): then it is factored once per run, in `flow`'s prelude.
    constant_mass: bool,
    /// Energy, momenta of the cyclic coordinates, outputs.
    row: Tape,
    /// Initial coordinates then rates (of the parameters).
    init: Tape,
    /// Every momentum (for [`ModelScene::momenta`]).
    momenta: Tape,
    /// The series recursions ([`crate::taylor`]): of `rhs` (`M q̈ = f`) for a model of scalar
    /// coordinates, of `flow` (`y' = F(t, y)`, the kinematics `Ṙ = R ω̂` with it) for a model
    /// with an orientation on SO(3).
    taylor: TaylorPlan,
    /// Names of the displayed coordinates and rates (quaternions and body angular velocities
    /// for the orientations on SO(3), then the scalar coordinates and their rates).
    display: Display,
    /// The tapes of the Lie-group methods ([`crate::group`]), for a model with one orientation
    /// on SO(3).
    group: Option<Group>,
    /// Why the Lie-group methods are not offered, when they are not.
    not_on_group: Option<String>,
    /// The Lagrangian's derivatives on the product `SO(3)ᴹ × ℝʸ`, for a model with several
    /// orientations on SO(3) ([`on_product::lagrangian_tape`]).
    product_lagrangian: Option<Tape>,
}

/// The inputs of a model's tapes at `values` (the parameters in order): time, coordinates and
/// rates zero.
fn inputs_at(model: &Model, values: impl Iterator<Item = f64>) -> Vec<f64> {
    let layout = model.layout;
    let mut inputs = vec![0.0; layout.param(model.params.len()) as usize];
    for (j, value) in values.enumerate() {
        inputs[layout.param(j) as usize] = value;
    }
    inputs
}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

impl ModelScene {
    /// The scene of a parsed model.
    #[must_use]
    pub fn new(mut model: Model) -> Self {
        let group = (model.layout.so3 == 1).then(|| Group::new(&mut model));
        let product_lagrangian =
            (model.layout.so3 >= 2).then(|| on_product::lagrangian_tape(&mut model));
        let spatial = spatial_momentum(&mut model);
        let (problems, not_on_group) = group_problems(&model, group.as_ref());
        let layout = model.layout;
        let n = layout.n;
        let fixed = move |k: u32| layout.is_param(k);
        let constant_mass = model
            .equations
            .mass
            .iter()
            .all(|&id| !model.graph.depends_on(id, &|k| !layout.is_param(k)));
        let system = first_order(&mut model.graph, &model.equations, layout, constant_mass);
        let mut flow_out = system.derivative;
        flow_out.extend(system.pivots);
        let flow = Tape::with_fixed(&model.graph, &flow_out, &fixed);
        let native = flow
            .compile(&state_args(&flow, layout), layout.state_len())
            .ok();
        let eq = &model.equations;
        let (cyclic, autonomous) = symmetries(&model);
        let mut outputs = eq.mass.clone();
        outputs.extend_from_slice(&eq.force);
        let rhs = Tape::with_fixed(&model.graph, &outputs, &fixed);
        let taylor = if layout.so3 == 0 {
            TaylorPlan::new(&rhs, 1 + 2 * n)
        } else {
            TaylorPlan::new(&flow, 1 + layout.state_len())
        };
        let display = Display::of(&model);
        let mut row_out = vec![eq.energy];
        let mut diagnostics = vec![leak("energy".into()), leak("energy_rel_err".into())];
        let mut conserved = Vec::new();
        if autonomous {
            conserved.push(leak(
                "energy function h = sum(q_dot dL/dq_dot) - L (energy, or Jacobi integral)".into(),
            ));
        }
        for i in 0..n {
            if cyclic[i] {
                row_out.push(eq.momenta[i]);
                let name = format!("p_{}", model.coordinates[i]);
                conserved.push(leak(format!(
                    "{name} (momentum of the cyclic coordinate {}, at the default parameters)",
                    model.coordinates[i]
                )));
                diagnostics.push(leak(name));
            }
        }
        let taken = |name: &str| {
            model.outputs.iter().any(|(n, _)| n == name)
                || model.coordinates.iter().any(|c| c == name)
        };
        for (axis, id) in spatial {
            let name = format!("L{axis}");
            if taken(&name) {
                continue;
            }
            row_out.push(id);
            conserved.push(leak(format!(
                "{name} (angular momentum about the model frame's {axis} axis, the sum of R Π \
                 over the orientations on SO(3): the model is invariant under turning them \
                 together about that axis, at the default parameters)"
            )));
            diagnostics.push(leak(name));
        }
        for (name, id) in &model.outputs {
            row_out.push(*id);
            diagnostics.push(leak(name.clone()));
        }
        let row = Tape::with_fixed(&model.graph, &row_out, &fixed);
        // The initial state in state order: coordinates, rotations, rates, angular velocities.
        let mut init_out = model.initial.clone();
        for o in &model.orientations {
            init_out.extend(o.initial_rotation.iter().flatten());
        }
        init_out.extend_from_slice(&model.initial_rates);
        for o in &model.orientations {
            init_out.extend_from_slice(&o.initial_omega);
        }
        let init = Tape::new(&model.graph, &init_out);
        let momenta = Tape::new(&model.graph, &eq.momenta);
        let parameters: Vec<ParamSpec> = model
            .params
            .iter()
            .map(|p| ParamSpec {
                name: leak(p.name.clone()),
                default: p.default,
                unit: leak(p.unit.clone()),
                description: leak(p.description.clone()),
                domain: p.domain,
            })
            .collect();
        let coordinates: Vec<&'static str> = display
            .coordinates
            .iter()
            .map(|c| leak(c.clone()))
            .collect();
        let rate_names: Vec<&'static str> = display.rates.iter().map(|c| leak(c.clone())).collect();
        let info = Box::leak(Box::new(SceneInfo {
            name: leak(model.name.clone()),
            summary: leak(if model.summary.is_empty() {
                format!("model file {}", model.origin)
            } else {
                model.summary.clone()
            }),
            coordinates: Box::leak(coordinates.into_boxed_slice()),
            parameters: Box::leak(parameters.into_boxed_slice()),
            conserved: Box::leak(conserved.into_boxed_slice()),
            oracle: leak(format!("model file {}", model.origin)),
            problems,
            needs_dense_output: false,
            default_integrator: leak(model.run.integrator.clone()),
            default_step: model.run.dt,
            // Not measured: a model has no reference solution of its own.
            default_error: f64::NAN,
            default_t_end: model.run.t_end,
            diagnostics: Box::leak(diagnostics.into_boxed_slice()),
            rate_names: if layout.so3 == 0 {
                &[]
            } else {
                Box::leak(rate_names.into_boxed_slice())
            },
            not_on_group: not_on_group.as_ref().map_or("", |why| leak(why.clone())),
        }));
        ModelScene {
            info,
            model,
            rhs,
            flow,
            native,
            constant_mass,
            row,
            init,
            momenta,
            taylor,
            display,
            group,
            not_on_group,
            product_lagrangian,
        }
    }

    /// Why the Lie-group methods (LGVI, Lie–Gauss, RKMK, …) do not run this model, or `None`
    /// when they do.
    #[must_use]
    pub fn not_on_group(&self) -> Option<&str> {
        self.not_on_group.as_deref()
    }

    /// The model.
    #[must_use]
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Instructions per right-hand-side evaluation (the body of its tape).
    #[must_use]
    pub fn rhs_instructions(&self) -> usize {
        self.flow.len()
    }

    /// The inputs of the model's tapes at `params`: time, coordinates and rates zero.
    fn inputs(&self, params: &Params) -> Vec<f64> {
        inputs_at(&self.model, params.iter().map(|(_, value)| value))
    }

    /// The initial state `(q, q̇)` at `params`.
    #[must_use]
    pub fn initial_state(&self, params: &Params) -> Vec<f64> {
        let mut w = self.init.workspace();
        self.init.run_all(&mut w, &self.inputs(params));
        (0..self.init.outputs())
            .map(|i| self.init.output(&w, i))
            .collect()
    }

    /// The momenta `∂L/∂q̇` at `(t, q, q̇)` and `params`.
    #[must_use]
    pub fn momenta(&self, params: &Params, t: f64, state: &[f64]) -> Vec<f64> {
        let mut inputs = self.inputs(params);
        inputs[0] = t;
        inputs[1..=state.len()].copy_from_slice(state);
        let mut w = self.momenta.workspace();
        self.momenta.run_all(&mut w, &inputs);
        (0..self.momenta.outputs())
            .map(|i| self.momenta.output(&w, i))
            .collect()
    }

    /// The state `(t, y)` of a row of this scene's CSV (`t`, the displayed coordinates and
    /// rates first): quaternions become rotation matrices again.
    #[must_use]
    pub fn state_of_row(&self, row: &[f64]) -> Vec<f64> {
        let layout = self.model.layout;
        let mut out = vec![0.0; 1 + layout.state_len()];
        out[0] = row[0];
        self.display.read(layout, &row[1..], &mut out[1..]);
        out
    }
}

/// Which coordinates are cyclic and whether the Lagrangian is autonomous, by evaluating
/// `∂L/∂qᵢ` and `∂L/∂t` at sample states (coordinates and rates in ±1.5, `t` in [0, 3]) at the
/// default parameters: a derivative that vanishes symbolically, or to round-off
/// (`≤ 1e-12 · (1 + |L|)`) at every sample (where it cancels only after simplification, as
/// `sin² + cos²` does), marks a symmetry. The samples are fixed, so the answer is reproducible.
fn symmetries(model: &Model) -> (Vec<bool>, bool) {
    let eq = &model.equations;
    let n = model.layout.n;
    let mut outputs = eq.dl_dq.clone();
    outputs.push(eq.dl_dt);
    outputs.push(eq.lagrangian);
    let tape = Tape::new(&model.graph, &outputs);
    let mut w = tape.workspace();
    let mut inputs = vec![0.0; model.layout.param(model.params.len()) as usize];
    for (j, p) in model.params.iter().enumerate() {
        inputs[model.layout.param(j) as usize] = p.default;
    }
    let mut cyclic: Vec<bool> = eq.dl_dq.iter().map(|_| true).collect();
    let mut autonomous = true;
    // A fixed low-discrepancy sequence (golden-ratio steps) over the state.
    let mut x = std::f64::consts::FRAC_1_PI;
    let mut next = || {
        x = (x + 0.618_033_988_749_894_9).fract();
        x
    };
    for _ in 0..8 {
        inputs[0] = 3.0 * next();
        for k in 0..model.layout.state_len() {
            inputs[1 + k] = 3.0 * next() - 1.5;
        }
        tape.run_all(&mut w, &inputs);
        let scale = 1e-12 * (1.0 + tape.output(&w, n + 1).abs());
        for i in 0..n {
            let d = tape.output(&w, i);
            cyclic[i] &= d.abs() <= scale;
        }
        autonomous &= tape.output(&w, n).abs() <= scale;
    }
    (cyclic, autonomous)
}

/// The components of the spatial angular momentum `J = Σ_f R_f Π_f` (`Π_f = ∂L/∂ω_f`) of a
/// model with orientations on SO(3) that it conserves, as `(axis, J · e_axis)`.
///
/// Turning every orientation together, `R_f ↦ exp(ε ê) R_f` (the body angular velocities and
/// the scalar coordinates unchanged), changes `L` at the rate `σ · e` with
/// `σ = Σ_f R_f τ_f(L)`, `τ_f` the left-trivialized derivative along `R_f`
/// ([`Algebra::rotation_derivative`]); where `σ · e = 0` everywhere, Noether's theorem gives
/// `J · e` conserved (Marsden & Ratiu, *Introduction to Mechanics and Symmetry*, §11.4, the
/// momentum map of the left action on `T SO(3)`, spatial angular momentum). `σ` is evaluated
/// at sample states as [`symmetries`] does (rotations `exp(ĥη)` with `η` in ±1.5): a component
/// that vanishes to `1e-12 · (1 + |L|)` at every sample is conserved. A model whose masses
/// are all carried by its orientations, without a potential, conserves all three (a free
/// satellite); with gravity along z, `J_z`; a mass the orientations do not carry, or a turning
/// model frame, breaks the symmetry, and nothing is reported.
fn spatial_momentum(model: &mut Model) -> Vec<(char, Id)> {
    let layout = model.layout;
    if layout.so3 == 0 {
        return Vec::new();
    }
    let lagrangian = model.equations.lagrangian;
    let momenta = model.equations.momenta.clone();
    let mut alg = Algebra {
        g: &mut model.graph,
    };
    let mut sigma = alg.zero3();
    let mut momentum = alg.zero3();
    for f in 0..layout.so3 {
        let r = layout.rotation(alg.g, f);
        let tau = alg.rotation_derivative(lagrangian, layout, f);
        let turned = alg.mat_vec(&r, tau);
        sigma = alg.add3(sigma, turned);
        let pi = [0, 1, 2].map(|c| momenta[layout.n + 3 * f + c]);
        let spatial = alg.mat_vec(&r, pi);
        momentum = alg.add3(momentum, spatial);
    }
    let mut outputs = sigma.to_vec();
    outputs.push(lagrangian);
    let tape = Tape::new(&model.graph, &outputs);
    let mut w = tape.workspace();
    let mut inputs = inputs_at(model, model.params.iter().map(|p| p.default));
    let mut conserved = [true; 3];
    let mut samples = Samples(std::f64::consts::FRAC_1_PI);
    let mut next = || 3.0 * samples.next() - 1.5;
    for _ in 0..8 {
        inputs[0] = 1.5 + next();
        for k in 0..layout.state_len() {
            inputs[1 + k] = next();
        }
        for f in 0..layout.so3 {
            let eta = nalgebra::Vector3::new(next(), next(), next());
            let r = nalgebra::Rotation3::new(eta);
            for a in 0..3 {
                for b in 0..3 {
                    inputs[layout.rot(f, a, b) as usize] = r[(a, b)];
                }
            }
        }
        tape.run_all(&mut w, &inputs);
        let scale = 1e-12 * (1.0 + tape.output(&w, 3).abs());
        for (c, ok) in conserved.iter_mut().enumerate() {
            *ok &= tape.output(&w, c).abs() <= scale;
        }
    }
    ['x', 'y', 'z']
        .into_iter()
        .zip(momentum)
        .zip(conserved)
        .filter(|(_, ok)| *ok)
        .map(|(pair, _)| pair)
        .collect()
}

impl Scene for ModelScene {
    fn info(&self) -> &'static SceneInfo {
        self.info
    }

    /// The model's bodies and point masses ([`ModelScene::view`]).
    fn drawing(&self, params: &Params) -> Option<Result<Drawing, SceneError>> {
        Some(Ok(self.view(params)))
    }

    /// Where the bodies and point masses are, by the model's own expressions
    /// ([`ModelScene::poses`]).
    fn placements(&self, params: &Params, rows: &[Vec<f64>]) -> Vec<Placed> {
        self.poses(params, rows)
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let y0 = self.initial_state(params);
        if let Some(i) = y0.iter().position(|x| !x.is_finite()) {
            let layout = self.model.layout;
            let (n, v) = (layout.n, layout.velocities_at());
            let orientation = |k: usize| &self.model.orientations[k].name;
            let what = if i < n {
                format!("the initial value of `{}`", self.model.coordinates[i])
            } else if i < v {
                format!(
                    "the initial orientation of frame `{}`",
                    orientation((i - n) / 9)
                )
            } else if i < v + n {
                format!("the initial rate of `{}`", self.model.coordinates[i - v])
            } else {
                format!(
                    "the initial angular velocity of frame `{}`",
                    orientation((i - v - n) / 3)
                )
            };
            return Err(SceneError::ModelRefused {
                model: self.info.name.to_string(),
                message: format!("{what} is {} at these parameters", y0[i]),
            });
        }
        // One size per state length: `2n` for `n ≤ 6` scalar coordinates, `2n + 12` beside one
        // orientation on SO(3) (`n ≤ 3`), which the Lie-group methods may run too, and
        // `2n + 12k` beside `k = 2 … 4` of them, which the vector-space methods run and the
        // Lie-group Runge–Kutta methods on the product SO(3)^k × R^(2n + 3k).
        match self.model.layout.state_len() {
            2 => self.run::<2>(params, plan, &y0, recorder),
            4 => self.run::<4>(params, plan, &y0, recorder),
            6 => self.run::<6>(params, plan, &y0, recorder),
            8 => self.run::<8>(params, plan, &y0, recorder),
            10 => self.run::<10>(params, plan, &y0, recorder),
            12 => self.run::<12>(params, plan, &y0, recorder),
            14 => self.run::<14>(params, plan, &y0, recorder),
            16 => self.run::<16>(params, plan, &y0, recorder),
            18 => self.run::<18>(params, plan, &y0, recorder),
            24 => self.run_multi::<24, 2, 6>(params, plan, &y0, recorder),
            26 => self.run_multi::<26, 2, 8>(params, plan, &y0, recorder),
            28 => self.run_multi::<28, 2, 10>(params, plan, &y0, recorder),
            30 => self.run_multi::<30, 2, 12>(params, plan, &y0, recorder),
            36 => self.run_multi::<36, 3, 9>(params, plan, &y0, recorder),
            38 => self.run_multi::<38, 3, 11>(params, plan, &y0, recorder),
            40 => self.run_multi::<40, 3, 13>(params, plan, &y0, recorder),
            42 => self.run_multi::<42, 3, 15>(params, plan, &y0, recorder),
            48 => self.run_multi::<48, 4, 12>(params, plan, &y0, recorder),
            50 => self.run_multi::<50, 4, 14>(params, plan, &y0, recorder),
            52 => self.run_multi::<52, 4, 16>(params, plan, &y0, recorder),
            54 => self.run_multi::<54, 4, 18>(params, plan, &y0, recorder),
            other => Err(SceneError::ModelRefused {
                model: self.info.name.to_string(),
                message: format!(
                    "a state of {other} numbers is beyond what a model may have \
                     ({} coordinates, {} orientations on SO(3))",
                    self.model.layout.n, self.model.layout.so3
                ),
            }),
        }
    }
}

/// Models loaded so far, one scene per (origin, text).
fn cache() -> &'static Mutex<HashMap<(String, String), &'static ModelScene>> {
    static CACHE: OnceLock<Mutex<HashMap<(String, String), &'static ModelScene>>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// The scene of model text (named `origin` in messages; files it names are relative to
/// `origin`'s directory). The same text and origin give the same scene.
///
/// # Errors
/// As [`Model::parse`].
pub fn from_text(text: &str, origin: &str) -> Result<&'static ModelScene, ModelFileError> {
    let key = (origin.to_string(), text.to_string());
    if let Some(scene) = cache().lock().map_err(|_| poisoned(origin))?.get(&key) {
        return Ok(scene);
    }
    let scene: &'static ModelScene =
        Box::leak(Box::new(ModelScene::new(Model::parse(text, origin)?)));
    cache()
        .lock()
        .map_err(|_| poisoned(origin))?
        .insert(key, scene);
    Ok(scene)
}

fn poisoned(origin: &str) -> ModelFileError {
    ModelFileError::Invalid {
        at: tumble_scenarios::toml_file::Location {
            origin: origin.to_string(),
            position: None,
        },
        key: "model".to_string(),
        message: "an earlier load of a model panicked".to_string(),
        excerpt: String::new(),
    }
}

/// The scene of the model file at `path`.
///
/// # Errors
/// As [`Model::load`].
pub fn load(path: &Path) -> Result<&'static ModelScene, ModelFileError> {
    let text = crate::file::read_text(path)?;
    from_text(&text, &path.display().to_string())
}

/// Whether TOML text is a model file (it has a `[model]` table) rather than a scene file.
#[must_use]
pub fn is_model_text(text: &str) -> bool {
    text.lines().any(|l| {
        let l = l.trim();
        l == "[model]"
            || l.starts_with("[model]")
            || l.starts_with("model.")
            || l.starts_with("model =")
    })
}

/// Whether the file at `path` is a model file ([`is_model_text`]).
#[must_use]
pub fn is_model_file(path: &Path) -> bool {
    std::fs::read_to_string(path).is_ok_and(|t| is_model_text(&t))
}
