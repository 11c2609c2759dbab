//! `stiction topography`: a height map in every supported format gives the same GW
//! parameters as the library's analysis of the map itself, with the public JSON keys; the
//! instruments' own files (written here by the reader tests' independent encoders) round
//! trip through the command, with their channels (`--channel`), undefined points
//! (`--undefined`) and `--file-format` names; the band (`--cutoff`, `--contact-radius`);
//! the scene fragment it writes runs as a scene, and a scene takes its surface from a map
//! (`surface.topography`) or from merged `--scene` files; bad files exit 2 naming the file.

mod common;

use common::{json, stiction, temp_dir};
use stiction::model::topography::{
    analyze_map, io, synthesize, Amplitudes, AnalysisOptions, Format, HeightMap, Normalization,
    SelfAffinePsd, SynthesisOptions,
};

#[path = "../crates/topography/tests/encoders/mod.rs"]
mod encoders;

/// zlib with stored (uncompressed) deflate blocks, for the encoders' compressed `.sur`:
/// a valid stream (RFC 1950/1951) without a compression crate in this package.
fn zlib(data: &[u8]) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    let mut chunks = data.chunks(65_535).peekable();
    if chunks.peek().is_none() {
        out.extend_from_slice(&[1, 0, 0, 0xff, 0xff]);
    }
    while let Some(c) = chunks.next() {
        out.push(u8::from(chunks.peek().is_none()));
        let n = c.len() as u16;
        out.extend_from_slice(&n.to_le_bytes());
        out.extend_from_slice(&(!n).to_le_bytes());
        out.extend_from_slice(c);
    }
    let (mut a, mut b) = (1u32, 0u32);
    for &x in data {
        a = (a + u32::from(x)) % 65_521;
        b = (b + a) % 65_521;
    }
    out.extend_from_slice(&((b << 16) | a).to_be_bytes());
    out
}

/// CRC-32 (IEEE) of a zip entry.
fn crc32(data: &[u8]) -> u32 {
    let mut c = !0u32;
    for &x in data {
        c ^= u32::from(x);
        for _ in 0..8 {
            c = if c & 1 == 1 {
                (c >> 1) ^ 0xedb8_8320
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// A zip archive of `entries`, stored (the encoders' `.plux`; PKWARE APPNOTE 4.3).
fn zip_archive(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let (mut out, mut central) = (Vec::new(), Vec::new());
    for (name, data) in entries {
        let offset = out.len() as u32;
        let (crc, n) = (crc32(data), data.len() as u32);
        let fields = |sig: u32, central: bool| {
            let mut h = sig.to_le_bytes().to_vec();
            if central {
                h.extend_from_slice(&20u16.to_le_bytes()); // made by
            }
            for v in [20u16, 0, 0, 0, 0x21] {
                h.extend_from_slice(&v.to_le_bytes()); // needed, flags, stored, time, date
            }
            for v in [crc, n, n] {
                h.extend_from_slice(&v.to_le_bytes());
            }
            h.extend_from_slice(&(name.len() as u16).to_le_bytes());
            h.extend_from_slice(&0u16.to_le_bytes()); // extra
            if central {
                for v in [0u16, 0, 0] {
                    h.extend_from_slice(&v.to_le_bytes()); // comment, disk, internal
                }
                h.extend_from_slice(&0u32.to_le_bytes()); // external
                h.extend_from_slice(&offset.to_le_bytes());
            }
            h.extend_from_slice(name.as_bytes());
            h
        };
        out.extend(fields(0x0403_4b50, false));
        out.extend_from_slice(data);
        central.extend(fields(0x0201_4b50, true));
    }
    let (at, size) = (out.len() as u32, central.len() as u32);
    out.extend(central);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    let k = entries.len() as u16;
    for v in [0u16, 0, k, k] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&size.to_le_bytes());
    out.extend_from_slice(&at.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    out
}

fn surface() -> stiction::model::topography::HeightMap {
    let psd = SelfAffinePsd::new(0.8, 1e-6, None, 40e-9, Normalization::RmsHeight(6e-9)).unwrap();
    let grid = SynthesisOptions {
        nx: 128,
        ny: 128,
        dx: 1e-8,
        dy: 1e-8,
        seed: 11,
        amplitudes: Amplitudes::Gaussian,
    };
    synthesize(&psd, &grid).unwrap()
}

#[test]
fn every_format_gives_the_librarys_parameters_with_the_public_keys() {
    let map = surface();
    let direct = analyze_map(&map, &AnalysisOptions::default()).unwrap();
    let dir = temp_dir("topography-formats");
    for (format, ext) in [
        (Format::Npy, "npy"),
        (Format::Gsf, "gsf"),
        (Format::Gwy, "gwy"),
        (Format::X3p, "x3p"),
        (Format::Text, "txt"),
    ] {
        let p = dir.join(format!("surface.{ext}"));
        io::write_path(&p, &map, format).unwrap();
        let mut args = vec!["topography", p.to_str().unwrap(), "--format", "json"];
        if matches!(format, Format::Npy) {
            // npy holds no spacing or unit
            args.extend(["--spacing", "1e-8", "--height-unit", "m"]);
        }
        let v = json(&stiction(&args));
        // the command gives what the library gives on the file, to the bit ...
        let read = io::ReadOptions {
            spacing: matches!(format, Format::Npy).then_some(1e-8),
            height_unit: matches!(format, Format::Npy)
                .then(|| stiction::model::topography::LengthUnit::parse("m").unwrap()),
            ..io::ReadOptions::default()
        };
        let m = io::read_path(&p, &read).unwrap();
        let lib = stiction::model::topography::analyze_measurement(&m, &AnalysisOptions::default())
            .unwrap();
        // ... and that is the map's own analysis to the precision of the format (gsf
        // stores single precision)
        assert!((lib.m2 / direct.m2 - 1.0).abs() < 1e-5, "{ext}");
        for key in ["rms_height", "m0", "m2", "m4", "alpha"] {
            let got = v[key].as_f64().unwrap_or_else(|| panic!("{ext}: {key}"));
            let want = match key {
                "rms_height" => lib.rms_height,
                "m0" => lib.m0,
                "m2" => lib.m2,
                "m4" => lib.m4,
                _ => lib.alpha,
            };
            assert!(
                (got / want - 1.0).abs() < 1e-12,
                "{ext} {key}: {got} vs {want}"
            );
        }
        for (route, gw) in [
            ("spectral", lib.spectral.gw),
            ("summits", lib.summits.as_ref().unwrap().gw),
        ] {
            let o = &v[route];
            for (key, want) in [
                ("sigma_s", gw.sigma_s),
                ("asperity_density", gw.asperity_density),
                ("radius", gw.radius),
                ("offset", gw.offset),
            ] {
                let got = o[key].as_f64().unwrap();
                assert!((got / want - 1.0).abs() < 1e-12, "{ext} {route}.{key}");
            }
        }
        // summits: sigma_s of the summits below the rms height, their plane above the mean
        let sm = &v["summits"];
        assert!(sm["sigma_s"].as_f64().unwrap() < v["rms_height"].as_f64().unwrap());
        assert!(sm["offset"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn the_scene_fragment_runs_as_the_switch_scene_it_is_pasted_into() {
    let map = surface();
    let dir = temp_dir("topography-scene");
    let p = dir.join("surface.x3p");
    io::write_path(&p, &map, Format::X3p).unwrap();
    let out = dir.join("out");
    let o = stiction(&[
        "topography",
        p.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let fragment = std::fs::read_to_string(out.join("surface.toml")).unwrap();
    let frag: toml::Table = toml::from_str(&fragment).unwrap();
    let sigma = frag["surface"]["sigma_s"].as_float().unwrap();
    let n = frag["surface"]["asperity_density"].as_float().unwrap();
    let r = frag["contact"]["radius"].as_float().unwrap();
    assert!(std::fs::read_to_string(out.join("topography.svg"))
        .unwrap()
        .starts_with("<svg"));
    let v = json(&stiction(&[
        "switch",
        "--set",
        &format!("surface.sigma_s={sigma:e}"),
        "--set",
        &format!("surface.asperity_density={n:e}"),
        "--set",
        &format!("contact.radius={r:e}"),
        "--cycles",
        "2",
        "--accuracy",
        "fast",
        "--format",
        "json",
    ]));
    assert_eq!(v["scene"]["surface"]["sigma_s"].as_f64().unwrap(), sigma);
    assert!(v["cycles"][0]["pull_out_pressure"].as_f64().unwrap() > 0.0);
}

#[test]
fn bad_height_maps_exit_2_naming_the_file() {
    let dir = temp_dir("topography-bad");
    let garbage = dir.join("garbage.x3p");
    std::fs::write(&garbage, b"PK\x03\x04 not really a zip").unwrap();
    let empty = dir.join("empty.txt");
    std::fs::write(&empty, b"").unwrap();
    let nan = dir.join("nan.txt");
    std::fs::write(
        &nan,
        b"# spacing = 1e-8 m\n# height_unit = nm\n1 2 3\n4 nan 6\n7 8 9\n",
    )
    .unwrap();
    for (p, extra) in [
        (&garbage, vec![]),
        (&empty, vec!["--spacing", "1e-8"]),
        (&nan, vec![]),
    ] {
        let mut args = vec!["topography", p.to_str().unwrap()];
        args.extend(extra);
        let o = stiction(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{p:?}: {err}");
        assert!(
            err.contains(p.file_name().unwrap().to_str().unwrap()),
            "{err}"
        );
        assert!(!err.contains("panicked"));
    }
    let o = stiction(&["topography", "/dev/null", "--spacing", "-1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--spacing"));
}

/// A flat map and a perfectly planar one leave only the detrending's rounding (rms a few
/// 1e-25 m on nanometre heights): refused as flat, naming the file, instead of analysed
/// into summits of a radius of megametres (the QA case of the tenth stop); a spacing no
/// instrument has (1e308 m, where the slopes underflow) is refused by name; a nearly flat
/// map that can be analysed writes a fragment whose out-of-domain values are commented out,
/// with a warning each, so the fragment never carries a value the scenes reject.
#[test]
fn flat_maps_and_impossible_spacings_are_refused_and_fragments_stay_in_the_scene_domain() {
    let dir = temp_dir("topography-flat");
    let grid = |f: &dyn Fn(usize, usize) -> f64| {
        let rows: Vec<String> = (0..8)
            .map(|j| {
                (0..8)
                    .map(|i| format!("{}", f(i, j)))
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect();
        format!(
            "# spacing = 10 nm\n# height_unit = nm\n{}\n",
            rows.join("\n")
        )
    };
    let flat = dir.join("flat.txt");
    std::fs::write(&flat, grid(&|_, _| 1.0)).unwrap();
    let tilted = dir.join("tilted.txt");
    std::fs::write(&tilted, grid(&|i, j| 0.5 * i as f64 + 0.3 * j as f64)).unwrap();
    for p in [&flat, &tilted] {
        let out = dir.join(format!("{}-out", p.file_name().unwrap().to_str().unwrap()));
        let o = stiction(&[
            "topography",
            p.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{p:?}: {err}");
        assert!(
            err.contains(p.file_name().unwrap().to_str().unwrap()),
            "{err}"
        );
        assert!(err.contains("flat to rounding"), "{err}");
        assert!(!out.exists(), "nothing written for a map refused");
    }
    // a rough map with a spacing no instrument has
    let rough = dir.join("rough.txt");
    std::fs::write(
        &rough,
        grid(&|i, j| ((i * 7 + j * 13) % 5) as f64 - 2.0 + 0.1 * (i * j % 3) as f64),
    )
    .unwrap();
    let o = stiction(&["topography", rough.to_str().unwrap(), "--spacing", "1e308"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("rough.txt") && err.contains("grid spacing"),
        "{err}"
    );
    // a rough map of nanometre spacing is analysed; the same heights in femtometres over
    // micrometres give summits too flat for a scene: commented out, with a warning
    let o = stiction(&["topography", rough.to_str().unwrap(), "--format", "json"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let smooth = dir.join("smooth.txt");
    let text = std::fs::read_to_string(&rough)
        .unwrap()
        .replace("# spacing = 10 nm", "# spacing = 1000 nm")
        .replace("# height_unit = nm", "# height_unit = 1e-15");
    std::fs::write(&smooth, text).unwrap();
    let out = dir.join("smooth-out");
    let o = stiction(&[
        "topography",
        smooth.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(err.contains("outside_scene_domain"), "{err}");
    let fragment = std::fs::read_to_string(out.join("surface.toml")).unwrap();
    // every value left uncommented in the fragment lies inside its scene key's domain
    let mut section = String::new();
    for line in fragment.lines() {
        let body = line.split('#').next().unwrap().trim();
        if body.starts_with('[') {
            section = body.trim_matches(|c| c == '[' || c == ']').to_string();
        } else if let Some((k, v)) = body.split_once('=') {
            let key = format!("{section}.{}", k.trim());
            let x: f64 = v.trim().parse().unwrap();
            let d = stiction::model::keys::key(&key).unwrap();
            assert!(d.domain.contains(x), "{key} = {x} left in the fragment");
        }
    }
    assert!(
        fragment.contains("# sigma_s = ") || fragment.contains("# radius = "),
        "{fragment}"
    );
}

/// A map whose heights overflow the analysis (+-1e308 m) exits 2 naming the file and what
/// overflowed, with nothing on standard output: never a report of null moments and a NaN
/// sigma_s.
#[test]
fn a_map_whose_moments_overflow_is_refused_naming_the_file() {
    let dir = temp_dir("topography-overflow");
    let p = dir.join("huge.txt");
    let rows: Vec<String> = (0..16)
        .map(|j| {
            (0..16)
                .map(|i| {
                    let k = (i * 7 + j * 13 + i * j) % 5;
                    format!("{:e}", (k as f64 - 2.0) * 0.5e308)
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    std::fs::write(
        &p,
        format!(
            "# spacing = 10 nm\n# height_unit = m\n{}\n",
            rows.join("\n")
        ),
    )
    .unwrap();
    for format in ["table", "json"] {
        let o = stiction(&["topography", p.to_str().unwrap(), "--format", format]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{format}: {err}");
        assert!(
            err.contains("huge.txt") && err.contains("overflow"),
            "{err}"
        );
        assert!(
            o.stdout.is_empty(),
            "{}",
            String::from_utf8_lossy(&o.stdout)
        );
    }
}

// ---------------------------------------------------------------------------------------
// The instruments' formats through the command line.

/// A 64 x 48 self-affine map on a square grid of 12.5 nm (whole picometres, as .vk4
/// stores them), rms 5 nm.
fn instrument_map() -> HeightMap {
    let psd = SelfAffinePsd::new(0.8, 0.4e-6, None, 50e-9, Normalization::RmsHeight(5e-9)).unwrap();
    let grid = SynthesisOptions {
        nx: 64,
        ny: 48,
        dx: 12.5e-9,
        dy: 12.5e-9,
        seed: 45,
        amplitudes: Amplitudes::Gaussian,
    };
    synthesize(&psd, &grid).unwrap()
}

fn grid_of(z: &[f64]) -> encoders::Grid<'_> {
    encoders::Grid {
        nx: 64,
        ny: 48,
        dx: 12.5e-9,
        dy: 12.5e-9,
        z,
    }
}

fn nanoscope_channels() -> Vec<encoders::NsImage> {
    vec![
        encoders::NsImage {
            name: "Amplitude Error",
            direction: "Trace",
            soft: None,
            factor: 1.0,
        },
        encoders::NsImage {
            name: "Height Sensor",
            direction: "Trace",
            soft: Some("Sens. Zsens"),
            factor: 1.0,
        },
        encoders::NsImage {
            name: "Height Sensor",
            direction: "Retrace",
            soft: Some("Sens. Zsens"),
            factor: -0.5,
        },
    ]
}

/// Every instrument format as its file: (file name, bytes, `--file-format` name).
fn instrument_files(z: &[f64]) -> Vec<(&'static str, Vec<u8>, &'static str)> {
    let g = grid_of(z);
    let header_text = {
        let mut t = format!(
            "h={} w={}\npixel size=12.5 nm\ndata unit=nm\nheight conversion factor (-> m)=1e-9\n",
            g.ny, g.nx
        );
        for j in 0..g.ny {
            let row: Vec<String> = (0..g.nx)
                .map(|i| {
                    let v = z[j * g.nx + i];
                    if v.is_finite() {
                        format!("{:.12e}", v * 1e9)
                    } else {
                        "NaN".into()
                    }
                })
                .collect();
            t += &row.join(" ");
            t += "\n";
        }
        t.into_bytes()
    };
    vec![
        (
            "afm.spm",
            encoders::nanoscope(&g, 4, &nanoscope_channels()),
            "nanoscope",
        ),
        ("wyko.opd", encoders::opd(&g, 632.8, 2), "opd"),
        ("zygo.dat", encoders::metropro(&g, 1, 2, false), "metropro"),
        (
            "mountains.sur",
            encoders::sur(&[encoders::SurObject {
                name: "Height",
                kind: 2,
                grid: &g,
                bits: 32,
                compressed: true,
            }]),
            "sur",
        ),
        ("senso.plu", encoders::plu(&g, 3), "plu"),
        ("senso.plux", encoders::plux(&g), "plu"),
        ("keyence.vk4", encoders::vk4(&g, 1), "vk4"),
        ("iso-text.sdf", encoders::sdf_text(&g), "sdf"),
        ("iso-binary.sdf", encoders::sdf_binary(&g, 7), "sdf"),
        ("matrix.txt", header_text, "text"),
    ]
}

fn f(v: &serde_json::Value, path: &str) -> f64 {
    let mut x = v;
    for k in path.split('.') {
        x = &x[k];
    }
    x.as_f64().unwrap_or_else(|| panic!("{path}: {x}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

/// Each instrument's file, written by the reader tests' independent encoder, through
/// `stiction topography`: the grid, the spacing and the statistics of the map written (to
/// the format's precision), exactly what the library gives on the file, the contract's
/// JSON keys, and the same numbers with the format named by `--file-format`.
#[test]
fn every_instrument_format_round_trips_through_the_command() {
    let map = instrument_map();
    let direct = analyze_map(&map, &AnalysisOptions::default()).unwrap();
    let dir = temp_dir("topography-instruments");
    for (name, bytes, format) in instrument_files(map.heights()) {
        let p = dir.join(name);
        std::fs::write(&p, &bytes).unwrap();
        let v = json(&stiction(&[
            "topography",
            p.to_str().unwrap(),
            "--format",
            "json",
        ]));
        // the contract's keys
        assert_eq!(v["source"]["format"], format, "{name}");
        assert_eq!(v["source"]["undefined_points"], 0, "{name}");
        assert!(v["source"]["channels"]
            .as_array()
            .is_some_and(|c| !c.is_empty()));
        assert_eq!(
            (v["grid"]["nx"].as_u64(), v["grid"]["ny"].as_u64()),
            (Some(64), Some(48)),
            "{name}"
        );
        for key in ["grid.dx", "grid.dy"] {
            assert!(
                rel(f(&v, key), 12.5e-9) < 1e-6,
                "{name} {key}: {}",
                f(&v, key)
            );
        }
        for key in ["m0", "m2", "m4", "m20", "m02", "m40", "m04", "m22"] {
            assert!(
                f(&v, &format!("moments.{key}")) > 0.0,
                "{name} moments.{key}"
            );
        }
        assert!(v["moments"]["m11"].is_number() && v["moments"]["method"].is_string());
        for key in [
            "summits.sigma_s",
            "summits.asperity_density",
            "summits.radius",
            "spectral.sigma_s",
        ] {
            assert!(f(&v, key) > 0.0, "{name} {key}");
        }
        // the map written, to the format's precision (quantised heights; f32 spacings)
        assert!(
            rel(f(&v, "rms_height"), direct.rms_height) < 1e-4,
            "{name}: rms {}",
            f(&v, "rms_height")
        );
        assert!(
            rel(f(&v, "m2"), direct.m2) < 1e-3,
            "{name}: m2 {} vs {}",
            f(&v, "m2"),
            direct.m2
        );
        let sigma_s = direct.summits.as_ref().unwrap().gw.sigma_s;
        assert!(
            rel(f(&v, "summits.sigma_s"), sigma_s) < 1e-3,
            "{name}: sigma_s {} vs {sigma_s}",
            f(&v, "summits.sigma_s")
        );
        // exactly the library's analysis of the file
        let m = io::read_path(&p, &io::ReadOptions::default()).unwrap();
        let lib = stiction::model::topography::analyze_measurement(&m, &AnalysisOptions::default())
            .unwrap();
        for (key, want) in [
            ("rms_height", lib.rms_height),
            ("summits.sigma_s", lib.summits.as_ref().unwrap().gw.sigma_s),
            (
                "summits.asperity_density",
                lib.summits.as_ref().unwrap().gw.asperity_density,
            ),
            ("spectral.radius", lib.spectral.gw.radius),
        ] {
            assert!(rel(f(&v, key), want) < 1e-12, "{name} {key}");
        }
        // the format by name: a file whose extension says nothing
        let anon = dir.join(format!("{name}.bin"));
        std::fs::write(&anon, &bytes).unwrap();
        let w = json(&stiction(&[
            "topography",
            anon.to_str().unwrap(),
            "--file-format",
            format,
            "--format",
            "json",
        ]));
        assert_eq!(w["source"]["format"], format);
        assert_eq!(
            w["summits"], v["summits"],
            "{name} as --file-format {format}"
        );
    }
    // a file read as a format it is not: exit 2 naming the file and the format
    let sur = dir.join("mountains.sur");
    let o = stiction(&["topography", sur.to_str().unwrap(), "--file-format", "vk4"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("mountains.sur") && err.contains("vk4"),
        "{err}"
    );
    // every new name is a --file-format value
    let o = stiction(&["topography", sur.to_str().unwrap(), "--file-format", "vk6"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    for name in ["nanoscope", "opd", "metropro", "sur", "plu", "vk4", "sdf"] {
        assert!(err.contains(name), "{name}: {err}");
    }
}

/// A file with several channels: the first height channel by default, another by name (any
/// case) or 0-based index, every channel listed; an unknown channel exits 2 listing them.
#[test]
fn channels_are_chosen_by_name_or_index_and_an_unknown_one_is_refused() {
    let map = instrument_map();
    let dir = temp_dir("topography-channels");
    let p = dir.join("afm.spm");
    std::fs::write(
        &p,
        encoders::nanoscope(&grid_of(map.heights()), 4, &nanoscope_channels()),
    )
    .unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["topography", p.to_str().unwrap(), "--format", "json"];
        args.extend_from_slice(extra);
        stiction(&args)
    };
    let trace = json(&run(&[]));
    assert_eq!(
        trace["source"]["channels"],
        serde_json::json!([
            "Amplitude Error (Trace)",
            "Height Sensor (Trace)",
            "Height Sensor (Retrace)"
        ])
    );
    assert_eq!(trace["source"]["title"], "Height Sensor (Trace)");
    for c in ["2", "height sensor (retrace)", "Height Sensor (Retrace)"] {
        let retrace = json(&run(&["--channel", c]));
        assert_eq!(retrace["source"]["title"], "Height Sensor (Retrace)", "{c}");
        // the retrace holds -0.5 x the heights
        assert!(
            rel(f(&retrace, "rms_height"), 0.5 * f(&trace, "rms_height")) < 1e-6,
            "{c}"
        );
    }
    assert_eq!(json(&run(&["--channel", "1"]))["summits"], trace["summits"]);
    let o = run(&["--channel", "Phase"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("afm.spm")
            && err.contains("\"Phase\" is not a channel")
            && err.contains("Height Sensor (Retrace)"),
        "{err}"
    );
    assert!(o.stdout.is_empty());
    let o = run(&["--channel", "7"]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&["--channel", " "]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("--channel"), "{err}");
}

/// Undefined points (the instruments' markers, NaN): refused by default with a non-zero
/// exit naming the file, the count and `--undefined`; counted in `source.undefined_points`
/// and filled with `--undefined fill`, in every format that marks them.
#[test]
fn undefined_points_are_refused_by_default_and_filled_on_request() {
    let map = instrument_map();
    let mut z = map.heights().to_vec();
    for k in [70, 71, 1500, 2000] {
        z[k] = f64::NAN;
    }
    let direct = analyze_map(&map, &AnalysisOptions::default()).unwrap();
    let dir = temp_dir("topography-undefined");
    let mut checked = 0;
    for (name, bytes, _) in instrument_files(&z) {
        // Nanoscope and Keyence files mark no points
        if ["afm.spm", "keyence.vk4"].contains(&name) {
            continue;
        }
        let p = dir.join(name);
        std::fs::write(&p, &bytes).unwrap();
        let o = stiction(&["topography", p.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains(name)
                && err.contains("4 of 3072 heights are undefined")
                && err.contains("--undefined fill"),
            "{name}: {err}"
        );
        assert!(o.stdout.is_empty());
        let v = json(&stiction(&[
            "topography",
            p.to_str().unwrap(),
            "--undefined",
            "fill",
            "--format",
            "json",
        ]));
        assert_eq!(v["source"]["undefined_points"], 4, "{name}");
        // four points of 3072 filled from their neighbours: the statistics barely move
        assert!(rel(f(&v, "rms_height"), direct.rms_height) < 0.01, "{name}");
        let o = stiction(&["topography", p.to_str().unwrap(), "--undefined", "fill"]);
        let table = String::from_utf8_lossy(&o.stdout);
        assert!(
            table.contains("4 undefined points filled (harmonic interpolation)"),
            "{name}: {table}"
        );
        // refuse, said explicitly, is the default
        let o = stiction(&["topography", p.to_str().unwrap(), "--undefined", "refuse"]);
        assert_eq!(o.status.code(), Some(2), "{name}");
        checked += 1;
    }
    assert_eq!(checked, 8);
    // a word that is neither
    let o = stiction(&[
        "topography",
        dir.join("wyko.opd").to_str().unwrap(),
        "--undefined",
        "zero",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("--undefined") && err.contains("fill"), "{err}");
}

// ---------------------------------------------------------------------------------------
// The band: --cutoff and --contact-radius.

/// `--cutoff` low-pass filters the map before the analysis: at the pixel scale (or 0) it
/// changes nothing; longer, the summits grow fewer, monotonically across the `band`
/// table; `--contact-radius` gives the contact's own cutoff, 4 sqrt(R sigma_s); a cutoff
/// that is no length or longer than half the scan exits 2 naming its option.
#[test]
fn a_cutoff_chooses_the_band_of_wavelengths_the_parameters_describe() {
    let map = surface();
    let dir = temp_dir("topography-band");
    let p = dir.join("surface.x3p");
    io::write_path(&p, &map, Format::X3p).unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["topography", p.to_str().unwrap(), "--format", "json"];
        args.extend_from_slice(extra);
        json(&stiction(&args))
    };
    let plain = run(&[]);
    assert_eq!(plain["cutoff"]["applied"], false);
    assert!(plain["cutoff"]["wavelength"].is_null());
    assert_eq!(plain["cutoff"]["from"], "none");
    assert!(rel(f(&plain, "cutoff.nyquist_wavelength"), 2e-8) < 1e-12);
    let band = plain["band"].as_array().unwrap();
    assert!(band.len() >= 4, "{}", band.len());
    assert!(band[0]["cutoff"].is_null() && band[0]["chosen"] == true);
    for w in band.windows(2) {
        let (a, b) = (
            f(&w[0], "summits.asperity_density"),
            f(&w[1], "summits.asperity_density"),
        );
        assert!(b < a, "the density falls with the cutoff: {a:e} -> {b:e}");
        assert!(f(&w[1], "cutoff") > w[0]["cutoff"].as_f64().unwrap_or(0.0));
    }
    // the pixel scale, the Nyquist wavelength and 0: the map as sampled
    for c in ["1e-8", "2e-8", "0"] {
        let v = run(&["--cutoff", c]);
        assert_eq!(v["summits"], plain["summits"], "--cutoff {c}");
        assert_eq!(v["spectral"], plain["spectral"], "--cutoff {c}");
        assert_eq!(v["cutoff"]["applied"], false);
    }
    // a longer cutoff: the report is its band row
    let v = run(&["--cutoff", "8e-8"]);
    assert_eq!(v["cutoff"]["applied"], true);
    assert_eq!(v["cutoff"]["from"], "given");
    let chosen: Vec<&serde_json::Value> = v["band"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["chosen"] == true)
        .collect();
    assert_eq!(chosen.len(), 1);
    assert_eq!(f(chosen[0], "cutoff"), 8e-8);
    assert_eq!(
        chosen[0]["summits"],
        serde_json::json!({
            "sigma_s": v["summits"]["sigma_s"], "asperity_density": v["summits"]["asperity_density"],
            "radius": v["summits"]["radius"], "offset": v["summits"]["offset"]
        })
    );
    assert!(f(&v, "summits.asperity_density") < 0.5 * f(&plain, "summits.asperity_density"));
    assert!(f(&v, "summits.radius") > f(&plain, "summits.radius"));
    // the contact's own scale
    let v = run(&["--contact-radius", "1e-7"]);
    let a = (1e-7 * f(&plain, "summits.sigma_s")).sqrt();
    assert_eq!(v["cutoff"]["from"], "contact_radius");
    assert!(rel(f(&v, "cutoff.spot_radius"), a) < 1e-12);
    assert!(rel(f(&v, "cutoff.wavelength"), 4.0 * a) < 1e-12);
    // --cutoff wins over the contact's
    assert_eq!(
        run(&["--contact-radius", "1e-7", "--cutoff", "0"])["summits"],
        plain["summits"]
    );
    // the table and the fragment say which band
    let out = dir.join("out");
    let o = stiction(&[
        "topography",
        p.to_str().unwrap(),
        "--cutoff",
        "8e-8",
        "--out",
        out.to_str().unwrap(),
    ]);
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(
        table.contains("band: wavelengths longer than the cutoff 80.00 nm")
            && table.contains("<- this report"),
        "{table}"
    );
    let fragment = std::fs::read_to_string(out.join("surface.toml")).unwrap();
    assert!(
        fragment.contains("# Band: wavelengths longer than the cutoff 8.0000e-8 m"),
        "{fragment}"
    );
    // refused, naming the option
    for (args, option, says) in [
        (["--cutoff", "-1e-8"], "--cutoff", ">= 0"),
        (
            ["--cutoff", "1e-3"],
            "--cutoff",
            "half the shorter scan side",
        ),
        (["--contact-radius", "0"], "--contact-radius", "> 0"),
        (
            ["--contact-radius", "1"],
            "--contact-radius",
            "half the shorter scan side",
        ),
    ] {
        let mut a = vec!["topography", p.to_str().unwrap()];
        a.extend(args);
        let o = stiction(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(option) && err.contains(says),
            "{args:?}: {err}"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Scenes whose surface comes from a map, and scenes merged from several files.

/// The paper's switch scene without the three keys a topography sets (unless `keep`
/// names them), with `extra` lines in `[surface]`.
fn switch_without_roughness(extra: &str, keep: &[&str]) -> String {
    let mut text = String::new();
    for line in stiction::model::scene::PAPER_SWITCH.lines() {
        let body = line.split('#').next().unwrap_or("").trim();
        if ["radius =", "sigma_s =", "asperity_density ="]
            .iter()
            .any(|k| body.starts_with(k) && !keep.iter().any(|kk| body.starts_with(kk)))
        {
            continue;
        }
        text.push_str(line);
        text.push('\n');
        if line.starts_with("[surface]") {
            text.push_str(extra);
            text.push('\n');
        }
    }
    text
}

fn switch_args<'a>(scenes: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec!["switch"];
    for s in scenes {
        args.extend(["--scene", s]);
    }
    args.extend(["--cycles", "2", "--accuracy", "fast", "--format", "json"]);
    args
}

/// `[surface] topography = "afm.x3p"` beside the scene file (the command runs elsewhere):
/// the switch runs on the map's summit parameters, the echo holds the file, the route and
/// the band; a key the scene gives wins with a warning naming both values; a map that
/// cannot be read exits 2 naming the key, the scene file and the map.
#[test]
fn a_switch_scene_takes_its_surface_from_a_map_file() {
    let map = surface();
    let dir = temp_dir("topography-switch-scene");
    io::write_path(dir.join("afm.x3p"), &map, Format::X3p).unwrap();
    let report = json(&stiction(&[
        "topography",
        dir.join("afm.x3p").to_str().unwrap(),
        "--format",
        "json",
    ]));
    let scene = dir.join("switch.toml");
    std::fs::write(
        &scene,
        switch_without_roughness("topography = \"afm.x3p\"", &[]),
    )
    .unwrap();
    let o = stiction(&switch_args(&[scene.to_str().unwrap()]));
    let v = json(&o);
    let s = &v["scene"];
    assert_eq!(
        s["surface"]["topography"],
        dir.join("afm.x3p").display().to_string()
    );
    assert_eq!(s["surface"]["topography_route"], "summits");
    assert_eq!(s["surface"]["topography_cutoff"], 0.0);
    assert_eq!(s["surface"]["sigma_s"], report["summits"]["sigma_s"]);
    assert_eq!(
        s["surface"]["asperity_density"],
        report["summits"]["asperity_density"]
    );
    assert_eq!(s["contact"]["radius"], report["summits"]["radius"]);
    assert!(f(&v["cycles"][0], "pull_out_pressure") > 0.0);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("topography_value_overridden"));
    // the scene's own sigma_s and radius win, with a warning naming both values; the band
    // is the contact's (4 sqrt(R sigma_s) with the scene's R)
    std::fs::write(
        &scene,
        switch_without_roughness("topography = \"afm.x3p\"\nsigma_s = 5e-9", &["radius ="]),
    )
    .unwrap();
    let o = stiction(&switch_args(&[scene.to_str().unwrap()]));
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    let v = json(&o);
    assert_eq!(f(&v, "scene.surface.sigma_s"), 5e-9);
    assert_eq!(f(&v, "scene.contact.radius"), 4e-6);
    assert!(f(&v, "scene.surface.topography_cutoff") > 0.0);
    assert!(
        err.contains("warning[topography_value_overridden]: surface.sigma_s = 5e-9 m given by")
            && err
                .contains("warning[topography_value_overridden]: contact.radius = 4e-6 m given by")
            && err.contains("afm.x3p"),
        "{err}"
    );
    // the design commands read the same scene: a map over the band
    let out = dir.join("map");
    let o = stiction(&[
        "design",
        "map",
        "--scene",
        scene.to_str().unwrap(),
        "--vary",
        "surface.topography_cutoff=0:4e-7:lin:3",
        "--accuracy",
        "fast",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("map.json")).unwrap()).unwrap();
    assert!(m.to_string().contains("surface.topography_cutoff"));
    // a map that is not there; an option without a map
    std::fs::write(
        &scene,
        switch_without_roughness("topography = \"gone.x3p\"", &[]),
    )
    .unwrap();
    let o = stiction(&switch_args(&[scene.to_str().unwrap()]));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("switch.toml")
            && err.contains("`surface.topography`")
            && err.contains("gone.x3p"),
        "{err}"
    );
    let o = stiction(&[
        "switch",
        "--set",
        "surface.topography_cutoff=1e-7",
        "--cycles",
        "1",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("surface.topography_cutoff") && err.contains("surface.topography"),
        "{err}"
    );
}

/// `--scene` repeated: the files merge in order, a later key winning; the fragment
/// `stiction topography --out` writes completes a switch scene without glue; an error names
/// the file that gave the key.
#[test]
fn scenes_given_twice_merge_in_order_and_errors_name_their_file() {
    let map = surface();
    let dir = temp_dir("topography-merge");
    let p = dir.join("afm.x3p");
    io::write_path(&p, &map, Format::X3p).unwrap();
    let out = dir.join("out");
    let o = stiction(&[
        "topography",
        p.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let fragment: toml::Table =
        toml::from_str(&std::fs::read_to_string(out.join("surface.toml")).unwrap()).unwrap();
    let paper = dir.join("switch.toml");
    std::fs::write(&paper, stiction::model::scene::PAPER_SWITCH).unwrap();
    let gap = dir.join("gap.toml");
    std::fs::write(&gap, "[switch]\nd0 = 2.5e-6\n").unwrap();
    let frag = out.join("surface.toml");
    let v = json(&stiction(&switch_args(&[
        paper.to_str().unwrap(),
        frag.to_str().unwrap(),
        gap.to_str().unwrap(),
    ])));
    let s = &v["scene"];
    assert_eq!(
        f(s, "surface.sigma_s"),
        fragment["surface"]["sigma_s"].as_float().unwrap()
    );
    assert_eq!(
        f(s, "surface.asperity_density"),
        fragment["surface"]["asperity_density"].as_float().unwrap()
    );
    assert_eq!(
        f(s, "contact.radius"),
        fragment["contact"]["radius"].as_float().unwrap()
    );
    assert_eq!(f(s, "switch.d0"), 2.5e-6);
    assert_eq!(f(s, "switch.t_d"), 0.15e-6);
    assert_eq!(f(s, "contact.youngs_modulus"), 410e9);
    // the order decides
    let v = json(&stiction(&switch_args(&[
        gap.to_str().unwrap(),
        paper.to_str().unwrap(),
    ])));
    assert_eq!(f(&v, "scene.switch.d0"), 2e-6);
    // an error names the file that gave the key, and its line
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "# a gap no switch has\n[switch]\nd0 = -1.0\n").unwrap();
    let o = stiction(&switch_args(&[
        paper.to_str().unwrap(),
        bad.to_str().unwrap(),
    ]));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("bad.toml: invalid `switch.d0` = -1e0 (line 3)"),
        "{err}"
    );
    let o = stiction(&switch_args(&[
        paper.to_str().unwrap(),
        dir.join("none.toml").to_str().unwrap(),
    ]));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("none.toml"), "{err}");
}
