use contact_core::{CoreError, LawError};
use thiserror::Error;

/// Errors of the `maugis-kim` crate.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MkError {
    /// A parameter outside its domain.
    #[error("invalid {field} = {value}: must be {allowed}")]
    Invalid {
        field: &'static str,
        value: f64,
        allowed: &'static str,
    },
    /// A point asked on the stable branch below its turning point.
    #[error(
        "Delta = {delta} lies below the turning point Delta_t = {turning}: no stable equilibrium"
    )]
    BelowTurningPoint { delta: f64, turning: f64 },
    /// A solver failure (bracket, convergence, non-finite value).
    #[error("Maugis-Kim solver: {0}")]
    Numeric(#[from] CoreError),
}

impl From<MkError> for LawError {
    fn from(e: MkError) -> Self {
        LawError::law(e)
    }
}

pub(crate) fn check_positive(field: &'static str, value: f64) -> Result<f64, MkError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MkError::Invalid {
            field,
            value,
            allowed: "finite and > 0",
        })
    }
}
