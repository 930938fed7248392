//! `TABLE:BASE` compositions reached from scenes: each runs every scene its base runs, is the
//! same method as its short name, reaches the table's order, and a method that cannot run a
//! scene is refused with the reason and the names that can.

use tumble_scenarios::scene::Rows;
use tumble_scenarios::scenes::{builtin, find};
use tumble_scenarios::{RunOptions, SceneError, StepControl};

fn final_row(scene: &str, integrator: &str, h: f64, t_end: f64) -> Vec<f64> {
    let scene = find(scene).unwrap();
    let opts = RunOptions {
        integrator: Some(integrator.into()),
        step: Some(StepControl::Fixed(h)),
        t_end: Some(t_end),
        every: Some(u64::MAX),
        ..RunOptions::default()
    };
    let mut rows = Rows::default();
    scene
        .run(&scene.info().default_params(), &opts, &mut rows)
        .unwrap_or_else(|e| panic!("{integrator}: {e}"));
    rows.0.pop().unwrap()
}

#[test]
fn every_scene_runs_a_composition_of_each_base_it_offers() {
    for scene in builtin() {
        let info = scene.info();
        let bases = info.composition_bases();
        assert!(
            !bases.is_empty(),
            "{}: every scene has a symmetric base",
            info.name
        );
        for base in bases {
            let name = format!("yoshida4:{base}");
            assert!(info.runs(&name), "{} {name}", info.name);
            let opts = RunOptions {
                integrator: Some(name.clone()),
                step: Some(StepControl::Fixed(info.default_step)),
                t_end: Some(20.0 * info.default_step),
                ..RunOptions::default()
            };
            let summary = scene
                .run(&info.default_params(), &opts, &mut Rows::default())
                .unwrap_or_else(|e| panic!("{} with {name}: {e}", info.name));
            assert!(summary.max_energy_rel_err < 1e-6, "{} {name}", info.name);
        }
    }
}

#[test]
fn a_table_base_name_is_the_same_method_as_its_short_name() {
    // The registry's short names are these compositions: bit for bit the same final state.
    for (scene, long, short) in [
        ("heavy-top", "kahan-li8:lgvi", "lgvi8"),
        ("free-hoop", "mclachlan4:lgvi", "lgvi4"),
        ("free-body", "kahan-li6:split2", "split6"),
    ] {
        assert_eq!(
            final_row(scene, long, 0.01, 0.5),
            final_row(scene, short, 0.01, 0.5),
            "{scene}"
        );
    }
}

#[test]
fn compositions_of_the_implicit_midpoint_reach_the_tables_order() {
    // The driven hoop as an ODE: error at t = 1 against gauss12 at a fine step, at h and h/2.
    let reference = final_row("driven-hoop", "gauss12", 1e-3, 1.0);
    for (name, order) in [("mclachlan4:gauss2", 4.0), ("kahan-li6:gauss2", 6.0)] {
        let error = |h: f64| {
            let row = final_row("driven-hoop", name, h, 1.0);
            (row[1] - reference[1])
                .abs()
                .max((row[2] - reference[2]).abs())
        };
        let observed = (error(0.05) / error(0.025)).log2();
        assert!((observed - order).abs() < 0.3, "{name}: order {observed}");
    }
}

#[test]
fn a_table_named_alone_is_refused_with_the_compositions_that_run_the_scene() {
    let scene = find("free-body").unwrap();
    let opts = RunOptions {
        integrator: Some("kahan-li8".into()),
        ..RunOptions::default()
    };
    let err = scene
        .run(&scene.info().default_params(), &opts, &mut Rows::default())
        .unwrap_err();
    assert!(matches!(err, SceneError::UnsupportedIntegrator { .. }));
    let text = err.to_string();
    assert!(text.contains("separable Hamiltonian"), "{text}");
    assert!(
        text.contains("kahan-li8:lgvi") && text.contains("kahan-li8:split2"),
        "{text}"
    );
    // The coupled hoop has no principal-axis splitting: `split2` compositions are refused.
    let hoop = find("free-hoop").unwrap().info();
    assert!(hoop.runs("kahan-li8:lgvi") && !hoop.runs("kahan-li8:split2"));
    let unknown = hoop.unsupported("kahan-li9:lgvi").to_string();
    assert!(unknown.contains("no such composition"), "{unknown}");
}
