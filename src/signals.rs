//! Clean interrupts: SIGINT (Ctrl-C), SIGTERM and SIGHUP (a dropped SSH session) set a flag
//! that running integrations poll before every step ([`tumble_scenarios::scene::CancelFlag`],
//! the sweep engine's cancel); the command then stops at a step boundary, keeps what is
//! complete (a sweep's journal), removes its temporary files, says what was kept and exits 130
//! (SIGINT), 143 (SIGTERM) or 129 (SIGHUP). A second signal while stopping ends the process at
//! once with the same status, after removing its temporary files and folder locks
//! ([`tumble_output::abort`]); what is complete stays.
//!
//! SIGHUP is handled only when the process did not inherit it ignored: under `nohup` (or any
//! parent that ignores it) a hangup keeps being ignored, as the user asked. The inherited
//! disposition is read from the kernel's `SigIgn` mask in `/proc/self/status` (no `unsafe`
//! call is needed); where that file does not exist, SIGHUP keeps its default action.

use std::sync::Arc;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use signal_hook::iterator::Signals;
use tumble_scenarios::Scene;
pub use tumble_studies::simulation::Interruptible;

/// The flags the handlers set.
struct Flags {
    any: Arc<AtomicBool>,
    int: Arc<AtomicBool>,
    term: Arc<AtomicBool>,
    hup: Arc<AtomicBool>,
}

/// The conventional exit status of a process ended by `signal` (128 + its number).
fn status_of(signal: i32) -> i32 {
    128 + signal
}

/// Whether `signal` is in the `SigIgn` mask of a `/proc/PID/status` text (`None` when the text
/// has no such line).
fn ignored_in(status: &str, signal: i32) -> Option<bool> {
    let mask = status.lines().find_map(|l| l.strip_prefix("SigIgn:"))?;
    let mask = u64::from_str_radix(mask.trim(), 16).ok()?;
    let bit = u32::try_from(signal - 1).ok()?;
    Some(mask.checked_shr(bit).is_some_and(|m| m & 1 == 1))
}

/// Whether this process inherited SIGHUP ignored (`nohup`); `None` where the kernel does not
/// say (no `/proc`).
fn hangup_ignored() -> Option<bool> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    ignored_in(&status, SIGHUP)
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
            hup: Arc::new(AtomicBool::new(false)),
        };
        let mut handled = vec![(SIGINT, &flags.int), (SIGTERM, &flags.term)];
        if hangup_ignored() == Some(false) {
            handled.push((SIGHUP, &flags.hup));
        }
        for &(signal, own) in &handled {
            let _ = signal_hook::flag::register(signal, own.clone());
            let _ = signal_hook::flag::register(signal, flags.any.clone());
        }
        // A second signal while the first is being handled ends the process at once, after
        // removing its temporary files and locks: a thread that counts the deliveries.
        let numbers: Vec<i32> = handled.iter().map(|(s, _)| *s).collect();
        if let Ok(mut signals) = Signals::new(&numbers) {
            let _ = std::thread::Builder::new()
                .name("tumble-signals".into())
                .spawn(move || {
                    let mut seen = 0u32;
                    for signal in signals.forever() {
                        seen += 1;
                        if seen >= 2 {
                            tumble_output::abort::remove_all();
                            std::process::exit(status_of(signal));
                        }
                    }
                });
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
/// SIGINT, 143 for SIGTERM, 129 for SIGHUP).
pub fn interrupted() -> Option<u8> {
    let flags = FLAGS.get()?;
    if flags.term.load(Ordering::Relaxed) {
        Some(143)
    } else if flags.hup.load(Ordering::Relaxed) {
        Some(129)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The `SigIgn` mask of `/proc/PID/status` is read bit by bit (SIGHUP is bit 0); a text
    /// without it says nothing.
    #[test]
    fn the_ignored_mask_is_read_per_signal() {
        let nohup = "Name:\ttumble\nSigBlk:\t0000000000000000\nSigIgn:\t0000000000000001\n";
        assert_eq!(ignored_in(nohup, SIGHUP), Some(true));
        assert_eq!(ignored_in(nohup, SIGINT), Some(false));
        let shell = "SigIgn:\t0000000000000006\n";
        assert_eq!(ignored_in(shell, SIGHUP), Some(false));
        assert_eq!(ignored_in(shell, SIGINT), Some(true));
        assert_eq!(ignored_in("Name:\ttumble\n", SIGHUP), None);
        assert_eq!(status_of(SIGHUP), 129);
        assert_eq!(status_of(SIGTERM), 143);
    }
}
