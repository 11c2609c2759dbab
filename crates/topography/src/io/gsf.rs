//! Gwyddion Simple Field `.gsf`.
//!
//! The magic line `Gwyddion Simple Field 1.0`, header lines `name = value` (XRes and YRes
//! mandatory; XReal, YReal (physical size, default 1 in Gwyddion: here, absent means "no
//! spacing"), XOffset, YOffset, Title, XYUnits, ZUnits optional), one to four NUL bytes
//! aligning the data to a multiple of 4, then XRes * YRes little-endian 32-bit floats, row by
//! row (Gwyddion user guide, "Gwyddion Simple Field").

use std::fmt::Write as _;
use std::path::Path;

use super::{FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::{read_bounded, Format};
use crate::map::HeightMap;

const MAGIC: &[u8] = b"Gwyddion Simple Field 1.0\n";
/// A header longer than this is refused (Gwyddion's own are a few hundred bytes).
const MAX_HEADER: usize = 1 << 20;

/// Reads a `.gsf` file.
pub fn read_gsf(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Measurement> {
    let path = path.as_ref();
    decode(path, &read_bounded(path, opts.max_bytes)?, opts)
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Gsf, opts);
    if !bytes.starts_with(MAGIC) {
        return Err(st.err(
            "magic line",
            "does not start with \"Gwyddion Simple Field 1.0\": not a GSF file",
        ));
    }
    let search = &bytes[..bytes.len().min(MAX_HEADER)];
    let Some(nul) = search.iter().position(|&b| b == 0) else {
        return Err(st.err(
            "header",
            if bytes.len() > MAX_HEADER {
                "no NUL byte ends the header within 1 MiB"
            } else {
                "no NUL byte ends the header (truncated file?)"
            },
        ));
    };
    let text = std::str::from_utf8(&bytes[MAGIC.len()..nul])
        .map_err(|_| st.err("header", "not UTF-8 text"))?;
    let data_start = (nul / 4 + 1) * 4;
    if bytes.len() < data_start || bytes[nul..data_start].iter().any(|&b| b != 0) {
        return Err(st.err(
            "header padding",
            "the header must end with 1 to 4 NUL bytes aligning the data to a multiple of 4",
        ));
    }
    let mut fields: Vec<(&str, &str, usize)> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line_no = k + 2;
        if line.trim().is_empty() {
            continue;
        }
        let Some((name, value)) = line.split_once('=') else {
            return Err(st.err(
                format!("header line {line_no}"),
                format!("{line:?} is not name = value"),
            ));
        };
        fields.push((name.trim(), value.trim(), line_no));
    }
    let get = |name: &str| fields.iter().find(|f| f.0 == name);
    let int = |st: &Settle, name: &str| -> Result<u64> {
        let (_, v, l) = get(name)
            .ok_or_else(|| st.err(format!("header field {name}"), "missing (mandatory)"))?;
        v.parse::<u64>().ok().filter(|&n| n > 0).ok_or_else(|| {
            st.err(
                format!("header field {name} (line {l})"),
                format!("{v:?} is not a positive integer"),
            )
        })
    };
    let real = |st: &Settle, name: &str| -> Result<Option<f64>> {
        match get(name) {
            None => Ok(None),
            Some((_, v, l)) => v
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x > 0.0)
                .map(Some)
                .ok_or_else(|| {
                    st.err(
                        format!("header field {name} (line {l})"),
                        format!("{v:?} is not a positive number"),
                    )
                }),
        }
    };
    let (nx, ny) = (int(&st, "XRes")?, int(&st, "YRes")?);
    let n = st.check_points(nx, ny)?;
    let want = n as u64 * 4;
    let have = (bytes.len() - data_start) as u64;
    if have != want {
        return Err(st.err(
            "data",
            format!(
                "{have} bytes of data after the header, but XRes x YRes = {nx} x {ny} floats need {want}{}",
                if have < want { " (truncated file)" } else { "" }
            ),
        ));
    }
    let (xr, yr) = (real(&st, "XReal")?, real(&st, "YReal")?);
    st.title = get("Title").map(|f| f.1.to_string());
    let xy = get("XYUnits").map_or(FileUnit::Absent, |f| FileUnit::from_file(f.1));
    let file_spacing = match (xr, yr, &xy) {
        (Some(x), Some(y), FileUnit::Length(u)) => {
            Some((x * u.to_metres / nx as f64, y * u.to_metres / ny as f64))
        }
        (Some(x), Some(y), FileUnit::Absent) => {
            st.notes
                .push("XYUnits is absent: XReal and YReal are taken in metres".to_string());
            Some((x / nx as f64, y / ny as f64))
        }
        (Some(_), Some(_), FileUnit::Other(u)) => {
            return Err(st.err(
                "header field XYUnits",
                format!("{u:?} is not a length unit"),
            ));
        }
        _ => None,
    };
    let spacing = st.spacing(file_spacing)?;
    let zu = get("ZUnits").map_or(FileUnit::Absent, |f| FileUnit::from_file(f.1));
    let unit = st.height_unit(zu, "header field ZUnits")?;
    let z: Vec<f64> = bytes[data_start..]
        .chunks_exact(4)
        .map(|b| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])))
        .collect();
    st.finish(nx as usize, ny as usize, spacing, unit, z)
}

/// The map as a GSF file (heights and sizes in metres, 32-bit floats: relative precision 6e-8).
pub fn encode_gsf(map: &HeightMap) -> Vec<u8> {
    let mut h = String::from_utf8_lossy(MAGIC).into_owned();
    let _ = writeln!(h, "XRes = {}", map.nx());
    let _ = writeln!(h, "YRes = {}", map.ny());
    let _ = writeln!(h, "XReal = {:e}", map.scan_x());
    let _ = writeln!(h, "YReal = {:e}", map.scan_y());
    let _ = writeln!(h, "XYUnits = m");
    let _ = writeln!(h, "ZUnits = m");
    let _ = writeln!(h, "Title = Height");
    let mut out = h.into_bytes();
    let pad = 4 - out.len() % 4;
    out.extend(std::iter::repeat_n(0u8, pad));
    for &v in map.heights() {
        out.extend_from_slice(&(v as f32).to_le_bytes());
    }
    out
}
