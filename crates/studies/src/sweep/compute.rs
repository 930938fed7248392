//! The compute record: `compute.csv` in a sweep folder, one line per run of `tumble sweep`
//! on it (the first run and every `--resume`), appended when the run ends — completed or
//! stopped by a signal. A merge gathers the records of all its shards.
//!
//! Columns: `shard` (`K/N`), `host`, `threads`, `wall_time_s`, `computed_points` (points
//! this run computed and appended to the journal), `failed_points` (how many of those failed),
//! `complete` (whether the shard was complete when the run ended). A run killed outright
//! (`SIGKILL`, a node lost) records nothing; its points in the journal are counted by
//! [`ComputeRecord::unrecorded`].

use std::fs::OpenOptions;
use std::io::Write;
use std::path::Path;
use std::time::Duration;

use super::{Shard, SweepError};

/// The compute record in a sweep folder.
pub const COMPUTE: &str = "compute.csv";

/// The columns of `compute.csv`.
const HEADER: [&str; 7] = [
    "shard",
    "host",
    "threads",
    "wall_time_s",
    "computed_points",
    "failed_points",
    "complete",
];

/// One run of a sweep on a folder.
#[derive(Debug, Clone, PartialEq)]
pub struct ComputeRun {
    /// The shard it ran.
    pub shard: Shard,
    /// The host it ran on.
    pub host: String,
    /// Worker threads.
    pub threads: usize,
    /// Wall time (reading and writing the journal included).
    pub wall_time: Duration,
    /// Points it computed.
    pub computed: u64,
    /// Of those, points that failed or panicked.
    pub failed: u64,
    /// Whether the shard was complete when it ended.
    pub complete: bool,
}

/// Totals over the runs of a record.
#[derive(Debug, Clone, PartialEq)]
pub struct ComputeTotals {
    /// Runs.
    pub runs: usize,
    /// Distinct hosts, in order of first appearance.
    pub hosts: Vec<String>,
    /// Points computed by all runs.
    pub computed: u64,
    /// Failed points among them.
    pub failed: u64,
    /// Sum of the runs' wall times.
    pub wall_time: Duration,
    /// Sum of threads × wall time (the capacity the runs held).
    pub thread_seconds: f64,
    /// The most threads of a run.
    pub max_threads: usize,
}

/// The runs recorded in a folder (or gathered from shard folders by a merge).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ComputeRecord {
    /// In the order they ran (a merge: shard by shard).
    pub runs: Vec<ComputeRun>,
}

impl ComputeRecord {
    /// The totals.
    #[must_use]
    pub fn totals(&self) -> ComputeTotals {
        let mut hosts: Vec<String> = Vec::new();
        for r in &self.runs {
            if !hosts.contains(&r.host) {
                hosts.push(r.host.clone());
            }
        }
        ComputeTotals {
            runs: self.runs.len(),
            hosts,
            computed: self.runs.iter().map(|r| r.computed).sum(),
            failed: self.runs.iter().map(|r| r.failed).sum(),
            wall_time: self.runs.iter().map(|r| r.wall_time).sum(),
            thread_seconds: self
                .runs
                .iter()
                .map(|r| r.threads as f64 * r.wall_time.as_secs_f64())
                .sum(),
            max_threads: self.runs.iter().map(|r| r.threads).max().unwrap_or(0),
        }
    }

    /// Points of `finished` (rows in a journal) that no recorded run computed: those of runs
    /// killed before they could record themselves.
    #[must_use]
    pub fn unrecorded(&self, finished: u64) -> u64 {
        finished.saturating_sub(self.totals().computed)
    }

    /// Reads `dir`'s record; a folder without one (written before records were kept) has
    /// an empty record.
    ///
    /// # Errors
    /// [`SweepError::Io`] when it cannot be read, [`SweepError::Compute`] when it is damaged.
    pub fn read(dir: &Path) -> Result<Self, SweepError> {
        let path = dir.join(COMPUTE);
        let text = match std::fs::read_to_string(&path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Self::default()),
            Err(source) => {
                return Err(SweepError::Io {
                    path,
                    what: "cannot read the compute record",
                    source,
                });
            }
        };
        // A run killed while appending leaves a torn last line: dropped.
        let complete = text.rfind('\n').map_or("", |i| &text[..=i]);
        let damaged = |line: usize, reason: String| SweepError::Compute {
            path: path.clone(),
            line,
            reason,
        };
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(complete.as_bytes());
        let mut runs = Vec::new();
        for (k, record) in reader.records().enumerate() {
            let line = k + 1;
            let record = record.map_err(|e| damaged(line, e.to_string()))?;
            if line == 1 {
                if record.iter().ne(HEADER) {
                    return Err(damaged(1, "not the header of a compute record".into()));
                }
                continue;
            }
            runs.push(parse_run(&record).map_err(|reason| damaged(line, reason))?);
        }
        Ok(Self { runs })
    }

    /// Writes the record as `dir`'s `compute.csv`, replacing any.
    ///
    /// # Errors
    /// When the file cannot be written.
    pub fn write(&self, dir: &Path) -> Result<(), SweepError> {
        let mut bytes = header_line()?;
        for run in &self.runs {
            bytes.extend(run_line(run)?);
        }
        tumble_output::Destination::check(&dir.join(COMPUTE))?.write_all(&bytes)?;
        Ok(())
    }

    /// Appends `run` to `dir`'s `compute.csv` (created with its header if missing).
    ///
    /// # Errors
    /// When the file cannot be written.
    pub fn append(dir: &Path, run: &ComputeRun) -> Result<(), SweepError> {
        let path = dir.join(COMPUTE);
        let io = |source| SweepError::Io {
            path: path.clone(),
            what: "cannot append to the compute record",
            source,
        };
        let mut file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(io)?;
        let mut bytes = Vec::new();
        if file.metadata().map_err(io)?.len() == 0 {
            bytes = header_line()?;
        }
        bytes.extend(run_line(run)?);
        file.write_all(&bytes).map_err(io)?;
        file.flush().map_err(io)
    }
}

fn csv_error(e: impl std::fmt::Display) -> SweepError {
    SweepError::Csv(e.to_string())
}

fn header_line() -> Result<Vec<u8>, SweepError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(HEADER).map_err(csv_error)?;
    w.into_inner().map_err(csv_error)
}

fn run_line(run: &ComputeRun) -> Result<Vec<u8>, SweepError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        run.shard.to_string(),
        run.host.replace(['\r', '\n'], " "),
        run.threads.to_string(),
        format!("{:.6}", run.wall_time.as_secs_f64()),
        run.computed.to_string(),
        run.failed.to_string(),
        run.complete.to_string(),
    ])
    .map_err(csv_error)?;
    w.into_inner().map_err(csv_error)
}

fn parse_run(record: &csv::StringRecord) -> Result<ComputeRun, String> {
    if record.len() != HEADER.len() {
        return Err(format!(
            "{} fields, the header has {}",
            record.len(),
            HEADER.len()
        ));
    }
    let whole = |j: usize| {
        record[j]
            .parse::<u64>()
            .map_err(|_| format!("{} `{}` is not a whole number", HEADER[j], &record[j]))
    };
    let seconds = record[3]
        .parse::<f64>()
        .ok()
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .ok_or_else(|| format!("wall_time_s `{}` is not a duration", &record[3]))?;
    Ok(ComputeRun {
        shard: Shard::parse(&record[0]).map_err(|e| e.to_string())?,
        host: record[1].to_string(),
        threads: usize::try_from(whole(2)?).map_err(|e| e.to_string())?,
        wall_time: seconds,
        computed: whole(4)?,
        failed: whole(5)?,
        complete: match &record[6] {
            "true" => true,
            "false" => false,
            other => return Err(format!("complete `{other}` is neither true nor false")),
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(shard: Shard, host: &str, threads: usize, computed: u64) -> ComputeRun {
        ComputeRun {
            shard,
            host: host.into(),
            threads,
            wall_time: Duration::from_millis(1500),
            computed,
            failed: 1,
            complete: false,
        }
    }

    #[test]
    fn records_append_read_back_and_add_up() {
        let tmp = tempfile::tempdir().unwrap();
        assert_eq!(
            ComputeRecord::read(tmp.path()).unwrap(),
            ComputeRecord::default()
        );
        let a = run(Shard::new(2, 3).unwrap(), "node-1", 4, 10);
        let b = run(Shard::new(2, 3).unwrap(), "node,2", 8, 5);
        ComputeRecord::append(tmp.path(), &a).unwrap();
        ComputeRecord::append(tmp.path(), &b).unwrap();
        let record = ComputeRecord::read(tmp.path()).unwrap();
        assert_eq!(record.runs, [a.clone(), b.clone()]);
        let t = record.totals();
        assert_eq!(t.runs, 2);
        assert_eq!(t.hosts, ["node-1", "node,2"]);
        assert_eq!((t.computed, t.failed, t.max_threads), (15, 2, 8));
        assert_eq!(t.wall_time, Duration::from_secs(3));
        assert!((t.thread_seconds - 18.0).abs() < 1e-12);
        assert_eq!(record.unrecorded(20), 5);
        assert_eq!(record.unrecorded(3), 0);
        // A torn last line is dropped; a damaged line is an error naming it.
        let path = tmp.path().join(COMPUTE);
        let mut text = std::fs::read_to_string(&path).unwrap();
        text.push_str("1/3,x,2,0.5");
        std::fs::write(&path, &text).unwrap();
        assert_eq!(ComputeRecord::read(tmp.path()).unwrap().runs.len(), 2);
        text.push_str(",1,0,maybe\n");
        std::fs::write(&path, &text).unwrap();
        let e = ComputeRecord::read(tmp.path()).unwrap_err().to_string();
        assert!(e.contains(":4:") && e.contains("maybe"), "{e}");
        // Written whole, it reads back the same.
        record.write(tmp.path()).unwrap();
        assert_eq!(ComputeRecord::read(tmp.path()).unwrap(), record);
    }
}
