//! Tables as Apache Parquet files: typed columns and key-value metadata.
//!
//! A [`Table`] is a list of named, equally long columns — `f64` (`DOUBLE`), `f64` that may be
//! undefined (`DOUBLE`, optional: written as null), `i64` (`INT64`) or text (`BYTE_ARRAY`
//! annotated `STRING`) — with string key-value pairs that go into the file's footer (the
//! metadata a JSON sidecar or manifest holds). [`Table::to_parquet`] encodes it as one row
//! group, uncompressed, in the bytes a [`crate::Destination`] then writes whole; values are
//! stored bit for bit, so a reader gets the same `f64`s the run computed.
//!
//! [`Table::kind`] tells CSV from Parquet by a path's extension, the way `--format` defaults.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use parquet::basic::{LogicalType, Repetition, Type as Physical};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::errors::ParquetError;
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;

/// A table that cannot be encoded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TableError {
    /// Columns of different lengths.
    #[error("column `{name}` has {len} values, the table's first column {expected}")]
    Ragged {
        /// The column.
        name: String,
        /// Its length.
        len: usize,
        /// The first column's length.
        expected: usize,
    },
    /// The Parquet encoder refused the table.
    #[error("cannot encode the table as Parquet: {0}")]
    Parquet(#[from] ParquetError),
}

/// The values of one column.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// Numbers, all defined.
    F64(Vec<f64>),
    /// Numbers, `None` where undefined (written as null).
    OptionalF64(Vec<Option<f64>>),
    /// Whole numbers (indices, counts).
    I64(Vec<i64>),
    /// Text.
    Text(Vec<String>),
}

impl Values {
    fn len(&self) -> usize {
        match self {
            Values::F64(v) => v.len(),
            Values::OptionalF64(v) => v.len(),
            Values::I64(v) => v.len(),
            Values::Text(v) => v.len(),
        }
    }
}

/// A named column.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// The column's name.
    pub name: String,
    /// Its values.
    pub values: Values,
}

/// Named columns of equal length and the file's key-value metadata.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    /// The columns, in order.
    pub columns: Vec<Column>,
    /// Key-value pairs for the file's footer.
    pub metadata: Vec<(String, String)>,
}

/// The file formats a table is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values with a header (shortest round-trip numbers).
    Csv,
    /// Apache Parquet.
    Parquet,
}

impl Format {
    /// The format a path's extension names: Parquet for `.parquet` (any case), else CSV.
    #[must_use]
    pub fn of_path(path: &Path) -> Format {
        if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("parquet"))
        {
            Format::Parquet
        } else {
            Format::Csv
        }
    }

    /// Parses `csv` or `parquet`.
    #[must_use]
    pub fn parse(name: &str) -> Option<Format> {
        match name.trim().to_ascii_lowercase().as_str() {
            "csv" => Some(Format::Csv),
            "parquet" => Some(Format::Parquet),
            _ => None,
        }
    }
}

impl Table {
    /// The Parquet file holding the table: its schema (one field per column, typed), one row
    /// group, its metadata in the footer.
    ///
    /// # Errors
    /// [`TableError::Ragged`] if the columns differ in length; [`TableError::Parquet`] if the
    /// encoder fails.
    pub fn to_parquet(&self) -> Result<Vec<u8>, TableError> {
        let rows = self.columns.first().map_or(0, |c| c.values.len());
        for c in &self.columns {
            if c.values.len() != rows {
                return Err(TableError::Ragged {
                    name: c.name.clone(),
                    len: c.values.len(),
                    expected: rows,
                });
            }
        }
        let fields = self
            .columns
            .iter()
            .map(|c| field(c).map(Arc::new))
            .collect::<Result<Vec<_>, _>>()?;
        let schema = Arc::new(
            Type::group_type_builder("schema")
                .with_fields(fields)
                .build()?,
        );
        let metadata = (!self.metadata.is_empty()).then(|| {
            self.metadata
                .iter()
                .map(|(k, v)| KeyValue::new(k.clone(), v.clone()))
                .collect()
        });
        let properties = WriterProperties::builder()
            .set_created_by(format!("tumble {}", env!("CARGO_PKG_VERSION")))
            .set_key_value_metadata(metadata)
            .build();
        let mut writer = SerializedFileWriter::new(Vec::new(), schema, Arc::new(properties))?;
        let mut group = writer.next_row_group()?;
        let mut columns = self.columns.iter();
        while let Some(mut out) = group.next_column()? {
            let Some(column) = columns.next() else {
                break;
            };
            match &column.values {
                Values::F64(v) => {
                    out.typed::<DoubleType>().write_batch(v, None, None)?;
                }
                Values::OptionalF64(v) => {
                    let defined: Vec<f64> = v.iter().flatten().copied().collect();
                    let levels: Vec<i16> = v.iter().map(|x| i16::from(x.is_some())).collect();
                    out.typed::<DoubleType>()
                        .write_batch(&defined, Some(&levels), None)?;
                }
                Values::I64(v) => {
                    out.typed::<Int64Type>().write_batch(v, None, None)?;
                }
                Values::Text(v) => {
                    let bytes: Vec<ByteArray> =
                        v.iter().map(|s| ByteArray::from(s.as_str())).collect();
                    out.typed::<ByteArrayType>()
                        .write_batch(&bytes, None, None)?;
                }
            }
            out.close()?;
        }
        group.close()?;
        Ok(writer.into_inner()?)
    }
}

/// The schema field of a column.
fn field(c: &Column) -> Result<Type, ParquetError> {
    let (physical, repetition, logical) = match c.values {
        Values::F64(_) => (Physical::DOUBLE, Repetition::REQUIRED, None),
        Values::OptionalF64(_) => (Physical::DOUBLE, Repetition::OPTIONAL, None),
        // A plain INT64 is a signed 64-bit integer to every reader.
        Values::I64(_) => (Physical::INT64, Repetition::REQUIRED, None),
        Values::Text(_) => (
            Physical::BYTE_ARRAY,
            Repetition::REQUIRED,
            Some(LogicalType::String),
        ),
    };
    Type::primitive_type_builder(&c.name, physical)
        .with_repetition(repetition)
        .with_logical_type(logical)
        .build()
}

/// The provenance record written beside a run's table `target`: `target` with `.json`
/// appended when it has an extension (`run.csv` → `run.csv.json`), and with the format's
/// extension and `.json` when it has none (`results` → `results.csv.json`), so that the record
/// is never a plain `NAME.json` a user may keep for something else.
#[must_use]
pub fn provenance_path(target: &Path, format: Format) -> PathBuf {
    let mut name = target.as_os_str().to_owned();
    if target.extension().is_none() {
        name.push(match format {
            Format::Csv => ".csv",
            Format::Parquet => ".parquet",
        });
    }
    name.push(".json");
    PathBuf::from(name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    /// The provenance record's name is never a bare `NAME.json`.
    #[test]
    fn provenance_names_keep_the_table_extension() {
        let p = |t: &str, f| provenance_path(Path::new(t), f);
        assert_eq!(p("run.csv", Format::Csv), PathBuf::from("run.csv.json"));
        assert_eq!(
            p("out/results", Format::Csv),
            PathBuf::from("out/results.csv.json")
        );
        assert_eq!(
            p("results", Format::Parquet),
            PathBuf::from("results.parquet.json")
        );
        assert_eq!(p("data.txt", Format::Csv), PathBuf::from("data.txt.json"));
    }
}
