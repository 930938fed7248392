//! `tumble work-precision SCENE --recommend FILE`: measures what the scene's recommendations
//! rest on (`tumble_studies::work_precision::measure_recommendations`) and writes it, with its
//! provenance, into the measurements file in place of the scene's entry.
//! `crates/scenarios/data/recommendations.toml` is the file the binary embeds
//! (`tumble_scenarios::recommendation`); `tools/recommendations.sh` measures every built-in
//! scene into it.

use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use tumble_scenarios::recommendation::{Measurements, Provenance, SceneMeasurements};
use tumble_scenarios::scenes::builtin;
use tumble_scenarios::{Params, Scene};
use tumble_studies::work_precision::{self, Config, LONG_FACTOR};

use super::{Args, REFERENCE_FACTOR, print_rung, stop_if_interrupted, study_reference};
use crate::output;

/// Runs `--recommend FILE` on `scene` (loaded from `origin` with `params`).
///
/// # Errors
/// A scene that is not built in, a `--set`, a scene without recommendations, too few
/// `--long-steps`, a FILE that cannot be read as a measurements file or cannot be written
/// (all before any run); a failing reference or method.
pub(super) fn run(
    scene: &dyn Scene,
    origin: &str,
    params: &Params,
    args: &Args,
    file: &Path,
) -> Result<()> {
    let info = scene.info();
    if origin != tumble_studies::simulation::BUILT_IN {
        bail!(
            "--recommend: measures a built-in scene's recommendations, and {origin} is a file; \
             name a built-in scene (`tumble scenes` lists them)"
        );
    }
    if let Some(set) = args.target.set.first() {
        bail!(
            "--recommend: measures the scene at its default parameters, which `--set {set}` \
             changes; drop --set"
        );
    }
    let recommendations = scene.recommendations();
    if recommendations.is_empty() {
        bail!(
            "--recommend: {} recommends no method, so there is nothing to measure",
            info.name
        );
    }
    if args.long_steps < 1000 {
        bail!("--long-steps {}: at least 1000 steps", args.long_steps);
    }
    let mut all = match std::fs::read_to_string(file) {
        Ok(text) => Measurements::parse(&text).map_err(|e| {
            anyhow!(
                "--recommend {}: not a measurements file ({e}); name the file \
                 `tumble work-precision --recommend` wrote, or a new one",
                file.display()
            )
        })?,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Measurements::default(),
        Err(e) => {
            return Err(anyhow!(e)).with_context(|| format!("--recommend {}", file.display()));
        }
    };
    output::check_all([("--recommend", file)])?;
    let provenance = provenance();

    let mut config = Config::new(info);
    config.max_run_seconds = args.max_seconds;
    config.max_reference_seconds = REFERENCE_FACTOR * args.max_seconds;
    let reference = study_reference(scene, origin, params, &config, file)?;
    eprintln!(
        "recommendations {} error bands (ladders retimed in turns, {} rounds), long runs of {} \
         steps",
        info.name,
        work_precision::RETIME_ROUNDS,
        args.long_steps
    );
    let measured = work_precision::measure_recommendations(
        scene,
        params,
        recommendations,
        &reference.state,
        &config,
        args.long_steps,
        Some(LONG_FACTOR * args.max_seconds),
        &mut print_rung,
    );
    stop_if_interrupted(file)?;
    let (bands, long_runs) = measured?;
    let entry = SceneMeasurements {
        name: info.name.to_string(),
        provenance,
        t_end: config.t_end,
        reference: reference.method,
        bands,
        long_runs,
    };
    for r in recommendations {
        let line = crate::cmd::scenes::measured(
            r.integrators.len(),
            entry.band(r.purpose),
            entry.long_run(r.purpose),
        );
        if let Some(line) = line {
            println!("{}\n  {line}", r.purpose);
        }
    }
    let order: Vec<&str> = builtin().iter().map(|s| s.info().name).collect();
    all.replace(entry, &order);
    let text = all.to_toml().map_err(|e| anyhow!("--recommend: {e}"))?;
    output::write_whole(file, text.as_bytes())?;
    eprintln!("output          {}", file.display());
    Ok(())
}

/// This invocation: the command as typed after the program's path, version and commit, date,
/// CPU, cores and the load average at the start.
fn provenance() -> Provenance {
    let record = crate::provenance::now(1);
    let command = std::iter::once("tumble".to_string())
        .chain(std::env::args().skip(1))
        .collect::<Vec<_>>()
        .join(" ");
    Provenance {
        command,
        tumble_version: record.tumble_version.to_string(),
        git_commit: record.git_commit.to_string(),
        date: record.date,
        cpu: record.cpu,
        cores: std::thread::available_parallelism().map_or(1, std::num::NonZero::get),
        load_average: std::fs::read_to_string("/proc/loadavg")
            .ok()
            .and_then(|l| l.split_whitespace().next()?.parse().ok()),
    }
}
