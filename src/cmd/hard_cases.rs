//! `tumble hard-cases`: the atlas of every method on a battery of cases that break
//! integrators (`tumble_studies::hard_cases`), written as `atlas.csv`, `manifest.json` and
//! `atlas.png`/`.svg` into an output folder.
//!
//! The built-in cases, `--cases` to choose among them, `--case-file` to add one's own; every
//! method that runs a case's scene, or `--integrators` (each optionally with its own setting,
//! `rk4:dt=0.05`). Everything is checked before the first run. The entries run in parallel;
//! each is journalled as it finishes, so `--resume` continues an atlas cut short by its
//! `--budget` or a signal. Exit status 0 when every entry finished (whatever its outcome: a
//! failure is a result of the atlas), 3 when the budget left entries to run, 130/143 on a
//! signal, 1 for any error.

use std::path::PathBuf;

use anyhow::{Result, bail};
use tumble_integrators::registry;
use tumble_studies::hard_cases::Case;
use tumble_studies::hard_cases::atlas::{self, AtlasConfig, AtlasReport, Method, Status};
use tumble_studies::hard_cases::record::AtlasRecord;

use crate::output;
use crate::signals;
use tumble_plot as plot;
use tumble_plot::atlas::{Atlas, AtlasCase};

/// Flags of `tumble hard-cases`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Built-in cases to run, comma-separated [default: all; `--list` names them].
    #[arg(long, value_name = "A,B,...", value_delimiter = ',')]
    pub cases: Vec<String>,
    /// A case file of one's own (TOML, see `--list` for the built-in ones' folder); repeat
    /// for several. With `--case-file` and no `--cases`, only the files are run.
    #[arg(long = "case-file", value_name = "FILE")]
    pub case_files: Vec<PathBuf>,
    /// Methods, comma-separated, each `NAME` (its setting chosen by the atlas's rule) or
    /// `NAME:dt=H` / `NAME:tol=T` [default: every method that runs a case's scene].
    #[arg(long, value_name = "X,Y,...", value_delimiter = ',')]
    pub integrators: Vec<String>,
    /// Wall-clock budget of the whole atlas in seconds: no entry starts after it; `--resume`
    /// continues.
    #[arg(long, value_name = "SECONDS", default_value_t = 420.0)]
    pub budget: f64,
    /// Wall-clock limit of each run in seconds (a run reaching it is recorded as `time-limit`;
    /// references get 4 times this).
    #[arg(long = "run-seconds", value_name = "SECONDS", default_value_t = 10.0)]
    pub run_seconds: f64,
    /// Worker threads [default: the number of cores].
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Output folder.
    #[arg(
        short = 'o',
        long = "output",
        value_name = "DIR",
        default_value = "out/hard-cases"
    )]
    pub output: PathBuf,
    /// Continue the atlas in the output folder.
    #[arg(long)]
    pub resume: bool,
    /// Take over the output folder's lock even if another tumble process seems to hold it.
    #[arg(long = "break-lock")]
    pub break_lock: bool,
    /// List the built-in cases (name, scene, why) and exit.
    #[arg(long)]
    pub list: bool,
}

/// The budget ran out with entries left: exit status 3.
#[derive(Debug)]
pub struct Unfinished {
    left: usize,
    dir: PathBuf,
}

impl Unfinished {
    /// The exit status.
    pub const EXIT_CODE: u8 = 3;
}

impl std::fmt::Display for Unfinished {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the budget ran out with {} entries left; run the same command with --resume to \
             finish {}",
            self.left,
            self.dir.display()
        )
    }
}

impl std::error::Error for Unfinished {}

/// Runs the subcommand.
///
/// # Errors
/// Invalid flags or case files (before any run), an unwritable folder; [`Unfinished`].
pub fn run(args: &Args) -> Result<()> {
    let built_in = Case::built_in()?;
    if args.list {
        for c in &built_in {
            println!(
                "{}  ({}, t_end = {} s)",
                c.name,
                c.scene.info().name,
                c.t_end
            );
            println!("    {}", atlas::parameters_text(c));
            println!("    {}", c.why);
        }
        println!("files: crates/studies/src/hard_cases/cases/");
        return Ok(());
    }
    let mut cases: Vec<Case> = Vec::new();
    if args.cases.is_empty() && args.case_files.is_empty() {
        cases.clone_from(&built_in);
    }
    for name in &args.cases {
        if cases.iter().any(|c| c.name == name.trim()) {
            bail!("--cases: `{}` twice", name.trim());
        }
        match built_in.iter().find(|c| c.name == name.trim()) {
            Some(c) => cases.push(c.clone()),
            None => bail!(
                "--cases: no built-in case `{name}`; the cases are: {}",
                built_in
                    .iter()
                    .map(|c| c.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }
    }
    for path in &args.case_files {
        let case = Case::load(path)?;
        if cases.iter().any(|c| c.name == case.name) {
            bail!(
                "{}: a case named `{}` is already in the atlas",
                path.display(),
                case.name
            );
        }
        cases.push(case);
    }
    let methods: Vec<Method> = if args.integrators.is_empty() {
        registry::methods()
            .iter()
            .filter(|m| cases.iter().any(|c| c.scene.info().kind_for(m).is_some()))
            .map(|info| Method {
                info,
                setting: None,
            })
            .collect()
    } else {
        args.integrators
            .iter()
            .map(|s| Method::parse(s).map_err(|e| anyhow::anyhow!("--integrators: {e}")))
            .collect::<Result<_>>()?
    };
    for (k, m) in methods.iter().enumerate() {
        if methods[..k].iter().any(|n| n.spec() == m.spec()) {
            bail!("--integrators: `{}` twice", m.spec());
        }
    }
    if let Some(m) = methods.iter().find(|m| {
        !cases
            .iter()
            .any(|c| c.scene.info().kind_for(m.info).is_some())
    }) {
        bail!(
            "--integrators: `{}` runs none of the cases' scenes",
            m.info.name
        );
    }
    for (flag, v) in [
        ("--budget", args.budget),
        ("--run-seconds", args.run_seconds),
    ] {
        if !(v.is_finite() && v > 0.0) {
            bail!("{flag} {v}: expected a positive number of seconds");
        }
    }
    let threads = match args.threads {
        Some(0) => bail!("--threads 0: at least one worker thread is needed"),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, usize::from),
    };
    let dir = &args.output;
    let files = ["atlas.csv", "manifest.json", "atlas.png", "atlas.svg"];
    output::check_folder(dir, &files.map(String::from))?;
    let _lock = output::lock_folder(dir, args.break_lock)?;

    let total = atlas::pairs(&cases, &methods).len();
    eprintln!(
        "hard cases   {} cases × {} methods: {total} entries, budget {} s, {} s a run",
        cases.len(),
        methods.len(),
        args.budget,
        args.run_seconds
    );
    let config = AtlasConfig {
        threads,
        run_seconds: args.run_seconds,
        budget: args.budget,
        resume: args.resume,
        cancel: Some(signals::flag()),
    };
    let report = atlas::run(&cases, &methods, dir, &config, &|done, total| {
        if done % 25 == 0 || done == total {
            eprintln!("progress     {done} of {total} entries");
        }
    })
    .map_err(anyhow::Error::msg)?;
    if let Some(code) = signals::interrupted() {
        return Err(signals::Interrupted {
            code,
            message: format!(
                "{} of {} entries are in {}; run the same command with --resume to finish",
                report.entries.len(),
                report.total,
                dir.join(atlas::JOURNAL).display()
            ),
        }
        .into());
    }
    // The workers the atlas ran on: no more than its entries.
    let workers = threads.clamp(1, report.total.max(1));
    write_outputs(&cases, &methods, &report, args, dir, workers)?;
    summary(&cases, &report);
    if !report.complete() {
        return Err(Unfinished {
            left: report.total - report.entries.len(),
            dir: dir.clone(),
        }
        .into());
    }
    Ok(())
}

/// `atlas.csv`, the figure and `manifest.json`.
fn write_outputs(
    cases: &[Case],
    methods: &[Method],
    report: &AtlasReport,
    args: &Args,
    dir: &std::path::Path,
    threads: usize,
) -> Result<()> {
    output::write_whole(
        &dir.join("atlas.csv"),
        &atlas::atlas_csv(&report.entries).map_err(anyhow::Error::msg)?,
    )?;
    let atlas_cases: Vec<AtlasCase> = cases
        .iter()
        .map(|c| AtlasCase {
            name: &c.name,
            scene: c.scene.info(),
            bounds_error: c.property.error.is_some(),
        })
        .collect();
    let figure = Atlas::of_entries(&atlas_cases, methods, &report.entries);
    for name in ["atlas.png", "atlas.svg"] {
        plot::save(&figure, &dir.join(name))?;
    }
    let manifest = AtlasRecord::new(
        crate::provenance::now(threads),
        cases,
        methods,
        report,
        args.budget,
        args.run_seconds,
    );
    output::write_whole(
        &dir.join("manifest.json"),
        serde_json::to_string_pretty(&manifest)?.as_bytes(),
    )?;
    Ok(())
}

/// Per case: how many methods met its property, and the outcomes of the others.
fn summary(cases: &[Case], report: &AtlasReport) {
    for case in cases {
        let entries: Vec<_> = report
            .entries
            .iter()
            .filter(|e| e.case == case.name)
            .collect();
        let count = |s: Status| entries.iter().filter(|e| e.status == s).count();
        let ok: Vec<&str> = entries
            .iter()
            .filter(|e| e.status == Status::Ok)
            .map(|e| e.method.as_str())
            .collect();
        eprintln!(
            "{:<26} ok {:>2}, violated {:>2}, failed {:>2}, time limit {:>2}{}",
            case.name,
            ok.len(),
            count(Status::Violated),
            count(Status::Failed),
            count(Status::TimeLimit),
            if ok.is_empty() {
                String::new()
            } else {
                format!(": {}", ok.join(" "))
            }
        );
    }
    eprintln!(
        "atlas        {} of {} entries in {:.1} s",
        report.entries.len(),
        report.total,
        report.seconds
    );
}
