use contact_core::{CoreError, LawError};
use thiserror::Error;

/// Errors of the `gw-surface` crate.
#[derive(Debug, Error)]
pub enum GwError {
    /// A parameter outside its domain.
    #[error("invalid {field} = {value}: must be {allowed}")]
    Invalid {
        field: &'static str,
        value: f64,
        allowed: &'static str,
    },
    /// The asperity law failed at a height.
    #[error("asperity law failed at height h = {height:e} m, separation d = {d:e} m: {source}")]
    Asperity {
        height: f64,
        d: f64,
        #[source]
        source: LawError,
    },
    /// Quadrature or root failure.
    #[error("surface integral: {0}")]
    Numeric(#[from] CoreError),
}

impl From<GwError> for LawError {
    fn from(e: GwError) -> Self {
        LawError::law(e)
    }
}
