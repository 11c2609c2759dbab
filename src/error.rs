//! The one error type of the root package: every crate's error kept typed, and the exit
//! status chosen by variant (2: bad input, 1: a numerical failure).

use crate::scene::SceneError;
use contact_core::{CoreError, LawError};

/// Why a command failed.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A scene file or value.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A command-line option outside its domain or in conflict with another.
    #[error("invalid {option}: {message}")]
    Usage {
        /// The option as written (`--cycles`).
        option: String,
        /// What is wrong.
        message: String,
    },
    /// An output file or folder.
    #[error("cannot write {path}: {source}")]
    Write {
        /// Where.
        path: String,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// A plot.
    #[error("cannot draw {path}: {message}")]
    Plot {
        /// Where.
        path: String,
        /// Why.
        message: String,
    },
    /// `contact-core`.
    #[error(transparent)]
    Core(#[from] CoreError),
    /// `maugis-kim`.
    #[error(transparent)]
    MaugisKim(#[from] maugis_kim::MkError),
    /// `asperity-plastic`.
    #[error(transparent)]
    Plastic(#[from] asperity_plastic::PlasticError),
    /// `gw-surface`.
    #[error(transparent)]
    Surface(#[from] gw_surface::GwError),
    /// `switch-1d`.
    #[error(transparent)]
    Switch(#[from] switch_1d::SwitchError),
    /// A law through the trait seam.
    #[error(transparent)]
    Law(#[from] LawError),
    /// `design-sweep`.
    #[error(transparent)]
    Design(#[from] design_sweep::DesignError),
    /// `contact-law`.
    #[error(transparent)]
    ContactLaw(#[from] contact_law::LawError),
    /// `calibrate`: finite-element data (naming line and column), options, or the fit.
    #[error(transparent)]
    Calibrate(#[from] calibrate::CalibError),
    /// A law file that cannot be read or is not a valid `law.json` (`stiction law eval`).
    #[error("{}", law_file_message(file, source))]
    LawFile {
        /// The file.
        file: String,
        /// Why.
        #[source]
        source: contact_law::LawError,
    },
    /// An error while running a scene, with the scene's file.
    #[error("{file}: {source}")]
    InScene {
        /// The scene file.
        file: String,
        /// What went wrong.
        source: Box<Error>,
    },
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
    /// refuses), 1 for a numerical failure.
    pub fn exit_code(&self) -> i32 {
        use contact_core::{Categorized, Category};
        let input = match self {
            Error::InScene { source, .. } => return source.exit_code(),
            Error::LawFile { .. } => true,
            Error::Scene(_) | Error::Usage { .. } | Error::Write { .. } | Error::Plot { .. } => {
                true
            }
            Error::Core(e) => e.category() == Category::Input,
            Error::MaugisKim(e) => e.category() == Category::Input,
            Error::Plastic(e) => e.category() == Category::Input,
            Error::Surface(e) => e.category() == Category::Input,
            Error::Switch(e) => e.category() == Category::Input,
            Error::Law(e) => e.category() == Category::Input,
            Error::Calibrate(e) => e.category() == Category::Input,
            Error::Design(e) => e.category() == Category::Input,
            Error::ContactLaw(e) => e.is_input(),
        };
        if input {
            2
        } else {
            1
        }
    }

    /// The error itself, without the scene file it is reported in.
    pub fn cause(&self) -> &Error {
        match self {
            Error::InScene { source, .. } => source.cause(),
            e => e,
        }
    }

    /// The same error, naming the scene it came from (scene errors name it already).
    pub fn in_scene(self, file: &str) -> Self {
        match self {
            e @ (Error::Scene(_) | Error::InScene { .. }) => e,
            e => Error::InScene {
                file: file.to_string(),
                source: Box::new(e),
            },
        }
    }

    /// A usage error.
    pub fn usage(option: &str, message: impl Into<String>) -> Self {
        Error::Usage {
            option: option.into(),
            message: message.into(),
        }
    }
}
