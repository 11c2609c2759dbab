use contact_core::{Categorized, Category, CoreError, LawError};
use thiserror::Error;

/// Errors of the `switch-1d` crate.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SwitchError {
    /// A parameter outside its domain, or a root/minimum/quadrature failure.
    #[error("switch: {0}")]
    Core(#[from] CoreError),
    /// The surface cannot absorb the impact energy within the separations it covers.
    #[error("the surface cannot absorb impact energy {energy:e} J/m^2 down to separation {d:e} m, where its asperities are pressed as deep as their radius: the work of the contact pressure there is {absorbed:e} J/m^2{}", if *absorbed < 0.0 { " (negative: adhesion pulls the surfaces together harder than the asperities push back, so the model has no end of impact)" } else if *absorbed == 0.0 { " (zero: no asperity is touched above that depth; earlier impacts flattened them down to it)" } else { "" })]
    EnergyNotAbsorbed {
        /// The impact energy per unit contact area (J/m^2).
        energy: f64,
        /// The deepest separation searched (m).
        d: f64,
        /// The energy absorbed there (J/m^2).
        absorbed: f64,
    },
    /// The hold pressure exceeds what the contact can bear down to the deepest separation
    /// its law is meant for.
    #[error("the hold pressure {hold:e} Pa per contact area exceeds the contact pressure down to separation {deepest:e} m, the deepest the surface law is meant for: no rest of the closed switch")]
    HoldNotBorne {
        /// The hold pressure (Pa per contact area).
        hold: f64,
        /// The deepest separation searched (m).
        deepest: f64,
    },
    /// The surface law failed.
    #[error("surface law: {0}")]
    Surface(#[from] LawError),
}

impl Categorized for SwitchError {
    /// The surface law's own category; an impact the surface cannot absorb is a numerical
    /// finding on valid input (the model has no end of impact there).
    fn category(&self) -> Category {
        match self {
            SwitchError::Core(c) => c.category(),
            SwitchError::Surface(e) => e.category(),
            SwitchError::EnergyNotAbsorbed { .. } | SwitchError::HoldNotBorne { .. } => {
                Category::Numerical
            }
        }
    }
}
