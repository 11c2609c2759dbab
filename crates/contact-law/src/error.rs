use thiserror::Error;

/// Errors of the `contact-law` crate: reading, validating, evaluating and tabulating a law.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum LawError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The operating-system error.
        #[source]
        source: std::io::Error,
    },
    /// The text is not JSON (syntax error, number out of range, nesting too deep).
    #[error("law file is not valid JSON: {0}")]
    Json(String),
    /// The JSON is well formed but breaks the `law.json` format.
    #[error("law file: {path}: {message}")]
    Format {
        /// JSON path of the offending value, e.g. `branches[3].retract.d[17]`.
        path: String,
        /// What is wrong, with the value found.
        message: String,
    },
    /// A file larger than the reader accepts.
    #[error("{path}: file larger than {limit} bytes")]
    TooLarge {
        /// The file.
        path: String,
        /// The limit (bytes).
        limit: u64,
    },
    /// A query outside the range the law was tabulated on.
    #[error("{0}")]
    OutOfRange(String),
    /// A non-finite or otherwise invalid argument (separation, state, option).
    #[error("invalid {name} = {value}: {allowed}")]
    Invalid {
        /// The argument.
        name: &'static str,
        /// Its value, as printed.
        value: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The law source (the model) failed while tabulating.
    #[error("law source failed at {context}: {source}")]
    Source {
        /// Where (separation, d_min, branch).
        context: String,
        /// The source's own error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync + 'static>,
    },
    /// The law source returned something the tabulator cannot use (a non-finite value, a
    /// reach at or below d_min, a pull-out off its branch).
    #[error("law source: {0}")]
    BadSource(String),
}

impl LawError {
    pub(crate) fn format(path: impl Into<String>, message: impl Into<String>) -> Self {
        LawError::Format {
            path: path.into(),
            message: message.into(),
        }
    }

    pub(crate) fn invalid(name: &'static str, value: f64, allowed: &'static str) -> Self {
        LawError::Invalid {
            name,
            value: fmt_num(value),
            allowed,
        }
    }
}

/// A number for a message: shortest round-trip form, scientific notation (never 309 digits).
pub(crate) fn fmt_num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

impl LawError {
    /// Whether this is bad input (a file, an argument, a query out of range) rather than a
    /// law source that failed or misbehaved while tabulating (a numerical failure). The
    /// crate depends on no model crate, so it states its category as a plain flag.
    pub fn is_input(&self) -> bool {
        !matches!(self, LawError::Source { .. } | LawError::BadSource(_))
    }
}
