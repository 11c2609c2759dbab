use thiserror::Error;

/// What kind of failure an error is: the input was outside what the model accepts, a
/// computation on valid input could not deliver, or the caller stopped the run. Front
/// ends map it to their own signal (the command line: exit status 2 for input, 1 for
/// numerical; Python: `InputError`, `NumericalError`, or the caller's own exception).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Category {
    /// A value outside its domain, a file or option that is not what it must be.
    Input,
    /// A solver, a quadrature or a search that failed on valid input.
    Numerical,
    /// A run its caller stopped before it finished (a front end's Ctrl-C, a progress
    /// reporter that asked to cancel): neither the input nor the numerics are at fault,
    /// and no result exists.
    Interrupted,
}

/// An error that knows its [`Category`]. Every crate's error type implements it, so the
/// decision between bad input and a numerical failure is made where the error is made,
/// not by whoever receives it.
pub trait Categorized {
    /// The error's category.
    fn category(&self) -> Category;
}

/// Errors of `contact-core`: invalid input to a validated constructor, or a numeric
/// adapter that could not deliver what it promised.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CoreError {
    /// A parameter outside its physical domain.
    #[error("invalid {field} = {value:e}: must be {allowed}")]
    Invalid {
        /// The parameter's name.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// A bracketed root search whose end points do not bracket a sign change.
    #[error("root of {what} not bracketed on [{lo:e}, {hi:e}] (f = {f_lo:e}, {f_hi:e})")]
    NotBracketed {
        /// What was solved.
        what: &'static str,
        /// Lower end.
        lo: f64,
        /// Upper end.
        hi: f64,
        /// f at the lower end.
        f_lo: f64,
        /// f at the upper end.
        f_hi: f64,
    },
    /// An iterative search that ran out of iterations.
    #[error("{what} did not converge in {iterations} iterations")]
    NoConvergence {
        /// What was solved.
        what: &'static str,
        /// The cap reached.
        iterations: usize,
    },
    /// A quadrature that could not reach its tolerance.
    #[error("quadrature of {what} reached error {achieved:e} > tolerance {tolerance:e}")]
    Quadrature {
        /// What was integrated.
        what: &'static str,
        /// The error estimate reached.
        achieved: f64,
        /// The target.
        tolerance: f64,
    },
    /// A function evaluated inside a solver returned a non-finite value (NaN or infinite).
    #[error("{what} is not finite at x = {x:e}")]
    NotFinite {
        /// The function.
        what: &'static str,
        /// Where.
        x: f64,
    },
    /// A computation its caller stopped before it finished (see [`Category::Interrupted`]).
    #[error("interrupted: the run was stopped before it finished")]
    Cancelled,
}

/// Error returned through the law traits. Each crate keeps its own error enum and
/// converts it into this one at the trait boundary, so that laws from different crates
/// (or from a user) compose without knowing each other's types; the original error stays
/// reachable through [`std::error::Error::source`] and [`LawError::downcast_ref`], and its
/// [`Category`] travels with it.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum LawError {
    /// An error of `contact-core` itself.
    #[error(transparent)]
    Core(#[from] CoreError),
    /// An error of a law implemented in another crate (or by a user).
    #[error("{source}")]
    Law {
        /// The law's own error.
        source: Box<dyn std::error::Error + Send + Sync + 'static>,
        /// Bad input or a numerical failure, as the law said.
        category: Category,
    },
}

impl LawError {
    /// Wraps the error of a law crate, keeping the category it gives itself.
    pub fn law<E: std::error::Error + Categorized + Send + Sync + 'static>(e: E) -> Self {
        let category = e.category();
        LawError::Law {
            source: Box::new(e),
            category,
        }
    }

    /// Wraps any error of a user's law as bad input (a parameter the law refuses).
    pub fn input<E: Into<Box<dyn std::error::Error + Send + Sync + 'static>>>(e: E) -> Self {
        LawError::Law {
            source: e.into(),
            category: Category::Input,
        }
    }

    /// Wraps any error of a user's law as a numerical failure.
    pub fn numerical<E: Into<Box<dyn std::error::Error + Send + Sync + 'static>>>(e: E) -> Self {
        LawError::Law {
            source: e.into(),
            category: Category::Numerical,
        }
    }

    /// The law crate's own error, if it is an `E`.
    pub fn downcast_ref<E: std::error::Error + 'static>(&self) -> Option<&E> {
        match self {
            LawError::Core(c) => (c as &dyn std::error::Error).downcast_ref(),
            LawError::Law { source, .. } => source.downcast_ref(),
        }
    }
}

impl Categorized for CoreError {
    /// `Invalid` is input; a solver or quadrature that failed is numerical.
    fn category(&self) -> Category {
        match self {
            CoreError::Invalid { .. } => Category::Input,
            CoreError::Cancelled => Category::Interrupted,
            _ => Category::Numerical,
        }
    }
}

impl Categorized for LawError {
    fn category(&self) -> Category {
        match self {
            LawError::Core(c) => c.category(),
            LawError::Law { category, .. } => *category,
        }
    }
}

/// The one positive-and-finite check of the workspace: `value` if it is finite and > 0.
///
/// ```
/// assert!(contact_core::positive("radius", 4e-6).is_ok());
/// let e = contact_core::positive("radius", -1.0).unwrap_err();
/// assert_eq!(e.to_string(), "invalid radius = -1e0: must be finite and > 0");
/// ```
pub fn positive(field: &'static str, value: f64) -> Result<f64, CoreError> {
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

/// `value` if it is finite (NaN and infinities are errors naming `field`).
pub fn finite(field: &'static str, value: f64) -> Result<f64, CoreError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(CoreError::Invalid {
            field,
            value,
            allowed: "finite",
        })
    }
}
