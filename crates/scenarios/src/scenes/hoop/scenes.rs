//! The `driven-hoop` and `spinning-hoop` scenes: their parameters, what they document, the
//! methods they recommend, and how they run on the models of the parent module.

use std::f64::consts::FRAC_PI_2;

use nalgebra::{SVector, Vector3};
use tumble_integrators::ProblemKind;

use super::{
    DrivenHoop, HoopParams, SpinningHoop, SpinningHoopHamiltonian, TaylorDrivenHoop,
    TaylorSpinningHoop, hoop_angular_momentum,
};
use crate::drawing::{Drawing, Motion};
use crate::error::SceneError;
use crate::params::{Domain, ParamSpec, Params};
use crate::recommendation::Measure;
use crate::scene::{
    Guide, Recommendation, Recorder, RunPlan, RunSummary, Scene, SceneInfo, run_hamiltonian,
    run_taylor_vector, run_vector,
};

/// Parameters shared by the hoop scenes, with their defaults.
const fn hoop_specs<const K: usize>(extra: [ParamSpec; K]) -> [ParamSpec; K] {
    extra
}

const M_SPEC: ParamSpec = ParamSpec {
    name: "M",
    default: 1.0,
    unit: "kg",
    description: "hoop mass",
    domain: Domain::Positive,
};
const A_SPEC: ParamSpec = ParamSpec {
    name: "a",
    default: 1.0,
    unit: "m",
    description: "hoop radius",
    domain: Domain::Positive,
};
const G_SPEC: ParamSpec = ParamSpec {
    name: "g",
    default: 9.81,
    unit: "m/s^2",
    description: "gravitational acceleration (lab z up)",
    domain: Domain::NonNegative,
};
const ALPHA_DOT0_SPEC: ParamSpec = ParamSpec {
    name: "alpha_dot0",
    default: 0.0,
    unit: "rad/s",
    description: "initial rate of the bead along the hoop",
    domain: Domain::Finite,
};

/// The fastest rate of a hoop scene's initial state (an upper estimate): the spin (parameter
/// `spin`) and the bead's rate added to the bead's pendulum frequency `√(g/a)` — each largest
/// at an end of any interval of its parameter, as sweeps need ([`Scene::initial_rate`]).
pub(crate) fn hoop_rate(params: &Params, spin: &str) -> Result<f64, SceneError> {
    let pendulum = (params.get("g")? / params.get("a")?).sqrt();
    Ok(params.get(spin)?.abs() + params.get("alpha_dot0")?.abs() + pendulum)
}

fn hoop_params(params: &Params) -> Result<HoopParams, SceneError> {
    Ok(HoopParams::new(
        params.get("M")?,
        params.get("m")?,
        params.get("a")?,
        params.get("g")?,
    )?)
}

static DRIVEN_SPECS: [ParamSpec; 7] = hoop_specs([
    M_SPEC,
    ParamSpec {
        name: "m",
        default: 0.1,
        unit: "kg",
        description: "bead mass",
        domain: Domain::NonNegative,
    },
    A_SPEC,
    G_SPEC,
    ParamSpec {
        name: "omega",
        default: 4.429_446_918_875_717,
        unit: "rad/s",
        description: "drive rate about lab z (default sqrt(2g/a): off-axis equilibrium at 60 deg)",
        domain: Domain::Finite,
    },
    ParamSpec {
        name: "alpha0",
        default: 0.5,
        unit: "rad",
        description: "initial bead angle from the bottom of the hoop",
        domain: Domain::Finite,
    },
    ALPHA_DOT0_SPEC,
]);

/// The `driven-hoop` scene.
pub static DRIVEN_HOOP: SceneInfo = SceneInfo {
    name: "driven-hoop",
    summary: "bead on a vertical hoop spun at constant omega about the lab vertical",
    coordinates: &["alpha"],
    parameters: &DRIVEN_SPECS,
    conserved: &["Jacobi integral (energy in the rotating frame)"],
    oracle: "alpha'' = (omega^2 cos alpha - g/a) sin alpha; cos alpha* = g/(a omega^2); \
             small oscillations Omega^2 = g/a - omega^2 (bottom), omega^2 - g^2/(a^2 omega^2) (alpha*)",
    problems: &[
        ProblemKind::Separable,
        ProblemKind::Split,
        ProblemKind::Ode,
        ProblemKind::TaylorSeries,
    ],
    needs_dense_output: false,
    default_integrator: "gauss8",
    default_step: 0.01,
    default_error: 4.1e-16,
    default_t_end: 10.0,
    diagnostics: &["energy", "energy_rel_err", "Lx", "Ly", "Lz", "tilt"],
    rate_names: &[],
    not_on_group: "",
};

/// Which method for what on `driven-hoop`; the measurements behind it are data
/// (`crate::recommendation`), written by `tumble work-precision driven-hoop --recommend`.
static DRIVEN_HOOP_RECOMMENDED: [Recommendation; 3] = [
    Recommendation {
        purpose: "error 1e-4 … 1e-8 at t = 10 s",
        integrators: &["vern9", "vern8"],
        measure: Measure::ToError(1e-8),
        compared_with: &["dop853"],
        reason: "",
    },
    Recommendation {
        purpose: "error 1e-8 … 1e-12",
        integrators: &["vern9"],
        measure: Measure::ToError(1e-12),
        compared_with: &["vern8", "dop853"],
        reason: "",
    },
    Recommendation {
        purpose: "Jacobi integral over 10^6 steps and more",
        integrators: &["kahan-li8", "sofroniou-spaletta10"],
        measure: Measure::LongRun,
        compared_with: &["vern9"],
        reason: "symplectic compositions of Verlet on the separable model: the Jacobi integral stays bounded",
    },
];

/// Runs `driven-hoop`.
#[derive(Debug, Clone, Copy, Default)]
pub struct DrivenHoopScene;

impl Scene for DrivenHoopScene {
    fn fixed_columns(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "tilt",
            "the hoop stands vertical, so its tilt is 0 by construction",
        )]
    }

    fn info(&self) -> &'static SceneInfo {
        &DRIVEN_HOOP
    }

    /// The hoop in its vertical plane turned at `omega`, the bead on it.
    fn drawing(&self, params: &Params) -> Option<Result<Drawing, SceneError>> {
        Some(params.get("a").and_then(|a| {
            let omega = Some(params.get("omega")?);
            Ok(Drawing::hoop(
                a,
                Motion::VerticalPlane { omega },
                Motion::BeadVertical { a, omega },
            ))
        }))
    }

    fn recommendations(&self) -> &'static [Recommendation] {
        &DRIVEN_HOOP_RECOMMENDED
    }

    fn initial_rate(&self, params: &Params) -> Option<Result<f64, SceneError>> {
        Some(hoop_rate(params, "omega"))
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let info = self.info();
        let scene = DrivenHoop::new(hoop_params(params)?, params.get("omega")?)?;
        let y0 = SVector::<f64, 2>::new(params.get("alpha0")?, params.get("alpha_dot0")?);
        let columns = info.columns().len();
        let row = |t: f64, y: &SVector<f64, 2>, out: &mut [f64]| {
            let angles = Vector3::new(scene.omega * t, FRAC_PI_2, 0.0);
            let rates = Vector3::new(scene.omega, 0.0, 0.0);
            let l = hoop_angular_momentum(&scene.hoop, &angles, &rates, y[0], y[1]);
            out[0] = t;
            out[1] = y[0];
            out[2] = y[1];
            out[3] = scene.energy(y[0], y[1]);
            out[4] = scene.energy_magnitude(y[1]);
            out[5] = l.x;
            out[6] = l.y;
            out[7] = l.z;
            out[8] = 0.0;
        };
        match plan.kind {
            // The separable model's state (α, p) per unit m a² is the ODE's (α, α̇).
            ProblemKind::Separable | ProblemKind::Split => {
                run_hamiltonian(&scene, y0, plan, columns, 3, row, recorder)
            }
            ProblemKind::TaylorSeries => run_taylor_vector(
                &TaylorDrivenHoop::new(&scene),
                y0,
                plan,
                columns,
                3,
                row,
                &mut [],
                recorder,
            ),
            _ => run_vector(&scene, y0, plan, columns, 3, row, &mut [], recorder),
        }
    }
}

static SPINNING_SPECS: [ParamSpec; 7] = hoop_specs([
    M_SPEC,
    ParamSpec {
        name: "m",
        default: 0.2,
        unit: "kg",
        description: "bead mass",
        domain: Domain::NonNegative,
    },
    ParamSpec {
        name: "a",
        default: 0.4,
        unit: "m",
        description: "hoop radius",
        domain: Domain::Positive,
    },
    G_SPEC,
    ParamSpec {
        name: "omega0",
        default: 5.0,
        unit: "rad/s",
        description: "initial spin of the hoop about the lab vertical (phi_dot)",
        domain: Domain::Finite,
    },
    ParamSpec {
        name: "alpha0",
        default: 3.1,
        unit: "rad",
        description: "initial bead angle from the bottom of the hoop (pi: the top)",
        domain: Domain::Finite,
    },
    ALPHA_DOT0_SPEC,
]);

/// The `spinning-hoop` scene.
pub static SPINNING_HOOP: SceneInfo = SceneInfo {
    name: "spinning-hoop",
    summary: "bead on a vertical hoop that turns freely about the lab vertical",
    coordinates: &["phi", "alpha"],
    parameters: &SPINNING_SPECS,
    conserved: &["energy", "Lz = (M a^2/2 + m a^2 sin^2 alpha) phi_dot"],
    oracle: "M=1, a=0.4, m=0.2, phi_dot=5 with the bead at the top gives phi_dot = 25/6 at 45 deg from the top",
    problems: &[
        ProblemKind::Separable,
        ProblemKind::Split,
        ProblemKind::Ode,
        ProblemKind::TaylorSeries,
    ],
    needs_dense_output: false,
    default_integrator: "gauss8",
    default_step: 0.01,
    default_error: 1.8e-13,
    default_t_end: 10.0,
    diagnostics: &["energy", "energy_rel_err", "Lx", "Ly", "Lz", "tilt"],
    rate_names: &[],
    not_on_group: "",
};

/// Which method for what on `spinning-hoop`; the measurements behind it are data
/// (`crate::recommendation`), written by `tumble work-precision spinning-hoop --recommend`.
static SPINNING_HOOP_RECOMMENDED: [Recommendation; 3] = [
    Recommendation {
        purpose: "error 1e-4 … 1e-8 at t = 10 s",
        integrators: &["vern9", "vern8"],
        measure: Measure::ToError(1e-8),
        compared_with: &["dop853"],
        reason: "",
    },
    Recommendation {
        purpose: "error 1e-8 … 1e-12",
        integrators: &["kahan-li8", "gauss10"],
        measure: Measure::ToError(1e-12),
        compared_with: &["gauss12", "vern9", "dop853"],
        reason: "",
    },
    Recommendation {
        purpose: "energy over 10^6 steps and more",
        integrators: &["kahan-li8", "gauss10"],
        measure: Measure::LongRun,
        compared_with: &["vern9"],
        reason: "symplectic; kahan-li8 integrates the Routh-reduced model, on which L_z is exact",
    },
];

/// The critical spin `√(g/a)` of a hoop map whose first axis is the initial spin `omega0`, with
/// `g` and `a` fixed at `params`: below it the bottom of a spinning hoop is the bead's only
/// stable position, above it the bead has a relative equilibrium off the bottom.
pub(crate) fn critical_spin(params: &Params, axes: &[&str]) -> Option<f64> {
    if axes.first() != Some(&"omega0") {
        return None;
    }
    let fixed = |n: &str| (!axes.contains(&n)).then(|| params.get(n).ok()).flatten();
    let w = (fixed("g")? / fixed("a")?).sqrt();
    (w.is_finite() && w > 0.0).then_some(w)
}

/// The critical spin as a map guide.
pub(crate) fn critical_spin_guide(w: f64) -> Guide {
    Guide::Vertical {
        x: w,
        label: " √(g/a)".to_string(),
    }
}

/// Runs `spinning-hoop`.
#[derive(Debug, Clone, Copy, Default)]
pub struct SpinningHoopScene;

impl Scene for SpinningHoopScene {
    fn fixed_columns(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "tilt",
            "the hoop stands vertical, so its tilt is 0 by construction",
        )]
    }

    fn info(&self) -> &'static SceneInfo {
        &SPINNING_HOOP
    }

    /// The hoop in its vertical plane at the azimuth `phi`, the bead on it.
    fn drawing(&self, params: &Params) -> Option<Result<Drawing, SceneError>> {
        Some(params.get("a").map(|a| {
            let omega = None;
            Drawing::hoop(
                a,
                Motion::VerticalPlane { omega },
                Motion::BeadVertical { a, omega },
            )
        }))
    }

    fn recommendations(&self) -> &'static [Recommendation] {
        &SPINNING_HOOP_RECOMMENDED
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
        let scene = SpinningHoop {
            hoop: hoop_params(params)?,
        };
        let y0 = SVector::<f64, 4>::new(
            0.0,
            params.get("alpha0")?,
            params.get("omega0")?,
            params.get("alpha_dot0")?,
        );
        let columns = info.columns().len();
        let row = move |t: f64, y: &SVector<f64, 4>, out: &mut [f64]| {
            let angles = Vector3::new(y[0], FRAC_PI_2, 0.0);
            let rates = Vector3::new(y[2], 0.0, 0.0);
            let l = hoop_angular_momentum(&scene.hoop, &angles, &rates, y[1], y[3]);
            out[..5].copy_from_slice(&[t, y[0], y[1], y[2], y[3]]);
            out[5] = scene.energy(y[1], y[2], y[3]);
            out[6] = scene.energy_magnitude(y[1], y[2], y[3]);
            out[7] = l.x;
            out[8] = l.y;
            out[9] = l.z;
            out[10] = 0.0;
        };
        match plan.kind {
            ProblemKind::Separable | ProblemKind::Split => {
                // State (α, L_z, α̇, −φ); rows in the scene's (φ, α, φ̇, α̇).
                let model = SpinningHoopHamiltonian { hoop: scene.hoop };
                run_hamiltonian(
                    &model,
                    model.from_rates(&y0),
                    plan,
                    columns,
                    5,
                    |t, y, out| row(t, &model.to_rates(y), out),
                    recorder,
                )
            }
            ProblemKind::TaylorSeries => run_taylor_vector(
                &TaylorSpinningHoop::new(&scene),
                y0,
                plan,
                columns,
                5,
                row,
                &mut [],
                recorder,
            ),
            _ => run_vector(&scene, y0, plan, columns, 5, row, &mut [], recorder),
        }
    }

    fn map_guides(&self, params: &Params, axes: &[&str], _x_range: (f64, f64)) -> Vec<Guide> {
        critical_spin(params, axes)
            .map(critical_spin_guide)
            .into_iter()
            .collect()
    }
}
