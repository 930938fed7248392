//! `free-hoop`: the article's question — the hoop free to rotate about its fixed centre in every
//! direction, the bead sliding on it. It tilts.
//!
//! # Model: SO(3) × ℝ
//!
//! The configuration is the hoop's orientation `R ∈ SO(3)` (body → lab) and the bead angle `α`
//! (geometry in [`super::hoop`]). As a rigid body coupled to one coordinate
//! ([`tumble_integrators::rigid::CoupledLagrangian`]):
//! `L = ½ Ωᵀ J(α) Ω + Ωᵀ B(α) α̇ + ½ M α̇² − V(R, α)` with
//! `J(α) = diag(Ma²/2, Ma²/2, Ma²) + m (|r|² 𝟙 − r rᵀ)`, `B = m r × ∂r/∂α`, `M = m a²`,
//! `V = m g (R r)_z`, `r = a (cos α, sin α, 0)`. The state is `(R, Π, α, p_α)` with `Π` the body
//! angular momentum about the pivot. No chart: the hoop may pass through horizontal. The model
//! gives the derivatives its integrators use — `∂J/∂α`, `∂²J/∂α²` (`B` and `M` are constant), the
//! moment of gravity and `∂V/∂α` — in closed form (tests check them against automatic
//! differentiation of the Lagrangian), so that its right-hand side and its variational step run
//! in plain `f64`.
//!
//! The coupled Lie-group variational integrator (`lgvi`: symplectic, symmetric, order 2) runs the
//! model on SO(3) × ℝ and conserves `L_z` to round-off (gravity is invariant under rotations
//! about the vertical). Vector-space methods (`rk4`, `dp5`, `dop853`, `gauss2`…`gauss12`) run the
//! flattened continuous equations `(R, Π, α, p_α) ∈ ℝ¹⁴`; Gauss–Legendre keeps `RᵀR = 𝟙` (a
//! quadratic invariant) to round-off. The default run is Gauss–Legendre 8 at dt = 0.01 s
//! (error 7e-16 at t = 10 s against the reference; the LGVI at dt = 1e-3 is 7e-5 off).
//!
//! Its AD twin and cross-check is the Euler-angle model [`super::hoop::FreeHoopEuler`].
//!
//! # Output
//!
//! Coordinates `qw, qx, qy, qz` (the unit quaternion of `R`, `w ≥ 0` at the start and the sign
//! continuous along the run) and `alpha`; rates
//! `omega_x, omega_y, omega_z` (body angular velocity) and `alpha_dot`; diagnostics `energy`,
//! `energy_rel_err`, `Lx, Ly, Lz` (lab, about the pivot) and `tilt` (`asin |n_z|`, `n = R e_z`).
//!
//! # Conserved
//!
//! Energy and `L_z`; with `g = 0` all of `L`, and time scales with `1/ω₀`.

use std::f64::consts::FRAC_PI_2;

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use tumble_integrators::rigid::{
    CoupledLagrangian, CoupledState, CoupledVectorField, KineticBlocks, KineticJet, LieVectorField,
    Scalar, coupled_energy, coupled_state_from_velocities, coupled_velocities,
};
use tumble_integrators::{Ode, ProblemKind};
use tumble_kinematics::EulerConvention;
use tumble_kinematics::so3::hat;

use super::hoop::{HoopParams, critical_spin, critical_spin_guide, hoop_rate, tilt_from_normal};
use crate::dispatch;
use crate::drawing::{Drawing, Motion};
use crate::error::SceneError;
use crate::params::{Domain, ParamSpec, Params};
use crate::recommendation::Measure;
use crate::scene::{
    Guide, Recommendation, Recorder, RowObserver, RunPlan, RunSummary, Scene, SceneInfo,
    continuous_quaternion, run_vector,
};

/// The free hoop on SO(3) × ℝ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeHoop {
    /// Shared hoop parameters.
    pub hoop: HoopParams,
}

impl CoupledLagrangian<1> for FreeHoop {
    fn kinetic<D: Scalar>(&self, q: &SVector<D, 1>) -> KineticBlocks<D, 1> {
        let p = &self.hoop;
        let a = D::from(p.radius);
        let m = D::from(p.bead_mass);
        let (s, c) = (q[0].sin(), q[0].cos());
        let r = Vector3::new(a * c, a * s, D::from(0.0));
        let dr = Vector3::new(-(a * s), a * c, D::from(0.0));
        let hoop = Matrix3::from_diagonal(&Vector3::new(
            D::from(p.diameter_moment()),
            D::from(p.diameter_moment()),
            D::from(p.normal_moment()),
        ));
        let bead = (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * m;
        KineticBlocks {
            rotational: hoop + bead,
            coupling: SMatrix::<D, 3, 1>::from_column_slice((r.cross(&dr) * m).as_slice()),
            internal: SMatrix::<D, 1, 1>::new(m * dr.norm_squared()),
        }
    }

    fn potential<D: Scalar>(&self, rotation: &Matrix3<D>, q: &SVector<D, 1>) -> D {
        let a = D::from(self.hoop.radius);
        let r = Vector3::new(a * q[0].cos(), a * q[0].sin(), D::from(0.0));
        (rotation * r).z * D::from(self.hoop.bead_mass * self.hoop.gravity)
    }

    /// Closed forms, with `e = (cos α, sin α, 0)`, `e' = (−sin α, cos α, 0)` and `μ = m a²`:
    /// `J = diag(Ma²/2, Ma²/2, Ma²) + μ (𝟙 − e eᵀ)`, `∂J/∂α = −μ (e' eᵀ + e e'ᵀ)`;
    /// `B = μ e × e' = (0, 0, μ)` and `M = μ`, both constant.
    fn kinetic_jet(&self, q: &SVector<f64, 1>) -> KineticJet<1> {
        let p = &self.hoop;
        let mu = p.bead_mass * p.radius * p.radius;
        let (s, c) = q[0].sin_cos();
        let (jd, jn) = (p.diameter_moment(), p.normal_moment());
        let rotational = Matrix3::new(
            jd + mu * s * s,
            -mu * c * s,
            0.0,
            -mu * c * s,
            jd + mu * c * c,
            0.0,
            0.0,
            0.0,
            jn + mu,
        );
        let (s2, c2) = (2.0 * s * c, c * c - s * s);
        let d_rotational = Matrix3::new(
            mu * s2,
            -mu * c2,
            0.0,
            -mu * c2,
            -mu * s2,
            0.0,
            0.0,
            0.0,
            0.0,
        );
        let coupling = SMatrix::<f64, 3, 1>::new(0.0, 0.0, mu);
        KineticJet {
            blocks: KineticBlocks {
                rotational,
                coupling,
                internal: SMatrix::<f64, 1, 1>::new(mu),
            },
            derivatives: [KineticBlocks {
                rotational: d_rotational,
                coupling: SMatrix::zeros(),
                internal: SMatrix::zeros(),
            }],
        }
    }

    /// Closed form: `∂²J/∂α² = 2μ [[cos 2α, sin 2α, 0], [sin 2α, −cos 2α, 0], [0, 0, 0]]`; `B`
    /// and `M` are constant.
    fn kinetic_hessian(&self, q: &SVector<f64, 1>) -> [[KineticBlocks<f64, 1>; 1]; 1] {
        let p = &self.hoop;
        let mu2 = 2.0 * p.bead_mass * p.radius * p.radius;
        let (s2, c2) = (2.0 * q[0]).sin_cos();
        [[KineticBlocks {
            rotational: Matrix3::new(
                mu2 * c2,
                mu2 * s2,
                0.0,
                mu2 * s2,
                -mu2 * c2,
                0.0,
                0.0,
                0.0,
                0.0,
            ),
            coupling: SMatrix::zeros(),
            internal: SMatrix::zeros(),
        }]]
    }

    /// Closed forms: with `z = Rᵀ e₃` (the vertical in body components), `V = m g a z·e`, the
    /// moment `−∂V/∂η = m g a (z × e)` and `∂V/∂α = m g a z·e'`.
    fn potential_derivatives(
        &self,
        rotation: &Matrix3<f64>,
        q: &SVector<f64, 1>,
    ) -> (Vector3<f64>, SVector<f64, 1>) {
        let k = self.hoop.bead_mass * self.hoop.gravity * self.hoop.radius;
        let (s, c) = q[0].sin_cos();
        let z = Vector3::new(rotation[(2, 0)], rotation[(2, 1)], rotation[(2, 2)]);
        (
            Vector3::new(-z.z * s, z.z * c, z.x * s - z.y * c) * k,
            SVector::<f64, 1>::new(k * (z.y * c - z.x * s)),
        )
    }
}

impl FreeHoop {
    /// The state with the hoop at ZYZ angles `(0, theta0, 0)` spinning at `omega0` about the lab
    /// vertical, the bead at `alpha0` moving at `alpha_dot0`.
    #[must_use]
    pub fn initial_state(
        &self,
        theta0: f64,
        omega0: f64,
        alpha0: f64,
        alpha_dot0: f64,
    ) -> CoupledState<1> {
        let conv = EulerConvention::ARTICLE;
        let angles = Vector3::new(0.0, theta0, 0.0);
        let rates = Vector3::new(omega0, 0.0, 0.0);
        let rotation = conv.to_rotation(&angles);
        let omega_body = conv.omega_body(&angles, &rates);
        coupled_state_from_velocities(
            self,
            rotation.matrix(),
            &omega_body,
            &SVector::<f64, 1>::new(alpha0),
            &SVector::<f64, 1>::new(alpha_dot0),
        )
    }

    /// The tilt `asin |n_z|` of a state (0: standing, π/2: horizontal).
    #[must_use]
    pub fn tilt(state: &CoupledState<1>) -> f64 {
        tilt_from_normal(&state.rotation.column(2).into_owned())
    }
}

/// Flattened state `(R column-major, Π, α, p_α)`.
pub type Flat = SVector<f64, 14>;

/// Flattens a state.
#[must_use]
pub fn flatten(s: &CoupledState<1>) -> Flat {
    let mut y = Flat::zeros();
    y.fixed_rows_mut::<9>(0)
        .copy_from_slice(s.rotation.as_slice());
    y.fixed_rows_mut::<3>(9).copy_from(&s.momentum);
    y[12] = s.q[0];
    y[13] = s.p[0];
    y
}

/// The state of a flattened vector.
#[must_use]
pub fn unflatten(y: &Flat) -> CoupledState<1> {
    CoupledState {
        rotation: Matrix3::from_column_slice(&y.as_slice()[..9]),
        momentum: Vector3::new(y[9], y[10], y[11]),
        q: SVector::<f64, 1>::new(y[12]),
        p: SVector::<f64, 1>::new(y[13]),
    }
}

/// The continuous equations of [`FreeHoop`] on `ℝ¹⁴`: `Ṙ = R hat Ω`, `(Π̇, α̇, ṗ)`.
#[derive(Debug, Clone, Copy)]
pub struct FlatFreeHoop(pub CoupledVectorField<FreeHoop, 1, 5>);

impl FlatFreeHoop {
    /// The flattened equations of `model`.
    ///
    /// # Errors
    /// Never for this model (the dimensions are fixed); kept for the API's sake.
    pub fn new(model: FreeHoop) -> Result<Self, SceneError> {
        Ok(FlatFreeHoop(CoupledVectorField::new(model)?))
    }
}

impl Ode<Flat> for FlatFreeHoop {
    fn rhs(&self, t: f64, y: &Flat, dy: &mut Flat) {
        let r = Matrix3::from_column_slice(&y.as_slice()[..9]);
        let v = SVector::<f64, 5>::from_column_slice(&y.as_slice()[9..]);
        let (xi, dv) = self.0.eval(t, &r, &v);
        let rd = r * hat(&xi);
        dy.fixed_rows_mut::<9>(0).copy_from_slice(rd.as_slice());
        dy.fixed_rows_mut::<5>(9).copy_from(&dv);
    }
}

/// Writes a row: t, quaternion (sign continuous along the run), α, body ω, α̇, energy,
/// (relative error slot), L, tilt.
pub(crate) fn write_row(
    model: &FreeHoop,
    t: f64,
    s: &CoupledState<1>,
    previous: &mut Option<nalgebra::Quaternion<f64>>,
    out: &mut [f64],
) {
    let q = continuous_quaternion(&s.rotation, previous);
    let (omega, qdot) = coupled_velocities(model, &s.q, &s.momentum, &s.p)
        .unwrap_or((Vector3::repeat(f64::NAN), SVector::<f64, 1>::new(f64::NAN)));
    let l = s.spatial_momentum();
    let energy = coupled_energy(model, s).unwrap_or(f64::NAN);
    // The energy scale's magnitude: T = ½(ω·m + α̇ p_α) plus the potential's amplitude m g a.
    let magnitude = 0.5 * (omega.dot(&s.momentum) + qdot.dot(&s.p)).abs()
        + model.hoop.bead_mass * model.hoop.gravity * model.hoop.radius;
    let values = [
        t,
        q.w,
        q.i,
        q.j,
        q.k,
        s.q[0],
        omega.x,
        omega.y,
        omega.z,
        qdot[0],
        energy,
        magnitude,
        l.x,
        l.y,
        l.z,
        FreeHoop::tilt(s),
    ];
    out.copy_from_slice(&values);
}

/// The final state at time `t` of a flattened run (`y`, from any integrator of
/// [`FlatFreeHoop`], a peer crate's included), as the scene's own run reports it for the
/// work–precision error (`tumble_studies::work_precision::state_error`): the coordinates
/// `qw, qx, qy, qz` (`w ≥ 0`; the error compares quaternions up to sign) and `alpha`, then
/// the rates `omega_x, omega_y, omega_z` (body) and `alpha_dot`.
#[must_use]
pub fn final_state(model: &FreeHoop, t: f64, y: &Flat) -> crate::scene::FinalState {
    let mut row = vec![0.0; FREE_HOOP.columns().len()];
    write_row(model, t, &unflatten(y), &mut None, &mut row);
    let n = FREE_HOOP.coordinates.len() + FREE_HOOP.rate_names.len();
    crate::scene::FinalState {
        t,
        values: row[1..=n].to_vec(),
    }
}

/// Column of the energy in a row.
const ENERGY_COLUMN: usize = 10;

static SPECS: [ParamSpec; 8] = [
    ParamSpec {
        name: "M",
        default: 1.0,
        unit: "kg",
        description: "hoop mass",
        domain: Domain::Positive,
    },
    ParamSpec {
        name: "m",
        default: 0.1,
        unit: "kg",
        description: "bead mass (positive: without a bead the hoop is a free body, and the bead \
                      angle has no dynamics)",
        domain: Domain::Positive,
    },
    ParamSpec {
        name: "a",
        default: 1.0,
        unit: "m",
        description: "hoop radius",
        domain: Domain::Positive,
    },
    ParamSpec {
        name: "g",
        default: 9.81,
        unit: "m/s^2",
        description: "gravitational acceleration (lab z up)",
        domain: Domain::NonNegative,
    },
    ParamSpec {
        name: "omega0",
        default: 4.0,
        unit: "rad/s",
        description: "initial spin of the hoop about the lab vertical",
        domain: Domain::Finite,
    },
    ParamSpec {
        name: "alpha0",
        default: 0.5,
        unit: "rad",
        description: "initial bead angle from the bottom of the hoop",
        domain: Domain::Finite,
    },
    ParamSpec {
        name: "alpha_dot0",
        default: 0.0,
        unit: "rad/s",
        description: "initial rate of the bead along the hoop",
        domain: Domain::Finite,
    },
    ParamSpec {
        name: "theta0",
        default: FRAC_PI_2,
        unit: "rad",
        description: "initial ZYZ angle theta of the hoop's normal from the vertical (pi/2: standing)",
        domain: Domain::Finite,
    },
];

/// The `free-hoop` scene.
pub static FREE_HOOP: SceneInfo = SceneInfo {
    name: "free-hoop",
    summary: "bead on a hoop free to rotate in every direction about its fixed centre: the hoop tilts",
    coordinates: &["qw", "qx", "qy", "qz", "alpha"],
    parameters: &SPECS,
    conserved: &["energy", "Lz", "all of L when g = 0"],
    oracle: "energy and Lz conserved (all of L when g = 0); agrees with the Euler-angle twin away from theta = 0, pi",
    problems: &[
        ProblemKind::CoupledRigidBody,
        ProblemKind::Ode,
        ProblemKind::TaylorSeries,
    ],
    needs_dense_output: false,
    default_integrator: "gauss8",
    default_step: 0.01,
    default_error: 7.3e-16,
    default_t_end: 10.0,
    diagnostics: &["energy", "energy_rel_err", "Lx", "Ly", "Lz", "tilt"],
    rate_names: &["omega_x", "omega_y", "omega_z", "alpha_dot"],
    not_on_group: "",
};

/// Which method for what on `free-hoop`; the measurements behind it are data
/// (`crate::recommendation`), written by `tumble work-precision free-hoop --recommend`.
static FREE_HOOP_RECOMMENDED: [Recommendation; 4] = [
    Recommendation {
        purpose: "error 1e-4 … 1e-8 at t = 10 s",
        integrators: &["vern8"],
        measure: Measure::ToError(1e-8),
        compared_with: &["dop853", "taylor"],
        reason: "",
    },
    Recommendation {
        purpose: "error 1e-8 … 1e-12",
        integrators: &["taylor", "vern9"],
        measure: Measure::ToError(1e-12),
        compared_with: &["vern8", "dop853"],
        reason: "taylor: order and step from the tolerance, coefficients by recursion, no stages",
    },
    Recommendation {
        purpose: "error 1e-12 … 1e-14",
        integrators: &["taylor"],
        measure: Measure::ToError(1e-14),
        compared_with: &["vern9"],
        reason: "order and step from the tolerance, coefficients by recursion, no stages",
    },
    Recommendation {
        purpose: "energy over 10^6 steps and more",
        integrators: &["gauss8", "lgvi6", "lie-gauss6"],
        measure: Measure::LongRun,
        compared_with: &["vern9"],
        reason: "symplectic; lgvi6 and lie-gauss6 are variational on the rotation group and keep L_z exact",
    },
];

/// Runs `free-hoop`.
#[derive(Debug, Clone, Copy, Default)]
pub struct FreeHoopScene;

impl FreeHoopScene {
    /// The model and initial state for `params`.
    ///
    /// # Errors
    /// Unknown or invalid parameters.
    pub fn model(params: &Params) -> Result<(FreeHoop, CoupledState<1>), SceneError> {
        let hoop = HoopParams::new(
            params.get("M")?,
            params.get("m")?,
            params.get("a")?,
            params.get("g")?,
        )?;
        let model = FreeHoop { hoop };
        let s0 = model.initial_state(
            params.get("theta0")?,
            params.get("omega0")?,
            params.get("alpha0")?,
            params.get("alpha_dot0")?,
        );
        Ok((model, s0))
    }
}

/// Runs the free hoop on SO(3) × ℝ with the plan's method (the coupled LGVI).
fn run_coupled(
    model: &FreeHoop,
    s0: CoupledState<1>,
    plan: &RunPlan,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, SceneError> {
    let mut state = s0;
    let mut observer = RowObserver::new(
        FREE_HOOP.columns().len(),
        ENERGY_COLUMN,
        plan,
        {
            let mut previous = None;
            move |t, s: &CoupledState<1>, out: &mut [f64]| {
                write_row(model, t, s, &mut previous, out)
            }
        },
        recorder,
    );
    let outcome = dispatch::run_coupled(model, &mut state, plan, &mut observer)?;
    observer.summary(&outcome)
}

impl Scene for FreeHoopScene {
    fn info(&self) -> &'static SceneInfo {
        &FREE_HOOP
    }

    /// The hoop turned by the rows' quaternion, the bead at `alpha` on it.
    fn drawing(&self, params: &Params) -> Option<Result<Drawing, SceneError>> {
        Some(
            params
                .get("a")
                .map(|a| Drawing::hoop(a, Motion::Quaternion, Motion::BeadFree { a })),
        )
    }

    fn recommendations(&self) -> &'static [Recommendation] {
        &FREE_HOOP_RECOMMENDED
    }

    /// The Euler–Poisson reduction ([`super::euler_poisson`]): the tilt, the bead, `ω`, the
    /// energy and `L_z` from `Γ = Rᵀ e_z`, `Π`, `α`, `p_α`.
    fn reduction(&self) -> Option<&'static crate::scene::Reduction> {
        Some(&super::euler_poisson::EULER_POISSON)
    }

    fn initial_rate(&self, params: &Params) -> Option<Result<f64, SceneError>> {
        Some(hoop_rate(params, "omega0"))
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let info = self.info();
        let (model, s0) = Self::model(params)?;
        if plan.kind == ProblemKind::CoupledRigidBody {
            return run_coupled(&model, s0, plan, recorder);
        }
        if plan.kind == ProblemKind::TaylorSeries {
            // The Taylor method on the hand-written coefficients (the reduction's, with the
            // other two rows of R).
            return crate::scene::run_taylor_vector(
                &super::euler_poisson::TaylorHoop::full(
                    super::euler_poisson::EulerPoissonHoop::new(&model),
                ),
                flatten(&s0),
                plan,
                info.columns().len(),
                ENERGY_COLUMN,
                {
                    let mut previous = None;
                    move |t, y, out| write_row(&model, t, &unflatten(y), &mut previous, out)
                },
                &mut [],
                recorder,
            );
        }
        let flat = FlatFreeHoop::new(model)?;
        run_vector(
            &flat,
            flatten(&s0),
            plan,
            info.columns().len(),
            ENERGY_COLUMN,
            {
                let mut previous = None;
                move |t, y, out| write_row(&model, t, &unflatten(y), &mut previous, out)
            },
            &mut [],
            recorder,
        )
    }

    /// The critical spin `√(g/a)` on a map over `omega0`; on a map of `omega0` against
    /// `alpha0`, also the bead's relative equilibrium on a hoop spun at `ω`,
    /// `cos α* = g/(a ω²)` (`ω > √(g/a)`): a bead released there at rest on the hoop stays
    /// there relative to the spinning hoop, so nothing tips the hoop — the map's valley of
    /// small tilt follows this curve.
    fn map_guides(&self, params: &Params, axes: &[&str], x_range: (f64, f64)) -> Vec<Guide> {
        let Some(critical) = critical_spin(params, axes) else {
            return Vec::new();
        };
        let mut guides = vec![critical_spin_guide(critical)];
        if axes.get(1) == Some(&"alpha0") {
            let end = x_range.1;
            let points = (0..=400)
                .map(|k| critical + (end - critical) * f64::from(k) / 400.0)
                .map(|w| (w, (critical * critical / (w * w)).acos()))
                .collect();
            guides.push(Guide::Curve {
                label: "cos α* = g/(a ω₀²)".to_string(),
                points,
            });
        }
        guides
    }
}
