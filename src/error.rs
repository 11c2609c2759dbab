//! The one error type of the command line: the model library's error kept typed, plus what
//! only a command line has (options; output files and plots, from the presentation layer). The exit status comes from the
//! error's category, decided where the error was made: 2 bad input, 1 numerical failure;
//! 3 when `--strict` finds a result outside the model's validity.

use contact_core::{Categorized, Category};
use stiction_model::{ModelError, SceneError};

/// Why a command failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The model library (scene, argument, laws, numerics).
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A command-line option outside its domain or in conflict with another.
    #[error("invalid {option}: {message}")]
    Usage {
        /// The option as written (`--cycles`).
        option: String,
        /// What is wrong.
        message: String,
    },
    /// An output file, folder or stream, or a plot (the presentation layer).
    #[error(transparent)]
    Report(#[from] stiction_report::ReportError),
    /// A law file that cannot be read or is not a valid `law.json` (`stiction law eval`).
    #[error("{}", law_file_message(file, source))]
    LawFile {
        /// The file.
        file: String,
        /// Why.
        #[source]
        source: contact_law::LawError,
    },
    /// `--strict`: the result lies outside the model's validity (it was written all the
    /// same).
    #[error("--strict: {0}")]
    Strict(String),
}

impl From<SceneError> for Error {
    fn from(e: SceneError) -> Self {
        Error::Model(e.into())
    }
}

impl From<contact_law::LawError> for Error {
    fn from(e: contact_law::LawError) -> Self {
        Error::Model(e.into())
    }
}

impl From<design_sweep::DesignError> for Error {
    fn from(e: design_sweep::DesignError) -> Self {
        Error::Model(e.into())
    }
}

impl From<calibrate::CalibError> for Error {
    fn from(e: calibrate::CalibError) -> Self {
        Error::Model(e.into())
    }
}

/// "law file FILE: why" (an I/O error names the file once).
fn law_file_message(file: &str, e: &contact_law::LawError) -> String {
    match e {
        contact_law::LawError::Io { source, .. } => {
            format!("law file {file}: cannot read: {source}")
        }
        contact_law::LawError::Format { path, message } => {
            format!("law file {file}: {path}: {message}")
        }
        contact_law::LawError::Json(m) => {
            let m = m.strip_prefix(&format!("{file}: ")).unwrap_or(m);
            format!("law file {file}: not valid JSON: {m}")
        }
        contact_law::LawError::TooLarge { limit, .. } => {
            format!("law file {file}: larger than {limit} bytes: not a law file")
        }
        e => format!("law file {file}: {e}"),
    }
}

impl Error {
    /// Exit status: 2 for bad input (scene, option, output path, a parameter a law
    /// refuses), 1 for a numerical failure, 3 for a result outside the model's validity
    /// under `--strict`.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Model(e) => match e.category() {
                Category::Input => 2,
                _ => 1,
            },
            Error::Usage { .. } | Error::Report(_) | Error::LawFile { .. } => 2,
            Error::Strict(_) => 3,
        }
    }

    /// A usage error.
    pub fn usage(option: &str, message: impl Into<String>) -> Self {
        Error::Usage {
            option: option.into(),
            message: message.into(),
        }
    }

    /// The model error inside, if any (without the scene file it is reported in).
    pub fn model(&self) -> Option<&ModelError> {
        match self {
            Error::Model(e) => Some(e.cause()),
            _ => None,
        }
    }
}
