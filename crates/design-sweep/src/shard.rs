//! `--shard K/N`: part K (1-based) of N interleaved parts of a grid.

use crate::DesignError;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Part `k` of `n` (1-based, `1 <= k <= n`): grid point `i` belongs to it iff
/// `i % n == k - 1`. Interleaving spreads slow and fast regions of a grid over all parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Shard {
    /// This part, 1..=n (a Slurm array task id `1-N` fits directly).
    pub k: usize,
    /// Number of parts.
    pub n: usize,
}

impl Shard {
    /// A validated shard: `n >= 1`, `1 <= k <= n`.
    pub fn new(k: usize, n: usize) -> Result<Shard, DesignError> {
        Self::checked(&format!("{k}/{n}"), k, n)
    }

    /// Parses `K/N`, e.g. `3/8`.
    pub fn parse(option: &str) -> Result<Shard, DesignError> {
        let err = |reason: String| DesignError::Shard {
            option: option.to_owned(),
            reason,
        };
        let (k, n) = option
            .split_once('/')
            .ok_or_else(|| err("expected K/N, e.g. 3/8 (part 3 of 8)".into()))?;
        let whole = |name: &str, s: &str| {
            s.trim()
                .parse::<usize>()
                .map_err(|_| err(format!("{name} `{s}` is not a whole number")))
        };
        let (k, n) = (whole("K", k)?, whole("N", n)?);
        Self::checked(option, k, n)
    }

    fn checked(option: &str, k: usize, n: usize) -> Result<Shard, DesignError> {
        let err = |reason: String| DesignError::Shard {
            option: option.to_owned(),
            reason,
        };
        if n == 0 {
            return Err(err("N = 0: there must be at least one part".into()));
        }
        if !(1..=n).contains(&k) {
            return Err(err(format!(
                "K = {k} must be in 1..={n} (parts are numbered from 1)"
            )));
        }
        Ok(Shard { k, n })
    }

    /// Whether grid point `i` belongs to this part.
    pub fn contains(&self, i: usize) -> bool {
        i % self.n == self.k - 1
    }

    /// The point indices of this part of a grid of `len` points, ascending.
    pub fn indices(&self, len: usize) -> impl Iterator<Item = usize> {
        (self.k - 1..len).step_by(self.n)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

impl FromStr for Shard {
    type Err = DesignError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Shard::parse(s)
    }
}
