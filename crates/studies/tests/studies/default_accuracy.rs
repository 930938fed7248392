//! Every built-in scene's default run (integrator, step or tolerance, horizon) is accurate to
//! 1e-9 in the work–precision error norm against the scene's reference, at its default
//! parameters and at three other points of its parameter space; and the error the scene states
//! for its default (`SceneInfo::default_error`, printed by `tumble scenes`) is what is measured.

use tumble_scenarios::scenes::find;
use tumble_scenarios::{Observe, RunOptions};
use tumble_studies::work_precision::{final_state, reference, state_error};

/// The default run's error at `params` (`(name, value)` overrides of the defaults).
fn default_error(scene: &str, overrides: &[(&str, f64)]) -> f64 {
    let scene = find(scene).unwrap();
    let info = scene.info();
    let mut params = info.default_params();
    for (k, v) in overrides {
        params.set(k, *v).unwrap();
    }
    let plan = RunOptions {
        observe: Observe::Ends,
        ..RunOptions::default()
    }
    .resolve(info)
    .unwrap();
    let r = reference(scene, &params, plan.t_end).unwrap();
    let (state, _) = final_state(scene, &params, &plan).unwrap();
    state_error(info, &state, &r.state)
}

fn check(scene: &str, others: [&[(&str, f64)]; 3]) {
    let stated = find(scene).unwrap().info().default_error;
    let at_defaults = default_error(scene, &[]);
    eprintln!("{scene}: default run error {at_defaults:.2e} (stated {stated:.1e})");
    assert!(at_defaults <= 1e-9, "{scene}: {at_defaults:e}");
    // The stated figure is the measured one (to the factor by which round-off may move it).
    assert!(
        at_defaults <= 3.0 * stated.max(1e-15) && stated <= 3.0 * at_defaults.max(1e-15),
        "{scene}: measured {at_defaults:e}, stated {stated:e}"
    );
    for params in others {
        let e = default_error(scene, params);
        eprintln!("{scene} at {params:?}: {e:.2e}");
        assert!(e <= 1e-9, "{scene} at {params:?}: {e:e}");
    }
}

#[test]
fn default_runs_are_accurate_driven_hoop() {
    check(
        "driven-hoop",
        [
            &[("omega", 6.0)],
            &[("alpha0", 2.5)],
            &[("omega", 2.0), ("alpha0", 0.3)],
        ],
    );
}

#[test]
fn default_runs_are_accurate_spinning_hoop() {
    check(
        "spinning-hoop",
        [
            &[("omega0", 2.0)],
            &[("alpha0", 1.0)],
            &[("m", 0.5), ("alpha_dot0", 3.0)],
        ],
    );
}

#[test]
fn default_runs_are_accurate_free_hoop() {
    check(
        "free-hoop",
        [
            &[("omega0", 8.0), ("alpha0", 1.2)],
            &[("omega0", 0.6), ("alpha0", 2.75)],
            &[("theta0", 1.0), ("omega0", 3.0)],
        ],
    );
}

#[test]
fn default_runs_are_accurate_free_body() {
    check(
        "free-body",
        [
            &[("I1", 1.0), ("I2", 1.5), ("I3", 2.2)],
            &[("m1", 1.0), ("m2", 0.1), ("m3", -0.3)],
            &[("I2", 2.9), ("m3", 2.0)],
        ],
    );
}

#[test]
fn default_runs_are_accurate_dzhanibekov() {
    check(
        "dzhanibekov",
        [
            &[("spin", 10.0)],
            &[("perturbation", 1e-2)],
            &[("spin", 30.0), ("mass", 0.2)],
        ],
    );
}

#[test]
fn default_runs_are_accurate_heavy_top() {
    check(
        "heavy-top",
        [
            &[("spin0", 20.0)],
            &[("tilt0", 0.5)],
            &[("mgl", 5.0), ("spin0", 80.0)],
        ],
    );
}

#[test]
fn default_runs_are_accurate_coriolis_drop() {
    check(
        "coriolis-drop",
        [
            &[("h", 50.0)],
            &[("colatitude", 0.7)],
            &[("omega_earth", 1e-3)],
        ],
    );
}
