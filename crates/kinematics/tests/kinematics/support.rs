//! Shared strategies and helpers.

use std::f64::consts::PI;

use nalgebra::{Matrix3, Quaternion, Rotation3, UnitQuaternion, Vector3};
use proptest::prelude::*;

/// A uniformly distributed unit vector (from three normal-ish coordinates, rejected near 0).
pub fn unit_vector() -> impl Strategy<Value = Vector3<f64>> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
        .prop_filter("not too short", |(x, y, z)| x * x + y * y + z * z > 1e-3)
        .prop_map(|(x, y, z)| Vector3::new(x, y, z).normalize())
}

/// Rotation angles in (0, π): ordinary ones, ones within 1e-12…1e-6 of 0 and ones within
/// 1e-12…1e-6 of π (log-uniform distances), and ones at exactly the edges of the ranges.
pub fn angle_below_pi() -> impl Strategy<Value = f64> {
    prop_oneof![
        2 => 1e-6f64..(PI - 1e-6),
        1 => (-12.0f64..-6.0).prop_map(|e| 10f64.powf(e)),
        1 => (-12.0f64..-6.0).prop_map(|e| PI - 10f64.powf(e)),
        1 => Just(1e-12),
        1 => Just(PI - 1e-12),
    ]
}

/// A rotation vector with |ω| < π (see [`angle_below_pi`]).
pub fn rotation_vector() -> impl Strategy<Value = Vector3<f64>> {
    (unit_vector(), angle_below_pi()).prop_map(|(n, a)| n * a)
}

/// A random rotation given by a random unit quaternion (uniform on SO(3)), or one near 0 or π.
pub fn rotation() -> impl Strategy<Value = Rotation3<f64>> {
    prop_oneof![
        (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
            .prop_filter("not too short", |(w, x, y, z)| w * w
                + x * x
                + y * y
                + z * z
                > 1e-3)
            .prop_map(|(w, x, y, z)| {
                UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)).to_rotation_matrix()
            }),
        // Built by nalgebra's own axis-angle constructor: independent of the code under test.
        (unit_vector(), angle_below_pi()).prop_map(|(n, a)| {
            Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(n), a)
        }),
    ]
}

/// Largest absolute entry of a matrix difference.
pub fn max_abs_diff(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).amax()
}

/// Difference of two angles modulo 2π, in (−π, π].
pub fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    if d > PI { d - 2.0 * PI } else { d }
}

/// Proptest settings: `default_cases` cases, or `PROPTEST_CASES` when set (to stress the bounds
/// with many more random cases than CI runs: `PROPTEST_CASES=200000 cargo test ...`).
/// `ProptestConfig::with_cases` alone would ignore the variable.
pub fn proptest_config(default_cases: u32) -> proptest::prelude::ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    proptest::prelude::ProptestConfig::with_cases(cases)
}
