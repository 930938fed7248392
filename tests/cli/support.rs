//! What every module of the binary's tests needs: the repository root, running `tumble` in a
//! folder, its stderr, and a run that must succeed.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root (scene files, meshes).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `tumble` in `dir`.
pub fn tumble_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("cannot run the tumble binary")
}

/// A run's stderr as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs `tumble` in `dir` and asserts that it succeeded.
pub fn succeeds(dir: &Path, args: &[&str]) -> Output {
    let out = tumble_in(dir, args);
    assert!(out.status.success(), "{args:?} failed: {}", stderr(&out));
    out
}
