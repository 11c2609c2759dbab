//! `stiction topography`: a height map in every supported format gives the same GW
//! parameters as the library's analysis of the map itself, with the public JSON keys; the
//! scene fragment it writes runs as a scene; bad files exit 2 naming the file.

mod common;

use common::{json, stiction, temp_dir};
use stiction::model::topography::{
    analyze_map, io, synthesize, Amplitudes, AnalysisOptions, Format, Normalization, SelfAffinePsd,
    SynthesisOptions,
};

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
