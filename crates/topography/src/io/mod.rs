//! Readers (and writers) of height-map files.
//!
//! Every reader takes the whole file through a bounded read (at most
//! [`ReadOptions::max_bytes`], so a FIFO or `/dev/zero` cannot exhaust memory), checks the
//! grid a file declares against [`ReadOptions::max_points`] before allocating it, and
//! returns a [`TopographyError`] naming the file, the format, where (line and column,
//! header field, object component, archive entry) and what is wrong.

use std::fmt;
use std::io::Read;
use std::path::Path;
use std::str::FromStr;

use serde::Serialize;

use crate::error::{Result, TopographyError};
use crate::map::{HeightMap, LengthUnit};

mod gsf;
mod gwy;
mod npy;
mod text;
mod x3p;

pub use gsf::{encode_gsf, read_gsf};
pub use gwy::{encode_gwy, read_gwy};
pub use npy::{encode_npy, read_npy};
pub use text::{encode_text_matrix, encode_xyz, read_text_matrix, read_xyz};
pub use x3p::{encode_x3p, read_x3p};

/// A supported file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Format {
    /// Plain text matrix: one row of heights per line (whitespace, comma or semicolon
    /// separated), `#` comment lines with `key = value` settings (docs/topography.md).
    Text,
    /// Text x, y, z columns on a regular grid, in any order.
    Xyz,
    /// NumPy `.npy`, a 2-D array (rows = y) of floats or integers, C or Fortran order.
    Npy,
    /// Gwyddion Simple Field `.gsf`.
    Gsf,
    /// Gwyddion native `.gwy` (GWYP serialised objects); the first channel `/N/data`.
    Gwy,
    /// ISO 25178-72 `.x3p` (XML 3D surface profile: zip with main.xml and binary data).
    X3p,
}

impl Format {
    /// Every format, in the order of the docs.
    pub const ALL: [Format; 6] = [
        Format::Text,
        Format::Xyz,
        Format::Npy,
        Format::Gsf,
        Format::Gwy,
        Format::X3p,
    ];

    /// The format's name as accepted by [`Format::from_str`].
    pub fn name(self) -> &'static str {
        match self {
            Format::Text => "text",
            Format::Xyz => "xyz",
            Format::Npy => "npy",
            Format::Gsf => "gsf",
            Format::Gwy => "gwy",
            Format::X3p => "x3p",
        }
    }

    /// The usual file extension (without the dot).
    pub fn extension(self) -> &'static str {
        match self {
            Format::Text => "txt",
            other => other.name(),
        }
    }

    /// The format a file extension names, if any (`txt`, `csv`, `dat`, `asc` are text).
    pub fn from_extension(ext: &str) -> Option<Format> {
        match ext.to_ascii_lowercase().as_str() {
            "txt" | "csv" | "dat" | "asc" | "tsv" => Some(Format::Text),
            "xyz" => Some(Format::Xyz),
            "npy" => Some(Format::Npy),
            "gsf" => Some(Format::Gsf),
            "gwy" => Some(Format::Gwy),
            "x3p" => Some(Format::X3p),
            _ => None,
        }
    }

    /// The format the first bytes announce, if they carry a magic number.
    pub fn sniff(head: &[u8]) -> Option<Format> {
        if head.starts_with(b"\x93NUMPY") {
            Some(Format::Npy)
        } else if head.starts_with(b"GWYP") || head.starts_with(b"GWYO") {
            Some(Format::Gwy)
        } else if head.starts_with(b"Gwyddion Simple Field") {
            Some(Format::Gsf)
        } else if head.starts_with(b"PK\x03\x04") {
            Some(Format::X3p)
        } else {
            None
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Format {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "text" | "txt" | "matrix" => Ok(Format::Text),
            "xyz" => Ok(Format::Xyz),
            "npy" => Ok(Format::Npy),
            "gsf" => Ok(Format::Gsf),
            "gwy" => Ok(Format::Gwy),
            "x3p" => Ok(Format::X3p),
            _ => Err(format!(
                "unknown format {s:?}: text, xyz, npy, gsf, gwy or x3p"
            )),
        }
    }
}

/// What the caller knows about a file, and the size caps.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ReadOptions {
    /// Read as this format instead of guessing from the extension and the first bytes.
    pub format: Option<Format>,
    /// Grid spacing (m) for a format that lacks one (text matrix, npy, a gsf without
    /// XReal/YReal). If the file has one too, this one is used and the report says so.
    pub spacing: Option<f64>,
    /// Unit of the heights, for a file that does not state it (text, xyz, npy). Overrides
    /// the file's unit if it does (the report says so).
    pub height_unit: Option<LengthUnit>,
    /// Unit of the x and y coordinates of an xyz file that does not state it.
    pub xy_unit: Option<LengthUnit>,
    /// Largest file (bytes) read. Default 256 MiB.
    pub max_bytes: u64,
    /// Largest grid (points) accepted, checked before the data are allocated.
    /// Default 2^26 (8192 x 8192).
    pub max_points: usize,
}

impl ReadOptions {
    /// Default cap on the file size: 256 MiB.
    pub const DEFAULT_MAX_BYTES: u64 = 256 << 20;
    /// Default cap on the grid: 2^26 points.
    pub const DEFAULT_MAX_POINTS: usize = 1 << 26;
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions {
            format: None,
            spacing: None,
            height_unit: None,
            xy_unit: None,
            max_bytes: Self::DEFAULT_MAX_BYTES,
            max_points: Self::DEFAULT_MAX_POINTS,
        }
    }
}

/// Where a map came from and how its units were settled.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Source {
    /// The file, as given.
    pub path: String,
    /// The format it was read as.
    pub format: Format,
    /// "file" or "options": where the grid spacing came from.
    pub spacing_from: &'static str,
    /// "file" or "options": where the height unit came from.
    pub height_unit_from: &'static str,
    /// Metres per unit of the stored heights.
    pub height_unit: f64,
    /// The channel or data title, if the file has one.
    pub title: Option<String>,
    /// Anything the reader did that the user should know (an option overriding the file, a
    /// channel chosen among several, ...).
    pub notes: Vec<String>,
}

/// A height map read from a file, with its provenance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Measurement {
    /// The map, SI.
    pub map: HeightMap,
    /// Where it came from.
    pub source: Source,
}

/// Reads a height map, choosing the reader from `opts.format`, else the extension, else the
/// first bytes (magic numbers), else text.
pub fn read_path(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Measurement> {
    let path = path.as_ref();
    let bytes = read_bounded(path, opts.max_bytes)?;
    let format = match opts.format {
        Some(f) => f,
        None => match path
            .extension()
            .and_then(|e| e.to_str())
            .and_then(Format::from_extension)
        {
            Some(f) => f,
            None => Format::sniff(&bytes).unwrap_or(Format::Text),
        },
    };
    decode(path, &bytes, format, opts)
}

/// Decodes bytes already in memory as `format` (`path` only names the data in errors).
pub fn decode(
    path: &Path,
    bytes: &[u8],
    format: Format,
    opts: &ReadOptions,
) -> Result<Measurement> {
    if bytes.len() as u64 > opts.max_bytes {
        return Err(TopographyError::TooLarge {
            path: path.to_path_buf(),
            what: format!("the data ({} bytes)", bytes.len()),
            limit: opts.max_bytes,
            unit: "bytes",
        });
    }
    let m = match format {
        Format::Text => text::decode_text(path, bytes, opts, false),
        Format::Xyz => text::decode_text(path, bytes, opts, true),
        Format::Npy => npy::decode(path, bytes, opts),
        Format::Gsf => gsf::decode(path, bytes, opts),
        Format::Gwy => gwy::decode(path, bytes, opts),
        Format::X3p => x3p::decode(path, bytes, opts),
    }?;
    // a measured map's spacing lies between a picometre and a metre (a file, or --spacing,
    // saying 1e308 m would make every slope underflow and the map read as flat)
    for (name, v) in [("dx", m.map.dx()), ("dy", m.map.dy())] {
        if !(HeightMap::MIN_SPACING..=HeightMap::MAX_SPACING).contains(&v) {
            return Err(TopographyError::InFile {
                path: path.to_path_buf(),
                source: Box::new(TopographyError::param(
                    name,
                    format!("{v:e} m"),
                    format!(
                        "a measured map's grid spacing lies in [{:e}, {:e}] m (a picometre to a metre)",
                        HeightMap::MIN_SPACING,
                        HeightMap::MAX_SPACING
                    ),
                )),
            });
        }
    }
    Ok(m)
}

/// The bytes of a map in `format` (heights and spacings in metres; formats with units
/// state them).
pub fn encode(map: &HeightMap, format: Format) -> Result<Vec<u8>> {
    Ok(match format {
        Format::Text => encode_text_matrix(map).into_bytes(),
        Format::Xyz => encode_xyz(map).into_bytes(),
        Format::Npy => encode_npy(map),
        Format::Gsf => encode_gsf(map),
        Format::Gwy => encode_gwy(map),
        Format::X3p => encode_x3p(map)?,
    })
}

/// Writes a map to `path` in `format`.
pub fn write_path(path: impl AsRef<Path>, map: &HeightMap, format: Format) -> Result<()> {
    let path = path.as_ref();
    let bytes = encode(map, format)?;
    std::fs::write(path, bytes).map_err(|source| TopographyError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Reads at most `max_bytes` of the file: a regular file's size is checked before reading,
/// and any other file (a FIFO, a device) is read through a limit of `max_bytes + 1`.
pub(crate) fn read_bounded(path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    let io = |source| TopographyError::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let too_large = |what: String| TopographyError::TooLarge {
        path: path.to_path_buf(),
        what,
        limit: max_bytes,
        unit: "bytes",
    };
    if let Ok(md) = file.metadata() {
        if md.is_dir() {
            return Err(io(std::io::Error::other("is a directory")));
        }
        if md.is_file() && md.len() > max_bytes {
            return Err(too_large(format!("the file ({} bytes)", md.len())));
        }
    }
    let mut buf = Vec::new();
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut buf)
        .map_err(io)?;
    if buf.len() as u64 > max_bytes {
        return Err(too_large(format!(
            "the stream (more than {max_bytes} bytes)"
        )));
    }
    Ok(buf)
}

/// A unit found in a file.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum FileUnit {
    /// No unit stated.
    Absent,
    /// A length unit.
    Length(LengthUnit),
    /// A unit that is not a length (V, A, deg, ...), as written.
    Other(String),
}

impl FileUnit {
    /// Interprets a unit string from a file: empty is absent, SI base units as in Gwyddion
    /// ("A" is the ampere).
    pub fn from_file(s: &str) -> FileUnit {
        let t = s.trim();
        if t.is_empty() {
            return FileUnit::Absent;
        }
        match LengthUnit::parse(t) {
            Ok(u) if t.parse::<f64>().is_err() => FileUnit::Length(u),
            _ => FileUnit::Other(t.to_string()),
        }
    }
}

/// Context shared by the readers to settle the grid spacing and the height unit.
pub(crate) struct Settle<'a> {
    pub path: &'a Path,
    pub format: Format,
    pub opts: &'a ReadOptions,
    pub notes: Vec<String>,
    pub title: Option<String>,
}

impl<'a> Settle<'a> {
    pub fn new(path: &'a Path, format: Format, opts: &'a ReadOptions) -> Self {
        Settle {
            path,
            format,
            opts,
            notes: Vec::new(),
            title: None,
        }
    }

    pub fn err(&self, location: impl Into<String>, message: impl Into<String>) -> TopographyError {
        TopographyError::Format {
            path: self.path.to_path_buf(),
            format: self.format,
            location: location.into(),
            message: message.into(),
        }
    }

    /// Refuses a grid above the point cap (before anything is allocated).
    pub fn check_points(&self, nx: u64, ny: u64) -> Result<usize> {
        let n = nx
            .checked_mul(ny)
            .filter(|&n| n <= self.opts.max_points as u64);
        n.map(|n| n as usize)
            .ok_or_else(|| TopographyError::TooLarge {
                path: self.path.to_path_buf(),
                what: format!("the grid {nx} x {ny}"),
                limit: self.opts.max_points as u64,
                unit: "points",
            })
    }

    /// The spacing (dx, dy) in metres from the file's (if any) and the options'.
    pub fn spacing(&mut self, file: Option<(f64, f64)>) -> Result<(f64, f64, &'static str)> {
        match (self.opts.spacing, file) {
            (Some(s), file) => {
                if !(s.is_finite() && s > 0.0) {
                    return Err(TopographyError::param(
                        "spacing",
                        s,
                        "must be finite and > 0 (m)",
                    ));
                }
                if let Some((fx, fy)) = file {
                    let close = |a: f64| (a - s).abs() <= 1e-9 * s;
                    if !(close(fx) && close(fy)) {
                        self.notes.push(format!(
                            "the spacing given in the options ({s:e} m) overrides the file's ({fx:e} x {fy:e} m)"
                        ));
                    }
                }
                Ok((s, s, "options"))
            }
            (None, Some((fx, fy))) => Ok((fx, fy, "file")),
            (None, None) => Err(TopographyError::MissingSpacing {
                path: self.path.to_path_buf(),
                format: self.format,
                what: "grid spacing",
            }),
        }
    }

    /// Metres per stored height unit from the file's unit and the options'.
    pub fn height_unit(&mut self, file: FileUnit, location: &str) -> Result<(f64, &'static str)> {
        match (self.opts.height_unit, file) {
            (Some(u), f) => {
                match f {
                    FileUnit::Length(fu) if (fu.to_metres - u.to_metres).abs() > 1e-12 * u.to_metres => {
                        self.notes.push(format!(
                            "the height unit given in the options ({:e} m) overrides the file's ({:e} m)",
                            u.to_metres, fu.to_metres
                        ))
                    }
                    FileUnit::Other(s) => self.notes.push(format!(
                        "the file's height unit {s:?} is not a length; the options' unit ({:e} m) is used",
                        u.to_metres
                    )),
                    _ => {}
                }
                Ok((u.to_metres, "options"))
            }
            (None, FileUnit::Length(u)) => Ok((u.to_metres, "file")),
            (None, FileUnit::Other(s)) => Err(self.err(
                location,
                format!("the heights are in {s:?}, not a length; give the length per unit with --height-unit"),
            )),
            (None, FileUnit::Absent) => Err(TopographyError::MissingUnit {
                path: self.path.to_path_buf(),
                format: self.format,
                what: "heights",
            }),
        }
    }

    /// Builds the measurement: heights (file units) scaled to metres, validated.
    pub fn finish(
        self,
        nx: usize,
        ny: usize,
        (dx, dy, spacing_from): (f64, f64, &'static str),
        (unit, unit_from): (f64, &'static str),
        mut z: Vec<f64>,
    ) -> Result<Measurement> {
        let bad = z.iter().filter(|v| !v.is_finite()).count();
        if bad > 0 {
            let k = z.iter().position(|v| !v.is_finite()).unwrap_or(0);
            return Err(self.err(
                "data",
                format!(
                    "{bad} of {} heights are not finite (NaN or infinite: invalid or missing points), \
                     the first at column {} row {} (0-based); fill or crop them first",
                    z.len(),
                    k % nx.max(1),
                    k / nx.max(1)
                ),
            ));
        }
        if unit != 1.0 {
            z.iter_mut().for_each(|v| *v *= unit);
        }
        let map = HeightMap::new(nx, ny, dx, dy, z).map_err(|e| self.err("grid", e.to_string()))?;
        Ok(Measurement {
            map,
            source: Source {
                path: self.path.display().to_string(),
                format: self.format,
                spacing_from,
                height_unit_from: unit_from,
                height_unit: unit,
                title: self.title,
                notes: self.notes,
            },
        })
    }
}
