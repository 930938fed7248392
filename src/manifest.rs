//! The text of the JSON records the commands write (a run's `FILE.csv.json`, the
//! `manifest.json` of sweep, work–precision and long-run folders). The records themselves are
//! `serde` types of `tumble-studies` (`record::RunRecord`, `sweep::record::SweepRecord`,
//! `work_precision::record::StudyRecord`, `hard_cases::record::AtlasRecord`) and `tumble-plot`
//! (`work_precision::LongManifest`, around the figure's `LongRecord`), read back by
//! `tumble plot` and Python.

use serde::Serialize;

/// Serializes a manifest as pretty JSON with a final newline.
///
/// # Errors
/// If serialization fails.
pub fn to_text(manifest: &impl Serialize) -> serde_json::Result<String> {
    let mut text = serde_json::to_string_pretty(manifest)?;
    text.push('\n');
    Ok(text)
}
