//! Keyence VK-X laser confocal microscope `.vk4` files.
//!
//! Layout, as reverse-engineered and documented by Gwyddion (`modules/file/keyence.c`),
//! SurfaceTopography (`IO/VK.py`) and the OSTI report 1419732 (vk4 Python driver);
//! little-endian:
//!
//! * 0: magic `VK4_`, 4: DLL version, 8: file type (4 zero bytes for a plain measurement);
//! * 12: the offset table, 18 u32: setting, colour peak, colour light, light 1-3, height
//!   1-3, four thumbnails, assemble, line measure, line thickness, string data, reserved;
//! * 84: the measurement conditions (u32 size >= 304, ...): `x_length_per_pixel`,
//!   `y_length_per_pixel` and `z_length_per_digit` at 252, 256 and 260 (u32, picometres);
//! * each image at its offset: width, height, bit depth (8, 16, 32), compression (0),
//!   byte size (= width x height x depth / 8), palette range min and max (u32), a 768-byte
//!   palette, then the unsigned values row by row.
//!
//! Heights: value x `z_length_per_digit` (pm); spacing `x_length_per_pixel`,
//! `y_length_per_pixel` (pm). (Gwyddion and SurfaceTopography give the scan size as (n - 1)
//! pixels, i.e. a pixel of (n - 1)/n of the stated length; the stated length per pixel is
//! used here.) The height images are height channels, the light (intensity) images are
//! channels that are not heights. `.vk3`, `.vk6` and `.vk7` files (`VK3_`, `VK6`, `VK7`) are
//! recognised and refused.

use std::path::Path;

use super::bin::{product, Bin};
use super::{Channel, FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::Format;
use crate::map::LengthUnit;

/// The first bytes of the Keyence files: VK4 (read), VK3, VK6, VK7 (refused).
pub(crate) const MAGICS: [&[u8]; 4] = [b"VK4_", b"VK3_", b"VK6", b"VK7"];
const TABLE: usize = 12;
const CONDITIONS: usize = 84;
const IMAGE_HEADER: usize = 28 + 768;

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Vk4, opts);
    for (magic, ext) in [(&b"VK6"[..], "vk6"), (b"VK7", "vk7"), (b"VK3_", "vk3")] {
        if bytes.starts_with(magic) {
            return Err(st.unsupported(&format!("a Keyence .{ext} file"), "export it as .x3p"));
        }
    }
    if !bytes.starts_with(b"VK4_") {
        return Err(st.err("magic", "does not start with VK4_: not a Keyence VK4 file"));
    }
    let b = Bin(bytes);
    match b.slice(8, 4) {
        Some([0, 0, 0, 0]) => {}
        Some(_) => {
            return Err(st.unsupported(
                "a Keyence VK4 assembly (stitched) file",
                "export the stitched height image as .x3p",
            ))
        }
        None => return Err(st.err("header", "truncated")),
    }
    let table = |k: usize| b.u32_le(TABLE + 4 * k);
    let cond = |off: usize| b.u32_le(CONDITIONS + off);
    let size = cond(0).ok_or_else(|| st.err("measurement conditions", "truncated"))?;
    if size < 304 {
        return Err(st.err("measurement conditions", format!("size {size} < 304")));
    }
    let mut entries = Vec::new();
    for k in 0..3 {
        if let Some(off) = table(6 + k).filter(|&o| o != 0) {
            entries.push((format!("Height {}", k + 1), true, off as usize));
        }
    }
    for k in 0..3 {
        if let Some(off) = table(3 + k).filter(|&o| o != 0) {
            entries.push((format!("Light {}", k + 1), false, off as usize));
        }
    }
    let list: Vec<Channel> = entries
        .iter()
        .map(|e| Channel::new(e.0.clone(), e.1))
        .collect();
    if list.is_empty() {
        return Err(st.err("offset table", "no height or light image"));
    }
    let k = st.choose_channel(&list)?;
    let (name, is_height, off) = entries[k].clone();
    let loc = format!("image {name:?} at byte {off}");
    let field = |o: usize| b.u32_le(off.saturating_add(o));
    let (Some(w), Some(h), Some(depth), Some(compression), Some(byte_size)) =
        (field(0), field(4), field(8), field(12), field(16))
    else {
        return Err(st.err(
            loc,
            "the image header runs past the end of the file (truncated)",
        ));
    };
    if !matches!(depth, 8 | 16 | 32) {
        return Err(st.err(loc, format!("bit depth {depth}: expected 8, 16 or 32")));
    }
    if compression != 0 {
        return Err(st.unsupported(
            &format!("a compressed VK4 image (compression {compression})"),
            "export it as .x3p",
        ));
    }
    if w == 0 || h == 0 {
        return Err(st.err(loc, format!("an empty image ({w} x {h})")));
    }
    let n = st.check_points(w as u64, h as u64)?;
    let bps = (depth / 8) as u64;
    if product(&[w as u64, h as u64, bps]) != Some(byte_size as u64) {
        return Err(st.err(
            loc,
            format!(
                "byte size {byte_size}, but {w} x {h} values of {depth} bits need {}",
                n as u64 * bps
            ),
        ));
    }
    let data = b.slice(off.saturating_add(IMAGE_HEADER), byte_size as usize).ok_or_else(|| {
        st.err(
            &loc,
            format!("its {byte_size} bytes run past the end of the file ({} bytes): truncated file?", bytes.len()),
        )
    })?;
    let z: Vec<f64> = match depth {
        8 => data.iter().map(|&v| f64::from(v)).collect(),
        16 => data
            .chunks_exact(2)
            .map(|v| f64::from(u16::from_le_bytes([v[0], v[1]])))
            .collect(),
        _ => data
            .chunks_exact(4)
            .map(|v| f64::from(u32::from_le_bytes([v[0], v[1], v[2], v[3]])))
            .collect(),
    };
    let (xp, yp, zd) = (cond(168), cond(172), cond(176));
    let file_spacing = match (xp, yp) {
        (Some(x), Some(y)) if x > 0 && y > 0 => Some((f64::from(x) * 1e-12, f64::from(y) * 1e-12)),
        _ => None,
    };
    let spacing = st.spacing(file_spacing)?;
    let unit = if is_height {
        match zd {
            Some(d) if d > 0 => FileUnit::Length(LengthUnit::factor(f64::from(d) * 1e-12)?),
            _ => {
                return Err(st.err(
                    "measurement conditions z_length_per_digit (byte 260)",
                    "0: the heights have no scale",
                ))
            }
        }
    } else {
        FileUnit::Other("light intensity".to_string())
    };
    let unit = st.height_unit(unit, &format!("image {name:?}"))?;
    st.finish(w as usize, h as usize, spacing, unit, z)
}
