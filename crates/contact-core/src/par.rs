//! Data-parallel maps over batches of independent evaluations: rayon with the `parallel`
//! feature (the default), a plain loop without it. The results are in input order and the
//! first error (in input order) is returned, so the outcome does not depend on the
//! feature or the thread count.

/// f over `xs`, in order; stops at an error.
#[cfg(feature = "parallel")]
pub fn map<T: Sync, R: Send, E: Send>(
    xs: &[T],
    f: impl Fn(&T) -> Result<R, E> + Sync,
) -> Result<Vec<R>, E> {
    use rayon::prelude::*;
    // a single item gains nothing from a task
    if xs.len() < 2 {
        return xs.iter().map(f).collect();
    }
    let out: Vec<Result<R, E>> = xs.par_iter().map(&f).collect();
    collect_exact(out.into_iter(), xs.len())
}

/// The values of `results` in order, or the first error: into a vector of `n` places
/// reserved at once (collecting `Result`s into a `Vec` cannot see the length and grows it
/// step by step, a fifth of a pressure's allocations before).
pub(crate) fn collect_exact<R, E>(
    results: impl Iterator<Item = Result<R, E>>,
    n: usize,
) -> Result<Vec<R>, E> {
    let mut v = Vec::with_capacity(n);
    for r in results {
        v.push(r?);
    }
    Ok(v)
}

/// f over `xs`, in order; stops at an error.
#[cfg(not(feature = "parallel"))]
pub fn map<T: Sync, R: Send, E: Send>(
    xs: &[T],
    f: impl Fn(&T) -> Result<R, E> + Sync,
) -> Result<Vec<R>, E> {
    collect_exact(xs.iter().map(f), xs.len())
}

/// Both closures, in parallel with the `parallel` feature.
#[cfg(feature = "parallel")]
pub fn join<A: Send, B: Send>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    rayon::join(a, b)
}

/// Both closures, one after the other.
#[cfg(not(feature = "parallel"))]
pub fn join<A: Send, B: Send>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    (a(), b())
}
