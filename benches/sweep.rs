//! Sweep throughput: points per second of `tumble_studies::sweep::run` with 1 and 2 worker
//! threads (the speedup is the ratio of the two throughputs criterion prints).
//!
//! The sweep is a slice of the built-in hoop-tilt map (`free-hoop`, gauss8, dt = 0.01, the
//! map's parameters) over 96 bead angles at omega0 = 4 rad/s and a 2 s horizon: points of
//! nearly equal cost, so the speedup measures the engine (pool, channel, journal) rather than
//! load imbalance. Each iteration runs the whole sweep into a fresh folder, journal included.
//! Criterion reports the throughput in points/s (`elem/s`).
//!
//! Then **the choice of the map's method**: for each candidate method and setting, a spread of
//! the built-in map's own points (its self-check points: the grid's corners and an even
//! spread, `TUMBLE_BENCH_POINTS`, default 96) run one after another on one thread, timed, and
//! re-run at the tighter setting of the self-check (half the step, or a tolerance 100 times
//! smaller) to state how far the metrics moved. The table gives points/s on one core and the
//! self-check. The fastest setting whose sampled self-check is ≤ 1e-7 is printed last; the
//! map then checks its choice on the whole grid with `tumble sweep diff` against a run 100
//! times tighter (`crates/studies/src/sweep/tilt-map.sweep.toml` says which and why).
//!
//! ```sh
//! cargo bench --bench sweep                 # both parts
//! cargo bench --bench sweep -- methods      # the method table only
//! ```

use std::hint::black_box;

use std::time::Instant;

use criterion::{Criterion, Throughput, criterion_group};
use tumble_studies::sweep::{
    self, CheckSize, Override, OverrideValue, RunConfig, SweepDefinition, check_points, run_point,
    self_check,
};

/// The benchmark's sweep: the free hoop as in the tilt map, one spin, 96 bead angles.
const SWEEP: &str = r#"
scene = "free-hoop"

[parameters]
M = 1.0
m = 0.1
a = 1.0
g = 9.81
omega0 = 4.0

[run]
integrator = "gauss8"
dt = 0.01
t_end = 2.0

[[axes]]
parameter = "alpha0"
range = [0.1, 3.0]
count = 96

[metrics]
record = ["max_tilt", "final_tilt", "max_energy_rel_err"]
"#;

fn bench(c: &mut Criterion) {
    let def = SweepDefinition::parse(SWEEP, "bench", &[]).expect("the benchmark's sweep is valid");
    let points = def.points();
    let mut group = c.benchmark_group("sweep");
    group.sample_size(10);
    group.measurement_time(std::time::Duration::from_secs(20));
    group.throughput(Throughput::Elements(points));
    for threads in [1usize, 2] {
        group.bench_function(format!("threads-{threads}"), |b| {
            b.iter(|| {
                let dir = tempfile::tempdir().expect("a temporary folder");
                let config = RunConfig {
                    threads,
                    ..RunConfig::default()
                };
                let report =
                    sweep::run(&def, dir.path(), &config, &mut |_| {}).expect("the sweep runs");
                assert!(report.complete() && report.failures().next().is_none());
                black_box(report.rows.len())
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench);

/// Candidate methods and settings for the map: `(integrator, "dt" or "tol", value)`.
const CANDIDATES: &[(&str, &str, f64)] = &[
    ("gauss8", "dt", 0.01),
    ("gauss8", "dt", 0.02),
    ("gauss12", "dt", 0.02),
    ("gauss12", "dt", 0.04),
    ("dp5", "tol", 1e-12),
    ("dop853", "tol", 1e-10),
    ("dop853", "tol", 1e-11),
    ("dop853", "tol", 1e-12),
    ("dop853", "tol", 1e-13),
    ("vern7", "tol", 1e-12),
    ("vern8", "tol", 1e-11),
    ("vern8", "tol", 1e-12),
    ("vern9", "tol", 1e-11),
    ("vern9", "tol", 1e-12),
    ("vern9", "tol", 1e-13),
    ("tsit5", "tol", 1e-12),
];

fn text(key: &str, value: &str) -> Override {
    Override {
        key: key.into(),
        value: OverrideValue::Text(value.into()),
        text: format!("{key}={value}"),
    }
}

fn number(key: &str, value: f64) -> Override {
    Override {
        key: key.into(),
        value: OverrideValue::Number(value),
        text: format!("{key}={value}"),
    }
}

/// Points/s on one core and the self-check of each candidate on the map's own points.
fn methods() {
    let n: u64 = std::env::var("TUMBLE_BENCH_POINTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(96);
    let map = SweepDefinition::tilt_map(&[]).expect("the built-in map is valid");
    let points = check_points(&map, CheckSize::Points(n));
    println!(
        "\nmap methods: {} of the map's {} points, one core; self-check = largest change of \
         max_tilt, final_tilt, time_tilt_exceeds at the tighter setting",
        points.len(),
        map.points()
    );
    println!(
        "{:<9} {:<14} {:>10} {:>11} {:>14}",
        "method", "setting", "points/s", "self-check", "where (index)"
    );
    let mut best: Option<(f64, String)> = None;
    for &(method, key, value) in CANDIDATES {
        let overrides = [
            text("run.integrator", method),
            number(&format!("run.{key}"), value),
        ];
        let Ok(def) = SweepDefinition::tilt_map(&overrides) else {
            println!("{method:<9} {key} = {value:<8e} not valid for the map");
            continue;
        };
        let start = Instant::now();
        let rows: Vec<_> = points.iter().map(|&i| run_point(&def, i)).collect();
        let rate = points.len() as f64 / start.elapsed().as_secs_f64();
        let check = self_check(&def, &rows, &points, 2).expect("the self-check runs");
        let worst = check
            .changes
            .iter()
            .filter(|c| c.metric != sweep::Metric::MaxEnergyRelErr)
            .max_by(|a, b| a.max_change.total_cmp(&b.max_change));
        let (change, at) = worst.map_or((0.0, None), |c| (c.max_change, c.index));
        let failed = rows
            .iter()
            .filter(|r| r.status != sweep::Status::Ok)
            .count()
            + check.status_changed.len();
        let setting = format!("{key} = {value:e}");
        println!(
            "{method:<9} {setting:<14} {rate:>10.1} {change:>11.2e} {:>14}{}",
            at.map_or(String::new(), |i| i.to_string()),
            if failed > 0 {
                format!("  ({failed} failed or changed status)")
            } else {
                String::new()
            }
        );
        if change <= 1e-7 && failed == 0 && best.as_ref().is_none_or(|(r, _)| rate > *r) {
            best = Some((rate, format!("{method} at {setting}")));
        }
    }
    match best {
        Some((rate, what)) => {
            println!(
                "fastest with a sampled self-check <= 1e-7: {what} ({rate:.1} points/s on one \
                 core); check it on the whole grid with `tumble sweep diff`"
            );
        }
        None => println!("no candidate has a self-check <= 1e-7"),
    }
}

fn main() {
    let only_methods = std::env::args().any(|a| a == "methods");
    if !only_methods {
        benches();
        Criterion::default().configure_from_args().final_summary();
    }
    methods();
}
