//! Two methods, one grid: a sweep of the free hoop with Gauss–Legendre 8 at dt = 0.01 s and
//! the same sweep with DOP853 at a tolerance of 1e-12 agree to 1e-8 in every metric — the
//! tilt metrics, a crossing time, the extremum and crossing of another column, a time average
//! — because every metric is located on each method's own dense output, not on its steps
//! (DOP853's steps here are about ten times longer). Compared with [`sweep::diff`], the
//! function behind `tumble sweep diff`.

use tumble_studies::sweep::{self, PointRow, SweepDefinition, run_point};

fn grid(run: &str) -> SweepDefinition {
    let text = format!(
        r#"
scene = "free-hoop"
[parameters]
M = 1.0
m = 0.1
a = 1.0
g = 9.81
alpha_dot0 = 0.0
theta0 = 1.5707963267948966
[run]
{run}
t_end = 10.0
[[axes]]
parameter = "omega0"
values = [1.0, 3.0, 4.5, 7.0]
[[axes]]
parameter = "alpha0"
values = [0.5, 1.6, 2.6]
[metrics]
record = ["max_tilt", "final_tilt", "time_tilt_exceeds", "min:alpha", "mean:tilt",
          "first_time:alpha<0", "max:alpha_dot"]
tilt_threshold = 0.2
"#
    );
    SweepDefinition::parse(&text, "agreement", &[]).unwrap()
}

fn rows(def: &SweepDefinition) -> Vec<PointRow> {
    (0..def.points()).map(|i| run_point(def, i)).collect()
}

#[test]
fn gauss8_and_dop853_sweeps_of_one_grid_agree_to_1e_8_in_every_metric() {
    let gauss = grid("integrator = \"gauss8\"\ndt = 0.01");
    let dop = grid("integrator = \"dop853\"\ntol = 1e-12");
    let d = sweep::diff(&gauss, &rows(&gauss), &dop, &rows(&dop)).unwrap();
    assert!(d.status_differs.is_empty(), "{d:?}");
    assert_eq!(d.metrics.len(), 7);
    for m in &d.metrics {
        eprintln!(
            "{}: largest {:.2e} at {:?} ({} compared)",
            m.metric, m.largest, m.at, m.compared
        );
        assert_eq!(
            m.defined_in_one, 0,
            "{}: defined by one method only",
            m.metric
        );
        assert!(
            m.compared >= 8,
            "{}: {} points compared",
            m.metric,
            m.compared
        );
        assert!(
            m.largest <= 1e-8,
            "{}: {:e} at {:?}",
            m.metric,
            m.largest,
            m.at
        );
    }
}

#[test]
fn sweeps_of_different_grids_are_not_compared() {
    let a = grid("integrator = \"gauss8\"\ndt = 0.01");
    let text = a.to_toml().replace(
        "values = [1.0, 3.0, 4.5, 7.0]",
        "values = [1.0, 3.0, 4.5, 7.5]",
    );
    let b = SweepDefinition::parse(&text, "other", &[]).unwrap();
    let fake = |def: &SweepDefinition| -> Vec<PointRow> {
        (0..def.points())
            .map(|i| PointRow {
                index: i,
                values: def.point(i),
                metrics: vec![Some(0.0); def.metrics.len()],
                status: sweep::Status::Ok,
                reason: String::new(),
            })
            .collect()
    };
    let err = sweep::diff(&a, &fake(&a), &b, &fake(&b))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("not the same grid") && err.contains("omega0 = 7.5"),
        "{err}"
    );
}
