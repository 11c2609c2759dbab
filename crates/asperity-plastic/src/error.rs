use contact_core::{CoreError, LawError};
use thiserror::Error;

/// Errors of the `asperity-plastic` crate.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PlasticError {
    /// A parameter outside its domain.
    #[error(transparent)]
    Invalid(#[from] CoreError),
    /// A negative or non-finite interference handed to the plasticity law.
    #[error("invalid {field} = {value}: must be {allowed}")]
    Domain {
        field: &'static str,
        value: f64,
        allowed: &'static str,
    },
}

impl From<PlasticError> for LawError {
    fn from(e: PlasticError) -> Self {
        LawError::law(e)
    }
}
