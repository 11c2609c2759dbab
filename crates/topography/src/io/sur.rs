//! Digital Surf `.sur` files (MountainsMap), plain (`DIGITAL SURF`) and compressed
//! (`DSCOMPRESSED`), with one or several objects.
//!
//! Layout, from the MountainsMap SDK description as Gwyddion (`modules/file/surffile.c`),
//! RosettaSciIO (`rsciio/digitalsurf`) and surfalize (`file/sur.py`) implement it;
//! little-endian; each object is a 512-byte header, a comment, a private zone and its data:
//!
//! | offset | field |
//! |---|---|
//! | 0 | signature `DIGITAL SURF` or `DSCOMPRESSED` (12 bytes) |
//! | 12, 14, 16, 18 | format (i16, 0 = PC; 257 = Macintosh, refused), number of objects (u16), version, object type (i16) |
//! | 20 | object name (30 bytes) |
//! | 86 | non-measured points flag (i16: 1 = the file has them) |
//! | 98 | bits per point (i16: 16 or 32) |
//! | 100, 104 | zmin, zmax (i32) |
//! | 108, 112, 116 | points per line, lines, total points (i32) |
//! | 120, 124, 128 | x, y, z spacing (f32, in the step units) |
//! | 180, 196, 212 | x, y, z step units (16 bytes each: `µm`, `nm`, ...) |
//! | 290 | inverted (i16) |
//! | 324 | compressed data size (u32) |
//! | 334, 336 | comment size, private zone size (i16) |
//! | 474 | z offset (f32, in the z step unit) |
//!
//! Data: points per line x lines signed integers of 16 or 32 bits, row by row; compressed,
//! a u32 count of streams, (raw length, zipped length) u32 pairs, then the zlib streams
//! (inflated here with a cap at the declared raw sizes). Heights: raw x z spacing + z offset
//! (z step unit). Non-measured points (flag 1): the value zmin - 2.
//!
//! Objects: every object is a channel (its name, or `object N`); surfaces (type 2), series
//! and multilayers of surfaces (5, 8), intensity, RGB and RGB-intensity surfaces (11, 13, 16)
//! are height channels; profiles (1, 4, 7, 17) are 1-D and refused as such, except a
//! "profile" with several lines (Gwyddion's exports label surfaces so), read as a surface;
//! images (intensity, binary, RGB) are channels that are not heights. The `inverted` flag is
//! reported in the notes, the heights taken as stored (as RosettaSciIO, surfalize and
//! SurfaceTopography read them).

use std::io::Read;
use std::path::Path;

use super::bin::{product, Bin};
use super::{Channel, FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::Format;

/// Signature of a plain file.
pub(crate) const MAGIC: &[u8] = b"DIGITAL SURF";
/// Signature of a compressed file.
pub(crate) const MAGIC_COMPRESSED: &[u8] = b"DSCOMPRESSED";
const HEADER: usize = 512;
/// Objects accepted in a file (series hold a few hundred at most).
const MAX_OBJECTS: usize = 65_535;

struct Object {
    at: usize,
    name: String,
    ty: i16,
    compressed: bool,
    special: bool,
    bits: i16,
    zmin: i32,
    nx: i32,
    ny: i32,
    dx: f64,
    dy: f64,
    dz: f64,
    units: [String; 3],
    inverted: i16,
    z_offset: f64,
    data_at: usize,
    data_len: usize,
}

fn type_name(ty: i16) -> &'static str {
    match ty {
        1 => "profile",
        2 => "surface",
        3 => "binary image",
        4 => "series of profiles",
        5 => "series of surfaces",
        6 => "meridian disc",
        7 => "multilayer profile",
        8 => "multilayer surface",
        9 => "parallel disc",
        10 => "intensity image",
        11 => "intensity surface",
        12 => "RGB image",
        13 => "RGB surface",
        14 => "force curve",
        15 => "series of force curves",
        16 => "RGB intensity surface",
        17 => "contour profile",
        18 => "series of RGB images",
        20 => "spectrum",
        21 => "hyperspectral cube",
        _ => "object",
    }
}

fn is_profile(ty: i16) -> bool {
    matches!(ty, 1 | 4 | 7 | 17)
}

fn is_surface(o: &Object) -> bool {
    matches!(o.ty, 2 | 5 | 8 | 11 | 13 | 16) || (is_profile(o.ty) && o.ny > 1)
}

fn parse_object(st: &Settle, b: Bin, at: usize, k: usize) -> Result<Object> {
    let loc = |f: &str| format!("object {k} (byte {at}), header field {f}");
    let trunc = |f: &str| {
        st.err(
            loc(f),
            "the file ends inside the 512-byte header (truncated)",
        )
    };
    let head = b.slice(at, HEADER).ok_or_else(|| trunc("signature"))?;
    let compressed = if head.starts_with(MAGIC) {
        false
    } else if head.starts_with(MAGIC_COMPRESSED) {
        true
    } else {
        return Err(st.err(loc("signature"), "not DIGITAL SURF nor DSCOMPRESSED"));
    };
    let h = Bin(head);
    let i16f = |o: usize| h.i16_le(o).unwrap_or(0);
    let i32f = |o: usize| h.i32_le(o).unwrap_or(0);
    let f32f = |o: usize| h.f32_le(o).map(f64::from).unwrap_or(f64::NAN);
    if i16f(12) == 257 {
        return Err(st.unsupported(
            "a Digital Surf file in the Macintosh byte order (format 257)",
            "save it from MountainsMap on a PC, or export it as .x3p",
        ));
    }
    let comment = i16f(334).max(0) as usize;
    let private = i16f(336).max(0) as usize;
    let data_at = at + HEADER + comment + private;
    let bits = i16f(98);
    let (nx, ny) = (i32f(108), i32f(112));
    let data_len = if compressed {
        h.u32_le(324).unwrap_or(0) as usize
    } else {
        let w = i32f(94).max(1) as u64;
        if !(bits == 16 || bits == 32) || nx <= 0 || ny <= 0 {
            0
        } else {
            product(&[nx as u64, ny as u64, bits as u64 / 8, w])
                .filter(|&l| l <= b.len() as u64)
                .ok_or_else(|| {
                    st.err(
                        loc("points per line"),
                        format!("{nx} x {ny} points of {bits} bits run past the end of the file ({} bytes): truncated file?", b.len()),
                    )
                })? as usize
        }
    };
    let unit = |o: usize| h.text(o, 16).unwrap_or_default();
    Ok(Object {
        at,
        name: h.text(20, 30).unwrap_or_default(),
        ty: i16f(18),
        compressed,
        special: i16f(86) == 1,
        bits,
        zmin: i32f(100),
        nx,
        ny,
        dx: f32f(120),
        dy: f32f(124),
        dz: f32f(128),
        units: [unit(180), unit(196), unit(212)],
        inverted: i16f(290),
        z_offset: f32f(474),
        data_at,
        data_len,
    })
}

/// The object's raw integers (inflated if compressed), at most `n` of them.
fn raw_values(st: &Settle, bytes: &[u8], o: &Object, n: usize, k: usize) -> Result<Vec<i64>> {
    let loc = format!("object {k} (byte {}) data", o.at);
    let width = (o.bits / 8) as usize;
    let want = n * width;
    let block = bytes
        .get(o.data_at..o.data_at.saturating_add(o.data_len))
        .filter(|_| o.data_at.checked_add(o.data_len).is_some())
        .ok_or_else(|| {
            st.err(&loc, format!("{} bytes at offset {} run past the end of the file ({} bytes): truncated file?", o.data_len, o.data_at, bytes.len()))
        })?;
    let data: Vec<u8> = if o.compressed {
        let b = Bin(block);
        let count = b.u32_le(0).ok_or_else(|| st.err(&loc, "no stream count"))? as usize;
        if count == 0 || count > 1024 {
            return Err(st.err(
                &loc,
                format!("{count} compressed streams (expected 1 to 1024)"),
            ));
        }
        let mut pos = 4 + 8 * count;
        let mut out = Vec::with_capacity(want.min(1 << 26));
        for s in 0..count {
            let (Some(raw_len), Some(zip_len)) = (b.u32_le(4 + 8 * s), b.u32_le(8 + 8 * s)) else {
                return Err(st.err(&loc, "the stream directory is truncated"));
            };
            let (raw_len, zip_len) = (raw_len as usize, zip_len as usize);
            let stream = b.slice(pos, zip_len).ok_or_else(|| {
                st.err(
                    &loc,
                    format!("stream {s} ({zip_len} bytes) runs past the data block"),
                )
            })?;
            pos += zip_len;
            if out.len().saturating_add(raw_len) > want {
                return Err(st.err(
                    &loc,
                    format!(
                        "the streams inflate beyond the {want} bytes of {} x {} points",
                        o.nx, o.ny
                    ),
                ));
            }
            let before = out.len();
            flate2::read::ZlibDecoder::new(stream)
                .take(raw_len as u64 + 1)
                .read_to_end(&mut out)
                .map_err(|e| st.err(&loc, format!("stream {s}: cannot inflate: {e}")))?;
            if out.len() - before != raw_len {
                return Err(st.err(
                    &loc,
                    format!(
                        "stream {s} inflates to {} bytes, its directory says {raw_len}",
                        out.len() - before
                    ),
                ));
            }
        }
        out
    } else {
        block.to_vec()
    };
    if data.len() < want {
        return Err(st.err(
            &loc,
            format!(
                "{} bytes, but {} x {} points of {} bits need {want}",
                data.len(),
                o.nx,
                o.ny,
                o.bits
            ),
        ));
    }
    Ok(if width == 2 {
        data[..want]
            .chunks_exact(2)
            .map(|v| i64::from(i16::from_le_bytes([v[0], v[1]])))
            .collect()
    } else {
        data[..want]
            .chunks_exact(4)
            .map(|v| i64::from(i32::from_le_bytes([v[0], v[1], v[2], v[3]])))
            .collect()
    })
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Sur, opts);
    let b = Bin(bytes);
    let first = parse_object(&st, b, 0, 0)?;
    let count = (b.u16_le(14).unwrap_or(1) as usize).clamp(1, MAX_OBJECTS);
    let mut objects = vec![first];
    while objects.len() < count {
        let last = objects.last().ok_or_else(|| st.err("objects", "none"))?;
        let next = last.data_at.saturating_add(last.data_len);
        if next >= bytes.len() {
            st.notes.push(format!(
                "the header announces {count} objects, the file holds {}",
                objects.len()
            ));
            break;
        }
        let k = objects.len();
        objects.push(parse_object(&st, b, next, k)?);
    }
    let list: Vec<Channel> = objects
        .iter()
        .enumerate()
        .map(|(k, o)| {
            let name = if o.name.is_empty() {
                format!("object {k}")
            } else {
                o.name.clone()
            };
            Channel::new(format!("{name} ({})", type_name(o.ty)), is_surface(o))
        })
        .collect();
    if opts.channel.is_none() && !list.iter().any(|c| c.height) {
        let o = &objects[0];
        if is_profile(o.ty) {
            let n = i64::from(o.nx).max(0) as u64 * i64::from(o.ny).max(0) as u64;
            return Err(st.profile(&format!("object 0 ({})", type_name(o.ty)), n));
        }
    }
    let k = st.choose_channel(&list)?;
    let o = &objects[k];
    let loc = |f: &str| format!("object {k} (byte {}), header field {f}", o.at);
    if is_profile(o.ty) && o.ny <= 1 {
        let n = i64::from(o.nx).max(0) as u64;
        return Err(st.profile(&format!("object {k} ({})", type_name(o.ty)), n));
    }
    if o.bits != 16 && o.bits != 32 {
        return Err(st.err(
            loc("bits per point"),
            format!("{}: expected 16 or 32", o.bits),
        ));
    }
    if o.nx <= 0 || o.ny <= 0 {
        return Err(st.err(
            loc("points per line"),
            format!("{} x {} points", o.nx, o.ny),
        ));
    }
    let (nx, ny) = (o.nx as u64, o.ny as u64);
    let n = st.check_points(nx, ny)?;
    let raw = raw_values(&st, bytes, o, n, k)?;
    if !(o.dz.is_finite() && o.dz != 0.0 && o.z_offset.is_finite()) {
        return Err(st.err(
            loc("z spacing"),
            format!("{} (offset {}): not a usable scale", o.dz, o.z_offset),
        ));
    }
    let nm = i64::from(o.zmin) - 2;
    let z: Vec<f64> = raw
        .into_iter()
        .map(|r| {
            if o.special && r == nm {
                f64::NAN
            } else {
                r as f64 * o.dz + o.z_offset
            }
        })
        .collect();
    if o.inverted != 0 {
        st.notes.push(format!(
            "the object's inverted flag is {}: the heights are taken as stored",
            o.inverted
        ));
    }
    if is_profile(o.ty) {
        st.notes.push(format!(
            "the object is labelled a {} but has {} lines: read as a surface",
            type_name(o.ty),
            o.ny
        ));
    }
    let step = |s: &str, v: f64, what: &str| -> Result<Option<f64>> {
        match FileUnit::from_file(s) {
            FileUnit::Length(u) if v.is_finite() && v > 0.0 => Ok(Some(v * u.to_metres)),
            _ if opts.spacing.is_some() => Ok(None),
            FileUnit::Length(_) => Err(st.err(loc(what), format!("{v} is not a positive spacing"))),
            _ => Err(st.err(
                loc(&format!("{what} unit")),
                format!("{s:?} is not a length unit"),
            )),
        }
    };
    let sx = step(&o.units[0], o.dx, "x spacing")?;
    let sy = step(&o.units[1], o.dy, "y spacing")?;
    let spacing = st.spacing(sx.zip(sy))?;
    let zu = FileUnit::from_file(&o.units[2]);
    let unit = st.height_unit(zu, &loc("z step unit"))?;
    st.finish(nx as usize, ny as usize, spacing, unit, z)
}
