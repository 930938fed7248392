//! The hostile-input suite: tables of bad flags, scene files, sweep files, damaged journals,
//! broken meshes and signals. Each case runs `tumble` in a fresh folder holding the case's
//! files and asserts the exit status, that stderr names what is wrong, that nothing panicked
//! (no `panicked`, no `RUST_BACKTRACE`, never exit 101) and that the folder holds exactly what
//! it held before (hidden temporary files and locks included).

mod flags;
mod journals;
mod meshes;
mod scene_files;
mod signals;
mod sweep_files;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The contents of a file a case creates.
#[derive(Clone, Copy)]
pub enum Content {
    /// Text.
    Text(&'static str),
    /// Bytes.
    Bytes(&'static [u8]),
    /// Made by a function (large or generated inputs).
    Made(fn() -> Vec<u8>),
}

/// One hostile input.
pub struct Case {
    /// What it tries.
    pub name: &'static str,
    /// The command line (after `tumble`).
    pub args: &'static [&'static str],
    /// Files created in the case's folder before the run (paths relative to it; folders are
    /// created as needed).
    pub files: &'static [(&'static str, Content)],
    /// Run in the case's folder before the listing is taken (a finished sweep to damage).
    pub setup: Option<fn(&Path)>,
    /// Expected exit status.
    pub code: i32,
    /// Fragments stderr must contain.
    pub message: &'static [&'static str],
}

impl Case {
    /// A case with no files and no setup.
    pub const fn new(
        name: &'static str,
        args: &'static [&'static str],
        code: i32,
        message: &'static [&'static str],
    ) -> Self {
        Case {
            name,
            args,
            files: &[],
            setup: None,
            code,
            message,
        }
    }

    /// With files to create.
    pub const fn files(mut self, files: &'static [(&'static str, Content)]) -> Self {
        self.files = files;
        self
    }

    /// With a setup step.
    pub const fn setup(mut self, setup: fn(&Path)) -> Self {
        self.setup = Some(setup);
        self
    }
}

/// Every file and folder under `dir` (hidden ones too), relative, with file sizes, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    fn walk(base: &Path, dir: &Path, out: &mut Vec<String>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let entry = entry.unwrap();
            let path = entry.path();
            let rel = path.strip_prefix(base).unwrap().display().to_string();
            let meta = std::fs::symlink_metadata(&path).unwrap();
            if meta.is_dir() {
                out.push(format!("{rel}/"));
                walk(base, &path, out);
            } else {
                out.push(format!("{rel} ({} bytes)", meta.len()));
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

/// Runs `tumble args` in `dir`, killed after 60 s; (exit code, stderr).
pub fn run_in(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(dir)
        .args(args)
        .env("RUST_BACKTRACE", "0")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot run the tumble binary");
    let mut stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        std::io::Read::read_to_string(&mut stderr, &mut text).ok();
        text
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break Some(status);
        }
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().ok();
            child.wait().ok();
            break None;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let text = reader.join().unwrap();
    (status.and_then(|s| s.code()), text)
}

/// What is wrong with `case`'s run, if anything.
fn check(case: &Case) -> Option<String> {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    for (path, content) in case.files {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        let bytes = match content {
            Content::Text(t) => t.as_bytes().to_vec(),
            Content::Bytes(b) => b.to_vec(),
            Content::Made(f) => f(),
        };
        std::fs::write(path, bytes).unwrap();
    }
    if let Some(setup) = case.setup {
        setup(dir);
    }
    let before = listing(dir);
    let (code, err) = run_in(dir, case.args);
    let after = listing(dir);
    let mut wrong = Vec::new();
    if code != Some(case.code) {
        wrong.push(format!("exit {code:?}, expected {}", case.code));
    }
    if code == Some(101) || err.contains("panicked") || err.contains("RUST_BACKTRACE") {
        wrong.push("panicked".to_string());
    }
    for fragment in case.message {
        if !err.contains(fragment) {
            wrong.push(format!("stderr lacks `{fragment}`"));
        }
    }
    if before != after {
        wrong.push(format!("folder changed: {before:?} -> {after:?}"));
    }
    (!wrong.is_empty()).then(|| {
        format!(
            "{} ({:?}): {}\n  stderr: {}",
            case.name,
            case.args,
            wrong.join("; "),
            err.trim_end().replace('\n', "\n          ")
        )
    })
}

/// Runs every case (four at a time) and fails with the list of those that went wrong.
pub fn run_table(cases: &[Case]) {
    let failures: Vec<String> = std::thread::scope(|s| {
        let chunks: Vec<_> = cases
            .chunks(cases.len().div_ceil(4).max(1))
            .map(|chunk| s.spawn(move || chunk.iter().filter_map(check).collect::<Vec<_>>()))
            .collect();
        chunks.into_iter().flat_map(|h| h.join().unwrap()).collect()
    });
    assert!(
        failures.is_empty(),
        "{} of {} hostile cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// Every table has distinct case names and the suite holds at least 100 cases.
#[test]
fn the_suite_holds_at_least_100_distinct_cases() {
    let tables: [&[Case]; 6] = [
        flags::CASES,
        scene_files::CASES,
        sweep_files::CASES,
        journals::CASES,
        journals::MORE,
        meshes::CASES,
    ];
    let mut names: Vec<&str> = tables
        .iter()
        .flat_map(|t| t.iter().map(|c| c.name))
        .collect();
    let n = names.len() + signals::CASES;
    names.sort_unstable();
    let before = names.len();
    names.dedup();
    assert_eq!(names.len(), before, "two cases share a name");
    assert!(n >= 100, "only {n} hostile cases");
}
