//! Grid axes `FIELD=FROM:TO:lin|log:N` and the 1-D or 2-D grid of a map.

use crate::point::check_field;
use crate::DesignError;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Largest number of values on one axis.
pub const MAX_AXIS_POINTS: usize = 100_000;
/// Largest number of points of a grid.
pub const MAX_GRID_POINTS: usize = 1_000_000;

/// How the values of an axis are spaced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Spacing {
    /// Evenly spaced values.
    Lin,
    /// Evenly spaced logarithms (FROM, TO > 0).
    Log,
}

impl fmt::Display for Spacing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Spacing::Lin => "lin",
            Spacing::Log => "log",
        })
    }
}

/// One varied field: `n` values from `from` to `to` (both included when `n >= 2`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    /// The scene key, `section.key`.
    pub field: String,
    /// First value.
    pub from: f64,
    /// Last value (not used when `n = 1`).
    pub to: f64,
    /// Spacing of the values.
    pub spacing: Spacing,
    /// Number of values.
    pub n: usize,
    /// The values, from `from` to `to`.
    pub values: Vec<f64>,
}

impl Axis {
    /// A validated axis. `FROM != TO`, both finite, `N >= 1`, and `FROM, TO > 0` for `log`.
    /// The values are bit-identical for the same arguments: lin `from + (to - from) * i / (n-1)`,
    /// log `exp(ln from + (ln to - ln from) * i / (n-1))` (evaluated left to right), with the
    /// end points exactly `from` and `to`.
    pub fn new(
        field: &str,
        from: f64,
        to: f64,
        spacing: Spacing,
        n: usize,
    ) -> Result<Axis, DesignError> {
        let option = format!("{field}={from}:{to}:{spacing}:{n}");
        Self::checked(&option, field, from, to, spacing, n)
    }

    /// Parses `FIELD=FROM:TO:lin|log:N`, e.g. `switch.k_s=1e2:1e5:log:31`.
    pub fn parse(option: &str) -> Result<Axis, DesignError> {
        let err = |reason: String| DesignError::Axis {
            option: option.to_owned(),
            reason,
        };
        let (field, rest) = option
            .split_once('=')
            .ok_or_else(|| err("expected FIELD=FROM:TO:lin|log:N".into()))?;
        let parts: Vec<&str> = rest.split(':').collect();
        if parts.len() != 4 {
            return Err(err(format!(
                "expected FROM:TO:lin|log:N after `{field}=`, got {} part(s) in `{rest}`",
                parts.len()
            )));
        }
        let number = |name: &str, s: &str| -> Result<f64, DesignError> {
            s.trim()
                .parse::<f64>()
                .map_err(|_| err(format!("{name} `{s}` is not a number")))
        };
        let from = number("FROM", parts[0])?;
        let to = number("TO", parts[1])?;
        let spacing = match parts[2].trim() {
            "lin" => Spacing::Lin,
            "log" => Spacing::Log,
            s => return Err(err(format!("spacing `{s}` must be lin or log"))),
        };
        let n = parts[3]
            .trim()
            .parse::<usize>()
            .map_err(|_| err(format!("N `{}` is not a whole number >= 1", parts[3])))?;
        Self::checked(option, field.trim(), from, to, spacing, n)
    }

    fn checked(
        option: &str,
        field: &str,
        from: f64,
        to: f64,
        spacing: Spacing,
        n: usize,
    ) -> Result<Axis, DesignError> {
        let err = |reason: String| DesignError::Axis {
            option: option.to_owned(),
            reason,
        };
        check_field(field).map_err(err)?;
        if !from.is_finite() {
            return Err(err(format!("FROM = {from:e} must be finite")));
        }
        if !to.is_finite() {
            return Err(err(format!("TO = {to:e} must be finite")));
        }
        if from == to {
            return Err(err(format!(
                "FROM and TO are both {from:e}: they must differ"
            )));
        }
        if spacing == Spacing::Log && !(from > 0.0 && to > 0.0) {
            return Err(err(format!(
                "log spacing needs FROM > 0 and TO > 0, got FROM = {from:e}, TO = {to:e}"
            )));
        }
        if !(1..=MAX_AXIS_POINTS).contains(&n) {
            return Err(err(format!("N = {n} must be in 1..={MAX_AXIS_POINTS}")));
        }
        Ok(Axis {
            field: field.to_owned(),
            from,
            to,
            spacing,
            n,
            values: spaced(from, to, spacing, n),
        })
    }

    /// The value in plotted coordinates: `log10(x)` on a log axis, `x` on a lin axis.
    pub(crate) fn plotted(&self, x: f64) -> f64 {
        match self.spacing {
            Spacing::Lin => x,
            Spacing::Log => x.log10(),
        }
    }

    /// Inverse of [`Axis::plotted`].
    pub(crate) fn unplotted(&self, t: f64) -> f64 {
        match self.spacing {
            Spacing::Lin => t,
            Spacing::Log => 10f64.powf(t),
        }
    }
}

impl FromStr for Axis {
    type Err = DesignError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Axis::parse(s)
    }
}

/// `n` values from `from` to `to`, end points exact.
pub(crate) fn spaced(from: f64, to: f64, spacing: Spacing, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![from];
    }
    let last = (n - 1) as f64;
    (0..n)
        .map(|i| {
            if i == 0 {
                from
            } else if i == n - 1 {
                to
            } else {
                let i = i as f64;
                match spacing {
                    Spacing::Lin => from + (to - from) * i / last,
                    Spacing::Log => {
                        let (a, b) = (from.ln(), to.ln());
                        (a + (b - a) * i / last).exp()
                    }
                }
            }
        })
        .collect()
}

/// A 1-D or 2-D grid. Point `i` of a 2-D grid is `(axes[0].values[i / n1],
/// axes[1].values[i % n1])` with `n1 = axes[1].n`: the first axis varies slowest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Grid {
    axes: Vec<Axis>,
}

impl Grid {
    /// A grid of one or two axes with distinct fields, at most [`MAX_GRID_POINTS`] points.
    pub fn new(axes: Vec<Axis>) -> Result<Grid, DesignError> {
        let g = Grid { axes };
        g.validate()?;
        Ok(g)
    }

    /// Parses one or two `--vary` options.
    pub fn parse<S: AsRef<str>>(options: &[S]) -> Result<Grid, DesignError> {
        let axes = options
            .iter()
            .map(|o| Axis::parse(o.as_ref()))
            .collect::<Result<Vec<_>, _>>()?;
        Grid::new(axes)
    }

    pub(crate) fn validate(&self) -> Result<(), DesignError> {
        let k = self.axes.len();
        if !(1..=2).contains(&k) {
            return Err(DesignError::Grid(format!(
                "{k} varied fields given: a map is 1-D or 2-D (one or two fields)"
            )));
        }
        if k == 2 && self.axes[0].field == self.axes[1].field {
            return Err(DesignError::Grid(format!(
                "field {} is varied twice",
                self.axes[0].field
            )));
        }
        for a in &self.axes {
            if a.values.len() != a.n || a.n == 0 {
                return Err(DesignError::Grid(format!(
                    "axis {} has {} values for n = {}",
                    a.field,
                    a.values.len(),
                    a.n
                )));
            }
        }
        let total = self
            .axes
            .iter()
            .try_fold(1usize, |acc, a| acc.checked_mul(a.n));
        match total {
            Some(t) if t <= MAX_GRID_POINTS => Ok(()),
            _ => Err(DesignError::Grid(format!(
                "{} points: at most {MAX_GRID_POINTS}",
                self.axes
                    .iter()
                    .map(|a| a.n.to_string())
                    .collect::<Vec<_>>()
                    .join(" x ")
            ))),
        }
    }

    /// The axes, slowest first.
    pub fn axes(&self) -> &[Axis] {
        &self.axes
    }

    /// Number of axes (1 or 2).
    pub fn dim(&self) -> usize {
        self.axes.len()
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.axes.iter().map(|a| a.n).product()
    }

    /// Never true: an axis has at least one value.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The per-axis indices of point `i` (slowest axis first).
    pub fn indices(&self, i: usize) -> Vec<usize> {
        let mut rest = i;
        let mut idx = vec![0; self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            idx[k] = rest % a.n;
            rest /= a.n;
        }
        idx
    }

    /// The field values of point `i`, one per axis.
    pub fn values(&self, i: usize) -> Vec<f64> {
        self.indices(i)
            .iter()
            .zip(&self.axes)
            .map(|(&j, a)| a.values[j])
            .collect()
    }

    /// The point index of per-axis indices (inverse of [`Grid::indices`]).
    pub fn index(&self, indices: &[usize]) -> usize {
        indices
            .iter()
            .zip(&self.axes)
            .fold(0, |acc, (&j, a)| acc * a.n + j)
    }
}
