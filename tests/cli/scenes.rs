//! `tumble scenes`: every built-in scene is listed, as text and as JSON, with what the library
//! documents for it.

use std::process::{Command, Output};

use serde_json::Value;
use tumble_scenarios::Domain;
use tumble_scenarios::recommendation::measurements;
use tumble_scenarios::scenes::builtin;

use crate::support::tumble_in;

fn tumble(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tumble"))
        .args(args)
        .output()
        .expect("cannot run the tumble binary")
}

#[test]
fn json_lists_every_builtin_scene_with_its_parameters_columns_and_defaults() {
    let out = tumble(&["scenes", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).expect("stdout is one JSON value");
    let listed = v.as_array().expect("an array of scenes");
    assert_eq!(listed.len(), builtin().len());
    for (entry, scene) in listed.iter().zip(builtin()) {
        let info = scene.info();
        assert_eq!(entry["name"], info.name);
        assert_eq!(entry["summary"], info.summary);
        let columns: Vec<&str> = entry["columns"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_str().unwrap())
            .collect();
        assert_eq!(columns, info.columns());
        let params = entry["parameters"].as_array().unwrap();
        assert_eq!(params.len(), info.parameters.len());
        for (p, spec) in params.iter().zip(info.parameters) {
            assert_eq!(p["name"], spec.name);
            assert_eq!(p["default"].as_f64().unwrap(), spec.default);
            assert_eq!(p["unit"], spec.unit);
            assert_eq!(p["description"], spec.description);
            assert_eq!(p["domain"], spec.domain.to_string());
        }
        assert_eq!(entry["default_integrator"], info.default_integrator);
        assert_eq!(entry["default_t_end"].as_f64().unwrap(), info.default_t_end);
        // Exactly one of a default step and a default tolerance.
        assert!(entry.get("default_dt").is_some() != entry.get("default_tol").is_some());
        let integrators: Vec<&str> = entry["integrators"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_str().unwrap())
            .collect();
        assert_eq!(integrators, info.integrators());
        assert!(!entry["conserved"].as_array().unwrap().is_empty());
        let recommended = entry["recommended"].as_array().unwrap();
        assert_eq!(recommended.len(), scene.recommendations().len());
        let measured = measurements().unwrap().scene(info.name).unwrap();
        assert_eq!(
            entry["measured_by"],
            serde_json::from_str::<Value>(&serde_json::to_string(&measured.provenance).unwrap())
                .unwrap()
        );
        assert_eq!(entry["measured_against"], measured.reference.as_str());
        for (r, rec) in recommended.iter().zip(scene.recommendations()) {
            assert_eq!(r["purpose"], rec.purpose);
            assert_eq!(r["integrators"], serde_json::json!(rec.integrators));
            assert_eq!(r["compared_with"], serde_json::json!(rec.compared_with));
            assert_eq!(r["reason"], rec.reason);
            assert_eq!(r["finest_error"].as_f64(), rec.finest_error());
            // Through JSON text, as the listing's numbers come (serde_json reads a decimal to
            // within an ulp, not always to the nearest double).
            let json = |v: String| serde_json::from_str::<Value>(&v).unwrap();
            let band = measured
                .band(rec.purpose)
                .map(|b| json(serde_json::to_string(b).unwrap()));
            let long = measured
                .long_run(rec.purpose)
                .map(|l| json(serde_json::to_string(l).unwrap()));
            assert_eq!(r.get("to_error"), band.as_ref());
            assert_eq!(r.get("long_run"), long.as_ref());
        }
    }
}

#[test]
fn text_listing_recommends_methods_by_purpose_for_every_builtin_scene() {
    let out = tumble(&["scenes"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for scene in builtin() {
        let recs = scene.recommendations();
        assert!(
            !recs.is_empty(),
            "{} has no recommendation",
            scene.info().name
        );
        for r in recs {
            let line = format!("{}: {}", r.purpose, r.integrators.join(", "));
            assert!(text.contains(&line), "missing: {line}");
        }
    }
}

/// The listing's times are data: every time it prints stands on a line of measurements (`to
/// 1e-8: …`), and every scene's block ends its recommendations with how they were measured
/// (the command, the date, the machine).
#[test]
fn text_listing_prints_times_only_as_measurements_with_their_provenance() {
    let out = tumble(&["scenes"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let mut timed = 0;
    for line in text.lines() {
        if line.contains(" µs") || line.contains(" ms") {
            assert!(line.trim_start().starts_with("to "), "timing prose: {line}");
            timed += 1;
        }
    }
    assert!(timed >= 10, "{timed} lines of times");
    for scene in builtin() {
        let name = scene.info().name;
        assert!(
            text.contains(&format!(
                "  measured     by `tumble work-precision {name} --recommend"
            )),
            "{name}: no provenance line"
        );
    }
}

#[test]
fn text_listing_names_every_scene_parameter_and_unit() {
    let out = tumble(&["scenes"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for scene in builtin() {
        let info = scene.info();
        assert!(text.contains(&format!("{} — ", info.name)), "{}", info.name);
        for p in info.parameters {
            assert!(
                text.lines().any(|l| {
                    let cells: Vec<&str> = l.split_whitespace().collect();
                    cells.first() == Some(&p.name) && (p.unit.is_empty() || cells.contains(&p.unit))
                }),
                "{}: parameter {} missing",
                info.name,
                p.name
            );
        }
    }
    // A fixed-step default is shown as its step.
    let driven = tumble_scenarios::scenes::find("driven-hoop")
        .unwrap()
        .info();
    let line = format!(
        "default run  {}, dt = {} s, t_end = {} s",
        driven.default_integrator, driven.default_step, driven.default_t_end
    );
    assert!(text.contains(&line), "{line} missing");
}

/// The values at and just beyond the ends of `domain`: `(value, inside)`.
fn boundary_values(domain: Domain) -> Vec<(f64, bool)> {
    let tiny = f64::from_bits(1); // the smallest positive double
    let non_finite = [
        (f64::INFINITY, false),
        (f64::NEG_INFINITY, false),
        (f64::NAN, false),
    ];
    let ends: &[(f64, bool)] = match domain {
        Domain::Positive => &[(0.0, false), (-0.0, false), (-tiny, false)],
        Domain::NonNegative => &[(0.0, true), (-0.0, true), (-tiny, false)],
        Domain::NonZero => &[(0.0, false), (-0.0, false)],
        // No finite end: zero, where a rate or an angle changes sign.
        Domain::Finite => &[(0.0, true)],
    };
    ends.iter().copied().chain(non_finite).collect()
}

/// Every scene, every parameter, at the ends of its documented domain (`tumble scenes`): a
/// value inside runs from the scene's defaults to a finite trajectory, or is refused before
/// the run by a message that names the parameter; a value outside is refused so. Never a
/// numerical failure at t = 0 (`m = 0` of the free hoop was one: inside ">= 0", every
/// integrator failed on its first step).
#[test]
fn every_domain_boundary_runs_or_is_refused_naming_the_parameter() {
    let tmp = tempfile::tempdir().unwrap();
    let mut wrong = Vec::new();
    let mut cases = 0;
    for scene in builtin() {
        let info = scene.info();
        // A few steps: what fails at a boundary fails at once.
        let t_end = (20.0 * info.default_step)
            .min(info.default_t_end)
            .to_string();
        for p in info.parameters {
            for (value, inside) in boundary_values(p.domain) {
                cases += 1;
                let set = format!("{}={value:?}", p.name);
                let args = ["simulate", info.name, "--set", &set, "--t-end", &t_end];
                let out = tumble_in(tmp.path(), &args);
                let err = String::from_utf8_lossy(&out.stderr);
                let named = err.contains(&format!("parameter `{}`", p.name));
                let verdict = match out.status.code() {
                    Some(0) if inside => {
                        let text = String::from_utf8_lossy(&out.stdout);
                        let finite = text.lines().skip(1).all(|l| {
                            l.split(',')
                                .all(|c| c.parse::<f64>().is_ok_and(f64::is_finite))
                        });
                        let rows = text.lines().count();
                        if finite && rows > 2 {
                            None
                        } else {
                            Some(format!("ran, but its output is not {rows} finite rows"))
                        }
                    }
                    Some(0) => Some("ran outside its domain".to_string()),
                    Some(1) if named => None,
                    code => Some(format!("exit {code:?} without naming the parameter")),
                };
                if let Some(v) = verdict {
                    wrong.push(format!(
                        "{} {set} ({} {}): {v}\n    {}",
                        info.name,
                        if inside { "inside" } else { "outside" },
                        p.domain,
                        err.trim_end().replace('\n', "\n    ")
                    ));
                }
            }
        }
    }
    assert!(cases > 100, "only {cases} boundary cases");
    assert!(
        wrong.is_empty(),
        "{} of {cases} boundary cases went wrong:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
}
