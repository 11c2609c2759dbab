use contact_core::{Categorized, Category, CoreError, LawError};
use thiserror::Error;

/// Errors of the `asperity-plastic` crate.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
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

impl Categorized for PlasticError {
    /// A pair that cannot yield and constants out of their domain are input.
    fn category(&self) -> Category {
        match self {
            PlasticError::Core(c) => c.category(),
            _ => Category::Input,
        }
    }
}

impl From<PlasticError> for LawError {
    fn from(e: PlasticError) -> Self {
        LawError::law(e)
    }
}
