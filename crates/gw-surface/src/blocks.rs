//! What the reload and the virgin tables share (docs/theory.md section 6.2): fixed blocks
//! in the interference x between the asperity's hard breaks and doubling points, each
//! halved into pieces until it converges, a table that ends for good at a block that
//! cannot, and one table per tolerance decade, kept for every surface of the asperity.

use crate::error::GwError;
use contact_core::{AsperityHistory, AsperityModel, CoreError};
use std::sync::{Arc, Mutex};

/// A block of more pieces than this is a failure: the table ends before it for good, and
/// eq 17 beyond it evaluates pressures. A smooth function needs a few pieces per block and
/// a kink two more per halving; more is the noise of the reload quadrature (where its
/// estimate falls short of its error) or a peak force that is not smooth. On the 200
/// random scenes of `cargo xtask accuracy` the blocks that converged took at most 106
/// pieces (accurate mode); those that did not used to run to 4096 pieces, tens of
/// seconds, once per cycle.
pub(crate) const MAX_BLOCK_PIECES: usize = 128;

/// A piece of a table: the upper end of the x range it covers.
pub(crate) trait Span {
    /// The piece's upper end (m).
    fn end(&self) -> f64;
}

/// A table in x (m): its pieces over fixed blocks ([`next_end`]), built in order up to
/// `x_max`. The blocks depend on the asperity alone, not on what was asked first, so
/// neither does a result.
#[derive(Debug, Clone)]
pub(crate) struct Blocks<P> {
    /// The tolerance decade the table was built to.
    pub(crate) eps: f64,
    /// Block ends built so far, increasing.
    ends: Vec<f64>,
    /// The asperity's hard breaks (virgin jump-in, zero, plastic breaks), increasing.
    breaks: Vec<f64>,
    pub(crate) pieces: Vec<P>,
    /// The block after `x_max` failed: more than [`MAX_BLOCK_PIECES`], or a value that
    /// could not be computed. Either is the same for the same asperity, so the table ends
    /// there for good: it is kept, never rebuilt, and serves every x below.
    failed: bool,
}

impl<P: Span> Blocks<P> {
    fn start<M: AsperityModel>(asperity: &M, eps: f64) -> Result<Self, GwError> {
        let breaks = hard_ends(asperity)?;
        Ok(Self {
            ends: vec![breaks[0]],
            breaks,
            eps,
            pieces: Vec::new(),
            failed: false,
        })
    }

    /// The covered range's upper end (m).
    pub(crate) fn x_max(&self) -> f64 {
        *self.ends.last().expect("a table has a block")
    }

    /// The lower end: the virgin jump-in (m); the tabulated functions are 0 below.
    pub(crate) fn x_min(&self) -> f64 {
        self.ends[0]
    }

    /// The ends of the blocks that bound a kink (the virgin jump-in, zero and the plastic
    /// breaks), m.
    pub(crate) fn hard_breaks(&self) -> &[f64] {
        &self.breaks
    }

    /// The piece that holds x (the last one beyond), None at and below x_min.
    pub(crate) fn piece(&self, x: f64) -> Option<&P> {
        if x <= self.x_min() || self.pieces.is_empty() {
            return None;
        }
        let i = self.pieces.partition_point(|p| p.end() < x);
        Some(&self.pieces[i.min(self.pieces.len() - 1)])
    }

    /// The table with every block up to one that covers `x_need`, each built by
    /// `block(table, a, b, first)` (its pieces pushed from index `first` on; false or an
    /// error: the block failed, and the table ends before it).
    fn extended<M: AsperityModel>(
        mut self,
        asperity: &M,
        x_need: f64,
        block: &mut impl FnMut(&mut Self, f64, f64, usize) -> Result<bool, GwError>,
    ) -> Self {
        let unit = 1e-3 * asperity.radius();
        while !self.failed && self.x_max() < x_need {
            let a = self.x_max();
            let b = next_end(a, &self.breaks, unit);
            let first = self.pieces.len();
            if let Ok(true) = block(&mut self, a, b, first) {
                self.ends.push(b);
            } else {
                self.pieces.truncate(first);
                self.failed = true;
            }
        }
        self
    }
}

/// The tables of one kind a set of surfaces has built, one per tolerance decade.
#[derive(Debug)]
pub(crate) struct Cache<P>(Mutex<Vec<Arc<Blocks<P>>>>);

impl<P> Default for Cache<P> {
    fn default() -> Self {
        Self(Mutex::new(Vec::new()))
    }
}

impl<P: Span + Clone> Cache<P> {
    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<Arc<Blocks<P>>>> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The table of `asperity` to within `eps` (rounded down to a power of ten) covering
    /// x up to `x_need` (m), extended block by block with `block` (see
    /// [`Blocks::extended`]); the error names `what` where the table ends below
    /// `x_need`. Only the table of that very decade serves, so a result never depends on
    /// which tables were built before. Built outside the lock: two callers at once may
    /// both build, and the same blocks give the same table either way.
    pub(crate) fn table<M: AsperityModel>(
        &self,
        asperity: &M,
        eps: f64,
        x_need: f64,
        what: &'static str,
        mut block: impl FnMut(&mut Blocks<P>, f64, f64, usize) -> Result<bool, GwError>,
    ) -> Result<Arc<Blocks<P>>, GwError> {
        let eps = 10f64.powf(eps.log10().floor());
        let found = self.lock().iter().find(|t| t.eps == eps).cloned();
        let table = match found {
            Some(t) if t.x_max() >= x_need || t.failed => t,
            found => {
                let base = match found {
                    Some(t) => (*t).clone(),
                    None => Blocks::start(asperity, eps)?,
                };
                let table = Arc::new(base.extended(asperity, x_need, &mut block));
                let mut tables = self.lock();
                tables.retain(|t| t.eps != table.eps);
                tables.push(table.clone());
                table
            }
        };
        if table.x_max() >= x_need {
            Ok(table)
        } else {
            Err(CoreError::NoConvergence {
                what,
                iterations: MAX_BLOCK_PIECES,
            }
            .into())
        }
    }
}

/// The end of the block after `last` (m): the next of the hard `breaks` or of the doubling
/// points `unit` 2^k, whichever comes first. The blocks so depend on the asperity alone,
/// and a break beyond the range asked leaves the blocks within it as they are (a
/// material that never yields in range gives the elastic law's table, to the bit).
fn next_end(last: f64, breaks: &[f64], unit: f64) -> f64 {
    let mut doubling = unit;
    while doubling <= last {
        doubling *= 2.0;
    }
    match breaks.iter().copied().find(|&b| b > last) {
        Some(b) if b < doubling => b,
        _ => doubling,
    }
}

/// The hard breaks of `asperity` (virgin jump-in, zero, plastic breaks), increasing: the
/// first block ends of the tables.
fn hard_ends<M: AsperityModel>(asperity: &M) -> Result<Vec<f64>, GwError> {
    let j0 = asperity
        .jump_in(AsperityHistory::VIRGIN)
        .map_err(|source| GwError::Asperity {
            height: 0.0,
            d: 0.0,
            source,
        })?;
    let mut ends = vec![j0.min(0.0)];
    if j0 < 0.0 {
        ends.push(0.0);
    }
    let mut breaks: Vec<f64> = asperity
        .plastic_breaks()
        .into_iter()
        .filter(|b| b.is_finite() && *b > 0.0)
        .collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    ends.extend(breaks);
    Ok(ends)
}
