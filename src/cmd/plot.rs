//! `tumble plot`: redraws a saved result without recomputing it — a `simulate` CSV (with its
//! `FILE.csv.json` beside it), a sweep folder or a work–precision folder — as PNG, SVG or
//! PDF, with the figure options of every plotting command. Each kind is drawn by the code its
//! command draws with ([`plot::trajectory::simulation`], [`plot::sweep::figures`],
//! [`plot::work_precision::study_figure`]), so with the same data and options the figure is
//! the same.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use tumble_scenarios::{Params, Scene, StepControl, scenes};
use tumble_studies::sweep;

use super::args::FigureArgs;
use crate::output;
use crate::plot;
use crate::plot::work_precision::Curve;

/// Which figure of a two-axis sweep to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SweepFigure {
    /// The heatmap of the metric over the grid.
    Map,
    /// The metric against the first axis along a few rows of the grid.
    Slices,
}

/// Flags of `tumble plot`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A `simulate` CSV (its `FILE.csv.json` beside it), a sweep folder or a work–precision
    /// folder.
    #[arg(value_name = "FILE.csv|DIR")]
    pub input: PathBuf,
    /// The figure to write: PNG, SVG or PDF by the extension.
    #[arg(
        short = 'o',
        long = "output",
        value_name = "FILE.png|FILE.svg|FILE.pdf"
    )]
    pub output: PathBuf,
    /// A simulate CSV: the columns to draw (default: every coordinate, rate and diagnostic the
    /// command draws).
    #[arg(long, value_name = "A,B,...", value_delimiter = ',')]
    pub columns: Vec<String>,
    /// A simulate CSV: only the rows with `T0 ≤ t ≤ T1`.
    #[arg(long = "t-range", value_name = "T0,T1")]
    pub t_range: Option<String>,
    /// A sweep: the metric to draw, by its name in `results.csv` (default: the first).
    #[arg(long, value_name = "NAME")]
    pub metric: Option<String>,
    /// A sweep over two axes: the map or its slices.
    #[arg(long, value_enum, default_value = "map")]
    pub figure: SweepFigure,
    /// A sweep: the most rows of the grid to draw as slices.
    #[arg(long, value_name = "N", default_value_t = 5)]
    pub slices: usize,
    /// A sweep map: colour by the base-10 logarithm of the metric.
    #[arg(long = "log-colour")]
    pub log_colour: bool,
    /// A sweep map: its colour map (cividis reads the same with a red–green colour-vision
    /// deficiency; grey prints in black and white).
    #[arg(long = "colour-map", value_enum, default_value = "viridis")]
    pub colour_map: crate::plot::colour::ColourMap,
    #[command(flatten)]
    pub style: FigureArgs,
}

/// Runs the subcommand.
///
/// # Errors
/// An input that is none of the three kinds, or damaged; an unknown column or metric; bad
/// figure options; an output that cannot be written. All before anything is written.
pub fn run(args: &Args) -> Result<()> {
    plot::Format::from_path(&args.output)?;
    let opts = args.style.options()?;
    let dest = output::Destination::check(&args.output)?;
    let input = &args.input;
    if args.slices == 0 {
        bail!("--slices 0: draw at least one slice");
    }
    if !input.exists() {
        bail!("{}: no such file or folder", input.display());
    }
    if input.is_dir() {
        if input.join(sweep::DEFINITION).is_file() {
            let (def, rows) = sweep::read_folder(input)?;
            let metric = match &args.metric {
                None => 0,
                Some(name) => def
                    .metrics
                    .iter()
                    .position(|m| m.name() == *name)
                    .with_context(|| {
                        let names: Vec<String> = def.metrics.iter().map(|m| m.name()).collect();
                        format!(
                            "--metric {name}: the sweep in {} has the metrics {}",
                            input.display(),
                            names.join(", ")
                        )
                    })?,
            };
            let choice = plot::sweep::Choice {
                metric,
                slices: args.slices,
                log_colour: args.log_colour,
                colour_map: args.colour_map,
            };
            let Some(figures) = plot::sweep::figures(&def, &rows, &choice) else {
                bail!(
                    "{}: only sweeps over a grid of one or two axes have figures",
                    input.display()
                );
            };
            match (args.figure, figures.map) {
                (SweepFigure::Map, Some(map)) => plot::save_to(&map, &dest, &opts)?,
                (SweepFigure::Map, None) if def.axes.len() == 2 => bail!(
                    "{}: the grid's values do not increase along an axis, so it has no map; \
                     --figure slices draws its slices",
                    input.display()
                ),
                _ => plot::save_to(&figures.slices, &dest, &opts)?,
            }
        } else if input.join("work-precision.csv").is_file() {
            let figure = work_precision_figure(input)?;
            plot::save_to(&figure, &dest, &opts)?;
        } else {
            bail!(
                "{}: neither a sweep folder (no {}) nor a work–precision folder (no \
                 work-precision.csv)",
                input.display(),
                sweep::DEFINITION
            );
        }
    } else {
        let figure = simulation_figure(input, args)?;
        plot::save_to(&figure, &dest, &opts)?;
    }
    eprintln!("plot         {}", args.output.display());
    Ok(())
}

/// Reads a JSON file into a value.
fn read_json(path: &Path) -> Result<serde_json::Value> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read it", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{}: not valid JSON", path.display()))
}

/// A string field of a JSON object.
fn field<'a>(json: &'a serde_json::Value, key: &str, path: &Path) -> Result<&'a str> {
    json[key]
        .as_str()
        .with_context(|| format!("{}: no `{key}` string", path.display()))
}

/// The scene named in a record and its parameters (the scene's defaults for any the record
/// leaves out).
pub(crate) fn scene_and_parameters(
    json: &serde_json::Value,
    path: &Path,
) -> Result<(&'static dyn Scene, Params)> {
    let name = field(json, "scene", path)?;
    let scene = scenes::find(name).with_context(|| format!("{}: scene", path.display()))?;
    let given: BTreeMap<String, f64> = serde_json::from_value(json["parameters"].clone())
        .with_context(|| format!("{}: `parameters` is not a table of numbers", path.display()))?;
    let mut params = scene.info().default_params();
    for (name, value) in &given {
        params
            .set(name, *value)
            .with_context(|| format!("{}: parameter {name}", path.display()))?;
    }
    Ok((scene, params))
}

/// The record `FILE.csv.json` that `simulate -o FILE.csv` writes beside its CSV, read.
///
/// # Errors
/// No record beside the CSV, or one that is not JSON.
pub(crate) fn simulation_record(csv_path: &Path) -> Result<(PathBuf, serde_json::Value)> {
    let record_path =
        crate::output::provenance_path(csv_path, tumble_output::table::Format::of_path(csv_path));
    if !record_path.is_file() {
        bail!(
            "{}: no record {} beside it (simulate -o FILE.csv writes one); a folder of a \
             sweep or work–precision study is given as the folder",
            csv_path.display(),
            record_path.display()
        );
    }
    let record = read_json(&record_path)?;
    Ok((record_path, record))
}

/// The figure of a `simulate` CSV and its record.
fn simulation_figure(csv_path: &Path, args: &Args) -> Result<plot::xy::StackedFigure> {
    let (record_path, record) = simulation_record(csv_path)?;
    let (scene, params) = scene_and_parameters(&record, &record_path)?;
    let info = scene.info();
    let step = match (record["dt"].as_f64(), record["tol"].as_f64()) {
        (Some(h), _) => StepControl::Fixed(h),
        (None, Some(t)) => StepControl::Tolerance(t),
        (None, None) => bail!("{}: neither `dt` nor `tol`", record_path.display()),
    };
    let integrator = field(&record, "integrator", &record_path)?;
    let (mut columns, mut values) = read_columns(csv_path)?;
    if !args.columns.is_empty() {
        for c in &args.columns {
            if !columns.contains(c) {
                bail!(
                    "--columns {c}: {} has the columns {}",
                    csv_path.display(),
                    columns.join(", ")
                );
            }
        }
        let keep: Vec<bool> = columns
            .iter()
            .map(|c| c == "t" || args.columns.contains(c))
            .collect();
        let mut k = keep.iter();
        columns.retain(|_| *k.next().unwrap_or(&false));
        let mut k = keep.iter();
        values.retain(|_| *k.next().unwrap_or(&false));
    }
    if let Some(range) = &args.t_range {
        let (t0, t1) = parse_range(range)?;
        let t = values.first().cloned().unwrap_or_default();
        for column in &mut values {
            let mut i = 0;
            column.retain(|_| {
                let inside = (t0..=t1).contains(&t[i]);
                i += 1;
                inside
            });
        }
        if values.first().is_none_or(Vec::is_empty) {
            bail!(
                "--t-range {range}: no row of {} lies in it",
                csv_path.display()
            );
        }
    }
    Ok(plot::trajectory::simulation(
        info,
        integrator,
        &super::simulate::step_words(step),
        params.iter(),
        &columns,
        &values,
    ))
}

/// `T0,T1` with `T0 < T1`.
fn parse_range(s: &str) -> Result<(f64, f64)> {
    let parsed: Option<(f64, f64)> = s
        .split_once(',')
        .and_then(|(a, b)| Some((a.trim().parse().ok()?, b.trim().parse().ok()?)));
    match parsed {
        Some((a, b)) if a < b => Ok((a, b)),
        _ => bail!("--t-range {s}: expected T0,T1 with T0 < T1 (seconds)"),
    }
}

/// A numeric CSV's header and its values column by column; `t` must be the first column.
pub(crate) fn read_columns(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>)> {
    let mut reader = csv::Reader::from_path(path)
        .with_context(|| format!("{}: cannot read it", path.display()))?;
    let columns: Vec<String> = reader.headers()?.iter().map(str::to_string).collect();
    if columns.first().map(String::as_str) != Some("t") {
        bail!(
            "{}: not a simulate CSV (its first column is not `t`)",
            path.display()
        );
    }
    let mut values = vec![Vec::new(); columns.len()];
    for (i, record) in reader.records().enumerate() {
        let record = record.with_context(|| format!("{}: row {}", path.display(), i + 2))?;
        for (j, cell) in record.iter().enumerate() {
            let v: f64 = cell.parse().with_context(|| {
                format!(
                    "{}: row {}, column {}: `{cell}` is not a number",
                    path.display(),
                    i + 2,
                    columns.get(j).map_or("?", String::as_str)
                )
            })?;
            if let Some(column) = values.get_mut(j) {
                column.push(v);
            }
        }
    }
    Ok((columns, values))
}

/// One row of `work-precision.csv`.
#[derive(serde::Deserialize)]
struct RungRow {
    integrator: String,
    order: String,
    evaluations: f64,
    error: f64,
    wall_time_s: f64,
}

/// The figure of a work–precision folder, from its CSV and manifest.
fn work_precision_figure(dir: &Path) -> Result<plot::xy::StackedFigure> {
    let manifest_path = dir.join("manifest.json");
    let manifest = read_json(&manifest_path)?;
    let (scene, params) = scene_and_parameters(&manifest, &manifest_path)?;
    let info = scene.info();
    let reference = &manifest["reference"];
    let agreement = reference["agreement"]
        .as_f64()
        .with_context(|| format!("{}: no reference agreement", manifest_path.display()))?;
    let t_end = manifest["t_end"]
        .as_f64()
        .with_context(|| format!("{}: no `t_end`", manifest_path.display()))?;
    let csv_path = dir.join("work-precision.csv");
    let mut reader = csv::Reader::from_path(&csv_path)
        .with_context(|| format!("{}: cannot read it", csv_path.display()))?;
    let mut curves: Vec<Curve> = Vec::new();
    for (i, row) in reader.deserialize::<RungRow>().enumerate() {
        let row = row.with_context(|| format!("{}: row {}", csv_path.display(), i + 2))?;
        let order = row.order.as_str();
        if !(matches!(order, "exact" | "variable") || order.parse::<u32>().is_ok()) {
            anyhow::bail!(
                "{}: row {}: order `{order}` (a number, `exact` or `variable`)",
                csv_path.display(),
                i + 2
            );
        }
        let label = plot::work_precision::curve_label(&row.integrator, order);
        let rung = (row.wall_time_s, row.evaluations, row.error);
        match curves.last_mut() {
            Some(c) if c.label == label => c.rungs.push(rung),
            _ => curves.push(Curve {
                integrator: row.integrator.clone(),
                label,
                rungs: vec![rung],
            }),
        }
    }
    let study = plot::work_precision::Study {
        scene: info.name,
        t_end,
        parameters: plot::labels::parameters(params.iter()),
        reference: (
            field(reference, "method", &manifest_path)?,
            field(reference, "cross_check", &manifest_path)?,
            agreement,
        ),
    };
    Ok(plot::work_precision::study_figure(&study, &curves))
}
