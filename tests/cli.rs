//! End-to-end tests of the command line: the JSON contracts of each subcommand.

mod common;
use common::{json, stiction, temp_file};

#[test]
fn md_json_has_the_contract_keys_and_the_jkr_limit() {
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
        for k in ["delta", "force", "a", "c", "stable"] {
            assert!(p.get(k).is_some(), "curve point lacks {k}");
        }
    }
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
    assert!((v["delta_cp"].as_f64().unwrap() - 1.4831702606020387e-9).abs() < 1e-20);
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
}

#[test]
fn scene_print_round_trips_through_every_subcommand_scene() {
    for kind in ["asperity", "surface", "switch"] {
        let out = stiction(&["scene", "--print", kind]);
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(text.contains("[contact]"));
        let f = temp_file(&format!("print-{kind}"), text.as_bytes());
        // the printed scene is accepted back (run the cheap one fully)
        if kind == "asperity" {
            assert!(stiction(&["asperity", "--scene", f.to_str().unwrap()])
                .status
                .success());
        }
    }
}

/// A cheap switch scene in a file of its own per `tag` (tests run in parallel).
fn small_switch_scene(tag: &str) -> std::path::PathBuf {
    let text = String::from_utf8(stiction(&["scene", "--print", "switch"]).stdout).unwrap();
    let text = text
        .replace("points = 200", "points = 16")
        .replace("accuracy = \"accurate\"", "accuracy = \"fast\"")
        .replace("cycles = 10", "cycles = 3");
    temp_file(&format!("switch-small-{tag}"), text.as_bytes())
}

#[test]
fn switch_json_has_the_contract_keys() {
    let f = small_switch_scene("json");
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
        "impact_energy",
        "restoring_pressure",
        "loading",
        "cycles",
        "elastic",
        "accommodated_after",
        "stiction",
        "extrapolated_fraction",
    ] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    let cycles = v["cycles"].as_array().unwrap();
    assert_eq!(cycles.len(), 3);
    for c in cycles {
        for k in ["cycle", "d_e", "pull_out_pressure", "unloading"] {
            assert!(c.get(k).is_some(), "cycle lacks {k}");
        }
        assert!(c["pull_out_pressure"].as_f64().unwrap() >= 0.0);
    }
    for k in ["d_e", "pull_out_pressure", "unloading"] {
        assert!(v["elastic"].get(k).is_some());
    }
    let restoring = v["restoring_pressure"].as_f64().unwrap();
    let worst = cycles
        .iter()
        .map(|c| c["pull_out_pressure"].as_f64().unwrap())
        .fold(0.0, f64::max);
    assert_eq!(v["stiction"].as_bool().unwrap(), worst > restoring);
}

#[test]
fn switch_writes_its_files() {
    let f = small_switch_scene("files");
    let dir = std::env::temp_dir().join(format!("stiction-out-{}", std::process::id()));
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
}

#[test]
fn surface_json_has_the_contract_keys() {
    let text = String::from_utf8(stiction(&["scene", "--print", "surface"]).stdout).unwrap();
    let text = text
        .replace("points = 200", "points = 12")
        .replace("accuracy = \"accurate\"", "accuracy = \"fast\"");
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
    for k in ["loading", "unloading", "pull_out_pressure"] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    assert!(v["pull_out_pressure"].as_f64().unwrap() > 0.0);
    assert_eq!(v["loading"].as_array().unwrap().len(), 12);
    assert!(v["loading"][0]["d"].as_f64().unwrap() == 8e-9);
}

#[test]
fn help_lists_the_built_subcommands() {
    let out = stiction(&["--help"]);
    let text = String::from_utf8(out.stdout).unwrap();
    for sub in ["md", "asperity", "surface", "switch", "scene"] {
        assert!(text.contains(sub), "--help lacks {sub}");
    }
}
