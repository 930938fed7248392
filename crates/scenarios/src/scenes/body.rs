//! The rigid-body scenes with a body of the user's own (a scene file's `[body]` table): the
//! free body, the Dzhanibekov handle and the heavy top.
//!
//! # Frames
//!
//! The user's frame is the frame of the body's description (the mesh file's coordinates, the
//! shapes' and points' positions): the initial orientation (`phi0, theta0, psi0`, the article's
//! ZYZ angles of that frame in the lab, `R = Rz(φ) Ry(θ) Rz(ψ)`) and angular velocity
//! (`omega_x0, omega_y0, omega_z0`, body components in that frame) are given there, and the
//! rows report it: `qw … qz` is the orientation of the user's frame, `omega_*` are components in
//! it. Internally the body moves in its principal frame (a diagonal tensor, ascending moments):
//! `Q` (columns the principal axes in the user's frame, the ZYZ angles `frame_*`) maps one to
//! the other, `R_principal = R_user Q`, `ω_principal = Qᵀ ω_user`, and the rows map back.
//!
//! # Parameters
//!
//! The body's parameters (`I1, I2, I3`, `frame_*`; for the top `mass`, `cx, cy, cz`) are
//! computed from the `[body]` table; the initial state and `g` are ordinary parameters
//! (`[parameters]`, `--set`).

use nalgebra::{Rotation3, Vector3};
use tumble_integrators::rigid::{FreeRigidBody, HeavyTop, RigidBodyState, TaylorHeavyTop};
use tumble_kinematics::EulerConvention;

use super::rigid::{
    FREE_BODY_PROBLEMS, HEAVY_TOP_PROBLEMS, check_momentum, inertia_body, intermediate_of,
    run_rigid, spec,
};
use crate::error::SceneError;
use crate::params::{Domain, ParamSpec, Params};
use crate::scene::{Recorder, RunPlan, RunSummary, Scene, SceneInfo};

/// The parameters computed from a `[body]` table (a scene file may not set them in
/// `[parameters]`).
pub const BODY_PARAMETERS: &[&str] = &[
    "I1",
    "I2",
    "I3",
    "frame_phi",
    "frame_theta",
    "frame_psi",
    "mass",
    "cx",
    "cy",
    "cz",
];

macro_rules! body_specs {
    ($($extra:expr),* $(,)?) => {
        [
            spec("I1", 1.0, "kg*m^2", "smallest principal moment (from [body])", Domain::Positive),
            spec("I2", 2.0, "kg*m^2", "middle principal moment (from [body])", Domain::Positive),
            spec("I3", 3.0, "kg*m^2", "largest principal moment (from [body])", Domain::Positive),
            spec("frame_phi", 0.0, "rad", "ZYZ angle phi of the principal axes in the body's frame (from [body])", Domain::Finite),
            spec("frame_theta", 0.0, "rad", "ZYZ angle theta of the principal axes in the body's frame (from [body])", Domain::Finite),
            spec("frame_psi", 0.0, "rad", "ZYZ angle psi of the principal axes in the body's frame (from [body])", Domain::Finite),
            $($extra,)*
            spec("phi0", 0.0, "rad", "initial ZYZ angle phi of the body's frame", Domain::Finite),
            spec("theta0", 0.0, "rad", "initial ZYZ angle theta of the body's frame", Domain::Finite),
            spec("psi0", 0.0, "rad", "initial ZYZ angle psi of the body's frame", Domain::Finite),
            spec("omega_x0", 0.0, "rad/s", "initial angular velocity, x of the body's frame", Domain::Finite),
            spec("omega_y0", 0.0, "rad/s", "initial angular velocity, y of the body's frame", Domain::Finite),
            spec("omega_z0", 0.0, "rad/s", "initial angular velocity, z of the body's frame", Domain::Finite),
        ]
    };
}

static FREE_SPECS: [ParamSpec; 12] = body_specs!();

static TOP_SPECS: [ParamSpec; 17] = body_specs!(
    spec(
        "mass",
        1.0,
        "kg",
        "mass of the body (from [body])",
        Domain::Positive
    ),
    spec(
        "cx",
        0.0,
        "m",
        "centre of mass from the pivot, x of the body's frame (from [body])",
        Domain::Finite
    ),
    spec(
        "cy",
        0.0,
        "m",
        "centre of mass from the pivot, y of the body's frame (from [body])",
        Domain::Finite
    ),
    spec(
        "cz",
        0.0,
        "m",
        "centre of mass from the pivot, z of the body's frame (from [body])",
        Domain::Finite
    ),
    spec(
        "g",
        9.81,
        "m/s^2",
        "gravitational acceleration (lab -z)",
        Domain::NonNegative
    ),
);

/// `free-body` with a body from a scene file.
pub static FREE_BODY_FILE: SceneInfo = SceneInfo {
    name: "free-body",
    summary: "torque-free rigid body from a scene file's [body] table",
    coordinates: &["qw", "qx", "qy", "qz"],
    parameters: &FREE_SPECS,
    conserved: &["energy", "L (vector)", "|m| (Casimir)"],
    oracle: "exact solution by Jacobi elliptic functions (column exact_err)",
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

/// `dzhanibekov` with a body from a scene file.
pub static DZHANIBEKOV_FILE: SceneInfo = SceneInfo {
    name: "dzhanibekov",
    summary: "a body from a scene file's [body] table spun near its intermediate axis flips",
    oracle: "flip period = half the period of the exact solution (4K(k)/lambda)",
    default_integrator: "exact",
    default_step: 1e-3,
    default_error: 0.0,
    default_t_end: 10.0,
    ..FREE_BODY_FILE
};

/// `heavy-top` with a body from a scene file.
pub static HEAVY_TOP_FILE: SceneInfo = SceneInfo {
    name: "heavy-top",
    summary: "heavy top on a fixed pivot, body from a scene file's [body] table",
    coordinates: &["qw", "qx", "qy", "qz"],
    parameters: &TOP_SPECS,
    conserved: &["energy", "Lz"],
    oracle: "energy and Lz conserved",
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

/// Which rigid-body scene a `[body]` table feeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BodySceneKind {
    /// `free-body`.
    Free,
    /// `dzhanibekov`.
    Dzhanibekov,
    /// `heavy-top`: needs a pivot.
    HeavyTop,
}

/// A rigid-body scene whose body comes from a scene file.
#[derive(Debug, Clone, Copy)]
pub struct BodyScene(pub BodySceneKind);

/// The scene taking a `[body]` table for the built-in scene `name`, if it takes one.
#[must_use]
pub fn for_scene(name: &str) -> Option<&'static BodyScene> {
    static FREE: BodyScene = BodyScene(BodySceneKind::Free);
    static DZH: BodyScene = BodyScene(BodySceneKind::Dzhanibekov);
    static TOP: BodyScene = BodyScene(BodySceneKind::HeavyTop);
    match name {
        "free-body" => Some(&FREE),
        "dzhanibekov" => Some(&DZH),
        "heavy-top" => Some(&TOP),
        _ => None,
    }
}

fn triple(params: &Params, names: [&str; 3]) -> Result<Vector3<f64>, SceneError> {
    Ok(Vector3::new(
        params.get(names[0])?,
        params.get(names[1])?,
        params.get(names[2])?,
    ))
}

fn zyz(angles: &Vector3<f64>) -> Rotation3<f64> {
    EulerConvention::ARTICLE.to_rotation(angles)
}

/// The principal moments, `Q` (principal axes in the user's frame) and the initial state in the
/// principal frame: `R = R_user Q`, `m = I Qᵀ ω_user`.
fn principal_state(
    params: &Params,
) -> Result<(Vector3<f64>, Rotation3<f64>, RigidBodyState), SceneError> {
    let moments = triple(params, ["I1", "I2", "I3"])?;
    let q = zyz(&triple(params, ["frame_phi", "frame_theta", "frame_psi"])?);
    let r0 = zyz(&triple(params, ["phi0", "theta0", "psi0"])?) * q;
    let omega = q.inverse() * triple(params, ["omega_x0", "omega_y0", "omega_z0"])?;
    let m0 = moments.component_mul(&omega);
    Ok((moments, q, RigidBodyState::new(&r0, m0)))
}

impl BodyScene {
    /// The torque-free body in its principal frame, `Q`, and its initial state there.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn free_body_and_state(
        params: &Params,
    ) -> Result<(FreeRigidBody, Rotation3<f64>, RigidBodyState), SceneError> {
        let (moments, q, s0) = principal_state(params)?;
        Ok((inertia_body(moments)?, q, s0))
    }

    /// The top in its principal frame about the pivot, `Q`, and its initial state there.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn top_and_state(
        params: &Params,
    ) -> Result<(HeavyTop, Rotation3<f64>, RigidBodyState), SceneError> {
        let (moments, q, s0) = principal_state(params)?;
        let body = inertia_body(moments)?;
        let center = q.inverse() * triple(params, ["cx", "cy", "cz"])?;
        let weight = params.get("mass")? * params.get("g")?;
        Ok((HeavyTop::new(body, weight, center)?, q, s0))
    }
}

impl Scene for BodyScene {
    fn info(&self) -> &'static SceneInfo {
        match self.0 {
            BodySceneKind::Free => &FREE_BODY_FILE,
            BodySceneKind::Dzhanibekov => &DZHANIBEKOV_FILE,
            BodySceneKind::HeavyTop => &HEAVY_TOP_FILE,
        }
    }

    fn initial_rate(&self, params: &Params) -> Option<Result<f64, SceneError>> {
        Some(triple(params, ["omega_x0", "omega_y0", "omega_z0"]).map(|w| w.norm()))
    }

    fn simulate(
        &self,
        params: &Params,
        plan: &RunPlan,
        recorder: &mut dyn Recorder,
    ) -> Result<RunSummary, SceneError> {
        let info = self.info();
        if self.0 == BodySceneKind::HeavyTop {
            let (top, q, s0) = Self::top_and_state(params)?;
            return run_rigid(
                info,
                top,
                None,
                &TaylorHeavyTop::new(&top),
                s0,
                None,
                *q.matrix(),
                plan,
                recorder,
            );
        }
        let (body, q, s0) = Self::free_body_and_state(params)?;
        check_momentum(
            info.name,
            "omega_x0, omega_y0, omega_z0",
            "must not all be zero (the body must rotate): give the body's initial angular \
             velocity under [parameters], e.g. `omega_z0 = 1.0`",
            &s0.momentum,
        )?;
        let r0 = Rotation3::from_matrix_unchecked(s0.rotation);
        let exact = body.flow(&r0, &s0.momentum)?;
        run_rigid(
            info,
            body,
            Some(body),
            &TaylorHeavyTop::free(&body),
            s0,
            Some(exact),
            *q.matrix(),
            plan,
            recorder,
        )
    }

    fn intermediate_axis(&self, params: &Params) -> Option<Result<Vector3<f64>, SceneError>> {
        if self.0 == BodySceneKind::HeavyTop {
            return None;
        }
        Some(
            Self::free_body_and_state(params)
                .and_then(|(body, q, _)| intermediate_of(body.principal_moments(), q.matrix())),
        )
    }
}

/// The frame the rows of a body scene are reported in, for the run's sidecar.
pub const REPORTED_FRAME: &str =
    "the [body] table's own frame (mesh-file coordinates); the model runs in the principal frame";
