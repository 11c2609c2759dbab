use crate::branch::Branch;
use asperity_plastic::PlasticError;
use contact_core::LawError;
use std::fmt;
use thiserror::Error;

/// Errors of the `calibrate` crate.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum CalibError {
    /// Bad finite-element data, located by its line (1-based, in the file) and column.
    #[error("line {line}, column {column}: {problem}")]
    Data {
        /// Line number in the file (1-based; the header is the first non-comment line).
        line: usize,
        /// The column: its header name (`force_n`), or `column 6` for a field beyond the header.
        column: String,
        /// What is wrong.
        problem: DataProblem,
    },
    /// The data could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
    /// Fewer data points than constants to fit.
    #[error("line {line}: the data end after {points} points, fewer than the {constants} constants to fit")]
    TooFewPoints {
        /// Line of the last data point.
        line: usize,
        /// Points in the data.
        points: usize,
        /// Constants selected by `--fit`.
        constants: usize,
    },
    /// A `--fit` selection that names no constant or an unknown one.
    #[error("invalid selection of constants {text:?}: {reason}")]
    Selection {
        /// The selection as given.
        text: String,
        /// Why it is invalid.
        reason: String,
    },
    /// Starting constants outside the domain of eq 13.
    #[error("invalid starting constants: {0}")]
    Start(#[from] PlasticError),
    /// An option outside its domain.
    #[error("invalid option {field} = {value:e}: must be {allowed}")]
    Option {
        /// The option.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The forward model failed at a data point at the starting (or requested) constants.
    #[error("model failed at line {line} (delta_max {delta_max:e} m, {branch}, delta {delta:e} m): {source}")]
    Model {
        /// The data line.
        line: usize,
        /// The curve's maximum interference (m).
        delta_max: f64,
        /// The curve's branch.
        branch: Branch,
        /// The interference (m).
        delta: f64,
        /// The law's error.
        #[source]
        source: LawError,
    },
    /// The forward model failed on the overlay grid (no data line involved).
    #[error(
        "model failed at delta {delta:e} m on the {branch} curve to {delta_max:e} m: {source}"
    )]
    Overlay {
        /// The curve's maximum interference (m).
        delta_max: f64,
        /// The curve's branch.
        branch: Branch,
        /// The interference (m).
        delta: f64,
        /// The law's error.
        #[source]
        source: LawError,
    },
    /// The singular value decomposition did not converge.
    #[error("singular value decomposition of the {rows} x {cols} Jacobian did not converge")]
    Svd {
        /// Rows of the Jacobian.
        rows: usize,
        /// Columns of the Jacobian.
        cols: usize,
    },
}

/// What is wrong with a line of finite-element data.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum DataProblem {
    /// The file has no header line.
    NoHeader,
    /// A required column is absent from the header.
    MissingColumn,
    /// A required column appears twice in the header.
    DuplicateColumn {
        /// 1-based position of its first appearance.
        first: usize,
    },
    /// The row ends before this column.
    MissingField,
    /// The row has more fields than the header.
    ExtraField,
    /// Not a number.
    NotANumber {
        /// The cell's text.
        text: String,
    },
    /// A number that is NaN or infinite.
    NotFinite {
        /// The cell's text.
        text: String,
    },
    /// A branch word other than `loading` and `unloading`.
    UnknownBranch {
        /// The cell's text.
        text: String,
    },
    /// delta above delta_max by more than a relative 1e-9.
    AboveDeltaMax {
        /// delta (m).
        delta: f64,
        /// delta_max (m).
        delta_max: f64,
    },
    /// delta_max <= 0.
    NonPositiveDeltaMax {
        /// The value (m).
        value: f64,
    },
    /// A curve (delta_max, branch) with fewer than 2 points.
    TooFewCurvePoints {
        /// The curve's delta_max (m).
        delta_max: f64,
        /// The curve's branch.
        branch: Branch,
        /// Its points.
        points: usize,
    },
    /// A curve whose forces are all zero: it has no scale to weight its residuals by.
    ZeroPeakForce {
        /// The curve's delta_max (m).
        delta_max: f64,
        /// The curve's branch.
        branch: Branch,
    },
    /// A curve whose peak force differs from the model's on the same curve (at the
    /// starting constants) by more than [`crate::FORCE_SCALE_LIMIT`]: forces in other
    /// units, or curves of another asperity than the scene's.
    ForceScale {
        /// The curve's peak |force| (N), the value on this line.
        force: f64,
        /// The curve's delta_max (m).
        delta_max: f64,
        /// The curve's branch.
        branch: Branch,
        /// The model's peak |force| on the curve's points (N).
        model_peak: f64,
    },
}

impl fmt::Display for DataProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DataProblem::NoHeader => write!(
                f,
                "no header line (expected delta_max_m, delta_m, force_n, branch)"
            ),
            DataProblem::MissingColumn => write!(f, "required column missing from the header"),
            DataProblem::DuplicateColumn { first } => {
                write!(f, "column repeated (first at position {first})")
            }
            DataProblem::MissingField => write!(f, "the row ends before this column"),
            DataProblem::ExtraField => write!(f, "the row has more fields than the header"),
            DataProblem::NotANumber { text } => write!(f, "not a number: {text:?}"),
            DataProblem::NotFinite { text } => write!(f, "not a finite number: {text:?}"),
            DataProblem::UnknownBranch { text } => {
                write!(f, "unknown branch {text:?} (expected loading or unloading)")
            }
            DataProblem::AboveDeltaMax { delta, delta_max } => write!(
                f,
                "delta {delta:e} m above the curve's delta_max {delta_max:e} m"
            ),
            DataProblem::NonPositiveDeltaMax { value } => {
                write!(f, "delta_max {value:e} m must be > 0")
            }
            DataProblem::TooFewCurvePoints {
                delta_max,
                branch,
                points,
            } => write!(
                f,
                "the {branch} curve with delta_max {delta_max:e} m has {points} point(s), needs at least 2"
            ),
            DataProblem::ZeroPeakForce { delta_max, branch } => write!(
                f,
                "the {branch} curve with delta_max {delta_max:e} m has only zero forces"
            ),
            DataProblem::ForceScale {
                force,
                delta_max,
                branch,
                model_peak,
            } => write!(
                f,
                "force {force:e} N, the peak of the {branch} curve with delta_max {delta_max:e} m, \
                 is {:.1e} times the scene's asperity model there ({model_peak:e} N at the \
                 starting constants); eq 13's constants cannot bridge more than a factor \
                 {:e}: are the forces in N, and are material, radius and adhesion those of \
                 the FE runs?",
                force / model_peak,
                crate::FORCE_SCALE_LIMIT
            ),
        }
    }
}

impl contact_core::Categorized for CalibError {
    /// Data, options, starting constants and parameters the model refuses are input; a
    /// fit that fails numerically is not.
    fn category(&self) -> contact_core::Category {
        use contact_core::Category;
        match self {
            CalibError::Data { .. }
            | CalibError::Io { .. }
            | CalibError::TooFewPoints { .. }
            | CalibError::Selection { .. }
            | CalibError::Start(_)
            | CalibError::Option { .. } => Category::Input,
            CalibError::Model { source, .. } | CalibError::Overlay { source, .. } => {
                source.category()
            }
            CalibError::Svd { .. } => Category::Numerical,
        }
    }
}
