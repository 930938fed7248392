//! Sweep throughput: points per second of `tumble_studies::sweep::run` with 1 and 2 worker
//! threads (the speedup is the ratio of the two throughputs criterion prints).
//!
//! The sweep is a slice of the built-in hoop-tilt map (`free-hoop`, gauss8, dt = 0.01, the
//! map's parameters) over 96 bead angles at omega0 = 4 rad/s and a 2 s horizon: points of
//! nearly equal cost, so the speedup measures the engine (pool, channel, journal) rather than
//! load imbalance. Each iteration runs the whole sweep into a fresh folder, journal included.
//! Criterion reports the throughput in points/s (`elem/s`).
//!
//! ```sh
//! cargo bench --bench sweep
//! ```

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use tumble_studies::sweep::{self, RunConfig, SweepDefinition};

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
criterion_main!(benches);
