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
