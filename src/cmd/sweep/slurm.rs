//! `tumble sweep slurm`: the job script that runs a sweep on a Slurm cluster — a job array of
//! `N` shards, each `--resume`-safe, and a merge job after all of them.
//!
//! Everything is checked before a file is written: the sweep (file and `--set`), the shard
//! count (at least 1, at most the points), the Slurm options, the tumble binary, and the
//! output folder (writable, not holding another sweep or the shards of another count). The
//! folder then holds `sweep.toml` (the resolved definition every shard runs), `submit.sh`
//! and `logs/`; the shards write `shard-K/`, the merge `merged/`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use tumble_studies::sweep::{self, DEFINITION, JOURNAL, SweepDefinition};

use super::{default_output, parse_override};
use crate::output;

/// Flags of `tumble sweep slurm`.
#[derive(clap::Args, Debug)]
pub struct SlurmArgs {
    /// The sweep file (TOML).
    #[arg(value_name = "SWEEP.toml")]
    pub file: PathBuf,
    /// Shards: the job array's size (at most the sweep's points).
    #[arg(long, value_name = "N")]
    pub shards: u64,
    /// CPUs of each shard's task (its worker threads), and of the merge job.
    #[arg(long = "cpus-per-task", value_name = "C", default_value_t = 1)]
    pub cpus_per_task: u32,
    /// Slurm partition [default: the cluster's default].
    #[arg(long, value_name = "P")]
    pub partition: Option<String>,
    /// Time limit of each task and of the merge, as Slurm writes it (`30`, `2:00:00`,
    /// `1-12:00:00`) [default: the partition's].
    #[arg(long, value_name = "T")]
    pub time: Option<String>,
    /// Output folder: the job script, the shards' folders, the merged sweep and the logs
    /// [default: out/NAME for a file NAME.sweep.toml]. It must be on a file system the
    /// cluster's nodes share.
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// The tumble binary the jobs run [default: this one].
    #[arg(long, value_name = "PATH")]
    pub tumble: Option<PathBuf>,
    /// Override a key of the sweep (as for `tumble sweep`); the shards run the resolved
    /// definition.
    #[arg(
        long = "set",
        value_name = "KEY=VALUE",
        allow_hyphen_values = true,
        action = clap::ArgAction::Append
    )]
    pub set: Vec<String>,
    /// As for `tumble sweep`, passed on to every shard.
    #[command(flatten)]
    pub limits: super::PointLimits,
}

/// The job script's name in the output folder.
pub const SCRIPT: &str = "submit.sh";

/// Everything the script needs, validated.
struct Plan {
    name: String,
    points: u64,
    shards: u64,
    cpus: u32,
    partition: Option<String>,
    time: Option<String>,
    dir: PathBuf,
    tumble: PathBuf,
    scene: &'static str,
    command_line: String,
    /// `tumble sweep` flags every shard passes on (` --allow-coarse-step`, ` --point-seconds S`).
    shard_flags: String,
}

/// Runs `tumble sweep slurm`.
///
/// # Errors
/// Any invalid input, before a file is written; a file that cannot be written.
pub fn run(args: &SlurmArgs) -> Result<()> {
    let overrides = args
        .set
        .iter()
        .map(|s| parse_override(s))
        .collect::<Result<Vec<_>>>()?;
    let def = SweepDefinition::load(&args.file, &overrides)?;
    let mut shard_flags = String::new();
    if args.limits.allow_coarse_step {
        shard_flags.push_str(" --allow-coarse-step");
    }
    if let Some(seconds) = args.limits.check(&def)? {
        shard_flags.push_str(&format!(" --point-seconds {seconds}"));
    }
    let points = def.points();
    if args.shards == 0 {
        bail!("--shards 0: at least one shard is needed");
    }
    if args.shards > points {
        bail!(
            "--shards {}: the sweep has {points} points; at most {points} shards (each gets \
             at least one point)",
            args.shards
        );
    }
    if args.cpus_per_task == 0 {
        bail!("--cpus-per-task 0: each task needs at least one CPU");
    }
    let partition = match &args.partition {
        Some(p)
            if p.is_empty()
                || !p
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_-.,".contains(c)) =>
        {
            bail!("--partition {p:?}: expected a partition name (letters, digits, `_-.,`)")
        }
        p => p.clone(),
    };
    let time = match &args.time {
        Some(t) if !valid_time(t) => bail!(
            "--time {t:?}: expected a Slurm time limit: MINUTES, MINUTES:SECONDS, \
             HOURS:MINUTES:SECONDS, DAYS-HOURS, DAYS-HOURS:MINUTES or DAYS-HOURS:MINUTES:SECONDS"
        ),
        t => t.clone(),
    };
    let tumble = binary(args.tumble.as_deref())?;
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| default_output(Some(&args.file)));
    let dir = absolute(&dir)?;
    let Some(dir_text) = dir.to_str() else {
        bail!("{}: the output folder's path is not UTF-8", dir.display());
    };
    if let Some(c) = dir_text.chars().find(|&c| !safe_path_char(c)) {
        bail!(
            "{}: the output folder's path holds {c:?}; the job script writes it unquoted \
             into #SBATCH lines, which take letters, digits and `/._+,:@=-` only: choose \
             another folder",
            dir.display()
        );
    }
    let text = def.to_toml();
    check_folder(&dir, &text, args.shards)?;
    let plan = Plan {
        name: job_name(&args.file),
        points,
        shards: args.shards,
        cpus: args.cpus_per_task,
        partition,
        time,
        dir,
        tumble,
        scene: def.scene.info().name,
        command_line: std::env::args().collect::<Vec<_>>().join(" "),
        shard_flags,
    };

    // Every check passed: the files.
    std::fs::create_dir_all(plan.dir.join("logs")).with_context(|| {
        format!(
            "{}: cannot create the logs folder",
            plan.dir.join("logs").display()
        )
    })?;
    output::write_whole(&plan.dir.join(DEFINITION), text.as_bytes())?;
    let script_path = plan.dir.join(SCRIPT);
    output::write_whole(&script_path, script(&plan).as_bytes())?;
    make_executable(&script_path)?;

    let per_shard = points.div_ceil(plan.shards);
    println!(
        "wrote {}: {} ({}), {points} points in {} shards of at most {per_shard}, {} CPU{} each",
        script_path.display(),
        plan.name,
        plan.scene,
        plan.shards,
        plan.cpus,
        if plan.cpus == 1 { "" } else { "s" }
    );
    println!("submit the shards and the merge job:");
    println!("  bash {}", script_path.display());
    println!("run some shards again (after a failure), then the merge:");
    println!("  bash {} 2,5", script_path.display());
    println!(
        "results  {}",
        plan.dir.join("merged").join("results.csv").display()
    );
    println!("logs     {}", plan.dir.join("logs").display());
    Ok(())
}

/// Whether `c` can stand unquoted in a shell word and an `#SBATCH` line.
fn safe_path_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || "/._+,:@=-".contains(c)
}

/// A Slurm time limit: `M`, `M:S`, `H:M:S`, `D-H`, `D-H:M`, `D-H:M:S` (or `infinite`).
fn valid_time(t: &str) -> bool {
    let number = |s: &str| !s.is_empty() && s.len() <= 9 && s.chars().all(|c| c.is_ascii_digit());
    let clock = |s: &str, most: usize| {
        let parts: Vec<&str> = s.split(':').collect();
        parts.len() <= most && parts.iter().all(|p| number(p))
    };
    if t == "infinite" || t == "unlimited" {
        return true;
    }
    match t.split_once('-') {
        Some((days, rest)) => number(days) && clock(rest, 3),
        None => clock(t, 3),
    }
}

/// The binary the jobs run: `--tumble`, or this process's own, as an absolute path to an
/// executable file.
fn binary(given: Option<&Path>) -> Result<PathBuf> {
    let path = match given {
        Some(p) => absolute(p)?,
        None => std::env::current_exe().context("cannot find the path of this tumble binary")?,
    };
    let meta = std::fs::metadata(&path)
        .with_context(|| format!("--tumble {}: cannot be used", path.display()))?;
    if !meta.is_file() {
        bail!("--tumble {}: not a file", path.display());
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        if meta.permissions().mode() & 0o111 == 0 {
            bail!("--tumble {}: not executable", path.display());
        }
    }
    let path = path.canonicalize().unwrap_or(path);
    if let Some(c) = path
        .to_str()
        .and_then(|s| s.chars().find(|c| "'\n\r".contains(*c)))
    {
        bail!("--tumble {}: the path holds {c:?}", path.display());
    }
    Ok(path)
}

/// `path` made absolute against the current folder (without resolving links).
fn absolute(path: &Path) -> Result<PathBuf> {
    std::path::absolute(path)
        .with_context(|| format!("{}: cannot make the path absolute", path.display()))
}

/// The job name: the sweep file's name without `.sweep.toml`.
fn job_name(file: &Path) -> String {
    let name = default_output(Some(file));
    name.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "_-.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Checks the output folder before anything is written: a folder (or a path where one can be
/// created), writable, not holding another sweep, and its shard folders from this shard count.
fn check_folder(dir: &Path, text: &str, shards: u64) -> Result<()> {
    output::check_folder(dir, &[DEFINITION.to_string(), SCRIPT.to_string()])?;
    // The nearest existing ancestor must take a new file.
    let mut probe = dir;
    while !probe.exists() {
        probe = probe
            .parent()
            .with_context(|| format!("{}: no existing folder above it", dir.display()))?;
    }
    tempfile::NamedTempFile::new_in(probe).with_context(|| {
        format!(
            "{}: the output folder cannot be written ({} does not take new files)",
            dir.display(),
            probe.display()
        )
    })?;
    if !dir.is_dir() {
        return Ok(());
    }
    let stored = dir.join(DEFINITION);
    if let Ok(old) = std::fs::read_to_string(&stored)
        && old != text
    {
        bail!(
            "{}: holds the shards of another sweep (its sweep.toml differs); choose another \
             output folder",
            dir.display()
        );
    }
    let entries = std::fs::read_dir(dir)
        .with_context(|| format!("{}: cannot list the output folder", dir.display()))?;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(k) = name.strip_prefix("shard-") else {
            continue;
        };
        if let Some(shard) = sweep::journal::shard_of(&entry.path().join(JOURNAL))?
            && (shard.count != shards || k != shard.index.to_string())
        {
            bail!(
                "{}: holds shard {shard} of a run in {} shards; generate the script with \
                 --shards {} or choose another output folder",
                entry.path().display(),
                shard.count,
                shard.count
            );
        }
    }
    Ok(())
}

#[cfg(unix)]
fn make_executable(path: &Path) -> Result<()> {
    use std::os::unix::fs::PermissionsExt;
    let mut perms = std::fs::metadata(path)?.permissions();
    perms.set_mode(perms.mode() | 0o755);
    std::fs::set_permissions(path, perms)
        .with_context(|| format!("{}: cannot make it executable", path.display()))
}

#[cfg(not(unix))]
fn make_executable(_: &Path) -> Result<()> {
    Ok(())
}

/// `'text'` for the shell.
fn quote(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

/// The `#SBATCH` lines every job shares.
fn common_directives(plan: &Plan) -> String {
    let mut s = format!("#SBATCH --cpus-per-task={}\n", plan.cpus);
    if let Some(p) = &plan.partition {
        let _ = writeln!(s, "#SBATCH --partition={p}");
    }
    if let Some(t) = &plan.time {
        let _ = writeln!(s, "#SBATCH --time={t}");
    }
    s.push_str("#SBATCH --open-mode=append\n");
    s
}

/// The job script.
fn script(plan: &Plan) -> String {
    let dir = plan.dir.to_string_lossy();
    let tumble = quote(&plan.tumble.to_string_lossy());
    let n = plan.shards;
    let name = &plan.name;
    let common = common_directives(plan);
    let sweep_file = quote(&format!("{dir}/{DEFINITION}"));
    format!(
        r#"#!/bin/bash
# Slurm jobs of the tumble sweep {name} ({scene}): {points} points in {n} shards.
# Written by: {command_line}
#
# Submit the {n} shards as a job array, then the merge job:
#   bash {dir}/{SCRIPT}
# Submit shards 2 and 5 again (e.g. after a failure), then the merge job:
#   bash {dir}/{SCRIPT} 2,5
#
# Shard K runs `tumble sweep --shard K/{n} --resume` into shard-K/: a task that is requeued
# or pre-empted continues where it stopped. The merge job starts when every task has ended,
# however it ended (afterany); it merges the shards into merged/, and when a shard is not
# finished it fails, listing the unfinished shards and the command to finish them.
# Logs: logs/shard-K.log, logs/merge.log. sbatch's environment variables (SBATCH_ACCOUNT,
# SBATCH_QOS, ...) apply to both jobs.
set -euo pipefail

tasks=${{1:-1-{n}}}
if ! [[ $tasks =~ ^[0-9]+(-[0-9]+)?(,[0-9]+(-[0-9]+)?)*$ ]]; then
    echo "usage: bash $0 [SHARDS]   (SHARDS as for sbatch --array: 2,5 or 1-3; default 1-{n})" >&2
    exit 2
fi
mkdir -p {dir}/logs

array=$(sbatch --parsable --array="$tasks" <<'SHARD_JOB'
#!/bin/bash
#SBATCH --job-name={name}
{common}#SBATCH --requeue
#SBATCH --output={dir}/logs/shard-%a.log
# One shard of the sweep: K is the array task. --resume continues the shard's journal after a
# requeue or a pre-emption; --break-lock takes over the lock of this task's previous run,
# killed on another node (Slurm never runs two copies of one array task).
k=$SLURM_ARRAY_TASK_ID
echo "tumble: shard $k/{n}, job ${{SLURM_ARRAY_JOB_ID}}_$k on $(hostname), start $(date -u +%FT%TZ), restarts ${{SLURM_RESTART_COUNT:-0}}" >&2
exec {tumble} sweep {sweep_file} --shard "$k/{n}" --resume --break-lock{shard_flags} \
    --threads "${{SLURM_CPUS_PER_TASK:-{cpus}}}" -o "{dir}/shard-$k"
SHARD_JOB
)
array=${{array%%;*}}

merge=$(sbatch --parsable --dependency="afterany:$array" <<'MERGE_JOB'
#!/bin/bash
#SBATCH --job-name={name}-merge
{common}#SBATCH --output={dir}/logs/merge.log
# After every shard's task has ended, however it ended: merge the shards; when some are not
# finished, list them and say how to finish them.
set -uo pipefail
echo "tumble: merge of {n} shards, job $SLURM_JOB_ID on $(hostname), start $(date -u +%FT%TZ)" >&2
shard_dirs=()
for k in $(seq 1 {n}); do
    shard_dirs+=("{dir}/shard-$k")
done
status=0
{tumble} sweep merge "${{shard_dirs[@]}}" -o "{dir}/merged" || status=$?
if [ "$status" -ne 0 ]; then
    unfinished=()
    for k in $(seq 1 {n}); do
        [ -f "{dir}/shard-$k/results.csv" ] || unfinished+=("$k")
    done
    if [ "${{#unfinished[@]}}" -gt 0 ]; then
        list=$(IFS=,; echo "${{unfinished[*]}}")
        echo "tumble: unfinished shards: $list (of {n}); see {dir}/logs/shard-K.log" >&2
        echo "tumble: finish them and merge with: bash {dir}/{SCRIPT} $list" >&2
    fi
fi
exit "$status"
MERGE_JOB
)
merge=${{merge%%;*}}

echo "shards   job array $array (tasks $tasks of {n}), logs {dir}/logs/shard-K.log"
echo "merge    job $merge, after every task has ended, log {dir}/logs/merge.log"
echo "results  {dir}/merged/results.csv"
"#,
        scene = plan.scene,
        points = plan.points,
        command_line = plan.command_line.replace('\n', " "),
        cpus = plan.cpus,
        shard_flags = plan.shard_flags,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slurm_time_limits() {
        for ok in [
            "30",
            "30:00",
            "2:00:00",
            "1-12",
            "1-12:30",
            "1-12:30:00",
            "infinite",
        ] {
            assert!(valid_time(ok), "{ok}");
        }
        for bad in ["", "1h", "1:2:3:4", "-1", "1-", "1-1:2:3:4", "2 h", "1:-2"] {
            assert!(!valid_time(bad), "{bad}");
        }
    }

    #[test]
    fn quoting_survives_quotes() {
        assert_eq!(quote("a'b"), r"'a'\''b'");
    }
}
