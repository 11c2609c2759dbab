use thiserror::Error;

/// Errors of `contact-core`: invalid input to a validated constructor, or a numeric
/// adapter that could not deliver what it promised.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CoreError {
    /// A parameter outside its physical domain.
    #[error("invalid {field} = {value}: must be {allowed}")]
    Invalid {
        field: &'static str,
        value: f64,
        allowed: &'static str,
    },
    /// A bracketed root search whose end points do not bracket a sign change.
    #[error("root of {what} not bracketed on [{lo}, {hi}] (f = {f_lo}, {f_hi})")]
    NotBracketed {
        what: &'static str,
        lo: f64,
        hi: f64,
        f_lo: f64,
        f_hi: f64,
    },
    /// A root search that ran out of iterations.
    #[error("root of {what} did not converge in {iterations} iterations")]
    NoConvergence {
        what: &'static str,
        iterations: usize,
    },
    /// A quadrature that could not reach its tolerance.
    #[error("quadrature of {what} reached error {achieved:e} > tolerance {tolerance:e}")]
    Quadrature {
        what: &'static str,
        achieved: f64,
        tolerance: f64,
    },
    /// A function evaluated inside a solver returned a non-finite value.
    #[error("{what} is not finite at x = {x}")]
    NotFinite { what: &'static str, x: f64 },
}

/// Error returned through the law traits. Each crate keeps its own error enum and
/// converts it into this one at the trait boundary, so that laws from different crates
/// (or from a user) compose without knowing each other's types.
#[derive(Debug, Error)]
pub enum LawError {
    #[error(transparent)]
    Core(#[from] CoreError),
    /// An error of a law implemented in another crate.
    #[error("{0}")]
    Law(Box<dyn std::error::Error + Send + Sync + 'static>),
}

impl LawError {
    /// Wraps the error of a law crate.
    pub fn law<E: std::error::Error + Send + Sync + 'static>(e: E) -> Self {
        LawError::Law(Box::new(e))
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(field: &'static str, value: f64) -> Result<f64, CoreError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CoreError::Invalid {
            field,
            value,
            allowed: "finite and > 0",
        })
    }
}
