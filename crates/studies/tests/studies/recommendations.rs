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
            let Some(target) = r.finest_error() else {
                continue;
            };
            let name = r.integrators[0];
            let method = registry::find(name).unwrap();
            let settings: Vec<StepControl> = if method.properties.adaptive {
                // Tolerances down to 1e-14, or to a hundredth of a band that ends at 1e-14
                // (the round-off level: the Taylor method, whose order follows its tolerance,
                // reaches it at a tolerance below it).
                let floor = 1e-14f64.min(target / 100.0);
                (0..7)
                    .map(|k| target / 10f64.powi(k))
                    .filter(|&tol| tol >= floor)
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

/// The embedded measurements (`tumble_scenarios::recommendation::measurements`, written by
/// `tumble work-precision SCENE --recommend`) hold, for every recommendation of every built-in
/// scene, the methods it names and compares in that order: each error band at its finest
/// error, which its first method reached; each long run with every method's energy error or
/// its failure; and nothing for what the recommendations do not measure. The file reads back
/// as it was written.
#[test]
fn embedded_measurements_cover_every_recommendation() {
    use tumble_scenarios::Measure;
    use tumble_scenarios::recommendation::{MEASUREMENTS_TOML, Measurements, measurements};

    let all = measurements().unwrap();
    let names: Vec<&str> = builtin().iter().map(|s| s.info().name).collect();
    for m in &all.scenes {
        assert!(names.contains(&m.name.as_str()), "unknown scene {}", m.name);
        let p = &m.provenance;
        assert!(
            p.command
                .contains(&format!("work-precision {} --recommend", m.name))
        );
        assert!(p.cores > 0 && !p.cpu.is_empty() && !p.date.is_empty());
    }
    for scene in builtin() {
        let info = scene.info();
        let recs = scene.recommendations();
        if recs.is_empty() {
            continue;
        }
        let m = all
            .scene(info.name)
            .unwrap_or_else(|| panic!("{}: not measured", info.name));
        assert_eq!(m.t_end, info.default_t_end, "{}", info.name);
        let (mut bands, mut longs) = (0, 0);
        for r in recs {
            let measured: Vec<&str> = r.measured_methods().collect();
            match r.measure {
                Measure::ToError(target) => {
                    let band = m
                        .band(r.purpose)
                        .unwrap_or_else(|| panic!("{}: {} not measured", info.name, r.purpose));
                    assert_eq!(band.target_error, target);
                    let got: Vec<&str> =
                        band.methods.iter().map(|x| x.integrator.as_str()).collect();
                    assert_eq!(got, measured, "{}: {}", info.name, r.purpose);
                    let first = &band.methods[0];
                    assert!(
                        first.seconds.is_some_and(|s| s > 0.0) && first.best_error <= target,
                        "{}: {} — {first:?}",
                        info.name,
                        r.purpose
                    );
                    bands += 1;
                }
                Measure::LongRun => {
                    let long = m
                        .long_run(r.purpose)
                        .unwrap_or_else(|| panic!("{}: {} not measured", info.name, r.purpose));
                    assert_eq!(long.dt, info.default_step);
                    let got: Vec<&str> =
                        long.methods.iter().map(|x| x.integrator.as_str()).collect();
                    assert_eq!(got, measured, "{}: {}", info.name, r.purpose);
                    for run in &long.methods {
                        assert!(
                            run.max_energy_rel_err.is_some() != run.failed.is_some(),
                            "{}: {run:?}",
                            info.name
                        );
                    }
                    longs += 1;
                }
                Measure::Nothing => {
                    assert!(m.band(r.purpose).is_none() && m.long_run(r.purpose).is_none());
                }
            }
        }
        assert_eq!(
            (bands, longs),
            (m.bands.len(), m.long_runs.len()),
            "{}",
            info.name
        );
    }
    let again = Measurements::parse(&all.to_toml().unwrap()).unwrap();
    assert_eq!(&again, all);
    assert_eq!(Measurements::parse(MEASUREMENTS_TOML).as_ref(), Ok(all));
}

/// A recommendation's reason is physics, never a measurement: no time, no error figure, no run
/// described in it (those are the embedded data's).
#[test]
fn reasons_state_no_measurements() {
    for scene in builtin() {
        for r in scene.recommendations() {
            let reason = r.reason;
            let figure = reason.as_bytes().windows(3).any(|w| {
                w[0].is_ascii_digit() && w[1] == b'e' && (w[2] == b'-' || w[2].is_ascii_digit())
            });
            assert!(
                !figure
                    && !reason.contains("µs")
                    && !reason.contains(" ms")
                    && !reason.contains("run"),
                "{}: {} — {reason}",
                scene.info().name,
                r.purpose
            );
        }
    }
}
