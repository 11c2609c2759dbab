//! End-to-end tests of the command line: the JSON contracts of each subcommand.

mod common;
use common::{has_null, json, scene_with, stiction, temp_dir, temp_file};

#[test]
fn md_json_has_the_contract_keys_the_jkr_limit_and_no_null() {
    let v = json(&stiction(&["md", "--lambda", "1000", "--points", "40"]));
    for k in [
        "lambda",
        "jump_in_delta",
        "turning_delta",
        "pull_off_load_control",
        "pull_off_displacement_control",
        "curve",
    ] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    assert!((v["pull_off_load_control"].as_f64().unwrap() + 1.5).abs() < 0.02);
    assert!((v["pull_off_displacement_control"].as_f64().unwrap() + 5.0 / 6.0).abs() < 0.02);
    let curve = v["curve"].as_array().unwrap();
    assert_eq!(curve.len(), 40);
    for p in curve {
        for k in ["delta", "force", "a", "c", "stable", "branch"] {
            assert!(p.get(k).is_some(), "curve point lacks {k}");
        }
        // s is infinite on the non-contact branch: omitted there, never null
        assert_eq!(p.get("s").is_some(), p["branch"] == "contact", "{p}");
    }
    assert!(!has_null(&v));
}

#[test]
fn md_single_point_follows_the_path_rule() {
    let v = json(&stiction(&["md", "--lambda", "0.5", "--delta", "-1.3"]));
    assert_eq!(v["path"], "approach");
    assert_eq!(v["force"].as_f64().unwrap(), 0.0); // below jump-in -2/(pi 0.5) = -1.273
    let v = json(&stiction(&[
        "md", "--lambda", "0.5", "--delta", "-1.3", "--path", "retract", "--from", "2",
    ]));
    assert!(v["force"].as_f64().unwrap() < 0.0);
    for k in ["lambda", "delta", "path", "force"] {
        assert!(v.get(k).is_some());
    }
}

#[test]
fn asperity_json_runs_from_out_of_contact_to_delta_max_and_back() {
    let v = json(&stiction(&[
        "asperity",
        "--format",
        "json",
        "--delta-max",
        "17e-9",
    ]));
    // eq 1 as printed (the paper's scene): delta_CP = 4e-6 (pi 1.6149608 3.42e9/(2 410e9))^2
    assert!((v["delta_cp"].as_f64().unwrap() - 1.791052120036274e-9).abs() < 1e-20);
    let case = &v["cases"][0];
    for k in [
        "delta_max",
        "delta_res",
        "r_res",
        "pull_off_force",
        "loading",
        "unloading",
    ] {
        assert!(case.get(k).is_some(), "missing {k}");
    }
    for k in ["accuracy", "error_estimate", "scene", "warnings"] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    assert_eq!(v["scene"]["contact"]["yield_modulus"], "as_printed");
    let load = case["loading"].as_array().unwrap();
    let unload = case["unloading"].as_array().unwrap();
    assert_eq!(
        load[0]["force"].as_f64().unwrap(),
        0.0,
        "loading starts out of contact"
    );
    assert!((load.last().unwrap()["delta"].as_f64().unwrap() - 17e-9).abs() < 1e-22);
    assert!((unload[0]["delta"].as_f64().unwrap() - 17e-9).abs() < 1e-22);
    assert_eq!(
        unload.last().unwrap()["force"].as_f64().unwrap(),
        0.0,
        "unloading ends jumped out"
    );
    let min = unload
        .iter()
        .map(|p| p["force"].as_f64().unwrap())
        .fold(0.0, f64::min);
    let pull = case["pull_off_force"].as_f64().unwrap();
    assert!(pull <= min && pull > 1.01 * min, "{pull} vs sampled {min}");
    assert!(!has_null(&v));
}

/// Every printed scene is accepted back by its command, which runs it to the end.
#[test]
fn scene_print_round_trips_through_every_subcommand() {
    let small: [(&str, &[(&str, &str)]); 3] = [
        ("asperity", &[("points", "points = 12")]),
        (
            "surface",
            &[
                ("points", "points = 6"),
                ("accuracy", "accuracy = \"fast\""),
            ],
        ),
        (
            "switch",
            &[
                ("points", "points = 0"),
                ("accuracy", "accuracy = \"fast\""),
                ("cycles", "cycles = 1"),
                ("elastic_comparison", "elastic_comparison = false"),
            ],
        ),
    ];
    for (kind, edits) in small {
        let text = scene_with(kind, edits);
        assert!(text.contains("[contact]"));
        let f = temp_file(&format!("print-{kind}"), text.as_bytes());
        let v = json(&stiction(&[
            kind,
            "--scene",
            f.to_str().unwrap(),
            "--format",
            "json",
        ]));
        assert_eq!(
            v["scene"]["contact"]["yield_modulus"], "as_printed",
            "{kind}"
        );
        assert!(!has_null(&v), "{kind}");
    }
}

/// A cheap switch scene in a file of its own per `tag` (tests run in parallel).
fn small_switch_scene(tag: &str, extra: &[(&str, &str)]) -> std::path::PathBuf {
    let mut edits = vec![
        ("points", "points = 16"),
        ("accuracy", "accuracy = \"fast\""),
        ("cycles", "cycles = 3"),
    ];
    edits.extend_from_slice(extra);
    temp_file(
        &format!("switch-small-{tag}"),
        scene_with("switch", &edits).as_bytes(),
    )
}

#[test]
fn switch_json_has_the_contract_keys_and_the_verdict_is_the_ratio() {
    let f = small_switch_scene("json", &[]);
    let v = json(&stiction(&[
        "switch",
        "--scene",
        f.to_str().unwrap(),
        "--format",
        "json",
    ]));
    for k in [
        "k_s",
        "v_pull_in",
        "dynamic_pull_in_voltage",
        "impact_energy",
        "restoring_pressure",
        "loading",
        "cycles",
        "elastic",
        "stiction",
        "closes",
        "pull_out_ratio",
        "extrapolated_fraction",
        "accuracy",
        "error_estimate",
        "scene",
        "warnings",
        "drive",
    ] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    // 3 fast cycles of the paper's switch do not accommodate: the key is omitted, not null
    assert!(v.get("accommodated_after").is_none());
    let cycles = v["cycles"].as_array().unwrap();
    assert_eq!(cycles.len(), 3);
    for c in cycles {
        for k in [
            "cycle",
            "d_e",
            "pull_out_pressure",
            "unloading",
            "sticks",
            "pull_out_ratio",
            "hold",
            "hold_status",
            "end_of_impact",
        ] {
            assert!(c.get(k).is_some(), "cycle lacks {k}");
        }
        assert!(c["pull_out_pressure"].as_f64().unwrap() >= 0.0);
        // the ohmic contract: the closed switch under the hold and at the end of impact
        for state in ["hold", "end_of_impact"] {
            for k in [
                "separation",
                "real_contact_fraction",
                "spot_density",
                "mean_spot_radius",
                "contact_resistance",
            ] {
                assert!(c[state][k].as_f64().is_some(), "{state} lacks {k}");
            }
        }
        // R = 1 / (G/A x phi A): the spots on phi x electrode_area give its scale
        let h = &c["hold"];
        assert!(h["contact_resistance"].as_f64().unwrap() > 0.0);
        assert!(
            (h["spots"].as_f64().unwrap() / (h["spot_density"].as_f64().unwrap() * 1e-8) - 1.0)
                .abs()
                < 1e-12
        );
    }
    assert!(v["hold_pressure"].as_f64().unwrap() > 0.0);
    for k in ["d_e", "pull_out_pressure", "unloading"] {
        assert!(v["elastic"].get(k).is_some());
    }
    let restoring = v["restoring_pressure"].as_f64().unwrap();
    let worst = cycles
        .iter()
        .map(|c| c["pull_out_pressure"].as_f64().unwrap())
        .fold(0.0, f64::max);
    let ratio = v["pull_out_ratio"].as_f64().unwrap();
    assert!((ratio - worst / restoring).abs() <= 1e-12 * ratio);
    assert_eq!(v["stiction"].as_bool().unwrap(), ratio > 1.0);
    assert_eq!(v["accuracy"]["mode"], "fast");
    assert_eq!(v["accuracy"]["pull_out_tolerance"].as_f64().unwrap(), 1e-4);
    assert_eq!(v["drive"]["given"][0], "impact_energy");
    assert!(v["closes"].as_bool().unwrap());
    assert!(!has_null(&v));
}

#[test]
fn switch_writes_its_files_together() {
    let f = small_switch_scene("files", &[]);
    let dir = temp_dir("switch-files").join("out");
    let out = stiction(&[
        "switch",
        "--scene",
        f.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for name in ["switch.json", "cycles.csv", "curves.csv", "switch.svg"] {
        let meta = std::fs::metadata(dir.join(name)).unwrap();
        assert!(meta.len() > 100, "{name} too small");
    }
    let table = String::from_utf8(out.stdout).unwrap();
    assert!(table.contains("verdict"));
    // every row of the written CSVs is as wide as its header, the elastic comparison's too
    for name in ["cycles.csv", "curves.csv"] {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        let mut lines = text.lines();
        let width = lines.next().unwrap().split(',').count();
        for l in lines {
            assert_eq!(l.split(',').count(), width, "{name}: {l}");
        }
    }
    assert!(
        std::fs::read_to_string(dir.join("cycles.csv"))
            .unwrap()
            .lines()
            .any(|l| l.starts_with("elastic,")),
        "the scene compares elastic asperities"
    );
    // the plot's title is the scene's
    let svg = std::fs::read_to_string(dir.join("switch.svg")).unwrap();
    assert!(svg.contains("paper Fig 4"));
}

#[test]
fn surface_json_has_the_contract_keys() {
    let text = scene_with(
        "surface",
        &[
            ("points", "points = 12"),
            ("accuracy", "accuracy = \"fast\""),
        ],
    );
    let f = temp_file("surface-small", text.as_bytes());
    let v = json(&stiction(&[
        "surface",
        "--scene",
        f.to_str().unwrap(),
        "--format",
        "json",
        "--unload-from",
        "8e-9",
    ]));
    for k in [
        "loading",
        "unloading",
        "reloading",
        "pull_out_pressure",
        "accuracy",
        "error_estimate",
        "scene",
    ] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    assert!(v["pull_out_pressure"].as_f64().unwrap() > 0.0);
    assert_eq!(v["loading"].as_array().unwrap().len(), 12);
    assert!(v["loading"][0]["d"].as_f64().unwrap() == 8e-9);
    assert!(!has_null(&v));
    // without unloading the pull-out is omitted, not null
    let v = json(&stiction(&[
        "surface",
        "--scene",
        f.to_str().unwrap(),
        "--format",
        "json",
        "--unload-from",
        "8e-9",
    ]));
    assert!(v.get("pull_out_pressure").is_some());
}

/// The help lists exactly the subcommands the binary accepts: each listed name runs
/// (`--help` of each succeeds) and the list is the built set.
#[test]
fn help_lists_the_built_subcommands() {
    let out = stiction(&["--help"]);
    let text = String::from_utf8(out.stdout).unwrap();
    let listed: Vec<String> = text
        .split("Commands:")
        .nth(1)
        .expect("a Commands section")
        .lines()
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|w| w != "help")
        .collect();
    let mut expected = vec![
        "md",
        "asperity",
        "surface",
        "switch",
        "calibrate",
        "law",
        "scene",
        "design",
        "topography",
    ];
    expected.sort();
    let mut got = listed.clone();
    got.sort();
    assert_eq!(got, expected, "--help lists {listed:?}");
    for name in &listed {
        assert!(
            stiction(&[name, "--help"]).status.success(),
            "{name} --help fails"
        );
    }
}

/// The ohmic columns of cycles.csv, and `--require` refused by name when the scene cannot
/// compute its quantity or the text does not parse (exit 2 before any point runs).
#[test]
fn ohmic_columns_and_the_requirement_option() {
    let f = small_switch_scene("ohmic", &[]);
    let out = stiction(&["switch", "--scene", f.to_str().unwrap(), "--format", "csv"]);
    assert!(out.status.success());
    let csv = String::from_utf8(out.stdout).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for k in [
        "hold_status",
        "hold_separation_m",
        "hold_real_contact_fraction",
        "hold_spot_density_per_m2",
        "hold_mean_spot_radius_m",
        "hold_contact_resistance_ohm",
        "end_contact_resistance_ohm",
    ] {
        assert!(header.contains(&k), "{header:?} lacks {k}");
    }
    let row: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    let at = |k: &str| header.iter().position(|h| *h == k).unwrap();
    assert_eq!(row[at("hold_status")], "rests");
    let r: f64 = row[at("hold_contact_resistance_ohm")].parse().unwrap();
    assert!(r > 0.0 && r.is_finite());
    for (require, needle) in [
        ("contact_resistance=1", "--require"),
        ("resistance<1", "unknown quantity"),
        ("contact_resistance<nan", "must be finite and > 0"),
    ] {
        let out = stiction(&[
            "design",
            "threshold",
            "--scene",
            f.to_str().unwrap(),
            "--vary",
            "switch.impact_energy",
            "--from",
            "0.1",
            "--to",
            "1",
            "--require",
            require,
        ]);
        assert_eq!(out.status.code(), Some(2), "{require}");
        let e = String::from_utf8(out.stderr).unwrap();
        assert!(e.contains(needle) && e.contains(require), "{e}");
        // one reason, said once (it read "must be invalid requirement" before)
        assert!(!e.contains("must be invalid"), "{e}");
    }
    // no electrode area: the resistance cannot be computed, said before any point runs
    let g = temp_file(
        "switch-no-area",
        scene_with("switch", &[("electrode_area", "# no electrode area")]).as_bytes(),
    );
    let out = stiction(&[
        "design",
        "threshold",
        "--scene",
        g.to_str().unwrap(),
        "--vary",
        "switch.impact_energy",
        "--from",
        "0.1",
        "--to",
        "1",
        "--require",
        "contact_resistance<1",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8(out.stderr).unwrap();
    assert!(e.contains("switch.electrode_area"), "{e}");
}
