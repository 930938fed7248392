//! `tumble scenes`: every built-in scene is listed, as text and as JSON, with what the library
//! documents for it.

use std::process::{Command, Output};

use serde_json::Value;
use tumble_scenarios::scenes::builtin;

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
