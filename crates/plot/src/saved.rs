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
//! A record's scene is resolved by [`recorded_scene`]: a built-in scene by its name, a scene
//! or model file (`simulate models/free-hoop-euler.toml -o FILE.csv`) by the path the record
//! holds as its `origin`.
//!
//! `tumble plot` and Python's `tumble.plot` both call [`figure`]; `tumble animate` reads a
//! saved run with [`run_record`], [`recorded_scene`] and [`read_columns`].

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;
use tumble_scenarios::{Params, Scene, scenes};
use tumble_studies::hard_cases::atlas::{Entry, Method};
use tumble_studies::hard_cases::record::AtlasRecord;
use tumble_studies::record::RunRecord;
use tumble_studies::simulation::{self, ParamOverride};
use tumble_studies::sweep;
use tumble_studies::work_precision::Rung;
use tumble_studies::work_precision::record::StudyRecord;

use crate::atlas::{Atlas, AtlasCase};
use crate::colour::ColourMap;
use crate::heatmap::Heatmap;
use crate::trajectory::RunResult;
use crate::work_precision::{Curve, LongManifest};
use crate::xy::{Series, StackedFigure};
use crate::{DrawResult, Figure, PlotError, Result};

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
        return Err(PlotError::choice("slices 0", "draw at least one slice"));
    }
    if !input.exists() {
        return Err(PlotError::content(input, "no such file or folder"));
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
        Err(PlotError::content(
            input,
            format!(
                "none of a sweep folder (no {}), a work–precision folder (no \
                 work-precision.csv), a long-run folder (no long.csv) or a hard-case atlas (no \
                 atlas.csv)",
                sweep::DEFINITION
            ),
        ))
    }
}

/// Reads a JSON file into a value of type `T`.
fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T> {
    let text = std::fs::read_to_string(path).map_err(|source| PlotError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| PlotError::Record {
        path: path.to_path_buf(),
        source,
    })
}

/// A CSV reader of `path`.
fn csv_reader(path: &Path) -> Result<csv::Reader<std::fs::File>> {
    csv::Reader::from_path(path).map_err(|source| PlotError::Csv {
        path: path.to_path_buf(),
        row: None,
        source,
    })
}

/// [`PlotError::Csv`] of row `i` of the body of `path` (the header is row 1).
fn row_error(path: &Path, i: usize) -> impl FnOnce(csv::Error) -> PlotError + '_ {
    move |source| PlotError::Csv {
        path: path.to_path_buf(),
        row: Some(i + 2),
        source,
    }
}

/// What a figure needs of a result's record: the scene and its parameters.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
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
        scene_of(&self.scene, &self.parameters, path)
    }
}

/// The built-in scene `name` at `parameters` (its defaults for any left out); `path` names the
/// record in messages.
///
/// # Errors
/// An unknown scene or parameter, or a value outside the parameter's domain.
pub fn scene_of(
    name: &str,
    parameters: &BTreeMap<String, f64>,
    path: &Path,
) -> Result<(&'static dyn Scene, Params)> {
    let scene_error = |what: String| {
        move |source| PlotError::Scene {
            path: path.to_path_buf(),
            what,
            source: Box::new(source),
        }
    };
    let scene = scenes::find(name).map_err(scene_error("scene".to_string()))?;
    let mut params = scene.info().default_params();
    for (key, value) in parameters {
        params
            .set(key, *value)
            .map_err(scene_error(format!("parameter {key}")))?;
    }
    Ok((scene, params))
}

/// The scene a record names, at its `parameters`: the built-in scene `name` when `origin` is
/// `builtin`, else the scene or model file `origin` read again (a path as the command was
/// given it, so relative to the folder it ran in), which must still declare `name`; a scene
/// file no longer there falls back to the built-in scene of that name. `path` names the record
/// in messages.
///
/// # Errors
/// A file that is not there (for a scene that is not built in), no longer reads or declares
/// another scene; an unknown scene or parameter, a value outside the parameter's domain.
pub fn recorded_scene(
    name: &str,
    origin: &str,
    parameters: &BTreeMap<String, f64>,
    path: &Path,
) -> Result<(&'static dyn Scene, Params)> {
    let file = Path::new(origin);
    if origin == simulation::BUILT_IN || (!file.is_file() && scenes::find(name).is_ok()) {
        return scene_of(name, parameters, path);
    }
    if !file.is_file() {
        return Err(PlotError::content(
            path,
            format!(
                "the scene `{name}` came from {origin}, which is not a file here (the record \
                 holds the path as the command was given it: run from the folder it ran in)"
            ),
        ));
    }
    let overrides: Vec<ParamOverride> = parameters
        .iter()
        .map(|(key, &value)| ParamOverride {
            label: format!("parameter {key} = {value}"),
            key: key.clone(),
            value,
        })
        .collect();
    let loaded = simulation::load_scene(origin, &overrides)
        .map_err(|e| PlotError::content(path, format!("the run's scene file: {}", e.0)))?;
    let declared = loaded.scene.info().name;
    if declared != name {
        return Err(PlotError::content(
            path,
            format!("{origin} declares the scene `{declared}` now; the run's was `{name}`"),
        ));
    }
    Ok((loaded.scene, loaded.params))
}

/// The record `FILE.csv.json` that `simulate -o FILE.csv` writes beside its CSV, read, with
/// its path.
///
/// # Errors
/// No record beside the CSV, or one that is not a run's record.
pub fn run_record(csv_path: &Path) -> Result<(PathBuf, RunRecord)> {
    let record_path = tumble_output::table::provenance_path(
        csv_path,
        tumble_output::table::Format::of_path(csv_path),
    );
    if !record_path.is_file() {
        return Err(PlotError::content(
            csv_path,
            format!(
                "no record {} beside it (simulate -o FILE.csv writes one); a folder of a sweep \
                 or work–precision study is given as the folder",
                record_path.display()
            ),
        ));
    }
    let record = read_json(&record_path)?;
    Ok((record_path, record))
}

/// The figure of a run's CSV and its record.
fn run_figure(csv_path: &Path, choice: &Choice) -> Result<StackedFigure> {
    let (record_path, record) = run_record(csv_path)?;
    let (scene, params) = recorded_scene(
        &record.scene,
        &record.origin,
        &record.parameters,
        &record_path,
    )?;
    let step = record
        .step()
        .map_err(|e| PlotError::content(&record_path, e.to_string()))?;
    let (mut columns, mut values) = read_columns(csv_path)?;
    if !choice.columns.is_empty() {
        for c in &choice.columns {
            if !columns.contains(c) {
                return Err(PlotError::choice(
                    format!("columns {c}"),
                    format!(
                        "{} has the columns {}",
                        csv_path.display(),
                        columns.join(", ")
                    ),
                ));
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
            return Err(PlotError::choice(
                format!("t range {t0},{t1}"),
                "expected T0,T1 with T0 < T1 (seconds)",
            ));
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
            return Err(PlotError::choice(
                format!("t range {t0},{t1}"),
                format!("no row of {} lies in it", csv_path.display()),
            ));
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
    let mut reader = csv_reader(path)?;
    let columns: Vec<String> = reader
        .headers()
        .map_err(|source| PlotError::Csv {
            path: path.to_path_buf(),
            row: Some(1),
            source,
        })?
        .iter()
        .map(str::to_string)
        .collect();
    if columns.first().map(String::as_str) != Some("t") {
        return Err(PlotError::content(
            path,
            "not a simulate CSV (its first column is not `t`)",
        ));
    }
    let mut values = vec![Vec::new(); columns.len()];
    for (i, record) in reader.records().enumerate() {
        let record = record.map_err(row_error(path, i))?;
        for (j, cell) in record.iter().enumerate() {
            let v: f64 = cell.parse().map_err(|_| {
                PlotError::content(
                    path,
                    format!(
                        "row {}, column {}: `{cell}` is not a number",
                        i + 2,
                        columns.get(j).map_or("?", String::as_str)
                    ),
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
            .ok_or_else(|| {
                let names: Vec<String> = def.metrics.iter().map(|m| m.name()).collect();
                PlotError::choice(
                    format!("metric {name}"),
                    format!(
                        "the sweep in {} has the metrics {}",
                        dir.display(),
                        names.join(", ")
                    ),
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
        return Err(PlotError::content(
            dir,
            "only sweeps over a grid of one or two axes have figures",
        ));
    };
    match (choice.figure, figures.map) {
        (SweepFigure::Map, Some(map)) => Ok(AnyFigure::Map(map)),
        (SweepFigure::Map, None) if def.axes.len() == 2 => Err(PlotError::content(
            dir,
            "the grid's values do not increase along an axis, so it has no map; its slices \
             can be drawn",
        )),
        _ => Ok(AnyFigure::Stacked(figures.slices)),
    }
}

/// The figure of a work–precision folder, from its CSV and manifest.
fn work_precision_figure(dir: &Path) -> Result<StackedFigure> {
    let manifest_path = dir.join("manifest.json");
    let manifest: StudyRecord = read_json(&manifest_path)?;
    let (scene, params) = recorded_scene(
        &manifest.scene,
        &manifest.origin,
        &manifest.parameters,
        &manifest_path,
    )?;
    let csv_path = dir.join("work-precision.csv");
    let mut reader = csv_reader(&csv_path)?;
    let mut curves: Vec<Curve> = Vec::new();
    for (i, row) in reader.deserialize::<Rung>().enumerate() {
        let row = row.map_err(row_error(&csv_path, i))?;
        let label = crate::work_precision::curve_label(&row.integrator, &row.order.to_string());
        let rung = (row.wall_time_s, row.evaluations as f64, row.error);
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
    let LongManifest { record, .. } = read_json(&manifest_path)?;
    let (_, params) = record.scene.scene(&manifest_path)?;
    let csv_path = dir.join("long.csv");
    let mut reader = csv_reader(&csv_path)?;
    let mut lines: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (i, row) in reader.deserialize::<LongRow>().enumerate() {
        let row = row.map_err(row_error(&csv_path, i))?;
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

/// The figure of a hard-case atlas folder, from `atlas.csv` and `manifest.json`.
fn atlas_figure(dir: &Path) -> Result<Atlas> {
    let manifest_path = dir.join("manifest.json");
    let record: AtlasRecord = read_json(&manifest_path)?;
    let scenes: Vec<&'static dyn Scene> = record
        .cases
        .iter()
        .map(|c| {
            scenes::find(&c.scene).map_err(|source| PlotError::Scene {
                path: manifest_path.clone(),
                what: format!("case {}", c.name),
                source: Box::new(source),
            })
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
        .map(|m| Method::parse(m).map_err(|e| PlotError::content(&manifest_path, e)))
        .collect::<Result<_>>()?;
    let csv_path = dir.join("atlas.csv");
    let mut reader = csv_reader(&csv_path)?;
    let entries: Vec<Entry> = reader
        .deserialize()
        .enumerate()
        .map(|(i, e)| e.map_err(row_error(&csv_path, i)))
        .collect::<Result<_>>()?;
    Ok(Atlas::of_entries(&cases, &methods, &entries))
}

#[cfg(test)]
mod tests {
    use super::*;
    use tumble_integrators::Flow;
    use tumble_output::Provenance;
    use tumble_scenarios::{Recorder, RunOptions, StepControl};
    use tumble_studies::record::{Estimated, RunSetup};
    use tumble_studies::simulation::DEFAULT_ENERGY_WARN;

    /// Every row of a run.
    struct Rows(Vec<Vec<f64>>);

    impl Recorder for Rows {
        fn row(&mut self, values: &[f64]) -> Flow {
            self.0.push(values.to_vec());
            Flow::Continue
        }
    }

    /// A short run of the free hoop written as `simulate -o DIR/run.csv` writes it; its record.
    fn write_run(dir: &Path) -> RunRecord {
        let scene = scenes::find("free-hoop").unwrap();
        let info = scene.info();
        let params = info.default_params();
        let plan = RunOptions {
            step: Some(StepControl::Fixed(0.05)),
            t_end: Some(1.0),
            ..RunOptions::default()
        }
        .resolve(info)
        .unwrap();
        let mut rows = Rows(Vec::new());
        let summary = scene.simulate(&params, &plan, &mut rows).unwrap();
        let csv_path = dir.join("run.csv");
        let record = RunRecord::new(
            Provenance::now("0.0.0", "unknown", 1),
            &RunSetup {
                info,
                origin: "builtin",
                frame: None,
                params: &params,
                plan: &plan,
            },
            &summary,
            &Estimated::Off,
            DEFAULT_ENERGY_WARN,
            csv_path.display().to_string(),
            0.5,
        );
        let mut w = csv::Writer::from_path(&csv_path).unwrap();
        w.write_record(info.columns()).unwrap();
        for row in &rows.0 {
            w.serialize(row).unwrap();
        }
        w.flush().unwrap();
        let text = serde_json::to_string_pretty(&record).unwrap() + "\n";
        std::fs::write(dir.join("run.csv.json"), text).unwrap();
        record
    }

    #[test]
    fn a_runs_record_reads_back_equal_to_the_one_written_and_draws() {
        let dir = tempfile::tempdir().unwrap();
        let written = write_run(dir.path());
        let csv_path = dir.path().join("run.csv");
        let (path, read) = run_record(&csv_path).unwrap();
        assert_eq!(path, dir.path().join("run.csv.json"));
        assert_eq!(read, written);
        let AnyFigure::Stacked(_) = figure(&csv_path, &Choice::default()).unwrap() else {
            panic!("a run's figure is stacked panels");
        };
    }

    #[test]
    fn a_damaged_record_is_refused_naming_the_file_and_the_field() {
        let dir = tempfile::tempdir().unwrap();
        write_run(dir.path());
        let csv_path = dir.path().join("run.csv");
        let record_path = dir.path().join("run.csv.json");
        let text = std::fs::read_to_string(&record_path).unwrap();
        std::fs::write(&record_path, text.replace("\"integrator\"", "\"method\"")).unwrap();
        let e = run_record(&csv_path).unwrap_err();
        let PlotError::Record { path, source } = &e else {
            panic!("{e:?}");
        };
        assert_eq!(path, &record_path);
        assert!(
            source.to_string().contains("missing field `integrator`"),
            "{source}"
        );
        std::fs::remove_file(&record_path).unwrap();
        let e = figure(&csv_path, &Choice::default()).unwrap_err();
        assert!(
            matches!(&e, PlotError::Content { path, .. } if *path == csv_path),
            "{e:?}"
        );
        assert!(e.to_string().contains("no record"), "{e}");
    }

    #[test]
    fn a_column_the_run_does_not_have_is_refused_with_the_columns_it_has() {
        let dir = tempfile::tempdir().unwrap();
        write_run(dir.path());
        let choice = Choice {
            columns: vec!["omega_w".to_string()],
            ..Choice::default()
        };
        let e = figure(&dir.path().join("run.csv"), &choice).unwrap_err();
        let PlotError::Choice { given, expected } = &e else {
            panic!("{e:?}");
        };
        assert_eq!(given, "columns omega_w");
        assert!(expected.contains("has the columns t, qw, qx"), "{expected}");
    }
}
