//! What a law file records about how it was made and how accurate it is.

use serde::{Deserialize, Serialize};

/// Statistics of the relative interpolation error
/// e = |p_interp - p_direct| / (|p_direct| + |p_pull_out(d_min)|) over a set of points.
///
/// e is infinite where the denominator vanishes and the interpolant is not exactly zero
/// (a law without adhesion, |p_pull_out| = 0, beyond a reach): `max` and `p99` are then
/// `+inf`, written as the string `"inf"` in `law.json` and in serde output (never a finite
/// stand-in, never `null`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ErrorStats {
    /// Largest e (`+inf` if some e is infinite, NaN if some e is NaN).
    #[serde(with = "error_value")]
    pub max: f64,
    /// 99th percentile of e (nearest rank: the ceil(0.99 n)-th smallest).
    #[serde(with = "error_value")]
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
    /// The largest of the three maxima: `+inf` if one is infinite, NaN if one is NaN (a
    /// missing value is never hidden behind the others).
    pub fn max(&self) -> f64 {
        let all = [self.virgin.max, self.approach.max, self.retract.max];
        if all.iter().any(|v| v.is_nan()) {
            return f64::NAN;
        }
        all.into_iter().fold(f64::NEG_INFINITY, f64::max)
    }

    /// True when every statistic is a finite number.
    pub fn is_finite(&self) -> bool {
        [self.virgin, self.approach, self.retract]
            .iter()
            .all(|s| s.max.is_finite() && s.p99.is_finite())
    }
}

/// The text of a non-finite error value (`"inf"`, `"-inf"`, `"nan"`), `None` for a finite
/// one: how `law.json` and serde output carry what JSON numbers cannot.
pub(crate) fn non_finite_word(v: f64) -> Option<&'static str> {
    if v.is_nan() {
        Some("nan")
    } else if v == f64::INFINITY {
        Some("inf")
    } else if v == f64::NEG_INFINITY {
        Some("-inf")
    } else {
        None
    }
}

/// The value of a non-finite error word (see [`non_finite_word`]).
pub(crate) fn from_non_finite_word(s: &str) -> Option<f64> {
    match s {
        "inf" => Some(f64::INFINITY),
        "-inf" => Some(f64::NEG_INFINITY),
        "nan" => Some(f64::NAN),
        _ => None,
    }
}

/// serde for an error statistic: a JSON number when finite, else the string `"inf"`,
/// `"-inf"` or `"nan"` (JSON has no such numbers; serde_json would write `null`).
mod error_value {
    use serde::de::{self, Deserializer, Visitor};
    use serde::Serializer;
    use std::fmt;

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        match super::non_finite_word(*v) {
            Some(w) => s.serialize_str(w),
            None => s.serialize_f64(*v),
        }
    }

    struct V;

    impl Visitor<'_> for V {
        type Value = f64;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("a number or one of the strings \"inf\", \"-inf\", \"nan\"")
        }
        fn visit_f64<E: de::Error>(self, v: f64) -> Result<f64, E> {
            Ok(v)
        }
        fn visit_u64<E: de::Error>(self, v: u64) -> Result<f64, E> {
            Ok(v as f64)
        }
        fn visit_i64<E: de::Error>(self, v: i64) -> Result<f64, E> {
            Ok(v as f64)
        }
        fn visit_str<E: de::Error>(self, v: &str) -> Result<f64, E> {
            super::from_non_finite_word(v)
                .ok_or_else(|| E::invalid_value(de::Unexpected::Str(v), &self))
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        d.deserialize_any(V)
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
    /// width) before meeting the tolerance, when a user grid of histories (not refined)
    /// misses it between two of them, or when the measured error is infinite or undefined;
    /// the measured error then says by how much.
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
