//! Readers (and writers) of height-map files.
//!
//! Every reader takes the whole file through a bounded read (at most
//! [`ReadOptions::max_bytes`], so a FIFO or `/dev/zero` cannot exhaust memory), checks the
//! grid a file declares against [`ReadOptions::max_points`] before allocating it, and
//! returns a [`TopographyError`] naming the file, the format, where (line and column,
//! header field, object component, archive entry) and what is wrong.
//!
//! The open exchange formats (text, xyz, npy, gsf, gwy, x3p) are read and written; the
//! instruments' own formats (Nanoscope, Wyko `.opd`, Zygo MetroPro, Digital Surf `.sur`,
//! Sensofar `.plu`/`.plux`, Keyence `.vk4`, ISO 25178-71 `.sdf`) are read, each from the
//! published or documented layout its module cites; variants they do not read are named and
//! refused with what to export instead. A file's channels are all listed in
//! [`Source::channels`]; the first height channel is read unless [`ReadOptions::channel`]
//! names another. Undefined points (the instruments' markers, NaN) become NaN inside the
//! readers and are then refused or filled as [`ReadOptions::undefined`] says
//! ([`Undefined`]), and counted in [`Source::undefined_points`]. A 1-D profile is refused.

use std::fmt;
use std::io::Read;
use std::path::Path;
use std::str::FromStr;

use serde::Serialize;

use crate::error::{Result, TopographyError};
use crate::map::{HeightMap, LengthUnit};

pub(crate) mod bin;
mod gsf;
mod gwy;
mod metropro;
mod nanoscope;
mod npy;
mod opd;
mod plu;
mod sdf;
mod sur;
mod text;
mod vk4;
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
    /// separated), `#` comment lines with `key = value` settings, or a header of
    /// `h=`, `w=`, `pixel size=`, `height conversion factor (-> m)=` lines (docs/topography.md).
    Text,
    /// Text x, y, z columns on a regular grid, in any order.
    Xyz,
    /// NumPy `.npy`, a 2-D array (rows = y) of floats or integers, C or Fortran order.
    Npy,
    /// Gwyddion Simple Field `.gsf`.
    Gsf,
    /// Gwyddion native `.gwy` (GWYP serialised objects); every channel `/N/data`.
    Gwy,
    /// ISO 25178-72 `.x3p` (XML 3D surface profile: zip with main.xml and binary data).
    X3p,
    /// Bruker / Veeco / Digital Instruments Nanoscope (`.spm`, `.di`, `.001`, ...): text
    /// header `\*File list` ... `\*File list end`, 16- or 32-bit images.
    Nanoscope,
    /// Wyko / Bruker Vision `.opd` (binary directory of blocks).
    Opd,
    /// Zygo MetroPro `.dat` (big-endian binary header, phase and intensity arrays); the
    /// HDF5 `.datx` is recognised and refused.
    Metropro,
    /// Digital Surf `.sur` (MountainsMap), plain or compressed, one or several objects.
    Sur,
    /// Sensofar `.plu` (SensoSCAN binary) and `.plux` (zip with index.xml).
    Plu,
    /// Keyence `.vk4` (the `.vk3`, `.vk6` and `.vk7` files are recognised and refused).
    Vk4,
    /// ISO 25178-71 / BCR surface data file `.sdf`, text or binary.
    Sdf,
}

impl Format {
    /// Every format, in the order of the docs.
    pub const ALL: [Format; 13] = [
        Format::Text,
        Format::Xyz,
        Format::Npy,
        Format::Gsf,
        Format::Gwy,
        Format::X3p,
        Format::Nanoscope,
        Format::Opd,
        Format::Metropro,
        Format::Sur,
        Format::Plu,
        Format::Vk4,
        Format::Sdf,
    ];

    /// The formats [`encode`] writes (the open exchange formats; the instruments' own
    /// formats are read only).
    pub const WRITABLE: [Format; 6] = [
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
            Format::Nanoscope => "nanoscope",
            Format::Opd => "opd",
            Format::Metropro => "metropro",
            Format::Sur => "sur",
            Format::Plu => "plu",
            Format::Vk4 => "vk4",
            Format::Sdf => "sdf",
        }
    }

    /// Every format's name, comma separated (for messages).
    pub fn names() -> String {
        Format::ALL.map(Format::name).join(", ")
    }

    /// Whether [`encode`] can write this format.
    pub fn has_writer(self) -> bool {
        Format::WRITABLE.contains(&self)
    }

    /// The usual file extension (without the dot).
    pub fn extension(self) -> &'static str {
        match self {
            Format::Text => "txt",
            Format::Nanoscope => "spm",
            Format::Metropro => "dat",
            other => other.name(),
        }
    }

    /// The format a file extension names, if any (`txt`, `csv`, `dat`, `asc` are text: a
    /// MetroPro `.dat` is told by its magic number first; `spm`, `di` and three digits
    /// (`001`) are Nanoscope).
    pub fn from_extension(ext: &str) -> Option<Format> {
        let e = ext.to_ascii_lowercase();
        match e.as_str() {
            "txt" | "csv" | "dat" | "asc" | "tsv" => Some(Format::Text),
            "xyz" => Some(Format::Xyz),
            "npy" => Some(Format::Npy),
            "gsf" => Some(Format::Gsf),
            "gwy" => Some(Format::Gwy),
            "x3p" => Some(Format::X3p),
            "spm" | "di" => Some(Format::Nanoscope),
            "opd" => Some(Format::Opd),
            "datx" => Some(Format::Metropro),
            "sur" => Some(Format::Sur),
            "plu" | "plux" => Some(Format::Plu),
            "vk4" | "vk3" | "vk6" | "vk7" => Some(Format::Vk4),
            "sdf" => Some(Format::Sdf),
            _ if e.len() == 3 && e.bytes().all(|b| b.is_ascii_digit()) => Some(Format::Nanoscope),
            _ => None,
        }
    }

    /// The format the bytes of a file announce by a magic number (or, for a zip archive,
    /// by its entries), if any.
    pub fn sniff(bytes: &[u8]) -> Option<Format> {
        let starts = |m: &[u8]| bytes.starts_with(m);
        if starts(b"\x93NUMPY") {
            Some(Format::Npy)
        } else if starts(b"GWYP") || starts(b"GWYO") {
            Some(Format::Gwy)
        } else if starts(b"Gwyddion Simple Field") {
            Some(Format::Gsf)
        } else if starts(b"PK\x03\x04") {
            Some(if plu::is_plux(bytes) {
                Format::Plu
            } else {
                Format::X3p
            })
        } else if nanoscope::MAGICS.iter().any(|m| starts(m)) {
            Some(Format::Nanoscope)
        } else if starts(opd::MAGIC) {
            Some(Format::Opd)
        } else if metropro::MAGICS.iter().any(|m| starts(m)) || starts(metropro::HDF5_MAGIC) {
            Some(Format::Metropro)
        } else if starts(sur::MAGIC) || starts(sur::MAGIC_COMPRESSED) {
            Some(Format::Sur)
        } else if vk4::MAGICS.iter().any(|m| starts(m)) {
            Some(Format::Vk4)
        } else if sdf::MAGICS.iter().any(|m| starts(m)) {
            Some(Format::Sdf)
        } else if plu::looks_like_plu(bytes) {
            Some(Format::Plu)
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
        let t = s.to_ascii_lowercase();
        if let Some(f) = Format::ALL.into_iter().find(|f| f.name() == t) {
            return Ok(f);
        }
        match t.as_str() {
            "txt" | "matrix" => Ok(Format::Text),
            "spm" | "di" | "bruker" | "veeco" => Ok(Format::Nanoscope),
            "wyko" => Ok(Format::Opd),
            "zygo" | "dat" => Ok(Format::Metropro),
            "plux" | "sensofar" => Ok(Format::Plu),
            "keyence" | "vk" => Ok(Format::Vk4),
            _ => Err(format!("unknown format {s:?}: one of {}", Format::names())),
        }
    }
}

/// What a reader does with undefined points (the instrument's markers of points it could
/// not measure, NaN or infinite values).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Undefined {
    /// Refuse the file, naming the count (the default: filling changes the statistics).
    #[default]
    Refuse,
    /// Fill them by harmonic (Laplace) interpolation from the defined neighbours
    /// ([`crate::fill_harmonic`]); the report's `source.notes` say so.
    Fill,
}

impl Undefined {
    /// The policy's name as accepted by [`Undefined::from_str`].
    pub fn name(self) -> &'static str {
        match self {
            Undefined::Refuse => "refuse",
            Undefined::Fill => "fill",
        }
    }
}

impl fmt::Display for Undefined {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Undefined {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "refuse" => Ok(Undefined::Refuse),
            "fill" => Ok(Undefined::Fill),
            _ => Err(format!("unknown policy {s:?}: refuse or fill")),
        }
    }
}

/// What the caller knows about a file, and the size caps.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReadOptions {
    /// Read as this format instead of guessing from the first bytes and the extension.
    pub format: Option<Format>,
    /// Grid spacing (m) for a format that lacks one (text matrix, npy, a gsf without
    /// XReal/YReal). If the file has one too, this one is used and the report says so.
    pub spacing: Option<f64>,
    /// Unit of the heights, for a file that does not state it (text, xyz, npy). Overrides
    /// the file's unit if it does (the report says so).
    pub height_unit: Option<LengthUnit>,
    /// Unit of the x and y coordinates of an xyz file that does not state it.
    pub xy_unit: Option<LengthUnit>,
    /// The channel to read: its name as listed in [`Source::channels`] (case-insensitive)
    /// or its 0-based index. None: the file's first height channel.
    pub channel: Option<String>,
    /// What to do with undefined points: refuse (default) or fill.
    pub undefined: Undefined,
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
            channel: None,
            undefined: Undefined::Refuse,
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
    /// The title of the channel read, if the file names it.
    pub title: Option<String>,
    /// Every channel of the file, in the file's order (a name or a 0-based index of this
    /// list chooses one; the default is the first height channel).
    pub channels: Vec<String>,
    /// Undefined points (the instrument's markers, NaN) in the channel read: 0, or the
    /// count that was filled (undefined points are refused unless filling was asked for).
    pub undefined_points: usize,
    /// Anything the reader did that the user should know (an option overriding the file, a
    /// channel chosen among several, points filled, ...).
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

/// Reads a height map, choosing the reader from `opts.format`, else the first bytes (magic
/// numbers), else the extension, else text.
pub fn read_path(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Measurement> {
    let path = path.as_ref();
    let bytes = read_bounded(path, opts.max_bytes)?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .and_then(Format::from_extension);
    let format = match opts.format {
        Some(f) => f,
        None => match Format::sniff(&bytes).or(ext) {
            Some(f) => f,
            None => {
                if std::str::from_utf8(&bytes).is_err() {
                    return Err(TopographyError::UnknownFormat {
                        path: path.to_path_buf(),
                        message: "binary data that carry none of the supported formats' magic numbers, and no known extension".to_string(),
                    });
                }
                Format::Text
            }
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
        Format::Nanoscope => nanoscope::decode(path, bytes, opts),
        Format::Opd => opd::decode(path, bytes, opts),
        Format::Metropro => metropro::decode(path, bytes, opts),
        Format::Sur => sur::decode(path, bytes, opts),
        Format::Plu => plu::decode(path, bytes, opts),
        Format::Vk4 => vk4::decode(path, bytes, opts),
        Format::Sdf => sdf::decode(path, bytes, opts),
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
/// state them). Only the open formats ([`Format::WRITABLE`]) have a writer.
pub fn encode(map: &HeightMap, format: Format) -> Result<Vec<u8>> {
    Ok(match format {
        Format::Text => encode_text_matrix(map).into_bytes(),
        Format::Xyz => encode_xyz(map).into_bytes(),
        Format::Npy => encode_npy(map),
        Format::Gsf => encode_gsf(map),
        Format::Gwy => encode_gwy(map),
        Format::X3p => encode_x3p(map)?,
        other => {
            return Err(TopographyError::param(
                "format",
                other,
                "an instrument's own format is read, not written: write x3p, gsf, gwy, npy, text or xyz",
            ))
        }
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
    /// The file's channels (empty: a single unnamed one).
    pub channels: Vec<String>,
}

/// A channel a reader found: its name and whether it holds heights (a length unit).
pub(crate) struct Channel {
    pub name: String,
    pub height: bool,
}

impl Channel {
    pub fn new(name: impl Into<String>, height: bool) -> Self {
        Channel {
            name: name.into(),
            height,
        }
    }
}

impl<'a> Settle<'a> {
    pub fn new(path: &'a Path, format: Format, opts: &'a ReadOptions) -> Self {
        Settle {
            path,
            format,
            opts,
            notes: Vec::new(),
            title: None,
            channels: Vec::new(),
        }
    }

    /// A file whose format is recognised but not read: named, with what to export instead.
    pub fn unsupported(&self, what: &str, instead: &str) -> TopographyError {
        self.err("format", format!("{what}: not supported; {instead}"))
    }

    /// Refuses a 1-D profile of `n` points.
    pub fn profile(&self, location: &str, n: u64) -> TopographyError {
        self.err(
            location,
            format!("a 1-D profile ({n} points): the model needs a 2-D height map"),
        )
    }

    /// Chooses the channel to read among `list` (every channel of the file, in order):
    /// `opts.channel` by name (case-insensitive) or 0-based index, else the first height
    /// channel. Records the list, the title and, for several channels, a note.
    pub fn choose_channel(&mut self, list: &[Channel]) -> Result<usize> {
        self.channels = list.iter().map(|c| c.name.clone()).collect();
        let describe = || {
            list.iter()
                .enumerate()
                .map(|(k, c)| {
                    format!(
                        "{k} {:?}{}",
                        c.name,
                        if c.height { " (heights)" } else { "" }
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        };
        if list.is_empty() {
            return Err(self.err("channels", "the file holds no image channel"));
        }
        let k = match self.opts.channel.as_deref() {
            Some(want) => find_channel(list.iter().map(|c| c.name.as_str()), want)
                .ok_or_else(|| {
                    self.err(
                        "channel",
                        format!(
                            "{want:?} is not a channel of this file (give a name or a 0-based index); its channels: {}",
                            describe()
                        ),
                    )
                })?,
            None => list.iter().position(|c| c.height).ok_or_else(|| {
                self.err(
                    "channels",
                    format!(
                        "no height channel among the file's channels ({}); choose one with --channel (with --height-unit for a channel that is not a length), or export the heights as .x3p",
                        describe()
                    ),
                )
            })?,
        };
        if list.len() > 1 {
            self.notes.push(format!(
                "the file has {} channels ({}); channel {k} ({:?}) was read",
                list.len(),
                describe(),
                list[k].name
            ));
        }
        self.title = Some(list[k].name.clone());
        Ok(k)
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

    /// Builds the measurement: refuses a 1-D profile, counts the undefined (non-finite)
    /// heights and refuses or fills them as `opts.undefined` says, scales the heights (file
    /// units) to metres and validates the map.
    pub fn finish(
        mut self,
        nx: usize,
        ny: usize,
        (dx, dy, spacing_from): (f64, f64, &'static str),
        (unit, unit_from): (f64, &'static str),
        mut z: Vec<f64>,
    ) -> Result<Measurement> {
        if self.channels.is_empty() {
            let name = self.title.clone().unwrap_or_else(|| "heights".to_string());
            if let Some(want) = self.opts.channel.as_deref() {
                if find_channel(std::iter::once(name.as_str()), want).is_none() {
                    return Err(self.err(
                        "channel",
                        format!("{want:?} is not a channel of this file: it holds one, 0 {name:?}"),
                    ));
                }
            }
            self.channels.push(name);
        }
        let n = z.len();
        if (nx == 1 || ny == 1) && n >= 2 {
            return Err(self.profile("grid", n as u64));
        }
        let bad = z.iter().filter(|v| !v.is_finite()).count();
        if bad > 0 {
            let k = z.iter().position(|v| !v.is_finite()).unwrap_or(0);
            let (col, row) = (k % nx.max(1), k / nx.max(1));
            if bad == n {
                return Err(self.err(
                    "data",
                    format!("all {n} heights are undefined (not finite, or marked invalid by the instrument): nothing to analyse"),
                ));
            }
            match self.opts.undefined {
                Undefined::Refuse => {
                    return Err(self.err(
                        "data",
                        format!(
                            "{bad} of {n} heights are undefined (not finite: NaN, infinite, or marked invalid by the instrument), \
                             the first at column {col} row {row} (0-based); read them with --undefined fill \
                             (harmonic interpolation from the defined neighbours), or crop them first"
                        ),
                    ));
                }
                Undefined::Fill => {
                    let s = crate::fill::fill_harmonic(nx, ny, &mut z)
                        .map_err(|e| self.err("data", e.to_string()))?;
                    self.notes.push(format!(
                        "{bad} of {n} heights were undefined (the first at column {col} row {row}) and were filled by \
                         harmonic (Laplace) interpolation from their defined neighbours ({} conjugate-gradient iterations, \
                         relative residual {:.1e}): filled points carry no measured roughness",
                        s.iterations, s.relative_residual
                    ));
                }
            }
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
                channels: self.channels,
                undefined_points: bad,
                notes: self.notes,
            },
        })
    }
}

/// The index of the channel `want` names: a name (case-insensitive, surrounding spaces
/// ignored) first, else a 0-based index.
fn find_channel<'a>(names: impl Iterator<Item = &'a str> + Clone, want: &str) -> Option<usize> {
    let w = want.trim();
    names
        .clone()
        .position(|n| n.trim().eq_ignore_ascii_case(w))
        .or_else(|| w.parse::<usize>().ok().filter(|&k| k < names.count()))
}
