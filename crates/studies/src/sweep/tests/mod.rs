//! Tests of sweep files, points, metrics on real scenes, the journal, resumption and shards:
//! the shared fixtures here, the tests by concern in the submodules.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use super::definition::splitmix64;
use super::*;
use tumble_scenarios::scene::{Rows, StepControl};
use tumble_scenarios::scenes::find;

fn parse(text: &str) -> Result<SweepDefinition, SweepFileError> {
    SweepDefinition::parse(text, "test.toml", &[])
}

fn set(key: &str, value: f64) -> Override {
    Override {
        key: key.to_string(),
        value: super::OverrideValue::Number(value),
        text: format!("{key}={value}"),
    }
}

/// A small hoop sweep: 3 × 2 points over half a second.
const SMALL: &str = r#"
scene = "free-hoop"

[parameters]
g = 9.81
a = 1.0

[run]
integrator = "gauss8"
dt = 0.01
t_end = 0.5

[[axes]]
parameter = "omega0"
range = [1.0, 5.0]
count = 3

[[axes]]
parameter = "alpha0"
values = [0.5, 2.0]

[metrics]
record = ["max_tilt", "final_tilt", "time_tilt_exceeds", "max_energy_rel_err"]
tilt_threshold = 0.01
"#;

fn small() -> SweepDefinition {
    parse(SMALL).unwrap()
}

fn results(def: &SweepDefinition, dir: &Path, config: &RunConfig<'_>) -> Vec<u8> {
    let report = run(def, dir, config, &mut |_| {}).unwrap();
    assert!(report.complete());
    results_csv(def, &report.rows).unwrap()
}

fn threads(n: usize) -> RunConfig<'static> {
    RunConfig {
        threads: n,
        ..RunConfig::default()
    }
}

fn error_line(e: &SweepFileError) -> usize {
    e.line().unwrap_or_else(|| panic!("no line in: {e}"))
}

mod convergence;
mod files;
mod metrics;
mod running;
