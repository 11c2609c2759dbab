//! Text matrices and x/y/z columns.
//!
//! Header convention (any `#` line; keys case-insensitive, `=` or `:` between key and value):
//!
//! * `# spacing = 10 nm` (both directions), `# dx = ...`, `# dy = ...` (a length with an
//!   optional unit; metres if none);
//! * `# height_unit = nm` (or `z_unit`), `# xy_unit = um` (xyz coordinates);
//! * `# format = xyz` makes a text file an xyz file;
//! * Gwyddion's ASCII export is understood: `# Width: 5.000 µm`, `# Height: 5.000 µm` (the
//!   scan size in x and y), `# Value units: m`.
//!
//! A header of plain `key=value` lines before the matrix (no `#`; a line whose first field is
//! not a number) is read too, as a common instrument export writes it:
//!
//! ```text
//! h=650 w=512
//! pixel size=0.1 um
//! data unit=rad
//! height conversion factor (-> m)=6.3e-8
//! ```
//!
//! `h` and `w` are the numbers of rows and columns (checked against the matrix), `pixel size`
//! the spacing in both directions, `height conversion factor (-> U)` the length unit `U`
//! (metres if absent) per stored value, which makes the `data unit` (here a phase in rad)
//! irrelevant; without a factor a `data unit` that is a length is the height unit. Any
//! other `key=value` line is skipped.
//!
//! Undefined points: `NaN`, `nan`, `inf`, `BAD` (any case) in the matrix or in the z column.

use std::fmt::Write as _;
use std::path::Path;

use super::{FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::{read_bounded, Format};
use crate::map::{parse_length, HeightMap, LengthUnit};

#[derive(Default)]
struct Header {
    dx: Option<f64>,
    dy: Option<f64>,
    width: Option<f64>,
    height: Option<f64>,
    z_unit: Option<(FileUnit, usize)>,
    xy_unit: Option<LengthUnit>,
    xyz: bool,
    /// `h=` and `w=` of a plain header (rows, columns), with their line.
    rows: Option<(u64, usize)>,
    cols: Option<(u64, usize)>,
    /// `height conversion factor (-> U)=f`: metres per stored value, with its line.
    conversion: Option<(f64, usize)>,
    /// `data unit=...`, with its line.
    data_unit: Option<(FileUnit, usize)>,
}

/// Whether a line (not a `#` comment) is a plain `key=value` header line: its first field
/// is not a number (nor an undefined-point word) and it holds `=` or `:`.
fn is_plain_header(t: &str) -> bool {
    if t.starts_with('#') || !(t.contains('=') || t.contains(':')) {
        return false;
    }
    let first = split_fields(t).into_iter().next().unwrap_or("");
    parse_number(first).is_none()
}

/// A number, or NaN for an undefined-point word (`NaN`, `inf`, `BAD`, any case).
fn parse_number(f: &str) -> Option<f64> {
    match f.parse::<f64>() {
        Ok(v) => Some(if v.is_finite() { v } else { f64::NAN }),
        Err(_) if f.eq_ignore_ascii_case("bad") => Some(f64::NAN),
        Err(_) => None,
    }
}

/// Reads a text matrix (see the module docs for the header convention).
pub fn read_text_matrix(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Measurement> {
    let path = path.as_ref();
    decode_text(path, &read_bounded(path, opts.max_bytes)?, opts, false)
}

/// Reads x/y/z columns on a regular grid (any point order).
pub fn read_xyz(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Measurement> {
    let path = path.as_ref();
    decode_text(path, &read_bounded(path, opts.max_bytes)?, opts, true)
}

fn split_fields(line: &str) -> Vec<&str> {
    if line.contains(';') {
        line.split(';').map(str::trim).collect()
    } else if line.contains(',') {
        line.split(',').map(str::trim).collect()
    } else {
        line.split_whitespace().collect()
    }
}

pub(crate) fn decode_text(
    path: &Path,
    bytes: &[u8],
    opts: &ReadOptions,
    xyz: bool,
) -> Result<Measurement> {
    let mut st = Settle::new(path, if xyz { Format::Xyz } else { Format::Text }, opts);
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let line = bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count()
                + 1;
            return Err(st.err(
                format!("line {line}"),
                format!(
                    "not UTF-8 text: a binary file whose format was not recognised (the formats read: {}); \
                     name its format, check the extension, or export it as .x3p",
                    Format::names()
                ),
            ));
        }
    };
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut h = Header {
        xyz,
        ..Header::default()
    };
    // Pass 1: header lines.
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if is_plain_header(t) {
            plain_header(&st, &mut h, t, k + 1)?;
            continue;
        }
        let Some(c) = line.trim_start().strip_prefix('#') else {
            continue;
        };
        let Some(sep) = c.find(['=', ':']) else {
            continue;
        };
        let key = c[..sep].trim().to_ascii_lowercase();
        let value = c[sep + 1..].trim();
        let at = format!("line {}", k + 1);
        let length =
            |v: &str| parse_length(v).map_err(|e| st.err(&at, format!("{key} = {v:?}: {e}")));
        match key.as_str() {
            "spacing" => {
                let v = length(value)?;
                h.dx = Some(v);
                h.dy = Some(v);
            }
            "dx" | "x_spacing" => h.dx = Some(length(value)?),
            "dy" | "y_spacing" => h.dy = Some(length(value)?),
            "width" => h.width = Some(length(value)?),
            "height" => h.height = Some(length(value)?),
            "height_unit" | "z_unit" | "value units" => {
                let u = FileUnit::from_file(value);
                if let FileUnit::Other(s) = &u {
                    if value.parse::<f64>().is_ok() {
                        // a bare factor is accepted here
                        let f = LengthUnit::parse(s).map_err(|e| st.err(&at, e.to_string()))?;
                        h.z_unit = Some((FileUnit::Length(f), k + 1));
                        continue;
                    }
                }
                h.z_unit = Some((u, k + 1));
            }
            "xy_unit" | "x_unit" => {
                h.xy_unit = Some(
                    LengthUnit::parse(value).map_err(|e| st.err(&at, format!("xy_unit: {e}")))?,
                )
            }
            "format" => match value.to_ascii_lowercase().as_str() {
                "xyz" => h.xyz = true,
                "matrix" | "text" => h.xyz = false,
                other => {
                    return Err(st.err(&at, format!("format = {other:?}: expected matrix or xyz")))
                }
            },
            _ => {}
        }
    }
    if h.xyz {
        st.format = Format::Xyz;
        return decode_xyz_body(st, text, h);
    }
    // Pass 2: the matrix.
    let mut z: Vec<f64> = Vec::new();
    let mut ncols = 0usize;
    let mut first_line = 0usize;
    let mut nrows = 0usize;
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') || is_plain_header(t) {
            continue;
        }
        let fields = split_fields(t);
        if nrows == 0 {
            ncols = fields.len();
            first_line = k + 1;
        } else if fields.len() != ncols {
            return Err(st.err(
                format!("line {}", k + 1),
                format!(
                    "{} values, but the first data line (line {first_line}) has {ncols}: rows must have equal lengths",
                    fields.len()
                ),
            ));
        }
        if z.len() + fields.len() > opts.max_points {
            st.check_points(nrows as u64 + 1, ncols as u64)?;
        }
        for (c, f) in fields.iter().enumerate() {
            let v = parse_value(&st, f, k + 1, c + 1)?;
            z.push(v);
        }
        nrows += 1;
    }
    if nrows == 0 {
        return Err(st.err("data", "no data lines (only comments or blank lines)"));
    }
    for (name, declared, found) in [("h", h.rows, nrows), ("w", h.cols, ncols)] {
        if let Some((v, line)) = declared {
            if v != found as u64 {
                return Err(st.err(
                    format!("line {line}"),
                    format!(
                        "{name}={v}, but the matrix has {found} {}",
                        if name == "h" { "rows" } else { "columns" }
                    ),
                ));
            }
        }
    }
    if let Some((f, line)) = h.conversion {
        let u = LengthUnit::factor(f).map_err(|e| st.err(format!("line {line}"), e.to_string()))?;
        h.z_unit = Some((FileUnit::Length(u), line));
    } else if h.z_unit.is_none() {
        h.z_unit = h.data_unit.take();
    }
    let file_spacing = match (
        h.dx.or(h.width.map(|w| w / ncols as f64)),
        h.dy.or(h.height.map(|w| w / nrows as f64)),
    ) {
        (Some(x), Some(y)) => Some((x, y)),
        (Some(x), None) => Some((x, x)),
        (None, Some(y)) => Some((y, y)),
        (None, None) => None,
    };
    let spacing = st.spacing(file_spacing)?;
    let (unit, at) = h.z_unit.map_or((FileUnit::Absent, 0), |(u, l)| (u, l));
    let unit = st.height_unit(unit, &format!("line {at}"))?;
    st.finish(ncols, nrows, spacing, unit, z)
}

/// One plain `key=value` header line (see the module docs): `h=650 w=512` (several pairs on
/// a line), `pixel size=0.1 um`, `data unit=rad`, `height conversion factor (-> m)=6e-8`.
fn plain_header(st: &Settle, h: &mut Header, t: &str, line: usize) -> Result<()> {
    let at = format!("line {line}");
    let tokens: Vec<&str> = t.split_whitespace().collect();
    let pairs: Vec<(&str, &str)> = if tokens.len() > 1 && tokens.iter().all(|w| w.contains('=')) {
        tokens.iter().filter_map(|w| w.split_once('=')).collect()
    } else {
        match t.split_once('=').or_else(|| t.split_once(':')) {
            Some(p) => vec![p],
            None => return Ok(()),
        }
    };
    for (key, value) in pairs {
        let key = key.trim().to_ascii_lowercase();
        let value = value.trim();
        let count = |v: &str| {
            v.parse::<u64>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| st.err(&at, format!("{key}={v:?} is not a positive integer")))
        };
        if key == "h" {
            h.rows = Some((count(value)?, line));
        } else if key == "w" {
            h.cols = Some((count(value)?, line));
        } else if key == "pixel size" {
            let v = parse_length(value)
                .map_err(|e| st.err(&at, format!("pixel size = {value:?}: {e}")))?;
            h.dx = Some(v);
            h.dy = Some(v);
        } else if key == "data unit" {
            h.data_unit = Some((FileUnit::from_file(value), line));
        } else if let Some(rest) = key.strip_prefix("height conversion factor") {
            // "(-> m)": the unit the factor converts to, metres if absent
            let unit = rest
                .trim()
                .strip_prefix('(')
                .and_then(|r| r.strip_suffix(')'))
                .map(|r| r.trim().trim_start_matches("->").trim())
                .unwrap_or("");
            let to = if unit.is_empty() {
                LengthUnit::METRE
            } else {
                LengthUnit::parse(unit)
                    .map_err(|e| st.err(&at, format!("height conversion factor: {e}")))?
            };
            let f = value
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v > 0.0)
                .ok_or_else(|| {
                    st.err(
                        &at,
                        format!("height conversion factor = {value:?} is not a positive number"),
                    )
                })?;
            h.conversion = Some((f * to.to_metres, line));
        }
    }
    Ok(())
}

/// A height: a number, or NaN for an undefined point (`NaN`, `inf`, `BAD`).
fn parse_value(st: &Settle, f: &str, line: usize, col: usize) -> Result<f64> {
    match parse_number(f) {
        Some(v) => Ok(v),
        None => Err(st.err(
            format!("line {line}, column {col}"),
            if f.is_empty() {
                "empty field".to_string()
            } else {
                format!("{f:?} is not a number")
            },
        )),
    }
}

/// Distinct values of a coordinate, merged within `tol`, sorted.
fn distinct(mut v: Vec<f64>, tol: f64) -> Vec<f64> {
    v.sort_by(|a, b| a.total_cmp(b));
    let mut out: Vec<f64> = Vec::new();
    for x in v {
        match out.last() {
            Some(&l) if x - l <= tol => {}
            _ => out.push(x),
        }
    }
    out
}

fn decode_xyz_body(mut st: Settle, text: &str, h: Header) -> Result<Measurement> {
    let opts = st.opts;
    let (mut xs, mut ys, mut zs, mut lines) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') || is_plain_header(t) {
            continue;
        }
        let f = split_fields(t);
        if f.len() != 3 {
            return Err(st.err(
                format!("line {}", k + 1),
                format!("{} values: an xyz file has three columns x, y, z", f.len()),
            ));
        }
        if zs.len() >= opts.max_points {
            st.check_points(zs.len() as u64 + 1, 1)?;
        }
        for (c, v) in [(1, f[0]), (2, f[1])] {
            let x = parse_value(&st, v, k + 1, c)?;
            if !x.is_finite() {
                return Err(st.err(
                    format!("line {}, column {c}", k + 1),
                    format!("{v:?}: an x or y coordinate must be a finite number"),
                ));
            }
        }
        xs.push(parse_value(&st, f[0], k + 1, 1)?);
        ys.push(parse_value(&st, f[1], k + 1, 2)?);
        zs.push(parse_value(&st, f[2], k + 1, 3)?);
        lines.push(k + 1);
    }
    let n = zs.len();
    if n == 0 {
        return Err(st.err("data", "no data lines"));
    }
    let axis = |st: &Settle, v: &[f64], name: &str| -> Result<(f64, f64, usize)> {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let tol = 1e-9 * (hi - lo).max(lo.abs().max(hi.abs()));
        let d = distinct(v.to_vec(), tol);
        if d.len() < 3 {
            return Err(st.err(
                "grid",
                format!("{} distinct {name} values: a map needs at least 3", d.len()),
            ));
        }
        let step = (hi - lo) / (d.len() - 1) as f64;
        for (k, &x) in d.iter().enumerate() {
            if ((x - lo) / step - k as f64).abs() > 1e-3 {
                return Err(st.err(
                    "grid",
                    format!(
                        "the {name} values are not on a regular grid: {} distinct values from {lo:e} to {hi:e}, \
                         but value {k} is {x:e} (expected {:e})",
                        d.len(),
                        lo + k as f64 * step
                    ),
                ));
            }
        }
        Ok((lo, step, d.len()))
    };
    let (x0, sx, nx) = axis(&st, &xs, "x")?;
    let (y0, sy, ny) = axis(&st, &ys, "y")?;
    st.check_points(nx as u64, ny as u64)?;
    if nx * ny != n {
        return Err(st.err(
            "grid",
            format!("{n} points, but their x and y values span a {nx} x {ny} grid ({} points): points are missing or repeated", nx * ny),
        ));
    }
    let mut z = vec![f64::NAN; n];
    let mut from = vec![0usize; n];
    for k in 0..n {
        let i = ((xs[k] - x0) / sx).round() as usize;
        let j = ((ys[k] - y0) / sy).round() as usize;
        let p = j * nx + i;
        if from[p] != 0 {
            return Err(st.err(
                format!("line {}", lines[k]),
                format!("point ({:e}, {:e}) repeats line {}", xs[k], ys[k], from[p]),
            ));
        }
        from[p] = lines[k];
        z[p] = zs[k];
    }
    let xy = match (opts.xy_unit, h.xy_unit) {
        (Some(u), Some(f)) => {
            if (u.to_metres - f.to_metres).abs() > 1e-12 * u.to_metres {
                st.notes.push(format!(
                    "the x/y unit given in the options ({:e} m) overrides the file's ({:e} m)",
                    u.to_metres, f.to_metres
                ));
            }
            u
        }
        (Some(u), None) | (None, Some(u)) => u,
        (None, None) => {
            return Err(crate::TopographyError::MissingUnit {
                path: st.path.to_path_buf(),
                format: st.format,
                what: "x/y coordinates (# xy_unit = um, or the option)",
            })
        }
    };
    let spacing = st.spacing(Some((sx * xy.to_metres, sy * xy.to_metres)))?;
    let (unit, at) = h.z_unit.map_or((FileUnit::Absent, 0), |(u, l)| (u, l));
    let unit = st.height_unit(unit, &format!("line {at}"))?;
    st.finish(nx, ny, spacing, unit, z)
}

/// A text matrix of the map in metres, with the header convention of this module
/// (`# dx`, `# dy`, `# height_unit = m`), values in Rust's shortest round-trip form.
pub fn encode_text_matrix(map: &HeightMap) -> String {
    let mut s = String::with_capacity(map.heights().len() * 24);
    let _ = writeln!(s, "# height map written by the stiction topography crate");
    let _ = writeln!(s, "# dx = {:e} m", map.dx());
    let _ = writeln!(s, "# dy = {:e} m", map.dy());
    let _ = writeln!(s, "# height_unit = m");
    for row in map.heights().chunks(map.nx()) {
        for (i, v) in row.iter().enumerate() {
            if i > 0 {
                s.push(' ');
            }
            let _ = write!(s, "{v:e}");
        }
        s.push('\n');
    }
    s
}

/// x y z columns of the map in metres (`# xy_unit = m`, `# height_unit = m`), row by row.
pub fn encode_xyz(map: &HeightMap) -> String {
    let mut s = String::with_capacity(map.heights().len() * 64);
    let _ = writeln!(s, "# format = xyz");
    let _ = writeln!(s, "# xy_unit = m");
    let _ = writeln!(s, "# height_unit = m");
    for j in 0..map.ny() {
        for i in 0..map.nx() {
            let _ = writeln!(
                s,
                "{:e} {:e} {:e}",
                i as f64 * map.dx(),
                j as f64 * map.dy(),
                map.at(i, j)
            );
        }
    }
    s
}
