//! Grid axes, numeric `FIELD=FROM:TO:lin|log:N` or categorical `FIELD=WORD,WORD,...`, and
//! the 1-D or 2-D grid of a map.

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

/// The value of one varied field at a grid point: a number (a numeric axis) or a word (a
/// categorical axis: a law name, a choice). What an evaluator receives per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Level<'a> {
    /// A number, in the field's SI unit.
    Number(f64),
    /// A word of a categorical axis.
    Word(&'a str),
}

impl<'a> Level<'a> {
    /// The number, if the level is one.
    pub fn number(self) -> Option<f64> {
        match self {
            Level::Number(x) => Some(x),
            Level::Word(_) => None,
        }
    }

    /// The word, if the level is one.
    pub fn word(self) -> Option<&'a str> {
        match self {
            Level::Number(_) => None,
            Level::Word(w) => Some(w),
        }
    }
}

impl fmt::Display for Level<'_> {
    /// A number in the shortest form that reads back exactly (`1.5e-9`), a word as it is.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Level::Number(x) => write!(f, "{x:e}"),
            Level::Word(w) => f.write_str(w),
        }
    }
}

impl Serialize for Level<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Level::Number(x) => s.serialize_f64(*x),
            Level::Word(w) => s.serialize_str(w),
        }
    }
}

/// One varied field: `n` values from `from` to `to` (both included when `n >= 2`), or, for
/// a **categorical** axis (`FIELD=WORD,WORD,...`: a law name or a choice of the scene), the
/// `n` words of `words` in the order given.
///
/// A categorical axis is laid out like a factor's codes: its `values` are the positions of
/// its words, `0, 1, ..., n-1` (`from` 0, `to` n-1, `spacing` lin), which is what orders the
/// grid and places the words on a plot; the words are what the evaluator receives
/// ([`Grid::levels`]) and what `map.json` and `map.csv` carry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "AxisIn", into = "AxisOut")]
pub struct Axis {
    /// The scene key, `section.key`.
    pub field: String,
    /// First value (0 on a categorical axis).
    pub from: f64,
    /// Last value (not used when `n = 1`; n-1 on a categorical axis).
    pub to: f64,
    /// Spacing of the values (lin on a categorical axis).
    pub spacing: Spacing,
    /// Number of values.
    pub n: usize,
    /// The values, from `from` to `to` (on a categorical axis the codes 0, 1, ..., n-1).
    pub values: Vec<f64>,
    /// The words of a categorical axis, in order; empty for a numeric axis.
    pub words: Vec<String>,
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

    /// A validated categorical axis over `words` (at least one; each ASCII letters, digits
    /// and `_`, not a number, none twice), in the order given. Which words the field
    /// accepts is the caller's to check (the scene's keys know their laws and choices).
    pub fn categorical<S: AsRef<str>>(field: &str, words: &[S]) -> Result<Axis, DesignError> {
        let words: Vec<&str> = words.iter().map(AsRef::as_ref).collect();
        let option = format!("{field}={}", words.join(","));
        Self::checked_words(&option, field, &words)
    }

    /// Parses an axis option: `FIELD=FROM:TO:lin|log:N` (numeric, e.g.
    /// `switch.k_s=1e2:1e5:log:31`) or `FIELD=WORD,WORD,...` (categorical, e.g.
    /// `contact.plasticity_law=etsion_kadin,kogut_etsion`). The colons decide: text after
    /// `=` with a `:` is the numeric form, text without one a list of words. A list whose
    /// words are numbers (`switch.k_s=1e9,2e9`) is refused: numbers are varied as
    /// FROM:TO:lin|log:N.
    pub fn parse(option: &str) -> Result<Axis, DesignError> {
        let err = |reason: String| DesignError::Axis {
            option: option.to_owned(),
            reason,
        };
        let (field, rest) = option.split_once('=').ok_or_else(|| {
            err("expected FIELD=FROM:TO:lin|log:N (numbers) or FIELD=WORD,WORD,... (words)".into())
        })?;
        if !rest.contains(':') {
            let words: Vec<&str> = rest.split(',').map(str::trim).collect();
            return Self::checked_words(option, field.trim(), &words);
        }
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
            words: Vec::new(),
        })
    }

    fn checked_words(option: &str, field: &str, words: &[&str]) -> Result<Axis, DesignError> {
        let err = |reason: String| DesignError::Axis {
            option: option.to_owned(),
            reason,
        };
        check_field(field).map_err(err)?;
        if words.len() > MAX_AXIS_POINTS {
            return Err(err(format!(
                "{} words: at most {MAX_AXIS_POINTS}",
                words.len()
            )));
        }
        for (i, w) in words.iter().enumerate() {
            if w.is_empty() {
                return Err(err(format!(
                    "word {} of WORD,WORD,... is empty (a numeric axis is FIELD=FROM:TO:lin|log:N)",
                    i + 1
                )));
            }
            if w.parse::<f64>().is_ok() {
                return Err(err(format!(
                    "`{w}` is a number: FIELD=WORD,WORD,... lists words (law names, choices); \
                     numbers are varied as FIELD=FROM:TO:lin|log:N"
                )));
            }
            if !w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                return Err(err(format!(
                    "word `{w}` must be ASCII letters, digits and _ (a law name or a choice)"
                )));
            }
            if words[..i].contains(w) {
                return Err(err(format!("word `{w}` is listed twice")));
            }
        }
        let n = words.len();
        Ok(Axis {
            field: field.to_owned(),
            from: 0.0,
            to: n.saturating_sub(1) as f64,
            spacing: Spacing::Lin,
            n,
            values: (0..n).map(|i| i as f64).collect(),
            words: words.iter().map(|w| (*w).to_owned()).collect(),
        })
    }

    /// Whether the axis lists words (`FIELD=WORD,WORD,...`) rather than numbers.
    pub fn is_categorical(&self) -> bool {
        !self.words.is_empty()
    }

    /// The value `j` of the axis: its number, or its word on a categorical axis.
    pub fn level(&self, j: usize) -> Level<'_> {
        match self.words.get(j) {
            Some(w) => Level::Word(w),
            None => Level::Number(self.values[j]),
        }
    }

    /// The axis as an option would give it: `FIELD=FROM:TO:spacing:N` (numbers in their
    /// shortest exact form) or `FIELD=WORD,WORD,...`.
    pub fn describe(&self) -> String {
        if self.is_categorical() {
            format!("{}={}", self.field, self.words.join(","))
        } else {
            format!(
                "{}={:e}:{:e}:{}:{}",
                self.field, self.from, self.to, self.spacing, self.n
            )
        }
    }

    /// The value in plotted coordinates: `log10(x)` on a log axis, `x` on a lin axis.
    pub fn plotted(&self, x: f64) -> f64 {
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

/// `map.json`'s record of an axis: `field, from, to, spacing, n, values` for a numeric axis
/// (the format of every map before categorical axes), `field, words, n` for a categorical
/// one.
#[derive(Serialize)]
#[serde(untagged)]
enum AxisOut {
    Numeric {
        field: String,
        from: f64,
        to: f64,
        spacing: Spacing,
        n: usize,
        values: Vec<f64>,
    },
    Categorical {
        field: String,
        words: Vec<String>,
        n: usize,
    },
}

impl From<Axis> for AxisOut {
    fn from(a: Axis) -> Self {
        if a.is_categorical() {
            AxisOut::Categorical {
                field: a.field,
                words: a.words,
                n: a.n,
            }
        } else {
            AxisOut::Numeric {
                field: a.field,
                from: a.from,
                to: a.to,
                spacing: a.spacing,
                n: a.n,
                values: a.values,
            }
        }
    }
}

/// An axis as `map.json` holds it, either form.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AxisIn {
    field: String,
    #[serde(default)]
    from: Option<f64>,
    #[serde(default)]
    to: Option<f64>,
    #[serde(default)]
    spacing: Option<Spacing>,
    n: usize,
    #[serde(default)]
    values: Option<Vec<f64>>,
    #[serde(default)]
    words: Option<Vec<String>>,
}

impl TryFrom<AxisIn> for Axis {
    type Error = String;
    fn try_from(a: AxisIn) -> Result<Self, String> {
        match (a.from, a.to, a.spacing, a.values, a.words) {
            (Some(from), Some(to), Some(spacing), Some(values), None) => Ok(Axis {
                field: a.field,
                from,
                to,
                spacing,
                n: a.n,
                values,
                words: Vec::new(),
            }),
            (None, None, None, None, Some(words)) => {
                if words.len() != a.n {
                    return Err(format!(
                        "axis {} has {} words for n = {}",
                        a.field,
                        words.len(),
                        a.n
                    ));
                }
                if words.is_empty() {
                    return Err(format!("axis {} has no words", a.field));
                }
                Axis::categorical(&a.field, &words).map_err(|e| e.to_string())
            }
            _ => Err(format!(
                "axis {}: either from, to, spacing and values (numbers) or words (a categorical axis)",
                a.field
            )),
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

    /// Parses one or two `--vary` options (each numeric or categorical, [`Axis::parse`]).
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
            let codes = a.values.iter().enumerate().all(|(i, &v)| v == i as f64);
            if a.is_categorical() && (a.words.len() != a.n || !codes) {
                return Err(DesignError::Grid(format!(
                    "categorical axis {} has {} words for n = {} (values: the codes 0..n)",
                    a.field,
                    a.words.len(),
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

    /// Whether an axis is categorical.
    pub fn has_categorical(&self) -> bool {
        self.axes.iter().any(Axis::is_categorical)
    }

    /// The field values of point `i`, one per axis: numbers, and the word's code (its
    /// position, 0, 1, ...) on a categorical axis. [`Grid::levels`] gives the words.
    pub fn values(&self, i: usize) -> Vec<f64> {
        self.indices(i)
            .iter()
            .zip(&self.axes)
            .map(|(&j, a)| a.values[j])
            .collect()
    }

    /// The field values of point `i`, one per axis: numbers, and words on a categorical
    /// axis. What an evaluator receives.
    pub fn levels(&self, i: usize) -> Vec<Level<'_>> {
        self.indices(i)
            .iter()
            .zip(&self.axes)
            .map(|(&j, a)| a.level(j))
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
