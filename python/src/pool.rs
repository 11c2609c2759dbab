//! The thread pool of the library's parallel loops in this process.
//!
//! The library runs its batches (a surface's pressures, a map's points) on the current
//! rayon pool. rayon's global pool does not survive `fork`: a child process (a
//! `multiprocessing` or `concurrent.futures` worker started by fork after the parent
//! computed something) inherits a pool whose threads do not exist, and its first parallel
//! loop would wait forever. Every computation of this module therefore runs in
//! [`install`]: on a pool made for the current process, made again in a forked child.

use rayon::{ThreadPool, ThreadPoolBuilder};
use std::sync::{Arc, Mutex};

static POOL: Mutex<Option<(u32, Arc<ThreadPool>)>> = Mutex::new(None);

fn pool() -> Option<Arc<ThreadPool>> {
    let pid = std::process::id();
    let mut slot = POOL.lock().unwrap_or_else(|p| p.into_inner());
    if let Some((owner, p)) = slot.as_ref() {
        if *owner == pid {
            return Some(p.clone());
        }
    }
    // a pool inherited through fork has no threads: forgotten, never dropped
    if let Some((_, inherited)) = slot.take() {
        std::mem::forget(inherited);
    }
    let p = Arc::new(ThreadPoolBuilder::new().build().ok()?);
    *slot = Some((pid, p.clone()));
    Some(p)
}

/// Runs `f` on this process's pool (on the caller's thread if no pool can be made).
pub fn install<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    match pool() {
        Some(p) => p.install(f),
        None => f(),
    }
}

/// Runs `f` with the GIL released, on this process's pool.
pub fn detach<T: Send, F: FnOnce() -> T + Send>(py: pyo3::Python<'_>, f: F) -> T {
    py.detach(|| install(f))
}

/// Runs `f` with the GIL released on the calling thread: for work that never enters a
/// parallel loop (a contact law's evaluation, a short vectorised call), where handing it
/// to the pool would cost more than the work.
pub fn detach_serial<T: Send, F: FnOnce() -> T + Send>(py: pyo3::Python<'_>, f: F) -> T {
    py.detach(f)
}

/// How often a long call looks at Python: signals (Ctrl-C) and the progress callback.
const TICK: std::time::Duration = std::time::Duration::from_millis(100);

/// The count of a long call as Python sees it: the stages of a run (a switch's cycles,
/// then its model-form combinations) added up, so that `done` never decreases and never
/// exceeds `total` (which grows when a further stage starts); and the stop flag the
/// library polls.
#[derive(Default)]
pub struct Reporter {
    count: Mutex<Count>,
    stop: std::sync::atomic::AtomicBool,
}

#[derive(Default, Clone, Copy)]
struct Count {
    /// The steps of the stages that ended.
    before: u64,
    /// The current stage's total and done.
    total: u64,
    done: u64,
}

impl Reporter {
    /// (done, total) over the stages so far.
    fn now(&self) -> (u64, u64) {
        let c = *self.count.lock().unwrap_or_else(|p| p.into_inner());
        (c.before + c.done, c.before + c.total)
    }

    fn stop(&self) {
        self.stop.store(true, std::sync::atomic::Ordering::SeqCst);
    }
}

impl stiction_model::Progress for Reporter {
    fn start(&self, total: u64, _what: &str) {
        let mut c = self.count.lock().unwrap_or_else(|p| p.into_inner());
        // a stage left without finish counts whole: what it skipped is not to be done
        c.before += c.total;
        c.total = total;
        c.done = 0;
    }

    fn set(&self, done: u64) {
        let mut c = self.count.lock().unwrap_or_else(|p| p.into_inner());
        c.done = c.done.max(done.min(c.total));
    }

    fn finish(&self) {
        let mut c = self.count.lock().unwrap_or_else(|p| p.into_inner());
        c.done = c.total;
    }

    fn cancelled(&self) -> bool {
        self.stop.load(std::sync::atomic::Ordering::Relaxed)
    }
}

/// Sets its flag when dropped (the computing thread ended, returned or panicked) and wakes
/// the waiting caller.
struct Ended<'a>(&'a (Mutex<bool>, std::sync::Condvar));

impl Drop for Ended<'_> {
    fn drop(&mut self) {
        *self.0 .0.lock().unwrap_or_else(|p| p.into_inner()) = true;
        self.0 .1.notify_all();
    }
}

/// Runs a long computation `f` with the GIL released (on this process's pool when
/// `pooled`, else on one thread), while the calling thread wakes every [`TICK`] to look at
/// Python: it checks for signals (so that Ctrl-C raises `KeyboardInterrupt` within a tick
/// or two of the library's next poll, even when `progress` is None) and calls
/// `progress(done, total)` when the count moved (at most ten times a second), then once
/// more with `(total, total)` when `f` succeeds. A signal's exception or an exception of
/// the callback stops the computation ([`stiction_model::Progress::cancelled`]) and is
/// raised once it has stopped; the library's error is raised as its Python exception.
pub fn run_reported<R, E, F>(
    py: pyo3::Python<'_>,
    progress: Option<&pyo3::Bound<'_, pyo3::PyAny>>,
    pooled: bool,
    f: F,
) -> pyo3::PyResult<R>
where
    R: Send,
    E: Into<stiction_model::ModelError> + Send,
    F: FnOnce(&dyn stiction_model::Progress) -> Result<R, E> + Send,
{
    use crate::errors::OrRaise;
    use pyo3::types::PyAnyMethods;
    let reporter = Reporter::default();
    let ended = (Mutex::new(false), std::sync::Condvar::new());
    let mut raised: Option<pyo3::PyErr> = None;
    let outcome = std::thread::scope(|scope| {
        let (r, e) = (&reporter, &ended);
        let worker = scope.spawn(move || {
            let _ended = Ended(e);
            if pooled {
                install(|| f(r))
            } else {
                f(r)
            }
        });
        let mut shown: Option<(u64, u64)> = None;
        loop {
            let finished = py.detach(|| {
                let (m, cv) = &ended;
                let g = m.lock().unwrap_or_else(|p| p.into_inner());
                let (g, _) = cv
                    .wait_timeout_while(g, TICK, |ended| !*ended)
                    .unwrap_or_else(|p| p.into_inner());
                *g
            });
            if finished {
                break;
            }
            if raised.is_some() {
                continue; // stopping: wait for the computation to end
            }
            if let Err(e) = py.check_signals() {
                raised = Some(e);
                reporter.stop();
                continue;
            }
            if let Some(cb) = progress {
                let now = reporter.now();
                if shown != Some(now) {
                    shown = Some(now);
                    if let Err(e) = cb.call1(now) {
                        raised = Some(e);
                        reporter.stop();
                    }
                }
            }
        }
        match worker.join() {
            Ok(out) => out,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    });
    if let Some(e) = raised {
        return Err(e);
    }
    let out = outcome.or_raise()?;
    if let Some(cb) = progress {
        let (_, total) = reporter.now();
        cb.call1((total, total))?;
    }
    Ok(out)
}
