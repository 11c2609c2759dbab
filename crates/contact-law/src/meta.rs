//! What a law file records about how it was made and how accurate it is.

use serde::{Deserialize, Serialize};

/// Statistics of the relative interpolation error
/// e = |p_interp - p_direct| / (|p_direct| + |p_pull_out(d_min)|) over a set of points.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ErrorStats {
    /// Largest e.
    pub max: f64,
    /// 99th percentile of e (nearest rank: the ceil(0.99 n)-th smallest).
    pub p99: f64,
    /// Number of points.
    pub samples: usize,
    /// Separation d (m) of the point with the largest e.
    pub worst_d: f64,
    /// History d_min (m) of that point (for the virgin envelope, d itself).
    pub worst_d_min: f64,
}

impl ErrorStats {
    /// Statistics of `(e, d, d_min)` triples; `None` for an empty set.
    pub fn from_samples(samples: &[(f64, f64, f64)]) -> Option<ErrorStats> {
        if samples.is_empty() {
            return None;
        }
        let mut worst = samples[0];
        for s in samples {
            // a NaN error (cannot happen with finite data) counts as the worst
            if s.0 > worst.0 || s.0.is_nan() {
                worst = *s;
            }
        }
        let mut e: Vec<f64> = samples.iter().map(|s| s.0).collect();
        e.sort_by(|a, b| a.total_cmp(b));
        let n = e.len();
        let rank = ((0.99 * n as f64).ceil() as usize).clamp(1, n);
        Some(ErrorStats {
            max: worst.0,
            p99: e[rank - 1],
            samples: n,
            worst_d: worst.1,
            worst_d_min: worst.2,
        })
    }
}

/// The interpolation error measured by the tabulator against direct evaluation of the
/// source at points off every grid, per branch kind.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeasuredError {
    /// Virgin envelope.
    pub virgin: ErrorStats,
    /// Approach (reload) branches.
    pub approach: ErrorStats,
    /// Retract branches.
    pub retract: ErrorStats,
    /// Seed of the pseudo-random points.
    pub seed: u64,
}

impl MeasuredError {
    /// The largest of the three maxima.
    pub fn max(&self) -> f64 {
        self.virgin.max.max(self.approach.max).max(self.retract.max)
    }
}

/// How the tabulator built the law.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TabulationInfo {
    /// Refinement tolerance on the relative error (see [`ErrorStats`]).
    pub tolerance: f64,
    /// Initial nodes per branch before adaptive refinement.
    pub points_per_branch: usize,
    /// `adaptive` or the user grid `FROM:TO:N`.
    pub d_min_rule: String,
    /// Calls of `LawSource::pressure` (tabulation and measurement).
    pub source_evaluations: usize,
    /// False when a refinement stopped at a cap (node count, branch count or minimum
    /// width) before meeting the tolerance, or when a user grid of histories (not
    /// refined) misses it between two of them; the measured error then says by how much.
    pub converged: bool,
}

/// The error of the one-number history after a partial reload, measured by
/// [`crate::tabulate::measure_partial_reload`]: the law's retract branch of d_min against
/// the source's retraction after a reload that turned at d_turn > d_min.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PartialReloadError {
    /// Same metric as [`ErrorStats`], d_min the deepest separation.
    pub stats: ErrorStats,
    /// The turning point d_turn (m) of the worst point.
    pub worst_d_turn: f64,
}
