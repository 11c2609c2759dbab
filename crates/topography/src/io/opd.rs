//! Wyko / Veeco / Bruker Vision `.opd` optical-profiler files.
//!
//! Layout, as reverse-engineered and documented by Gwyddion (`modules/file/opdfile.c`) and
//! SurfaceTopography (`IO/OPD.py`), little-endian throughout:
//!
//! * two bytes `01 00`, then a directory of 24-byte block entries: a 16-byte name (NUL or
//!   space padded), a u16 type, a u32 size, a u16 flags. The first entry is the directory
//!   itself (`Directory`, type 1, size = 24 x number of entries); the blocks' contents
//!   follow the directory in the order of the entries;
//! * types: 3 array, 5 text, 6 short (i16), 7 float (f32), 8 double, 12 long (i32);
//! * an array is `xres`, `yres`, element size (u16 each: 4 float, 2 i16, 1 byte), then the
//!   values column by column (x outer), each column from the top of the image down;
//! * `Pixel_size` (float, mm), `Wavelength` (float, nm), `Mult` (short, default 1),
//!   `Aspect` (float, dy / dx, default 1).
//!
//! Heights: value x Wavelength / Mult (nm) for the height arrays (`RAW_DATA`, `RAW DATA`,
//! `Raw`, `OPD`, `SAMPLE_DATA`); the intensity arrays (`Image`, `Intensity`, `SecArr_0`)
//! and any other array are listed as channels that are not heights. Undefined points: a
//! float that is not finite or whose magnitude is 1e10 or more (Vision writes about 1e38), an
//! i16 of 32766 or more. Spacing: Pixel_size in x, Pixel_size x Aspect in y.

use std::path::Path;

use super::bin::{product, Bin};
use super::{Channel, FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::Format;
use crate::map::LengthUnit;

/// The first bytes of an OPD file.
pub(crate) const MAGIC: &[u8] = b"\x01\x00Directory";
const ENTRY: usize = 24;
const HEIGHTS: [&str; 5] = ["RAW_DATA", "RAW DATA", "Raw", "OPD", "SAMPLE_DATA"];
/// A float of this magnitude or more marks an undefined point.
const BAD_FLOAT: f64 = 1e10;
const BAD_INT16: i16 = 32766;

struct Block {
    name: String,
    ty: u16,
    pos: usize,
    size: usize,
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Opd, opts);
    let b = Bin(bytes);
    if !bytes.starts_with(b"\x01\x00") {
        return Err(st.err("magic", "does not start with 01 00: not an OPD file"));
    }
    let entry = |k: usize| -> Option<(String, u16, u32, u16)> {
        let at = 2usize.checked_add(k.checked_mul(ENTRY)?)?;
        Some((
            b.text(at, 16)?,
            b.u16_le(at + 16)?,
            b.u32_le(at + 18)?,
            b.u16_le(at + 22)?,
        ))
    };
    let (dname, dtype, dsize, _) = entry(0).ok_or_else(|| {
        st.err(
            "directory",
            "the file ends inside the directory entry (truncated)",
        )
    })?;
    if dname != "Directory" || dtype != 1 {
        return Err(st.err(
            "directory",
            format!("the first block is {dname:?} of type {dtype}, not the Directory (type 1): not an OPD file"),
        ));
    }
    let dsize = dsize as usize;
    if !dsize.is_multiple_of(ENTRY) || dsize < ENTRY {
        return Err(st.err(
            "directory",
            format!("its size {dsize} is not a positive multiple of {ENTRY} bytes"),
        ));
    }
    let nblocks = dsize / ENTRY;
    let data_start = 2usize.saturating_add(dsize);
    if data_start > bytes.len() {
        return Err(st.err(
            "directory",
            format!("{nblocks} entries of {ENTRY} bytes run past the end of the file ({} bytes): truncated file?", bytes.len()),
        ));
    }
    let mut blocks = Vec::new();
    let mut pos = data_start;
    for k in 1..nblocks {
        let (name, ty, size, _) =
            entry(k).ok_or_else(|| st.err(format!("directory entry {k}"), "truncated"))?;
        let size = size as usize;
        let end = pos.checked_add(size).filter(|&e| e <= bytes.len()).ok_or_else(|| {
            st.err(
                format!("block {name:?} (directory entry {k})"),
                format!("{size} bytes at offset {pos} run past the end of the file ({} bytes): truncated file?", bytes.len()),
            )
        })?;
        if size > 0 {
            if ty == 1 {
                return Err(st.err(
                    format!("block {name:?}"),
                    "a nested directory (corrupt file?)",
                ));
            }
            blocks.push(Block {
                name,
                ty,
                pos,
                size,
            });
        }
        pos = end;
    }
    let find = |name: &str| blocks.iter().find(|b| b.name == name);
    let float = |st: &Settle, name: &str| -> Result<Option<f64>> {
        match find(name) {
            None => Ok(None),
            Some(bl) if bl.ty == 7 && bl.size >= 4 => Ok(b.f32_le(bl.pos).map(f64::from)),
            Some(bl) if bl.ty == 8 && bl.size >= 8 => Ok(b.f64_le(bl.pos)),
            Some(bl) => Err(st.err(
                format!("block {name:?}"),
                format!("type {} of {} bytes, expected a float", bl.ty, bl.size),
            )),
        }
    };
    let arrays: Vec<&Block> = blocks.iter().filter(|bl| bl.ty == 3).collect();
    let list: Vec<Channel> = arrays
        .iter()
        .map(|bl| Channel::new(bl.name.clone(), HEIGHTS.contains(&bl.name.as_str())))
        .collect();
    if list.is_empty() {
        return Err(st.err("directory", "no array block: the file holds no image"));
    }
    let k = st.choose_channel(&list)?;
    let arr = arrays[k];
    let is_height = list[k].height;
    let at = format!("block {:?}", arr.name);
    let (xres, yres, elsize) = match (
        b.u16_le(arr.pos),
        b.u16_le(arr.pos + 2),
        b.u16_le(arr.pos + 4),
    ) {
        (Some(x), Some(y), Some(e)) if arr.size >= 6 => (x as u64, y as u64, e as u64),
        _ => return Err(st.err(&at, "too short for the array's dimensions")),
    };
    if !matches!(elsize, 1 | 2 | 4) {
        return Err(st.err(
            &at,
            format!("element size {elsize}: expected 1 (byte), 2 (i16) or 4 (float)"),
        ));
    }
    if xres == 0 || yres == 0 {
        return Err(st.err(&at, format!("an empty array ({xres} x {yres})")));
    }
    let n = st.check_points(xres, yres)?;
    let need = product(&[xres, yres, elsize]).unwrap_or(u64::MAX);
    if (arr.size as u64) < need.saturating_add(6) {
        return Err(st.err(
            &at,
            format!(
                "{} bytes, but {xres} x {yres} values of {elsize} bytes need {}",
                arr.size - 6,
                need
            ),
        ));
    }
    let data = &bytes[arr.pos + 6..arr.pos + 6 + need as usize];
    let (nx, ny) = (xres as usize, yres as usize);
    let mut z = vec![f64::NAN; n];
    // stored column by column (x outer), each column from the last row to the first
    for (s, v) in data.chunks_exact(elsize as usize).enumerate() {
        let (i, jj) = (s / ny, s % ny);
        let j = ny - 1 - jj;
        z[j * nx + i] = match elsize {
            4 => {
                let f = f64::from(f32::from_le_bytes([v[0], v[1], v[2], v[3]]));
                if f.is_finite() && f.abs() < BAD_FLOAT {
                    f
                } else {
                    f64::NAN
                }
            }
            2 => {
                let x = i16::from_le_bytes([v[0], v[1]]);
                if x < BAD_INT16 {
                    f64::from(x)
                } else {
                    f64::NAN
                }
            }
            _ => f64::from(v[0]),
        };
    }
    let pixel = float(&st, "Pixel_size")?;
    let aspect = float(&st, "Aspect")?.unwrap_or(1.0);
    let file_spacing = match pixel {
        Some(p) if p.is_finite() && p > 0.0 && aspect.is_finite() && aspect > 0.0 => {
            Some((p * 1e-3, p * aspect * 1e-3))
        }
        Some(p) if opts.spacing.is_none() => {
            return Err(st.err(
                "block \"Pixel_size\"",
                format!("{p} mm (aspect {aspect}) is not a positive pixel size"),
            ))
        }
        _ => None,
    };
    let spacing = st.spacing(file_spacing)?;
    let unit = if is_height {
        let mult = match find("Mult") {
            Some(bl) if bl.ty == 6 => b.i16_le(bl.pos).map(f64::from).unwrap_or(1.0),
            Some(bl) if bl.ty == 12 => b.i32_le(bl.pos).map(f64::from).unwrap_or(1.0),
            _ => 1.0,
        };
        match float(&st, "Wavelength")? {
            Some(w) if w.is_finite() && w > 0.0 && mult > 0.0 => FileUnit::Length(
                LengthUnit::factor(w * 1e-9 / mult)
                    .map_err(|e| st.err("block \"Wavelength\"", e.to_string()))?,
            ),
            Some(w) => {
                return Err(st.err(
                    "block \"Wavelength\"",
                    format!("{w} nm (Mult {mult}) does not give a positive height unit"),
                ))
            }
            None => FileUnit::Other("wavelengths (no Wavelength block)".to_string()),
        }
    } else {
        FileUnit::Other(format!("intensity ({})", arr.name))
    };
    let unit = st.height_unit(unit, &at)?;
    st.finish(nx, ny, spacing, unit, z)
}
