//! Sweep files and their points: parsing, overrides, errors naming key and line, grid and
//! random sampling.

use super::*;

#[test]
fn the_built_in_tilt_map_is_a_valid_grid_of_the_free_hoop() {
    let def = SweepDefinition::tilt_map(&[]).unwrap();
    assert_eq!(def.scene.info().name, "free-hoop");
    assert_eq!(def.axes[0].parameter, "omega0");
    assert_eq!(def.metrics[0], Metric::MaxTilt);
    assert_eq!(def.params.get("g").unwrap(), 9.81);
    assert_eq!(def.params.get("a").unwrap(), 1.0);
    // The critical spin sqrt(g/a) lies inside the spin range.
    let spins = def.axes[0].grid_values();
    let critical = 9.81f64.sqrt();
    assert!(spins[0] < critical && critical < spins[spins.len() - 1]);
}

#[test]
fn grid_points_vary_the_last_axis_fastest_with_exact_decimal_values() {
    let def = small();
    assert_eq!(def.points(), 6);
    let points: Vec<Vec<f64>> = (0..6).map(|i| def.point(i)).collect();
    assert_eq!(
        points,
        vec![
            vec![1.0, 0.5],
            vec![1.0, 2.0],
            vec![3.0, 0.5],
            vec![3.0, 2.0],
            vec![5.0, 0.5],
            vec![5.0, 2.0],
        ]
    );
    let decimals = parse(&SMALL.replace(
        "range = [1.0, 5.0]\ncount = 3",
        "range = [0.1, 3.0]\ncount = 30",
    ))
    .unwrap();
    let values = decimals.axes[0].grid_values();
    for (k, v) in values.iter().enumerate() {
        let exact: f64 = format!("{}.{}", (k + 1) / 10, (k + 1) % 10)
            .parse()
            .unwrap();
        assert_eq!(*v, exact, "value {k}");
    }
    // Log spacing: equal ratios, exact ends.
    let log = parse(&SMALL.replace("count = 3", "count = 3\nspacing = \"log\"")).unwrap();
    let v = log.axes[0].grid_values();
    assert_eq!(v[0], 1.0);
    assert_eq!(v[2], 5.0);
    assert!((v[1] - 5f64.sqrt()).abs() < 1e-15);
}

#[test]
fn splitmix64_matches_the_reference_outputs() {
    // Vigna's splitmix64.c from state 0, and Java's SplittableRandom(1234567).nextLong().
    assert_eq!(splitmix64(0, 0), 0xE220_A839_7B1D_CDAF);
    let java = [
        6_457_827_717_110_365_317u64,
        3_203_168_211_198_807_973,
        9_817_491_932_198_370_423,
        4_593_380_528_125_082_431,
        16_408_922_859_458_223_821,
    ];
    for (n, &expected) in java.iter().enumerate() {
        assert_eq!(splitmix64(1_234_567, n as u64), expected, "output {n}");
    }
}

#[test]
fn random_samples_depend_on_the_seed_and_index_only() {
    let text = SMALL.replace("count = 3\n", "").replace(
        "values = [0.5, 2.0]",
        "range = [0.1, 3.0]\nspacing = \"log\"",
    ) + "\n[random]\nsamples = 200\nseed = 7\n";
    let def = parse(&text).unwrap();
    assert_eq!(def.points(), 200);
    let all: Vec<Vec<f64>> = (0..200).map(|i| def.point(i)).collect();
    for p in &all {
        assert!((1.0..5.0).contains(&p[0]), "{p:?}");
        assert!((0.1..=3.0).contains(&p[1]), "{p:?}");
    }
    // Spread over the range (log-uniform: about half below the geometric mean).
    let below = all.iter().filter(|p| p[1] < (0.3f64).sqrt()).count();
    assert!((60..140).contains(&below), "{below}");
    assert_eq!(def.point(123), all[123]);
    let other = parse(&text.replace("seed = 7", "seed = 8")).unwrap();
    assert_ne!(other.point(0), all[0]);
}

#[test]
fn the_resolved_text_parses_back_to_itself() {
    let random = SMALL
        .replace("count = 3\n", "")
        .replace("values = [0.5, 2.0]", "range = [0.1, 3.0]")
        + "\n[random]\nsamples = 5\nseed = 9223372036854775807\n";
    for text in [SMALL.to_string(), random, super::TILT_MAP.to_string()] {
        let def = parse(&text).unwrap();
        let resolved = def.to_toml();
        let again = SweepDefinition::parse(&resolved, "resolved", &[]).unwrap();
        assert_eq!(again.to_toml(), resolved);
        assert_eq!(again.points(), def.points());
        assert_eq!(again.point(def.points() - 1), def.point(def.points() - 1));
    }
}

#[test]
fn overrides_replace_keys_and_are_validated() {
    let def = SweepDefinition::parse(
        SMALL,
        "test.toml",
        &[
            set("run.dt", 0.005),
            set("M", 2.0),
            set("axes.omega0.count", 5.0),
            set("axes.alpha0.start", 1.0),
        ],
    );
    // `alpha0` lists values: a start does not go with them.
    let e = def.unwrap_err();
    assert!(e.to_string().contains("--set axes.alpha0.start=1"), "{e}");
    let def = SweepDefinition::parse(
        SMALL,
        "test.toml",
        &[
            set("run.dt", 0.005),
            set("M", 2.0),
            set("axes.omega0.count", 5.0),
        ],
    )
    .unwrap();
    assert_eq!(def.plan.step, StepControl::Fixed(0.005));
    assert_eq!(def.params.get("M").unwrap(), 2.0);
    assert_eq!(def.points(), 10);
    for (o, needle) in [
        (set("omega0", 3.0), "swept by the axis at test.toml:"),
        (set("run.dt", 0.0), "run.dt"),
        (set("run.dt", 1.0), "larger than the horizon"),
        (set("M", -1.0), "positive"),
        (set("speed", 1.0), "has no parameter `speed`"),
        (set("run.every", 2.0), "unknown key"),
        (set("random.seed", 2.0), "is a grid"),
        (set("axes.theta0.count", 2.0), "no axis sweeps `theta0`"),
        (set("axes.omega0.count", 2.5), "whole number"),
        (set("metrics.tilt_threshold", 2.0), "between 0 and pi/2"),
    ] {
        let e = SweepDefinition::parse(SMALL, "test.toml", std::slice::from_ref(&o)).unwrap_err();
        assert!(e.to_string().contains(needle), "{o:?}: {e}");
        assert!(
            matches!(e.origin(), Some(Origin::Override(_)))
                || e.to_string().contains("--set")
                || matches!(e, SweepFileError::Scene { .. }),
            "{o:?}: {e}"
        );
    }
}

#[test]
fn bad_files_name_the_key_and_its_line() {
    // (change to SMALL, line of the offending key, words the message must contain)
    let cases: &[(&str, &str, usize, &str)] = &[
        ("[run]", "[run]\nsteps = 3", 9, "steps"),
        (
            "scene = \"free-hoop\"",
            "scene = \"free-hop\"",
            2,
            "unknown scene",
        ),
        ("g = 9.81", "g = -9.81", 5, "parameters.g"),
        ("a = 1.0", "a = \"big\"", 6, "must be a number"),
        (
            "integrator = \"gauss8\"",
            "integrator = \"lgvi2\"",
            9,
            "run.integrator",
        ),
        ("dt = 0.01", "dt = 0.01\ntol = 1e-9", 11, "not both"),
        ("t_end = 0.5", "t_end = -1.0", 11, "run.t_end"),
        ("dt = 0.01", "dt = 2.0", 10, "larger than the horizon"),
        (
            "parameter = \"omega0\"",
            "parameter = \"spin\"",
            14,
            "has no parameter `spin`",
        ),
        ("range = [1.0, 5.0]", "range = [5.0, 1.0]", 15, "increasing"),
        ("range = [1.0, 5.0]", "range = [1.0]", 15, "two numbers"),
        (
            "range = [1.0, 5.0]",
            "range = [-1.0, 5.0]\nspacing = \"log\"",
            15,
            "positive range",
        ),
        ("range = [1.0, 5.0]", "range = [1.0, nan]", 15, "finite"),
        ("count = 3", "count = 1", 16, "whole number >= 2"),
        ("count = 3", "count = 3\nspacing = \"cubic\"", 17, "linear"),
        ("values = [0.5, 2.0]", "values = []", 20, "empty"),
        ("values = [0.5, 2.0]", "values = [0.5, inf]", 20, "finite"),
        (
            "parameter = \"alpha0\"",
            "parameter = \"omega0\"",
            19,
            "already swept",
        ),
        (
            "g = 9.81",
            "g = 9.81\nalpha0 = 1.0",
            6,
            "a parameter is either fixed or swept",
        ),
        (
            "\"max_tilt\", ",
            "\"max_tlit\", ",
            23,
            "unknown metric `max_tlit`",
        ),
        ("\"max_tilt\", ", "\"flips\", ", 23, "torque-free bodies"),
        ("\"max_tilt\", ", "\"final_tilt\", ", 23, "listed twice"),
        (
            "tilt_threshold = 0.01",
            "tilt_threshold = 1.6",
            24,
            "between 0 and pi/2",
        ),
        (
            "\"time_tilt_exceeds\", ",
            "",
            24,
            "only `time_tilt_exceeds`",
        ),
        ("tilt_threshold = 0.01", "", 23, "needs `tilt_threshold"),
        ("record = [", "record = []\n#", 23, "empty"),
    ];
    for (from, to, line, needle) in cases {
        assert!(SMALL.contains(from), "{from}");
        let text = SMALL.replacen(from, to, 1);
        let e = parse(&text).expect_err(&format!("{to:?} was accepted"));
        let msg = e.to_string();
        assert!(msg.contains(needle), "{to:?}: {msg}");
        assert_eq!(error_line(&e), *line, "{to:?}: {msg}");
        assert!(msg.starts_with("test.toml:"), "{msg}");
    }
    let e = parse("[[axes]]\nparameter = \"omega0\"\nvalues = [1.0]\n").unwrap_err();
    assert!(
        matches!(
            e,
            SweepFileError::File(tumble_scenarios::toml_file::TomlFileError::MissingScene { .. })
        ),
        "{e}"
    );
    let e = parse("scene = \"free-hoop\"\n").unwrap_err();
    assert!(matches!(e, SweepFileError::NoAxes { .. }), "{e}");
    let e = parse("scene = \"free-hoop\"\n[[axes]]\nparameter = \"m\"\n").unwrap_err();
    assert!(e.to_string().contains("values"), "{e}");
    // Metrics of another kind of scene.
    let e = parse(
        "scene = \"dzhanibekov\"\n[[axes]]\nparameter = \"spin\"\nvalues = [1.0]\n\
         [metrics]\nrecord = [\"max_tilt\"]\n",
    )
    .unwrap_err();
    assert!(e.to_string().contains("needs a hoop scene"), "{e}");
    assert_eq!(error_line(&e), 6);
}

#[test]
fn random_sweeps_take_ranges_a_count_of_samples_and_a_seed() {
    let base = SMALL.replace("values = [0.5, 2.0]", "range = [0.1, 3.0]");
    let e = parse(&(base.clone() + "\n[random]\nsamples = 5\nseed = 1\n")).unwrap_err();
    assert!(e.to_string().contains("has no count"), "{e}");
    let no_count = base.replace("count = 3\n", "");
    let e = parse(&(no_count.clone() + "\n[random]\nsamples = 5\n")).unwrap_err();
    assert!(e.to_string().contains("random.seed"), "{e}");
    let e = parse(&(no_count.clone() + "\n[random]\nsamples = 0\nseed = 1\n")).unwrap_err();
    assert!(e.to_string().contains(">= 1"), "{e}");
    let e = parse(&(SMALL.replace("count = 3\n", "") + "\n[random]\nsamples = 5\nseed = 1\n"))
        .unwrap_err();
    assert!(e.to_string().contains("drawn in a `range`"), "{e}");
    assert!(parse(&(no_count + "\n[random]\nsamples = 5\nseed = 1\n")).is_ok());
}

#[test]
fn log_spaced_values_land_exactly_on_decades() {
    let text = SMALL.replace(
        "parameter = \"alpha0\"\nvalues = [0.5, 2.0]",
        "parameter = \"alpha0\"\nrange = [1e-6, 1.0]\ncount = 13\nspacing = \"log\"",
    );
    let def = parse(&text).unwrap();
    let values = def.axes[1].grid_values();
    for (k, decade) in [
        (0, 1e-6),
        (2, 1e-5),
        (4, 1e-4),
        (6, 1e-3),
        (8, 1e-2),
        (10, 0.1),
        (12, 1.0),
    ] {
        assert_eq!(values[k], decade, "{values:?}");
    }
    // Between decades: 10^(-5.5), to round-off.
    assert!((values[1] / 10f64.powf(-5.5) - 1.0).abs() < 1e-15);
}
