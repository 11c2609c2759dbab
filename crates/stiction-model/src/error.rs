//! The one error type of the model library: every crate's error kept typed, scene errors
//! naming file, key, line and value, and a [`Category`] for every variant (bad input or a
//! numerical failure), decided by the error that was made, never by its receiver.

use contact_core::{Categorized, Category, CoreError, LawError};

/// A scene error: a file that could not be read or parsed, a key that is unknown or
/// missing, or a value outside its domain. Always bad input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file cannot be opened or read.
    #[error("{file}: cannot read: {message}")]
    Read {
        /// The file.
        file: String,
        /// Why (the system's message).
        message: String,
    },
    /// The file is larger than [`crate::scene::MAX_SCENE_BYTES`].
    #[error("{file}: larger than {limit} bytes: not a scene file")]
    TooLarge {
        /// The file.
        file: String,
        /// The limit.
        limit: u64,
    },
    /// The file is not UTF-8 text.
    #[error("{file}: not UTF-8 text")]
    NotText {
        /// The file.
        file: String,
    },
    /// The file is empty.
    #[error("{file}: empty scene file")]
    Empty {
        /// The file.
        file: String,
    },
    /// TOML or JSON syntax.
    #[error("{file}: {message}")]
    Parse {
        /// The file.
        file: String,
        /// The parser's message (with line and column).
        message: String,
    },
    /// A key no scene of this kind takes.
    #[error("{file}: unknown key `{key}`{line} in a {kind} scene{hint}")]
    Unknown {
        /// The file.
        file: String,
        /// The key (`section.key`).
        key: String,
        /// " (line N)" where the key stands, or empty.
        line: String,
        /// The scene's kind.
        kind: String,
        /// "; did you mean ...?" or the keys of its section.
        hint: String,
    },
    /// A value outside its domain (or of the wrong type).
    #[error("{file}: invalid `{key}` = {value}{line}: must be {allowed}")]
    Field {
        /// The file.
        file: String,
        /// The key (`section.key`).
        key: String,
        /// The value as written (numbers in scientific notation).
        value: String,
        /// " (line N)" where the key stands, or empty.
        line: String,
        /// The domain or rule.
        allowed: String,
    },
    /// A required key.
    #[error("{file}: missing `{key}`: {explanation}")]
    Missing {
        /// The file.
        file: String,
        /// The key.
        key: String,
        /// What to give and why.
        explanation: String,
    },
}

impl SceneError {
    /// The scene key this error is about, if any.
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::Unknown { key, .. }
            | SceneError::Field { key, .. }
            | SceneError::Missing { key, .. } => Some(key),
            _ => None,
        }
    }

    /// The message without the file (a design point has none of its own).
    pub fn without_file(&self) -> String {
        let full = self.to_string();
        let file = match self {
            SceneError::Read { file, .. }
            | SceneError::TooLarge { file, .. }
            | SceneError::NotText { file }
            | SceneError::Empty { file }
            | SceneError::Parse { file, .. }
            | SceneError::Unknown { file, .. }
            | SceneError::Field { file, .. }
            | SceneError::Missing { file, .. } => file,
        };
        full.strip_prefix(&format!("{file}: "))
            .map(str::to_string)
            .unwrap_or(full)
    }
}

/// Why a model could not be built or run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A scene file or value.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// An argument of a run outside its domain, named as the library names it (`lambda`,
    /// `vary`, `d_min`, ...); front ends say which of their options set it.
    #[error("invalid {name} = {value}: must be {allowed}")]
    Argument {
        /// The argument's name in the library.
        name: String,
        /// The value as given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// An argument of a run that cannot be used, with what to give instead (`vary`: an
    /// unknown field, a field in conflict with the scene's drive).
    #[error("invalid {name}: {message}")]
    Option {
        /// The argument's name in the library.
        name: String,
        /// What is wrong and what to give.
        message: String,
    },
    /// A law registered twice, or a law entry that is not usable.
    #[error("law registry: {0}")]
    Registry(String),
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
    /// `switch-dynamics`.
    #[error(transparent)]
    Dynamics(#[from] switch_dynamics::DynamicsError),
    /// A law through the trait seam (a user's law included).
    #[error(transparent)]
    Law(#[from] LawError),
    /// `design-sweep`.
    #[error(transparent)]
    Design(#[from] design_sweep::DesignError),
    /// `contact-law`.
    #[error(transparent)]
    ContactLaw(#[from] contact_law::LawError),
    /// `calibrate`.
    #[error(transparent)]
    Calibrate(#[from] calibrate::CalibError),
    /// `topography`: a height map that cannot be read or analysed (always bad input: the
    /// crate refuses what it cannot use and says why).
    #[error(transparent)]
    Topography(#[from] topography::TopographyError),
    /// The run was stopped by its caller ([`crate::Progress::cancelled`]) before it
    /// finished: no result exists.
    #[error("interrupted: the run was stopped before it finished")]
    Cancelled,
    /// An error while running a scene, with the scene's file.
    #[error("{file}: {source}")]
    InScene {
        /// The scene file.
        file: String,
        /// What went wrong.
        source: Box<ModelError>,
    },
}

impl ModelError {
    /// An argument error.
    pub fn argument(
        name: impl Into<String>,
        value: impl Into<String>,
        allowed: impl Into<String>,
    ) -> Self {
        ModelError::Argument {
            name: name.into(),
            value: value.into(),
            allowed: allowed.into(),
        }
    }

    /// The error itself, without the scene file it is reported in.
    pub fn cause(&self) -> &ModelError {
        match self {
            ModelError::InScene { source, .. } => source.cause(),
            e => e,
        }
    }

    /// The same error, naming the scene it came from (scene errors name it already; a
    /// cancelled run names none: it is the caller's doing, not the scene's).
    pub fn in_scene(self, file: &str) -> Self {
        match self {
            e @ (ModelError::Scene(_) | ModelError::InScene { .. } | ModelError::Cancelled) => e,
            e => ModelError::InScene {
                file: file.to_string(),
                source: Box::new(e),
            },
        }
    }

    /// `ModelError::Cancelled` for an error of a run that `progress` stopped (whatever
    /// the error it surfaced as on its way out: a law's, a solver's, a design point's), or
    /// whose category is [`Category::Interrupted`]; the error itself otherwise.
    pub fn or_cancelled(self, progress: &dyn crate::Progress) -> Self {
        if progress.cancelled() || self.category() == Category::Interrupted {
            ModelError::Cancelled
        } else {
            self
        }
    }

    /// The message without a scene file (design points have none of their own).
    pub fn without_file(&self) -> String {
        match self.cause() {
            ModelError::Scene(s) => s.without_file(),
            e => e.to_string(),
        }
    }
}

impl Categorized for ModelError {
    /// Scene, argument and registry errors are input; the crates' errors carry their own
    /// category (a law's parameter it refuses is input, a solver's failure numerical).
    fn category(&self) -> Category {
        match self {
            ModelError::Scene(_)
            | ModelError::Argument { .. }
            | ModelError::Option { .. }
            | ModelError::Registry(_) => Category::Input,
            ModelError::Core(e) => e.category(),
            ModelError::MaugisKim(e) => e.category(),
            ModelError::Plastic(e) => e.category(),
            ModelError::Surface(e) => e.category(),
            ModelError::Switch(e) => e.category(),
            ModelError::Dynamics(e) => e.category(),
            ModelError::Law(e) => e.category(),
            ModelError::Design(e) => e.category(),
            ModelError::ContactLaw(e) => {
                if e.is_input() {
                    Category::Input
                } else {
                    Category::Numerical
                }
            }
            ModelError::Calibrate(e) => e.category(),
            ModelError::Topography(_) => Category::Input,
            ModelError::Cancelled => Category::Interrupted,
            ModelError::InScene { source, .. } => source.category(),
        }
    }
}
