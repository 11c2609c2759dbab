//! ISO 25178-71 surface data files `.sdf` (the SDF of the EU BCR "SURFSTAND" project, text
//! and binary).
//!
//! Layout, from ISO 25178-71:2012 (software measurement standards: file format) as Gwyddion
//! (`modules/file/sdfile.c`) and SurfaceTopography (`IO/SDF.py`) read it:
//!
//! * text (`aBCR-1.0`, `aISO-1.0`): the version on the first line, then `Key = value` lines
//!   (`;` starts a comment) with `ManufacID`, `CreateDate`, `ModDate`, `NumPoints` (x
//!   points), `NumProfiles` (y points), `Xscale`, `Yscale` (m per point), `Zscale` (m per
//!   unit), `Zresolution`, `Compression`, `DataType`, `CheckType`, a line `*`, the values
//!   (whitespace separated, row by row; `BAD` is a point not measured), `*`, then an optional
//!   trailer;
//! * binary (`bBCR-1.0`, `bISO-1.0`, `bCR-1.0`): an 81-byte little-endian header, version
//!   (8), ManufacID (10), CreateDate (12), ModDate (12), NumPoints, NumProfiles (u16),
//!   Xscale, Yscale, Zscale, Zresolution (f64), Compression, DataType, CheckType (u8), then
//!   the values;
//! * DataType: 0 u8, 1 u16, 2 u32, 3 f32, 4 i8, 5 i16, 6 i32, 7 f64; an i16 or i32 at its
//!   minimum, or a NaN, is a point not measured (ISO 25178-71).
//!
//! Heights: value x Zscale (m). Compression other than 0 is refused; a single profile
//! (NumProfiles = 1) is refused as 1-D.

use std::path::Path;

use super::bin::{product, Bin};
use super::{FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::Format;
use crate::map::LengthUnit;

/// The first bytes of the text and binary variants.
pub(crate) const MAGICS: [&[u8]; 5] = [b"aBCR-", b"aISO-", b"bBCR-", b"bISO-", b"bCR-"];
const BIN_HEADER: usize = 81;
const SIZES: [u64; 8] = [1, 2, 4, 4, 1, 2, 4, 8];

struct Params {
    nx: u64,
    ny: u64,
    xscale: f64,
    yscale: f64,
    zscale: f64,
    compression: i64,
    data_type: i64,
    check_type: i64,
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Sdf, opts);
    let (p, z) =
        match bytes.first() {
            Some(b'a') => text(&st, bytes)?,
            Some(b'b') => binary(&st, bytes)?,
            _ => return Err(st.err(
                "version",
                "does not start with aBCR-/aISO- (text) or bBCR-/bISO- (binary): not an SDF file",
            )),
        };
    if p.check_type != 0 {
        st.notes.push(format!(
            "CheckType = {}: the checksum is not verified",
            p.check_type
        ));
    }
    let file_spacing =
        (p.xscale.is_finite() && p.xscale > 0.0 && p.yscale.is_finite() && p.yscale > 0.0)
            .then_some((p.xscale, p.yscale));
    if file_spacing.is_none() && opts.spacing.is_none() {
        return Err(st.err(
            "header Xscale, Yscale",
            format!("{} x {}: not positive spacings", p.xscale, p.yscale),
        ));
    }
    let spacing = st.spacing(file_spacing)?;
    if !(p.zscale.is_finite() && p.zscale != 0.0) {
        return Err(st.err("header Zscale", format!("{}: not a usable scale", p.zscale)));
    }
    let z = z.into_iter().map(|v| v * p.zscale).collect();
    let unit = st.height_unit(FileUnit::Length(LengthUnit::METRE), "header Zscale")?;
    st.finish(p.nx as usize, p.ny as usize, spacing, unit, z)
}

fn check(st: &Settle, p: &Params) -> Result<usize> {
    if p.compression != 0 {
        return Err(st.unsupported(
            &format!("a compressed SDF file (Compression = {})", p.compression),
            "write it uncompressed, or export it as .x3p",
        ));
    }
    if !(0..8).contains(&p.data_type) {
        return Err(st.err(
            "header DataType",
            format!("{}: expected 0 to 7", p.data_type),
        ));
    }
    if p.nx == 0 || p.ny == 0 {
        return Err(st.err(
            "header NumPoints, NumProfiles",
            format!("an empty grid ({} x {})", p.nx, p.ny),
        ));
    }
    if p.ny == 1 || p.nx == 1 {
        return Err(st.profile("header NumProfiles", p.nx.saturating_mul(p.ny)));
    }
    st.check_points(p.nx, p.ny)
}

fn undefined(data_type: i64, v: f64) -> bool {
    match data_type {
        5 => v == f64::from(i16::MIN),
        6 => v == f64::from(i32::MIN),
        _ => !v.is_finite(),
    }
}

fn binary(st: &Settle, bytes: &[u8]) -> Result<(Params, Vec<f64>)> {
    let b = Bin(bytes);
    if bytes.len() < BIN_HEADER {
        return Err(st.err(
            "header",
            format!(
                "{} bytes: the binary header has {BIN_HEADER} (truncated)",
                bytes.len()
            ),
        ));
    }
    let f = |at: usize| b.f64_le(at).unwrap_or(f64::NAN);
    let p = Params {
        nx: b.u16_le(42).unwrap_or(0) as u64,
        ny: b.u16_le(44).unwrap_or(0) as u64,
        xscale: f(46),
        yscale: f(54),
        zscale: f(62),
        compression: i64::from(b.u8(78).unwrap_or(0)),
        data_type: i64::from(b.u8(79).unwrap_or(0)),
        check_type: i64::from(b.u8(80).unwrap_or(0)),
    };
    let n = check(st, &p)?;
    let size = SIZES[p.data_type as usize];
    let need = product(&[p.nx, p.ny, size]).unwrap_or(u64::MAX);
    let data = b.slice(BIN_HEADER, need as usize).filter(|_| need <= bytes.len() as u64).ok_or_else(|| {
        st.err(
            "data",
            format!(
                "{} bytes after the header, but {} x {} values of {size} bytes need {need} (truncated file?)",
                bytes.len() - BIN_HEADER,
                p.nx,
                p.ny
            ),
        )
    })?;
    let mut z = Vec::with_capacity(n);
    for v in data.chunks_exact(size as usize) {
        let x = match p.data_type {
            0 => f64::from(v[0]),
            1 => f64::from(u16::from_le_bytes([v[0], v[1]])),
            2 => f64::from(u32::from_le_bytes([v[0], v[1], v[2], v[3]])),
            3 => f64::from(f32::from_le_bytes([v[0], v[1], v[2], v[3]])),
            4 => f64::from(v[0] as i8),
            5 => f64::from(i16::from_le_bytes([v[0], v[1]])),
            6 => f64::from(i32::from_le_bytes([v[0], v[1], v[2], v[3]])),
            _ => f64::from_le_bytes([v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]]),
        };
        z.push(if undefined(p.data_type, x) {
            f64::NAN
        } else {
            x
        });
    }
    Ok((p, z))
}

fn text(st: &Settle, bytes: &[u8]) -> Result<(Params, Vec<f64>)> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        st.err(
            format!("byte {}", e.valid_up_to()),
            "not text: a text SDF (first byte 'a') must be ASCII",
        )
    })?;
    let mut keys: Vec<(String, String, usize)> = Vec::new();
    let mut found_star = false;
    let mut data_start = 0usize;
    let mut offset = 0usize;
    for (k, raw) in text.split('\n').enumerate() {
        offset += raw.len() + 1;
        let l = raw.trim();
        if k == 0 || l.is_empty() || l.starts_with(';') {
            continue;
        }
        if l.starts_with('*') {
            found_star = true;
            data_start = offset.min(text.len());
            break;
        }
        let (key, value) = match l.split_once('=') {
            Some((a, b)) => (a.trim(), b.trim()),
            None => match l.split_once(char::is_whitespace) {
                Some((a, b)) => (a.trim(), b.trim()),
                None => (l, ""),
            },
        };
        keys.push((key.to_ascii_lowercase(), value.to_string(), k + 1));
    }
    if !found_star {
        return Err(st.err("header", "no line * ends the header (truncated file?)"));
    }
    let get = |name: &str| keys.iter().find(|e| e.0 == name.to_ascii_lowercase());
    let int = |name: &str, default: Option<i64>| -> Result<i64> {
        match get(name) {
            None => default.ok_or_else(|| st.err(format!("header {name}"), "missing")),
            Some((_, v, line)) => v.parse::<i64>().map_err(|_| {
                st.err(
                    format!("header {name} (line {line})"),
                    format!("{v:?} is not an integer"),
                )
            }),
        }
    };
    let real = |name: &str| -> Result<f64> {
        match get(name) {
            None => Err(st.err(format!("header {name}"), "missing")),
            Some((_, v, line)) => v.parse::<f64>().map_err(|_| {
                st.err(
                    format!("header {name} (line {line})"),
                    format!("{v:?} is not a number"),
                )
            }),
        }
    };
    let count = |name: &str| -> Result<u64> {
        let v = int(name, None)?;
        u64::try_from(v).map_err(|_| st.err(format!("header {name}"), format!("{v} is negative")))
    };
    let p = Params {
        nx: count("NumPoints")?,
        ny: count("NumProfiles")?,
        xscale: real("Xscale")?,
        yscale: real("Yscale")?,
        zscale: real("Zscale")?,
        compression: int("Compression", Some(0))?,
        data_type: int("DataType", None)?,
        check_type: int("CheckType", Some(0))?,
    };
    let n = check(st, &p)?;
    let body = &text[data_start..];
    let body = body.split('*').next().unwrap_or("");
    let mut z = Vec::with_capacity(n);
    for (k, tok) in body.split_whitespace().enumerate() {
        if k >= n {
            return Err(st.err(
                "data",
                format!("more than NumPoints x NumProfiles = {n} values before the closing *"),
            ));
        }
        let v = if tok.eq_ignore_ascii_case("bad") {
            f64::NAN
        } else {
            tok.parse::<f64>().map_err(|_| {
                st.err(
                    format!("data value {k}"),
                    format!("{tok:?} is not a number"),
                )
            })?
        };
        z.push(if undefined(p.data_type, v) {
            f64::NAN
        } else {
            v
        });
    }
    if z.len() != n {
        return Err(st.err(
            "data",
            format!(
                "{} values, but NumPoints x NumProfiles = {} x {} = {n} (truncated file?)",
                z.len(),
                p.nx,
                p.ny
            ),
        ));
    }
    Ok((p, z))
}
