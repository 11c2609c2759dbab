//! law.json and law.csv: round trips, the required keys, the scene, and corrupted files
//! whose errors name the JSON path and the value.

mod common;

use common::law;
use contact_law::{ContactLaw, LawError};
use proptest::prelude::*;
use serde_json::{json, Value};

fn tmpdir() -> std::path::PathBuf {
    let d = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("contact-law");
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn a_json_round_trip_gives_the_same_law_and_the_same_text() {
    let law = law();
    let text = law.to_json_string();
    let back = ContactLaw::from_json_str(&text).unwrap();
    assert_eq!(&back, law);
    assert_eq!(back.to_json_string(), text);
    let file = tmpdir().join("law.json");
    law.write_json(&file).unwrap();
    assert_eq!(&ContactLaw::from_path(&file).unwrap(), law);
}

#[test]
fn the_file_has_the_required_self_describing_keys_and_no_null() {
    let text = law().to_json_string();
    assert!(!text.contains("null") && !text.contains("NaN") && !text.contains("inf"));
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["format"], "stiction-contact-law");
    assert_eq!(v["version"], 2);
    assert_eq!(
        v["units"],
        json!({"d": "m", "d_min": "m", "pressure": "Pa", "tangent": "Pa/m"})
    );
    assert!(v["sign_convention"]
        .as_str()
        .unwrap()
        .contains("compressive positive"));
    assert!(v["reference_plane"]
        .as_str()
        .unwrap()
        .contains("mean plane of asperity heights"));
    assert_eq!(v["interpolation"]["in_d"]["rule"], "steffen-1990");
    assert_eq!(
        v["interpolation"]["in_d_min"]["rule"],
        "scaled-cubic-at-fixed-x"
    );
    assert!(
        v["interpolation"]["pressure_floor"]["value"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    for k in ["measured", "beyond_reach", "above_table", "below_table"] {
        assert!(v["regions"][k].is_string(), "regions.{k}");
    }
    let m = &v["interpolation"]["measured_error"];
    for k in ["metric", "method", "seed"] {
        assert!(!m[k].is_null(), "{k}");
    }
    for k in ["virgin", "approach", "retract"] {
        for s in ["max", "p99", "samples"] {
            assert!(m[k][s].is_number(), "{k}.{s}");
        }
    }
    let grid = v["d_min_grid"].as_array().unwrap();
    let branches = v["branches"].as_array().unwrap();
    assert_eq!(grid.len(), branches.len());
    let b = &branches[3];
    assert_eq!(b["d_min"], grid[3]);
    for k in ["approach", "retract"] {
        assert_eq!(b[k]["d"][0], b["d_min"]);
        assert_eq!(
            b[k]["d"].as_array().unwrap().len(),
            b[k]["pressure"].as_array().unwrap().len()
        );
        assert_eq!(
            b[k]["reach"],
            *b[k]["d"].as_array().unwrap().last().unwrap()
        );
    }
    assert!(b["pull_out"]["pressure"].as_f64().unwrap() < 0.0);
    assert!(b["approach"]["most_tensile"]["d"].is_number());
    for k in ["approach", "retract"] {
        let e = b["measured_error"][k].as_f64().unwrap();
        assert!((0.0..=2e-4).contains(&e), "{k}: {e}");
    }
    assert!(v["virgin"]["d"].is_array() && v["virgin"]["reach"].is_number());
    assert!(v["scene"].is_object());
    assert!(v["length_scale"].is_number() && v["tabulation"]["converged"].is_boolean());
}

#[test]
fn the_scene_is_stored_and_returned_uninterpreted() {
    let mut law = law().clone();
    let scene =
        json!({"name": "switch", "eq1": {"reading": "S_Y = 1.5 H"}, "laws": ["md", "ek"], "n": 3});
    law.set_scene(scene.clone()).unwrap();
    let back = ContactLaw::from_json_str(&law.to_json_string()).unwrap();
    assert_eq!(back.scene(), &scene);
    assert!(law.set_scene(json!([1, 2])).is_err());
    let e = law.set_scene(json!({"a": {"b": null}})).unwrap_err();
    assert!(e.to_string().contains("scene.a.b"), "{e}");
}

/// Applies `edit` to the law's JSON tree and returns the reader's error.
fn corrupt(edit: impl FnOnce(&mut Value)) -> LawError {
    let mut v: Value = serde_json::from_str(&law().to_json_string()).unwrap();
    edit(&mut v);
    ContactLaw::from_json_str(&serde_json::to_string(&v).unwrap()).unwrap_err()
}

fn path_of(e: &LawError) -> String {
    match e {
        LawError::Format { path, .. } => path.clone(),
        other => panic!("not a format error: {other}"),
    }
}

/// An edit of the JSON tree.
type Edit = Box<dyn FnOnce(&mut Value)>;

#[test]
fn corrupted_files_give_errors_naming_the_field_and_the_value() {
    let cases: Vec<(&str, Edit, &str)> = vec![
        (
            "format",
            Box::new(|v| v["format"] = json!("other-law")),
            "other-law",
        ),
        ("version", Box::new(|v| v["version"] = json!(3)), "3"),
        (
            "version",
            Box::new(|v| v["version"] = json!(1)),
            "tabulate it again",
        ),
        (
            "interpolation.in_d_min.rule",
            Box::new(|v| v["interpolation"]["in_d_min"]["rule"] = json!("linear-at-fixed-x")),
            "linear-at-fixed-x",
        ),
        (
            "interpolation.pressure_floor.value",
            Box::new(|v| v["interpolation"]["pressure_floor"]["value"] = json!(-1.0)),
            "-1",
        ),
        (
            "interpolation.pressure_floor",
            Box::new(|v| {
                v["interpolation"]
                    .as_object_mut()
                    .unwrap()
                    .remove("pressure_floor");
            }),
            "missing",
        ),
        (
            "regions.elsewhere",
            Box::new(|v| v["regions"]["elsewhere"] = json!("x")),
            "unknown key",
        ),
        (
            "branches[2].measured_error.retract",
            Box::new(|v| v["branches"][2]["measured_error"]["retract"] = json!(-1.0)),
            ">= 0",
        ),
        (
            "branches[2].retract.positive_tangent",
            Box::new(|v| {
                v["branches"][2]["retract"]["positive_tangent"] =
                    json!({"d": 1e-9, "tangent": 1e15, "rise": 1.0, "relative_rise": 0.1})
            }),
            "must match the curve",
        ),
        (
            "positive_retract_tangent",
            Box::new(|v| {
                v["positive_retract_tangent"] = json!({"branches": 3, "d_min_range": [1e-9, 2e-9],
                    "worst": {}, "largest_relative_rise": 0.1, "advice": "none"})
            }),
            "must match the branches",
        ),
        ("units.d", Box::new(|v| v["units"]["d"] = json!("nm")), "nm"),
        (
            "interpolation.in_d.rule",
            Box::new(|v| v["interpolation"]["in_d"]["rule"] = json!("spline")),
            "spline",
        ),
        (
            "branches[3].retract.d[17]",
            Box::new(|v| {
                let x = v["branches"][3]["retract"]["d"][16].clone();
                v["branches"][3]["retract"]["d"][17] = x;
            }),
            "increase strictly",
        ),
        (
            "branches[2].approach.pressure[5]",
            Box::new(|v| v["branches"][2]["approach"]["pressure"][5] = json!("abc")),
            "abc",
        ),
        (
            "branches[0].pull_out.d",
            Box::new(|v| v["branches"][0]["pull_out"]["d"] = Value::Null),
            "null",
        ),
        (
            "virgin.pressure",
            Box::new(|v| {
                v["virgin"]["pressure"].as_array_mut().unwrap().pop();
            }),
            "lengths must match",
        ),
        (
            "branches[1].d_min",
            Box::new(|v| v["branches"][1]["d_min"] = json!(1.0)),
            "d_min_grid[1]",
        ),
        (
            "branches[0].retract.reach",
            Box::new(|v| v["branches"][0]["retract"]["reach"] = json!(1.0)),
            "last separation",
        ),
        (
            "branches[0].pull_out.d",
            Box::new(|v| v["branches"][0]["pull_out"]["d"] = json!(1.0)),
            "on its curve",
        ),
        (
            "branches[4].approach.d[0]",
            Box::new(|v| v["branches"][4]["approach"]["d"][0] = json!(0.0)),
            "starts at its d_min",
        ),
        (
            "branches",
            Box::new(|v| {
                v["branches"].as_array_mut().unwrap().pop();
            }),
            "one branch per d_min",
        ),
        (
            "virgin.most_tensile",
            Box::new(|v| {
                v["virgin"].as_object_mut().unwrap().remove("most_tensile");
            }),
            "missing",
        ),
        (
            "branches[2].retract.colour",
            Box::new(|v| v["branches"][2]["retract"]["colour"] = json!(1)),
            "unknown key",
        ),
        (
            "scene.x",
            Box::new(|v| v["scene"] = json!({"x": null})),
            "null",
        ),
        (
            "d_min_grid",
            Box::new(|v| v["d_min_grid"] = json!({})),
            "array",
        ),
        (
            "tabulation.converged",
            Box::new(|v| v["tabulation"]["converged"] = json!(1)),
            "true or false",
        ),
        (
            "interpolation.measured_error.retract.samples",
            Box::new(|v| v["interpolation"]["measured_error"]["retract"]["samples"] = json!(-3)),
            "-3",
        ),
    ];
    for (want, edit, value) in cases {
        let e = corrupt(edit);
        assert_eq!(path_of(&e), want, "{e}");
        let m = e.to_string();
        assert!(m.contains(want) && m.contains(value), "{want}: {m}");
    }
}

#[test]
fn text_that_is_not_a_law_is_rejected_without_panic() {
    for text in [
        "",
        "{",
        "[1,2]",
        "null",
        "{\"format\": \"stiction-contact-law\"}",
        "{\"version\": 1}",
        "1e400",
    ] {
        assert!(ContactLaw::from_json_str(text).is_err(), "{text}");
    }
    let big = law()
        .to_json_string()
        .replacen("\"version\": 2", "\"version\": 1e400", 1);
    assert!(matches!(
        ContactLaw::from_json_str(&big),
        Err(LawError::Json(_))
    ));
    let e = ContactLaw::from_path("/nonexistent-dir/law.json").unwrap_err();
    assert!(
        matches!(e, LawError::Io { .. }) && e.to_string().contains("/nonexistent-dir/law.json")
    );
    let file = tmpdir().join("binary.json");
    std::fs::write(&file, [0xff, 0xfe, 0x00]).unwrap();
    assert!(ContactLaw::from_path(&file).is_err());
}

#[test]
fn the_csv_is_the_long_form_of_the_nodes() {
    let law = law();
    let mut buf = Vec::new();
    law.write_csv(&mut buf).unwrap();
    let text = String::from_utf8(buf).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("d_min_m,path,d_m,pressure_pa,tangent_pa_per_m")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let n_branch: usize = law
        .branches()
        .iter()
        .map(|b| b.approach().d().len() + b.retract().d().len())
        .sum();
    assert_eq!(rows.len(), law.virgin().d().len() + n_branch);
    let f = |s: &str| s.parse::<f64>().unwrap();
    // virgin rows first, with an empty d_min; values are the tabulated data and the
    // evaluator's tangent there
    for (i, r) in rows.iter().take(law.virgin().d().len()).enumerate() {
        assert_eq!((r[0], r[1]), ("", "virgin"));
        assert_eq!(
            (f(r[2]), f(r[3])),
            (law.virgin().d()[i], law.virgin().pressure()[i])
        );
        assert_eq!(f(r[4]), law.virgin_pressure(f(r[2])).unwrap().1);
    }
    let rest = &rows[law.virgin().d().len()..];
    let b = &law.branches()[2];
    let start: usize = law.branches()[..2]
        .iter()
        .map(|b| b.approach().d().len() + b.retract().d().len())
        .sum();
    let r = &rest[start];
    assert_eq!(
        (f(r[0]), r[1], f(r[2]), f(r[3])),
        (b.d_min(), "approach", b.d_min(), b.approach().pressure()[0])
    );
    let r = &rest[start + b.approach().d().len()];
    assert_eq!((f(r[0]), r[1]), (b.d_min(), "retract"));
    assert!(rest
        .iter()
        .all(|r| r.len() == 5 && (r[1] == "approach" || r[1] == "retract")));
    let file = tmpdir().join("law.csv");
    law.write_csv_file(&file).unwrap();
    assert_eq!(std::fs::read_to_string(&file).unwrap(), text);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]
    /// Any single-byte corruption of a valid file is read without panic: either a valid law
    /// or an error.
    #[test]
    fn corrupting_one_byte_never_panics(pos in 0usize..1_000_000, byte in any::<u8>()) {
        let text = small_law();
        let mut bytes = text.as_bytes().to_vec();
        let i = pos % bytes.len();
        bytes[i] = byte;
        if let Ok(s) = String::from_utf8(bytes) {
            let _ = ContactLaw::from_json_str(&s);
        }
    }
}

/// A small law file (coarse user grid) for the byte-corruption property.
fn small_law() -> &'static str {
    use contact_law::tabulate::{tabulate, Tabulation};
    static TEXT: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    TEXT.get_or_init(|| {
        let o = Tabulation {
            points_per_branch: 6,
            tolerance: 0.05,
            random_points: 4,
            ..Tabulation::uniform("3e-9:6e-9:2".parse().unwrap())
        };
        tabulate(&common::toy(), &o).unwrap().to_json_string()
    })
}
