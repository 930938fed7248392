//! The free hoop's Euler–Poisson reduction in sweeps: which model a sweep runs, and that the
//! two models give the same metrics.
//!
//! A sweep of tilt, bead and energy metrics runs the reduction (8 numbers); the same sweep with
//! one metric the reduction cannot give (`max:Lx`, the lab `x` component of the angular
//! momentum, needs the whole rotation) runs the full model (14). The reduction is the full
//! vector field carried by the linear map `R ↦ Rᵀ e_z`, and a Runge–Kutta method commutes with
//! a linear map: at a fixed step both runs are the same computation in exact arithmetic, and
//! every shared metric agrees to round-off — with Gauss–Legendre, which keeps `RᵀR = 𝟙` and
//! `|Γ| = 1` (quadratic invariants) to round-off, since the tilt `asin |n_z|/|n|` normalises
//! by a column of `R` in one model and by `Γ`, a row, in the other (an explicit method leaves
//! them different by its orthogonality error: 8e-11 rad with rk4 at dt = 0.002 s). With error control the step sequences differ
//! (the full error estimate also weighs the rest of `R`), and they agree to the tolerance's
//! level.

use tumble_studies::sweep::{self, Metric, PointRow, SweepDefinition, run_point};

const REDUCED_METRICS: &str = r#""max_tilt", "final_tilt", "time_tilt_exceeds", "min:alpha",
          "mean:tilt", "max:alpha_dot", "max:omega_z", "final:Lz", "final:energy",
          "max_energy_rel_err""#;

fn grid(run: &str, extra_metric: &str) -> SweepDefinition {
    let text = format!(
        r#"
scene = "free-hoop"
[parameters]
alpha_dot0 = 0.3
theta0 = 1.4
[run]
{run}
t_end = 10.0
[[axes]]
parameter = "omega0"
values = [0.8, 3.0, 4.5, 7.75]
[[axes]]
parameter = "alpha0"
values = [0.5, 2.42, 2.85]
[metrics]
record = [{REDUCED_METRICS}{extra_metric}]
tilt_threshold = 0.3
"#
    );
    SweepDefinition::parse(&text, "reduced-model", &[]).unwrap()
}

fn rows(def: &SweepDefinition) -> Vec<PointRow> {
    (0..def.points()).map(|i| run_point(def, i)).collect()
}

/// The largest difference of each shared metric between the reduced and the full sweep (the
/// full one has one metric more, at the end), relative to `1 + |value|`; a tilt compared by
/// its sine `|n_z|`, since `asin` multiplies a round-off in `n_z` by `1/cos(tilt)`, without
/// bound as the hoop nears flat (the grid's (0.8, 2.85) comes within 1e-6 of it).
fn largest_differences(run: &str) -> Vec<(String, f64, usize)> {
    let reduced = grid(run, "");
    let full = grid(run, r#", "max:Lx""#);
    assert_eq!(reduced.reduction().map(|r| r.name), Some("euler-poisson"));
    assert!(full.reduction().is_none(), "max:Lx needs the full model");
    let (a, b) = (rows(&reduced), rows(&full));
    reduced
        .metrics
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let mut largest = 0.0_f64;
            let mut compared = 0;
            for (ra, rb) in a.iter().zip(&b) {
                assert_eq!(ra.status, sweep::Status::Ok, "{}", ra.reason);
                assert_eq!(rb.status, sweep::Status::Ok, "{}", rb.reason);
                match (ra.metrics[k], rb.metrics[k]) {
                    (Some(x), Some(y)) => {
                        let tilt = matches!(m.as_column(Some(0.3)), Some((_, "tilt")))
                            && *m != Metric::TimeTiltExceeds;
                        let d = if *m == Metric::MaxEnergyRelErr {
                            (x - y).abs()
                        } else if tilt {
                            (x.sin() - y.sin()).abs()
                        } else {
                            (x - y).abs() / (1.0 + y.abs())
                        };
                        largest = largest.max(d);
                        compared += 1;
                    }
                    (None, None) => {}
                    (x, y) => panic!("{m}: {x:?} against {y:?} at point {}", ra.index),
                }
            }
            (m.name(), largest, compared)
        })
        .collect()
}

/// How far a metric of the two models may differ when both runs are the same computation in
/// exact arithmetic (see [`reduced_and_full_models_agree_to_round_off_at_a_fixed_step`]).
fn round_off_bound(metric: &str) -> f64 {
    match metric.split(':').next().unwrap_or("") {
        "max_tilt" | "max" | "min" => 2e-11,
        "time_tilt_exceeds" | "first_time" => 1e-10,
        _ => 1e-12,
    }
}

#[test]
fn reduced_and_full_models_agree_to_round_off_at_a_fixed_step() {
    let differences = largest_differences("integrator = \"gauss8\"\ndt = 0.01");
    for (metric, largest, compared) in &differences {
        eprintln!("{metric}: {largest:.1e} over {compared} points");
    }
    for (metric, largest, compared) in differences {
        assert!(compared >= 6, "{metric}: {compared} points compared");
        // Values of the state (final, mean, conserved quantities): round-off, accumulated over
        // 1000 steps (6e-13 in the sine of the final tilt on these sensitive points). A located
        // extremum: Brent's method stops at √ε·t in time, where a value is settled only to
        // ~f''(√ε t)²/2 (≈ 1e-12 on these spins), so a round-off difference that turns its
        // path moves the value that much. A crossing time: the round-off of the crossed value
        // divided by its rate.
        let bound = round_off_bound(&metric);
        assert!(largest <= bound, "{metric}: {largest:e} (bound {bound:e})");
    }
}

#[test]
fn reduced_and_full_models_agree_to_the_tolerance_with_error_control() {
    for (metric, largest, compared) in largest_differences("integrator = \"dop853\"\ntol = 1e-12") {
        eprintln!("{metric}: {largest:.1e} over {compared} points");
        assert!(compared >= 6, "{metric}: {compared} points compared");
        assert!(largest <= 1e-8, "{metric}: {largest:e}");
    }
}

/// The Taylor method on the hand-written coefficients: a fixed order at a fixed step is the
/// same polynomial for `Γ, Π, α, p_α` in both models (the other rows of `R` do not enter
/// them), so every shared metric agrees to round-off, as Gauss–Legendre's do (order 16 at
/// dt = 0.01 s leaves `RᵀR = 𝟙` to round-off); with its order and step from the tolerance the
/// step sequences differ, and they agree to the tolerance's level.
#[test]
fn reduced_and_full_models_agree_with_the_taylor_method() {
    for (metric, largest, compared) in largest_differences("integrator = \"taylor16\"\ndt = 0.01") {
        eprintln!("taylor16: {metric}: {largest:.1e} over {compared} points");
        assert!(compared >= 6, "{metric}: {compared} points compared");
        let bound = round_off_bound(&metric);
        assert!(largest <= bound, "{metric}: {largest:e} (bound {bound:e})");
    }
    for (metric, largest, compared) in largest_differences("integrator = \"taylor\"\ntol = 1e-12") {
        eprintln!("taylor: {metric}: {largest:.1e} over {compared} points");
        assert!(compared >= 6, "{metric}: {compared} points compared");
        assert!(largest <= 1e-8, "{metric}: {largest:e}");
    }
}

/// The Taylor method of a fixed order `p` on the reduction converges at order `p`: halving
/// the step divides the final state's error (against vern9 at 1e-15) by about `2ᵖ`.
#[test]
fn the_taylor_method_on_the_reduction_has_its_order() {
    let metrics = r#""final:alpha", "final:alpha_dot", "final:omega_x", "final:Lz""#;
    let run = |integrator: &str, step: &str| {
        let text = format!(
            r#"
scene = "free-hoop"
[parameters]
alpha_dot0 = 0.3
theta0 = 1.4
omega0 = 3.0
alpha0 = 2.42
[run]
integrator = "{integrator}"
{step}
t_end = 2.0
[[axes]]
parameter = "m"
values = [0.1]
[metrics]
record = [{metrics}]
"#
        );
        let def = SweepDefinition::parse(&text, "order", &[]).unwrap();
        assert!(def.reduction().is_some());
        let row = run_point(&def, 0);
        assert_eq!(row.status, sweep::Status::Ok, "{}", row.reason);
        row.metrics
            .into_iter()
            .map(Option::unwrap)
            .collect::<Vec<f64>>()
    };
    let exact = run("vern9", "tol = 1e-15");
    let error = |values: Vec<f64>| {
        values
            .iter()
            .zip(&exact)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (
        error(run("taylor8", "dt = 0.04")),
        error(run("taylor8", "dt = 0.02")),
    );
    let order = (coarse / fine).log2();
    eprintln!("taylor8: {coarse:.2e} at dt = 0.04, {fine:.2e} at 0.02: order {order:.2}");
    assert!(fine > 1e-12, "above round-off: {fine:e}");
    assert!((7.5..=8.7).contains(&order), "observed order {order}");
}

/// The rule: the reduction runs for a vector-space method (the Taylor method among them) whose
/// every metric it gives; a
/// Lie-group method (the coupled LGVI integrates `R` itself) or a metric of the full rotation
/// runs the full model.
#[test]
fn the_reduction_runs_only_where_it_serves() {
    assert!(
        grid("integrator = \"vern9\"\ntol = 1e-10", "")
            .reduction()
            .is_some()
    );
    assert!(
        grid("integrator = \"gauss8\"\ndt = 0.01", "")
            .reduction()
            .is_some()
    );
    assert!(
        grid("integrator = \"taylor\"\ntol = 1e-12", "")
            .reduction()
            .is_some()
    );
    assert!(
        grid("integrator = \"lgvi\"\ndt = 0.001", "")
            .reduction()
            .is_none()
    );
    for full_only in ["max:qw", "final:Ly", "mean:qz"] {
        let def = grid(
            "integrator = \"dop853\"\ntol = 1e-10",
            &format!(", \"{full_only}\""),
        );
        assert!(def.reduction().is_none(), "{full_only}");
    }
}
