//! ISO 25178-72 `.x3p` (XML 3D surface profile), the openly documented exchange format of
//! areal topography (openGPS reference implementation and schema ISO5436_2.xsd).
//!
//! A zip archive holding `main.xml` (root `ISO5436_2`) and, for binary data, the file its
//! `Record3/DataLink/PointDataLink` names (usually `bindata/data.bin`). Read here:
//!
//! * `Record1/FeatureType` = `SUR` (an areal surface; `PRF` profiles and `PCL` point clouds
//!   are refused);
//! * `Record1/Axes/CX`, `CY`: `AxisType` `I` (incremental) with `Increment` (the spacing, m)
//!   and `Offset`; `CZ`: `AxisType` `A`, `DataType` `I` (i16), `L` (i32), `F` (f32) or `D`
//!   (f64), optional `Increment` and `Offset` (z = Offset + Increment * raw);
//! * `Record3/MatrixDimension/SizeX`, `SizeY`, `SizeZ` (= 1 layer);
//! * the data: little-endian values, x fastest, or `Record3/DataList/Datum` elements;
//!   `MD5ChecksumPointData`, when present, is verified; invalid points (NaN, an empty
//!   `Datum`, or a 0 bit in `bindata/valid.bin`) are undefined points.
//!
//! x3p stores SI units (metres) by definition, so the height unit is known.

use std::io::{Cursor, Read, Write};
use std::path::Path;

use md5::{Digest, Md5};

use super::{FileUnit, Measurement, ReadOptions, Settle};
use crate::error::{Result, TopographyError};
use crate::io::{read_bounded, Format};
use crate::map::{HeightMap, LengthUnit};

/// Largest `main.xml` accepted (bytes).
const MAX_XML: u64 = 64 << 20;

/// Reads a `.x3p` file.
pub fn read_x3p(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Measurement> {
    let path = path.as_ref();
    decode(path, &read_bounded(path, opts.max_bytes)?, opts)
}

fn hex(d: &[u8]) -> String {
    d.iter().map(|b| format!("{b:02x}")).collect()
}

/// Reads a zip entry with a cap, checking the declared size first.
pub(crate) fn entry(
    st: &Settle,
    zip: &mut zip::ZipArchive<Cursor<&[u8]>>,
    name: &str,
    cap: u64,
    exact: bool,
) -> Result<Option<Vec<u8>>> {
    let mut f = match zip.by_name(name) {
        Ok(f) => f,
        Err(zip::result::ZipError::FileNotFound) => return Ok(None),
        Err(e) => return Err(st.err(format!("archive entry {name}"), e.to_string())),
    };
    if exact && f.size() != cap {
        return Err(st.err(
            format!("archive entry {name}"),
            format!(
                "{} bytes, but main.xml's grid and data type need {cap}",
                f.size()
            ),
        ));
    }
    if f.size() > cap {
        return Err(TopographyError::TooLarge {
            path: st.path.to_path_buf(),
            what: format!("archive entry {name} ({} bytes uncompressed)", f.size()),
            limit: cap,
            unit: "bytes",
        });
    }
    let mut buf = Vec::new();
    (&mut f).take(cap + 1).read_to_end(&mut buf).map_err(|e| {
        st.err(
            format!("archive entry {name}"),
            format!("cannot decompress: {e}"),
        )
    })?;
    if buf.len() as u64 > cap {
        return Err(TopographyError::TooLarge {
            path: st.path.to_path_buf(),
            what: format!("archive entry {name} (decompresses beyond its declared size)"),
            limit: cap,
            unit: "bytes",
        });
    }
    Ok(Some(buf))
}

fn child<'a, 'i>(node: roxmltree::Node<'a, 'i>, name: &str) -> Option<roxmltree::Node<'a, 'i>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

fn path_text<'a>(root: roxmltree::Node<'a, '_>, path: &[&str]) -> Option<&'a str> {
    let mut n = root;
    for p in path {
        n = child(n, p)?;
    }
    n.text().map(str::trim)
}

pub(crate) fn decode(path: &Path, bytes: &[u8], opts: &ReadOptions) -> Result<Measurement> {
    let mut st = Settle::new(path, Format::X3p, opts);
    if !bytes.starts_with(b"PK\x03\x04") {
        return Err(st.err(
            "archive",
            "does not start with a zip signature (PK): not an x3p file",
        ));
    }
    let mut zip =
        zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| st.err("archive", e.to_string()))?;
    let xml_bytes = entry(
        &st,
        &mut zip,
        "main.xml",
        MAX_XML.min(opts.max_bytes),
        false,
    )?
    .ok_or_else(|| {
        st.err(
            "archive",
            if zip
                .file_names()
                .filter_map(|r| r.ok())
                .any(|n| n == "index.xml")
            {
                "no main.xml entry (an index.xml: a Sensofar .plux file? read it as plu)"
            } else {
                "no main.xml entry"
            },
        )
    })?;
    let xml = std::str::from_utf8(&xml_bytes).map_err(|_| st.err("main.xml", "not UTF-8"))?;
    let doc = roxmltree::Document::parse(xml).map_err(|e| st.err("main.xml", e.to_string()))?;
    let root = doc.root_element();
    if root.tag_name().name() != "ISO5436_2" {
        return Err(st.err(
            "main.xml",
            format!(
                "root element {}, expected ISO5436_2",
                root.tag_name().name()
            ),
        ));
    }
    let get = |p: &[&str]| path_text(root, p);
    let field = |p: &[&str]| format!("main.xml {}", p.join("/"));
    let need = |st: &Settle, p: &[&str]| get(p).ok_or_else(|| st.err(field(p), "missing"));
    let number = |st: &Settle, p: &[&str], default: Option<f64>| -> Result<f64> {
        match get(p) {
            None => default.ok_or_else(|| st.err(field(p), "missing")),
            Some(t) => t
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| st.err(field(p), format!("{t:?} is not a number"))),
        }
    };
    let feature = need(&st, &["Record1", "FeatureType"])?;
    if feature != "SUR" {
        return Err(st.err(
            field(&["Record1", "FeatureType"]),
            match feature {
                "PRF" => {
                    "PRF: a 1-D profile: the model needs a 2-D height map (an areal surface, SUR)"
                        .to_string()
                }
                _ => format!(
                    "{feature}: only areal surfaces (SUR) are height maps (PCL is a point cloud)"
                ),
            },
        ));
    }
    let mut inc = [0.0; 2];
    for (k, ax) in ["CX", "CY"].iter().enumerate() {
        let t = need(&st, &["Record1", "Axes", ax, "AxisType"])?;
        if t != "I" {
            return Err(st.err(
                field(&["Record1", "Axes", ax, "AxisType"]),
                format!(
                    "{t}: only incremental (I) lateral axes, i.e. a regular grid, are supported"
                ),
            ));
        }
        let v = number(&st, &["Record1", "Axes", ax, "Increment"], None)?;
        if !(v > 0.0) {
            return Err(st.err(
                field(&["Record1", "Axes", ax, "Increment"]),
                format!("{v} is not a positive spacing"),
            ));
        }
        inc[k] = v;
    }
    let dtype = need(&st, &["Record1", "Axes", "CZ", "DataType"])?.to_string();
    let size = match dtype.as_str() {
        "I" => 2,
        "L" => 4,
        "F" => 4,
        "D" => 8,
        other => {
            return Err(st.err(
                field(&["Record1", "Axes", "CZ", "DataType"]),
                format!("{other}: expected I, L, F or D"),
            ))
        }
    };
    let z_inc = number(&st, &["Record1", "Axes", "CZ", "Increment"], Some(1.0))?;
    let z_off = number(&st, &["Record1", "Axes", "CZ", "Offset"], Some(0.0))?;
    let dim = |st: &Settle, d: &str| -> Result<u64> {
        let p = ["Record3", "MatrixDimension", d];
        let t = need(st, &p)?;
        t.parse::<u64>()
            .map_err(|_| st.err(field(&p), format!("{t:?} is not a size")))
    };
    let (nx, ny, nz) = (dim(&st, "SizeX")?, dim(&st, "SizeY")?, dim(&st, "SizeZ")?);
    if nz != 1 {
        return Err(st.err(
            field(&["Record3", "MatrixDimension", "SizeZ"]),
            format!("{nz} layers; one is supported"),
        ));
    }
    let n = st.check_points(nx, ny)?;
    let mut raw: Vec<f64> = if let Some(link) = get(&["Record3", "DataLink", "PointDataLink"]) {
        let want = n as u64 * size;
        let data = entry(&st, &mut zip, link, want, true)?.ok_or_else(|| {
            st.err(
                field(&["Record3", "DataLink", "PointDataLink"]),
                format!("{link}: no such entry in the archive"),
            )
        })?;
        if data.len() as u64 != want {
            return Err(st.err(
                format!("archive entry {link}"),
                format!("{} bytes, but {nx} x {ny} values of type {dtype} need {want} (truncated file?)", data.len()),
            ));
        }
        if let Some(sum) = get(&["Record3", "DataLink", "MD5ChecksumPointData"]) {
            let got = hex(&Md5::digest(&data));
            if !got.eq_ignore_ascii_case(sum) {
                return Err(st.err(
                    format!("archive entry {link}"),
                    format!("MD5 checksum {got} differs from {sum} in main.xml (corrupt data)"),
                ));
            }
        }
        match dtype.as_str() {
            "I" => data
                .chunks_exact(2)
                .map(|b| f64::from(i16::from_le_bytes([b[0], b[1]])))
                .collect(),
            "L" => data
                .chunks_exact(4)
                .map(|b| f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])))
                .collect(),
            "F" => data
                .chunks_exact(4)
                .map(|b| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])))
                .collect(),
            _ => data
                .chunks_exact(8)
                .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
                .collect(),
        }
    } else if let Some(list) = child(root, "Record3").and_then(|r| child(r, "DataList")) {
        let mut v = Vec::with_capacity(n.min(1 << 20));
        for (k, d) in list
            .children()
            .filter(|c| c.is_element() && c.tag_name().name() == "Datum")
            .enumerate()
        {
            if k >= n {
                return Err(st.err(
                    "main.xml Record3/DataList",
                    format!("more than SizeX x SizeY = {n} Datum elements"),
                ));
            }
            let t = d.text().map(str::trim).unwrap_or("");
            let x = if t.is_empty() {
                f64::NAN // an empty Datum is an invalid point
            } else {
                t.parse::<f64>().map_err(|_| {
                    st.err(
                        format!("main.xml Record3/DataList/Datum[{k}]"),
                        format!("{t:?} is not a number"),
                    )
                })?
            };
            v.push(x);
        }
        if v.len() != n {
            return Err(st.err(
                "main.xml Record3/DataList",
                format!("{} Datum elements, but SizeX x SizeY = {n}", v.len()),
            ));
        }
        v
    } else {
        return Err(st.err("main.xml Record3", "neither DataLink nor DataList: no data"));
    };
    if let Some(valid) = entry(
        &st,
        &mut zip,
        "bindata/valid.bin",
        (n as u64).div_ceil(8),
        false,
    )? {
        let invalid: Vec<usize> = (0..n)
            .filter(|&k| valid.get(k / 8).is_none_or(|b| b & (1 << (k % 8)) == 0))
            .collect();
        if !invalid.is_empty() {
            st.notes.push(format!(
                "bindata/valid.bin marks {} of {n} points invalid: they are undefined points",
                invalid.len()
            ));
        }
        for k in invalid {
            if let Some(v) = raw.get_mut(k) {
                *v = f64::NAN;
            }
        }
    }
    let z: Vec<f64> = raw.into_iter().map(|r| z_off + z_inc * r).collect();
    let spacing = st.spacing(Some((inc[0], inc[1])))?;
    let unit = st.height_unit(
        FileUnit::Length(LengthUnit::METRE),
        "main.xml Record1/Axes/CZ",
    )?;
    st.finish(nx as usize, ny as usize, spacing, unit, z)
}

/// The map as an x3p file: `main.xml` (FeatureType SUR, incremental x/y axes, f64 heights,
/// with the data's MD5), `bindata/data.bin`, and `md5checksum.hex` of main.xml.
pub fn encode_x3p(map: &HeightMap) -> Result<Vec<u8>> {
    let mut data = Vec::with_capacity(map.heights().len() * 8);
    for v in map.heights() {
        data.extend_from_slice(&v.to_le_bytes());
    }
    let xml = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:schemaLocation="http://www.opengps.eu/2008/ISO5436_2 http://www.opengps.eu/2008/ISO5436_2/ISO5436_2.xsd">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{dx:e}</Increment><Offset>0</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{dy:e}</Increment><Offset>0</Offset></CY>
      <CZ><AxisType>A</AxisType><DataType>D</DataType><Increment>1</Increment><Offset>0</Offset></CZ>
    </Axes>
  </Record1>
  <Record3>
    <MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
    <DataLink><PointDataLink>bindata/data.bin</PointDataLink><MD5ChecksumPointData>{md5}</MD5ChecksumPointData></DataLink>
  </Record3>
  <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>
"#,
        dx = map.dx(),
        dy = map.dy(),
        nx = map.nx(),
        ny = map.ny(),
        md5 = hex(&Md5::digest(&data)),
    );
    let zerr = |e: zip::result::ZipError| TopographyError::param("x3p archive", "", e.to_string());
    let ioerr = |e: std::io::Error| TopographyError::param("x3p archive", "", e.to_string());
    let mut w = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let opt = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    w.start_file("main.xml", opt).map_err(zerr)?;
    w.write_all(xml.as_bytes()).map_err(ioerr)?;
    w.start_file("bindata/data.bin", opt).map_err(zerr)?;
    w.write_all(&data).map_err(ioerr)?;
    w.start_file("md5checksum.hex", opt).map_err(zerr)?;
    w.write_all(format!("{} *main.xml\n", hex(&Md5::digest(xml.as_bytes()))).as_bytes())
        .map_err(ioerr)?;
    Ok(w.finish().map_err(zerr)?.into_inner())
}
