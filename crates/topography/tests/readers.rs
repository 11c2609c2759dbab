//! Every reader: round trips of known maps, and bad files of each format refused with a
//! message naming the file and what is wrong (never a panic).

use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};

use proptest::prelude::*;
use topography::io::{decode, encode};
use topography::{read_path, Format, HeightMap, LengthUnit, ReadOptions, TopographyError};

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
    for format in Format::ALL {
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
            "not a finite height",
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
    assert!(e.contains("1 of 117 points are marked invalid"), "{e}");
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
        let format = Format::ALL[format_ix];
        let mut bytes = encode(&sample_map(), format).unwrap();
        let k = ((bytes.len() - 1) as f64 * pos) as usize;
        bytes[k] = byte;
        let opts = npy_opts();
        let _ = decode(Path::new("fuzz"), &bytes, format, &opts);
        let n = (bytes.len() as f64 * cut) as usize;
        let _ = decode(Path::new("fuzz"), &bytes[..n], format, &opts);
    }
}
