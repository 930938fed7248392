//! `coriolis-drop`: a body dropped from rest in a frame rotating with the Earth.
//!
//! # Model
//!
//! Coordinates `(x, y, z)`: east, north, up, in a local frame at colatitude `θ` that rotates with
//! the Earth at `ω = Ω (0, sin θ, cos θ)` (frame components). Per unit mass, the Lagrangian in the
//! rotating frame is `L = ½ |ṙ + ω × r|² − g z`; its Euler–Lagrange equations are Newton's law
//! with the Coriolis and centrifugal forces, `r̈ = −g ẑ − 2 ω × ṙ − ω × (ω × r)` (`g` is the
//! locally measured gravity, which already contains the centrifugal term of the frame's origin).
//! The Jacobi integral `½|ṙ|² + g z − ½|ω × r|²` is conserved.
//!
//! # Oracle
//!
//! Released at rest from height `h`, the body lands `x = Ω sin θ (2h)^{3/2} / (3 √g)` to the east
//! (to first order in Ω): 2.2 cm for `h = 100 m` at the equator. The run ends at the landing
//! (a terminal event at `z = 0`).

use std::f64::consts::FRAC_PI_2;

use nalgebra::{RealField, SVector, Vector3};
use tumble_integrators::taylor::{TaylorError, check_finite};
use tumble_integrators::{Action, Direction, Event, Ode, ProblemKind, TaylorSystem};
use tumble_kinematics::frames::{EARTH_ANGULAR_SPEED, RotatingFrame, earth_rotation_enu};

use crate::error::SceneError;
use crate::lagrangian::Lagrangian;
use crate::params::{Domain, ParamSpec, Params};
use crate::recommendation::Measure;
use crate::scene::{
    Recommendation, Recorder, RunPlan, RunSummary, Scene, SceneInfo, run_taylor_vector, run_vector,
};

/// The drop in the rotating frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoriolisDrop {
    /// The frame's angular velocity (frame components, rad/s).
    pub omega: Vector3<f64>,
    /// Local gravity (m/s²).
    pub g: f64,
}

impl CoriolisDrop {
    /// The drop at colatitude `colatitude` on a planet turning at `angular_speed`.
    #[must_use]
    pub fn new(angular_speed: f64, colatitude: f64, g: f64) -> Self {
        CoriolisDrop {
            omega: earth_rotation_enu(angular_speed, colatitude),
            g,
        }
    }

    /// The Jacobi integral per unit mass, `½|ṙ|² + g z − ½|ω × r|²`.
    #[must_use]
    pub fn jacobi_integral(&self, r: &Vector3<f64>, v: &Vector3<f64>) -> f64 {
        0.5 * v.norm_squared() + self.g * r.z - 0.5 * self.omega.cross(r).norm_squared()
    }

    /// The magnitude of the Jacobi integral's terms, `½|v|² + g|z| + ½|ω × r|²` (the energy
    /// scale of [`crate::scene::run_vector`]).
    #[must_use]
    pub fn jacobi_magnitude(&self, r: &Vector3<f64>, v: &Vector3<f64>) -> f64 {
        0.5 * v.norm_squared() + (self.g * r.z).abs() + 0.5 * self.omega.cross(r).norm_squared()
    }
}

impl Lagrangian<3> for CoriolisDrop {
    fn lagrangian<D: RealField + Copy>(&self, _t: D, q: &SVector<D, 3>, qd: &SVector<D, 3>) -> D {
        let w: Vector3<D> = self.omega.map(nalgebra::convert);
        let v = qd + w.cross(q);
        v.norm_squared() * nalgebra::convert::<f64, D>(0.5)
            - q[2] * nalgebra::convert::<f64, D>(self.g)
    }
}

/// Hand-written right-hand side, state `(x, y, z, ẋ, ẏ, ż)`, through the kinematics crate's
/// rotating-frame forces.
impl Ode<SVector<f64, 6>> for CoriolisDrop {
    fn rhs(&self, _t: f64, y: &SVector<f64, 6>, dy: &mut SVector<f64, 6>) {
        let r = Vector3::new(y[0], y[1], y[2]);
        let v = Vector3::new(y[3], y[4], y[5]);
        let a = RotatingFrame::uniform(self.omega).relative_acceleration(
            &Vector3::new(0.0, 0.0, -self.g),
            &r,
            &v,
        );
        dy[0] = v.x;
        dy[1] = v.y;
        dy[2] = v.z;
        dy[3] = a.x;
        dy[4] = a.y;
        dy[5] = a.z;
    }
}

/// The drop's equations as a [`TaylorSystem`] on `(r, ṙ)`: linear, so the coefficients are
/// `(k + 1) rₖ₊₁ = ṙₖ` and `(k + 1) ṙₖ₊₁ = −2 ω × ṙₖ − ω × (ω × rₖ)`, plus `(0, 0, −g)` at
/// order 0 (Moore 1966; the right-hand side of [`CoriolisDrop`]).
#[derive(Debug, Clone, Copy)]
pub struct TaylorCoriolisDrop(pub CoriolisDrop);

impl TaylorSystem for TaylorCoriolisDrop {
    fn dim(&self) -> usize {
        6
    }

    fn coefficients(
        &self,
        _t0: f64,
        x0: &[f64],
        order: usize,
        coeffs: &mut [f64],
    ) -> Result<(), TaylorError> {
        let w = self.0.omega;
        coeffs[..6].copy_from_slice(&x0[..6]);
        for k in 0..order {
            let at = k * 6;
            let r = Vector3::new(coeffs[at], coeffs[at + 1], coeffs[at + 2]);
            let v = Vector3::new(coeffs[at + 3], coeffs[at + 4], coeffs[at + 5]);
            let gravity = if k == 0 { -self.0.g } else { 0.0 };
            let a = Vector3::new(0.0, 0.0, gravity) - 2.0 * w.cross(&v) - w.cross(&w.cross(&r));
            let scale = 1.0 / (k + 1) as f64;
            let next = [v.x, v.y, v.z, a.x, a.y, a.z];
            for (i, x) in next.iter().enumerate() {
                coeffs[at + 6 + i] = x * scale;
            }
        }
        check_finite(coeffs, 6, order)
    }
}

static SPECS: [ParamSpec; 4] = [
    ParamSpec {
        name: "h",
        default: 100.0,
        unit: "m",
        description: "release height",
        domain: Domain::Positive,
    },
    ParamSpec {
        name: "g",
        default: 9.81,
        unit: "m/s^2",
        description: "local gravitational acceleration",
        domain: Domain::Positive,
    },
    ParamSpec {
        name: "colatitude",
        default: FRAC_PI_2,
        unit: "rad",
        description: "colatitude of the site (pi/2: the equator)",
        domain: Domain::Finite,
    },
    ParamSpec {
        name: "omega_earth",
        default: EARTH_ANGULAR_SPEED,
        unit: "rad/s",
        description: "the planet's angular speed",
        domain: Domain::Finite,
    },
];

/// The `coriolis-drop` scene.
pub static CORIOLIS_DROP: SceneInfo = SceneInfo {
    name: "coriolis-drop",
    summary: "a body dropped from rest in a frame rotating with the Earth lands east of its release point",
    coordinates: &["x", "y", "z"],
    parameters: &SPECS,
    conserved: &["Jacobi integral 1/2 |v|^2 + g z - 1/2 |omega x r|^2 (per unit mass)"],
    oracle: "lands x = omega sin(colatitude) (2h)^(3/2) / (3 sqrt(g)) east: 2.2 cm from 100 m at the equator",
    problems: &[ProblemKind::Ode, ProblemKind::TaylorSeries],
    needs_dense_output: true,
    default_integrator: "dop853",
    default_step: 1e-3,
    default_error: 4.0e-14,
    default_t_end: 60.0,
    diagnostics: &["energy", "energy_rel_err"],
    rate_names: &[],
    not_on_group: "",
};

/// Which method for what on `coriolis-drop`; the measurements behind it are data
/// (`crate::recommendation`), written by `tumble work-precision coriolis-drop --recommend`.
static CORIOLIS_DROP_RECOMMENDED: [Recommendation; 1] = [Recommendation {
    purpose: "any accuracy",
    integrators: &["rk4", "gauss8"],
    measure: Measure::ToError(1e-12),
    compared_with: &["dop853"],
    reason: "the fall is nearly a polynomial in t",
}];

/// Runs `coriolis-drop` until the body lands (or the horizon).
#[derive(Debug, Clone, Copy, Default)]
pub struct CoriolisDropScene;

impl Scene for CoriolisDropScene {
    fn info(&self) -> &'static SceneInfo {
        &CORIOLIS_DROP
    }

    fn recommendations(&self) -> &'static [Recommendation] {
        &CORIOLIS_DROP_RECOMMENDED
    }

    fn initial_rate(&self, params: &Params) -> Option<Result<f64, SceneError>> {
        Some(params.get("omega_earth").map(f64::abs))
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let info = self.info();
        let model = CoriolisDrop::new(
            params.get("omega_earth")?,
            params.get("colatitude")?,
            params.get("g")?,
        );
        let mut y0 = SVector::<f64, 6>::zeros();
        y0[2] = params.get("h")?;
        let mut events = [Event::new(
            |_t, y: &SVector<f64, 6>| y[2],
            Direction::Falling,
            Action::Terminate,
        )];
        let row = |t: f64, y: &SVector<f64, 6>, out: &mut [f64]| {
            out[0] = t;
            out[1..7].copy_from_slice(y.as_slice());
            let r = Vector3::new(y[0], y[1], y[2]);
            let v = Vector3::new(y[3], y[4], y[5]);
            out[7] = model.jacobi_integral(&r, &v);
            out[8] = model.jacobi_magnitude(&r, &v);
        };
        let columns = info.columns().len();
        if plan.kind == ProblemKind::TaylorSeries {
            return run_taylor_vector(
                &TaylorCoriolisDrop(model),
                y0,
                plan,
                columns,
                7,
                row,
                &mut events,
                recorder,
            );
        }
        run_vector(&model, y0, plan, columns, 7, row, &mut events, recorder)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::taylor_check::check;

    #[test]
    fn coriolis_drop_coefficients_follow_its_right_hand_side_and_flow() {
        // A fast frame, so that the Coriolis and centrifugal terms weigh in every coefficient.
        let model = CoriolisDrop::new(0.7, 0.8, 9.81);
        let f = |y: &SVector<f64, 6>| {
            let mut dy = SVector::zeros();
            model.rhs(0.0, y, &mut dy);
            dy
        };
        let x0 = SVector::from([1.0, -2.0, 100.0, 0.5, 0.3, -4.0]);
        check(&TaylorCoriolisDrop(model), f, x0);
    }
}
