//! What an abrupt end removes: the paths of this process's temporary files and folder locks,
//! so that a command stopped by a second signal (which does not wait for the run to reach a
//! step boundary) still leaves no hidden temporary file and no lock behind.
//!
//! [`crate::Destination`]'s temporary files and [`crate::FolderLock`]'s lock file register
//! here when they are made; [`remove_all`] deletes every registered path that still exists.
//! A temporary file that was renamed over its target no longer exists under its temporary
//! name, and a dropped lock has removed its file, so removing what is registered never touches
//! a finished output. Entries whose file is gone are pruned as the list grows.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The registered paths.
static PATHS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Above this many entries, registering first drops those whose file no longer exists.
const PRUNE_ABOVE: usize = 256;

/// Registers `path` for removal by [`remove_all`].
pub fn register(path: &Path) {
    let Ok(mut paths) = PATHS.lock() else { return };
    if paths.len() >= PRUNE_ABOVE {
        paths.retain(|p| p.symlink_metadata().is_ok());
    }
    paths.push(path.to_path_buf());
}

/// Forgets `path` (a lock released normally).
pub fn forget(path: &Path) {
    if let Ok(mut paths) = PATHS.lock() {
        paths.retain(|p| p != path);
    }
}

/// Removes every registered path that still exists and returns those it removed. Called on
/// an abrupt end (a second signal), from a normal thread.
pub fn remove_all() -> Vec<PathBuf> {
    let paths = match PATHS.lock() {
        Ok(mut paths) => std::mem::take(&mut *paths),
        Err(poisoned) => std::mem::take(&mut *poisoned.into_inner()),
    };
    paths
        .into_iter()
        .filter(|p| std::fs::remove_file(p).is_ok())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Registered files that still exist are removed; files renamed away (a temporary file
    /// persisted over its target) and forgotten ones are left alone.
    #[test]
    fn remove_all_deletes_what_is_left_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let left = dir.path().join(".left.tmp");
        let renamed = dir.path().join(".renamed.tmp");
        let target = dir.path().join("target.csv");
        let lock = dir.path().join(".tumble.lock");
        for p in [&left, &renamed, &lock] {
            std::fs::write(p, b"x").unwrap();
            register(p);
        }
        std::fs::rename(&renamed, &target).unwrap();
        forget(&lock);
        let removed = remove_all();
        assert!(removed.contains(&left));
        assert!(!left.exists());
        assert!(target.exists());
        assert!(lock.exists());
        assert!(!removed.contains(&lock));
    }
}
