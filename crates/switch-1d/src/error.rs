use contact_core::{CoreError, LawError};
use thiserror::Error;

/// Errors of the `switch-1d` crate.
#[derive(Debug, Error)]
pub enum SwitchError {
    /// A parameter outside its domain, or a root/minimum/quadrature failure.
    #[error("switch: {0}")]
    Core(#[from] CoreError),
    /// The surface cannot absorb the impact energy within the separations it covers.
    #[error("the surface cannot absorb impact energy {energy:e} J/m^2: at separation {d:e} m it has absorbed only {absorbed:e} J/m^2")]
    EnergyNotAbsorbed {
        /// The impact energy per unit contact area (J/m^2).
        energy: f64,
        /// The deepest separation searched (m).
        d: f64,
        /// The energy absorbed there (J/m^2).
        absorbed: f64,
    },
    /// The surface law failed.
    #[error("surface law: {0}")]
    Surface(#[from] LawError),
}
