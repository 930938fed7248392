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

/// Where the mass matrix is singular the accelerations are NaN (the driver then stops with
/// the state), natively and interpreted alike: the spherical pendulum with its rod along the
/// vertical, where the mass matrix `diag(m l², m l² sin²θ)` loses its second pivot; a step
/// away, both evaluations are finite and agree.
#[test]
fn a_singular_mass_matrix_gives_nan_accelerations_both_ways() {
    let models = shipped_models();
    let (_, scene) = models
        .iter()
        .find(|(name, _)| name == "spherical-pendulum.toml")
        .unwrap();
    let params = scene.info().default_params();
    for evaluation in [Evaluation::Native, Evaluation::Interpreted] {
        let ode = scene.ode_with(&params, evaluation);
        // (theta, phi, theta_dot, phi_dot)
        let mut dy = [0.0; 4];
        ode.rhs_slice(0.0, &[0.0, 0.3, 0.5, 2.0], &mut dy);
        assert_eq!(&dy[..2], &[0.5, 2.0], "{evaluation:?}");
        assert!(dy[2].is_nan() && dy[3].is_nan(), "{evaluation:?}: {dy:?}");
        ode.rhs_slice(0.0, &[0.6, 0.3, 0.5, 2.0], &mut dy);
        assert!(dy.iter().all(|x| x.is_finite()), "{evaluation:?}: {dy:?}");
    }
}

/// The accelerations the right-hand side computes on its tape (the Cholesky factorization
/// and substitutions written out on the expression graph) are bit for bit those of the
/// numeric routines of `tumble_model::mechanics` applied to the mass matrix and forces
/// evaluated at the same state: the solve for a mass matrix that changes with the state, the
/// product with the inverse (computed once, column by column) for one that does not. For
/// every shipped model, along 300 RK4 steps, natively and interpreted.
#[test]
fn the_taped_solve_is_bit_for_bit_the_numeric_cholesky_solve() {
    use tumble_model::mechanics::{cholesky_factor, cholesky_solve, cholesky_substitute};
    for (name, scene) in shipped_models() {
        let params = scene.info().default_params();
        let y0 = scene.initial_state(&params);
        let layout = scene.model().layout;
        let (dof, v) = (layout.dof(), layout.velocities_at());
        for evaluation in [Evaluation::Native, Evaluation::Interpreted] {
            let ode = scene.ode_with(&params, evaluation);
            // A mass matrix of the parameters alone (the graph's, not a numerical test).
            let model = scene.model();
            let constant = model
                .equations
                .mass
                .iter()
                .all(|&id| !model.graph.depends_on(id, &|k| !model.layout.is_param(k)));
            let history = rk4_history(&ode, &y0, 1e-3);
            let mut dy = vec![0.0; y0.len()];
            // Every third record is a state.
            for (k, y) in history.iter().skip(2).step_by(3).enumerate() {
                let t = 1e-3 * k as f64;
                ode.rhs_slice(t, y, &mut dy);
                let (mut m, mut b) = (ode.mass_matrix(t, y), ode.forces(t, y));
                let expected: Vec<f64> = if constant {
                    assert!(cholesky_factor(&mut m, dof) > 0.0, "{name}");
                    let mut inverse = vec![0.0; dof * dof];
                    for j in 0..dof {
                        let mut e = vec![0.0; dof];
                        e[j] = 1.0;
                        cholesky_substitute(&m, &mut e, dof);
                        for i in 0..dof {
                            inverse[i * dof + j] = e[i];
                        }
                    }
                    (0..dof)
                        .map(|i| (0..dof).map(|j| inverse[i * dof + j] * b[j]).sum())
                        .collect()
                } else {
                    assert!(cholesky_solve(&mut m, &mut b, dof) > 0.0, "{name}");
                    b
                };
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&dy[v..v + dof]),
                    bits(&expected),
                    "{name} {evaluation:?} state {k}"
                );
            }
        }
    }
}
