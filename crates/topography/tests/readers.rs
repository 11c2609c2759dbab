//! Every reader: round trips of known maps, and bad files of each format refused with a
//! message naming the file and what is wrong (never a panic).

use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};

use proptest::prelude::*;
use topography::io::{decode, encode};
use topography::{
    read_path, Format, HeightMap, LengthUnit, ReadOptions, TopographyError, Undefined,
};

mod encoders;
use encoders::Grid;

/// zlib-compresses `data` (the encoders' compressed `.sur`).
fn zlib(data: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    e.write_all(data).unwrap();
    e.finish().unwrap()
}

/// A zip archive of `entries`, deflated (the encoders' `.plux`).
fn zip_archive(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opt = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, data) in entries {
        w.start_file(*name, opt).unwrap();
        w.write_all(data).unwrap();
    }
    w.finish().unwrap().into_inner()
}

/// A 13 x 9 map with dx != dy and heights of both signs spanning decades.
fn sample_map() -> HeightMap {
    let (nx, ny) = (13, 9);
    let z = (0..nx * ny)
        .map(|k| {
            let (i, j) = ((k % nx) as f64, (k / nx) as f64);
            1e-9 * ((0.7 * i).sin() * (1.3 * j).cos() + 0.01 * i * j - 0.3)
                * (1.0 + 1e-3 * k as f64)
        })
        .collect();
    HeightMap::new(nx, ny, 12.5e-9, 7.5e-9, z).unwrap()
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("topography-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn write(name: &str, bytes: &[u8]) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Options that supply what formats without units lack.
fn with_units() -> ReadOptions {
    ReadOptions {
        spacing: None,
        height_unit: None,
        ..ReadOptions::default()
    }
}

fn err_of(path: &Path, opts: &ReadOptions) -> String {
    match read_path(path, opts) {
        Ok(m) => panic!("{} was accepted: {:?}", path.display(), m.source),
        Err(e) => {
            let s = e.to_string();
            assert!(
                s.contains(&path.display().to_string()),
                "error does not name the file: {s}"
            );
            s
        }
    }
}

fn assert_close_maps(a: &HeightMap, b: &HeightMap, rel: f64) {
    assert_eq!((a.nx(), a.ny()), (b.nx(), b.ny()));
    assert!(
        (a.dx() / b.dx() - 1.0).abs() < 1e-12 && (a.dy() / b.dy() - 1.0).abs() < 1e-12,
        "spacing"
    );
    let scale = b.heights().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (x, y) in a.heights().iter().zip(b.heights()) {
        assert!((x - y).abs() <= rel * scale, "{x} vs {y}");
    }
}

#[test]
fn every_format_round_trips_a_map() {
    let map = sample_map();
    for format in Format::WRITABLE {
        let bytes = encode(&map, format).unwrap();
        let path = write(&format!("round.{}", format.extension()), &bytes);
        let mut opts = with_units();
        if format == Format::Npy {
            // npy has no units and one spacing: give them
            let sq =
                HeightMap::new(map.nx(), map.ny(), 5e-9, 5e-9, map.heights().to_vec()).unwrap();
            std::fs::write(&path, encode(&sq, format).unwrap()).unwrap();
            opts.spacing = Some(5e-9);
            opts.height_unit = Some(LengthUnit::METRE);
            let m = read_path(&path, &opts).unwrap();
            assert_close_maps(&m.map, &sq, 0.0);
            assert_eq!(m.source.spacing_from, "options");
            continue;
        }
        let m = read_path(&path, &opts).unwrap_or_else(|e| panic!("{format}: {e}"));
        assert_eq!(m.source.format, format);
        // gsf stores 32-bit floats
        let rel = if format == Format::Gsf { 1e-7 } else { 0.0 };
        assert_close_maps(&m.map, &map, rel);
        assert_eq!(m.source.spacing_from, "file");
        assert_eq!(m.source.height_unit_from, "file");
    }
}

#[test]
fn formats_are_recognised_by_magic_without_an_extension() {
    let map = sample_map();
    for format in [Format::Gsf, Format::Gwy, Format::X3p] {
        let p = write(&format!("noext-{format}"), &encode(&map, format).unwrap());
        assert_eq!(
            read_path(&p, &ReadOptions::default())
                .unwrap()
                .source
                .format,
            format
        );
    }
    // a text file saying it holds xyz columns
    let p = write("noext-xyz", encode(&map, Format::Xyz).unwrap().as_slice());
    assert_eq!(
        read_path(&p, &ReadOptions::default())
            .unwrap()
            .source
            .format,
        Format::Xyz
    );
}

#[test]
fn text_header_conventions_and_gwyddion_export() {
    let t = "# spacing = 10 nm\n# height_unit = nm\n1 2 3\n4 5 6\n7 8 9.5\n";
    let m = read_path(write("conv.txt", t.as_bytes()), &ReadOptions::default()).unwrap();
    assert!((m.map.dx() - 10e-9).abs() < 1e-22 && (m.map.dy() - 10e-9).abs() < 1e-22);
    assert!((m.map.at(2, 2) - 9.5e-9).abs() < 1e-22);
    // Gwyddion's ASCII export: scan size and value units
    let t = "# Channel: Height\n# Width: 3.000 µm\n# Height: 1.500 µm\n# Value units: m\n\
             1e-9\t2e-9\t3e-9\n4e-9\t5e-9\t6e-9\n7e-9\t8e-9\t9e-9\n";
    let m = read_path(
        write("gwyexport.txt", t.as_bytes()),
        &ReadOptions::default(),
    )
    .unwrap();
    assert!((m.map.dx() - 1e-6).abs() < 1e-18 && (m.map.dy() - 0.5e-6).abs() < 1e-18);
    // comma-separated, spacing and unit from the options
    let t = "1, 2, 3\n4, 5, 6\n7, 8, 9\n";
    let opts = ReadOptions {
        spacing: Some(2e-8),
        height_unit: Some(LengthUnit::parse("um").unwrap()),
        ..ReadOptions::default()
    };
    let m = read_path(write("comma.csv", t.as_bytes()), &opts).unwrap();
    assert!((m.map.at(1, 1) - 5e-6).abs() < 1e-18 && m.map.dx() == 2e-8);
    // an option that contradicts the file wins, and says so
    let t = "# spacing = 10 nm\n# height_unit = nm\n1 2 3\n4 5 6\n7 8 9\n";
    let m = read_path(write("override.txt", t.as_bytes()), &opts).unwrap();
    assert_eq!(m.map.dx(), 2e-8);
    assert_eq!(m.source.notes.len(), 2, "{:?}", m.source.notes);
}

#[test]
fn xyz_in_any_order_with_units() {
    let mut lines = vec![
        "# xy_unit = um".to_string(),
        "# height_unit = nm".to_string(),
    ];
    for k in (0..12).rev() {
        let (i, j) = (k % 4, k / 4);
        lines.push(format!("{} {} {}", 0.5 * i as f64, 0.25 * j as f64, k));
    }
    let m = read_path(
        write("order.xyz", lines.join("\n").as_bytes()),
        &ReadOptions::default(),
    )
    .unwrap();
    assert_eq!((m.map.nx(), m.map.ny()), (4, 3));
    assert!((m.map.dx() - 0.5e-6).abs() < 1e-18 && (m.map.dy() - 0.25e-6).abs() < 1e-18);
    assert!((m.map.at(3, 2) - 11e-9).abs() < 1e-20);
}

#[test]
fn npy_integers_fortran_order_and_big_endian() {
    use npyz::WriterBuilder;
    let (ny, nx) = (3u64, 4u64);
    // column-major int16: element (r, c) = 10 r + c
    let mut buf = Vec::new();
    {
        let mut w = npyz::WriteOptions::new()
            .dtype(npyz::DType::Plain("<i2".parse().unwrap()))
            .shape(&[ny, nx])
            .order(npyz::Order::Fortran)
            .writer(&mut buf)
            .begin_nd()
            .unwrap();
        for c in 0..nx as i16 {
            for r in 0..ny as i16 {
                w.push(&(10 * r + c)).unwrap();
            }
        }
        w.finish().unwrap();
    }
    let opts = ReadOptions {
        spacing: Some(1e-8),
        height_unit: Some(LengthUnit::parse("nm").unwrap()),
        ..ReadOptions::default()
    };
    let m = read_path(write("fortran.npy", &buf), &opts).unwrap();
    for r in 0..3 {
        for c in 0..4 {
            assert!((m.map.at(c, r) - (10 * r + c) as f64 * 1e-9).abs() < 1e-20);
        }
    }
    let mut buf = Vec::new();
    {
        let mut w = npyz::WriteOptions::new()
            .dtype(npyz::DType::Plain(">f4".parse().unwrap()))
            .shape(&[3, 3])
            .writer(&mut buf)
            .begin_nd()
            .unwrap();
        for k in 0..9 {
            w.push(&(k as f32 * 0.5)).unwrap();
        }
        w.finish().unwrap();
    }
    let m = read_path(write("big.npy", &buf), &opts).unwrap();
    assert!((m.map.at(2, 2) - 4.0e-9).abs() < 1e-20);
}

#[test]
fn x3p_with_an_inline_data_list_and_integer_data() {
    let xml = r#"<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>
<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-8</Increment><Offset>0</Offset></CX>
<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>3e-8</Increment><Offset>0</Offset></CY>
<CZ><AxisType>A</AxisType><DataType>L</DataType><Increment>1e-10</Increment><Offset>5e-9</Offset></CZ>
</Axes></Record1>
<Record3><MatrixDimension><SizeX>3</SizeX><SizeY>3</SizeY><SizeZ>1</SizeZ></MatrixDimension>
<DataList>{DATA}</DataList></Record3></p:ISO5436_2>"#;
    let data: String = (0..9).map(|k| format!("<Datum>{k}</Datum>")).collect();
    let bytes = zip_of(&[("main.xml", xml.replace("{DATA}", &data).as_bytes())]);
    let m = read_path(write("list.x3p", &bytes), &ReadOptions::default()).unwrap();
    assert!((m.map.at(2, 2) - (5e-9 + 8.0 * 1e-10)).abs() < 1e-20);
    assert_eq!((m.map.dx(), m.map.dy()), (2e-8, 3e-8));
    // an empty Datum is an invalid point
    let data: String = (0..9)
        .map(|k| {
            if k == 4 {
                "<Datum/>".to_string()
            } else {
                format!("<Datum>{k}</Datum>")
            }
        })
        .collect();
    let bytes = zip_of(&[("main.xml", xml.replace("{DATA}", &data).as_bytes())]);
    let e = err_of(&write("hole.x3p", &bytes), &ReadOptions::default());
    assert!(e.contains("not finite"), "{e}");
}

fn zip_of(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let opt = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, data) in entries {
        w.start_file(*name, opt).unwrap();
        w.write_all(data).unwrap();
    }
    w.finish().unwrap().into_inner()
}

fn unzip(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut z = zip::ZipArchive::new(Cursor::new(bytes)).unwrap();
    (0..z.len())
        .map(|k| {
            let mut f = z.by_index(k).unwrap();
            let mut v = Vec::new();
            std::io::Read::read_to_end(&mut f, &mut v).unwrap();
            (f.name().unwrap().to_string(), v)
        })
        .collect()
}

#[test]
fn bad_text_files() {
    let o = ReadOptions::default();
    let cases: &[(&str, &str, &str)] = &[
        (
            "word.txt",
            "# spacing = 1 nm\n# height_unit = nm\n1 2 3\n4 x 6\n7 8 9\n",
            "line 4, column 2",
        ),
        (
            "ragged.txt",
            "# spacing = 1 nm\n# height_unit = nm\n1 2 3\n4 5\n7 8 9\n",
            "line 4",
        ),
        (
            "nan.txt",
            "# spacing = 1 nm\n# height_unit = nm\n1 2 3\n4 NaN 6\n7 8 9\n",
            "--undefined fill",
        ),
        ("empty.txt", "# spacing = 1 nm\n", "no data lines"),
        (
            "nospacing.txt",
            "# height_unit = nm\n1 2 3\n4 5 6\n7 8 9\n",
            "--spacing",
        ),
        (
            "nounit.txt",
            "# spacing = 1 nm\n1 2 3\n4 5 6\n7 8 9\n",
            "--height-unit",
        ),
        (
            "badunit.txt",
            "# spacing = 1 furlong\n1 2 3\n4 5 6\n7 8 9\n",
            "line 1",
        ),
        (
            "small.txt",
            "# spacing = 1 nm\n# height_unit = nm\n1 2\n3 4\n",
            "at least 3 x 3",
        ),
        (
            "emptyfield.csv",
            "# spacing = 1 nm\n# height_unit = nm\n1,,3\n4,5,6\n7,8,9\n",
            "empty field",
        ),
    ];
    for (name, text, what) in cases {
        let e = err_of(&write(name, text.as_bytes()), &o);
        assert!(e.contains(what), "{name}: {e}");
    }
    let e = err_of(&write("binary.txt", &[0x31, 0x20, 0xff, 0xfe, 0x0a]), &o);
    assert!(e.contains("not UTF-8"), "{e}");
}

#[test]
fn bad_xyz_files() {
    let o = ReadOptions::default();
    let head = "# xy_unit = nm\n# height_unit = nm\n";
    let grid = |skip: Option<usize>, dup: bool, jitter: bool| {
        let mut s = head.to_string();
        for k in 0..16 {
            if Some(k) == skip {
                continue;
            }
            let x = (k % 4) as f64 + if jitter && k == 5 { 0.3 } else { 0.0 };
            s.push_str(&format!("{} {} {}\n", x, k / 4, k));
        }
        if dup {
            s.push_str("1 1 99\n");
        }
        s
    };
    let e = err_of(
        &write("missing.xyz", grid(Some(6), false, false).as_bytes()),
        &o,
    );
    assert!(e.contains("missing or repeated"), "{e}");
    let mut s = grid(Some(6), false, false);
    s.push_str("1 1 99\n"); // point (1,1) twice, (2,1) missing
    let e = err_of(&write("dup.xyz", s.as_bytes()), &o);
    assert!(e.contains("repeats line"), "{e}");
    let e = err_of(
        &write("irregular.xyz", grid(None, false, true).as_bytes()),
        &o,
    );
    assert!(e.contains("regular grid"), "{e}");
    let e = err_of(&write("cols.xyz", format!("{head}1 2\n").as_bytes()), &o);
    assert!(e.contains("three columns"), "{e}");
    let e = err_of(
        &write(
            "nounits.xyz",
            b"0 0 1\n1 0 1\n2 0 1\n0 1 1\n1 1 1\n2 1 1\n0 2 1\n1 2 1\n2 2 1\n",
        ),
        &o,
    );
    assert!(e.contains("x/y coordinates"), "{e}");
}

fn npy_opts() -> ReadOptions {
    ReadOptions {
        spacing: Some(1e-8),
        height_unit: Some(LengthUnit::METRE),
        ..ReadOptions::default()
    }
}

#[test]
fn bad_npy_files() {
    let good = encode(&sample_map(), Format::Npy).unwrap();
    let o = npy_opts();
    let e = err_of(&write("magic.npy", b"NUMPY\x01\x00 this is not it"), &o);
    assert!(e.contains("magic"), "{e}");
    let e = err_of(&write("trunc.npy", &good[..good.len() - 8]), &o);
    assert!(e.contains("truncated"), "{e}");
    let e = err_of(&write("trunchead.npy", &good[..20]), &o);
    assert!(e.contains("header"), "{e}");
    let e = err_of(&write("nospacing.npy", &good), &ReadOptions::default());
    assert!(e.contains("--spacing"), "{e}");
    // 1-D, complex, and a huge declared shape with no data
    for (name, descr, shape, what) in [
        ("oned.npy", "'<f8'", "(9,)", "2-D"),
        ("complex.npy", "'<c16'", "(3, 3)", "expected float"),
        ("huge.npy", "'<f8'", "(100000, 100000)", "exceeds the cap"),
    ] {
        let e = err_of(&write(name, &npy_with_header(descr, shape, &[0u8; 72])), &o);
        assert!(e.contains(what), "{name}: {e}");
    }
    // NaN data
    let z = vec![0.0, 1.0, f64::NAN, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0];
    let mut data = Vec::new();
    z.iter()
        .for_each(|v| data.extend_from_slice(&v.to_le_bytes()));
    let e = err_of(
        &write("nan.npy", &npy_with_header("'<f8'", "(3, 3)", &data)),
        &o,
    );
    assert!(e.contains("not finite"), "{e}");
}

fn npy_with_header(descr: &str, shape: &str, data: &[u8]) -> Vec<u8> {
    let mut h = format!("{{'descr': {descr}, 'fortran_order': False, 'shape': {shape}, }}");
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(h.len() as u16).to_le_bytes());
    out.extend_from_slice(h.as_bytes());
    out.extend_from_slice(data);
    out
}

#[test]
fn bad_gsf_files() {
    let good = encode(&sample_map(), Format::Gsf).unwrap();
    let o = ReadOptions::default();
    let e = err_of(
        &write("magic.gsf", b"Gwyddion Simple Field 2.0\nXRes = 3\n"),
        &o,
    );
    assert!(e.contains("magic"), "{e}");
    let e = err_of(&write("trunc.gsf", &good[..good.len() - 4]), &o);
    assert!(e.contains("truncated"), "{e}");
    let text =
        String::from_utf8_lossy(&good[..good.iter().position(|&b| b == 0).unwrap()]).into_owned();
    let data_at = (text.len() / 4 + 1) * 4;
    let rebuild = |header: &str| {
        let mut v = header.as_bytes().to_vec();
        let pad = 4 - v.len() % 4;
        v.extend(std::iter::repeat_n(0u8, pad));
        v.extend_from_slice(&good[data_at..]);
        v
    };
    let e = err_of(
        &write("noxres.gsf", &rebuild(&text.replace("XRes = 13\n", ""))),
        &o,
    );
    assert!(e.contains("XRes") && e.contains("missing"), "{e}");
    let e = err_of(
        &write(
            "volts.gsf",
            &rebuild(&text.replace("ZUnits = m", "ZUnits = V")),
        ),
        &o,
    );
    assert!(e.contains("not a length"), "{e}");
    let e = err_of(
        &write(
            "bigres.gsf",
            &rebuild(&text.replace("XRes = 13", "XRes = 1000000000")),
        ),
        &o,
    );
    assert!(e.contains("exceeds the cap"), "{e}");
    let e = err_of(&write("nonul.gsf", text.as_bytes()), &o);
    assert!(e.contains("NUL"), "{e}");
    let mut nan = good.clone();
    let at = data_at + 4 * 20;
    nan[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let e = err_of(&write("nan.gsf", &nan), &o);
    assert!(
        e.contains("not finite") && e.contains("column 7 row 1"),
        "{e}"
    );
    // volts are accepted when the user gives the length per volt
    let opts = ReadOptions {
        height_unit: Some(LengthUnit::factor(2e-6).unwrap()),
        ..ReadOptions::default()
    };
    let m = read_path(
        write(
            "volts-ok.gsf",
            &rebuild(&text.replace("ZUnits = m", "ZUnits = V")),
        ),
        &opts,
    )
    .unwrap();
    assert_eq!(m.source.notes.len(), 1);
}

#[test]
fn bad_gwy_files() {
    let good = encode(&sample_map(), Format::Gwy).unwrap();
    let o = ReadOptions::default();
    let e = err_of(&write("magic.gwy", b"GWYQ\0\0\0\0"), &o);
    assert!(e.contains("GWYP"), "{e}");
    let e = err_of(&write("old.gwy", b"GWYO\0\0\0\0"), &o);
    assert!(e.contains("1.x"), "{e}");
    // every truncation is refused with a message
    for cut in (5..good.len()).step_by(7) {
        let e = decode(Path::new("cut.gwy"), &good[..cut], Format::Gwy, &o)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("cut.gwy") && e.contains("gwy file"),
            "cut at {cut}: {e}"
        );
    }
    // data count != xres * yres: patch xres from 13 to 12 (the i32 after "xres\0i")
    let mut bad = good.clone();
    let at = find(&good, b"xres\0i") + 6;
    bad[at] = 12;
    let e = err_of(&write("count.gwy", &bad), &o);
    assert!(
        e.contains("component data of /0/data") && e.contains("12 x 9"),
        "{e}"
    );
    // a component of unknown type
    let mut bad = good.clone();
    bad[find(&good, b"xres\0i") + 5] = b'z';
    let e = err_of(&write("type.gwy", &bad), &o);
    assert!(e.contains("unknown component type"), "{e}");
    // a huge declared array count
    let mut bad = good.clone();
    let at = find(&good, b"data\0D") + 6;
    bad[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let e = err_of(&write("count2.gwy", &bad), &o);
    assert!(e.contains("remain"), "{e}");
    // no channel: rename /0/data
    let mut bad = good.clone();
    let at = find(&good, b"/0/data\0o");
    bad[at + 3] = b'x';
    let e = err_of(&write("nochannel.gwy", &bad), &o);
    assert!(e.contains("no channel"), "{e}");
    // the grid cap is checked before the data are decoded
    let small = ReadOptions {
        max_points: 100,
        ..ReadOptions::default()
    };
    let e = err_of(&write("cap.gwy", &good), &small);
    assert!(
        e.contains("the grid 13 x 9 exceeds the cap of 100 points"),
        "{e}"
    );
}

fn find(hay: &[u8], needle: &[u8]) -> usize {
    hay.windows(needle.len()).position(|w| w == needle).unwrap()
}

#[test]
fn bad_x3p_files() {
    let good = encode(&sample_map(), Format::X3p).unwrap();
    let entries = unzip(&good);
    let xml = String::from_utf8(
        entries
            .iter()
            .find(|e| e.0 == "main.xml")
            .unwrap()
            .1
            .clone(),
    )
    .unwrap();
    let data = entries
        .iter()
        .find(|e| e.0 == "bindata/data.bin")
        .unwrap()
        .1
        .clone();
    let o = ReadOptions::default();
    let e = err_of(&write("magic.x3p", b"not a zip"), &o);
    assert!(e.contains("zip"), "{e}");
    let e = err_of(&write("trunc.x3p", &good[..good.len() / 2]), &o);
    assert!(e.contains("x3p file"), "{e}");
    let e = err_of(
        &write("noxml.x3p", &zip_of(&[("bindata/data.bin", &data)])),
        &o,
    );
    assert!(e.contains("no main.xml"), "{e}");
    let prf = xml.replace("<FeatureType>SUR", "<FeatureType>PRF");
    let e = err_of(
        &write(
            "prf.x3p",
            &zip_of(&[("main.xml", prf.as_bytes()), ("bindata/data.bin", &data)]),
        ),
        &o,
    );
    assert!(e.contains("PRF"), "{e}");
    let e = err_of(
        &write(
            "short.x3p",
            &zip_of(&[
                ("main.xml", xml.as_bytes()),
                ("bindata/data.bin", &data[..data.len() - 8]),
            ]),
        ),
        &o,
    );
    assert!(e.contains("bindata/data.bin") && e.contains("need"), "{e}");
    let mut flipped = data.clone();
    flipped[3] ^= 1;
    let e = err_of(
        &write(
            "md5.x3p",
            &zip_of(&[("main.xml", xml.as_bytes()), ("bindata/data.bin", &flipped)]),
        ),
        &o,
    );
    assert!(e.contains("MD5"), "{e}");
    let mut valid = vec![0xffu8; (13 * 9usize).div_ceil(8)];
    valid[2] = 0xfe;
    let e = err_of(
        &write(
            "valid.x3p",
            &zip_of(&[
                ("main.xml", xml.as_bytes()),
                ("bindata/data.bin", &data),
                ("bindata/valid.bin", &valid),
            ]),
        ),
        &o,
    );
    assert!(e.contains("1 of 117 heights are undefined"), "{e}");
    let huge = xml.replace("<SizeX>13</SizeX>", "<SizeX>130000000</SizeX>");
    let e = err_of(
        &write(
            "huge.x3p",
            &zip_of(&[("main.xml", huge.as_bytes()), ("bindata/data.bin", &data)]),
        ),
        &o,
    );
    assert!(e.contains("exceeds the cap"), "{e}");
    let bad_xml = xml.replace("</Record1>", "");
    let e = err_of(
        &write("xml.x3p", &zip_of(&[("main.xml", bad_xml.as_bytes())])),
        &o,
    );
    assert!(e.contains("main.xml"), "{e}");
}

#[test]
fn size_caps_hold_for_files_and_streams() {
    let big = write("big.txt", &vec![b'1'; 4096]);
    let small = ReadOptions {
        max_bytes: 1000,
        ..ReadOptions::default()
    };
    let e = err_of(&big, &small);
    assert!(
        e.contains("the file (4096 bytes) exceeds the cap of 1000 bytes"),
        "{e}"
    );
    // an endless stream is cut at the cap instead of exhausting memory
    if Path::new("/dev/zero").exists() {
        let opts = ReadOptions {
            format: Some(Format::Gwy),
            max_bytes: 1 << 20,
            ..ReadOptions::default()
        };
        match read_path("/dev/zero", &opts) {
            Err(TopographyError::TooLarge { what, .. }) => {
                assert!(what.contains("stream"), "{what}")
            }
            other => panic!("{other:?}"),
        }
    }
    // a text matrix with more values than the point cap
    let opts = ReadOptions {
        max_points: 8,
        spacing: Some(1e-9),
        height_unit: Some(LengthUnit::METRE),
        ..ReadOptions::default()
    };
    let e = err_of(&write("points.txt", b"1 2 3\n4 5 6\n7 8 9\n"), &opts);
    assert!(e.contains("points"), "{e}");
    let e = err_of(&tmp(""), &ReadOptions::default());
    assert!(e.contains("cannot read"), "{e}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]
    /// Corrupting any byte of a valid file of any format gives a map or an error, never a
    /// panic (and never an unbounded allocation: the caps hold).
    #[test]
    fn corrupted_files_never_panic(format_ix in 0usize..6, pos in 0.0f64..1.0, byte in any::<u8>(), cut in 0.5f64..1.0) {
        let format = Format::WRITABLE[format_ix];
        let mut bytes = encode(&sample_map(), format).unwrap();
        let k = ((bytes.len() - 1) as f64 * pos) as usize;
        bytes[k] = byte;
        let opts = npy_opts();
        let _ = decode(Path::new("fuzz"), &bytes, format, &opts);
        let n = (bytes.len() as f64 * cut) as usize;
        let _ = decode(Path::new("fuzz"), &bytes[..n], format, &opts);
    }
}

// ---------------------------------------------------------------------------------------
// The instruments' formats: round trips through the independent writers of `encoders`.

fn grid(map: &HeightMap) -> Grid<'_> {
    Grid {
        nx: map.nx(),
        ny: map.ny(),
        dx: map.dx(),
        dy: map.dy(),
        z: map.heights(),
    }
}

/// The sample map on a square grid (formats with one lateral resolution).
fn square_map() -> HeightMap {
    let m = sample_map();
    HeightMap::new(m.nx(), m.ny(), 12.5e-9, 12.5e-9, m.heights().to_vec()).unwrap()
}

fn read_bytes(name: &str, bytes: &[u8], opts: &ReadOptions) -> topography::Measurement {
    let p = write(name, bytes);
    read_path(&p, opts).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn err_bytes(name: &str, bytes: &[u8], opts: &ReadOptions) -> String {
    err_of(&write(name, bytes), opts)
}

/// Every height within `tol` (m) of the expected; same grid; spacings within `rel`.
fn assert_map(
    m: &HeightMap,
    (nx, ny, dx, dy, rel): (usize, usize, f64, f64, f64),
    expected: impl Fn(usize, usize) -> f64,
    tol: f64,
) {
    assert_eq!((m.nx(), m.ny()), (nx, ny), "grid");
    assert!((m.dx() / dx - 1.0).abs() <= rel, "dx {} vs {dx}", m.dx());
    assert!((m.dy() / dy - 1.0).abs() <= rel, "dy {} vs {dy}", m.dy());
    for j in 0..ny {
        for i in 0..nx {
            let (a, b) = (m.at(i, j), expected(i, j));
            assert!(
                (a - b).abs() <= tol,
                "({i}, {j}): {a:e} vs {b:e} (tol {tol:e})"
            );
        }
    }
}

fn max_abs(map: &HeightMap) -> f64 {
    map.heights().iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

fn fill() -> ReadOptions {
    ReadOptions {
        undefined: Undefined::Fill,
        ..ReadOptions::default()
    }
}

fn channel(c: &str) -> ReadOptions {
    ReadOptions {
        channel: Some(c.to_string()),
        ..ReadOptions::default()
    }
}

fn ns_images() -> Vec<encoders::NsImage> {
    use encoders::NsImage;
    vec![
        NsImage {
            name: "Amplitude Error",
            direction: "Trace",
            soft: None,
            factor: 1.0,
        },
        NsImage {
            name: "Height Sensor",
            direction: "Trace",
            soft: Some("Sens. Zsens"),
            factor: 1.0,
        },
        NsImage {
            name: "Height Sensor",
            direction: "Retrace",
            soft: Some("Sens. Zsens"),
            factor: -0.5,
        },
    ]
}

#[test]
fn nanoscope_round_trips_in_16_and_32_bits_and_lists_its_channels() {
    let map = sample_map();
    let g = grid(&map);
    for bpp in [2u32, 4] {
        let bytes = encoders::nanoscope(&g, bpp, &ns_images());
        let q = encoders::nanoscope_quantum(max_abs(&map) * 1e9, bpp) * 1e-9;
        let m = read_bytes(&format!("afm{bpp}.spm"), &bytes, &ReadOptions::default());
        assert_eq!(m.source.format, Format::Nanoscope);
        assert_eq!(
            m.source.channels,
            [
                "Amplitude Error (Trace)",
                "Height Sensor (Trace)",
                "Height Sensor (Retrace)"
            ]
        );
        assert_eq!(m.source.title.as_deref(), Some("Height Sensor (Trace)"));
        assert_eq!(
            (m.source.spacing_from, m.source.height_unit_from),
            ("file", "file")
        );
        assert_map(
            &m.map,
            (13, 9, 12.5e-9, 7.5e-9, 1e-12),
            |i, j| map.at(i, j),
            0.51 * q,
        );
        assert!(
            m.source.notes.iter().any(|n| n.contains("3 channels")),
            "{:?}",
            m.source.notes
        );
        // the retrace by index and by name (any case)
        for c in ["2", "height sensor (retrace)"] {
            let r = read_bytes(&format!("afm{bpp}-r.spm"), &bytes, &channel(c));
            assert_map(
                &r.map,
                (13, 9, 12.5e-9, 7.5e-9, 1e-12),
                |i, j| -0.5 * map.at(i, j),
                0.51 * q,
            );
        }
        // a channel in volts needs a length per volt; an unknown one lists the channels
        let e = err_bytes(
            &format!("afm{bpp}-v.spm"),
            &bytes,
            &channel("Amplitude Error (Trace)"),
        );
        assert!(
            e.contains("not a length") && e.contains("--height-unit"),
            "{e}"
        );
        let e = err_bytes(&format!("afm{bpp}-x.spm"), &bytes, &channel("Phase"));
        assert!(
            e.contains("\"Phase\" is not a channel")
                && e.contains("1 \"Height Sensor (Trace)\" (heights)"),
            "{e}"
        );
        // told by its header without an extension, and by a numbered extension
        for name in [format!("afm{bpp}"), format!("afm{bpp}.003")] {
            assert_eq!(
                read_bytes(&name, &bytes, &ReadOptions::default())
                    .source
                    .format,
                Format::Nanoscope
            );
        }
    }
    // an old (4.2) header: AFM image list, `Image data`, `Z scale` as the full range
    let mut old = b"\\*File list\r\n\\Version: 0x04220200\r\n\\*Afm list\r\n\\Scan size: 300 nm\r\n\\Samps/line: 3\r\n\\Lines: 4\r\n".to_vec();
    old.extend_from_slice(b"\\*AFM image list\r\n\\Data offset: 512\r\n\\Data length: 24\r\n\\Samps/line: 3\r\n\\Number of lines: 4\r\n");
    old.extend_from_slice(b"\\Scan size: 300 nm\r\n\\Image data: Height\r\n\\Z scale: 6.5536 \xb5m\r\n\\*File list end\r\n");
    old.resize(512, 0);
    for k in 0..12i16 {
        old.extend_from_slice(&(1000 * (k - 6)).to_le_bytes());
    }
    let m = read_bytes("old.001", &old, &ReadOptions::default());
    assert_eq!(m.source.channels, ["Height"]);
    // 1 LSB = 6.5536 um / 65536 = 0.1 nm; stored bottom line first
    assert_map(
        &m.map,
        (3, 4, 100e-9, 75e-9, 1e-12),
        |i, j| 1000.0 * ((3 - j) as f64 * 3.0 + i as f64 - 6.0) * 0.1e-9,
        1e-20,
    );
    // no height channel: refused, saying what to export
    let bytes = encoders::nanoscope(&g, 2, &ns_images()[..1]);
    let e = err_bytes("amp.spm", &bytes, &ReadOptions::default());
    assert!(
        e.contains("nanoscope file")
            && e.contains("without a height channel")
            && e.contains(".x3p"),
        "{e}"
    );
    // the text variant and force files are recognised and refused
    let e = err_bytes(
        "text.spm",
        b"?*File list\r\n\\Version: 0x04310006\r\n",
        &ReadOptions::default(),
    );
    assert!(
        e.contains("not supported") && e.contains("text data"),
        "{e}"
    );
    // a data offset past the end
    let mut cut = encoders::nanoscope(&g, 2, &ns_images());
    cut.truncate(cut.len() - 10);
    let e = err_bytes("cut.spm", &cut, &channel("2"));
    assert!(e.contains("truncated") && e.contains("Data offset"), "{e}");
}

#[test]
fn opd_round_trips_its_heights_spacing_and_undefined_points() {
    let map = sample_map();
    let mut z = map.heights().to_vec();
    let bytes = encoders::opd(&grid(&map), 632.8, 2);
    let m = read_bytes("wyko.opd", &bytes, &ReadOptions::default());
    assert_eq!(m.source.format, Format::Opd);
    assert_eq!(m.source.channels, ["RAW_DATA", "Image"]);
    let tol = 1e-6 * max_abs(&map);
    assert_map(
        &m.map,
        (13, 9, 12.5e-9, 7.5e-9, 1e-6),
        |i, j| map.at(i, j),
        tol,
    );
    assert_eq!(
        read_bytes("wyko", &bytes, &ReadOptions::default())
            .source
            .format,
        Format::Opd
    );
    // the intensity is a channel, but not heights
    let e = err_bytes("wyko-i.opd", &bytes, &channel("Image"));
    assert!(
        e.contains("intensity") && e.contains("--height-unit"),
        "{e}"
    );
    // an undefined point (1e38): refused with its count, or filled
    z[20] = f64::NAN;
    let g = Grid {
        z: &z,
        ..grid(&map)
    };
    let bytes = encoders::opd(&g, 632.8, 2);
    let e = err_bytes("hole.opd", &bytes, &ReadOptions::default());
    assert!(
        e.contains("1 of 117 heights are undefined")
            && e.contains("--undefined fill")
            && e.contains("column 7 row 1"),
        "{e}"
    );
    let m = read_bytes("hole-fill.opd", &bytes, &fill());
    assert_eq!(m.source.undefined_points, 1);
    assert!(
        m.source.notes.iter().any(|n| n.contains("harmonic")),
        "{:?}",
        m.source.notes
    );
    let neighbours = [map.at(6, 1), map.at(8, 1), map.at(7, 0), map.at(7, 2)];
    let mean = neighbours.iter().sum::<f64>() / 4.0;
    assert!(
        (m.map.at(7, 1) - mean).abs() < 1e-6 * max_abs(&map),
        "the filled point is the mean of its neighbours"
    );
    // truncation names the block
    let e = err_bytes(
        "cut.opd",
        &bytes[..bytes.len() - 40],
        &ReadOptions::default(),
    );
    assert!(e.contains("opd file") && e.contains("past the end"), "{e}");
}

#[test]
fn metropro_round_trips_every_header_format_and_phase_resolution() {
    let map = square_map();
    for fmt in 1..=3u16 {
        for res in 0..=2i16 {
            for sign in [false, true] {
                let bytes = encoders::metropro(&grid(&map), fmt, res, sign);
                // a .dat is a MetroPro file by its magic number, not a text matrix
                let m = read_bytes(
                    &format!("zygo{fmt}{res}{sign}.dat"),
                    &bytes,
                    &ReadOptions::default(),
                );
                assert_eq!(m.source.format, Format::Metropro);
                assert_eq!(m.source.channels, ["Phase", "Intensity"]);
                let q = encoders::metropro_quantum(res);
                assert_map(
                    &m.map,
                    (13, 9, 12.5e-9, 12.5e-9, 1e-7),
                    |i, j| map.at(i, j),
                    0.51 * q,
                );
            }
        }
    }
    let mut z = map.heights().to_vec();
    z[0] = f64::NAN;
    z[5] = f64::NAN;
    let bytes = encoders::metropro(
        &Grid {
            z: &z,
            ..grid(&map)
        },
        2,
        1,
        false,
    );
    let e = err_bytes("hole.dat", &bytes, &ReadOptions::default());
    assert!(e.contains("2 of 117 heights are undefined"), "{e}");
    assert_eq!(
        read_bytes("hole2.dat", &bytes, &fill())
            .source
            .undefined_points,
        2
    );
    // intensity only on request, and it is not a length
    let e = err_bytes("int.dat", &bytes, &channel("Intensity"));
    assert!(e.contains("not a length"), "{e}");
    // the HDF5 .datx is recognised and refused
    let mut h5 = b"\x89HDF\r\n\x1a\n".to_vec();
    h5.extend_from_slice(&[0u8; 600]);
    for name in ["zygo.datx", "zygo-h5"] {
        let e = err_bytes(name, &h5, &ReadOptions::default());
        assert!(
            e.contains("metropro file")
                && e.contains("HDF5")
                && e.contains("not supported")
                && e.contains(".x3p"),
            "{e}"
        );
    }
    // a truncated phase block
    let e = err_bytes(
        "cut.dat",
        &bytes[..bytes.len() - 4],
        &ReadOptions::default(),
    );
    assert!(e.contains("truncated"), "{e}");
}

#[test]
fn sur_round_trips_plain_compressed_and_multi_object_files() {
    let map = sample_map();
    let g = grid(&map);
    for (bits, compressed) in [(16i16, false), (32, false), (16, true), (32, true)] {
        let intensity = encoders::SurObject {
            name: "Intensity",
            kind: 10,
            grid: &g,
            bits: 16,
            compressed,
        };
        let surface = encoders::SurObject {
            name: "Topography",
            kind: 2,
            grid: &g,
            bits,
            compressed,
        };
        let bytes = encoders::sur(&[intensity, surface]);
        let m = read_bytes(
            &format!("mm{bits}{compressed}.sur"),
            &bytes,
            &ReadOptions::default(),
        );
        assert_eq!(m.source.format, Format::Sur);
        assert_eq!(
            m.source.channels,
            ["Intensity (intensity image)", "Topography (surface)"]
        );
        assert_eq!(m.source.title.as_deref(), Some("Topography (surface)"));
        let q = encoders::sur_quantum(&g, bits);
        assert_map(
            &m.map,
            (13, 9, 12.5e-9, 7.5e-9, 1e-7),
            |i, j| encoders::sur_expected(&g, bits, map.at(i, j)),
            1e-6 * q,
        );
        assert_map(
            &m.map,
            (13, 9, 12.5e-9, 7.5e-9, 1e-7),
            |i, j| map.at(i, j),
            0.51 * q + 1e-16,
        );
        assert_eq!(
            read_bytes(
                &format!("mm{bits}{compressed}"),
                &bytes,
                &ReadOptions::default()
            )
            .source
            .format,
            Format::Sur
        );
    }
    // non-measured points (zmin - 2)
    let mut z = map.heights().to_vec();
    z[50] = f64::NAN;
    let gh = Grid {
        z: &z,
        ..grid(&map)
    };
    let bytes = encoders::sur(&[encoders::SurObject {
        name: "",
        kind: 2,
        grid: &gh,
        bits: 32,
        compressed: false,
    }]);
    let e = err_bytes("hole.sur", &bytes, &ReadOptions::default());
    assert!(e.contains("1 of 117 heights are undefined"), "{e}");
    let m = read_bytes("hole-fill.sur", &bytes, &fill());
    assert_eq!(
        (m.source.undefined_points, m.source.channels.as_slice()),
        (1, ["object 0 (surface)".to_string()].as_slice())
    );
    // a profile is 1-D: refused saying so
    let row: Vec<f64> = map.heights()[..13].to_vec();
    let gp = Grid {
        nx: 13,
        ny: 1,
        dx: 1e-8,
        dy: 1e-8,
        z: &row,
    };
    let bytes = encoders::sur(&[encoders::SurObject {
        name: "Profile",
        kind: 1,
        grid: &gp,
        bits: 16,
        compressed: false,
    }]);
    let e = err_bytes("profile.sur", &bytes, &ReadOptions::default());
    assert!(
        e.contains("a 1-D profile (13 points): the model needs a 2-D height map"),
        "{e}"
    );
    // a compressed stream that inflates to more than declared
    let surface = encoders::SurObject {
        name: "T",
        kind: 2,
        grid: &g,
        bits: 16,
        compressed: true,
    };
    let mut bytes = encoders::sur(&[surface]);
    let raw_len_at = 512 + "$_tests\n$Writer = encoders.rs\n".len() + 4;
    bytes[raw_len_at..raw_len_at + 4].copy_from_slice(&10u32.to_le_bytes());
    let e = err_bytes("zip.sur", &bytes, &ReadOptions::default());
    assert!(e.contains("sur file") && e.contains("stream 0"), "{e}");
}

#[test]
fn plu_and_plux_round_trip() {
    let map = sample_map();
    let g = grid(&map);
    let tol = 1e-7 * max_abs(&map);
    let bytes = encoders::plu(&g, 3);
    for name in ["senso.plu", "senso"] {
        let m = read_bytes(name, &bytes, &ReadOptions::default());
        assert_eq!(m.source.format, Format::Plu);
        assert_eq!(m.source.channels, ["layer 0"]);
        assert_map(
            &m.map,
            (13, 9, 12.5e-9, 7.5e-9, 1e-7),
            |i, j| map.at(i, j),
            tol,
        );
    }
    let e = err_bytes(
        "profile.plu",
        &encoders::plu(&g, 1),
        &ReadOptions::default(),
    );
    assert!(e.contains("a 1-D profile (117 points)"), "{e}");
    let e = err_bytes("image.plu", &encoders::plu(&g, 0), &ReadOptions::default());
    assert!(
        e.contains("confocal image") && e.contains("not supported"),
        "{e}"
    );
    let mut z = map.heights().to_vec();
    z[3] = f64::NAN;
    let gh = Grid {
        z: &z,
        ..grid(&map)
    };
    assert_eq!(
        read_bytes("hole.plu", &encoders::plu(&gh, 3), &fill())
            .source
            .undefined_points,
        1
    );
    // PLUx: a zip told from an x3p by its entries
    let bytes = encoders::plux(&gh);
    for name in ["senso.plux", "senso-zip"] {
        let m = read_bytes(name, &bytes, &fill());
        assert_eq!(
            (m.source.format, m.source.undefined_points),
            (Format::Plu, 1)
        );
        assert_map(
            &m.map,
            (13, 9, 12.5e-9, 7.5e-9, 1e-12),
            |i, j| {
                if (i, j) == (3, 0) {
                    m.map.at(3, 0)
                } else {
                    map.at(i, j)
                }
            },
            tol,
        );
    }
    let e = err_bytes(
        "plux-as.x3p",
        &bytes,
        &ReadOptions {
            format: Some(Format::X3p),
            ..ReadOptions::default()
        },
    );
    assert!(e.contains("read it as plu"), "{e}");
}

#[test]
fn vk4_round_trips_and_vk6_vk7_are_refused() {
    let map = sample_map();
    let bytes = encoders::vk4(&grid(&map), 1);
    let m = read_bytes("keyence.vk4", &bytes, &ReadOptions::default());
    assert_eq!(m.source.format, Format::Vk4);
    assert_eq!(m.source.channels, ["Height 1", "Light 1"]);
    // unsigned heights from the minimum: compare after removing the mean
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let (ma, mb) = (mean(m.map.heights()), mean(map.heights()));
    assert_map(
        &m.map,
        (13, 9, 12.5e-9, 7.5e-9, 0.0),
        |i, j| map.at(i, j) - mb + ma,
        0.51e-12 * 2.0,
    );
    assert_eq!(
        read_bytes("keyence", &bytes, &ReadOptions::default())
            .source
            .format,
        Format::Vk4
    );
    let e = err_bytes("keyence-l.vk4", &bytes, &channel("light 1"));
    assert!(
        e.contains("light intensity") && e.contains("not a length"),
        "{e}"
    );
    for (magic, ext) in [(&b"VK6"[..], "vk6"), (b"VK7", "vk7")] {
        let mut b = magic.to_vec();
        b.extend_from_slice(&[0u8; 200]);
        for name in [format!("k.{ext}"), format!("k-{ext}")] {
            let e = err_bytes(&name, &b, &ReadOptions::default());
            assert!(
                e.contains(&format!(
                    "a Keyence .{ext} file: not supported; export it as .x3p"
                )),
                "{e}"
            );
        }
    }
}

#[test]
fn sdf_text_and_binary_round_trip() {
    let map = sample_map();
    let g = grid(&map);
    let tol = 1e-15 * max_abs(&map);
    for (name, bytes) in [
        ("t.sdf", encoders::sdf_text(&g)),
        ("b.sdf", encoders::sdf_binary(&g, 7)),
    ] {
        let m = read_bytes(name, &bytes, &ReadOptions::default());
        assert_eq!(m.source.format, Format::Sdf);
        assert_map(
            &m.map,
            (13, 9, 12.5e-9, 7.5e-9, 1e-15),
            |i, j| map.at(i, j),
            4.0 * tol,
        );
        assert_eq!(
            read_bytes(&name.replace(".sdf", ""), &bytes, &ReadOptions::default())
                .source
                .format,
            Format::Sdf
        );
    }
    let q = max_abs(&map) / 30000.0;
    let m = read_bytes(
        "i16.sdf",
        &encoders::sdf_binary(&g, 5),
        &ReadOptions::default(),
    );
    assert_map(
        &m.map,
        (13, 9, 12.5e-9, 7.5e-9, 1e-15),
        |i, j| map.at(i, j),
        0.51 * q,
    );
    let mut z = map.heights().to_vec();
    z[7] = f64::NAN;
    z[8] = f64::NAN;
    let gh = Grid {
        z: &z,
        ..grid(&map)
    };
    for (name, bytes) in [
        ("ht.sdf", encoders::sdf_text(&gh)),
        ("hb.sdf", encoders::sdf_binary(&gh, 5)),
    ] {
        let e = err_bytes(name, &bytes, &ReadOptions::default());
        assert!(e.contains("2 of 117 heights are undefined"), "{name}: {e}");
    }
    let row: Vec<f64> = map.heights()[..13].to_vec();
    let gp = Grid {
        nx: 13,
        ny: 1,
        dx: 1e-8,
        dy: 1e-8,
        z: &row,
    };
    let e = err_bytes("p.sdf", &encoders::sdf_text(&gp), &ReadOptions::default());
    assert!(e.contains("a 1-D profile (13 points)"), "{e}");
}

#[test]
fn a_text_matrix_with_an_instrument_header_is_read() {
    let t = "h=3 w=4\npixel size=0.5 um\ndata unit=rad\nheight conversion factor (-> m)=2e-8\n\
             1 2 3 4\n5 6 7 8\n9 10 11 12.5\n";
    let m = read_bytes("matrix.txt", t.as_bytes(), &ReadOptions::default());
    assert_eq!((m.map.nx(), m.map.ny()), (4, 3));
    assert!((m.map.dx() - 0.5e-6).abs() < 1e-20 && (m.map.dy() - 0.5e-6).abs() < 1e-20);
    assert!((m.map.at(3, 2) - 12.5 * 2e-8).abs() < 1e-20);
    assert_eq!(m.source.height_unit_from, "file");
    // the factor to another unit; a data unit that is a length without a factor
    let t2 = t.replace("(-> m)=2e-8", "(-> nm)=2");
    let m = read_bytes("matrix-nm.txt", t2.as_bytes(), &ReadOptions::default());
    assert!((m.map.at(0, 0) - 2e-9).abs() < 1e-22);
    let t3 = "h=3 w=3\npixel size=1 nm\ndata unit=nm\n1 2 3\n4 5 6\n7 8 9\n";
    let m = read_bytes("matrix-unit.txt", t3.as_bytes(), &ReadOptions::default());
    assert!((m.map.at(2, 2) - 9e-9).abs() < 1e-22);
    // a phase without a factor is not a length; declared sizes are checked
    let e = err_bytes(
        "matrix-rad.txt",
        t3.replace("data unit=nm", "data unit=rad").as_bytes(),
        &ReadOptions::default(),
    );
    assert!(e.contains("\"rad\"") && e.contains("not a length"), "{e}");
    let e = err_bytes(
        "matrix-h.txt",
        t.replace("h=3", "h=650").as_bytes(),
        &ReadOptions::default(),
    );
    assert!(
        e.contains("line 1") && e.contains("h=650, but the matrix has 3 rows"),
        "{e}"
    );
    // undefined words
    let t4 = t.replace("7 8", "NaN BAD");
    let m = read_bytes("matrix-nan.txt", t4.as_bytes(), &fill());
    assert_eq!(m.source.undefined_points, 2);
    // one line is a 1-D profile
    let e = err_bytes(
        "line.txt",
        b"# spacing = 1 nm\n# height_unit = nm\n1 2 3 4 5 6 7\n",
        &ReadOptions::default(),
    );
    assert!(
        e.contains("a 1-D profile (7 points): the model needs a 2-D height map"),
        "{e}"
    );
    let e = err_bytes(
        "column.txt",
        b"# spacing = 1 nm\n# height_unit = nm\n1\n2\n3\n4\n",
        &ReadOptions::default(),
    );
    assert!(e.contains("a 1-D profile (4 points)"), "{e}");
}

#[test]
fn undefined_points_are_refused_by_default_and_filled_harmonically_on_request() {
    // a tilted plane with an interior hole: the harmonic fill reproduces the plane exactly
    let (nx, ny) = (10, 10);
    let plane = |i: usize, j: usize| 2.0 + 0.5 * i as f64 - 0.25 * j as f64;
    let hole = |i: usize, j: usize| (3..5).contains(&i) && (4..7).contains(&j);
    let mut t = String::from("# spacing = 1 nm\n# height_unit = nm\n");
    for j in 0..ny {
        let row: Vec<String> = (0..nx)
            .map(|i| {
                if hole(i, j) {
                    "NaN".to_string()
                } else {
                    plane(i, j).to_string()
                }
            })
            .collect();
        t += &row.join(" ");
        t += "\n";
    }
    let e = err_bytes("plane-hole.txt", t.as_bytes(), &ReadOptions::default());
    assert!(
        e.contains("6 of 100 heights are undefined")
            && e.contains("column 3 row 4")
            && e.contains("--undefined fill"),
        "{e}"
    );
    let m = read_bytes("plane-fill.txt", t.as_bytes(), &fill());
    assert_eq!(m.source.undefined_points, 6);
    for j in 0..ny {
        for i in 0..nx {
            assert!(
                (m.map.at(i, j) - plane(i, j) * 1e-9).abs() < 1e-21,
                "({i}, {j})"
            );
        }
    }
    // the count is in the report's JSON at source.undefined_points (a rough map, a hole)
    let mut t = String::from("# spacing = 1 nm\n# height_unit = nm\n");
    for j in 0..ny {
        let row: Vec<String> = (0..nx)
            .map(|i| {
                if hole(i, j) {
                    "NaN".to_string()
                } else {
                    ((i * 7 + j * 13) % 5).to_string()
                }
            })
            .collect();
        t += &row.join(" ");
        t += "\n";
    }
    let m = read_bytes("rough-fill.txt", t.as_bytes(), &fill());
    let r = topography::analyze_measurement(&m, &topography::AnalysisOptions::default()).unwrap();
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["source"]["undefined_points"], 6);
    assert_eq!(json["source"]["channels"][0], "heights");
    // a file that defines no point at all is refused even when filling
    let e = err_bytes(
        "all-nan.txt",
        b"# spacing = 1 nm\n# height_unit = nm\nnan nan nan\nnan nan nan\nnan nan nan\n",
        &fill(),
    );
    assert!(e.contains("all 9 heights are undefined"), "{e}");
    // "undefined" words parse case-insensitively; the policy parses from words
    assert_eq!("fill".parse::<Undefined>(), Ok(Undefined::Fill));
    assert!("maybe"
        .parse::<Undefined>()
        .unwrap_err()
        .contains("refuse or fill"));
}

#[test]
fn single_channel_formats_take_channel_0_or_their_name() {
    let bytes = encode(&sample_map(), Format::Gwy).unwrap();
    let m = read_bytes("one.gwy", &bytes, &channel("height"));
    assert_eq!(m.source.channels, ["Height"]);
    assert_eq!(
        read_bytes("one0.gwy", &bytes, &channel("0"))
            .source
            .title
            .as_deref(),
        Some("Height")
    );
    let e = err_bytes("one1.gwy", &bytes, &channel("1"));
    assert!(
        e.contains("\"1\" is not a channel") && e.contains("0 \"Height\""),
        "{e}"
    );
    let t = "# spacing = 1 nm\n# height_unit = nm\n1 2 3\n4 5 6\n7 8 9\n";
    assert_eq!(
        read_bytes("one.txt", t.as_bytes(), &channel("0"))
            .source
            .channels,
        ["heights"]
    );
    let e = err_bytes("one2.txt", t.as_bytes(), &channel("phase"));
    assert!(e.contains("it holds one, 0 \"heights\""), "{e}");
}

#[test]
fn format_names_and_unknown_binaries() {
    let e = "bogus".parse::<Format>().unwrap_err();
    for f in Format::ALL {
        assert!(e.contains(f.name()), "{e}");
        assert_eq!(f.name().parse::<Format>(), Ok(f));
    }
    assert!(encode(&sample_map(), Format::Opd).is_err());
    let e = err_bytes(
        "mystery",
        &[0xde, 0xad, 0xbe, 0xef, 0xff, 0x00, 0x01],
        &ReadOptions::default(),
    );
    assert!(
        e.contains("unknown format") && e.contains("nanoscope") && e.contains("sdf"),
        "{e}"
    );
    let e = err_bytes(
        "mystery.txt",
        &[0xde, 0xad, 0xbe, 0xef, 0xff, 0x00, 0x01],
        &ReadOptions::default(),
    );
    assert!(e.contains("not UTF-8") && e.contains("metropro"), "{e}");
}

/// Every instrument file the writers make: (name, format, bytes).
fn instrument_files() -> Vec<(&'static str, Format, Vec<u8>)> {
    let map = sample_map();
    let sq = square_map();
    let g = grid(&map);
    let mut z = map.heights().to_vec();
    z[30] = f64::NAN;
    let gh = Grid {
        z: &z,
        ..grid(&map)
    };
    let obj = |kind, bits, compressed| encoders::SurObject {
        name: "S",
        kind,
        grid: &g,
        bits,
        compressed,
    };
    vec![
        (
            "nanoscope-16",
            Format::Nanoscope,
            encoders::nanoscope(&g, 2, &ns_images()),
        ),
        (
            "nanoscope-32",
            Format::Nanoscope,
            encoders::nanoscope(&g, 4, &ns_images()),
        ),
        ("opd", Format::Opd, encoders::opd(&gh, 632.8, 1)),
        (
            "metropro-1",
            Format::Metropro,
            encoders::metropro(&grid(&sq), 1, 0, false),
        ),
        (
            "metropro-3",
            Format::Metropro,
            encoders::metropro(&grid(&sq), 3, 2, true),
        ),
        (
            "sur",
            Format::Sur,
            encoders::sur(&[obj(10, 16, false), obj(2, 32, false)]),
        ),
        (
            "sur-z",
            Format::Sur,
            encoders::sur(&[obj(2, 16, true), obj(12, 16, true)]),
        ),
        ("plu", Format::Plu, encoders::plu(&gh, 3)),
        ("plux", Format::Plu, encoders::plux(&g)),
        ("vk4", Format::Vk4, encoders::vk4(&g, 1)),
        ("sdf-a", Format::Sdf, encoders::sdf_text(&gh)),
        ("sdf-b", Format::Sdf, encoders::sdf_binary(&g, 5)),
    ]
}

#[test]
fn every_instrument_file_is_told_by_its_magic_and_capped() {
    for (name, format, bytes) in instrument_files() {
        assert_eq!(Format::sniff(&bytes), Some(format), "{name}");
        let m = decode(Path::new(name), &bytes, format, &fill())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(m.source.format, format);
        // every one states its spacing and its height unit
        assert_eq!(
            (m.source.spacing_from, m.source.height_unit_from),
            ("file", "file"),
            "{name}"
        );
        assert!(!m.source.channels.is_empty(), "{name}");
        // the grid cap is checked before the data are decoded
        let small = ReadOptions {
            max_points: 50,
            undefined: Undefined::Fill,
            ..ReadOptions::default()
        };
        let e = decode(Path::new(name), &bytes, format, &small)
            .unwrap_err()
            .to_string();
        assert!(e.contains("exceeds the cap of 50 points"), "{name}: {e}");
        // every truncation is an error naming the file and the format, never a panic
        let step = (bytes.len() / 97).max(1);
        for cut in (0..bytes.len()).step_by(step) {
            if let Err(e) = decode(Path::new(name), &bytes[..cut], format, &fill()) {
                let e = e.to_string();
                assert!(e.contains(name), "{name} cut at {cut}: {e}");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, .. ProptestConfig::default() })]
    /// Random corruption of any instrument file (byte flips anywhere, a truncation) gives a
    /// map or an error, never a panic, whether read as its format or as the format its
    /// corrupted bytes announce.
    #[test]
    fn corrupted_instrument_files_never_panic(
        file in 0usize..12,
        flips in proptest::collection::vec((0.0f64..1.0, any::<u8>()), 1..6),
        cut in 0.0f64..1.0,
        truncate in any::<bool>(),
    ) {
        let files = instrument_files();
        let (name, format, mut bytes) = files.into_iter().nth(file).unwrap();
        for (pos, byte) in flips {
            let k = ((bytes.len() - 1) as f64 * pos) as usize;
            bytes[k] = byte;
        }
        if truncate {
            bytes.truncate((bytes.len() as f64 * cut) as usize);
        }
        let opts = fill();
        let _ = decode(Path::new(name), &bytes, format, &opts);
        if let Some(f) = Format::sniff(&bytes) {
            let _ = decode(Path::new(name), &bytes, f, &opts);
        }
    }
}

/// Every 4-byte window of the first 1200 bytes of every instrument file set to extreme
/// values (all ones, zero, the largest and the smallest i32, in both byte orders): an error
/// or a map, never a panic (an overflow of a size taken from the file would panic in a
/// debug build) and never an allocation beyond the caps.
#[test]
fn header_fields_at_extreme_values_never_panic() {
    let patterns: [[u8; 4]; 5] = [
        [0xff; 4],
        [0; 4],
        [0x7f, 0xff, 0xff, 0xff],
        [0xff, 0xff, 0xff, 0x7f],
        [0x80, 0, 0, 0],
    ];
    let opts = ReadOptions {
        max_points: 1 << 20,
        ..fill()
    };
    for (name, format, bytes) in instrument_files() {
        for at in 0..bytes.len().min(1200).saturating_sub(3) {
            for p in patterns {
                let mut b = bytes.clone();
                b[at..at + 4].copy_from_slice(&p);
                let _ = decode(Path::new(name), &b, format, &opts);
            }
        }
    }
}
