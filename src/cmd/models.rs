//! `tumble models`: list the model files of a directory (the shipped `models/` by default) with
//! their coordinates, CSV columns, parameters, conserved quantities, default run and the
//! integrators that run them. A model file runs wherever a scene name is accepted:
//! `tumble simulate models/heavy-top.toml`, `scene = "heavy-top.toml"` in a sweep file.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use serde::Serialize;
use tumble_studies::catalog::{Entry, entry};

/// Flags of `tumble models`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The directory of model files (`*.toml` with a `[model]` table).
    #[arg(default_value = "models")]
    pub dir: PathBuf,
    /// Print a JSON array of objects (path, then the fields of `tumble scenes --json`).
    #[arg(long)]
    pub json: bool,
}

/// A model file and its catalogue entry.
#[derive(Serialize)]
struct Listed {
    path: String,
    #[serde(flatten)]
    entry: Entry,
}

/// Runs the subcommand.
///
/// # Errors
/// An unreadable directory, or a model file that does not load (its place and what is wrong).
pub fn run(args: &Args) -> Result<()> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&args.dir)
        .with_context(|| format!("{}: cannot list the model directory", args.dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml") && tumble_model::is_model_file(p))
        .collect();
    paths.sort();
    if paths.is_empty() {
        bail!(
            "{}: no model files (TOML files with a [model] table); the shipped models are in \
             the repository's models/ directory",
            args.dir.display()
        );
    }
    let listed = paths
        .iter()
        .map(|p| listed(p))
        .collect::<Result<Vec<_>>>()?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&listed)?);
    } else {
        print!("{}", text(&listed));
    }
    Ok(())
}

fn listed(path: &Path) -> Result<Listed> {
    let scene = tumble_model::load(path).map_err(|e| anyhow::anyhow!("{e}"))?;
    let entry = entry(scene)
        .with_context(|| format!("{}: its own defaults are invalid", path.display()))?;
    Ok(Listed {
        path: path.display().to_string(),
        entry,
    })
}

fn text(listed: &[Listed]) -> String {
    let mut out = String::new();
    for (k, l) in listed.iter().enumerate() {
        let e = &l.entry;
        if k > 0 {
            out.push('\n');
        }
        out += &format!("{} — {}\n", l.path, e.summary);
        out += &format!("  name         {}\n", e.name);
        out += &format!("  coordinates  {}\n", e.coordinates.join(", "));
        out += &format!("  CSV columns  {}\n", e.columns.join(", "));
        out += &super::scenes::parameters(e);
        if !e.conserved.is_empty() {
            out += &format!("  conserved    {}\n", e.conserved.join("; "));
        }
        let step = match (e.default_dt, e.default_tol) {
            (Some(h), _) => format!("dt = {h} s"),
            (None, Some(tol)) => format!("tol = {tol:e}"),
            (None, None) => String::new(),
        };
        out += &format!(
            "  default run  {}, {step}, t_end = {} s\n",
            e.default_integrator, e.default_t_end
        );
        out += &format!("  integrators  {}\n", e.integrators.join(", "));
    }
    out
}
