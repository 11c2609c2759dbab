//! Sensofar `.plu` (SensoSCAN, PLu 2000 and 2006) and `.plux` (SensoVIEW / SensoSCAN 6) files.
//!
//! `.plu`, as reverse-engineered and documented by Gwyddion (`modules/file/sensofar.c`) and
//! SurfaceTopography (`IO/PLU.py`); little-endian, a 500-byte header:
//!
//! * 0: the acquisition date, a C `ctime` string (`Tue May 12 10:31:46 2015`, NUL at 24) in a
//!   128-byte field (the only signature the format has), 128: time (u32), 132: a 256-byte
//!   comment;
//! * 388, the axes calibration: yres, xres, N_tall (u32), dy_multip, `mppx`, `mppy` (f32,
//!   um per pixel in x and y), x0, y0, mpp_tall, z0 (f32);
//! * 428, the measure configuration: type (u32: 3 topography; 1 profile and 5 thickness
//!   profile are 1-D; 0 a confocal image, 2 multiple profiles, 4 coordinates, 6 custom are
//!   refused), algorithm, method, objective, area, ... , then at 489 the number of layers
//!   (u8);
//! * 500: each layer, yres and xres (u32), then xres x yres f32 heights (um) row by row,
//!   then its minimum and maximum (f32). 1000001 marks a non-measured point.
//!
//! `.plux` is a zip archive: `index.xml` (root `xml`) gives `GENERAL/IMAGE_SIZE_X`,
//! `IMAGE_SIZE_Y`, `FOV_X`, `FOV_Y` (um per pixel) and, per layer, `LAYER_N/FILENAME_Z`,
//! the entry holding the layer's f32 heights (um) row by row, NaN where not measured
//! (SurfaceTopography `IO/PLUX.py`, surfalize `file/plux.py`). Every layer is a height
//! channel (`layer N`).

use std::io::Cursor;
use std::path::Path;

use super::bin::Bin;
use super::{Channel, FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::Format;
use crate::map::LengthUnit;

const HEADER: usize = 500;
const NON_MEASURED: f32 = 1_000_001.0;
const TOPOGRAPHY: u32 = 3;
/// Layers accepted (PLu files hold one or a few).
const MAX_LAYERS: usize = 255;

/// Whether the bytes start like a PLu file: a `ctime` date (`Www Mmm dd hh:mm:ss yyyy`)
/// with a NUL at byte 24, and room for the header.
pub(crate) fn looks_like_plu(bytes: &[u8]) -> bool {
    if bytes.len() < HEADER + 8 || bytes.get(24) != Some(&0) {
        return false;
    }
    let Ok(s) = std::str::from_utf8(&bytes[..24]) else {
        return false;
    };
    let w: Vec<&str> = s.split_whitespace().collect();
    const DAYS: [&str; 7] = ["Mon", "Tue", "Wed", "Thu", "Fri", "Sat", "Sun"];
    const MONTHS: [&str; 12] = [
        "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
    ];
    w.len() == 5
        && DAYS.contains(&w[0])
        && MONTHS.contains(&w[1])
        && w[2].parse::<u8>().is_ok()
        && w[3].split(':').count() == 3
        && w[3].split(':').all(|p| p.parse::<u8>().is_ok())
        && w[4].parse::<u16>().is_ok()
}

/// Whether a zip archive is a PLUx (an `index.xml` and no x3p `main.xml`).
pub(crate) fn is_plux(bytes: &[u8]) -> bool {
    match zip::ZipArchive::new(Cursor::new(bytes)) {
        Ok(z) => {
            let names: Vec<String> = z
                .file_names()
                .filter_map(|r| r.ok())
                .map(|n| n.into_owned())
                .collect();
            names.iter().any(|n| n == "index.xml") && !names.iter().any(|n| n == "main.xml")
        }
        Err(_) => false,
    }
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    if bytes.starts_with(b"PK\x03\x04") {
        return decode_plux(path, bytes, opts);
    }
    let mut st = Settle::new(path, Format::Plu, opts);
    let b = Bin(bytes);
    if bytes.len() < HEADER + 8 {
        return Err(st.err(
            "header",
            format!(
                "{} bytes: a PLu file has a 500-byte header and its data (truncated?)",
                bytes.len()
            ),
        ));
    }
    if !looks_like_plu(bytes) {
        return Err(st.err(
            "header (date field)",
            "does not start with a date such as \"Tue May 12 10:31:46 2015\": not a Sensofar PLu file",
        ));
    }
    let u32f = |at: usize| b.u32_le(at).unwrap_or(0);
    let ty = u32f(428);
    let (ly, lx) = (u32f(HEADER) as u64, u32f(HEADER + 4) as u64);
    match ty {
        TOPOGRAPHY => {}
        1 | 5 => return Err(st.profile("measure configuration, type", lx.saturating_mul(ly))),
        other => {
            let what = match other {
                0 => "a confocal image",
                2 => "multiple profiles",
                4 => "coordinates",
                6 => "a custom measurement",
                _ => "an unknown measurement type",
            };
            return Err(st.unsupported(
                &format!("a PLu file holding {what} (measurement type {other}), not a topography"),
                "export the topography as .x3p or .plu",
            ));
        }
    }
    let layers = (b.u8(489).unwrap_or(1) as usize).clamp(1, MAX_LAYERS);
    // every layer: its dimensions, data, and (when present) min and max
    let mut spans = Vec::new();
    let mut pos = HEADER;
    for k in 0..layers {
        let loc = format!("layer {k} (byte {pos})");
        let (Some(y), Some(x)) = (b.u32_le(pos), b.u32_le(pos + 4)) else {
            if k == 0 {
                return Err(st.err(loc, "truncated"));
            }
            st.notes.push(format!(
                "the header announces {layers} layers, the file holds {k}"
            ));
            break;
        };
        let (x, y) = (x as u64, y as u64);
        let need = x.checked_mul(y).and_then(|n| n.checked_mul(4));
        let start = pos + 8;
        let end = need
            .and_then(|w| (start as u64).checked_add(w))
            .filter(|&e| e <= bytes.len() as u64);
        let Some(end) = end else {
            if k == 0 {
                return Err(st.err(
                    loc,
                    format!("{x} x {y} points of 4 bytes run past the end of the file ({} bytes): truncated file?", bytes.len()),
                ));
            }
            st.notes.push(format!(
                "the header announces {layers} layers, the file holds {k} whole ones"
            ));
            break;
        };
        spans.push((x, y, start));
        pos = (end as usize).saturating_add(8);
    }
    let list: Vec<Channel> = (0..spans.len())
        .map(|k| Channel::new(format!("layer {k}"), true))
        .collect();
    let k = st.choose_channel(&list)?;
    let (x, y, start) = spans[k];
    if x == 0 || y == 0 {
        return Err(st.err(format!("layer {k}"), format!("an empty layer ({x} x {y})")));
    }
    let n = st.check_points(x, y)?;
    let z: Vec<f64> = bytes[start..start + 4 * n]
        .chunks_exact(4)
        .map(|v| {
            let f = f32::from_le_bytes([v[0], v[1], v[2], v[3]]);
            if f == NON_MEASURED || !f.is_finite() {
                f64::NAN
            } else {
                f64::from(f)
            }
        })
        .collect();
    let (mx, my) = (b.f32_le(404).map(f64::from), b.f32_le(408).map(f64::from));
    let file_spacing = match (mx, my) {
        (Some(a), Some(c)) if a.is_finite() && c.is_finite() && a != 0.0 && c != 0.0 => {
            Some((a.abs() * 1e-6, c.abs() * 1e-6))
        }
        _ => None,
    };
    let spacing = st.spacing(file_spacing)?;
    let um = LengthUnit::parse("um")?;
    let unit = st.height_unit(FileUnit::Length(um), "layer data")?;
    st.finish(x as usize, y as usize, spacing, unit, z)
}

fn child<'a, 'i>(node: roxmltree::Node<'a, 'i>, name: &str) -> Option<roxmltree::Node<'a, 'i>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

fn decode_plux(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Plu, opts);
    let mut zip =
        zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| st.err("archive", e.to_string()))?;
    let xml = super::x3p::entry(
        &st,
        &mut zip,
        "index.xml",
        (16u64 << 20).min(opts.max_bytes),
        false,
    )?
    .ok_or_else(|| st.err("archive", "no index.xml entry: not a Sensofar PLUx file"))?;
    let xml = String::from_utf8(xml).map_err(|_| st.err("index.xml", "not UTF-8"))?;
    let doc = roxmltree::Document::parse(&xml).map_err(|e| st.err("index.xml", e.to_string()))?;
    let root = doc.root_element();
    let general =
        child(root, "GENERAL").ok_or_else(|| st.err("index.xml", "no GENERAL element"))?;
    let text = |name: &str| child(general, name).and_then(|n| n.text()).map(str::trim);
    let int = |st: &Settle, name: &str| -> Result<u64> {
        let t = text(name).ok_or_else(|| st.err(format!("index.xml GENERAL/{name}"), "missing"))?;
        t.parse::<u64>().ok().filter(|&v| v > 0).ok_or_else(|| {
            st.err(
                format!("index.xml GENERAL/{name}"),
                format!("{t:?} is not a positive integer"),
            )
        })
    };
    let (nx, ny) = (int(&st, "IMAGE_SIZE_X")?, int(&st, "IMAGE_SIZE_Y")?);
    let n = st.check_points(nx, ny)?;
    let mut files = Vec::new();
    while let Some(layer) = child(root, &format!("LAYER_{}", files.len())) {
        let f = child(layer, "FILENAME_Z")
            .and_then(|n| n.text())
            .map(|t| t.trim().to_string());
        files.push(f.unwrap_or_default());
        if files.len() >= MAX_LAYERS {
            break;
        }
    }
    let list: Vec<Channel> = (0..files.len())
        .map(|k| Channel::new(format!("layer {k}"), true))
        .collect();
    if list.is_empty() {
        return Err(st.err("index.xml", "no LAYER_0 element: no height data"));
    }
    let k = st.choose_channel(&list)?;
    let name = files[k].clone();
    if name.is_empty() {
        return Err(st.err(format!("index.xml LAYER_{k}/FILENAME_Z"), "missing"));
    }
    let want = n as u64 * 4;
    let data = super::x3p::entry(&st, &mut zip, &name, want, true)?.ok_or_else(|| {
        st.err(
            format!("index.xml LAYER_{k}/FILENAME_Z"),
            format!("{name}: no such entry in the archive"),
        )
    })?;
    let z: Vec<f64> = data
        .chunks_exact(4)
        .map(|v| {
            let f = f32::from_le_bytes([v[0], v[1], v[2], v[3]]);
            if f == NON_MEASURED || !f.is_finite() {
                f64::NAN
            } else {
                f64::from(f)
            }
        })
        .collect();
    let fov = |name: &str| {
        text(name)
            .and_then(|t| t.parse::<f64>().ok())
            .filter(|v| v.is_finite() && *v > 0.0)
    };
    let file_spacing = fov("FOV_X")
        .zip(fov("FOV_Y"))
        .map(|(a, c)| (a * 1e-6, c * 1e-6));
    let spacing = st.spacing(file_spacing)?;
    let um = LengthUnit::parse("um")?;
    let unit = st.height_unit(FileUnit::Length(um), &format!("archive entry {name}"))?;
    st.finish(nx as usize, ny as usize, spacing, unit, z)
}
