//! Physics guards and honest output: a switch that does not close, warnings where the
//! model leaves its ground, every choice shown, and output that survives its process.

mod common;
use common::{has_null, json, scene_with, stiction, temp_dir, temp_file};
use std::process::{Command, Stdio};

fn switch_scene(tag: &str, edits: &[(&str, &str)]) -> std::path::PathBuf {
    let mut all = vec![
        ("points", "points = 0"),
        ("accuracy", "accuracy = \"fast\""),
        ("cycles", "cycles = 2"),
        ("elastic_comparison", "elastic_comparison = false"),
    ];
    all.extend_from_slice(edits);
    temp_file(
        &format!("guard-{tag}"),
        scene_with("switch", &all).as_bytes(),
    )
}

/// Released from rest under a step voltage, the electrode closes only above the dynamic
/// pull-in voltage sqrt(27/32) V_PI (d0 >= g/2): below it the answer is a clean "does
/// not close", above it the run goes on.
#[test]
fn below_the_dynamic_pull_in_voltage_the_switch_does_not_close() {
    // the paper's K_s: V_PI = 48.2405 V, dynamic pull-in sqrt(27/32) V_PI = 44.3117 V
    for (u, closes) in [
        ("30.0", false),
        ("44.2", false),
        ("44.5", true),
        ("48.0", true),
    ] {
        let f = switch_scene(
            &format!("close-{u}"),
            &[(
                "impact_energy",
                &format!("k_s = 8.440183830384662e9\nvoltage = {u}"),
            )],
        );
        let out = stiction(&["switch", "--scene", f.to_str().unwrap(), "--format", "json"]);
        let v = json(&out);
        assert!((v["dynamic_pull_in_voltage"].as_f64().unwrap() - 44.3117).abs() < 1e-3);
        assert_eq!(v["closes"].as_bool().unwrap(), closes, "U = {u}");
        if closes {
            assert!(!v["cycles"].as_array().unwrap().is_empty());
            assert!(v["impact_energy"].as_f64().unwrap() > 0.0);
        } else {
            assert!(v["cycles"].as_array().unwrap().is_empty());
            assert!(!v["stiction"].as_bool().unwrap());
            let table = stiction(&["switch", "--scene", f.to_str().unwrap()]);
            assert!(table.status.success());
            assert!(String::from_utf8_lossy(&table.stdout).contains("does not close"));
        }
        assert_eq!(v["drive"]["mode"], "spring");
        assert!(!has_null(&v));
    }
}

#[test]
fn the_table_says_what_was_given_and_what_was_derived() {
    let f = switch_scene("drive-a", &[]);
    let text =
        String::from_utf8(stiction(&["switch", "--scene", f.to_str().unwrap()]).stdout).unwrap();
    assert!(text.contains("K_s = 8.44018e9 Pa/m (derived)"), "{text}");
    assert!(text.contains("E_I = 5e-1 J/m^2 (given)"), "{text}");
    assert!(
        text.contains("eq 1 as_printed")
            && text.contains("accuracy fast")
            && text.contains("maugis_kim"),
        "{text}"
    );
    assert!(text.contains("ratio"));
    let f = switch_scene(
        "drive-b",
        &[("impact_energy", "k_s = 1e10\nvoltage = 60.0")],
    );
    let text =
        String::from_utf8(stiction(&["switch", "--scene", f.to_str().unwrap()]).stdout).unwrap();
    assert!(
        text.contains("(given), U = 60.0000 V (given)") && text.contains("J/m^2 (derived)"),
        "{text}"
    );
}

/// A gold-like film: adhesion alone presses an asperity beyond its yield onset (the
/// paper's caveat), and the pressures exceed what separate contacts carry; the paper's Ru
/// scene raises none of these.
#[test]
fn warnings_where_the_model_leaves_its_ground() {
    let f = switch_scene(
        "gold",
        &[
            ("youngs_modulus", "youngs_modulus = 79e9"),
            ("yield_stress", "yield_stress = 0.3e9"),
        ],
    );
    let out = stiction(&["switch", "--scene", f.to_str().unwrap(), "--format", "json"]);
    let v = json(&out);
    let codes: Vec<&str> = v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["code"].as_str().unwrap())
        .collect();
    assert!(codes.contains(&"adhesion_yields_asperity"), "{codes:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.lines()
            .any(|l| l.starts_with("warning[adhesion_yields_asperity]:")),
        "{err}"
    );
    let paper = switch_scene("paper-ru", &[]);
    let v = json(&stiction(&[
        "switch",
        "--scene",
        paper.to_str().unwrap(),
        "--format",
        "json",
    ]));
    assert!(
        v["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .all(|w| w["code"] != "adhesion_yields_asperity"),
        "{v}"
    );
}

/// Beyond delta_max/delta_CP = 110 the fits extrapolate; the share of the load carried
/// there is what is reported.
#[test]
fn a_surface_pressed_far_beyond_the_fits_warns() {
    let text = scene_with(
        "surface",
        &[
            ("points", "points = 4"),
            ("accuracy", "accuracy = \"fast\""),
            ("unload_from", "unload_from = -9e-7"),
            ("sigma_s", "sigma_s = 5e-8"),
        ],
    );
    let f = temp_file("guard-deep", text.as_bytes());
    let v = json(&stiction(&[
        "surface",
        "--scene",
        f.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let codes: Vec<&str> = v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["code"].as_str().unwrap())
        .collect();
    assert!(codes.contains(&"beyond_fit_range"), "{codes:?}");
    assert!(codes.contains(&"pressure_above_hardness"), "{codes:?}");
}

#[test]
fn a_closed_pipe_ends_quietly_and_a_full_disk_is_an_error() {
    // reader gone: exit 0, nothing on stderr
    let mut child = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(["md", "--lambda", "1", "--points", "100000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!String::from_utf8_lossy(&out.stderr).contains("panicked"));
    if std::path::Path::new("/dev/full").exists() {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_stiction"))
            .args(["md", "--lambda", "1"])
            .stdout(full)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_ne!(out.status.code(), Some(0));
        assert_ne!(out.status.code(), Some(101), "{err}");
        assert!(
            err.contains("standard output") && !err.contains("panicked"),
            "{err}"
        );
    }
}

#[test]
fn output_folders_are_replaced_whole_or_left_alone() {
    let base = temp_dir("atomic");
    let dir = base.join("out");
    let f = switch_scene("atomic", &[("points", "points = 8")]);
    let run = |scene: &std::path::Path| {
        stiction(&[
            "switch",
            "--scene",
            scene.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
        ])
    };
    assert!(run(&f).status.success());
    let first = std::fs::read(dir.join("switch.json")).unwrap();
    // a folder that holds something else is refused, and nothing in it is touched
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    let out = run(&f);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("notes.txt"));
    assert_eq!(std::fs::read(dir.join("switch.json")).unwrap(), first);
    std::fs::remove_file(dir.join("notes.txt")).unwrap();
    // a run without curves leaves no plot of an earlier run beside its results
    let no_curves = switch_scene("atomic-0", &[("points", "points = 0")]);
    assert!(run(&no_curves).status.success());
    assert!(
        !dir.join("switch.svg").exists(),
        "stale switch.svg left behind"
    );
    assert!(dir.join("switch.json").exists());
    // a failing run (cannot write: the target's parent is a file) leaves the old results
    let blocked = base.join("file-not-dir");
    std::fs::write(&blocked, "x").unwrap();
    let out = stiction(&[
        "switch",
        "--scene",
        f.to_str().unwrap(),
        "--out",
        blocked.join("out").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    // no staging folders are left anywhere
    let leftovers: Vec<_> = std::fs::read_dir(&base)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(".out."))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn an_endless_scene_file_is_refused_without_reading_it_whole() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    let t = std::time::Instant::now();
    let out = stiction(&["switch", "--scene", "/dev/zero"]);
    assert_eq!(out.status.code(), Some(2));
    // a device is refused before it is opened (scenes are regular files)
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("/dev/zero") && err.contains("character device"),
        "{err}"
    );
    assert!(t.elapsed().as_secs() < 20);
}

/// A user law returning NaN is reported as such, not as a quadrature tolerance.
#[test]
fn a_law_returning_nan_is_named() {
    use stiction::asperity_plastic::{Elastic, ElastoPlasticAsperity};
    use stiction::contact_core::{AdhesionLaw, Jumps, LawError, Path, SurfaceLaw};
    use stiction::gw_surface::{GreenwoodWilliamson, Quadrature, Roughness};
    #[derive(Clone, Copy)]
    struct Broken;
    impl AdhesionLaw for Broken {
        fn force(&self, _r: f64, delta: f64, _p: Path) -> Result<f64, LawError> {
            Ok(if delta > 1e-9 {
                f64::NAN
            } else {
                delta.max(0.0)
            })
        }
        fn jumps(&self, _r: f64) -> Result<Jumps, LawError> {
            Ok(Jumps {
                jump_in: 0.0,
                jump_out: 0.0,
            })
        }
    }
    let gw = GreenwoodWilliamson::new(
        ElastoPlasticAsperity::new(Elastic::new(4e-6).unwrap(), Broken),
        Roughness {
            sigma_s: 7.78e-9,
            asperity_density: 1e13,
        },
        Quadrature::default(),
    )
    .unwrap();
    let e = gw
        .pressure(0.0, &gw.virgin(), Path::Approach)
        .unwrap_err()
        .to_string();
    assert!(e.contains("NaN") && e.contains("asperity law"), "{e}");
}

/// An infinite yield stress (elastic asperities: "never yields") is echoed by name in every
/// JSON that carries the scene, and delta_CP = inf likewise: never as null.
#[test]
fn infinite_values_are_named_never_null() {
    let edits = [
        ("yield_stress", "yield_stress = inf"),
        ("counter", "counter = \"material\"\ncounter_youngs_modulus = 168e9\ncounter_poisson_ratio = 0.38\ncounter_yield_stress = inf"),
        ("plasticity_law", "plasticity_law = \"elastic\""),
    ];
    for (kind, args) in [
        ("switch", vec!["--cycles", "1", "--accuracy", "fast"]),
        ("surface", vec!["--accuracy", "fast"]),
        ("asperity", vec![]),
    ] {
        let f = temp_file(
            &format!("inf-yield-{kind}"),
            scene_with(kind, &edits).as_bytes(),
        );
        let mut a = vec![kind, "--scene", f.to_str().unwrap(), "--format", "json"];
        a.extend(args);
        let v = json(&stiction(&a));
        assert!(!has_null(&v), "{kind}: a null in the JSON");
        assert_eq!(v["scene"]["contact"]["yield_stress"], "inf", "{kind}");
        assert_eq!(
            v["scene"]["contact"]["counter_yield_stress"], "inf",
            "{kind}"
        );
        if kind == "asperity" {
            assert_eq!(v["delta_cp"], "inf");
        }
    }
}

/// With a soft counter-film that yields first (Au-like: E = 79 GPa, S_Y = 0.3 GPa, under
/// Ru), the adhesion warning quotes the counter-film's E and S_Y, the body whose delta_CP
/// it compares with, not the asperity's.
#[test]
fn adhesion_warning_names_the_body_that_yields_first() {
    let scene = scene_with(
        "asperity",
        &[(
            "counter",
            "counter = \"material\"\ncounter_youngs_modulus = 79e9\ncounter_poisson_ratio = 0.42\ncounter_yield_stress = 0.3e9",
        )],
    );
    let f = temp_file("counter-yields-first", scene.as_bytes());
    let v = json(&stiction(&[
        "asperity",
        "--scene",
        f.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let w = v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|w| w["code"] == "adhesion_yields_asperity")
        .expect("gold-like counter-film: adhesion yields it");
    let m = w["message"].as_str().unwrap();
    assert!(
        m.contains("counter-surface yields first: E = 79.00 GPa, S_Y = 300.0 MPa"),
        "{m}"
    );
}
