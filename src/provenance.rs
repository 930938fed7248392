//! How an output was made: the version and git commit of the binary, the command line, the date,
//! the host and its CPU, the threads. Written beside `simulate`'s CSV and into the manifests of
//! sweep and work–precision folders.

use serde::Serialize;

/// The record of one invocation.
#[derive(Debug, Clone, Serialize)]
pub struct Provenance {
    /// `tumble` version.
    pub tumble_version: &'static str,
    /// Git commit the binary was built from (`-dirty` with uncommitted changes).
    pub git_commit: &'static str,
    /// The command line, argument by argument.
    pub command_line: Vec<String>,
    /// When the command started (UTC, RFC 3339).
    pub date: String,
    /// Host name.
    pub host: String,
    /// CPU model.
    pub cpu: String,
    /// Worker threads used.
    pub threads: usize,
}

impl Provenance {
    /// The record of this process, using `threads` workers.
    #[must_use]
    pub fn now(threads: usize) -> Self {
        Self {
            tumble_version: env!("CARGO_PKG_VERSION"),
            git_commit: env!("TUMBLE_GIT_COMMIT"),
            command_line: std::env::args().collect(),
            date: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
            host: tumble_output::host_name(),
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
