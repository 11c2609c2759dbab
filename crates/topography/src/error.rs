//! The crate's one error type.

use std::path::PathBuf;

use crate::io::Format;

/// Everything that can go wrong in this crate: a bad file (named, with what is wrong and
/// where), a refused size, or a parameter outside its domain. No function of the crate
/// panics on user input; each returns one of these instead.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TopographyError {
    /// The file could not be opened or read.
    #[error("{path}: cannot read: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The file, a part of it, or the grid it declares exceeds a size cap
    /// (`ReadOptions::max_bytes`, `ReadOptions::max_points`). Checked before the data are
    /// read or allocated.
    #[error(
        "{path}: {what} exceeds the cap of {limit} {unit}; raise the cap if the file is genuine"
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// What is too large ("the file", "the grid 70000 x 70000", "entry bindata/data.bin").
        what: String,
        /// The cap.
        limit: u64,
        /// The cap's unit ("bytes" or "points").
        unit: &'static str,
    },
    /// The file's content is not what its format requires.
    #[error("{path}: {format} file: {location}: {message}")]
    Format {
        /// The file.
        path: PathBuf,
        /// The format it was read as.
        format: Format,
        /// Where: "line 3, column 5", "header field XRes", "component xres of /0/data".
        location: String,
        /// What is wrong.
        message: String,
    },
    /// The file gives no grid spacing (or no physical size) and none was given in the options.
    #[error("{path}: {format} file gives no {what}; give it as an option (--spacing METRES; in Python spacing=) or in the file")]
    MissingSpacing {
        /// The file.
        path: PathBuf,
        /// The format it was read as.
        format: Format,
        /// "grid spacing", "x/y unit".
        what: &'static str,
    },
    /// The file gives no unit for the heights and none was given in the options.
    #[error("{path}: {format} file gives no unit for the {what}; give it as an option (--height-unit UNIT; in Python height_unit=) or in the header (# height_unit = nm)")]
    MissingUnit {
        /// The file.
        path: PathBuf,
        /// The format it was read as.
        format: Format,
        /// "heights", "x/y coordinates".
        what: &'static str,
    },
    /// The format could not be told from the extension or the first bytes.
    #[error(
        "{path}: unknown format ({message}); name it explicitly (one of {formats}), or export it as .x3p",
        formats = crate::io::Format::names()
    )]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// Why it was not recognised.
        message: String,
    },
    /// A unit string that is not a length unit this crate knows.
    #[error("unit {unit:?} is not a length unit (m, mm, um, nm, pm, angstrom, or a factor to metres such as 1e-9)")]
    Unit {
        /// The string given.
        unit: String,
    },
    /// A parameter outside its domain (a height map with a non-finite value, a negative
    /// spacing, a Hurst exponent outside (0, 1], ...).
    #[error("{name} = {value}: {message}")]
    Parameter {
        /// The parameter's name.
        name: &'static str,
        /// Its value, printed.
        value: String,
        /// The allowed range or what is wrong.
        message: String,
    },
    /// The map read from a file could not be analysed (a parameter of it outside its
    /// domain, such as a map flat to rounding): the file named with the reason.
    #[error("{path}: {source}")]
    InFile {
        /// The file.
        path: PathBuf,
        /// What is wrong with its map.
        source: Box<TopographyError>,
    },
}

impl TopographyError {
    pub(crate) fn param(
        name: &'static str,
        value: impl ToString,
        message: impl Into<String>,
    ) -> Self {
        TopographyError::Parameter {
            name,
            value: value.to_string(),
            message: message.into(),
        }
    }
}

/// The crate's result type.
pub type Result<T, E = TopographyError> = std::result::Result<T, E>;
