//! Gwyddion native `.gwy` files, written from the published format description
//! (Gwyddion user guide, "Format of Gwyddion Files").
//!
//! Little-endian throughout. The magic `GWYP`, then one serialised object: a NUL-terminated
//! type name, a u32 byte size of the component list, then the components, each a
//! NUL-terminated name, a one-byte type and the data:
//! `b` bool (1 byte), `c` char (1), `i` i32, `q` i64, `d` f64, `s` NUL-terminated string,
//! `o` object; upper case for arrays (`C I Q D S O`): a u32 count, then the items.
//!
//! The top object is a `GwyContainer` whose component `/N/data` holds the N-th channel as a
//! `GwyDataField` with `xres`, `yres` (i32), `xreal`, `yreal` (f64, physical size),
//! optional `xoff`, `yoff`, `si_unit_xy`, `si_unit_z` (`GwySIUnit` objects whose `unitstr`
//! is the unit) and `data` (xres * yres f64, row by row). Every channel is listed (its
//! title is `/N/data/title`); the one read is the lowest N whose z unit is a length, or
//! the one `ReadOptions::channel` names.

use std::path::Path;

use super::{Channel, FileUnit, Measurement, ReadOptions, Settle};
use crate::error::{Result, TopographyError};
use crate::io::{read_bounded, Format};
use crate::map::HeightMap;

/// Deepest object nesting accepted (Gwyddion's own files nest 3-4 deep).
const MAX_DEPTH: usize = 64;

/// Reads a `.gwy` file.
pub fn read_gwy(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Measurement> {
    let path = path.as_ref();
    decode(path, &read_bounded(path, opts.max_bytes)?, opts)
}

/// A parsed value; arrays of doubles are kept as a byte range and decoded on demand.
#[derive(Debug)]
enum Value {
    Int(i64),
    Double(f64),
    Str(String),
    Object(Object),
    Doubles { start: usize, count: usize },
    Other,
}

#[derive(Debug)]
struct Object {
    name: String,
    at: usize,
    components: Vec<(String, Value)>,
}

impl Object {
    fn get(&self, name: &str) -> Option<&Value> {
        self.components.iter().find(|c| c.0 == name).map(|c| &c.1)
    }
}

struct Parser<'a, 'b> {
    buf: &'a [u8],
    st: &'b Settle<'b>,
}

impl Parser<'_, '_> {
    fn err(&self, at: usize, message: impl Into<String>) -> TopographyError {
        self.st.err(format!("byte {at}"), message)
    }

    fn take(&self, pos: &mut usize, len: usize, end: usize, what: &str) -> Result<usize> {
        let start = *pos;
        match start.checked_add(len) {
            Some(e) if e <= end => {
                *pos = e;
                Ok(start)
            }
            _ => Err(self.err(
                start,
                format!("{what} needs {len} bytes but only {} remain in its object (truncated or corrupt file)", end - start),
            )),
        }
    }

    fn cstring(&self, pos: &mut usize, end: usize, what: &str) -> Result<String> {
        let start = *pos;
        let Some(len) = self.buf[start..end].iter().position(|&b| b == 0) else {
            return Err(self.err(
                start,
                format!("{what}: no NUL ends the string before the end of its object"),
            ));
        };
        *pos = start + len + 1;
        String::from_utf8(self.buf[start..start + len].to_vec())
            .map_err(|_| self.err(start, format!("{what}: not UTF-8")))
    }

    fn u32(&self, pos: &mut usize, end: usize, what: &str) -> Result<usize> {
        let s = self.take(pos, 4, end, what)?;
        Ok(u32::from_le_bytes([
            self.buf[s],
            self.buf[s + 1],
            self.buf[s + 2],
            self.buf[s + 3],
        ]) as usize)
    }

    fn bytes8(&self, s: usize) -> [u8; 8] {
        let mut b = [0u8; 8];
        b.copy_from_slice(&self.buf[s..s + 8]);
        b
    }

    fn object(&self, pos: &mut usize, end: usize, depth: usize) -> Result<Object> {
        let at = *pos;
        if depth > MAX_DEPTH {
            return Err(self.err(at, format!("objects nested deeper than {MAX_DEPTH}")));
        }
        let name = self.cstring(pos, end, "object type name")?;
        let size = self.u32(pos, end, &format!("size of object {name}"))?;
        let obj_end = self.take(
            pos,
            size,
            end,
            &format!("object {name} (declared {size} bytes)"),
        )? + size;
        let mut p = *pos - size;
        let mut components = Vec::new();
        while p < obj_end {
            let cat = p;
            let cname = self.cstring(&mut p, obj_end, &format!("a component name in {name}"))?;
            let what = format!("component {cname} of {name}");
            let t = self.take(&mut p, 1, obj_end, &what)?;
            let ty = self.buf[t];
            let value = match ty {
                b'b' | b'c' => {
                    self.take(&mut p, 1, obj_end, &what)?;
                    Value::Other
                }
                b'i' => {
                    let s = self.take(&mut p, 4, obj_end, &what)?;
                    let b = &self.buf[s..s + 4];
                    Value::Int(i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as i64)
                }
                b'q' => Value::Int(i64::from_le_bytes(
                    self.bytes8(self.take(&mut p, 8, obj_end, &what)?),
                )),
                b'd' => Value::Double(f64::from_le_bytes(
                    self.bytes8(self.take(&mut p, 8, obj_end, &what)?),
                )),
                b's' => Value::Str(self.cstring(&mut p, obj_end, &what)?),
                b'o' => Value::Object(self.object(&mut p, obj_end, depth + 1)?),
                b'C' | b'I' | b'Q' | b'D' => {
                    let count = self.u32(&mut p, obj_end, &what)?;
                    let item = match ty {
                        b'C' => 1,
                        b'I' => 4,
                        _ => 8,
                    };
                    let start = self.take(
                        &mut p,
                        count.saturating_mul(item),
                        obj_end,
                        &format!("{what} ({count} items)"),
                    )?;
                    if ty == b'D' {
                        Value::Doubles { start, count }
                    } else {
                        Value::Other
                    }
                }
                b'S' => {
                    let count = self.u32(&mut p, obj_end, &what)?;
                    for _ in 0..count {
                        self.cstring(&mut p, obj_end, &what)?;
                    }
                    Value::Other
                }
                b'O' => {
                    let count = self.u32(&mut p, obj_end, &what)?;
                    for _ in 0..count {
                        self.object(&mut p, obj_end, depth + 1)?;
                    }
                    Value::Other
                }
                other => {
                    return Err(self.err(
                        t,
                        format!(
                            "{what}: unknown component type {:?} (corrupt file?)",
                            other as char
                        ),
                    ))
                }
            };
            let _ = cat;
            components.push((cname, value));
        }
        *pos = obj_end;
        Ok(Object {
            name,
            at,
            components,
        })
    }
}

fn unit_of(field: &Object, key: &str) -> FileUnit {
    match field.get(key) {
        Some(Value::Object(u)) => match u.get("unitstr") {
            Some(Value::Str(s)) => FileUnit::from_file(s),
            _ => FileUnit::Absent,
        },
        _ => FileUnit::Absent,
    }
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Gwy, opts);
    if bytes.starts_with(b"GWYO") {
        return Err(st.err(
            "magic",
            "GWYO: the Gwyddion 1.x format is not supported; re-save the file with Gwyddion 2",
        ));
    }
    if !bytes.starts_with(b"GWYP") {
        return Err(st.err("magic", "does not start with GWYP: not a Gwyddion file"));
    }
    let parser = Parser {
        buf: bytes,
        st: &st,
    };
    let mut pos = 4;
    let top = parser.object(&mut pos, bytes.len(), 0)?;
    if pos != bytes.len() {
        return Err(st.err(
            format!("byte {pos}"),
            format!("{} bytes follow the top object", bytes.len() - pos),
        ));
    }
    if top.name != "GwyContainer" {
        return Err(st.err(
            "byte 4",
            format!("the top object is a {}, not a GwyContainer", top.name),
        ));
    }
    let mut channels: Vec<(u64, &str, &Object)> = top
        .components
        .iter()
        .filter_map(|(k, v)| {
            let id = k
                .strip_prefix('/')?
                .strip_suffix("/data")?
                .parse::<u64>()
                .ok()?;
            match v {
                Value::Object(o) if o.name == "GwyDataField" => Some((id, k.as_str(), o)),
                _ => None,
            }
        })
        .collect();
    channels.sort_by_key(|c| c.0);
    if channels.is_empty() {
        return Err(st.err(
            "GwyContainer",
            "no channel: no component /N/data holding a GwyDataField",
        ));
    }
    let title_of = |key: &str| match top.get(&format!("{key}/title")) {
        Some(Value::Str(s)) => Some(s.clone()),
        _ => None,
    };
    let list: Vec<Channel> = channels
        .iter()
        .map(|&(_, key, field)| {
            Channel::new(
                title_of(key).unwrap_or_else(|| key.to_string()),
                matches!(unit_of(field, "si_unit_z"), FileUnit::Length(_)),
            )
        })
        .collect();
    let chosen = {
        let mut probe = Settle::new(path, Format::Gwy, opts);
        let k = probe.choose_channel(&list)?;
        (k, probe.notes, probe.channels)
    };
    let (k, notes, names) = chosen;
    let (_, key, field) = channels[k];
    let title = title_of(key);
    let loc = |c: &str| format!("component {c} of {key} (GwyDataField at byte {})", field.at);
    let int = |c: &str| -> Result<u64> {
        match field.get(c) {
            Some(Value::Int(v)) if *v > 0 => Ok(*v as u64),
            Some(Value::Int(v)) => Err(st.err(loc(c), format!("{v} is not a positive size"))),
            Some(_) => Err(st.err(loc(c), "has the wrong type (expected i)")),
            None => Err(st.err(loc(c), "missing")),
        }
    };
    let real = |c: &str| -> Result<f64> {
        match field.get(c) {
            Some(Value::Double(v)) if v.is_finite() && *v > 0.0 => Ok(*v),
            Some(Value::Double(v)) => {
                Err(st.err(loc(c), format!("{v} is not a positive finite size")))
            }
            Some(_) => Err(st.err(loc(c), "has the wrong type (expected d)")),
            None => Err(st.err(loc(c), "missing")),
        }
    };
    let (nx, ny) = (int("xres")?, int("yres")?);
    let n = st.check_points(nx, ny)?;
    let (xreal, yreal) = (real("xreal")?, real("yreal")?);
    let (start, count) = match field.get("data") {
        Some(Value::Doubles { start, count }) => (*start, *count),
        Some(_) => {
            return Err(st.err(
                loc("data"),
                "has the wrong type (expected D, an array of doubles)",
            ))
        }
        None => return Err(st.err(loc("data"), "missing")),
    };
    if count != n {
        return Err(st.err(
            loc("data"),
            format!("{count} values, but xres x yres = {nx} x {ny} = {n}"),
        ));
    }
    let xy = unit_of(field, "si_unit_xy");
    let zu = unit_of(field, "si_unit_z");
    let z: Vec<f64> = bytes[start..start + 8 * n]
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
        .collect();
    let (xy_loc, z_loc) = (loc("si_unit_xy"), loc("si_unit_z"));
    st.title = Some(title.unwrap_or_else(|| key.to_string()));
    st.notes = notes;
    st.channels = names;
    let file_spacing = match xy {
        FileUnit::Length(u) => Some((
            xreal * u.to_metres / nx as f64,
            yreal * u.to_metres / ny as f64,
        )),
        FileUnit::Absent => None,
        FileUnit::Other(u) if st.opts.spacing.is_none() => {
            return Err(st.err(xy_loc, format!("lateral unit {u:?} is not a length")));
        }
        FileUnit::Other(_) => None,
    };
    let spacing = st.spacing(file_spacing)?;
    let unit = st.height_unit(zu, &z_loc)?;
    st.finish(nx as usize, ny as usize, spacing, unit, z)
}

fn put_name(out: &mut Vec<u8>, name: &str, ty: u8) {
    out.extend_from_slice(name.as_bytes());
    out.push(0);
    out.push(ty);
}

fn object(name: &str, components: &[u8]) -> Vec<u8> {
    let mut o = Vec::with_capacity(name.len() + 5 + components.len());
    o.extend_from_slice(name.as_bytes());
    o.push(0);
    o.extend_from_slice(&(components.len() as u32).to_le_bytes());
    o.extend_from_slice(components);
    o
}

fn si_unit(unit: &str) -> Vec<u8> {
    let mut c = Vec::new();
    put_name(&mut c, "unitstr", b's');
    c.extend_from_slice(unit.as_bytes());
    c.push(0);
    object("GwySIUnit", &c)
}

/// The map as a `.gwy` file: a GwyContainer with channel `/0/data` (title "Height"), sizes
/// and heights in metres.
pub fn encode_gwy(map: &HeightMap) -> Vec<u8> {
    let mut f = Vec::with_capacity(map.heights().len() * 8 + 256);
    put_name(&mut f, "xres", b'i');
    f.extend_from_slice(&(map.nx() as i32).to_le_bytes());
    put_name(&mut f, "yres", b'i');
    f.extend_from_slice(&(map.ny() as i32).to_le_bytes());
    put_name(&mut f, "xreal", b'd');
    f.extend_from_slice(&map.scan_x().to_le_bytes());
    put_name(&mut f, "yreal", b'd');
    f.extend_from_slice(&map.scan_y().to_le_bytes());
    put_name(&mut f, "xoff", b'd');
    f.extend_from_slice(&0f64.to_le_bytes());
    put_name(&mut f, "yoff", b'd');
    f.extend_from_slice(&0f64.to_le_bytes());
    put_name(&mut f, "si_unit_xy", b'o');
    f.extend(si_unit("m"));
    put_name(&mut f, "si_unit_z", b'o');
    f.extend(si_unit("m"));
    put_name(&mut f, "data", b'D');
    f.extend_from_slice(&(map.heights().len() as u32).to_le_bytes());
    for v in map.heights() {
        f.extend_from_slice(&v.to_le_bytes());
    }
    let field = object("GwyDataField", &f);
    let mut c = Vec::with_capacity(field.len() + 64);
    put_name(&mut c, "/0/data", b'o');
    c.extend(field);
    put_name(&mut c, "/0/data/title", b's');
    c.extend_from_slice(b"Height\0");
    let mut out = b"GWYP".to_vec();
    out.extend(object("GwyContainer", &c));
    out
}
