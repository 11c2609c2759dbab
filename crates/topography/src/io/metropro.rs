//! Zygo MetroPro `.dat` files (header formats 1, 2 and 3).
//!
//! Layout, from the MetroPro Reference Guide (Zygo OMP-0347, "Data Format", binary data
//! file) as Gwyddion (`modules/file/metropro.c`) and SurfaceTopography (`IO/MetroPro.py`)
//! read it; big-endian throughout:
//!
//! * magic u32 `0x881B036F` (header format 1), `0x881B0370` (2) or `0x881B0371` (3), then
//!   header_format u16 and header_size u32 (834 bytes for formats 1 and 2, 4096 for 3);
//! * intensity: `ac_width`, `ac_height` (u16 at 52, 54), `ac_n_buckets` (u16 at 56);
//!   phase: `cn_width`, `cn_height` (u16 at 68, 70);
//! * `intf_scale_factor` S (f32 at 164), `wavelength_in` lambda (f32 at 168, m),
//!   `obliquity_factor` O (f32 at 176), `lateral_res` (f32 at 184, the camera resolution,
//!   m per pixel), `phase_res` (i16 at 218: 0, 1, 2 for R = 4096, 32768, 131072), `sign`
//!   (i16 at 232);
//! * after the header: the intensity buckets (`ac_n_buckets` x `ac_height` x `ac_width` u16,
//!   row by row; 65412 and above are invalid), then the phase (connected) data,
//!   `cn_height` x `cn_width` i32 row by row, 2147483640 and above invalid.
//!
//! Heights: phase x S x O x lambda / R (m), negated when `sign` is set. The phase data are
//! the height channel ("Phase"); each intensity bucket is a channel that is not a height.
//! The HDF5 `.datx` (Mx software) is recognised and refused: no pure-Rust HDF5 reader
//! sound enough for untrusted files is in this workspace (docs/topography.md); Mx exports
//! .x3p.

use std::path::Path;

use super::bin::{product, Bin};
use super::{Channel, FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::Format;
use crate::map::LengthUnit;

/// The magic numbers of header formats 1, 2 and 3.
pub(crate) const MAGICS: [&[u8]; 3] = [
    b"\x88\x1b\x03\x6f",
    b"\x88\x1b\x03\x70",
    b"\x88\x1b\x03\x71",
];
/// The signature of an HDF5 file (a Zygo `.datx`).
pub(crate) const HDF5_MAGIC: &[u8] = b"\x89HDF\r\n\x1a\n";
const INVALID_PHASE: i32 = 2_147_483_640;
const INVALID_INTENSITY: u16 = 65412;

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Metropro, opts);
    if bytes.starts_with(HDF5_MAGIC) {
        return Err(st.unsupported(
            "an HDF5 file (a Zygo .datx from Mx, or another HDF5 container)",
            "export it from Mx as .x3p (or as a MetroPro .dat)",
        ));
    }
    let Some(format) = MAGICS
        .iter()
        .position(|m| bytes.starts_with(m))
        .map(|k| k as u16 + 1)
    else {
        return Err(st.err(
            "magic",
            "not 0x881B036F, 0x881B0370 or 0x881B0371: not a MetroPro file",
        ));
    };
    let b = Bin(bytes);
    let need = |st: &Settle, v: Option<u16>, what: &str| {
        v.ok_or_else(|| {
            st.err(
                format!("header field {what}"),
                "the file ends inside the header (truncated)",
            )
        })
    };
    let header_format = need(&st, b.u16_be(4), "header_format")?;
    let header_size =
        b.u32_be(6)
            .ok_or_else(|| st.err("header field header_size", "truncated"))? as usize;
    if header_format != format {
        return Err(st.err(
            "header field header_format",
            format!("{header_format}, but the magic number is header format {format}'s"),
        ));
    }
    let expected = if format == 3 { 4096 } else { 834 };
    if header_size != expected {
        return Err(st.err(
            "header field header_size",
            format!("{header_size}: header format {format} has {expected} bytes"),
        ));
    }
    if bytes.len() < header_size {
        return Err(st.err(
            "header",
            format!(
                "{} bytes, but the header alone has {header_size}: truncated file",
                bytes.len()
            ),
        ));
    }
    let u16f = |at: usize| b.u16_be(at).unwrap_or(0) as u64;
    let f32f = |at: usize| b.f32_be(at).map(f64::from).unwrap_or(f64::NAN);
    let (ac_w, ac_h, buckets) = (u16f(52), u16f(54), u16f(56));
    let (cn_w, cn_h) = (u16f(68), u16f(70));
    let ac_bytes = product(&[2, ac_w, ac_h, buckets]).unwrap_or(u64::MAX);
    let cn_bytes = product(&[4, cn_w, cn_h]).unwrap_or(u64::MAX);
    let total = (header_size as u64)
        .saturating_add(ac_bytes)
        .saturating_add(cn_bytes);
    if (bytes.len() as u64) < total {
        return Err(st.err(
            "data",
            format!(
                "{} bytes, but the header, {buckets} intensity bucket(s) of {ac_w} x {ac_h} and the {cn_w} x {cn_h} phase data need {total}: truncated file",
                bytes.len()
            ),
        ));
    }
    let mut list = Vec::new();
    if cn_w * cn_h > 0 {
        list.push(Channel::new("Phase", true));
    }
    if ac_w * ac_h > 0 {
        for k in 0..buckets {
            list.push(Channel::new(
                if buckets == 1 {
                    "Intensity".to_string()
                } else {
                    format!("Intensity {}", k + 1)
                },
                false,
            ));
        }
    }
    if list.is_empty() {
        return Err(st.err(
            "header",
            "neither phase (height) nor intensity data (all sizes are 0)",
        ));
    }
    if !list[0].height && opts.channel.is_none() {
        return Err(st.unsupported(
            "a MetroPro file with intensity data only (no phase data)",
            "measure or export the surface (phase) map, e.g. as .x3p",
        ));
    }
    let k = st.choose_channel(&list)?;
    let lateral = f32f(184);
    let file_spacing = (lateral.is_finite() && lateral > 0.0).then_some((lateral, lateral));
    let sign = b.i16_be(232).unwrap_or(0) != 0;
    if list[k].height {
        let (nx, ny) = (cn_w as usize, cn_h as usize);
        let n = st.check_points(cn_w, cn_h)?;
        let start = header_size + ac_bytes as usize;
        let data = &bytes[start..start + 4 * n];
        let z: Vec<f64> = data
            .chunks_exact(4)
            .map(|v| {
                let x = i32::from_be_bytes([v[0], v[1], v[2], v[3]]);
                if x >= INVALID_PHASE {
                    f64::NAN
                } else {
                    f64::from(x)
                }
            })
            .collect();
        let r = match b.i16_be(218).unwrap_or(-1) {
            0 => 4096.0,
            1 => 32768.0,
            2 => 131072.0,
            other => {
                return Err(st.err(
                    "header field phase_res (byte 218)",
                    format!("{other}: expected 0, 1 or 2 (phase resolution 4096, 32768 or 131072)"),
                ))
            }
        };
        let mut scale = 1.0 / r;
        for (name, at) in [
            ("intf_scale_factor", 164),
            ("wavelength_in", 168),
            ("obliquity_factor", 176),
        ] {
            let v = f32f(at);
            if !(v.is_finite() && v > 0.0) {
                return Err(st.err(
                    format!("header field {name} (byte {at})"),
                    format!("{v}: must be > 0"),
                ));
            }
            scale *= v;
        }
        if sign {
            scale = -scale;
            st.notes.push("the header's sign flag is set: the heights are negated (as Gwyddion and SurfaceTopography read it)".to_string());
        }
        let z = z.into_iter().map(|v| v * scale).collect();
        let spacing = st.spacing(file_spacing)?;
        let unit = st.height_unit(FileUnit::Length(LengthUnit::METRE), "phase data")?;
        st.finish(nx, ny, spacing, unit, z)
    } else {
        let bucket = (k - usize::from(cn_w * cn_h > 0)) as u64;
        let (nx, ny) = (ac_w as usize, ac_h as usize);
        let n = st.check_points(ac_w, ac_h)?;
        let start = header_size + (bucket * 2 * n as u64) as usize;
        let z = bytes[start..start + 2 * n]
            .chunks_exact(2)
            .map(|v| {
                let x = u16::from_be_bytes([v[0], v[1]]);
                if x >= INVALID_INTENSITY {
                    f64::NAN
                } else {
                    f64::from(x)
                }
            })
            .collect();
        let spacing = st.spacing(file_spacing)?;
        let unit = st.height_unit(
            FileUnit::Other("intensity counts".to_string()),
            "intensity data",
        )?;
        st.finish(nx, ny, spacing, unit, z)
    }
}
