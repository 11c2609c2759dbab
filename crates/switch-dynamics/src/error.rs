use contact_core::{Categorized, Category, CoreError, LawError};
use switch_1d::SwitchError;
use thiserror::Error;

/// Errors of the `switch-dynamics` crate.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// A parameter outside its domain.
    #[error("invalid {field} = {value:e}: must be {allowed}")]
    Invalid {
        /// The parameter (the scene key's last part).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The ODE integrator failed (a step size collapsed, a root could not be located).
    #[error("the time integration failed in the {phase}: {message}")]
    Integrator {
        /// Which phase (flight, contact, release).
        phase: &'static str,
        /// The integrator's message.
        message: String,
    },
    /// The phase did not end within its time limit.
    #[error("the {phase} did not end within {limit:e} s ({what})")]
    Timeout {
        /// Which phase.
        phase: &'static str,
        /// The limit (s).
        limit: f64,
        /// What was expected.
        what: &'static str,
    },
    /// The plate turned back before touching, or (below the static pull-in voltage) crept
    /// to its equilibrium short of the contact: the voltage does not close the switch
    /// against the spring and the gas.
    #[error("the electrode stopped {gap:e} m short of the contact {time:e} s after the voltage step (it turned back, or rests at its equilibrium below the static pull-in voltage): the voltage does not close the switch against the spring and the gas")]
    DoesNotClose {
        /// When it turned (s).
        time: f64,
        /// Its distance from the contact's reach there (m).
        gap: f64,
    },
    /// More bounces than the limit.
    #[error("the electrode bounced more than {limit} times without being captured by the contact: the bounces do not decay (raise dynamics.max_bounces, or add gas damping)")]
    TooManyBounces {
        /// The limit.
        limit: usize,
    },
    /// The surface law failed.
    #[error("surface law: {0}")]
    Surface(#[from] LawError),
    /// The quasi-static switch computations failed.
    #[error(transparent)]
    Switch(#[from] SwitchError),
}

impl From<CoreError> for DynamicsError {
    fn from(e: CoreError) -> Self {
        DynamicsError::Switch(SwitchError::Core(e))
    }
}

impl Categorized for DynamicsError {
    /// Parameters are input; the integrator, a phase that does not end and endless bounces
    /// are numerical; the surface's and the switch's errors keep their own category.
    fn category(&self) -> Category {
        match self {
            DynamicsError::Invalid { .. } => Category::Input,
            DynamicsError::Integrator { .. }
            | DynamicsError::Timeout { .. }
            | DynamicsError::TooManyBounces { .. } => Category::Numerical,
            DynamicsError::DoesNotClose { .. } => Category::Input,
            DynamicsError::Surface(e) => e.category(),
            DynamicsError::Switch(e) => e.category(),
        }
    }
}
