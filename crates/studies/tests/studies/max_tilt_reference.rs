//! The free hoop's largest tilt within 10 s (M = 1, m = 0.1, a = 1, g = 9.81, standing, bead at
//! rest) against independent references — SciPy's DOP853 at a tolerance of 1e-13 with the
//! maximum refined by Brent's method. The metric locates maxima on the method's dense output
//! (the collocation polynomial, DOP853's 7th-order extension), so a method's long steps cost it
//! nothing: Gauss–Legendre 8 at dt = 0.01 s reproduces all eight to 1e-9 (1.4e-10 at worst;
//! the quartic through step samples it replaced was 6.4e-8 off at (6.6, 1.6)).
//!
//! DOP853 at a tolerance of 1e-12 reproduces seven of them to 1e-10 (9.9e-11 at (0.6, 2.75),
//! where the hoop nearly lies flat). At (0.8, 2.85) it is 2.7e-9 off: there the maximum is
//! sensitive (d(max)/dω₀ ≈ 200) and `τ = asin s` amplifies the error of the smooth signal
//! `s = |n_z|` by `1/cos τ ≈ 28`; in `s`, the quantity the integration controls, the error is
//! 9.8e-11. That point is checked in `s` (≤ 2e-10) and in `τ` at its measured 3e-9, and falls
//! with the tolerance (1.1e-10 in `τ` at 1e-14).

use tumble_studies::sweep::{SweepDefinition, run_point};

/// `(omega0, alpha0, max tilt)`.
const REFERENCE: [(f64, f64, f64); 8] = [
    (0.6, 2.75, 1.5621714742),
    (0.8, 2.85, 1.5351076135),
    (2.0, 1.0, 0.3813429648),
    (5.3, 2.1, 0.3156334350),
    (5.5, 2.2, 0.2269868000),
    (6.3, 2.25, 0.2042603227),
    (6.4, 2.35, 0.2196029939),
    (6.6, 1.6, 0.1081468955),
];

fn max_tilt(run: &str, omega0: f64, alpha0: f64) -> f64 {
    let text = format!(
        r#"
scene = "free-hoop"
[parameters]
M = 1.0
m = 0.1
a = 1.0
g = 9.81
[run]
{run}
t_end = 10.0
[[axes]]
parameter = "omega0"
values = [{omega0:?}]
[[axes]]
parameter = "alpha0"
values = [{alpha0:?}]
[metrics]
record = ["max_tilt"]
"#
    );
    let def = SweepDefinition::parse(&text, "reference", &[]).unwrap();
    let row = run_point(&def, 0);
    row.metrics[0].unwrap_or_else(|| panic!("{omega0}, {alpha0}: {}", row.reason))
}

#[test]
fn max_tilt_matches_the_independent_references_with_gauss8_and_dop853() {
    let mut worst: f64 = 0.0;
    for (omega0, alpha0, reference) in REFERENCE {
        for run in [
            "integrator = \"gauss8\"\ndt = 0.01",
            "integrator = \"dop853\"\ntol = 1e-12",
        ] {
            let got = max_tilt(run, omega0, alpha0);
            let d = (got - reference).abs();
            let ds = (got.sin() - reference.sin()).abs();
            eprintln!(
                "({omega0}, {alpha0}) {}: {got:.10} vs {reference:.10}: {d:.1e} (in sin: {ds:.1e})",
                run.replace('\n', " ")
            );
            if run.contains("dop853") && (omega0, alpha0) == (0.8, 2.85) {
                assert!(ds <= 2e-10, "({omega0}, {alpha0}) {run}: {ds:e} in sin tau");
                assert!(d <= 3e-9, "({omega0}, {alpha0}) {run}: {d:e}");
            } else {
                worst = worst.max(d);
            }
        }
    }
    // The references carry 10 decimals: agreement to 1e-9 is their resolution.
    assert!(worst <= 1e-9, "worst {worst:e}");
}
