use contact_core::{Categorized, Category, CoreError, LawError};
use thiserror::Error;

/// Errors of the `gw-surface` crate.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum GwError {
    /// A parameter outside its domain, or a quadrature/root failure.
    #[error("surface: {0}")]
    Core(#[from] CoreError),
    /// The asperity law returned a value that is not a number (NaN or infinite).
    #[error("the asperity law returned {value} (not a finite force) at height h = {height:e} m, separation d = {d:e} m")]
    LawNotFinite {
        /// Asperity height (m).
        height: f64,
        /// Separation (m).
        d: f64,
        /// What it returned.
        value: f64,
    },
    /// The asperity law failed at a height.
    #[error("asperity law failed at height h = {height:e} m, separation d = {d:e} m: {source}")]
    Asperity {
        /// Asperity height (m).
        height: f64,
        /// Separation (m).
        d: f64,
        /// The law's error.
        #[source]
        source: LawError,
    },
}

impl Categorized for GwError {
    /// The asperity law's own category; a law returning a non-finite force is a numerical
    /// failure.
    fn category(&self) -> Category {
        match self {
            GwError::Core(c) => c.category(),
            GwError::Asperity { source, .. } => source.category(),
            GwError::LawNotFinite { .. } => Category::Numerical,
        }
    }
}

impl From<GwError> for LawError {
    fn from(e: GwError) -> Self {
        LawError::law(e)
    }
}
