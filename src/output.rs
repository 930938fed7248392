//! Output files: every path the command line writes goes through a
//! [`tumble_output::Destination`] — regular files appear whole or not at all, character
//! devices and FIFOs are streamed to, anything else is refused before any work.

use std::path::Path;

use anyhow::Result;
pub use tumble_output::table::provenance_path;
pub use tumble_output::{Destination, Mode};

/// Whether `dest` is a regular file that exists now (so that writing it replaces it; the
/// summary says so).
#[must_use]
pub fn replaces(dest: &Destination) -> bool {
    matches!(dest.mode(), Mode::Atomic { target } if target.is_file())
}

/// Checks, before any work, that every path in `paths` can be written, and that no two of them
/// name the same file (after following links). `paths` pairs each path with the flag or role
/// that named it, for messages.
///
/// # Errors
/// The first path that cannot be written, or two roles writing one file.
pub fn check_all<'a>(
    paths: impl IntoIterator<Item = (&'a str, &'a Path)>,
) -> Result<Vec<Destination>> {
    let mut seen: Vec<(&str, Destination)> = Vec::new();
    for (role, path) in paths {
        let dest = Destination::check(path).map_err(|e| anyhow::anyhow!("{role} {e}"))?;
        if matches!(dest.mode(), Mode::Atomic { .. })
            && let Some((other, _)) = seen.iter().find(|(_, d)| d.file() == dest.file())
        {
            anyhow::bail!(
                "{role} {}: the same file as {other}; give them different paths",
                path.display()
            );
        }
        seen.push((role, dest));
    }
    Ok(seen.into_iter().map(|(_, d)| d).collect())
}

/// Refuses an output that would replace an input file being read (`-o` naming the scene file).
///
/// # Errors
/// If `dest` is a regular-file target that is `input` (after following links).
pub fn refuse_input(role: &str, dest: &Destination, input: &Path, what: &str) -> Result<()> {
    if let (Mode::Atomic { target }, Ok(input_file)) = (dest.mode(), std::fs::canonicalize(input))
        && std::fs::canonicalize(target).unwrap_or_else(|_| target.clone()) == input_file
    {
        anyhow::bail!(
            "{role} {}: the same file as {what} {}; give the output another path",
            dest.path().display(),
            input.display()
        );
    }
    Ok(())
}

/// Writes `bytes` to `path` whole or not at all (streamed if `path` is a device or FIFO).
///
/// # Errors
/// If `path` cannot be written.
pub fn write_whole(path: &Path, bytes: &[u8]) -> Result<()> {
    Destination::check(path)?.write_all(bytes)?;
    Ok(())
}

/// Checks, before any work, the files a command will write into the folder `dir`: `dir` is a
/// directory or does not exist yet, and each of `names` in it can be written (a directory or a
/// socket where a result goes is refused now, not after the run).
///
/// # Errors
/// `dir` exists and is not a directory, or one of the files cannot be written.
pub fn check_folder(dir: &Path, names: &[String]) -> Result<()> {
    if dir.exists() && !dir.is_dir() {
        anyhow::bail!(
            "{}: is not a directory; give the output folder's path",
            dir.display()
        );
    }
    if dir.is_dir() {
        for name in names {
            Destination::check(&dir.join(name))?;
        }
    }
    Ok(())
}

/// Creates the output folder `dir` if needed, locks it for this process (see
/// [`tumble_output::FolderLock`]) and removes the temporary files a killed run left in it; the
/// lock is released when the returned guard is dropped.
///
/// # Errors
/// The folder cannot be created, or another live tumble process holds it.
pub fn lock_folder(dir: &Path, break_lock: bool) -> Result<FolderGuard> {
    let created = !dir.exists();
    std::fs::create_dir_all(dir)
        .map_err(|e| anyhow::anyhow!("{}: cannot create the output folder: {e}", dir.display()))?;
    let since = humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string();
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let lock = FolderGuard {
        lock: Some(tumble_output::FolderLock::acquire(
            dir, &since, &command, break_lock,
        )?),
        created: created.then(|| dir.to_path_buf()),
    };
    // Nobody else writes here now: temporary files are what a killed run left.
    let removed = tumble_output::remove_stale_temp_files(dir).map_err(|e| {
        anyhow::anyhow!(
            "{}: cannot remove the temporary files an interrupted run left: {e}",
            dir.display()
        )
    })?;
    for path in removed {
        eprintln!(
            "removed {} (a temporary file an interrupted run left)",
            path.display()
        );
    }
    Ok(lock)
}

/// A locked output folder: the lock is released when dropped, and a folder this process created
/// is removed again if the command left it empty (it failed before writing anything).
#[derive(Debug)]
pub struct FolderGuard {
    lock: Option<tumble_output::FolderLock>,
    created: Option<std::path::PathBuf>,
}

impl Drop for FolderGuard {
    fn drop(&mut self) {
        drop(self.lock.take());
        if let Some(dir) = &self.created {
            // Fails, as it should, unless the folder is empty.
            let _ = std::fs::remove_dir(dir);
        }
    }
}
