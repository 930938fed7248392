//! `tumble scenes`: list the built-in scenes with their coordinates, CSV columns, parameters
//! (name, default, unit, domain, description), conserved quantities, oracle, default run and
//! applicable integrators.
//!
//! `--json` prints the same as a JSON array of objects. The default step shown is the one a run
//! without `--dt`/`--tol` uses (the scene's options resolved), a fixed step `dt` or a
//! tolerance `tol` depending on the default integrator.

use anyhow::{Context, Result};
use serde::Serialize;
use tumble_scenarios::scenes::builtin;
use tumble_scenarios::{RunOptions, SceneInfo, StepControl};

/// Flags of `tumble scenes`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print a JSON array of objects (name, summary, coordinates, columns, parameters,
    /// conserved, oracle, problems, integrators, composition_bases, default_integrator,
    /// default_error, default_dt or
    /// default_tol, default_t_end) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// One parameter in the JSON output.
#[derive(Serialize)]
struct Parameter {
    name: &'static str,
    default: f64,
    unit: &'static str,
    domain: String,
    description: &'static str,
}

/// One scene in the JSON output; field order is the documented key order.
#[derive(Serialize)]
struct Entry {
    name: &'static str,
    summary: &'static str,
    coordinates: &'static [&'static str],
    columns: Vec<String>,
    parameters: Vec<Parameter>,
    conserved: &'static [&'static str],
    oracle: &'static str,
    problems: Vec<&'static str>,
    integrators: Vec<&'static str>,
    composition_bases: Vec<&'static str>,
    default_integrator: &'static str,
    default_error: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    default_dt: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    default_tol: Option<f64>,
    default_t_end: f64,
}

fn entry(info: &SceneInfo) -> Result<Entry> {
    let resolved = RunOptions::default()
        .resolve(info)
        .with_context(|| format!("scene `{}`: its own defaults are invalid", info.name))?;
    let (default_dt, default_tol) = match resolved.step {
        StepControl::Fixed(h) => (Some(h), None),
        StepControl::Tolerance(tol) => (None, Some(tol)),
    };
    Ok(Entry {
        name: info.name,
        summary: info.summary,
        coordinates: info.coordinates,
        columns: info.columns(),
        parameters: info
            .parameters
            .iter()
            .map(|p| Parameter {
                name: p.name,
                default: p.default,
                unit: p.unit,
                domain: p.domain.to_string(),
                description: p.description,
            })
            .collect(),
        conserved: info.conserved,
        oracle: info.oracle,
        problems: info.problems.iter().map(|k| k.name()).collect(),
        integrators: info.integrators(),
        composition_bases: info.composition_bases(),
        default_integrator: info.default_integrator,
        default_error: info.default_error,
        default_dt,
        default_tol,
        default_t_end: resolved.t_end,
    })
}

/// Runs the subcommand.
///
/// # Errors
/// If a scene's own defaults do not validate (a bug in the scene) or JSON serialization fails.
pub fn run(args: &Args) -> Result<()> {
    let entries = builtin()
        .iter()
        .map(|s| entry(s.info()))
        .collect::<Result<Vec<_>>>()?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&entries)?);
    } else {
        print!("{}", text(&entries));
    }
    Ok(())
}

/// Left-aligned columns separated by two spaces; the last column is not padded.
fn table(header: &[&str], rows: &[Vec<String>], indent: &str) -> String {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for r in rows {
        for (w, c) in widths.iter_mut().zip(r) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |cells: &[&str]| {
        let mut s = indent.to_string();
        for (i, (c, w)) in cells.iter().zip(&widths).enumerate() {
            if i + 1 == cells.len() {
                s.push_str(c);
            } else {
                s.push_str(&format!("{c:<w$}  "));
            }
        }
        s.trim_end().to_string() + "\n"
    };
    let mut out = line(header);
    for r in rows {
        out += &line(&r.iter().map(String::as_str).collect::<Vec<_>>());
    }
    out
}

/// The human-readable listing: one block per scene.
fn text(entries: &[Entry]) -> String {
    let mut out = String::new();
    for (k, e) in entries.iter().enumerate() {
        if k > 0 {
            out.push('\n');
        }
        out += &format!("{} — {}\n", e.name, e.summary);
        out += &format!("  coordinates  {}\n", e.coordinates.join(", "));
        out += &format!("  CSV columns  {}\n", e.columns.join(", "));
        out += "  parameters\n";
        let rows: Vec<Vec<String>> = e
            .parameters
            .iter()
            .map(|p| {
                vec![
                    p.name.to_string(),
                    p.default.to_string(),
                    p.unit.to_string(),
                    p.domain.clone(),
                    p.description.to_string(),
                ]
            })
            .collect();
        out += &table(
            &["name", "default", "unit", "domain", "description"],
            &rows,
            "    ",
        );
        out += &format!("  conserved    {}\n", e.conserved.join("; "));
        out += &format!("  oracle       {}\n", e.oracle);
        let step = match (e.default_dt, e.default_tol) {
            (Some(h), _) => format!("dt = {h} s"),
            (None, Some(tol)) => format!("tol = {tol:e}"),
            (None, None) => String::new(),
        };
        out += &format!(
            "  default run  {}, {step}, t_end = {} s; error {:.1e} against the reference\n",
            e.default_integrator, e.default_t_end, e.default_error
        );
        out += &format!("  integrators  {}\n", e.integrators.join(", "));
        if !e.composition_bases.is_empty() {
            out += &format!(
                "  compositions TABLE:BASE, BASE one of {} (`tumble integrators` lists them)\n",
                e.composition_bases.join(", ")
            );
        }
    }
    out
}
