//! Clean interrupts: SIGINT (Ctrl-C) and SIGTERM set a flag that running integrations poll
//! before every step ([`tumble_scenarios::scene::CancelFlag`], the sweep engine's cancel); the
//! command then stops at a step boundary, keeps what is complete (a sweep's journal), removes
//! its temporary files, says what was kept and exits 130 (SIGINT) or 143 (SIGTERM). A second
//! signal while stopping ends the process at once with the same status.

use std::sync::Arc;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

use signal_hook::consts::{SIGINT, SIGTERM};
use tumble_scenarios::Scene;
pub use tumble_studies::simulation::Interruptible;

/// The flags the handlers set.
struct Flags {
    any: Arc<AtomicBool>,
    int: Arc<AtomicBool>,
    term: Arc<AtomicBool>,
}

static FLAGS: OnceLock<Flags> = OnceLock::new();

/// Installs the handlers (once; later calls do nothing). Fails silently where signals cannot
/// be handled: the default behaviour (termination) then applies. Only commands that poll the
/// flag install them; the others keep the default behaviour.
fn install() {
    FLAGS.get_or_init(|| {
        let flags = Flags {
            any: Arc::new(AtomicBool::new(false)),
            int: Arc::new(AtomicBool::new(false)),
            term: Arc::new(AtomicBool::new(false)),
        };
        for (signal, own, code) in [(SIGINT, &flags.int, 130), (SIGTERM, &flags.term, 143)] {
            // A second signal while the first is being handled exits at once.
            let _ =
                signal_hook::flag::register_conditional_shutdown(signal, code, flags.any.clone());
            let _ = signal_hook::flag::register(signal, own.clone());
            let _ = signal_hook::flag::register(signal, flags.any.clone());
        }
        flags
    });
}

/// The flag that running work polls.
pub fn flag() -> &'static AtomicBool {
    install();
    FLAGS.get().map_or_else(
        || {
            static NEVER: AtomicBool = AtomicBool::new(false);
            &NEVER
        },
        |f| &f.any,
    )
}

/// The signal that interrupted the command, if any: its conventional exit status (130 for
/// SIGINT, 143 for SIGTERM).
pub fn interrupted() -> Option<u8> {
    let flags = FLAGS.get()?;
    if flags.term.load(Ordering::Relaxed) {
        Some(143)
    } else if flags.int.load(Ordering::Relaxed) || flags.any.load(Ordering::Relaxed) {
        Some(130)
    } else {
        None
    }
}

/// The error a command returns when it stopped for a signal.
#[derive(Debug)]
pub struct Interrupted {
    /// Exit status.
    pub code: u8,
    /// What was kept and how to go on.
    pub message: String,
}

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "interrupted: {}", self.message)
    }
}

impl std::error::Error for Interrupted {}

/// A scene whose runs stop at a step boundary once a signal arrived
/// ([`tumble_studies::simulation::Interruptible`] on the signals' flag).
#[must_use]
pub fn interruptible(scene: &'static dyn Scene) -> Interruptible {
    Interruptible {
        scene,
        flag: flag(),
    }
}

/// The result of a simulation whose rows go to `output`: a run stopped by a signal becomes
/// [`Interrupted`] (the output was not written), other errors pass through.
///
/// # Errors
/// The run's error.
pub fn simulated<T>(
    result: Result<T, tumble_scenarios::SceneError>,
    output: &std::path::Path,
) -> anyhow::Result<T> {
    match result {
        Err(tumble_scenarios::SceneError::Interrupted { t }) => Err(Interrupted {
            code: interrupted().unwrap_or(130),
            message: format!(
                "the simulation stopped at t = {t}; {} was not written",
                output.display()
            ),
        }
        .into()),
        other => Ok(other?),
    }
}
