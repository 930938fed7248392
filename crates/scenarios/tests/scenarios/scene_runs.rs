//! Running built-in scenes: rows and columns, defaults, overrides, and bad options rejected
//! before any work starts.

use tumble_scenarios::scene::Rows;
use tumble_scenarios::scenes::{builtin, find};
use tumble_scenarios::{RunOptions, SceneError, StepControl};

#[test]
fn every_builtin_scene_runs_on_its_defaults_and_conserves_its_energy() {
    for scene in builtin() {
        let info = scene.info();
        let params = info.default_params();
        let mut rows = Rows::default();
        let opts = RunOptions {
            t_end: Some(2.0),
            ..RunOptions::default()
        };
        let summary = scene.run(&params, &opts, &mut rows).unwrap();
        let columns = info.columns();
        assert_eq!(columns[0], "t");
        assert!(rows.0.iter().all(|r| r.len() == columns.len()));
        assert_eq!(rows.0.first().unwrap()[0], 0.0);
        assert!((rows.0.last().unwrap()[0] - 2.0).abs() < 1e-12);
        // Default integrators: Gauss s = 4 at h = 0.01 (hoops), DOP853 at 1e-10 (drop) conserve
        // energy to ~1e-10 over 2 s; the free hoop's LGVI (order 2, h = 1e-3) to ~1e-6.
        let bound = if info.default_integrator == "lgvi" {
            1e-5
        } else {
            1e-9
        };
        assert!(
            summary.max_energy_rel_err < bound,
            "{}: {}",
            info.name,
            summary.max_energy_rel_err
        );
        let k = columns.iter().position(|c| c == "energy_rel_err").unwrap();
        assert!(rows.0.iter().all(|r| r[k] <= summary.max_energy_rel_err));
    }
}

#[test]
fn every_n_steps_thins_the_rows() {
    let scene = find("driven-hoop").unwrap();
    let params = scene.info().default_params();
    let mut rows = Rows::default();
    let opts = RunOptions {
        t_end: Some(1.0),
        every: Some(10),
        step: Some(StepControl::Fixed(0.01)),
        ..RunOptions::default()
    };
    scene.run(&params, &opts, &mut rows).unwrap();
    // Steps 0, 10, …, 100 (the observer also sees the final state once).
    assert!((11..=12).contains(&rows.0.len()), "{} rows", rows.0.len());
}

#[test]
fn bad_options_and_parameters_are_rejected_with_their_names() {
    let scene = find("spinning-hoop").unwrap();
    let mut params = scene.info().default_params();
    let run = |p: &tumble_scenarios::Params, o: RunOptions| scene.run(p, &o, &mut Rows::default());
    for (opts, what) in [
        (
            RunOptions {
                step: Some(StepControl::Fixed(0.0)),
                ..Default::default()
            },
            "dt",
        ),
        (
            RunOptions {
                step: Some(StepControl::Fixed(-0.1)),
                ..Default::default()
            },
            "dt",
        ),
        (
            RunOptions {
                step: Some(StepControl::Fixed(f64::NAN)),
                ..Default::default()
            },
            "dt",
        ),
        (
            RunOptions {
                step: Some(StepControl::Fixed(100.0)),
                t_end: Some(1.0),
                ..Default::default()
            },
            "dt",
        ),
        (
            RunOptions {
                t_end: Some(-1.0),
                ..Default::default()
            },
            "t_end",
        ),
        (
            RunOptions {
                every: Some(0),
                ..Default::default()
            },
            "every",
        ),
        (
            RunOptions {
                integrator: Some("dop853".into()),
                step: Some(StepControl::Fixed(0.1)),
                ..Default::default()
            },
            "dt",
        ),
        (
            RunOptions {
                integrator: Some("rk4".into()),
                step: Some(StepControl::Tolerance(1e-8)),
                ..Default::default()
            },
            "tol",
        ),
    ] {
        let err = run(&params, opts.clone()).unwrap_err();
        assert!(err.to_string().starts_with(what), "{opts:?}: {err}");
    }
    assert!(matches!(
        run(
            &params,
            RunOptions {
                integrator: Some("nope".into()),
                ..Default::default()
            }
        ),
        Err(SceneError::UnsupportedIntegrator { .. })
    ));
    assert!(matches!(
        params.set("mass", 1.0),
        Err(SceneError::UnknownParameter { .. })
    ));
    assert!(matches!(
        params.set("M", -1.0),
        Err(SceneError::InvalidParameter { .. })
    ));
    assert!(matches!(
        params.set("g", f64::NAN),
        Err(SceneError::InvalidParameter { .. })
    ));
    params.set("omega0", 2.0).unwrap();
    assert_eq!(params.get("omega0").unwrap(), 2.0);
    assert!(matches!(
        find("no-such-scene"),
        Err(SceneError::UnknownScene { .. })
    ));
}

/// Dispatch covers the registry: every method a scene derives from its problem kinds builds a
/// stepper and runs the scene (20 steps at its default step, or a tolerance of 1e-8), conserving
/// energy to the method's accuracy (1e-3 relative at this short horizon).
#[test]
fn every_scene_runs_every_integrator_it_lists() {
    use tumble_integrators::registry;
    for scene in builtin() {
        let info = scene.info();
        let params = info.default_params();
        let integrators = info.integrators();
        assert!(
            integrators.contains(&info.default_integrator),
            "{}",
            info.name
        );
        for name in integrators {
            let method = registry::find(name).unwrap();
            let step = if method.properties.adaptive {
                StepControl::Tolerance(1e-8)
            } else {
                StepControl::Fixed(info.default_step)
            };
            let opts = RunOptions {
                integrator: Some(name.to_string()),
                step: Some(step),
                t_end: Some(20.0 * info.default_step),
                ..RunOptions::default()
            };
            let summary = scene
                .run(&params, &opts, &mut tumble_scenarios::scene::Discard)
                .unwrap_or_else(|e| panic!("{} with {name}: {e}", info.name));
            assert!(summary.steps >= 1, "{} with {name}", info.name);
            assert!(
                summary.max_energy_rel_err < 1e-3,
                "{} with {name}: energy error {}",
                info.name,
                summary.max_energy_rel_err
            );
        }
    }
}

/// A method that shares no problem kind with a scene is refused before any work, with the
/// scene's applicable methods in the message.
#[test]
fn a_method_of_another_problem_kind_is_refused_with_the_applicable_ones() {
    let scene = find("free-hoop").unwrap();
    let opts = RunOptions {
        integrator: Some("verlet".into()),
        ..RunOptions::default()
    };
    let err = scene
        .run(&scene.info().default_params(), &opts, &mut Rows::default())
        .unwrap_err();
    assert!(
        matches!(err, SceneError::UnsupportedIntegrator { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("lgvi"), "{err}");
    // The events of the Coriolis drop need dense output: every method of its kind has one
    // (Gauss–Legendre through its collocation polynomial); the rigid-body methods are not
    // of its kind.
    let drop = find("coriolis-drop").unwrap().info();
    assert!(drop.runs("gauss8") && drop.runs("dop853") && drop.runs("rk4"));
    assert!(!drop.runs("lgvi"));
}

/// `every` thins the rows but never drops the final state: 1000 steps written every 300th
/// give t = 0, 0.3, 0.6, 0.9 and 1.
#[test]
fn the_final_state_is_written_whatever_the_cadence() {
    let scene = find("free-body").unwrap();
    let opts = RunOptions {
        step: Some(StepControl::Fixed(1e-3)),
        t_end: Some(1.0),
        every: Some(300),
        ..RunOptions::default()
    };
    let mut rows = Rows::default();
    let summary = scene
        .run(&scene.info().default_params(), &opts, &mut rows)
        .unwrap();
    let times: Vec<f64> = rows.0.iter().map(|r| r[0]).collect();
    assert_eq!(times, [0.0, 0.3, 0.6, 0.9, 1.0]);
    assert_eq!(summary.rows, 5);
}

/// Rows at chosen times come from the method's dense output: DOP853's rows at t = 0.37, 1.5,
/// 2.25 agree with Gauss–Legendre 12 stepping exactly onto those times to its accuracy, and
/// the steps (hence the final state) are those of the run without output times.
#[test]
fn rows_at_chosen_times_agree_with_a_run_that_steps_onto_them() {
    let scene = find("free-hoop").unwrap();
    let params = scene.info().default_params();
    let at = vec![0.37, 1.5, 2.25];
    let dense = RunOptions {
        integrator: Some("dop853".into()),
        step: Some(StepControl::Tolerance(1e-13)),
        t_end: Some(3.0),
        at: Some(at.clone()),
        ..RunOptions::default()
    };
    let mut rows = Rows::default();
    let with = scene.run(&params, &dense, &mut rows).unwrap();
    assert_eq!(
        rows.0.iter().map(|r| r[0]).collect::<Vec<_>>(),
        [0.37, 1.5, 2.25, 3.0]
    );
    let plain = RunOptions {
        at: None,
        ..dense.clone()
    };
    let mut all = Rows::default();
    let without = scene.run(&params, &plain, &mut all).unwrap();
    assert_eq!(with.steps, without.steps);
    assert_eq!(rows.0.last().unwrap(), all.0.last().unwrap());
    // Gauss12 at h = 0.01 passes through 0.37, 1.5 and 2.25 (to rounding of k h).
    let fine = RunOptions {
        integrator: Some("gauss12".into()),
        step: Some(StepControl::Fixed(0.01)),
        t_end: Some(3.0),
        ..RunOptions::default()
    };
    let mut reference = Rows::default();
    scene.run(&params, &fine, &mut reference).unwrap();
    let columns = scene.info().columns();
    let state = 1..columns.iter().position(|c| c == "energy").unwrap();
    for row in &rows.0[..3] {
        let r = reference
            .0
            .iter()
            .find(|r| (r[0] - row[0]).abs() < 1e-12)
            .unwrap();
        for k in state.clone() {
            assert!(
                (row[k] - r[k]).abs() < 1e-9,
                "t = {}: {} = {} vs {}",
                row[0],
                columns[k],
                row[k],
                r[k]
            );
        }
    }
}

/// Output times are checked before any work: outside the horizon, out of order, repeated,
/// both `at` and `output_dt`, or a method without dense output — each a named option error.
#[test]
fn bad_output_times_are_refused_before_any_work() {
    let scene = find("free-hoop").unwrap();
    let info = scene.info();
    let bad = [
        (Some(vec![0.5, 11.0]), None, None, "at"),
        (Some(vec![0.5, 0.2]), None, None, "at"),
        (Some(vec![0.5, 0.5]), None, None, "at"),
        (Some(vec![]), None, None, "at"),
        (None, Some(-1.0), None, "output_dt"),
        (None, Some(0.0), None, "output_dt"),
        (Some(vec![1.0]), Some(0.1), None, "output_dt"),
    ];
    for (at, output_dt, integrator, option) in bad {
        let opts = RunOptions {
            integrator: Some(integrator.unwrap_or("dop853").to_string()),
            at: at.clone(),
            output_dt,
            ..RunOptions::default()
        };
        match opts.resolve(info) {
            Err(SceneError::InvalidOption { option: o, .. }) => {
                assert_eq!(o, option, "{at:?} {output_dt:?}");
            }
            other => panic!("{at:?} {output_dt:?}: {other:?}"),
        }
    }
    let every = RunOptions {
        integrator: Some("gauss8".into()),
        step: Some(StepControl::Fixed(0.01)),
        t_end: Some(1.0),
        output_dt: Some(0.25),
        ..RunOptions::default()
    };
    let plan = every.resolve(info).unwrap();
    assert_eq!(plan.times.unwrap(), [0.0, 0.25, 0.5, 0.75, 1.0]);
}
