//! Running shipped models.

use std::path::PathBuf;

use tumble_model::ModelScene;
use tumble_scenarios::scene::Rows;
use tumble_scenarios::{RunOptions, Scene, StepControl};

/// The shipped model `models/NAME.toml`.
pub fn shipped(name: &str) -> &'static ModelScene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(format!("{name}.toml"));
    tumble_model::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Rows of `scene` with `set` applied to its defaults.
pub fn run(
    scene: &dyn Scene,
    set: &[(&str, f64)],
    integrator: &str,
    step: StepControl,
    t_end: f64,
) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut params = scene.info().default_params();
    for (k, v) in set {
        params.set(k, *v).unwrap();
    }
    let options = RunOptions {
        integrator: Some(integrator.to_string()),
        step: Some(step),
        t_end: Some(t_end),
        ..RunOptions::default()
    };
    let mut rows = Rows::default();
    scene
        .run(&params, &options, &mut rows)
        .unwrap_or_else(|e| panic!("{e}"));
    (scene.info().columns(), rows.0)
}

/// The column `name` of `rows`.
pub fn column(columns: &[String], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let i = columns
        .iter()
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column {name} in {columns:?}"));
    rows.iter().map(|r| r[i]).collect()
}
