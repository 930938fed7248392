//! The folder lock: one command at a time writes into an output folder ([`FolderLock`]).

use std::fs::OpenOptions;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use crate::abort;

/// An exclusive lock on an output folder, held while a command writes into it: a second
/// command on the same folder (a requeued cluster job whose first run is still alive, a second
/// terminal) is refused with the holder's pid, host and start time instead of interleaving its
/// writes. The lock is the file `.tumble.lock` in the folder, created exclusively and removed
/// when the lock is dropped. A lock left by a process that no longer runs on this host (killed
/// with `kill -9`) is stale and taken over; `break_lock` takes over any lock.
#[derive(Debug)]
pub struct FolderLock {
    path: PathBuf,
}

/// The lock file's name.
pub const LOCK_FILE: &str = ".tumble.lock";

/// Why a folder could not be locked.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LockError {
    /// Another process holds the lock.
    #[error(
        "{}: in use by tumble process {pid} on {host} since {since} ({command}); wait for it to \
         finish, or pass --break-lock if it is gone",
        dir.display()
    )]
    Held {
        /// The folder.
        dir: PathBuf,
        /// The holder's pid.
        pid: u32,
        /// The holder's host.
        host: String,
        /// When it took the lock.
        since: String,
        /// What it runs.
        command: String,
    },
    /// The lock file could not be created, read or removed.
    #[error("{}: cannot lock the folder: {source}", dir.display())]
    Io {
        /// The folder.
        dir: PathBuf,
        /// The I/O error.
        #[source]
        source: io::Error,
    },
}

/// This machine's host name (Linux: `/proc/sys/kernel/hostname`).
#[must_use]
pub fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| "unknown".to_string())
}

impl FolderLock {
    /// Locks the existing folder `dir` for this process; `since` and `command` describe it to a
    /// process that finds the folder locked.
    ///
    /// # Errors
    /// [`LockError::Held`] when a live process holds it (and `break_lock` is false);
    /// [`LockError::Io`] when the lock file cannot be written.
    pub fn acquire(
        dir: &Path,
        since: &str,
        command: &str,
        break_lock: bool,
    ) -> Result<Self, LockError> {
        let path = dir.join(LOCK_FILE);
        let io = |source| LockError::Io {
            dir: dir.to_path_buf(),
            source,
        };
        let me = std::process::id();
        let host = host_name();
        for _ in 0..3 {
            match OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut file) => {
                    let record = format!("{me}\n{host}\n{since}\n{command}\n");
                    file.write_all(record.as_bytes())
                        .and_then(|()| file.sync_all())
                        .map_err(|e| {
                            let _ = std::fs::remove_file(&path);
                            io(e)
                        })?;
                    abort::register(&path);
                    return Ok(Self { path });
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {
                    let text = std::fs::read_to_string(&path).unwrap_or_default();
                    let mut lines = text.lines();
                    let pid: u32 = lines.next().and_then(|p| p.parse().ok()).unwrap_or(0);
                    let holder_host = lines.next().unwrap_or("").to_string();
                    let held_since = lines.next().unwrap_or("").to_string();
                    let held_command = lines.next().unwrap_or("").to_string();
                    // A holder on this host that no longer runs left a stale lock; so did one
                    // that died between creating the file and writing it (empty for over 10 s).
                    let stale = (holder_host == host
                        && pid != 0
                        && !Path::new(&format!("/proc/{pid}")).exists())
                        || (text.is_empty()
                            && std::fs::metadata(&path)
                                .and_then(|m| m.modified())
                                .ok()
                                .and_then(|t| t.elapsed().ok())
                                .is_some_and(|age| age.as_secs() > 10));
                    if stale || break_lock {
                        match std::fs::remove_file(&path) {
                            Ok(()) => continue,
                            Err(e) if e.kind() == io::ErrorKind::NotFound => continue,
                            Err(e) => return Err(io(e)),
                        }
                    }
                    return Err(LockError::Held {
                        dir: dir.to_path_buf(),
                        pid,
                        host: holder_host,
                        since: held_since,
                        command: held_command,
                    });
                }
                Err(e) => return Err(io(e)),
            }
        }
        Err(io(io::Error::other(
            "the lock file keeps reappearing (another process is taking it)",
        )))
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
        abort::forget(&self.path);
    }
}
