//! Progress on standard error for long runs: an indicatif bar that appears only when
//! stderr is a terminal and the run has already taken two seconds.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// After this long a run shows its bar.
const DELAY: Duration = Duration::from_secs(2);

struct State {
    bar: ProgressBar,
    start: Instant,
    shown: bool,
}

/// A progress bar for the model library's runs ([`stiction_model::Progress`]).
pub struct Bar {
    state: Mutex<Option<State>>,
    terminal: bool,
}

impl Bar {
    /// A bar that shows on a terminal only.
    pub fn new() -> Self {
        Self {
            state: Mutex::new(None),
            terminal: std::io::stderr().is_terminal(),
        }
    }
}

impl Default for Bar {
    fn default() -> Self {
        Self::new()
    }
}

impl stiction_model::Progress for Bar {
    fn start(&self, total: u64, what: &str) {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
        if let Ok(style) =
            ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} ({elapsed}, eta {eta})")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(what.to_string());
        if let Ok(mut s) = self.state.lock() {
            *s = Some(State {
                bar,
                start: Instant::now(),
                shown: false,
            });
        }
    }

    fn set(&self, done: u64) {
        if let Ok(mut guard) = self.state.lock() {
            if let Some(s) = guard.as_mut() {
                if !s.shown && self.terminal && s.start.elapsed() >= DELAY {
                    s.bar.set_draw_target(ProgressDrawTarget::stderr());
                    s.shown = true;
                }
                s.bar.set_position(done);
            }
        }
    }

    fn finish(&self) {
        if let Ok(mut guard) = self.state.lock() {
            if let Some(s) = guard.take() {
                s.bar.finish_and_clear();
            }
        }
    }
}
