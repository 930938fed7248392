//! The data of the principal-axes explorer: a body (the sources of `tumble inertia`) about its
//! centre of mass, its inertia tensor, principal moments and axes in its own frame, and for
//! each of the 24 Euler conventions the angles that turn it into its principal frame. The page
//! turns the body by the sliders' angles and shows `R I Rᵀ`, `R c` and `R Q` as
//! `tumble inertia --euler … --json` reports them.

use nalgebra::{Matrix3, Point3, Vector3};
use serde_json::{Value, json};
use tumble_inertia::MassProperties;
use tumble_kinematics::{EulerConvention, RotationKind};
use tumble_scenarios::drawing::Part;

use super::geometry;

fn rows(m: &Matrix3<f64>) -> Value {
    json!([0, 1, 2].map(|i| [0, 1, 2].map(|j| m[(i, j)])))
}

fn triple(v: &Vector3<f64>) -> Value {
    json!([v.x, v.y, v.z])
}

/// A convention's key in the page: `intrinsic-zyz`, `extrinsic-xyz`.
fn key(convention: &EulerConvention) -> String {
    let kind = match convention.kind {
        RotationKind::Intrinsic => "intrinsic",
        RotationKind::Extrinsic => "extrinsic",
    };
    format!(
        "{kind}-{}",
        convention.sequence.to_string().to_ascii_lowercase()
    )
}

/// The explorer's data for `body` built from `parts` (in the body's frame), the sliders
/// starting at the ZYZ angles `start`.
#[must_use]
pub fn data(
    body: &MassProperties,
    parts: &[Part],
    sources: &[String],
    start: &Vector3<f64>,
) -> Value {
    let c: Point3<f64> = body.center_of_mass();
    let principal = body.principal();
    let snaps: serde_json::Map<String, Value> = EulerConvention::all()
        .map(|conv| {
            let d = body.principal_euler_with(&conv);
            (
                key(&conv),
                json!({"angles": triple(&d.angles), "gimbal_lock": d.gimbal_lock}),
            )
        })
        .collect();
    json!({
        "mass": body.mass(),
        "center_of_mass": triple(&c.coords),
        "inertia": rows(body.inertia()),
        "principal_moments": triple(&principal.moments),
        "principal_axes": rows(principal.axes.matrix()),
        "principal_euler": snaps,
        "start": triple(start),
        "parts": geometry::parts(parts, &c).iter().map(geometry::Render::json).collect::<Vec<_>>(),
        "reach": geometry::reach(parts, &c),
        "sources": sources,
    })
}
