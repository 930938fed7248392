//! How an output was made: the version and git commit of the program, the command line, the
//! date, the host and its CPU, the threads. Written beside `simulate`'s CSV, into the manifests
//! of sweep, work–precision and atlas folders, and handed to Python with a run's record.

use serde::{Deserialize, Serialize};

/// The record of one invocation.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Provenance {
    /// `tumble` version.
    pub tumble_version: String,
    /// Git commit the program was built from (`-dirty` with uncommitted changes; `unknown`
    /// when it was built outside a git checkout).
    pub git_commit: String,
    /// The command line, argument by argument.
    pub command_line: Vec<String>,
    /// When the command started (UTC, RFC 3339, to the second).
    pub date: String,
    /// Host name.
    pub host: String,
    /// CPU model.
    pub cpu: String,
    /// Worker threads used.
    pub threads: usize,
}

impl Provenance {
    /// The record of this process, built as `tumble_version` from `git_commit`, using
    /// `threads` workers.
    #[must_use]
    pub fn now(tumble_version: &str, git_commit: &str, threads: usize) -> Self {
        Self {
            tumble_version: tumble_version.to_string(),
            git_commit: git_commit.to_string(),
            command_line: std::env::args().collect(),
            date: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
            host: crate::host_name(),
            cpu: cpu_model(),
            threads,
        }
    }
}

/// The CPU model (Linux: `model name` in `/proc/cpuinfo`; the architecture elsewhere).
fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string())
}
