//! The records tumble writes read back equal to what was written: a run's record
//! (`FILE.csv.json`) through JSON, a work–precision study's rows through the CSV text
//! `work-precision.csv` holds and its manifest through JSON, a sweep's and an atlas's
//! `manifest.json` through JSON, to the bit; and the CSV's columns are the record's fields, in
//! order, so a writer and a reader of the same type agree by construction.

use std::collections::BTreeMap;

use tumble_integrators::registry::Order;
use tumble_output::Provenance;
use tumble_scenarios::RunOptions;
use tumble_scenarios::scene::{Discard, StepControl};
use tumble_scenarios::scenes::find;
use tumble_studies::error_estimate::{Tap, WrittenRows, estimate};
use tumble_studies::hard_cases::Case;
use tumble_studies::hard_cases::atlas::{self, AtlasConfig, Method};
use tumble_studies::hard_cases::record::AtlasRecord;
use tumble_studies::record::{EstimateStatus, Estimated, RunRecord, RunSetup};
use tumble_studies::simulation::{BODY_FRAME, DEFAULT_ENERGY_WARN};
use tumble_studies::sweep::record::SweepRecord;
use tumble_studies::sweep::{self, CheckSize, RunConfig, Shard, SweepDefinition};
use tumble_studies::work_precision::Rung;
use tumble_studies::work_precision::record::{
    FailedRungRecord, LadderRecord, ReferenceRecord, StudyRecord,
};

/// The record of a short run of `scene` with `step`, its error estimated.
fn run_record(scene: &str, step: StepControl) -> RunRecord {
    let scene = find(scene).unwrap();
    let info = scene.info();
    let params = info.default_params();
    let plan = RunOptions {
        step: Some(step),
        t_end: Some(1.0),
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
    let estimated = Estimated::Done(estimate(scene, &params, &plan, &summary, &rows).unwrap());
    RunRecord::new(
        Provenance::now("0.0.0", "unknown", 1),
        &RunSetup {
            info,
            origin: "builtin",
            frame: None,
            params: &params,
            plan: &plan,
        },
        &summary,
        &estimated,
        DEFAULT_ENERGY_WARN,
        "run.csv".to_string(),
        0.25,
    )
}

#[test]
fn a_run_record_reads_back_equal_to_the_one_written() {
    for (scene, step) in [
        ("free-hoop", StepControl::Fixed(1e-2)),
        ("heavy-top", StepControl::Tolerance(1e-10)),
    ] {
        let record = run_record(scene, step);
        assert_eq!(record.step().unwrap(), step);
        assert_eq!(record.frame, BODY_FRAME);
        assert_eq!(record.error_estimate.status, EstimateStatus::Estimated);
        let text = serde_json::to_string_pretty(&record).unwrap();
        let back: RunRecord = serde_json::from_str(&text).unwrap();
        assert_eq!(back, record, "{scene}");
        // Bit for bit, not only as compared numbers.
        assert_eq!(
            back.max_energy_rel_err.to_bits(),
            record.max_energy_rel_err.to_bits()
        );
        assert_eq!(serde_json::to_string_pretty(&back).unwrap(), text);
    }
}

#[test]
fn a_run_records_keys_are_the_files_keys_in_order() {
    let record = run_record("free-hoop", StepControl::Fixed(1e-2));
    let value = serde_json::to_value(&record).unwrap();
    let text = serde_json::to_string_pretty(&record).unwrap();
    let top: Vec<&str> = text
        .lines()
        .filter_map(|l| l.strip_prefix("  \"")?.split_once('"').map(|(k, _)| k))
        .collect();
    assert_eq!(
        top,
        [
            "provenance",
            "scene",
            "origin",
            "frame",
            "parameters",
            "integrator",
            "dt",
            "tol",
            "t_end",
            "every",
            "at",
            "csv",
            "columns",
            "rows",
            "steps",
            "evaluations",
            "reached_t",
            "max_energy_rel_err",
            "energy_warning",
            "error_estimate",
            "wall_time_s",
        ]
    );
    // An estimate that is off or failed carries no figures.
    assert!(value["error_estimate"]["final"].is_f64());
    let mut off = record.clone();
    off.error_estimate = tumble_studies::record::EstimateRecord::of(&Estimated::Off);
    let off_value = serde_json::to_value(&off).unwrap();
    assert_eq!(
        off_value["error_estimate"],
        serde_json::json!({"status": "off"})
    );
    let back: RunRecord = serde_json::from_value(off_value).unwrap();
    assert_eq!(back, off);
}

#[test]
fn a_record_with_both_or_neither_step_is_refused() {
    let mut record = run_record("free-hoop", StepControl::Fixed(1e-2));
    record.tol = Some(1e-9);
    assert!(
        record
            .step()
            .unwrap_err()
            .to_string()
            .contains("both `dt` and `tol`")
    );
    record.dt = None;
    record.tol = None;
    assert!(record.step().unwrap_err().to_string().contains("neither"));
}

fn rung(integrator: &str, order: Order, control: StepControl, error: f64) -> Rung {
    let (dt, tol) = control.dt_tol();
    Rung {
        integrator: integrator.to_string(),
        order,
        dt,
        tol,
        steps: 4096,
        evaluations: 16385,
        error,
        max_energy_rel_err: 3.1e-13,
        wall_time_s: 1.2345678901234567e-5,
        repeats: 7,
    }
}

#[test]
fn work_precision_rows_read_back_from_their_csv_equal_to_those_written() {
    let rows = vec![
        rung(
            "rk4",
            Order::Finite(4),
            StepControl::Fixed(1.0 / 3.0),
            0.03819485488124899,
        ),
        rung(
            "dop853",
            Order::Finite(8),
            StepControl::Tolerance(1e-10),
            4.8e-15,
        ),
        rung("exact", Order::Exact, StepControl::Fixed(0.5), 0.0),
        rung(
            "taylor",
            Order::Variable,
            StepControl::Tolerance(1e-14),
            1.0e-300,
        ),
    ];
    let text = Rung::csv_text(&rows).unwrap();
    // Rust's shortest decimal form, never an exponent; an absent step or tolerance empty.
    assert_eq!(
        text.lines().nth(2).unwrap(),
        "dop853,8,,0.0000000001,4096,16385,0.0000000000000048,0.00000000000031,\
         0.000012345678901234568,7"
    );
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let back: Vec<Rung> = reader.deserialize().collect::<Result<_, _>>().unwrap();
    assert_eq!(back, rows);
    for (a, b) in back.iter().zip(&rows) {
        assert_eq!(a.error.to_bits(), b.error.to_bits());
        assert_eq!(a.wall_time_s.to_bits(), b.wall_time_s.to_bits());
    }
    // An order that is none of a number, `exact` and `variable` is refused, naming it.
    let damaged = text.replacen("rk4,4,", "rk4,fourth,", 1);
    let e = csv::Reader::from_reader(damaged.as_bytes())
        .deserialize::<Rung>()
        .next()
        .unwrap()
        .unwrap_err();
    assert!(e.to_string().contains("order `fourth`"), "{e}");
}

#[test]
fn work_precision_columns_are_the_row_records_fields_in_order() {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.serialize(rung("rk4", Order::Finite(4), StepControl::Fixed(0.1), 1e-3))
        .unwrap();
    let serialized = String::from_utf8(w.into_inner().unwrap()).unwrap();
    let header = serialized.lines().next().unwrap();
    assert_eq!(header, Rung::COLUMNS.join(","));
    let written = Rung::csv_text(&[] as &[Rung]).unwrap();
    assert_eq!(written.trim_end(), header);
}

#[test]
fn a_study_record_reads_back_equal_to_the_one_written() {
    let ladder = |name: &str, order: Order| LadderRecord {
        failures: vec![FailedRungRecord {
            control: "dt = 0.5".to_string(),
            reason: "the Newton iteration did not converge".to_string(),
        }],
        name: name.to_string(),
        order,
        rungs: 12,
        stopped: "error below 1e-14".to_string(),
    };
    let record = StudyRecord {
        command: "work-precision".to_string(),
        error: tumble_studies::work_precision::record::ERROR_WORDS.to_string(),
        integrators: vec![
            ladder("rk4", Order::Finite(4)),
            ladder("exact", Order::Exact),
            ladder("taylor", Order::Variable),
        ],
        max_run_seconds: 0.5,
        origin: "builtin".to_string(),
        parameters: BTreeMap::from([("omega0".to_string(), 4.0), ("m".to_string(), 0.1)]),
        provenance: Provenance::now("0.0.0", "unknown", 1),
        reference: ReferenceRecord {
            agreement: 3.2e-15,
            cross_check: "dop853 tol = 1e-13".to_string(),
            method: "gauss12 dt = 6.25e-4".to_string(),
            self_agreement: 1e-16,
            self_check: "gauss12 dt = 3.125e-4".to_string(),
        },
        scene: "free-hoop".to_string(),
        t_end: 10.0,
        tumble_version: "0.0.0".to_string(),
        wall_time: tumble_studies::work_precision::record::WALL_TIME_WORDS.to_string(),
    };
    let text = serde_json::to_string_pretty(&record).unwrap();
    // The orders as the manifest has always written them: a number, null, "variable".
    assert!(text.contains("\"order\": 4,"), "{text}");
    assert!(text.contains("\"order\": null,"), "{text}");
    assert!(text.contains("\"order\": \"variable\","), "{text}");
    let back: StudyRecord = serde_json::from_str(&text).unwrap();
    assert_eq!(back, record);
}

/// `text` read back as a `T` is the record written, and writes the same text: every `f64`
/// to the bit (two `f64`s with the same shortest decimal form are one).
fn reads_back_to_the_bit<T>(record: &T) -> T
where
    T: serde::Serialize + serde::de::DeserializeOwned + PartialEq + std::fmt::Debug,
{
    let text = serde_json::to_string_pretty(record).unwrap();
    let back: T = serde_json::from_str(&text).unwrap();
    assert_eq!(&back, record);
    assert_eq!(serde_json::to_string_pretty(&back).unwrap(), text);
    back
}

#[test]
fn a_sweep_record_reads_back_equal_to_the_one_written() {
    let refined = SweepDefinition::parse(
        include_str!("../fixtures/refined-map.sweep.toml"),
        "refined.toml",
        &[],
    )
    .unwrap();
    let listed = SweepDefinition::parse(
        "scene = \"free-hoop\"\n[run]\nt_end = 0.5\n[[axes]]\nparameter = \"omega0\"\n\
         values = [1.5, 2.0, 3.25]\n",
        "listed.toml",
        &[],
    )
    .unwrap();
    let random = SweepDefinition::parse(
        "scene = \"free-hoop\"\n[run]\nt_end = 0.5\n[[axes]]\nparameter = \"omega0\"\n\
         range = [1.0, 6.0]\nspacing = \"log\"\n[random]\nsamples = 3\nseed = 42\n",
        "random.toml",
        &[],
    )
    .unwrap();
    let tmp = tempfile::tempdir().unwrap();
    for (k, def) in [refined, listed, random].iter().enumerate() {
        let dir = tmp.path().join(k.to_string());
        let report = sweep::run(def, &dir, &RunConfig::default(), &mut |_| {}).unwrap();
        let check = sweep::check_sweep(def, &report.rows, CheckSize::Points(2), 1).unwrap();
        let record = SweepRecord::new(
            Provenance::now("0.0.0", "unknown", 1),
            def,
            &report,
            Shard::ALL,
            "sweep",
            &["tilt-map.png".to_string()],
            check.as_ref().map(|c| (c, 1e-3)),
        );
        assert_eq!(record.points, report.total);
        assert_eq!(record.refinement.is_some(), k == 0);
        assert!(record.self_check.is_some());
        let back = reads_back_to_the_bit(&record);
        assert_eq!(back.definition.axes.len(), def.axes.len(), "{}", def.origin);
    }
}

#[test]
fn an_atlas_record_reads_back_equal_to_the_one_written() {
    let cases = [Case::parse(super::hard_cases::QUICK, "quick.case.toml").unwrap()];
    let methods = [
        Method::parse("rk4:dt=0.01").unwrap(),
        Method::parse("dop853").unwrap(),
    ];
    let tmp = tempfile::tempdir().unwrap();
    let config = AtlasConfig {
        threads: 1,
        run_seconds: 60.0,
        budget: 600.0,
        resume: false,
        cancel: None,
    };
    let report = atlas::run(&cases, &methods, tmp.path(), &config, &|_, _| {}).unwrap();
    let record = AtlasRecord::new(
        Provenance::now("0.0.0", "unknown", 1),
        &cases,
        &methods,
        &report,
        600.0,
        60.0,
    );
    assert_eq!(record.methods, ["rk4:dt=0.01", "dop853"]);
    assert_eq!(record.counts.values().sum::<usize>(), 2);
    let back = reads_back_to_the_bit(&record);
    assert_eq!(back.cases[0].scene, "free-hoop");
}
