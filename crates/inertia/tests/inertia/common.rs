//! Shared helpers: data paths, relative errors, and the observed-order harness.

use std::path::PathBuf;

use nalgebra::{Matrix3, Rotation3, Vector3};
use proptest::prelude::*;

/// A file under `crates/inertia/tests/data`.
pub fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// The workspace root (two levels above this crate).
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `‖a − b‖ / ‖b‖` (Frobenius).
pub fn rel_err(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).norm() / b.norm()
}

/// Round-off floor below which errors no longer measure discretization (STYLE: ~1e-13).
const FLOOR: f64 = 1e-13;

/// Least-squares slope of `log(error)` against `log(h)` over the points above the round-off
/// floor, up to where the error stops decreasing. Returns the slope and how many points it used.
pub fn observed_order(hs: &[f64], errors: &[f64]) -> (f64, usize) {
    assert_eq!(hs.len(), errors.len());
    let mut points: Vec<(f64, f64)> = Vec::new();
    for (&h, &e) in hs.iter().zip(errors) {
        if e <= FLOOR {
            break;
        }
        if let Some(&(_, last)) = points.last()
            && e.ln() >= last
        {
            break;
        }
        points.push((h.ln(), e.ln()));
    }
    let n = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(sx, sy), &(x, y)| (sx + x, sy + y));
    let (mx, my) = (sx / n, sy / n);
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(sxy, sxx), &(x, y)| {
        (sxy + (x - mx) * (y - my), sxx + (x - mx) * (x - mx))
    });
    (sxy / sxx, points.len())
}

/// Asserts that the errors decrease like `h^nominal` (±0.3) over at least three points, and
/// prints the observed rate.
pub fn assert_order(what: &str, hs: &[f64], errors: &[f64], nominal: f64) -> f64 {
    let (p, used) = observed_order(hs, errors);
    let shown: Vec<String> = errors.iter().map(|e| format!("{e:.3e}")).collect();
    println!(
        "{what}: observed order {p:.3} from {used} points, errors [{}]",
        shown.join(", ")
    );
    assert!(
        used >= 3,
        "{what}: only {used} points above the round-off floor: {errors:?}"
    );
    assert!(
        (p - nominal).abs() <= 0.3,
        "{what}: observed order {p} is not {nominal} ± 0.3; errors {errors:?}"
    );
    p
}

/// Random rotations: uniform-ish via a random axis and angle.
pub fn rotation() -> impl Strategy<Value = Rotation3<f64>> {
    (
        -1.0..1.0f64,
        -1.0..1.0f64,
        -1.0..1.0f64,
        -std::f64::consts::PI..std::f64::consts::PI,
    )
        .prop_filter("axis must not vanish", |(x, y, z, _)| {
            x * x + y * y + z * z > 1e-4
        })
        .prop_map(|(x, y, z, angle)| {
            Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(Vector3::new(x, y, z)), angle)
        })
}

/// Random vectors with components in `[-scale, scale]`.
pub fn vector(scale: f64) -> impl Strategy<Value = Vector3<f64>> {
    (-scale..scale, -scale..scale, -scale..scale).prop_map(|(x, y, z)| Vector3::new(x, y, z))
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
