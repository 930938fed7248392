//! `plot` and `plot_run`: figures drawn by `tumble_plot`, the code the command line draws
//! with, so that a figure from Python is the file `tumble` writes from the same result.

use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use tumble_plot::colour::ColourMap;
use tumble_plot::options::{Size, SvgText};
use tumble_plot::saved::{self, Choice, SweepFigure};
use tumble_plot::trajectory::RunResult;
use tumble_plot::{FigureOptions, Format};
use tumble_scenarios::StepControl;

/// An error of the figure code as a `ValueError`, with its causes.
fn failed(e: &tumble_plot::PlotError) -> PyErr {
    PyValueError::new_err(crate::message(e))
}

/// The figure options of `figure_size`, `font_size`, `dpi` and `svg_text`, checked.
fn options(
    figure_size: Option<&str>,
    font_size: Option<f64>,
    dpi: Option<f64>,
    svg_text: &str,
) -> PyResult<FigureOptions> {
    let svg_text = match svg_text {
        "font" => SvgText::Font,
        "paths" => SvgText::Paths,
        other => {
            return Err(PyValueError::new_err(format!(
                "svg_text={other:?}: give 'font' or 'paths'"
            )));
        }
    };
    let opts = FigureOptions {
        size: figure_size
            .map(Size::parse)
            .transpose()
            .map_err(|e| PyValueError::new_err(format!("figure_size: {}", crate::message(&e))))?,
        font_pt: font_size,
        dpi,
        svg_text,
    };
    opts.validate().map_err(|e| failed(&e))?;
    Ok(opts)
}

/// Draws a figure into `output` (PNG, SVG or PDF by its extension), whole or not at all.
fn save(
    figure: &(impl tumble_plot::Figure + Clone),
    output: &str,
    opts: &FigureOptions,
) -> PyResult<()> {
    let path = PathBuf::from(output);
    Format::from_path(&path).map_err(|e| failed(&e))?;
    tumble_plot::save_with(figure, &path, opts).map_err(|e| failed(&e))
}

/// Redraws a saved result as `tumble plot` does (see the Python docstring of `tumble.plot`).
#[pyfunction]
#[pyo3(signature = (input, output, *, columns=None, t_range=None, metric=None, figure="map",
    slices=5, log_colour=false, colour_map="viridis", figure_size=None, font_size=None,
    dpi=None, svg_text="font"))]
pub(crate) fn plot(
    input: &str,
    output: &str,
    columns: Option<Vec<String>>,
    t_range: Option<(f64, f64)>,
    metric: Option<String>,
    figure: &str,
    slices: usize,
    log_colour: bool,
    colour_map: &str,
    figure_size: Option<&str>,
    font_size: Option<f64>,
    dpi: Option<f64>,
    svg_text: &str,
) -> PyResult<()> {
    let opts = options(figure_size, font_size, dpi, svg_text)?;
    let figure = match figure {
        "map" => SweepFigure::Map,
        "slices" => SweepFigure::Slices,
        other => {
            return Err(PyValueError::new_err(format!(
                "figure={other:?}: give 'map' or 'slices'"
            )));
        }
    };
    let colour_map = ColourMap::from_name(colour_map).ok_or_else(|| {
        PyValueError::new_err(format!(
            "colour_map={colour_map:?}: give 'viridis', 'cividis', 'magma' or 'grey'"
        ))
    })?;
    let choice = Choice {
        columns: columns.unwrap_or_default(),
        t_range,
        metric,
        figure,
        slices,
        log_colour,
        colour_map,
    };
    let drawn = saved::figure(std::path::Path::new(input), &choice).map_err(|e| failed(&e))?;
    save(&drawn, output, &opts)
}

/// Draws a run held in memory (see `tumble.Simulation.plot`): the scene's declaration
/// (`scene`, `coordinates`, `rates`), how it ran, and its columns as `rows` native-endian
/// `f64`s each, one after another.
#[pyfunction]
#[pyo3(signature = (scene, coordinates, rates, integrator, dt, tol, parameters, columns, data,
    rows, output, *, figure_size=None, font_size=None, dpi=None, svg_text="font"))]
pub(crate) fn plot_run(
    scene: String,
    coordinates: Vec<String>,
    rates: Vec<String>,
    integrator: String,
    dt: Option<f64>,
    tol: Option<f64>,
    parameters: Vec<(String, f64)>,
    columns: Vec<String>,
    data: &Bound<'_, PyBytes>,
    rows: usize,
    output: &str,
    figure_size: Option<&str>,
    font_size: Option<f64>,
    dpi: Option<f64>,
    svg_text: &str,
) -> PyResult<()> {
    let opts = options(figure_size, font_size, dpi, svg_text)?;
    let step = StepControl::from_dt_tol(dt, tol)
        .map_err(crate::refused)?
        .ok_or_else(|| PyValueError::new_err("dt and tol: a run has one of them"))?;
    let bytes = data.as_bytes();
    if bytes.len() != columns.len() * rows * 8 {
        return Err(PyValueError::new_err(format!(
            "data: {} bytes for {} columns of {rows} rows",
            bytes.len(),
            columns.len()
        )));
    }
    let values: Vec<Vec<f64>> = bytes
        .chunks_exact(8 * rows.max(1))
        .take(columns.len())
        .map(|column| {
            column
                .chunks_exact(8)
                .map(|b| f64::from_ne_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
                .collect()
        })
        .collect();
    let values = if rows == 0 {
        vec![Vec::new(); columns.len()]
    } else {
        values
    };
    let run = RunResult {
        scene,
        coordinates,
        rates,
        integrator,
        step,
        parameters,
        columns,
        values,
    };
    save(&run.figure(), output, &opts)
}
