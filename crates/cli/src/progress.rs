//! Progress bars on a terminal (stderr), silent in pipes, with `--quiet` or with `--json`.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// How often a long run reports progress on stderr when stderr is not a terminal.
pub const LINE_EVERY: Duration = Duration::from_secs(5);

/// Progress as plain lines on stderr, for when stderr is not a terminal (where [`bar`] is
/// hidden): at most one line every [`LINE_EVERY`], none in a run shorter than that.
pub struct Lines {
    what: &'static str,
    total: u64,
    start: Instant,
    last: Instant,
    show: bool,
}

impl Lines {
    /// Progress of `total` steps of `what`; silent on a terminal or unless `show`.
    pub fn new(what: &'static str, total: u64, show: bool) -> Self {
        let now = Instant::now();
        Lines {
            what,
            total,
            start: now,
            last: now,
            show: show && !std::io::stderr().is_terminal(),
        }
    }

    /// `done` steps are finished; prints a line when [`LINE_EVERY`] has passed since the last.
    pub fn at(&mut self, done: u64) {
        if !self.show || done % 1024 != 0 {
            return;
        }
        let now = Instant::now();
        if now.duration_since(self.last) < LINE_EVERY {
            return;
        }
        self.last = now;
        let secs = now.duration_since(self.start).as_secs_f64();
        eprintln!(
            "mason: {}: {done}/{} ({:.0} %, {:.0}/s, {secs:.0} s)",
            self.what,
            self.total,
            100.0 * done as f64 / self.total.max(1) as f64,
            done as f64 / secs.max(1e-9)
        );
    }
}

/// A progress bar for `len` steps, hidden unless stderr is a terminal and `show` is true.
pub fn bar(len: u64, message: &str, show: bool) -> ProgressBar {
    if !show || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} ({per_sec}, {eta})")
            .expect("valid template")
            .progress_chars("=> "),
    );
    pb.set_message(message.to_string());
    pb
}
