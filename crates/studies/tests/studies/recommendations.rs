//! What `tumble scenes` recommends holds: every recommended method runs its scene, and the
//! first method of each accuracy band reaches the band's finest error at the scene's default
//! parameters and horizon, against the scene's reference in the work–precision norm, at one of
//! a short ladder of settings: a tolerance of the target down to a millionth of it (not below
//! 1e-14; an unstable motion, such as the spinning hoop's bead starting near the top, amplifies
//! the local errors by thousands), or the scene's default step down to a 256th of it.

use tumble_integrators::registry;
use tumble_scenarios::scenes::builtin;
use tumble_scenarios::{Observe, StepControl};
use tumble_studies::work_precision::{final_state, plan, reference, state_error};

#[test]
fn recommended_methods_run_their_scenes() {
    for scene in builtin() {
        let info = scene.info();
        for r in scene.recommendations() {
            assert!(!r.integrators.is_empty(), "{}: {}", info.name, r.purpose);
            for name in r.integrators {
                assert!(
                    info.runs(name),
                    "{}: `{name}` is recommended for {} but does not run the scene",
                    info.name,
                    r.purpose
                );
            }
        }
    }
}

#[test]
fn recommended_methods_reach_their_error_bands() {
    let mut checked = 0;
    for scene in builtin() {
        let info = scene.info();
        let params = info.default_params();
        let t_end = info.default_t_end;
        let reference = reference(*scene, &params, t_end).unwrap();
        for r in scene.recommendations() {
            let Some(target) = r.finest_error else {
                continue;
            };
            let name = r.integrators[0];
            let method = registry::find(name).unwrap();
            let settings: Vec<StepControl> = if method.properties.adaptive {
                (0..7)
                    .map(|k| target / 10f64.powi(k))
                    .filter(|&tol| tol >= 1e-14)
                    .map(StepControl::Tolerance)
                    .collect()
            } else {
                (0..9)
                    .map(|k| StepControl::Fixed(info.default_step / 2f64.powi(k)))
                    .collect()
            };
            let errors: Vec<f64> = settings
                .iter()
                .map(|&step| {
                    let plan = plan(info, name, step, t_end, Observe::Ends).unwrap();
                    let (state, _) = final_state(*scene, &params, &plan).unwrap();
                    state_error(info, &state, &reference.state)
                })
                .collect();
            // An error of exactly zero is the reference's own run (the same method and step),
            // which proves nothing: it does not count.
            let best = errors
                .iter()
                .copied()
                .filter(|&e| e > 0.0)
                .fold(f64::INFINITY, f64::min);
            eprintln!(
                "{}: {} — {name} reaches {best:.2e} (target {target:.0e})",
                info.name, r.purpose
            );
            assert!(
                best <= target,
                "{}: `{name}` is recommended for {} but its errors are {errors:?}",
                info.name,
                r.purpose
            );
            checked += 1;
        }
    }
    assert!(checked >= 12, "only {checked} bands checked");
}
