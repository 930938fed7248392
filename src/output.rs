//! Output files that appear whole or not at all.
//!
//! Every file the command line writes (CSV, plots) is first written to a temporary file in the
//! destination's own directory and renamed over the destination only once it is complete, so an
//! interrupted or failed run never leaves a truncated file that looks finished. A temporary file
//! that is not kept is removed when it is dropped (also on an early return with `?`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use tempfile::{Builder, NamedTempFile, TempPath};

/// The directory a path lives in (`.` for a bare file name).
#[must_use]
pub fn directory_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// A new, empty temporary file beside `path` (same directory, so the final rename is atomic),
/// named `.NAME.XXXXXX.tmp.EXT` with `path`'s extension, created with the usual permissions
/// (`0666` less the umask, as a plain create would; tempfile's default is `0600`).
///
/// # Errors
/// If the directory does not exist or is not writable.
pub fn temp_file_beside(path: &Path) -> Result<NamedTempFile> {
    let dir = directory_of(path);
    if !dir.is_dir() {
        bail!(
            "{}: the directory {} does not exist",
            path.display(),
            dir.display()
        );
    }
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    let suffix = match path.extension() {
        Some(ext) => format!(".tmp.{}", ext.to_string_lossy()),
        None => ".tmp".to_string(),
    };
    let prefix = format!(".{name}.");
    let mut builder = Builder::new();
    builder.prefix(&prefix).suffix(&suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder
        .tempfile_in(&dir)
        .with_context(|| format!("{}: cannot create a file beside it", path.display()))
}

/// A temporary path beside `path`, for writers that open the file themselves (the plot
/// backends); see [`temp_file_beside`].
///
/// # Errors
/// As [`temp_file_beside`].
pub fn temp_path_beside(path: &Path) -> Result<TempPath> {
    Ok(temp_file_beside(path)?.into_temp_path())
}

/// Renames a finished temporary file over `path`.
///
/// # Errors
/// If the rename fails; the temporary file is then removed.
pub fn commit(temp: TempPath, path: &Path) -> Result<()> {
    temp.persist(path)
        .map_err(|e| e.error)
        .with_context(|| format!("cannot write {}", path.display()))
}
