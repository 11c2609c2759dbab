//! The one error type of the presentation layer.

/// Why a result could not be presented or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// An output file, folder or stream.
    #[error("cannot write {path}: {source}")]
    Write {
        /// Where (as the user named it).
        path: String,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// A plot that could not be drawn.
    #[error("cannot draw {path}: {message}")]
    Plot {
        /// The file it was drawn for.
        path: String,
        /// Why.
        message: String,
    },
    /// A CSV table that could not be formed.
    #[error("cannot write the CSV table: {0}")]
    Csv(String),
}

impl ReportError {
    /// A plot of the file `path` that failed with `message`.
    pub fn plot(path: &std::path::Path, message: impl Into<String>) -> Self {
        ReportError::Plot {
            path: path.display().to_string(),
            message: message.into(),
        }
    }
}
