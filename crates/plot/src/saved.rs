//! Saved results read back and drawn: the figure of each result tumble writes, from its files
//! alone, through the same code the command that computed it drew with — so with the same
//! data and [`crate::FigureOptions`] the file is the same, byte for byte.
//!
//! | result | files read | figure |
//! |---|---|---|
//! | a run (`simulate -o FILE.csv`) | `FILE.csv`, `FILE.csv.json` | [`RunResult::figure`] |
//! | a sweep folder | `sweep.toml`, `results.csv` | [`crate::sweep::figures`]: map or slices |
//! | a work–precision folder | `work-precision.csv`, `manifest.json` | [`crate::work_precision::study_figure`] |
//! | a long-run folder (`work-precision --long`) | `long.csv`, `manifest.json` | [`crate::work_precision::long_figure`] |
//! | a hard-case atlas folder | `atlas.csv`, `manifest.json` | [`Atlas::of_entries`] |
//!
//! `tumble plot` and Python's `tumble.plot` both call [`figure`]; `tumble animate` reads a
//! saved run with [`run_record`] and [`read_columns`].

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use plotters::coord::Shift;
use plotters::prelude::*;
use tumble_scenarios::{Params, Scene, StepControl, scenes};
use tumble_studies::hard_cases::atlas::{Entry, Method};
use tumble_studies::sweep;

use crate::atlas::{Atlas, AtlasCase};
use crate::colour::ColourMap;
use crate::heatmap::Heatmap;
use crate::trajectory::RunResult;
use crate::work_precision::{Curve, LongRecord};
use crate::xy::{Series, StackedFigure};
use crate::{DrawResult, Figure};

/// Which figure of a two-axis sweep to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum SweepFigure {
    /// The heatmap of the metric over the grid.
    #[default]
    Map,
    /// The metric against the first axis along a few rows of the grid.
    Slices,
}

/// What to draw of a saved result; each field applies to one kind and is ignored by the
/// others.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    /// A run: the columns to draw (empty: every coordinate, rate and diagnostic).
    pub columns: Vec<String>,
    /// A run: only the rows with `t0 ≤ t ≤ t1`.
    pub t_range: Option<(f64, f64)>,
    /// A sweep: the metric, by its name in `results.csv` (`None`: the first).
    pub metric: Option<String>,
    /// A sweep over two axes: the map or its slices.
    pub figure: SweepFigure,
    /// A sweep: the most rows of the grid drawn as slices.
    pub slices: usize,
    /// A sweep map: colour by the base-10 logarithm of the metric.
    pub log_colour: bool,
    /// A sweep map: its colour map.
    pub colour_map: ColourMap,
}

impl Default for Choice {
    fn default() -> Self {
        Choice {
            columns: Vec::new(),
            t_range: None,
            metric: None,
            figure: SweepFigure::Map,
            slices: 5,
            log_colour: false,
            colour_map: ColourMap::Viridis,
        }
    }
}

/// A figure of any kind tumble draws, as [`figure`] returns it.
#[derive(Debug, Clone)]
pub enum AnyFigure {
    /// Stacked panels: a run, a sweep's slices, a work–precision study, a long run.
    Stacked(StackedFigure),
    /// A sweep's map.
    Map(Heatmap),
    /// A hard-case atlas.
    Atlas(Atlas),
}

impl Figure for AnyFigure {
    fn size(&self) -> (u32, u32) {
        match self {
            AnyFigure::Stacked(f) => f.size(),
            AnyFigure::Map(f) => f.size(),
            AnyFigure::Atlas(f) => f.size(),
        }
    }

    fn set_size(&mut self, size: (u32, u32)) {
        match self {
            AnyFigure::Stacked(f) => f.set_size(size),
            AnyFigure::Map(f) => f.set_size(size),
            AnyFigure::Atlas(f) => f.set_size(size),
        }
    }

    fn fit_width(&mut self, width: u32) {
        match self {
            AnyFigure::Stacked(f) => f.fit_width(width),
            AnyFigure::Map(f) => f.fit_width(width),
            AnyFigure::Atlas(f) => f.fit_width(width),
        }
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: f64,
    ) -> DrawResult<DB> {
        match self {
            AnyFigure::Stacked(f) => f.draw(root, scale),
            AnyFigure::Map(f) => f.draw(root, scale),
            AnyFigure::Atlas(f) => f.draw(root, scale),
        }
    }
}

/// The figure of the saved result at `input`: a run's CSV (its record beside it), or a
/// sweep, work–precision, long-run or atlas folder (see the module doc).
///
/// # Errors
/// An input that is none of these, or damaged; a column, range or metric the result does not
/// have.
pub fn figure(input: &Path, choice: &Choice) -> Result<AnyFigure> {
    if choice.slices == 0 {
        bail!("slices 0: draw at least one slice");
    }
    if !input.exists() {
        bail!("{}: no such file or folder", input.display());
    }
    if !input.is_dir() {
        return Ok(AnyFigure::Stacked(run_figure(input, choice)?));
    }
    if input.join(sweep::DEFINITION).is_file() {
        sweep_figure(input, choice)
    } else if input.join("work-precision.csv").is_file() {
        Ok(AnyFigure::Stacked(work_precision_figure(input)?))
    } else if input.join("long.csv").is_file() {
        Ok(AnyFigure::Stacked(long_figure(input)?))
    } else if input.join("atlas.csv").is_file() {
        Ok(AnyFigure::Atlas(atlas_figure(input)?))
    } else {
        bail!(
            "{}: none of a sweep folder (no {}), a work–precision folder (no \
             work-precision.csv), a long-run folder (no long.csv) or a hard-case atlas (no \
             atlas.csv)",
            input.display(),
            sweep::DEFINITION
        )
    }
}

/// Reads a JSON file into a value of type `T`.
fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read it", path.display()))?;
    serde_json::from_str(&text)
        .with_context(|| format!("{}: not a record tumble wrote", path.display()))
}

/// What a figure needs of a result's record: the scene and its parameters.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct SceneRecord {
    /// The scene's name.
    pub scene: String,
    /// Its parameters (the scene's defaults for any left out).
    #[serde(default)]
    pub parameters: BTreeMap<String, f64>,
}

impl SceneRecord {
    /// The built-in scene named and its parameters; `path` names the record in messages.
    ///
    /// # Errors
    /// An unknown scene or parameter.
    pub fn scene(&self, path: &Path) -> Result<(&'static dyn Scene, Params)> {
        let scene =
            scenes::find(&self.scene).with_context(|| format!("{}: scene", path.display()))?;
        let mut params = scene.info().default_params();
        for (name, value) in &self.parameters {
            params
                .set(name, *value)
                .with_context(|| format!("{}: parameter {name}", path.display()))?;
        }
        Ok((scene, params))
    }
}

/// What a figure needs of the record `simulate -o FILE.csv` writes beside its CSV.
#[derive(Debug, Clone, serde::Deserialize)]
pub struct RunRecordView {
    /// The scene and its parameters.
    #[serde(flatten)]
    pub scene: SceneRecord,
    /// The integrator's name.
    pub integrator: String,
    /// The fixed step, if the run had one.
    pub dt: Option<f64>,
    /// The tolerance, if the run was adaptive.
    pub tol: Option<f64>,
}

impl RunRecordView {
    /// The run's step control.
    ///
    /// # Errors
    /// A record with neither `dt` nor `tol`.
    pub fn step(&self, path: &Path) -> Result<StepControl> {
        match (self.dt, self.tol) {
            (Some(h), _) => Ok(StepControl::Fixed(h)),
            (None, Some(t)) => Ok(StepControl::Tolerance(t)),
            (None, None) => bail!("{}: neither `dt` nor `tol`", path.display()),
        }
    }
}

/// The record `FILE.csv.json` that `simulate -o FILE.csv` writes beside its CSV, read, with
/// its path.
///
/// # Errors
/// No record beside the CSV, or one that is not a run's record.
pub fn run_record(csv_path: &Path) -> Result<(PathBuf, RunRecordView)> {
    let record_path = tumble_output::table::provenance_path(
        csv_path,
        tumble_output::table::Format::of_path(csv_path),
    );
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

/// The figure of a run's CSV and its record.
fn run_figure(csv_path: &Path, choice: &Choice) -> Result<StackedFigure> {
    let (record_path, record) = run_record(csv_path)?;
    let (scene, params) = record.scene.scene(&record_path)?;
    let step = record.step(&record_path)?;
    let (mut columns, mut values) = read_columns(csv_path)?;
    if !choice.columns.is_empty() {
        for c in &choice.columns {
            if !columns.contains(c) {
                bail!(
                    "columns {c}: {} has the columns {}",
                    csv_path.display(),
                    columns.join(", ")
                );
            }
        }
        let keep: Vec<bool> = columns
            .iter()
            .map(|c| c == "t" || choice.columns.contains(c))
            .collect();
        let mut k = keep.iter();
        columns.retain(|_| *k.next().unwrap_or(&false));
        let mut k = keep.iter();
        values.retain(|_| *k.next().unwrap_or(&false));
    }
    if let Some((t0, t1)) = choice.t_range {
        if !(t0 < t1) {
            bail!("t range {t0},{t1}: expected T0,T1 with T0 < T1 (seconds)");
        }
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
                "t range {t0},{t1}: no row of {} lies in it",
                csv_path.display()
            );
        }
    }
    let run = RunResult::of_scene(
        scene.info(),
        &record.integrator,
        step,
        &params,
        columns,
        values,
    );
    Ok(run.figure())
}

/// A numeric CSV's header and its values column by column; `t` must be the first column.
///
/// # Errors
/// An unreadable file, a first column other than `t`, a cell that is not a number.
pub fn read_columns(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>)> {
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

/// The figure of a sweep folder.
fn sweep_figure(dir: &Path, choice: &Choice) -> Result<AnyFigure> {
    let (def, rows) = sweep::read_folder(dir)?;
    let metric = match &choice.metric {
        None => 0,
        Some(name) => def
            .metrics
            .iter()
            .position(|m| m.name() == *name)
            .with_context(|| {
                let names: Vec<String> = def.metrics.iter().map(|m| m.name()).collect();
                format!(
                    "metric {name}: the sweep in {} has the metrics {}",
                    dir.display(),
                    names.join(", ")
                )
            })?,
    };
    let drawn = crate::sweep::Choice {
        metric,
        slices: choice.slices,
        log_colour: choice.log_colour,
        colour_map: choice.colour_map,
    };
    let Some(figures) = crate::sweep::figures(&def, &rows, &drawn) else {
        bail!(
            "{}: only sweeps over a grid of one or two axes have figures",
            dir.display()
        );
    };
    match (choice.figure, figures.map) {
        (SweepFigure::Map, Some(map)) => Ok(AnyFigure::Map(map)),
        (SweepFigure::Map, None) if def.axes.len() == 2 => bail!(
            "{}: the grid's values do not increase along an axis, so it has no map; its \
             slices can be drawn",
            dir.display()
        ),
        _ => Ok(AnyFigure::Stacked(figures.slices)),
    }
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

/// What the work–precision figure needs of its `manifest.json`.
#[derive(serde::Deserialize)]
struct StudyRecord {
    #[serde(flatten)]
    scene: SceneRecord,
    t_end: f64,
    reference: ReferenceRecord,
}

/// The reference of a work–precision study, as its manifest records it.
#[derive(serde::Deserialize)]
struct ReferenceRecord {
    method: String,
    cross_check: String,
    agreement: f64,
}

/// The figure of a work–precision folder, from its CSV and manifest.
fn work_precision_figure(dir: &Path) -> Result<StackedFigure> {
    let manifest_path = dir.join("manifest.json");
    let manifest: StudyRecord = read_json(&manifest_path)?;
    let (scene, params) = manifest.scene.scene(&manifest_path)?;
    let csv_path = dir.join("work-precision.csv");
    let mut reader = csv::Reader::from_path(&csv_path)
        .with_context(|| format!("{}: cannot read it", csv_path.display()))?;
    let mut curves: Vec<Curve> = Vec::new();
    for (i, row) in reader.deserialize::<RungRow>().enumerate() {
        let row = row.with_context(|| format!("{}: row {}", csv_path.display(), i + 2))?;
        let order = row.order.as_str();
        if !(matches!(order, "exact" | "variable") || order.parse::<u32>().is_ok()) {
            bail!(
                "{}: row {}: order `{order}` (a number, `exact` or `variable`)",
                csv_path.display(),
                i + 2
            );
        }
        let label = crate::work_precision::curve_label(&row.integrator, order);
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
    let reference = &manifest.reference;
    let study = crate::work_precision::Study {
        scene: scene.info().name,
        t_end: manifest.t_end,
        parameters: crate::labels::parameters(params.iter()),
        reference: (
            &reference.method,
            &reference.cross_check,
            reference.agreement,
        ),
    };
    Ok(crate::work_precision::study_figure(&study, &curves))
}

/// One row of `long.csv`.
#[derive(serde::Deserialize)]
struct LongRow {
    integrator: String,
    control: String,
    t: f64,
    max_energy_rel_err: f64,
}

/// The figure of a long-run folder, from `long.csv` and `manifest.json`.
fn long_figure(dir: &Path) -> Result<StackedFigure> {
    let manifest_path = dir.join("manifest.json");
    let record: LongRecord = read_json(&manifest_path)?;
    let (_, params) = record.scene.scene(&manifest_path)?;
    let csv_path = dir.join("long.csv");
    let mut reader = csv::Reader::from_path(&csv_path)
        .with_context(|| format!("{}: cannot read it", csv_path.display()))?;
    let mut lines: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (i, row) in reader.deserialize::<LongRow>().enumerate() {
        let row = row.with_context(|| format!("{}: row {}", csv_path.display(), i + 2))?;
        let label = crate::work_precision::long_label(&row.integrator, &row.control);
        let point = (row.t, row.max_energy_rel_err);
        match lines.last_mut() {
            Some((l, points)) if *l == label => points.push(point),
            _ => lines.push((label, vec![point])),
        }
    }
    let series = lines
        .into_iter()
        .map(|(label, points)| Series::line(label, points))
        .collect();
    Ok(record.figure(&params, series))
}

/// What the atlas figure needs of its `manifest.json`.
#[derive(serde::Deserialize)]
struct AtlasRecord {
    cases: Vec<AtlasCaseRecord>,
    methods: Vec<String>,
}

/// A case as the atlas's manifest records it.
#[derive(serde::Deserialize)]
struct AtlasCaseRecord {
    name: String,
    scene: String,
    bounds_error: bool,
}

/// The figure of a hard-case atlas folder, from `atlas.csv` and `manifest.json`.
fn atlas_figure(dir: &Path) -> Result<Atlas> {
    let manifest_path = dir.join("manifest.json");
    let record: AtlasRecord = read_json(&manifest_path)?;
    let scenes: Vec<&'static dyn Scene> = record
        .cases
        .iter()
        .map(|c| {
            scenes::find(&c.scene)
                .with_context(|| format!("{}: case {}", manifest_path.display(), c.name))
        })
        .collect::<Result<_>>()?;
    let cases: Vec<AtlasCase> = record
        .cases
        .iter()
        .zip(&scenes)
        .map(|(c, s)| AtlasCase {
            name: &c.name,
            scene: s.info(),
            bounds_error: c.bounds_error,
        })
        .collect();
    let methods: Vec<Method> = record
        .methods
        .iter()
        .map(|m| Method::parse(m).map_err(|e| anyhow::anyhow!("{}: {e}", manifest_path.display())))
        .collect::<Result<_>>()?;
    let csv_path = dir.join("atlas.csv");
    let mut reader = csv::Reader::from_path(&csv_path)
        .with_context(|| format!("{}: cannot read it", csv_path.display()))?;
    let entries: Vec<Entry> = reader
        .deserialize()
        .enumerate()
        .map(|(i, e)| e.with_context(|| format!("{}: row {}", csv_path.display(), i + 2)))
        .collect::<Result<_>>()?;
    Ok(Atlas::of_entries(&cases, &methods, &entries))
}
