use contact_core::{CoreError, LawError};
use thiserror::Error;

/// Errors of the `asperity-plastic` crate.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PlasticError {
    /// A parameter outside its domain, or a solver failure.
    #[error(transparent)]
    Core(#[from] CoreError),
    /// The Etsion-Kadin law for a pair in which no body can yield.
    #[error("no body of the pair can yield (infinite yield stress): use the Elastic law")]
    NeverYields,
    /// Constants of eq 13 outside their domain.
    #[error("invalid effective-radius constant {field} = {value:e}: must be {allowed}")]
    Fit {
        /// Which constant (`c1[0]` ... `c2[2]`).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
}

impl From<PlasticError> for LawError {
    fn from(e: PlasticError) -> Self {
        LawError::law(e)
    }
}
