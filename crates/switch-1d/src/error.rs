use contact_core::{CoreError, LawError};
use thiserror::Error;

/// Errors of the `switch-1d` crate.
#[derive(Debug, Error)]
pub enum SwitchError {
    /// A parameter outside its domain.
    #[error("invalid {field} = {value}: must be {allowed}")]
    Invalid {
        field: &'static str,
        value: f64,
        allowed: String,
    },
    /// The surface cannot absorb the impact energy within the separations it covers.
    #[error("the surface cannot absorb impact energy {energy} J/m^2: at separation {d:e} m it has absorbed only {absorbed} J/m^2")]
    EnergyNotAbsorbed { energy: f64, d: f64, absorbed: f64 },
    /// The surface law failed.
    #[error("surface law: {0}")]
    Surface(#[from] LawError),
    /// A root or minimum search failed.
    #[error("switch solver: {0}")]
    Numeric(#[from] CoreError),
}

pub(crate) fn positive(field: &'static str, v: f64) -> Result<f64, SwitchError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(SwitchError::Invalid {
            field,
            value: v,
            allowed: "finite and > 0".into(),
        })
    }
}
