use thiserror::Error;

/// Errors of the `design-sweep` crate. Every message names the offending input.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum DesignError {
    /// A `--vary FIELD=FROM:TO:lin|log:N` (or `FIELD=WORD,WORD,...`) option that does not
    /// parse or validate.
    #[error("invalid varied field `{option}`: {reason}")]
    Axis {
        /// The option text as given.
        option: String,
        /// What is wrong, with the offending value.
        reason: String,
    },
    /// A grid that is not 1-D or 2-D, repeats a field, or is too large.
    #[error("invalid grid: {0}")]
    Grid(String),
    /// A `--shard K/N` option that does not parse or validate.
    #[error("invalid shard `{option}`: {reason}")]
    Shard {
        /// The option text as given.
        option: String,
        /// What is wrong, with the offending value.
        reason: String,
    },
    /// Shards that cannot be merged; `shard` names the directory (or label) at fault.
    #[error("cannot merge {shard}: {reason}")]
    Merge {
        /// The label (directory) the caller gave for the shard at fault.
        shard: String,
        /// What is wrong.
        reason: String,
    },
    /// A `map.json` that does not parse as a design map.
    #[error("not a design map: {0}")]
    MapJson(String),
    /// A `map.json` (or `probability.json`) file that cannot be read (missing, not a regular file, larger than
    /// [`crate::MAX_MAP_BYTES`], not UTF-8) or whose content is not a design map
    /// ([`crate::Map::read_path`]).
    #[error("{path}: {reason}")]
    MapFile {
        /// The file.
        path: String,
        /// What is wrong.
        reason: String,
    },
    /// A second requirement (`--require`) that does not parse.
    #[error("invalid requirement {0}")]
    Requirement(String),
    /// Invalid threshold-search input (range, tolerance, field name).
    #[error("invalid threshold search: {0}")]
    Threshold(String),
    /// Every scan point of a threshold search failed: there is nothing to answer with.
    #[error("threshold search over {parameter}: all {points} scan points failed; first at {value:e}: {detail}")]
    ScanFailed {
        /// The field that was varied.
        parameter: String,
        /// The number of scan points.
        points: usize,
        /// The first scan value.
        value: f64,
        /// The first failure's message.
        detail: String,
    },
    /// A `--scatter FIELD=DIST` option that does not parse or validate.
    #[error("invalid scattered field `{option}`: {reason}")]
    Scatter {
        /// The option text as given.
        option: String,
        /// What is wrong, with the offending value.
        reason: String,
    },
    /// A `--correlate A,B=RHO` option that does not parse or validate.
    #[error("invalid correlation `{option}`: {reason}")]
    Correlation {
        /// The option text as given.
        option: String,
        /// What is wrong, with the offending value.
        reason: String,
    },
    /// An invalid probability request (samples, confidence, target half-width, ...).
    #[error("invalid probability request: {0}")]
    Probability(String),
    /// A `probability.json` that does not parse as a probability run.
    #[error("not a probability run: {0}")]
    ProbabilityJson(String),
}

impl contact_core::Categorized for DesignError {
    /// Every failure of a search on valid input is `ScanFailed`; the rest is input.
    fn category(&self) -> contact_core::Category {
        match self {
            DesignError::ScanFailed { .. } => contact_core::Category::Numerical,
            _ => contact_core::Category::Input,
        }
    }
}
