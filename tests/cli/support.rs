//! What every module of the binary's tests needs: the repository root, running `tumble` in a
//! folder, its stderr, a run that must succeed, a record read through its type, and a run
//! interrupted by a signal.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

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

/// The JSON record at `path`, read as its type `T` (so every reader of the type can read what
/// the command wrote) and returned as a JSON value: `T` must hold every key, as written.
pub fn record<T>(path: &Path) -> serde_json::Value
where
    T: serde::Serialize + serde::de::DeserializeOwned,
{
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let typed: T = serde_json::from_str(&text)
        .unwrap_or_else(|e| panic!("{} is not its record type: {e}", path.display()));
    let value: serde_json::Value = serde_json::from_str(&text).expect("a record is JSON");
    assert_eq!(
        serde_json::to_value(&typed).unwrap(),
        value,
        "{}: the record type does not hold every key as written",
        path.display()
    );
    value
}

/// Waits until `ready()`, failing after 60 s.
pub fn wait_for(what: &str, ready: impl Fn() -> bool) {
    let start = Instant::now();
    while !ready() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "timed out waiting for {what}"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// Sends signal `name` (`INT`, `TERM`, `KILL`) to process `pid`.
pub fn signal(pid: u32, name: &str) {
    let ok = Command::new("kill")
        .args([format!("-{name}"), pid.to_string()])
        .status()
        .expect("cannot run kill")
        .success();
    assert!(ok, "kill -{name} failed");
}

/// Starts `tumble args` in `dir` in the background (stdin and stdout null, stderr piped).
pub fn start(dir: &Path, args: &[&str]) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(dir)
        .args(args)
        .env("RUST_BACKTRACE", "0")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot run the tumble binary")
}

/// Starts `tumble args` in `dir`, waits for `ready`, sends `signal` and waits for the end;
/// (exit code, stderr).
pub fn interrupt(
    dir: &Path,
    args: &[&str],
    ready: impl Fn() -> bool,
    signal_name: &str,
) -> (Option<i32>, String) {
    let child = start(dir, args);
    wait_for("the run to start", ready);
    signal(child.id(), signal_name);
    let out = child.wait_with_output().expect("cannot wait for tumble");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Asserts that a run did not panic (no exit 101, no panic message or backtrace hint).
pub fn no_panic(code: Option<i32>, err: &str) {
    assert_ne!(code, Some(101), "{err}");
    assert!(
        !err.contains("panicked") && !err.contains("RUST_BACKTRACE"),
        "{err}"
    );
}
