//! Progress of a running sweep on stderr: a bar with an ETA when stderr is a terminal; in a
//! batch log (no terminal) a line every `--progress-every` seconds with the points done,
//! points per second and an ETA.

use std::io::IsTerminal;
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use tumble_studies::sweep::Progress;

/// Where the progress goes.
pub enum Reporter {
    /// A bar on the terminal.
    Bar(ProgressBar),
    /// Lines from a timer thread.
    Lines(Lines),
    /// Nothing.
    Quiet,
}

impl Reporter {
    /// A bar when stderr is a terminal; otherwise a line every `every` (none when `None`).
    pub fn new(every: Option<Duration>) -> Self {
        if std::io::stderr().is_terminal() {
            Reporter::Bar(progress_bar())
        } else if let Some(every) = every {
            Reporter::Lines(Lines::start(every))
        } else {
            Reporter::Quiet
        }
    }

    /// Records where the sweep stands.
    pub fn update(&self, p: &Progress) {
        match self {
            Reporter::Bar(bar) => update_bar(bar, p),
            Reporter::Lines(lines) => lines.update(p),
            Reporter::Quiet => {}
        }
    }

    /// Clears the bar or stops the lines.
    pub fn finish(self) {
        match self {
            Reporter::Bar(bar) => bar.finish_and_clear(),
            Reporter::Lines(lines) => lines.stop(),
            Reporter::Quiet => {}
        }
    }
}

/// A progress bar with an ETA on stderr.
fn progress_bar() -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{wide_bar} {pos}/{len} points, {msg}{elapsed_precise}, ETA {eta_precise}",
    ) {
        bar.set_style(style);
    }
    bar
}

fn update_bar(bar: &ProgressBar, p: &Progress) {
    if bar.length() != Some(p.total) {
        bar.set_length(p.total);
        // The ETA counts only this run's points.
        bar.set_position(p.finished);
        bar.reset_eta();
    }
    bar.set_position(p.finished);
    if p.failed > 0 {
        bar.set_message(format!("{} failed, ", p.failed));
    }
}

/// The state the timer thread reads.
struct State {
    progress: Option<Progress>,
    stop: bool,
}

/// Progress lines on stderr from a thread woken every period.
pub struct Lines {
    shared: Arc<(Mutex<State>, Condvar)>,
    thread: Option<JoinHandle<()>>,
}

impl Lines {
    fn start(every: Duration) -> Self {
        let shared = Arc::new((
            Mutex::new(State {
                progress: None,
                stop: false,
            }),
            Condvar::new(),
        ));
        let theirs = Arc::clone(&shared);
        let started = Instant::now();
        let thread = std::thread::Builder::new()
            .name("tumble-progress".into())
            .spawn(move || {
                timer_loop(&theirs, started, every, |p, elapsed| {
                    eprintln!("{}", line(p, elapsed));
                });
            })
            .ok();
        Lines { shared, thread }
    }

    fn update(&self, p: &Progress) {
        if let Ok(mut state) = self.shared.0.lock() {
            state.progress = Some(*p);
        }
    }

    fn stop(mut self) {
        if let Ok(mut state) = self.shared.0.lock() {
            state.stop = true;
        }
        self.shared.1.notify_all();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// The timer thread's loop: a line every `every` until `stop`. The flag is read under the lock
/// before every wait, so a stop signalled before this thread first takes the lock (or between
/// two waits) is seen at once rather than after a whole period: `stop` sets the flag under the
/// same lock, and the thread only waits while holding it and seeing the flag unset.
fn timer_loop(
    shared: &(Mutex<State>, Condvar),
    started: Instant,
    every: Duration,
    mut emit: impl FnMut(&Progress, Duration),
) {
    let (lock, wake) = shared;
    let Ok(mut state) = lock.lock() else { return };
    let mut next = started + every;
    loop {
        if state.stop {
            return;
        }
        let now = Instant::now();
        if now < next {
            match wake.wait_timeout(state, next - now) {
                Ok((s, _)) => state = s,
                Err(_) => return,
            }
            continue;
        }
        next += every;
        if let Some(p) = state.progress {
            emit(&p, started.elapsed());
        }
    }
}

/// `progress    120 of 500 points (24.0 %), 2 failed, 3.9 points/s, elapsed 31 s, ETA 1 min 38 s`.
fn line(p: &Progress, elapsed: Duration) -> String {
    let done = p.finished;
    let computed = p.finished - p.resumed;
    let s = elapsed.as_secs_f64();
    let rate = (s > 0.0).then(|| computed as f64 / s);
    let percent = if p.total == 0 {
        100.0
    } else {
        100.0 * done as f64 / p.total as f64
    };
    let failed = if p.failed > 0 {
        format!(", {} failed", p.failed)
    } else {
        String::new()
    };
    let eta = match rate {
        _ if done >= p.total => "ETA 0 s".to_string(),
        Some(r) if r > 0.0 => format!("ETA {}", duration((p.total - done) as f64 / r)),
        _ => "ETA unknown".to_string(),
    };
    format!(
        "progress     {done} of {} points ({percent:.1} %){failed}, {:.2} points/s, elapsed {}, \
         {eta}",
        p.total,
        rate.unwrap_or(0.0),
        duration(s)
    )
}

/// Seconds as `42 s`, `3 min 20 s`, `2 h 05 min`.
pub(super) fn duration(s: f64) -> String {
    let s = s.round().min(1e12) as u64;
    if s < 60 {
        format!("{s} s")
    } else if s < 3600 {
        format!("{} min {:02} s", s / 60, s % 60)
    } else {
        format!("{} h {:02} min", s / 3600, (s % 3600) / 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_say_points_rate_and_eta() {
        let p = Progress {
            total: 500,
            finished: 120,
            resumed: 20,
            failed: 2,
        };
        assert_eq!(
            line(&p, Duration::from_secs(25)),
            "progress     120 of 500 points (24.0 %), 2 failed, 4.00 points/s, elapsed 25 s, \
             ETA 1 min 35 s"
        );
        let start = Progress {
            total: 10,
            finished: 0,
            resumed: 0,
            failed: 0,
        };
        assert!(line(&start, Duration::ZERO).ends_with("ETA unknown"));
        assert_eq!(duration(7325.0), "2 h 02 min");
    }

    /// A stop signalled before the timer thread first waits is seen at once: the loop, run on
    /// this thread with the flag already set and a period of an hour, returns without emitting.
    #[test]
    fn a_stop_before_the_first_wait_is_not_lost() {
        let shared = (
            Mutex::new(State {
                progress: None,
                stop: true,
            }),
            Condvar::new(),
        );
        let mut lines = 0;
        let begun = Instant::now();
        timer_loop(&shared, begun, Duration::from_secs(3600), |_, _| lines += 1);
        assert_eq!(lines, 0);
        assert!(begun.elapsed() < Duration::from_secs(60));
    }

    /// `stop` right after `start`, whichever of the two threads takes the lock first, returns
    /// long before the hour-long period (the race the flag check before each wait closes),
    /// two hundred times in a row.
    #[test]
    fn stopping_at_once_never_waits_for_the_period() {
        for _ in 0..200 {
            let begun = Instant::now();
            let lines = Lines::start(Duration::from_secs(3600));
            lines.update(&Progress {
                total: 1,
                finished: 1,
                resumed: 0,
                failed: 0,
            });
            lines.stop();
            assert!(begun.elapsed() < Duration::from_secs(60));
        }
    }
}
