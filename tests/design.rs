//! `stiction design threshold | map | merge` end to end: critical values against direct
//! `switch` runs on both sides, maps against direct runs, sharding and merging byte for
//! byte, per-point statuses, and the errors that say what to give instead.
//!
//! Scenes are the paper's switch in the fast mode with few cycles, driven by a spring
//! (`k_s`) and read with eq 1 "composite", where the paper's K_s = 8.44e9 Pa/m sits near the
//! stiction boundary (pull-out ratio about 1.07).

mod common;
use common::{has_null, json, scene_with, stiction, temp_dir, temp_file};
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

/// The paper's switch, spring-driven, composite eq 1, fast, at most `cycles` cycles, no
/// curves, no elastic comparison (exactly what a design point runs), with `more` edits.
fn spring_scene(cycles: usize, more: &[(&str, &str)]) -> String {
    let cycles = format!("cycles = {cycles}");
    let mut edits: Vec<(&str, &str)> = vec![
        ("impact_energy", "k_s = 8.44e9"),
        ("yield_modulus", "yield_modulus = \"composite\""),
        ("accuracy", "accuracy = \"fast\""),
        ("cycles", &cycles),
        ("points", "points = 0"),
        ("elastic_comparison", "elastic_comparison = false"),
    ];
    edits.extend_from_slice(more);
    scene_with("switch", &edits)
}

fn file(tag: &str, text: &str) -> String {
    temp_file(tag, text.as_bytes()).display().to_string()
}

/// Runs the binary with RAYON_NUM_THREADS set.
fn stiction_threads(threads: usize, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(args)
        .env("RAYON_NUM_THREADS", threads.to_string())
        .current_dir(std::env::temp_dir())
        .output()
        .expect("run stiction")
}

fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "exit {:?}, stderr: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

fn fails(out: &Output, code: i32, fragments: &[&str]) -> String {
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(code), "stderr: {err}");
    for f in fragments {
        assert!(err.contains(f), "`{f}` not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    err
}

fn read_json(p: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

/// The pull-out ratio of a direct `switch --until-accommodated` run of `scene` with
/// `lines` replaced.
fn direct(tag: &str, scene: &str, lines: &[(&str, String)]) -> Value {
    let mut text: Vec<String> = scene.lines().map(str::to_string).collect();
    for (key, line) in lines {
        let pos = text
            .iter()
            .position(|l| l.trim_start().starts_with(&format!("{key} =")))
            .unwrap_or_else(|| panic!("no {key}"));
        text[pos] = line.clone();
    }
    let path = file(tag, &(text.join("\n") + "\n"));
    json(&stiction(&[
        "switch",
        "--scene",
        &path,
        "--until-accommodated",
        "--format",
        "json",
    ]))
}

#[test]
fn critical_stiffness_separates_direct_runs_that_stick_from_runs_that_are_free() {
    let scene = spring_scene(3, &[]);
    let s = file("design-threshold", &scene);
    let v = json(&stiction(&[
        "design",
        "threshold",
        "--scene",
        &s,
        "--vary",
        "switch.k_s",
        "--from",
        "2e9",
        "--to",
        "1e11",
        "--format",
        "json",
    ]));
    assert!(!has_null(&v));
    for k in [
        "parameter",
        "critical_value",
        "free_side",
        "ratio_at_from",
        "ratio_at_to",
        "evaluations",
        "uncertainty",
        "crossings",
        "scan",
    ] {
        assert!(v.get(k).is_some(), "missing {k} in {v}");
    }
    assert_eq!(v["parameter"], "switch.k_s");
    assert_eq!(v["unit"], "Pa/m");
    assert_eq!(v["accuracy"], "fast");
    // a stiffer spring is free: the restoring pressure K_s d0 grows faster than the
    // pull-out of the harder impact (E_I grows with K_s at U = V_PI)
    assert_eq!(v["free_side"], "above");
    assert_eq!(v["kind"], "continuous");
    assert_eq!(v["crossings"].as_array().unwrap().len(), 1);
    assert!(v["ratio_at_from"].as_f64().unwrap() > 1.0);
    assert!(v["ratio_at_to"].as_f64().unwrap() < 1.0);
    let k = v["critical_value"].as_f64().unwrap();
    assert!((8.44e9..1e11).contains(&k), "{k}");
    // the uncertainty follows the fast mode's 1e-4 on the ratio: small but not zero
    let u = v["uncertainty"].as_f64().unwrap();
    assert!(u > 0.0 && u < 1e-3 * k, "{u} of {k}");
    assert!(v["evaluations"].as_u64().unwrap() >= v["scan"].as_array().unwrap().len() as u64);

    // direct runs 1 % either side: the stiffer one is free, the softer one sticks
    let ratio = |f: f64| {
        let r = direct(
            "design-threshold-direct",
            &scene,
            &[("k_s", format!("k_s = {:e}", k * f))],
        );
        assert_eq!(r["closes"], true);
        r["pull_out_ratio"].as_f64().unwrap()
    };
    let (above, below) = (ratio(1.01), ratio(1.0 / 1.01));
    assert!(above < 1.0, "ratio {above} above the critical K_s");
    assert!(below > 1.0, "ratio {below} below the critical K_s");

    // the table says the same in words
    let t = ok(&stiction(&[
        "design",
        "threshold",
        "--scene",
        &s,
        "--vary",
        "switch.k_s",
        "--from",
        "2e9",
        "--to",
        "1e11",
    ]));
    assert!(t.contains("free above") && t.contains("Pa/m"), "{t}");
}

#[test]
fn no_crossing_in_the_range_is_an_answer_with_both_end_ratios() {
    // eq 1 as printed: the paper's switch sticks at every K_s of the range (ratio ~ 150)
    let s = file(
        "design-nocross",
        &spring_scene(2, &[("yield_modulus", "yield_modulus = \"as_printed\"")]),
    );
    let args = [
        "design",
        "threshold",
        "--scene",
        &s,
        "--vary",
        "switch.k_s",
        "--from",
        "5e9",
        "--to",
        "2e10",
    ];
    let mut with_json = args.to_vec();
    with_json.extend(["--format", "json"]);
    let v = json(&stiction(&with_json));
    assert!(!has_null(&v));
    assert_eq!(v["free_side"], "nowhere");
    assert!(v["critical_value"].is_null() && v.get("uncertainty").is_none());
    assert!(v["crossings"].as_array().unwrap().is_empty());
    let (a, b) = (
        v["ratio_at_from"].as_f64().unwrap(),
        v["ratio_at_to"].as_f64().unwrap(),
    );
    assert!(a > 10.0 && b > 10.0, "{a} {b}");
    // lin scan (less than a decade): 9 points, nothing refined
    assert_eq!(v["evaluations"], 9);
    let t = ok(&stiction(&args));
    assert!(t.contains("none in range: sticks"), "{t}");
    // the modelling choices that move a verdict are echoed (eq 1's reading alone moves
    // this switch's ratio a hundredfold): the laws in the JSON and the table, the scene
    assert_eq!(v["laws"]["yield_modulus"], "as_printed");
    assert_eq!(v["laws"]["reload"], "as_printed");
    assert_eq!(v["laws"]["adhesion"], "maugis_kim");
    assert_eq!(v["scene"]["contact"]["yield_modulus"], "as_printed");
    assert!(
        t.lines().any(|l| l.starts_with("laws ")
            && l.contains("maugis_kim adhesion")
            && l.contains("eq 1 as_printed")
            && l.contains("reload as_printed")),
        "{t}"
    );
}

#[test]
fn drive_conflicts_and_unknown_fields_are_bad_input_that_say_what_to_give() {
    // the paper's scene gives impact_energy: K_s and the voltage are derived
    let out = stiction(&[
        "design",
        "threshold",
        "--vary",
        "switch.k_s",
        "--from",
        "1e9",
        "--to",
        "1e10",
    ]);
    fails(
        &out,
        2,
        &["switch.k_s", "`k_s = <Pa/m>`", "instead of `impact_energy`"],
    );
    let dir = temp_dir("design-conflict");
    let out = stiction(&[
        "design",
        "map",
        "--vary",
        "switch.voltage=40:60:lin:3",
        "--out",
        dir.join("m").to_str().unwrap(),
    ]);
    fails(&out, 2, &["switch.voltage", "`k_s = <Pa/m>`"]);
    assert!(!dir.join("m").exists(), "nothing is written on bad input");
    // a spring scene derives E_I: it cannot be varied
    let s = file("design-conflict-spring", &spring_scene(2, &[]));
    let out = stiction(&[
        "design",
        "threshold",
        "--scene",
        &s,
        "--vary",
        "switch.impact_energy",
        "--from",
        "0.1",
        "--to",
        "1",
    ]);
    fails(
        &out,
        2,
        &["`impact_energy = <J/m^2>`", "switch.k_s or switch.voltage"],
    );
    // unknown and non-numeric keys list the fields that can be varied
    for (field, why) in [
        ("switch.ks", "unknown field `switch.ks`"),
        ("contact.adhesion_law", "not a numeric key"),
        ("cycles", "top-level setting"),
    ] {
        let out = stiction(&[
            "design",
            "threshold",
            "--scene",
            &s,
            "--vary",
            field,
            "--from",
            "1",
            "--to",
            "2",
        ]);
        fails(
            &out,
            2,
            &[
                why,
                "switch.k_s",
                "surface.sigma_s",
                "contact.work_of_adhesion",
            ],
        );
    }
    // a range end outside the field's domain
    let out = stiction(&[
        "design",
        "threshold",
        "--scene",
        &s,
        "--vary",
        "surface.sigma_s",
        "--from",
        "1e-12",
        "--to",
        "1e-8",
    ]);
    fails(&out, 2, &["--from", "surface.sigma_s", "1e-11"]);
    // a bad shard and a bad axis
    let out = stiction(&[
        "design",
        "map",
        "--scene",
        &s,
        "--vary",
        "switch.k_s=1e9:1e10:log:2",
        "--shard",
        "3/2",
        "--out",
        dir.join("m").to_str().unwrap(),
    ]);
    fails(&out, 2, &["--shard `3/2`"]);
    let out = stiction(&[
        "design",
        "map",
        "--scene",
        &s,
        "--vary",
        "switch.k_s=1e9:1e10:cubic:2",
        "--out",
        dir.join("m").to_str().unwrap(),
    ]);
    fails(&out, 2, &["cubic", "lin or log"]);
}

#[test]
fn a_2d_map_whole_equals_its_two_shards_merged_byte_for_byte() {
    let s = file("design-shards", &spring_scene(2, &[]));
    let dir = temp_dir("design-shards");
    let d = |name: &str| dir.join(name).display().to_string();
    let map = |threads: usize, out: &str, shard: Option<&str>| {
        let mut args = vec![
            "design",
            "map",
            "--scene",
            &s,
            "--vary",
            "switch.k_s=4e9:4e10:log:3",
            "--vary",
            "surface.sigma_s=5e-9:1.1e-8:lin:3",
            "--out",
            out,
        ];
        if let Some(k) = shard {
            args.extend(["--shard", k]);
        }
        ok(&stiction_threads(threads, &args))
    };
    let whole = map(1, &d("whole"), None);
    assert!(
        whole.contains("3 x 3 = 9 points") && whole.contains("wrote"),
        "{whole}"
    );
    map(2, &d("part1"), Some("1/2"));
    map(2, &d("part2"), Some("2/2"));
    let merged = ok(&stiction(&[
        "design",
        "merge",
        &d("part2"),
        &d("part1"),
        "--out",
        &d("merged"),
    ]));
    assert!(merged.contains("9 points"), "{merged}");
    for f in ["map.csv", "map.json", "map.svg"] {
        let a = std::fs::read(dir.join("whole").join(f)).unwrap();
        let b = std::fs::read(dir.join("merged").join(f)).unwrap();
        assert!(
            a == b,
            "{f} of the merged shards differs from the whole run"
        );
    }
    // the parts hold interleaved points and record their shard
    let p1 = read_json(&dir.join("part1/map.json"));
    let idx: Vec<u64> = p1["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["index"].as_u64().unwrap())
        .collect();
    assert_eq!(idx, [0, 2, 4, 6, 8]);
    assert_eq!(p1["shard"]["k"], 1);
    // the whole map: header, physics across the grid, no null
    let csv = std::fs::read_to_string(dir.join("whole/map.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "switch.k_s,surface.sigma_s,pull_out_ratio,largest_pull_out_pa,restoring_pressure_pa,cycles_to_accommodation,first_sticking_cycle,sticks,closes,validity_holds,accommodation_cause,contact_resistance,real_contact_fraction,status"
    );
    assert_eq!(csv.lines().count(), 10);
    let v = read_json(&dir.join("whole/map.json"));
    assert!(!has_null(&v) && v.get("shard").is_none());
    assert_eq!(v["scene"]["switch"]["k_s"], 8.44e9);
    assert_eq!(v["scene"]["until_accommodated"], true);
    let ratio = |i: usize| v["points"][i]["pull_out_ratio"].as_f64().unwrap();
    for i in 0..9 {
        let p = &v["points"][i];
        assert_eq!(p["status"], "ok");
        let r = ratio(i);
        assert_eq!(p["sticks"], r > 1.0);
        let k = p["values"]["switch.k_s"].as_f64().unwrap();
        let restoring = p["restoring_pressure_pa"].as_f64().unwrap();
        assert!((restoring / (k * 2e-6) - 1.0).abs() < 1e-12, "K_s d0");
        let pull = p["largest_pull_out_pa"].as_f64().unwrap();
        assert!((r - pull / restoring).abs() <= 1e-12 * r, "phi = 1");
    }
    // rougher is freer (fewer, farther asperities), stiffer is freer
    for k in 0..3 {
        assert!(ratio(3 * k) > ratio(3 * k + 1) && ratio(3 * k + 1) > ratio(3 * k + 2));
    }
    for j in 0..3 {
        assert!(ratio(j) > ratio(3 + j) && ratio(3 + j) > ratio(6 + j));
    }
    let svg = std::fs::read_to_string(dir.join("whole/map.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("switch.k_s"));
    // a missing part is named
    let out = stiction(&["design", "merge", &d("part1"), "--out", &d("half")]);
    fails(&out, 2, &["missing part(s) 2/2"]);
    // the merged map may not overwrite a part
    let out = stiction(&[
        "design",
        "merge",
        &d("part1"),
        &d("part2"),
        "--out",
        &d("part1"),
    ]);
    fails(&out, 2, &["is one of the parts"]);
}

#[test]
fn map_points_equal_direct_switch_runs_including_a_switch_that_does_not_close() {
    let scene = spring_scene(3, &[]);
    let s = file("design-direct", &scene);
    let dir = temp_dir("design-direct");
    // U = 30 V is below the dynamic pull-in of K_s = 8.44e9 (about 44 V): no contact
    ok(&stiction(&[
        "design",
        "map",
        "--scene",
        &s,
        "--vary",
        "switch.voltage=30:60:lin:2",
        "--vary",
        "contact.work_of_adhesion=0.5:1:lin:2",
        "--out",
        dir.join("m").to_str().unwrap(),
    ]));
    let v = read_json(&dir.join("m/map.json"));
    assert!(!has_null(&v));
    let points = v["points"].as_array().unwrap();
    for p in points {
        let u = p["values"]["switch.voltage"].as_f64().unwrap();
        let w = p["values"]["contact.work_of_adhesion"].as_f64().unwrap();
        let r = direct(
            "design-direct-run",
            &scene,
            &[
                ("k_s", format!("k_s = 8.44e9\nvoltage = {u:e}")),
                ("work_of_adhesion", format!("work_of_adhesion = {w:e}")),
            ],
        );
        assert_eq!(p["closes"], r["closes"], "{p}");
        // the same computation: the same number, bit for bit
        assert_eq!(
            p["pull_out_ratio"].as_f64(),
            r["pull_out_ratio"].as_f64(),
            "{p}"
        );
        assert_eq!(
            p["largest_pull_out_pa"].as_f64(),
            r["largest_pull_out"].as_f64()
        );
        assert_eq!(
            p["restoring_pressure_pa"].as_f64(),
            r["restoring_pressure"].as_f64()
        );
        assert_eq!(p["sticks"], r["stiction"]);
        assert_eq!(
            p.get("cycles_to_accommodation").and_then(Value::as_u64),
            r.get("accommodated_after").and_then(Value::as_u64)
        );
        assert_eq!(
            p.get("first_sticking_cycle").and_then(Value::as_u64),
            r.get("first_sticking_cycle").and_then(Value::as_u64)
        );
        if u < 40.0 {
            assert_eq!(p["status"], "does_not_close");
            assert_eq!(p["pull_out_ratio"], 0.0);
            assert_eq!(p["sticks"], false);
        } else {
            assert_eq!(p["status"], "ok");
        }
    }
    // more adhesion, more pull-out at the closing voltage
    let r = |i: usize| points[i]["pull_out_ratio"].as_f64().unwrap();
    assert!(r(3) > r(2), "{} {}", r(3), r(2));
}

#[test]
fn a_point_out_of_a_domain_gets_its_status_and_the_map_goes_on() {
    let s = file("design-domain", &spring_scene(2, &[]));
    let dir = temp_dir("design-domain");
    let out = ok(&stiction(&[
        "design",
        "map",
        "--scene",
        &s,
        "--vary",
        "surface.sigma_s=0:1.6e-8:lin:3",
        "--out",
        dir.join("m").to_str().unwrap(),
    ]));
    assert!(out.contains("out_of_domain 1"), "{out}");
    let csv = std::fs::read_to_string(dir.join("m/map.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows[1], "0e0,,,,,,,,,,,,out_of_domain");
    assert!(
        rows[2].ends_with(",ok") && rows[3].ends_with(",ok"),
        "{csv}"
    );
    let v = read_json(&dir.join("m/map.json"));
    assert!(!has_null(&v));
    let p0 = &v["points"][0];
    assert!(p0.get("pull_out_ratio").is_none());
    let detail = p0["detail"].as_str().unwrap();
    assert!(
        detail.contains("surface.sigma_s") && detail.contains("1e-11"),
        "{detail}"
    );
    assert!(
        !detail.contains("design point:"),
        "no file in a point's message: {detail}"
    );
    assert!(std::fs::read_to_string(dir.join("m/map.svg"))
        .unwrap()
        .contains("<svg"));
}

#[test]
fn merge_refuses_shards_of_different_scenes_or_grids() {
    let a = file("design-merge-a", &spring_scene(1, &[]));
    let b = file(
        "design-merge-b",
        &spring_scene(1, &[("work_of_adhesion", "work_of_adhesion = 0.9")]),
    );
    let dir = temp_dir("design-merge");
    let d = |name: &str| dir.join(name).display().to_string();
    let part = |scene: &str, vary: &str, shard: &str, out: &str| {
        ok(&stiction(&[
            "design", "map", "--scene", scene, "--vary", vary, "--shard", shard, "--out", out,
        ]))
    };
    let grid = "switch.k_s=5e9:2e10:log:2";
    part(&a, grid, "1/2", &d("a1"));
    part(&b, grid, "2/2", &d("b2"));
    part(&a, "switch.k_s=5e9:3e10:log:2", "2/2", &d("a2-other-grid"));
    let out = stiction(&["design", "merge", &d("a1"), &d("b2"), "--out", &d("m")]);
    fails(
        &out,
        2,
        &["b2", "scene differs", "/contact/work_of_adhesion"],
    );
    let out = stiction(&[
        "design",
        "merge",
        &d("a1"),
        &d("a2-other-grid"),
        "--out",
        &d("m"),
    ]);
    fails(&out, 2, &["a2-other-grid", "grid"]);
    let out = stiction(&["design", "merge", &d("a1"), &d("nowhere"), "--out", &d("m")]);
    fails(&out, 2, &["nowhere", "map.json"]);
    assert!(
        !dir.join("m").exists(),
        "nothing is written when merge refuses"
    );
}

// ------------------------------------------------------------ categorical axes

/// Every point of `design map` on `vary` (one point object per index) and its CSV rows.
fn map_points(dir: &Path, scene: &str, vary: &[&str], more: &[&str]) -> (Vec<Value>, Vec<String>) {
    let mut args = vec!["design", "map", "--scene", scene];
    for v in vary {
        args.extend(["--vary", v]);
    }
    let out = dir.display().to_string();
    args.extend(["--out", &out]);
    args.extend_from_slice(more);
    ok(&stiction(&args));
    let v = read_json(&dir.join("map.json"));
    assert!(!has_null(&v));
    let csv = std::fs::read_to_string(dir.join("map.csv")).unwrap();
    (
        v["points"].as_array().unwrap().clone(),
        csv.lines().map(str::to_string).collect(),
    )
}

/// A point object without its `index` and `values`: what the point computed.
fn computed(p: &Value) -> Value {
    let mut p = p.clone();
    let o = p.as_object_mut().unwrap();
    o.remove("index");
    o.remove("values");
    p
}

#[test]
fn a_law_by_stiffness_map_equals_the_single_law_maps_bit_for_bit() {
    let s = file("design-laws", &spring_scene(3, &[]));
    let dir = temp_dir("design-laws");
    let ks = "switch.k_s=5e9:4e10:log:3";
    let laws = ["etsion_kadin", "kogut_etsion"];
    let (both, both_csv) = map_points(
        &dir.join("both"),
        &s,
        &["contact.plasticity_law=etsion_kadin,kogut_etsion", ks],
        &[],
    );
    assert_eq!(both.len(), 6);
    assert!(both_csv[0].starts_with("contact.plasticity_law,switch.k_s,pull_out_ratio,"));
    for (w, law) in laws.iter().enumerate() {
        let set = format!("contact.plasticity_law={law}");
        let (single, single_csv) = map_points(&dir.join(law), &s, &[ks], &["--set", &set]);
        assert_eq!(single.len(), 3);
        for (j, p) in single.iter().enumerate() {
            let q = &both[3 * w + j];
            // the word at every point, the number as the single map has it
            assert_eq!(q["values"]["contact.plasticity_law"], *law, "{q}");
            assert_eq!(q["values"]["switch.k_s"], p["values"]["switch.k_s"]);
            // the same computation: every number the same, bit for bit
            assert_eq!(computed(q), computed(p), "{law} point {j}");
            assert_eq!(
                q["pull_out_ratio"].as_f64().map(f64::to_bits),
                p["pull_out_ratio"].as_f64().map(f64::to_bits)
            );
            // and the CSV row is the single map's row behind the word
            assert_eq!(
                both_csv[1 + 3 * w + j],
                format!("{law},{}", single_csv[1 + j])
            );
        }
    }
    // the laws differ where it matters (docs/validation.md 5b): at K_s = 1.41e10 the
    // paper's law is free after accommodation and Kogut-Etsion's still sticks
    let ratio = |i: usize| both[i]["pull_out_ratio"].as_f64().unwrap();
    for j in 0..3 {
        assert!(ratio(3 + j) > ratio(j), "Kogut-Etsion pulls out harder");
    }
    assert!(
        ratio(1) < 1.0 && ratio(4) > 1.0,
        "{} {}",
        ratio(1),
        ratio(4)
    );
    // the table gives each law its boundary along K_s
    let t = ok(&stiction(&[
        "design",
        "map",
        "--scene",
        &s,
        "--vary",
        "contact.plasticity_law=etsion_kadin,kogut_etsion",
        "--vary",
        ks,
        "--out",
        dir.join("again").to_str().unwrap(),
    ]));
    assert!(
        t.contains("contact.plasticity_law = etsion_kadin: switch.k_s ~ ")
            && t.contains("contact.plasticity_law = kogut_etsion: switch.k_s ~ "),
        "{t}"
    );
    // the base scene's modelling choices are echoed, with the caveat that an axis varies
    // one of them here
    assert!(
        t.lines().any(|l| l.starts_with("laws ")
            && l.contains("plasticity")
            && l.contains("a map axis may vary them")),
        "{t}"
    );
    let svg = std::fs::read_to_string(dir.join("both/map.svg")).unwrap();
    assert!(svg.contains("contact.plasticity_law = kogut_etsion"));
}

#[test]
fn choice_keys_vary_like_the_scene_would_set_them() {
    // every point equals a direct run of the scene with the word set
    let scene = spring_scene(2, &[]);
    let s = file("design-choices", &scene);
    let dir = temp_dir("design-choices");
    for (key, line_key, words) in [
        (
            "contact.yield_modulus",
            "yield_modulus",
            ["as_printed", "composite"],
        ),
        ("contact.reload", "reload", ["as_printed", "bounded"]),
        (
            "contact.adhesion_law",
            "adhesion_law",
            ["maugis_kim", "dmt"],
        ),
    ] {
        let vary = format!("{key}={}", words.join(","));
        let (points, _) = map_points(&dir.join(line_key), &s, &[&vary], &[]);
        for (p, w) in points.iter().zip(words) {
            assert_eq!(p["values"][key], w);
            let r = direct(
                "design-choice-direct",
                &scene,
                &[(line_key, format!("{line_key} = \"{w}\""))],
            );
            assert_eq!(
                p["pull_out_ratio"].as_f64().map(f64::to_bits),
                r["pull_out_ratio"].as_f64().map(f64::to_bits),
                "{key} = {w}"
            );
        }
    }
    // eq 1 as printed puts the ratio far above the composite reading (about 100x)
    let (points, _) = map_points(
        &dir.join("yield_modulus"),
        &s,
        &["contact.yield_modulus=as_printed,composite"],
        &[],
    );
    let r: Vec<f64> = points
        .iter()
        .map(|p| p["pull_out_ratio"].as_f64().unwrap())
        .collect();
    assert!(r[0] > 50.0 * r[1], "{r:?}");
}

#[test]
fn words_a_key_does_not_take_are_refused_before_any_point_runs() {
    let s = file("design-words-bad", &spring_scene(1, &[]));
    let dir = temp_dir("design-words-bad");
    let out_dir = dir.join("m");
    let map = |vary: &str| {
        stiction(&[
            "design",
            "map",
            "--scene",
            &s,
            "--vary",
            vary,
            "--vary",
            "switch.k_s=5e9:2e10:log:2",
            "--out",
            out_dir.to_str().unwrap(),
        ])
    };
    // an unknown law: the option, the word and the laws there are
    let bad = "contact.plasticity_law=etsion_kadin,kogut_etsoin";
    fails(
        &map(bad),
        2,
        &[
            "--vary",
            bad,
            "`kogut_etsoin` is not a registered plasticity law",
            "etsion_kadin, kogut_etsion, adhesion_coupled, elastic",
        ],
    );
    fails(
        &map("contact.adhesion_law=maugis_kim,bradley"),
        2,
        &["`bradley`", "adhesion law", "maugis_kim, jkr, dmt, hertz"],
    );
    fails(
        &map("contact.reload=bounded,loose"),
        2,
        &[
            "`loose` is not a choice of contact.reload",
            "as_printed, bounded",
        ],
    );
    // a numeric key takes numbers, a law takes words
    fails(
        &map("surface.sigma_s=rough,smooth"),
        2,
        &[
            "surface.sigma_s takes numbers",
            "surface.sigma_s=FROM:TO:lin|log:N",
        ],
    );
    fails(
        &map("contact.plasticity_law=1:2:lin:2"),
        2,
        &["contact.plasticity_law", "takes words", "WORD,WORD"],
    );
    // a list of numbers is not a list of words
    fails(
        &map("surface.sigma_s=5e-9,8e-9"),
        2,
        &["`5e-9` is a number"],
    );
    // an unknown field lists the fields that take words
    fails(
        &map("contact.law=etsion_kadin"),
        2,
        &[
            "unknown field `contact.law`",
            "contact.plasticity_law",
            "contact.reload",
        ],
    );
    // twice the same word
    fails(
        &map("contact.reload=bounded,bounded"),
        2,
        &["`bounded` is listed twice"],
    );
    assert!(!out_dir.exists(), "nothing is written on bad input");
}

#[test]
fn law_map_shards_merge_and_parts_with_other_words_are_refused() {
    let s = file("design-law-shards", &spring_scene(1, &[]));
    let dir = temp_dir("design-law-shards");
    let d = |name: &str| dir.join(name).display().to_string();
    let laws = "contact.plasticity_law=etsion_kadin,kogut_etsion";
    let run = |laws: &str, shard: Option<&str>, out: &str| {
        let mut args = vec![
            "design",
            "map",
            "--scene",
            &s,
            "--vary",
            "switch.k_s=5e9:2e10:log:2",
            "--vary",
            laws,
            "--out",
            out,
        ];
        if let Some(k) = shard {
            args.extend(["--shard", k]);
        }
        ok(&stiction(&args))
    };
    run(laws, None, &d("whole"));
    run(laws, Some("1/2"), &d("p1"));
    run(laws, Some("2/2"), &d("p2"));
    run(
        "contact.plasticity_law=etsion_kadin,elastic",
        Some("2/2"),
        &d("p2-elastic"),
    );
    run(
        "contact.plasticity_law=kogut_etsion,etsion_kadin",
        Some("2/2"),
        &d("p2-swapped"),
    );
    ok(&stiction(&[
        "design",
        "merge",
        &d("p2"),
        &d("p1"),
        "--out",
        &d("merged"),
    ]));
    for f in ["map.csv", "map.json", "map.svg"] {
        assert!(
            std::fs::read(dir.join("whole").join(f)).unwrap()
                == std::fs::read(dir.join("merged").join(f)).unwrap(),
            "{f} of the merged shards differs from the whole run"
        );
    }
    for other in ["p2-elastic", "p2-swapped"] {
        let out = stiction(&["design", "merge", &d("p1"), &d(other), "--out", &d("m")]);
        fails(
            &out,
            2,
            &[
                other,
                "the words of contact.plasticity_law",
                "etsion_kadin, kogut_etsion",
            ],
        );
    }
    assert!(
        !dir.join("m").exists(),
        "nothing is written when merge refuses"
    );
}

/// A design runs a switch scene: another kind is said to be one, not reported by the
/// first key a switch does not take (`unknown key unload_from`, the QA case of the tenth
/// stop).
#[test]
fn a_design_of_a_surface_scene_says_it_needs_a_switch_scene() {
    let text = String::from_utf8(stiction(&["scene", "--print", "surface"]).stdout).unwrap();
    let s = file("design-surface-scene", &text);
    for args in [
        vec![
            "design",
            "threshold",
            "--scene",
            &s,
            "--vary",
            "surface.sigma_s",
            "--from",
            "2e-9",
            "--to",
            "1e-8",
        ],
        vec![
            "design",
            "map",
            "--scene",
            &s,
            "--vary",
            "surface.sigma_s=2e-9:1e-8:log:3",
            "--out",
            "/nonexistent/never",
        ],
    ] {
        let err = fails(
            &stiction(&args),
            2,
            &[
                "invalid --scene",
                "a surface scene",
                "a design runs a switch scene",
            ],
        );
        assert!(!err.contains("unload_from"), "{err}");
    }
}

/// Issue 42's contract on the command line: `--model-form check` on `switch`, `design
/// threshold`, `design map` and `design probability`, its JSON keys, and the scene key.
#[test]
fn the_model_form_check_is_reported_by_every_command_that_takes_it() {
    let out = stiction(&[
        "switch",
        "--accuracy",
        "fast",
        "--model-form",
        "check",
        "--format",
        "json",
    ]);
    let v = json(&out);
    let m = &v["model_form"];
    assert_eq!(m["robust"], Value::Bool(true));
    assert_eq!(m["flips"], serde_json::json!([]));
    let runs = m["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 8);
    for r in runs {
        for k in ["pull_out_ratio", "stiction", "laws", "validity_holds"] {
            assert!(r.get(k).is_some(), "runs[].{k}");
        }
    }
    assert_eq!(runs[0]["pull_out_ratio"], v["pull_out_ratio"]);
    let range = m["ratio_range"].as_array().unwrap();
    assert!(range[0].as_f64().unwrap() < 1.1 && range[1].as_f64().unwrap() > 150.0);
    assert!(m["excluded"]
        .as_array()
        .unwrap()
        .iter()
        .any(|e| e["value"] == "jkr"));
    assert!(!has_null(&v));
    // the table says it in words
    let t = stiction(&["switch", "--accuracy", "fast", "--model-form", "check"]);
    assert!(String::from_utf8_lossy(&t.stdout)
        .contains("model form: sticks under all 8 combinations; smallest ratio 1.07"));
    // the scene key does the same; single has no check
    let scene = file(
        "mf",
        &scene_with(
            "switch",
            &[("accuracy", "accuracy = \"fast\"\nmodel_form = \"check\"")],
        ),
    );
    let v = json(&stiction(&[
        "switch", "--scene", &scene, "--format", "json",
    ]));
    assert_eq!(v["model_form"]["runs"].as_array().unwrap().len(), 8);
    let v = json(&stiction(&[
        "switch",
        "--scene",
        &scene,
        "--model-form",
        "single",
        "--format",
        "json",
    ]));
    assert!(v.get("model_form").is_none());
    // a probability run: the range over the combinations
    let v = json(&stiction(&[
        "design",
        "probability",
        "--set",
        "contact.yield_modulus=composite",
        "--scatter",
        "surface.sigma_s=lognormal(7.78e-9,1.1)",
        "--samples",
        "6",
        "--accuracy",
        "fast",
        "--no-exact",
        "--model-form",
        "check",
        "--format",
        "json",
    ]));
    let r = v["model_form"]["stiction_probability_range"]
        .as_array()
        .unwrap();
    assert!(r[0].as_f64().unwrap() <= r[1].as_f64().unwrap());
    assert_eq!(v["model_form"]["runs"].as_array().unwrap().len(), 8);
    // a threshold: a critical value per combination
    let v = json(&stiction(&[
        "design",
        "threshold",
        "--vary",
        "switch.impact_energy",
        "--from",
        "0.05",
        "--to",
        "2",
        "--accuracy",
        "fast",
        "--model-form",
        "check",
        "--format",
        "json",
    ]));
    assert_eq!(v["model_form"]["runs"].as_array().unwrap().len(), 8);
    // a map: the share that sticks at each point, in model_form.json
    let dir = temp_dir("mfmap");
    let out = dir.join("m");
    let o = stiction(&[
        "design",
        "map",
        "--vary",
        "surface.sigma_s=3e-9:5e-8:log:2",
        "--accuracy",
        "fast",
        "--model-form",
        "check",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mf: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("model_form.json")).unwrap())
            .unwrap();
    let share = mf["share_sticking"].as_array().unwrap();
    assert_eq!(share.len(), 2);
    for s in share {
        let s = s.as_f64().unwrap();
        assert!((0.0..=1.0).contains(&s));
    }
}

/// Issue 43 item 4: `--count-outside-validity` makes the answer over every sample that ran
/// the headline; without it that answer is given beside (`all_samples`).
#[test]
fn samples_outside_validity_are_answered_over_all_samples() {
    // a yield stress that adhesion alone exceeds: every sample outside validity
    let args = [
        "design",
        "probability",
        "--set",
        "contact.yield_stress=3e8",
        "--scatter",
        "surface.sigma_s=lognormal(7.78e-9,1.1)",
        "--samples",
        "5",
        "--accuracy",
        "fast",
        "--no-exact",
        "--format",
        "json",
    ];
    let apart = json(&stiction(&args));
    assert!(apart.get("stiction_probability").is_none());
    assert_eq!(apart["outside_validity"], 5);
    let p = apart["all_samples"]["stiction"]["probability"]
        .as_f64()
        .unwrap();
    let mut with: Vec<&str> = args.to_vec();
    with.push("--count-outside-validity");
    let counted = json(&stiction(&with));
    assert_eq!(counted["stiction_probability"].as_f64(), Some(p));
    assert_eq!(counted["count_outside_validity"], Value::Bool(true));
}

/// A checked map sharded on the command line and merged gives the whole map's shares.
#[test]
fn a_checked_map_merges_its_shards_model_form_checks() {
    let dir = temp_dir("mfshard");
    let run = |extra: &[&str], out: &Path| {
        let mut args = vec![
            "design",
            "map",
            "--vary",
            "surface.sigma_s=3e-9:5e-8:log:4",
            "--accuracy",
            "fast",
            "--model-form",
            "check",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = stiction(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    let (whole, a, b, merged) = (dir.join("w"), dir.join("a"), dir.join("b"), dir.join("m"));
    run(&[], &whole);
    run(&["--shard", "1/2"], &a);
    run(&["--shard", "2/2"], &b);
    let o = stiction(&[
        "design",
        "merge",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let read = |d: &Path| -> Value {
        serde_json::from_str(&std::fs::read_to_string(d.join("model_form.json")).unwrap()).unwrap()
    };
    assert_eq!(
        read(&merged)["share_sticking"],
        read(&whole)["share_sticking"]
    );
    assert_eq!(
        read(&merged)["robust_points"],
        read(&whole)["robust_points"]
    );
    assert!(whole.join("model_form.svg").exists());
}

/// A checked probability run sharded on the command line and merged gives the whole run's
/// probabilities and intervals under every combination.
#[test]
fn a_checked_probability_run_merges_its_shards_model_form_checks() {
    let dir = temp_dir("mfprob");
    let run = |extra: &[&str], out: &Path| {
        let mut args = vec![
            "design",
            "probability",
            "--set",
            "contact.yield_modulus=composite",
            "--scatter",
            "surface.sigma_s=lognormal(7.78e-9,1.1)",
            "--samples",
            "6",
            "--accuracy",
            "fast",
            "--no-exact",
            "--model-form",
            "check",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = stiction(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    let (whole, a, b, merged) = (dir.join("w"), dir.join("a"), dir.join("b"), dir.join("m"));
    run(&[], &whole);
    run(&["--shard", "1/2"], &a);
    run(&["--shard", "2/2"], &b);
    let o = stiction(&[
        "design",
        "merge",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let read = |d: &Path| -> Value {
        serde_json::from_str(&std::fs::read_to_string(d.join("model_form.json")).unwrap()).unwrap()
    };
    let (m, w) = (read(&merged), read(&whole));
    assert_eq!(
        m["stiction_probability_range"],
        w["stiction_probability_range"]
    );
    for (x, y) in m["runs"]
        .as_array()
        .unwrap()
        .iter()
        .zip(w["runs"].as_array().unwrap())
    {
        assert_eq!(x["sticking"], y["sticking"]);
        assert_eq!(x["counted"], y["counted"]);
        assert_eq!(x["interval"], y["interval"]);
        assert_eq!(x["laws"], y["laws"]);
    }
    assert_eq!(m["summary"], w["summary"]);
}
