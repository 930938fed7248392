//! The recorder of `tumble simulate`: rows streamed as CSV and kept column by column when a
//! plot or a Parquet file needs them.

use std::io::{self, Write};

use anyhow::Result;
use tumble_integrators::Flow;
use tumble_scenarios::Recorder;

/// A writer that counts the bytes it passes on.
struct Counting<W> {
    inner: W,
    count: u64,
}

impl<W: Write> Write for Counting<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.count += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// Writes rows as CSV (unless the output is Parquet) and keeps them, column by column, when a
/// plot or a Parquet file needs them.
pub(super) struct CsvRecorder<W: Write> {
    csv: Option<csv::Writer<Counting<W>>>,
    /// The header, written with the first row (a run that fails before its first row, such as
    /// a model refused at t = 0, leaves a stream output empty).
    header: Option<Vec<String>>,
    keep: Option<Vec<Vec<f64>>>,
    error: Option<csv::Error>,
    /// Stdout was closed by the reader (`| head`): stop quietly.
    closed: bool,
    /// `--max-output` in bytes: the run stops once the output would pass it (a fixed-step run
    /// is refused before it starts when its estimate does; an adaptive run's rows are counted
    /// as they are written).
    limit: f64,
    /// Bytes of output so far: written CSV, or about 22 a value for kept rows alone.
    bytes: f64,
    /// The time of the row that passed the limit.
    pub(super) over_at: Option<f64>,
}

impl<W: Write> CsvRecorder<W> {
    pub(super) fn new(out: Option<W>, columns: &[String], keep: bool, limit: f64) -> Result<Self> {
        Ok(CsvRecorder {
            header: out.is_some().then(|| columns.to_vec()),
            csv: out.map(|inner| csv::Writer::from_writer(Counting { inner, count: 0 })),
            keep: keep.then(|| vec![Vec::new(); columns.len()]),
            error: None,
            closed: false,
            limit,
            bytes: 0.0,
            over_at: None,
        })
    }

    fn fail(&mut self, e: csv::Error) -> Flow {
        if matches!(e.kind(), csv::ErrorKind::Io(io) if io.kind() == io::ErrorKind::BrokenPipe) {
            self.closed = true;
        } else {
            self.error = Some(e);
        }
        Flow::Stop
    }

    /// Flushes; the kept columns and whether the reader closed the output early, or the first
    /// write error.
    pub(super) fn finish(mut self) -> Result<(Option<Vec<Vec<f64>>>, bool)> {
        if let Some(e) = self.error.take() {
            return Err(e.into());
        }
        // A run that wrote no row still gives a CSV with its header.
        if let (Some(csv), Some(header)) = (&mut self.csv, self.header.take()) {
            csv.write_record(&header)?;
        }
        if !self.closed
            && let Some(csv) = &mut self.csv
            && let Err(e) = csv.flush()
        {
            if e.kind() == io::ErrorKind::BrokenPipe {
                self.closed = true;
            } else {
                return Err(e.into());
            }
        }
        Ok((self.keep, self.closed))
    }
}

impl<W: Write> Recorder for CsvRecorder<W> {
    fn row(&mut self, values: &[f64]) -> Flow {
        // The output's size: the CSV bytes written so far (the writer's buffer aside), or 22
        // bytes a value when the rows are only kept.
        self.bytes = match &self.csv {
            Some(csv) => csv.get_ref().count as f64,
            None => self.bytes + 22.0 * values.len() as f64,
        };
        if self.bytes > self.limit {
            self.over_at = values.first().copied();
            return Flow::Stop;
        }
        if let Some(csv) = &mut self.csv {
            let written = match self.header.take() {
                Some(header) => csv.write_record(&header),
                None => Ok(()),
            };
            if let Err(e) = written.and_then(|()| csv.serialize(values)) {
                return self.fail(e);
            }
        }
        if let Some(keep) = &mut self.keep {
            for (column, &v) in keep.iter_mut().zip(values) {
                column.push(v);
            }
        }
        Flow::Continue
    }
}
