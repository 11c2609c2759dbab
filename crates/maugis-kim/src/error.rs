use contact_core::{Categorized, Category, CoreError, LawError};
use thiserror::Error;

/// Errors of the `maugis-kim` crate.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MkError {
    /// A parameter outside its domain, or a solver failure (bracket, convergence,
    /// non-finite value).
    #[error(transparent)]
    Core(#[from] CoreError),
    /// A point asked on the stable branch below its turning point.
    #[error(
        "Delta = {delta:e} lies below the turning point Delta_t = {turning:e}: no stable equilibrium"
    )]
    BelowTurningPoint {
        /// The interference asked (nondimensional).
        delta: f64,
        /// The turning point's interference (nondimensional).
        turning: f64,
    },
    /// An interference so far beyond the junction that a double cannot resolve the
    /// contact branch there.
    #[error("Delta = {delta:e} lies beyond the range a double can resolve on the contact branch")]
    Unresolvable {
        /// The interference asked (nondimensional).
        delta: f64,
    },
}

impl Categorized for MkError {
    /// A parameter outside its domain is input; everything else is a solver's failure.
    fn category(&self) -> Category {
        match self {
            MkError::Core(c) => c.category(),
            _ => Category::Numerical,
        }
    }
}

impl From<MkError> for LawError {
    fn from(e: MkError) -> Self {
        LawError::law(e)
    }
}
