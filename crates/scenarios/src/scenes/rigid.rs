//! Rigid bodies on SO(3): `free-body`, `dzhanibekov` and `heavy-top`.
//!
//! # Model
//!
//! State `(R, m)`: the orientation (body → lab) and the body angular momentum about the centre
//! of mass (free bodies) or the fixed point (the top); `Ṙ = R hat Ω`, `ṁ = m × Ω + M(R)`,
//! `Ω = J⁻¹ m`, with `J` the body-frame inertia (not necessarily diagonal) and `M` the moment of
//! the potential (zero for free bodies; `M = w (Rᵀ e₃) × ρ` for the heavy top).
//!
//! # Scenes
//!
//! * `free-body`: a torque-free asymmetric body. Oracle: the exact elliptic-function solution
//!   ([`tumble_integrators::rigid::ExactFlow`]); the `exact_err` column is the distance of each
//!   row from it (`max(max|ΔR|, |Δm|/|m|)`). Energy and `L` conserved.
//! * `dzhanibekov`: the T-handle (inertia from the inertia crate's mesh-checked composition of two
//!   boxes) spun about its intermediate axis with a small perturbation: it flips periodically;
//!   the flip period is half the exact solution's period.
//! * `heavy-top`: the Lagrange top; defaults are Simo & Wong's hard case `J = diag(5, 5, 1)`,
//!   `Mgl = 20`, `Λ₀ = exp(hat(0.05, 0, 0))`, `W₀ = (0, 0, 50)` (body angular velocity),
//!   `H ≈ 1269.975`, `t ∈ [0, 10]`. Energy, `L_z` and (symmetric top) `L·e₃` conserved.
//!
//! # Output
//!
//! Coordinates `qw, qx, qy, qz` (unit quaternion of `R`, `w ≥ 0` at the start, sign continuous
//! along the run), rates `omega_x, omega_y,
//! omega_z` (body angular velocity), diagnostics `energy, energy_rel_err, Lx, Ly, Lz` (lab) and,
//! for free bodies, `exact_err`.
//!
//! # References
//! * J. C. Simo, K. K. Wong, "Unconditionally stable algorithms for rigid body dynamics that
//!   exactly preserve energy and momentum", Int. J. Numer. Methods Eng. 31 (1991) 19–52.

use nalgebra::{Matrix3, Rotation3, SVector, Vector3};
use tumble_inertia::{MassSpec, THandle};
use tumble_integrators::rigid::{
    EulerEquations, ExactFlow, FreeRigidBody, HeavyTop, LieVectorField, RigidBody, RigidBodyState,
    TaylorHeavyTop,
};
use tumble_integrators::{Ode, ProblemKind};
use tumble_kinematics::so3::{exp, hat};

use crate::dispatch;
use crate::drawing::Drawing;
use crate::error::SceneError;
use crate::params::{Domain, ParamSpec, Params};
use crate::recommendation::Measure;
use crate::scene::{
    Recommendation, Recorder, RowObserver, RunPlan, RunSummary, Scene, SceneInfo,
    continuous_quaternion, run_vector,
};

/// Flattened state `(R column-major, m)`.
pub type Flat = SVector<f64, 12>;

/// Flattens a rigid-body state.
#[must_use]
pub fn flatten(s: &RigidBodyState) -> Flat {
    let mut y = Flat::zeros();
    y.fixed_rows_mut::<9>(0)
        .copy_from_slice(s.rotation.as_slice());
    y.fixed_rows_mut::<3>(9).copy_from(&s.momentum);
    y
}

/// The state of a flattened vector.
#[must_use]
pub fn unflatten(y: &Flat) -> RigidBodyState {
    RigidBodyState {
        rotation: Matrix3::from_column_slice(&y.as_slice()[..9]),
        momentum: Vector3::new(y[9], y[10], y[11]),
    }
}

/// Euler's equations with the orientation on `ℝ¹²`, for vector-space integrators.
#[derive(Debug, Clone, Copy)]
pub struct FlatRigidBody<B>(pub B);

impl<B: RigidBody> Ode<Flat> for FlatRigidBody<B> {
    fn rhs(&self, t: f64, y: &Flat, dy: &mut Flat) {
        let r = Matrix3::from_column_slice(&y.as_slice()[..9]);
        let m = Vector3::new(y[9], y[10], y[11]);
        let (omega, dm) = EulerEquations(&self.0).eval(t, &r, &m);
        let rd = r * hat(&omega);
        dy.fixed_rows_mut::<9>(0).copy_from_slice(rd.as_slice());
        dy.fixed_rows_mut::<3>(9).copy_from(&dm);
    }
}

/// The magnitude of a rigid body's energy: `T` plus the potential's amplitude
/// `√(V² + |M|²)`, which for a potential linear in `R`, `V = w (Rᵀe₃)·ρ` (gravity on a body
/// turning about a fixed point), is `w |ρ|` at every orientation (`|V|² + |M|² =
/// w² ((u·ρ)² + |u × ρ|²)`, `u = Rᵀe₃` a unit vector). The energy scale of
/// [`crate::scene::run_vector`].
fn energy_magnitude<B: RigidBody>(body: &B, s: &RigidBodyState) -> f64 {
    let v = body.potential(&s.rotation);
    body.body().energy(&s.momentum).abs() + v.hypot(body.torque(&s.rotation).norm())
}

/// Writes a row: t, quaternion, body ω, energy, its magnitude `|T| + |V|` (the relative error
/// slot, see [`crate::scene::run_vector`]), L, and the distance from
/// the exact solution when one is given.
///
/// `frame` maps the model's body frame to the frame the rows are reported in (the columns of
/// `frame` are the model's axes in the reported frame): the reported orientation is
/// `R frameᵀ` and the reported angular velocity `frame ω`. The built-in scenes report their
/// model frame (`frame` the identity, which changes no bit); scenes whose body comes from a
/// scene file integrate in the principal frame and report the file's frame.
fn write_row<B: RigidBody>(
    body: &B,
    exact: Option<&ExactFlow>,
    frame: &Matrix3<f64>,
    t: f64,
    s: &RigidBodyState,
    previous: &mut Option<nalgebra::Quaternion<f64>>,
    out: &mut [f64],
) {
    let q = continuous_quaternion(&(s.rotation * frame.transpose()), previous);
    let omega = frame * body.body().omega(&s.momentum);
    let l = s.rotation * s.momentum;
    let head = [
        t,
        q.w,
        q.i,
        q.j,
        q.k,
        omega.x,
        omega.y,
        omega.z,
        body.hamiltonian(s),
        energy_magnitude(body, s),
        l.x,
        l.y,
        l.z,
    ];
    out[..head.len()].copy_from_slice(&head);
    if let (Some(flow), Some(slot)) = (exact, out.get_mut(head.len())) {
        let (r, m) = flow.at(t);
        let dr = (r.matrix() - s.rotation).amax();
        let dm = (m - s.momentum).norm() / m.norm().max(f64::MIN_POSITIVE);
        *slot = dr.max(dm);
    }
}

/// Column of the energy in a row.
const ENERGY_COLUMN: usize = 8;

/// Runs a rigid body with the plan's method; `free` is the same body as a [`FreeRigidBody`]
/// when it is torque-free (the scene then offers [`ProblemKind::FreeRigidBody`]), `taylor`
/// the same body's Taylor coefficients (for `taylor`, `taylor8`, … and `taylor-dd`).
/// `frame` as in [`write_row`].
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_rigid<B: RigidBody + Copy>(
    info: &'static SceneInfo,
    body: B,
    free: Option<FreeRigidBody>,
    taylor: &TaylorHeavyTop,
    s0: RigidBodyState,
    exact: Option<ExactFlow>,
    frame: Matrix3<f64>,
    plan: &RunPlan,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError> {
    let columns = info.columns().len();
    let mut previous = None;
    let mut row = move |t: f64, s: &RigidBodyState, out: &mut [f64]| {
        write_row(&body, exact.as_ref(), &frame, t, s, &mut previous, out);
    };
    if matches!(
        plan.kind,
        ProblemKind::TaylorSeries | ProblemKind::DoubleDoubleTaylorSeries
    ) {
        // The Taylor methods on the hand-written coefficients of Euler's equations.
        return crate::scene::run_taylor_vector(
            taylor,
            flatten(&s0),
            plan,
            columns,
            ENERGY_COLUMN,
            |t, y, out| row(t, &unflatten(y), out),
            &mut [],
            recorder,
        );
    }
    if plan.kind == ProblemKind::Ode {
        return run_vector(
            &FlatRigidBody(body),
            flatten(&s0),
            plan,
            columns,
            ENERGY_COLUMN,
            |t, y, out| row(t, &unflatten(y), out),
            &mut [],
            recorder,
        );
    }
    let mut observer = RowObserver::new(columns, ENERGY_COLUMN, plan, row, recorder);
    let mut state = s0;
    let outcome = dispatch::run_rigid_body(&body, free.as_ref(), &mut state, plan, &mut observer)?;
    observer.summary(&outcome)
}

/// A torque-free body's kinds of problem, most specific first.
pub(crate) const FREE_BODY_PROBLEMS: &[ProblemKind] = &[
    ProblemKind::FreeRigidBody,
    ProblemKind::RigidBody,
    ProblemKind::LieVectorField,
    ProblemKind::Ode,
    ProblemKind::TaylorSeries,
    ProblemKind::DoubleDoubleTaylorSeries,
];

/// The heavy top's kinds of problem.
pub(crate) const HEAVY_TOP_PROBLEMS: &[ProblemKind] = &[
    ProblemKind::RigidBody,
    ProblemKind::LieVectorField,
    ProblemKind::Ode,
    ProblemKind::TaylorSeries,
    ProblemKind::DoubleDoubleTaylorSeries,
];

pub(crate) const fn spec(
    name: &'static str,
    default: f64,
    unit: &'static str,
    description: &'static str,
    domain: Domain,
) -> ParamSpec {
    ParamSpec {
        name,
        default,
        unit,
        description,
        domain,
    }
}

static FREE_BODY_SPECS: [ParamSpec; 6] = [
    spec(
        "I1",
        1.0,
        "kg*m^2",
        "principal moment about body x",
        Domain::Positive,
    ),
    spec(
        "I2",
        2.0,
        "kg*m^2",
        "principal moment about body y",
        Domain::Positive,
    ),
    spec(
        "I3",
        3.0,
        "kg*m^2",
        "principal moment about body z",
        Domain::Positive,
    ),
    spec(
        "m1",
        0.4,
        "kg*m^2/s",
        "initial body angular momentum, x",
        Domain::Finite,
    ),
    spec(
        "m2",
        -0.8,
        "kg*m^2/s",
        "initial body angular momentum, y",
        Domain::Finite,
    ),
    spec(
        "m3",
        0.6,
        "kg*m^2/s",
        "initial body angular momentum, z",
        Domain::Finite,
    ),
];

/// The `free-body` scene.
pub static FREE_BODY: SceneInfo = SceneInfo {
    name: "free-body",
    summary: "torque-free asymmetric rigid body",
    coordinates: &["qw", "qx", "qy", "qz"],
    parameters: &FREE_BODY_SPECS,
    conserved: &["energy", "L (vector)", "|m| (Casimir)"],
    oracle: "exact solution by Jacobi elliptic functions and an elliptic integral of the third kind (column exact_err)",
    problems: FREE_BODY_PROBLEMS,
    needs_dense_output: false,
    default_integrator: "split4",
    default_step: 0.01,
    default_error: 1.2e-12,
    default_t_end: 20.0,
    diagnostics: &["energy", "energy_rel_err", "Lx", "Ly", "Lz", "exact_err"],
    rate_names: &["omega_x", "omega_y", "omega_z"],
    not_on_group: "",
};

/// Which method for what on `free-body`; the measurements behind it are data
/// (`crate::recommendation`), written by `tumble work-precision free-body --recommend`.
static FREE_BODY_RECOMMENDED: [Recommendation; 4] = [
    Recommendation {
        purpose: "any accuracy",
        integrators: &["split-exact2"],
        measure: Measure::ToError(1e-12),
        compared_with: &[],
        reason: "the torque-free flow is exact in this splitting",
    },
    Recommendation {
        purpose: "a general method, error 1e-4 … 1e-8 at t = 20 s",
        integrators: &["vern8"],
        measure: Measure::ToError(1e-8),
        compared_with: &["dop853"],
        reason: "",
    },
    Recommendation {
        purpose: "a general method, error 1e-8 … 1e-12",
        integrators: &["vern9", "vern8"],
        measure: Measure::ToError(1e-12),
        compared_with: &["dop853", "taylor"],
        reason: "",
    },
    Recommendation {
        purpose: "energy over 10^6 steps and more",
        integrators: &["lgvi", "split6"],
        measure: Measure::LongRun,
        compared_with: &["vern9"],
        reason: "symplectic; lgvi keeps the spatial momentum exact",
    },
];

/// The body with principal moments `moments`; a non-physical inertia (a moment not positive, or
/// the triangle inequality `I1 + I2 ≥ I3` violated) is a parameter error naming I1, I2, I3.
pub(crate) fn inertia_body(moments: Vector3<f64>) -> Result<FreeRigidBody, SceneError> {
    FreeRigidBody::from_principal_moments(moments).map_err(|e| match e {
        tumble_integrators::Error::InvalidParameter { value, reason, .. } => {
            SceneError::Model(crate::error::ModelError::InvalidParameter {
                name: "I1, I2, I3".into(),
                value,
                reason,
            })
        }
        other => SceneError::Integration(other),
    })
}

/// The intermediate one of principal `moments` as a column of `axes`, or an error when no
/// moment lies strictly between the others.
pub(crate) fn intermediate_of(
    moments: Vector3<f64>,
    axes: &Matrix3<f64>,
) -> Result<Vector3<f64>, SceneError> {
    let middle = (0..3).find(|&k| {
        let (a, b) = (moments[(k + 1) % 3], moments[(k + 2) % 3]);
        (a < moments[k] && moments[k] < b) || (b < moments[k] && moments[k] < a)
    });
    match middle {
        Some(k) => Ok(axes.column(k).into_owned()),
        None => Err(SceneError::InvalidOption {
            option: "flips",
            value: f64::NAN,
            reason: format!(
                "the principal moments {:?} have no strict middle one: the intermediate axis \
                 is not defined",
                moments.as_slice()
            ),
        }),
    }
}

/// Refuses a body that does not rotate: `names` are the parameters that set its initial
/// angular momentum (or velocity), as the user writes them.
pub(crate) fn check_momentum(
    scene: &str,
    names: &str,
    requirement: &'static str,
    m: &Vector3<f64>,
) -> Result<(), SceneError> {
    if m.norm() > 0.0 {
        Ok(())
    } else {
        Err(SceneError::InvalidParameter {
            scene: scene.to_string(),
            name: names.into(),
            value: 0.0,
            requirement,
        })
    }
}

/// Runs `free-body`.
#[derive(Debug, Clone, Copy, Default)]
pub struct FreeBodyScene;

impl Scene for FreeBodyScene {
    fn info(&self) -> &'static SceneInfo {
        &FREE_BODY
    }

    /// The body as the uniform box with its principal moments.
    fn drawing(&self, params: &Params) -> Option<Result<Drawing, SceneError>> {
        let moments = || -> Result<[f64; 3], SceneError> {
            Ok([params.get("I1")?, params.get("I2")?, params.get("I3")?])
        };
        Some(moments().map(Drawing::equivalent_box))
    }

    fn recommendations(&self) -> &'static [Recommendation] {
        &FREE_BODY_RECOMMENDED
    }

    fn initial_rate(&self, params: &Params) -> Option<Result<f64, SceneError>> {
        let mut sum = 0.0;
        for (m, i) in [("m1", "I1"), ("m2", "I2"), ("m3", "I3")] {
            match (params.get(m), params.get(i)) {
                (Ok(m), Ok(i)) => sum += (m / i).powi(2),
                (Err(e), _) | (_, Err(e)) => return Some(Err(e)),
            }
        }
        Some(Ok(sum.sqrt()))
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let info = self.info();
        let moments = Vector3::new(params.get("I1")?, params.get("I2")?, params.get("I3")?);
        let body = inertia_body(moments)?;
        let m0 = Vector3::new(params.get("m1")?, params.get("m2")?, params.get("m3")?);
        check_momentum(
            info.name,
            "m1, m2, m3",
            "must not all be zero (the body must rotate): give one of them, e.g. --set m3=1",
            &m0,
        )?;
        let r0 = Rotation3::identity();
        let exact = body.flow(&r0, &m0)?;
        let s0 = RigidBodyState::new(&r0, m0);
        run_rigid(
            info,
            body,
            Some(body),
            &TaylorHeavyTop::free(&body),
            s0,
            Some(exact),
            Matrix3::identity(),
            plan,
            recorder,
        )
    }

    fn intermediate_axis(&self, params: &Params) -> Option<Result<Vector3<f64>, SceneError>> {
        Some((|| {
            let moments = Vector3::new(params.get("I1")?, params.get("I2")?, params.get("I3")?);
            intermediate_of(moments, &Matrix3::identity())
        })())
    }
}

static DZHANIBEKOV_SPECS: [ParamSpec; 3] = [
    spec(
        "mass",
        0.05,
        "kg",
        "mass of the T-handle (80 x 20 x 20 mm bar on a 60 mm stem)",
        Domain::Positive,
    ),
    spec(
        "spin",
        20.0,
        "rad/s",
        "initial spin about the intermediate principal axis",
        Domain::NonZero,
    ),
    spec(
        "perturbation",
        1e-3,
        "",
        "initial angular velocity about each of the other principal axes, relative to the spin",
        Domain::Finite,
    ),
];

/// The `dzhanibekov` scene.
pub static DZHANIBEKOV: SceneInfo = SceneInfo {
    name: "dzhanibekov",
    summary: "T-handle spun near its intermediate axis flips periodically (Dzhanibekov effect)",
    coordinates: &["qw", "qx", "qy", "qz"],
    parameters: &DZHANIBEKOV_SPECS,
    conserved: &["energy", "L (vector)", "|m| (Casimir)"],
    oracle: "flip period = half the period of the exact solution (4K(k)/lambda)",
    problems: FREE_BODY_PROBLEMS,
    needs_dense_output: false,
    default_integrator: "exact",
    default_step: 1e-3,
    default_error: 1.8e-14,
    default_t_end: 10.0,
    diagnostics: &["energy", "energy_rel_err", "Lx", "Ly", "Lz", "exact_err"],
    rate_names: &["omega_x", "omega_y", "omega_z"],
    not_on_group: "",
};

/// Which method for what on `dzhanibekov`; the measurements behind it are data
/// (`crate::recommendation`), written by `tumble work-precision dzhanibekov --recommend`.
static DZHANIBEKOV_RECOMMENDED: [Recommendation; 3] = [
    Recommendation {
        purpose: "any accuracy",
        integrators: &["exact"],
        measure: Measure::Nothing,
        compared_with: &[],
        reason: "the closed-form solution in Jacobi elliptic functions, evaluated at each output time; split-exact2 is exact in a single step, but its round-off grows as the step shrinks, amplified by the flips",
    },
    Recommendation {
        purpose: "a general method, error 1e-4 … 1e-10 at t = 10 s",
        integrators: &["vern7", "dop853"],
        measure: Measure::ToError(1e-10),
        compared_with: &["vern9", "vern8"],
        reason: "",
    },
    Recommendation {
        purpose: "energy over 10^6 steps and more",
        integrators: &["dmv", "gauss2", "vern9"],
        measure: Measure::LongRun,
        compared_with: &[],
        reason: "dmv and gauss2 are symplectic and keep the momentum map exact",
    },
];

/// Runs `dzhanibekov`.
#[derive(Debug, Clone, Copy, Default)]
pub struct DzhanibekovScene;

impl DzhanibekovScene {
    /// The T-handle's body and its initial state (identity orientation, spin about the
    /// intermediate axis plus the perturbation on the others).
    ///
    /// # Errors
    /// Invalid parameters; an invalid T-handle (not for the standard one).
    pub fn body_and_state(params: &Params) -> Result<(FreeRigidBody, RigidBodyState), SceneError> {
        let props = THandle::STANDARD.mass_properties(MassSpec::TotalMass(params.get("mass")?))?;
        let body = FreeRigidBody::from_inertia(props.inertia())?;
        let axes = props.principal().axes;
        let spin = params.get("spin")?;
        let eps = params.get("perturbation")? * spin;
        let omega = axes.matrix() * Vector3::new(eps, spin, eps);
        let m0 = props.inertia() * omega;
        Ok((body, RigidBodyState::new(&Rotation3::identity(), m0)))
    }
}

impl Scene for DzhanibekovScene {
    fn info(&self) -> &'static SceneInfo {
        &DZHANIBEKOV
    }

    /// The standard T-handle's mesh.
    fn drawing(&self, _params: &Params) -> Option<Result<Drawing, SceneError>> {
        Some(Drawing::t_handle())
    }

    fn recommendations(&self) -> &'static [Recommendation] {
        &DZHANIBEKOV_RECOMMENDED
    }

    fn initial_rate(&self, params: &Params) -> Option<Result<f64, SceneError>> {
        Some(
            params
                .get("perturbation")
                .and_then(|eps| Ok(params.get("spin")?.abs() * (1.0 + 2.0 * eps * eps).sqrt())),
        )
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let info = self.info();
        let (body, s0) = Self::body_and_state(params)?;
        check_momentum(
            info.name,
            "spin",
            "must not be zero (the body must rotate)",
            &s0.momentum,
        )?;
        let exact = body.flow(&Rotation3::identity(), &s0.momentum)?;
        run_rigid(
            info,
            body,
            Some(body),
            &TaylorHeavyTop::free(&body),
            s0,
            Some(exact),
            Matrix3::identity(),
            plan,
            recorder,
        )
    }

    fn intermediate_axis(&self, params: &Params) -> Option<Result<Vector3<f64>, SceneError>> {
        Some(Self::body_and_state(params).and_then(|(body, _)| {
            intermediate_of(body.principal_moments(), body.principal_axes().matrix())
        }))
    }
}

static HEAVY_TOP_SPECS: [ParamSpec; 6] = [
    spec(
        "I1",
        5.0,
        "kg*m^2",
        "moment about body x, about the pivot",
        Domain::Positive,
    ),
    spec(
        "I2",
        5.0,
        "kg*m^2",
        "moment about body y, about the pivot",
        Domain::Positive,
    ),
    spec(
        "I3",
        1.0,
        "kg*m^2",
        "moment about the symmetry axis body z",
        Domain::Positive,
    ),
    spec(
        "mgl",
        20.0,
        "N*m",
        "weight times the pivot-to-centre-of-mass distance (along body z)",
        Domain::NonNegative,
    ),
    spec(
        "tilt0",
        0.05,
        "rad",
        "initial rotation about lab x: Lambda0 = exp(hat(tilt0, 0, 0))",
        Domain::Finite,
    ),
    spec(
        "spin0",
        50.0,
        "rad/s",
        "initial body angular velocity about body z",
        Domain::Finite,
    ),
];

/// The `heavy-top` scene.
pub static HEAVY_TOP: SceneInfo = SceneInfo {
    name: "heavy-top",
    summary: "Lagrange top on a fixed pivot; defaults are Simo and Wong's hard case (H = 1269.975)",
    coordinates: &["qw", "qx", "qy", "qz"],
    parameters: &HEAVY_TOP_SPECS,
    conserved: &["energy", "Lz", "L . e3 (symmetric top)"],
    oracle: "energy H = 1269.975 conserved; Lz and the spin L . (R e3) conserved",
    problems: HEAVY_TOP_PROBLEMS,
    needs_dense_output: false,
    default_integrator: "vern9",
    default_step: 1e-3,
    default_error: 2.7e-12,
    default_t_end: 10.0,
    diagnostics: &["energy", "energy_rel_err", "Lx", "Ly", "Lz"],
    rate_names: &["omega_x", "omega_y", "omega_z"],
    not_on_group: "",
};

/// Which method for what on `heavy-top`; the measurements behind it are data
/// (`crate::recommendation`), written by `tumble work-precision heavy-top --recommend`.
static HEAVY_TOP_RECOMMENDED: [Recommendation; 4] = [
    Recommendation {
        purpose: "error 1e-4 … 1e-8 at t = 10 s",
        integrators: &["split-exact8", "vern8"],
        measure: Measure::ToError(1e-8),
        compared_with: &["dop853", "taylor"],
        reason: "kicks around the exact free flow: only gravity's part has an error",
    },
    Recommendation {
        purpose: "error 1e-8 … 1e-12",
        integrators: &["taylor", "split-exact8"],
        measure: Measure::ToError(1e-12),
        compared_with: &["vern9", "dop853"],
        reason: "taylor: order and step from the tolerance, coefficients by recursion, no stages",
    },
    Recommendation {
        purpose: "error 1e-12 … 1e-14",
        integrators: &["taylor"],
        measure: Measure::ToError(1e-14),
        compared_with: &["split-exact8", "vern9"],
        reason: "order and step from the tolerance, coefficients by recursion, no stages",
    },
    Recommendation {
        purpose: "energy over 10^6 steps and more",
        integrators: &["split6", "lgvi6"],
        measure: Measure::LongRun,
        compared_with: &["vern9"],
        reason: "symplectic; lgvi6 keeps L·e3 exact",
    },
];

/// Runs `heavy-top`.
#[derive(Debug, Clone, Copy, Default)]
pub struct HeavyTopScene;

impl HeavyTopScene {
    /// The top and its initial state.
    ///
    /// # Errors
    /// Invalid parameters (non-physical inertia).
    pub fn top_and_state(params: &Params) -> Result<(HeavyTop, RigidBodyState), SceneError> {
        let moments = Vector3::new(params.get("I1")?, params.get("I2")?, params.get("I3")?);
        let body = inertia_body(moments)?;
        let top = HeavyTop::new(body, params.get("mgl")?, Vector3::z())?;
        let r0 = exp(&Vector3::new(params.get("tilt0")?, 0.0, 0.0));
        let w0 = Vector3::new(0.0, 0.0, params.get("spin0")?);
        let m0 = body.inertia() * w0;
        Ok((top, RigidBodyState::new(&r0, m0)))
    }
}

impl Scene for HeavyTopScene {
    fn info(&self) -> &'static SceneInfo {
        &HEAVY_TOP
    }

    /// The symmetric top's axis and disk.
    fn drawing(&self, _params: &Params) -> Option<Result<Drawing, SceneError>> {
        Some(Ok(Drawing::symmetric_top()))
    }

    fn recommendations(&self) -> &'static [Recommendation] {
        &HEAVY_TOP_RECOMMENDED
    }

    fn initial_rate(&self, params: &Params) -> Option<Result<f64, SceneError>> {
        Some(params.get("spin0").map(f64::abs))
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let info = self.info();
        let (top, s0) = Self::top_and_state(params)?;
        run_rigid(
            info,
            top,
            None,
            &TaylorHeavyTop::new(&top),
            s0,
            None,
            Matrix3::identity(),
            plan,
            recorder,
        )
    }
}
