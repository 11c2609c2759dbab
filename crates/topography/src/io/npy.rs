//! NumPy `.npy` arrays (through the `npyz` crate).
//!
//! A 2-D array of shape (ny, nx): rows are y. Floats (f4, f8) and integers (1-8 bytes,
//! signed or not) of either byte order, C or Fortran order. The format carries no units:
//! the spacing and the height unit come from the options.

use std::path::Path;

use npyz::{DType, NpyFile, NpyHeader, Order, TypeChar, WriterBuilder};

use super::{FileUnit, Measurement, ReadOptions, Settle};
use crate::error::Result;
use crate::io::{read_bounded, Format};
use crate::map::HeightMap;

/// Reads a `.npy` file.
pub fn read_npy(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Measurement> {
    let path = path.as_ref();
    decode(path, &read_bounded(path, opts.max_bytes)?, opts)
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::Npy, opts);
    if !bytes.starts_with(b"\x93NUMPY") {
        return Err(st.err("magic", "does not start with \\x93NUMPY: not a .npy file"));
    }
    // The header length is checked against the file before npyz allocates it.
    let declared = match bytes.get(6) {
        Some(1) => bytes
            .get(8..10)
            .map(|b| u16::from_le_bytes([b[0], b[1]]) as usize + 10),
        Some(2 | 3) => bytes
            .get(8..12)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize + 12),
        _ => {
            return Err(st.err(
                "version",
                match bytes.get(6..8) {
                    Some(v) => format!(
                        "unknown .npy format version {}.{} (1.0, 2.0 and 3.0 are read)",
                        v[0], v[1]
                    ),
                    None => "the file ends before its format version".to_string(),
                },
            ))
        }
    };
    match declared {
        Some(end) if end <= bytes.len() => {}
        _ => {
            return Err(st.err(
                "header",
                "the header is longer than the file (truncated file)",
            ))
        }
    }
    let mut reader: &[u8] = bytes;
    let header =
        NpyHeader::from_reader(&mut reader).map_err(|e| st.err("header", e.to_string()))?;
    let have = reader.len() as u64;
    let file = NpyFile::with_header(header, reader);
    let shape = file.shape().to_vec();
    if shape.len() == 1 {
        return Err(st.profile("header field shape", shape[0]));
    }
    if shape.len() != 2 {
        return Err(st.err(
            "header field shape",
            format!("{shape:?}: a height map is a 2-D array (rows = y, columns = x)"),
        ));
    }
    let (ny, nx) = (shape[0], shape[1]);
    let n = st.check_points(nx, ny)?;
    let DType::Plain(ts) = file.dtype() else {
        return Err(st.err(
            "header field descr",
            "a structured or nested dtype; expected floats or integers",
        ));
    };
    let size = ts.size_field();
    let ok = match ts.type_char() {
        TypeChar::Float => matches!(size, 4 | 8),
        TypeChar::Int | TypeChar::Uint => matches!(size, 1 | 2 | 4 | 8),
        _ => false,
    };
    if !ok {
        return Err(st.err(
            "header field descr",
            format!("dtype {ts}: expected float32/64 or an integer type"),
        ));
    }
    let order = file.order();
    // The data must be exactly n items: check before decoding.
    let want = n as u64 * size;
    if have != want {
        return Err(st.err(
            "data",
            format!(
                "{have} bytes of data, but shape ({ny}, {nx}) of {ts} needs {want}{}",
                if have < want { " (truncated file)" } else { "" }
            ),
        ));
    }
    let read_err = |e: std::io::Error| st.err("data", e.to_string());
    let raw: Vec<f64> = match (ts.type_char(), size) {
        (TypeChar::Float, 4) => file
            .into_vec::<f32>()
            .map_err(read_err)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Float, _) => file.into_vec::<f64>().map_err(read_err)?,
        (TypeChar::Int, 1) => file
            .into_vec::<i8>()
            .map_err(read_err)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Int, 2) => file
            .into_vec::<i16>()
            .map_err(read_err)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Int, 4) => file
            .into_vec::<i32>()
            .map_err(read_err)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (TypeChar::Int, _) => file
            .into_vec::<i64>()
            .map_err(read_err)?
            .into_iter()
            .map(|v| v as f64)
            .collect(),
        (_, 1) => file
            .into_vec::<u8>()
            .map_err(read_err)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (_, 2) => file
            .into_vec::<u16>()
            .map_err(read_err)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (_, 4) => file
            .into_vec::<u32>()
            .map_err(read_err)?
            .into_iter()
            .map(f64::from)
            .collect(),
        (_, _) => file
            .into_vec::<u64>()
            .map_err(read_err)?
            .into_iter()
            .map(|v| v as f64)
            .collect(),
    };
    let (nx, ny) = (nx as usize, ny as usize);
    let z = match order {
        Order::C => raw,
        Order::Fortran => {
            // element (row r, column c) is at c * ny + r
            let mut z = vec![0.0; n];
            for c in 0..nx {
                for r in 0..ny {
                    z[r * nx + c] = raw[c * ny + r];
                }
            }
            z
        }
    };
    let spacing = st.spacing(None)?;
    let unit = st.height_unit(FileUnit::Absent, "header")?;
    st.finish(nx, ny, spacing, unit, z)
}

/// The map as a little-endian f64 `.npy` array of shape (ny, nx), in metres. The format
/// has no place for the spacing: give it when reading back.
pub fn encode_npy(map: &HeightMap) -> Vec<u8> {
    fn write(map: &HeightMap, buf: &mut Vec<u8>) -> std::io::Result<()> {
        let mut w = npyz::WriteOptions::new()
            .default_dtype()
            .shape(&[map.ny() as u64, map.nx() as u64])
            .writer(buf)
            .begin_nd()?;
        w.extend(map.heights().iter().copied())?;
        w.finish()
    }
    let mut buf = Vec::new();
    // Writing to a Vec cannot fail.
    let _ = write(map, &mut buf);
    buf
}
