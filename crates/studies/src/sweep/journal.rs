//! The journal: a sweep folder's resumable state, and the rows of `results.csv`.
//!
//! A sweep folder holds `sweep.toml` (the resolved definition, [`SweepDefinition::to_toml`])
//! and `journal.csv`: a first line `# tumble sweep journal v1, shard K/N, definition
//! fnv1a64:HEX`, the CSV header of `results.csv`, then one row per finished point in the
//! order points finished. Rows are appended and flushed every 16 rows or 2 s; a process
//! killed mid-write leaves at most a torn last line (no final newline), which reading drops and
//! the next run truncates before appending. `results.csv` is the header and the rows sorted by
//! index, so it depends only on the points' results.
//!
//! Every number is written in its shortest form that reads back to the same `f64` (ryu,
//! through the `csv` crate, as `tumble simulate` writes trajectories); counts as integers;
//! undefined values (a threshold never crossed, the metrics of a failed point) as empty
//! fields. A reason is one line (line breaks become spaces).

use std::collections::BTreeMap;
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use tumble_output::table::{Column, Table, Values};

use super::definition::SweepDefinition;
use super::{Shard, SweepError};

/// How a point ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Status {
    /// Integrated over the whole horizon; every metric computed.
    Ok,
    /// A typed error (invalid parameters, non-convergence, a non-finite state).
    Failed,
    /// The point's code panicked; the panic's message is the reason.
    Panicked,
}

impl Status {
    /// As written in `results.csv`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Failed => "failed",
            Status::Panicked => "panicked",
        }
    }

    fn from_name(s: &str) -> Option<Status> {
        [Status::Ok, Status::Failed, Status::Panicked]
            .into_iter()
            .find(|st| st.name() == s)
    }
}

/// One point's row.
#[derive(Debug, Clone, PartialEq)]
pub struct PointRow {
    /// Index in the sweep (`0 … points − 1`).
    pub index: u64,
    /// The axis values.
    pub values: Vec<f64>,
    /// The metrics, in the definition's order (`None`: undefined or failed).
    pub metrics: Vec<Option<f64>>,
    /// How it ended.
    pub status: Status,
    /// Why it failed (empty when ok).
    pub reason: String,
}

/// The journal in a sweep folder.
pub const JOURNAL: &str = "journal.csv";
/// The resolved definition in a sweep folder.
pub const DEFINITION: &str = "sweep.toml";
/// The results in a sweep folder (written by the caller when the sweep is complete).
pub const RESULTS: &str = "results.csv";

/// FNV-1a (64 bit) of `bytes`: a stable fingerprint of the definition text.
#[must_use]
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// The journal's first line.
fn first_line(shard: Shard, definition: &str) -> String {
    format!(
        "# tumble sweep journal v1, shard {}/{}, definition fnv1a64:{:016x}",
        shard.index,
        shard.count,
        fnv1a64(definition.as_bytes())
    )
}

/// Parses the journal's first line: the shard and the fingerprint.
fn parse_first_line(line: &str) -> Option<(Shard, u64)> {
    let rest = line.strip_prefix("# tumble sweep journal v1, shard ")?;
    let (shard, rest) = rest.split_once(", definition fnv1a64:")?;
    let (k, n) = shard.split_once('/')?;
    let shard = Shard::new(k.parse().ok()?, n.parse().ok()?).ok()?;
    Some((shard, u64::from_str_radix(rest.trim_end(), 16).ok()?))
}

/// The shard a journal was written for, from its first line; `None` when there is no
/// journal at `path`.
///
/// # Errors
/// [`SweepError::Io`] when it cannot be read, [`SweepError::Journal`] when its first line is
/// not a journal's.
pub fn shard_of(path: &Path) -> Result<Option<Shard>, SweepError> {
    use std::io::BufRead;
    let file = match File::open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(source) => {
            return Err(SweepError::Io {
                path: path.to_path_buf(),
                what: "cannot read the journal",
                source,
            });
        }
    };
    let mut first = String::new();
    std::io::BufReader::new(file.take(4096))
        .read_line(&mut first)
        .map_err(|source| SweepError::Io {
            path: path.to_path_buf(),
            what: "cannot read the journal",
            source,
        })?;
    parse_first_line(first.trim_end())
        .map(|(shard, _)| Some(shard))
        .ok_or_else(|| SweepError::Journal {
            path: path.to_path_buf(),
            line: 1,
            reason: "not a tumble sweep journal's first line".into(),
        })
}

/// One field of a row: the `csv` crate writes floats in their shortest round-trip form (ryu),
/// as `tumble simulate` writes trajectories.
#[derive(serde::Serialize)]
#[serde(untagged)]
enum Field<'a> {
    Whole(u64),
    Signed(i64),
    Float(f64),
    Text(&'a str),
}

/// Writes a row as one CSV record.
fn write_row<W: Write>(
    w: &mut csv::Writer<W>,
    def: &SweepDefinition,
    row: &PointRow,
) -> Result<(), SweepError> {
    let reason = row.reason.replace(['\r', '\n'], " ");
    let mut out = Vec::with_capacity(4 + row.values.len() + row.metrics.len());
    out.push(Field::Whole(row.index));
    if let Some(level) = def.level(row.index) {
        out.push(Field::Whole(u64::from(level)));
    }
    out.extend(row.values.iter().map(|&v| Field::Float(v)));
    for (m, v) in def.metrics.iter().zip(&row.metrics) {
        out.push(match v {
            None => Field::Text(""),
            Some(x) if m.is_count() && x.fract() == 0.0 && x.abs() < 2f64.powi(53) => {
                Field::Signed(*x as i64)
            }
            Some(x) => Field::Float(*x),
        });
    }
    out.push(Field::Text(row.status.name()));
    out.push(Field::Text(&reason));
    w.serialize(&out)
        .map_err(|e| SweepError::Csv(e.to_string()))
}

/// `results.csv`: the header and `rows` (which must be in index order), as bytes.
///
/// # Errors
/// Never in practice (writing to memory); kept for the CSV writer's signature.
pub fn results_csv(def: &SweepDefinition, rows: &[PointRow]) -> Result<Vec<u8>, SweepError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let csv_error = |e: csv::Error| SweepError::Csv(e.to_string());
    w.write_record(def.columns()).map_err(csv_error)?;
    for row in rows {
        write_row(&mut w, def, row)?;
    }
    w.into_inner().map_err(|e| SweepError::Csv(e.to_string()))
}

/// `results.csv` as a typed table, column for column: `index` and `level` as integers, the
/// axes as numbers, the metrics as numbers that are null where undefined, `status` and
/// `reason` (line breaks as spaces) as text. `metadata` goes into the file's footer.
#[must_use]
pub fn results_table(
    def: &SweepDefinition,
    rows: &[PointRow],
    metadata: Vec<(String, String)>,
) -> Table {
    let whole = |x: u64| i64::try_from(x).unwrap_or(i64::MAX);
    let mut values: Vec<Values> = vec![Values::I64(rows.iter().map(|r| whole(r.index)).collect())];
    if def.refine.is_some() {
        let level = |r: &PointRow| def.level(r.index).map_or(-1, i64::from);
        values.push(Values::I64(rows.iter().map(level).collect()));
    }
    for k in 0..def.axes.len() {
        values.push(Values::F64(rows.iter().map(|r| r.values[k]).collect()));
    }
    for k in 0..def.metrics.len() {
        values.push(Values::OptionalF64(
            rows.iter().map(|r| r.metrics[k]).collect(),
        ));
    }
    values.push(Values::Text(
        rows.iter().map(|r| r.status.name().to_string()).collect(),
    ));
    values.push(Values::Text(
        rows.iter()
            .map(|r| r.reason.replace(['\r', '\n'], " "))
            .collect(),
    ));
    Table {
        columns: def
            .columns()
            .into_iter()
            .zip(values)
            .map(|(name, values)| Column { name, values })
            .collect(),
        metadata,
    }
}

/// The rows of a `results.csv` text, checked against the definition (the header, every
/// field, the axis values of every index).
///
/// # Errors
/// The 1-based line and what is wrong with it.
pub(crate) fn parse_results(
    def: &SweepDefinition,
    text: &str,
) -> Result<Vec<PointRow>, (usize, String)> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| (1, e.to_string()))?
        .iter()
        .map(str::to_string)
        .collect();
    if header != def.columns() {
        return Err((
            1,
            format!(
                "the header is [{}], the sweep's columns are [{}]",
                header.join(","),
                def.columns().join(",")
            ),
        ));
    }
    let mut rows = Vec::new();
    for (k, record) in reader.records().enumerate() {
        let line = k + 2;
        let record = record.map_err(|e| (line, e.to_string()))?;
        rows.push(parse_row(def, &record).map_err(|reason| (line, reason))?);
    }
    Ok(rows)
}

/// Parses one journal record into a row, checking it against the definition.
fn parse_row(def: &SweepDefinition, record: &csv::StringRecord) -> Result<PointRow, String> {
    let n_axes = def.axes.len();
    let n_metrics = def.metrics.len();
    // A refined sweep's rows carry the point's level after its index.
    let first = 1 + usize::from(def.refine.is_some());
    if record.len() != first + 2 + n_axes + n_metrics {
        return Err(format!(
            "{} fields, the header has {}",
            record.len(),
            first + 2 + n_axes + n_metrics
        ));
    }
    let index: u64 = record[0]
        .parse()
        .map_err(|_| format!("index `{}` is not a whole number", &record[0]))?;
    if index >= def.points() {
        return Err(format!(
            "index {index} is beyond the sweep's {} points",
            def.points()
        ));
    }
    if let Some(level) = def.level(index)
        && record[1] != level.to_string()
    {
        return Err(format!(
            "the level of point {index} is `{}`, the refinement gives {level}",
            &record[1]
        ));
    }
    let number = |s: &str| {
        s.parse::<f64>()
            .map_err(|_| format!("`{s}` is not a number"))
    };
    let values = (0..n_axes)
        .map(|j| number(&record[first + j]))
        .collect::<Result<Vec<_>, _>>()?;
    // The axis values are those of the index: a journal of another sweep is caught here too.
    let expected = def.point(index);
    if values
        .iter()
        .zip(&expected)
        .any(|(a, b)| a.to_bits() != b.to_bits())
    {
        return Err(format!(
            "the axis values of point {index} are {values:?}, the definition gives {expected:?}"
        ));
    }
    let metrics = (0..n_metrics)
        .map(|j| {
            let s = &record[first + n_axes + j];
            if s.is_empty() {
                Ok(None)
            } else {
                number(s).map(Some)
            }
        })
        .collect::<Result<Vec<_>, _>>()?;
    let status = Status::from_name(&record[first + n_axes + n_metrics]).ok_or_else(|| {
        format!(
            "status `{}` is none of ok, failed, panicked",
            &record[first + n_axes + n_metrics]
        )
    })?;
    Ok(PointRow {
        index,
        values,
        metrics,
        status,
        reason: record[first + 1 + n_axes + n_metrics].to_string(),
    })
}

/// What a journal holds.
pub(crate) struct Contents {
    /// The shard it belongs to.
    pub shard: Shard,
    /// The rows of finished points, by index.
    pub rows: BTreeMap<u64, PointRow>,
    /// Length in bytes of its complete lines (a torn last line is beyond).
    pub complete_len: u64,
}

/// Reads the journal at `path` written for `def` (whose resolved text is `definition`).
pub(crate) fn read(
    path: &Path,
    def: &SweepDefinition,
    definition: &str,
) -> Result<Contents, SweepError> {
    let mut bytes = Vec::new();
    File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .map_err(|source| SweepError::Io {
            path: path.to_path_buf(),
            what: "cannot read the journal",
            source,
        })?;
    let complete_len = bytes.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    let text = std::str::from_utf8(&bytes[..complete_len]).map_err(|_| SweepError::Journal {
        path: path.to_path_buf(),
        line: 0,
        reason: "not UTF-8 text".into(),
    })?;
    let corrupt = |line: usize, reason: String| SweepError::Journal {
        path: path.to_path_buf(),
        line,
        reason,
    };
    let Some((first, rest)) = text.split_once('\n') else {
        return Err(corrupt(1, "empty or without its first line".into()));
    };
    let (shard, fingerprint) = parse_first_line(first).ok_or_else(|| {
        corrupt(
            1,
            format!("`{first}` is not a tumble sweep journal's first line"),
        )
    })?;
    if fingerprint != fnv1a64(definition.as_bytes()) {
        return Err(SweepError::DifferentSweep {
            dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
            reason: format!(
                "its journal was written for another definition (fingerprint {fingerprint:016x}, \
                 this sweep's is {:016x})",
                fnv1a64(definition.as_bytes())
            ),
        });
    }
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(rest.as_bytes());
    let mut records = reader.records();
    let header = match records.next() {
        Some(Ok(h)) => h,
        Some(Err(e)) => return Err(corrupt(2, e.to_string())),
        None => return Err(corrupt(2, "no header line".into())),
    };
    if header.iter().ne(def.columns().iter().map(String::as_str)) {
        return Err(corrupt(
            2,
            format!(
                "header `{}` is not this sweep's `{}`",
                header.iter().collect::<Vec<_>>().join(","),
                def.columns().join(",")
            ),
        ));
    }
    let mut rows: BTreeMap<u64, PointRow> = BTreeMap::new();
    for (k, record) in records.enumerate() {
        let line = k + 3;
        let record = record.map_err(|e| corrupt(line, e.to_string()))?;
        let row = parse_row(def, &record).map_err(|reason| corrupt(line, reason))?;
        // A refined sweep's shard owns coarse cells, not indices: the points on a face between
        // two shards' cells belong to both.
        if def.refine.is_none() && !shard.contains(row.index) {
            return Err(corrupt(
                line,
                format!("point {} is not in shard {shard}", row.index),
            ));
        }
        match rows.get(&row.index) {
            Some(previous) if *previous != row => {
                return Err(corrupt(
                    line,
                    format!("point {} appears twice with different results", row.index),
                ));
            }
            _ => {
                rows.insert(row.index, row);
            }
        }
    }
    Ok(Contents {
        shard,
        rows,
        complete_len: complete_len as u64,
    })
}

/// Appends rows to a journal, flushing every [`Writer::CHUNK`] rows or [`Writer::PERIOD`],
/// whichever comes first.
pub(crate) struct Writer {
    path: PathBuf,
    out: BufWriter<File>,
    unflushed: usize,
    flushed_at: Instant,
}

impl Writer {
    /// Rows between flushes.
    pub const CHUNK: usize = 16;
    /// Longest time rows stay unflushed (slow points: little work lost to a kill).
    pub const PERIOD: Duration = Duration::from_secs(2);

    /// Creates a journal (which must not exist) with its first line and header.
    pub(crate) fn create(
        path: &Path,
        def: &SweepDefinition,
        definition: &str,
        shard: Shard,
    ) -> Result<Self, SweepError> {
        let io = |source| SweepError::Io {
            path: path.to_path_buf(),
            what: "cannot create the journal",
            source,
        };
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(path)
            .map_err(io)?;
        let mut w = Writer {
            path: path.to_path_buf(),
            out: BufWriter::new(file),
            unflushed: 0,
            flushed_at: Instant::now(),
        };
        let mut head = csv::Writer::from_writer(Vec::new());
        head.write_record(def.columns())
            .map_err(|e| SweepError::Csv(e.to_string()))?;
        let head = head
            .into_inner()
            .map_err(|e| SweepError::Csv(e.to_string()))?;
        writeln!(w.out, "{}", first_line(shard, definition)).map_err(io)?;
        w.out.write_all(&head).map_err(io)?;
        w.flush()?;
        Ok(w)
    }

    /// Opens an existing journal for appending after its `complete_len` bytes of complete
    /// lines (dropping a torn last line).
    pub(crate) fn append(path: &Path, complete_len: u64) -> Result<Self, SweepError> {
        let io = |source| SweepError::Io {
            path: path.to_path_buf(),
            what: "cannot reopen the journal",
            source,
        };
        let mut file = OpenOptions::new().write(true).open(path).map_err(io)?;
        file.set_len(complete_len).map_err(io)?;
        file.seek(SeekFrom::End(0)).map_err(io)?;
        Ok(Writer {
            path: path.to_path_buf(),
            out: BufWriter::new(file),
            unflushed: 0,
            flushed_at: Instant::now(),
        })
    }

    /// Appends a row; flushes at the end of a chunk.
    pub(crate) fn push(&mut self, def: &SweepDefinition, row: &PointRow) -> Result<(), SweepError> {
        let mut line = csv::Writer::from_writer(Vec::new());
        write_row(&mut line, def, row)?;
        let line = line
            .into_inner()
            .map_err(|e| SweepError::Csv(e.to_string()))?;
        self.out.write_all(&line).map_err(|source| SweepError::Io {
            path: self.path.clone(),
            what: "cannot append to the journal",
            source,
        })?;
        self.unflushed += 1;
        if self.unflushed >= Self::CHUNK || self.flushed_at.elapsed() >= Self::PERIOD {
            self.flush()?;
        }
        Ok(())
    }

    /// Writes everything buffered to the file.
    pub(crate) fn flush(&mut self) -> Result<(), SweepError> {
        self.unflushed = 0;
        self.flushed_at = Instant::now();
        self.out.flush().map_err(|source| SweepError::Io {
            path: self.path.clone(),
            what: "cannot write the journal",
            source,
        })
    }
}
