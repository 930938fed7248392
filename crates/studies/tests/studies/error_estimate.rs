//! A run's error estimate (`error_estimate`) against the true error: the final state's
//! difference from the scene's independent reference (`work_precision::reference`: the exact
//! flow for the free rigid body, else Gauss–Legendre at a step 16 times below the default,
//! cross-checked by DOP853 at 1e-13). On every scene's default run and at least two coarse
//! settings per scene the estimate is within a factor 10 of the true error or above it, and a
//! trustworthy estimate of an error above round-off is within a factor 10 of it.

use tumble_scenarios::RunOptions;
use tumble_scenarios::scene::{Discard, FinalState, StepControl};
use tumble_scenarios::scenes::find;
use tumble_studies::error_estimate::{
    ErrorEstimate, Tap, Trust, WrittenRows, estimate, final_difference,
};
use tumble_studies::work_precision::reference;

/// The estimate of `scene`'s run (`integrator`, `step`: the defaults when `None`) and the true
/// error of its final state against the scene's reference.
fn estimated_and_true(
    scene: &str,
    integrator: Option<&str>,
    step: Option<StepControl>,
) -> (ErrorEstimate, f64) {
    let scene = find(scene).unwrap();
    let info = scene.info();
    let params = info.default_params();
    let plan = RunOptions {
        integrator: integrator.map(str::to_string),
        step,
        ..RunOptions::default()
    }
    .resolve(info)
    .unwrap();
    let mut rows = WrittenRows::new(info);
    let summary = scene
        .simulate(
            &params,
            &plan,
            &mut Tap {
                inner: &mut Discard,
                rows: &mut rows,
            },
        )
        .unwrap();
    let est = estimate(scene, &params, &plan, &summary, &rows).unwrap();
    let r = reference(scene, &params, plan.t_end).unwrap();
    let last = rows.last();
    let ours = FinalState {
        t: last[0],
        values: last[1..].to_vec(),
    };
    let truth = final_difference(info, &ours, &r.state, summary.terminated);
    eprintln!(
        "{:14} {:8} {:14} estimate {:9.2e} (max over {} rows {:9.2e})  true {:9.2e}  ratio {:8.2}  {}",
        info.name,
        plan.integrator(),
        tumble_studies::error_estimate::words(plan.step),
        est.final_error,
        est.rows_compared,
        est.max_error,
        truth,
        est.final_error / truth,
        est.trust_words()
    );
    (est, truth)
}

fn check(scene: &str, integrator: Option<&str>, step: Option<StepControl>) {
    let (est, truth) = estimated_and_true(scene, integrator, step);
    assert!(
        est.final_error >= truth / 10.0,
        "{scene} {integrator:?} {step:?}: estimate {:e} below a tenth of the true error {truth:e}",
        est.final_error
    );
    if est.trust == Trust::Trustworthy && truth > 1e-13 {
        assert!(
            est.final_error <= 10.0 * truth,
            "{scene} {integrator:?} {step:?}: estimate {:e} above 10× the true error {truth:e}",
            est.final_error
        );
    }
}

use StepControl::{Fixed, Tolerance};

#[test]
fn estimates_bound_the_true_error_driven_hoop() {
    check("driven-hoop", None, None);
    check("driven-hoop", Some("rk4"), Some(Fixed(0.01)));
    check("driven-hoop", Some("verlet"), Some(Fixed(0.01)));
    check("driven-hoop", Some("dp5"), Some(Tolerance(1e-6)));
}

#[test]
fn estimates_bound_the_true_error_spinning_hoop() {
    check("spinning-hoop", None, None);
    check("spinning-hoop", Some("rk4"), Some(Fixed(0.01)));
    check("spinning-hoop", Some("gauss4"), Some(Fixed(0.05)));
    check("spinning-hoop", Some("dop853"), Some(Tolerance(1e-7)));
}

#[test]
fn estimates_bound_the_true_error_free_hoop() {
    check("free-hoop", None, None);
    check("free-hoop", Some("lgvi"), Some(Fixed(0.01)));
    check("free-hoop", Some("rk4"), Some(Fixed(0.01)));
    check("free-hoop", Some("dp5"), Some(Tolerance(1e-6)));
}

#[test]
fn estimates_bound_the_true_error_free_body() {
    check("free-body", None, None);
    check("free-body", Some("lgvi"), Some(Fixed(0.01)));
    check("free-body", Some("rk4"), Some(Fixed(0.05)));
    check("free-body", Some("dp5"), Some(Tolerance(1e-6)));
}

#[test]
fn estimates_bound_the_true_error_dzhanibekov() {
    check("dzhanibekov", None, None);
    check("dzhanibekov", Some("split2"), Some(Fixed(1e-3)));
    check("dzhanibekov", Some("rk4"), Some(Fixed(1e-2)));
    check("dzhanibekov", Some("dop853"), Some(Tolerance(1e-7)));
}

#[test]
fn estimates_bound_the_true_error_heavy_top() {
    check("heavy-top", None, None);
    check("heavy-top", Some("lgvi"), Some(Fixed(1e-3)));
    check("heavy-top", Some("rk4"), Some(Fixed(1e-3)));
    check("heavy-top", Some("dop853"), Some(Tolerance(1e-7)));
}

#[test]
fn estimates_bound_the_true_error_coriolis_drop() {
    check("coriolis-drop", None, None);
    check("coriolis-drop", Some("rk4"), Some(Fixed(0.1)));
    check("coriolis-drop", Some("dp5"), Some(Tolerance(1e-6)));
    check("coriolis-drop", Some("gauss4"), Some(Fixed(0.5)));
}
