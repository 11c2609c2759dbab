//! Bruker / Veeco / Digital Instruments Nanoscope files (`.spm`, `.di`, `.001`, ...),
//! versions 4.3 to 9.x ("Ciao" headers) and the older 3.x-4.2 headers.
//!
//! Layout, from the published descriptions (S. Manne, "Digital Instrument's Nanoscope file
//! format description" and "Nanoscope 4.3x and later file format description", University of
//! Arizona; NanoScope Command Reference Manual, appendix B "Data File Format", section B.6.3,
//! as summarised by J. R. Hampton, "Additional Information on the Scaling in NanoScope Data
//! Files", 2009), cross-checked against the layouts Gwyddion (`nanoscope.c`) and
//! SurfaceTopography (`IO/DI.py`) read:
//!
//! * a text header (Latin-1, CR LF lines) from `\*File list` to `\*File list end`, in
//!   sections `\*Section name`, each line `\Key: value`; Ciao parameters are
//!   `\@Key: V [soft scale] (hard scale) hard value`, with an optional group `\@2:Key`;
//! * one `\*Ciao image list` (`\*AFM image list`, ... in older files) per image channel:
//!   `\Data offset`, `\Data length`, `\Bytes/pixel` (2 or 4), `\Samps/line` (x points),
//!   `\Number of lines` (y points), `\Scan Size: 5 5 ~m` (x and y sizes; `~m` is um; one
//!   size in old files), `\@2:Image Data: S [Height] "Height"` (the channel),
//!   `\@2:Z scale: V [Sens. Zsens] (0.006713867 V/LSB) 440.0 V`, `\Line Direction`;
//! * the data: little-endian signed integers of `Bytes/pixel` bytes (32-bit from version
//!   9.2 on when the data length says so, as Gwyddion reads them), lines stored bottom up.
//!
//! Heights: z = raw x (hard value / 256^Bytes/pixel) x soft scale, where the soft scale is the
//! value of `\@Sens. Zsens: V 19.56 nm/V` (found in the scanner or scan list) and its unit
//! gives the height unit (`nm/V` -> nm). The hard scale in parentheses is the acquisition's
//! and is not used: the saved data are rescaled to the full integer range (Command
//! Reference Manual B.6.3). `\@Z magnify: C [2:Z scale] ...` is a display scaling that leaves
//! the data alone ("allows the user to change scaling of Z scale off-line without actually
//! affecting the real data in the file") and is not applied, as neither Gwyddion nor
//! SurfaceTopography applies it. Old headers give `\Z scale: 1.575 um` (the full range).
//!
//! Every image list is a channel; a channel is a height channel when its scale resolves to a
//! length. The first height channel is read unless `ReadOptions::channel` names another.
//! Rows are flipped so that row 0 is the last line stored (the top of the image as the
//! instrument and Gwyddion show it). The text-data variant (`?*File list`) and force files
//! are recognised and refused.

use std::path::Path;

use super::bin::{find, latin1};
use super::{Channel, FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::Format;

/// The first bytes of a Nanoscope file: binary, text-data and force variants.
pub(crate) const MAGICS: [&[u8]; 3] = [b"\\*File list", b"?*File list", b"\\*Force file list"];
/// A header longer than this is refused (NanoScope's are 8-80 KiB).
const MAX_HEADER: usize = 8 << 20;

struct Section {
    name: String,
    line: usize,
    entries: Vec<(String, String, usize)>,
}

impl Section {
    fn get(&self, key: &str) -> Option<(&str, usize)> {
        self.entries
            .iter()
            .find(|e| e.0.eq_ignore_ascii_case(key))
            .map(|e| (e.1.as_str(), e.2))
    }
    fn is(&self, names: &[&str]) -> bool {
        names.iter().any(|n| self.name.eq_ignore_ascii_case(n))
    }
}

const IMAGE_LISTS: [&str; 5] = [
    "Ciao image list",
    "AFM image list",
    "STM image list",
    "NCAFM image list",
    "Image list",
];
const SCAN_LISTS: [&str; 4] = ["Ciao scan list", "Afm list", "Stm list", "NC Afm list"];

/// A Ciao value `V [soft] (hard scale) hard value unit`, or an old `value unit`.
struct Value {
    soft: Option<String>,
    hard: f64,
    unit: String,
}

fn parse_number_unit(s: &str) -> Option<(f64, String)> {
    let s = s.trim();
    let end = s.find(char::is_whitespace).unwrap_or(s.len());
    let v = s[..end].parse::<f64>().ok()?;
    Some((v, s[end..].trim().to_string()))
}

fn parse_ciao(value: &str) -> Option<Value> {
    let mut s = value.trim();
    // the type letter (V, C, S), if present
    if let Some(rest) = s
        .strip_prefix(['V', 'C', 'S'])
        .filter(|r| r.starts_with(char::is_whitespace))
    {
        s = rest.trim_start();
    }
    let mut soft = None;
    if let Some(rest) = s.strip_prefix('[') {
        let close = rest.find(']')?;
        let name = rest[..close].trim();
        if !name.is_empty() {
            soft = Some(name.to_string());
        }
        s = rest[close + 1..].trim_start();
    }
    if s.starts_with('(') {
        let mut depth = 0usize;
        let mut end = None;
        for (k, c) in s.char_indices() {
            match c {
                '(' => depth += 1,
                ')' => {
                    depth = depth.saturating_sub(1);
                    if depth == 0 {
                        end = Some(k);
                        break;
                    }
                }
                _ => {}
            }
        }
        s = s[end? + 1..].trim_start();
    }
    let (hard, unit) = parse_number_unit(s)?;
    Some(Value { soft, hard, unit })
}

/// A Nanoscope unit string as a file unit (`~m` is um; Latin-1 µ is decoded already).
fn unit_of(s: &str) -> FileUnit {
    let t = s.trim().replace('~', "u");
    FileUnit::from_file(&t)
}

struct Header {
    sections: Vec<Section>,
}

impl Header {
    /// A key from the first section (not an image list) that has it: scanner and scan lists.
    fn global(&self, key: &str) -> Option<(&str, usize)> {
        self.sections
            .iter()
            .filter(|s| !s.is(&IMAGE_LISTS))
            .find_map(|s| s.get(key))
    }
    fn scan_list(&self) -> Option<&Section> {
        self.sections.iter().find(|s| s.is(&SCAN_LISTS))
    }
}

fn first_number(s: &str) -> Option<f64> {
    s.split_whitespace().next()?.parse::<f64>().ok()
}

/// The scale of an image list: stored units per LSB (before / 256^bpp) and their unit.
fn scale(st: &Settle, h: &Header, img: &Section) -> Result<(f64, FileUnit)> {
    let at = |key: &str, line: usize| format!("header line {line} ({key}, {})", img.name);
    if let Some((v, line)) = img
        .get("@2:Z scale")
        .or_else(|| img.get("@3:Z scale"))
        .or_else(|| img.get("@4:Z scale"))
    {
        let c = parse_ciao(v).ok_or_else(|| {
            st.err(
                at("@2:Z scale", line),
                format!("{v:?} is not V [soft scale] (hard scale) value"),
            )
        })?;
        match c.soft {
            Some(soft) => {
                let key = format!("@{soft}");
                let (sv, sline) = h.global(&key).ok_or_else(|| {
                    st.err(
                        at("@2:Z scale", line),
                        format!("the Z scale refers to the soft scale [{soft}], which the header does not define (\\{key})"),
                    )
                })?;
                let sens = parse_ciao(sv).ok_or_else(|| {
                    st.err(
                        format!("header line {sline} (\\{key})"),
                        format!("{sv:?} is not a value with a unit"),
                    )
                })?;
                let numerator = sens.unit.split('/').next().unwrap_or("").trim().to_string();
                Ok((c.hard * sens.hard, unit_of(&numerator)))
            }
            None => Ok((c.hard, unit_of(&c.unit))),
        }
    } else if let Some((v, line)) = img.get("Z scale") {
        // old headers: the full range, value and unit (a length, or V/LSB)
        let (x, unit) = parse_number_unit(v).ok_or_else(|| {
            st.err(
                at("Z scale", line),
                format!("{v:?} is not a value with a unit"),
            )
        })?;
        let unit = unit.split('(').next().unwrap_or("").trim().to_string();
        Ok((x, unit_of(&unit)))
    } else {
        Err(st.err(
            format!("{} at header line {}", img.name, img.line),
            "no \\@2:Z scale (nor \\Z scale): the heights cannot be scaled",
        ))
    }
}

fn channel_name(img: &Section, k: usize) -> String {
    let base = img
        .get("@2:Image Data")
        .or_else(|| img.get("@3:Image Data"))
        .map(|(v, _)| {
            if let (Some(a), Some(b)) = (v.find('"'), v.rfind('"')) {
                if b > a + 1 {
                    return v[a + 1..b].to_string();
                }
            }
            match (v.find('['), v.find(']')) {
                (Some(a), Some(b)) if b > a + 1 => v[a + 1..b].to_string(),
                _ => v.trim().to_string(),
            }
        })
        .or_else(|| img.get("Image data").map(|(v, _)| v.trim().to_string()))
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| format!("image {k}"));
    match img.get("Line Direction") {
        Some((d, _)) if !d.trim().is_empty() => format!("{base} ({})", d.trim()),
        _ => base,
    }
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Nanoscope, opts);
    if bytes.starts_with(b"?*File list") {
        return Err(st.unsupported(
            "a Nanoscope file with text data (?*File list)",
            "export it from NanoScope Analysis as a binary .spm, or as .x3p",
        ));
    }
    if bytes.starts_with(b"\\*Force file list") {
        return Err(st.unsupported(
            "a Nanoscope force-curve file (\\*Force file list), not an image",
            "a height map needs an image capture; export the height image as .x3p",
        ));
    }
    if !bytes.starts_with(b"\\*File list") {
        return Err(st.err(
            "magic",
            "does not start with \\*File list: not a Nanoscope file",
        ));
    }
    let search = &bytes[..bytes.len().min(MAX_HEADER)];
    let end = find(search, b"\\*File list end").ok_or_else(|| {
        st.err(
            "header",
            if bytes.len() > MAX_HEADER {
                "no \\*File list end within 8 MiB"
            } else {
                "no \\*File list end: the header is truncated"
            },
        )
    })?;
    let text = latin1(&bytes[..end]);
    let mut sections: Vec<Section> = Vec::new();
    for (k, raw) in text.split('\n').enumerate() {
        let line_no = k + 1;
        let l = raw.trim();
        if l.is_empty() {
            continue;
        }
        if let Some(name) = l.strip_prefix("\\*") {
            sections.push(Section {
                name: name.trim().to_string(),
                line: line_no,
                entries: Vec::new(),
            });
        } else if let Some(rest) = l.strip_prefix('\\') {
            // a group prefix "@2:" holds a colon of its own
            let skip = if let Some(group) = rest.strip_prefix('@') {
                let digits = group.bytes().take_while(u8::is_ascii_digit).count();
                if digits > 0 && rest.as_bytes().get(1 + digits) == Some(&b':') {
                    digits + 2
                } else {
                    0
                }
            } else {
                0
            };
            let (key, value) = match rest[skip..].find(':') {
                Some(c) => (&rest[..skip + c], rest[skip + c + 1..].trim()),
                None => (rest, ""),
            };
            let Some(sec) = sections.last_mut() else {
                return Err(st.err(
                    format!("header line {line_no}"),
                    "a parameter before any \\*section",
                ));
            };
            sec.entries
                .push((key.trim().to_string(), value.to_string(), line_no));
        }
    }
    let h = Header { sections };
    let images: Vec<&Section> = h.sections.iter().filter(|s| s.is(&IMAGE_LISTS)).collect();
    let list: Vec<Channel> = images
        .iter()
        .enumerate()
        .map(|(k, img)| {
            let height = matches!(scale(&st, &h, img), Ok((_, FileUnit::Length(_))));
            Channel::new(channel_name(img, k), height)
        })
        .collect();
    if list.is_empty() {
        return Err(st.unsupported(
            "a Nanoscope file with no image (no \\*Ciao image list)",
            "export the height image as .x3p",
        ));
    }
    if !list.iter().any(|c| c.height) && opts.channel.is_none() {
        let names: Vec<String> = list.iter().map(|c| format!("{:?}", c.name)).collect();
        return Err(st.unsupported(
            &format!(
                "a Nanoscope file without a height channel (its channels: {}, none scaled to a length)",
                names.join(", ")
            ),
            "export the height channel as .x3p, or choose a channel with --channel and give its --height-unit",
        ));
    }
    let k = st.choose_channel(&list)?;
    let img = images[k];
    let loc = |key: &str| match img.get(key) {
        Some((_, line)) => format!("header line {line} ({key}, {})", img.name),
        None => format!("{} at header line {} ({key})", img.name, img.line),
    };
    let int = |st: &Settle, key: &str| -> Result<u64> {
        let (v, _) = img.get(key).ok_or_else(|| st.err(loc(key), "missing"))?;
        first_number(v)
            .filter(|x| x.is_finite() && *x >= 0.0 && x.fract() == 0.0 && *x < 9.0e15)
            .map(|x| x as u64)
            .ok_or_else(|| st.err(loc(key), format!("{v:?} is not a non-negative integer")))
    };
    let mut nx = int(&st, "Samps/line")?;
    let mut ny = int(&st, "Number of lines")?;
    if nx == 0 || ny == 0 {
        return Err(st.err(loc("Samps/line"), format!("an empty image ({nx} x {ny})")));
    }
    let offset = int(&st, "Data offset")?;
    let length = int(&st, "Data length")?;
    let qbpp = match img.get("Bytes/pixel") {
        None => 2,
        Some(_) => int(&st, "Bytes/pixel")?,
    };
    if qbpp != 2 && qbpp != 4 {
        return Err(st.err(loc("Bytes/pixel"), format!("{qbpp}: expected 2 or 4")));
    }
    let version = h
        .global("Version")
        .and_then(|(v, _)| {
            u64::from_str_radix(
                v.trim().trim_start_matches("0x").trim_start_matches("0X"),
                16,
            )
            .ok()
        })
        .unwrap_or(0);
    // scan size: this image's, else the scan list's
    let (size_text, size_line) = img
        .get("Scan Size")
        .or_else(|| h.global("Scan Size"))
        .ok_or_else(|| st.err(loc("Scan Size"), "missing"))?;
    let nums: Vec<f64> = size_text
        .split_whitespace()
        .map_while(|t| t.parse::<f64>().ok())
        .collect();
    let unit_text: String = size_text
        .split_whitespace()
        .skip(nums.len())
        .collect::<Vec<_>>()
        .join(" ");
    let (mut xreal, mut yreal) = match nums.as_slice() {
        [x] => (*x, *x),
        [x, y, ..] => (*x, *y),
        [] => {
            return Err(st.err(
                format!("header line {size_line} (Scan Size)"),
                format!("{size_text:?} is not a size with a unit"),
            ))
        }
    };
    let xy_unit = match unit_of(&unit_text) {
        FileUnit::Length(u) => Some(u),
        _ if opts.spacing.is_some() => None,
        _ => {
            return Err(st.err(
                format!("header line {size_line} (Scan Size)"),
                format!("{unit_text:?} is not a length unit"),
            ))
        }
    };
    // 16-bit data, or 32-bit (Bytes/pixel 4, or version 9.2 and later when the length says so)
    let n0 = st.check_points(nx, ny)?;
    let elem: u64 = if qbpp == 4 || (version >= 0x0920_0000 && length >= 4 * n0 as u64) {
        4
    } else {
        2
    };
    let (gx, gy) = match h.scan_list() {
        Some(s) => (
            s.get("Samps/line").and_then(|(v, _)| first_number(v)),
            s.get("Lines").and_then(|(v, _)| first_number(v)),
        ),
        None => (None, None),
    };
    let need = |nx: u64, ny: u64| nx.checked_mul(ny).and_then(|n| n.checked_mul(elem));
    if need(nx, ny) != Some(length) {
        match (gx, gy) {
            (Some(gx), Some(gy))
                if gx >= 1.0 && gy >= 1.0 && gx < 1e9 && gy < 1e9
                    && need(gx as u64, gy as u64) == Some(length) =>
            {
                st.notes.push(format!(
                    "the image list's size {nx} x {ny} does not match its data length ({length} bytes); the scan list's {gx} x {gy} does and was used"
                ));
                xreal *= gx / nx as f64;
                yreal *= gy / ny as f64;
                nx = gx as u64;
                ny = gy as u64;
            }
            _ if need(nx, ny).is_some_and(|w| w < length) => st.notes.push(format!(
                "the data length ({length} bytes) exceeds the {nx} x {ny} image's; the first bytes were read"
            )),
            _ => {
                return Err(st.err(
                    loc("Data length"),
                    format!(
                        "{length} bytes, but {nx} x {ny} points of {elem} bytes need {}",
                        need(nx, ny).map_or("more than 2^64".to_string(), |w| w.to_string())
                    ),
                ))
            }
        }
    } else {
        // a non-square aspect: the scan size is the square frame's (Gwyddion's reading)
        let aspect = |s: &Section| {
            s.get("Aspect ratio")
                .and_then(|(v, _)| {
                    v.split(':')
                        .next()
                        .and_then(|a| a.trim().parse::<f64>().ok())
                })
                .is_some_and(|a| a > 0.0 && a != 1.0)
        };
        if aspect(img) {
            let scale = match (h.scan_list().is_some_and(aspect), gy) {
                (false, Some(gy)) if gy >= 1.0 => ny as f64 / gy,
                _ => ny as f64 / nx as f64,
            };
            if scale != 1.0 {
                yreal *= scale;
                st.notes.push(format!(
                    "a non-square aspect ratio: the y scan size was scaled by {scale} to the image's {ny} lines"
                ));
            }
        }
    }
    let n = st.check_points(nx, ny)?;
    let bytes_needed = (n as u64) * elem;
    let end_data = offset
        .checked_add(bytes_needed)
        .filter(|&e| e <= bytes.len() as u64);
    let Some(end_data) = end_data else {
        return Err(st.err(
            loc("Data offset"),
            format!(
                "the image's {bytes_needed} bytes at offset {offset} run past the end of the file ({} bytes): truncated file?",
                bytes.len()
            ),
        ));
    };
    let (per_lsb, unit) = scale(&st, &h, img)?;
    let q = per_lsb / 256f64.powi(qbpp as i32);
    let data = &bytes[offset as usize..end_data as usize];
    let raw: Vec<f64> = if elem == 4 {
        data.chunks_exact(4)
            .map(|b| f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])) * q)
            .collect()
    } else {
        data.chunks_exact(2)
            .map(|b| f64::from(i16::from_le_bytes([b[0], b[1]])) * q)
            .collect()
    };
    let (nxu, nyu) = (nx as usize, ny as usize);
    let mut z = Vec::with_capacity(n);
    for row in raw.chunks_exact(nxu).rev() {
        z.extend_from_slice(row);
    }
    let file_spacing = xy_unit.map(|u| {
        (
            xreal.abs() * u.to_metres / nx as f64,
            yreal.abs() * u.to_metres / ny as f64,
        )
    });
    let file_spacing =
        file_spacing.filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite());
    let spacing = st.spacing(file_spacing)?;
    let unit = match unit {
        FileUnit::Length(u) => FileUnit::Length(u),
        FileUnit::Other(s) => FileUnit::Other(s),
        FileUnit::Absent => FileUnit::Other("V".to_string()),
    };
    let zloc = loc("@2:Z scale");
    let unit = st.height_unit(unit, &zloc)?;
    st.finish(nxu, nyu, spacing, unit, z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ciao_values_parse() {
        let v = parse_ciao("V [Sens. Zsens] (0.006713867 V/LSB) 440.0000 V").unwrap();
        assert_eq!(v.soft.as_deref(), Some("Sens. Zsens"));
        assert_eq!(v.hard, 440.0);
        assert_eq!(v.unit, "V");
        let v = parse_ciao("V 19.56 nm/V").unwrap();
        assert_eq!((v.soft, v.hard, v.unit.as_str()), (None, 19.56, "nm/V"));
        let v = parse_ciao("V (0.0001 (x) V/LSB) 2.5 V").unwrap();
        assert_eq!(v.hard, 2.5);
        assert!(parse_ciao("V [unclosed 3 V").is_none());
        assert!(matches!(unit_of("~m"), FileUnit::Length(u) if u.to_metres == 1e-6));
    }
}
