//! The provenance of this binary's outputs: [`tumble_output::Provenance`] with the version and
//! git commit the binary was built from.

pub use tumble_output::Provenance;

/// The record of this process, using `threads` workers.
#[must_use]
pub fn now(threads: usize) -> Provenance {
    Provenance::now(
        env!("CARGO_PKG_VERSION"),
        env!("TUMBLE_GIT_COMMIT"),
        threads,
    )
}
