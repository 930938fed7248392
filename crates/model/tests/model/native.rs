//! Models evaluated as native code (the default) against the interpreter.

use std::path::PathBuf;

use tumble_model::{Evaluation, ModelScene};
use tumble_scenarios::Scene;

/// Every shipped model file (sweep files aside).
fn shipped_models() -> Vec<(String, &'static ModelScene)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../models");
    let mut models: Vec<(String, &'static ModelScene)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            name.ends_with(".toml") && !name.ends_with(".sweep.toml")
        })
        .map(|p| {
            let scene = tumble_model::load(&p).unwrap_or_else(|e| panic!("{e}"));
            (p.file_name().unwrap().to_string_lossy().into_owned(), scene)
        })
        .collect();
    models.sort_by(|a, b| a.0.cmp(&b.0));
    models
}

/// 300 classical RK4 steps of `dt` from `y0`, every stage's right-hand side recorded.
fn rk4_history(ode: &tumble_model::scene::ModelOde<'_>, y0: &[f64], dt: f64) -> Vec<Vec<f64>> {
    let n = y0.len();
    let mut y = y0.to_vec();
    let mut history = Vec::new();
    let (mut k1, mut k2, mut k3, mut k4, mut z) = (
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
    );
    for step in 0..300 {
        let t = step as f64 * dt;
        ode.rhs_slice(t, &y, &mut k1);
        for i in 0..n {
            z[i] = y[i] + 0.5 * dt * k1[i];
        }
        ode.rhs_slice(t + 0.5 * dt, &z, &mut k2);
        for i in 0..n {
            z[i] = y[i] + 0.5 * dt * k2[i];
        }
        ode.rhs_slice(t + 0.5 * dt, &z, &mut k3);
        for i in 0..n {
            z[i] = y[i] + dt * k3[i];
        }
        ode.rhs_slice(t + dt, &z, &mut k4);
        for i in 0..n {
            y[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        history.extend([k1.clone(), k4.clone(), y.clone()]);
    }
    history
}

/// Every shipped model is compiled to native code on load, and integrating it gives the
/// interpreter's trajectory bit for bit: every stage's accelerations and every state of 300
/// RK4 steps (the compiled code performs the same operations in the same order).
#[test]
fn native_code_integrates_every_shipped_model_bit_for_bit_as_interpreted() {
    let models = shipped_models();
    assert!(models.len() >= 9, "{} models", models.len());
    for (name, scene) in models {
        assert_eq!(scene.evaluation(), Evaluation::Native, "{name}");
        let params = scene.info().default_params();
        let y0 = scene.initial_state(&params);
        let native = rk4_history(&scene.ode_with(&params, Evaluation::Native), &y0, 1e-3);
        let interpreted = rk4_history(&scene.ode_with(&params, Evaluation::Interpreted), &y0, 1e-3);
        for (k, (a, b)) in native.iter().zip(&interpreted).enumerate() {
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(a), bits(b), "{name}: record {k}: {a:?} vs {b:?}");
        }
        // The run moved: the comparison is not of constant states.
        let last = native.last().unwrap();
        assert!(last.iter().zip(&y0).any(|(a, b)| a != b), "{name}");
    }
}
