//! `stiction design probability` end to end: the JSON contract, the exact single-field
//! answer beside the Monte Carlo estimate, shards merged against one run byte for byte, the
//! same answer on any thread count, and the errors that name the field at fault.
//!
//! The scene is the paper's switch driven by a spring (K_s), eq 1 "composite", fast mode,
//! at most 3 cycles, whose critical K_s is about 1.3e10 Pa/m (docs/design.md).

mod common;
use common::{has_null, json, scene_with, stiction, temp_dir, temp_file};
use serde_json::Value;
use std::process::{Command, Output};

fn spring_scene() -> String {
    let text = scene_with(
        "switch",
        &[
            ("impact_energy", "k_s = 8.44e9"),
            ("yield_modulus", "yield_modulus = \"composite\""),
            ("accuracy", "accuracy = \"fast\""),
            ("cycles", "cycles = 3"),
        ],
    );
    temp_file("probability-spring", text.as_bytes())
        .display()
        .to_string()
}

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

const SPRING: &str = "switch.k_s=lognormal(1.25e10,1.3)";

#[test]
fn json_holds_the_contract_and_the_exact_answer_lies_in_the_interval() {
    let s = spring_scene();
    let v = json(&stiction(&[
        "design",
        "probability",
        "--scene",
        &s,
        "--scatter",
        SPRING,
        "--samples",
        "30",
        "--seed",
        "5",
        "--format",
        "json",
    ]));
    assert!(!has_null(&v));
    assert_eq!(v["samples"], 30);
    assert_eq!(v["confidence"], 0.95);
    assert_eq!(v["outside_validity"], 0);
    assert_eq!(v["does_not_close_probability"], 0.0);
    let p = v["stiction_probability"].as_f64().unwrap();
    let (lo, hi) = (
        v["ci_low"].as_f64().unwrap(),
        v["ci_high"].as_f64().unwrap(),
    );
    assert!(lo <= p && p <= hi);
    let by = v["by_cycle"].as_array().unwrap();
    assert_eq!(by.len(), 3);
    for (n, c) in by.iter().enumerate() {
        assert_eq!(c["cycle"], n + 1);
        let q = c["probability"].as_f64().unwrap();
        assert!(c["ci_low"].as_f64().unwrap() <= q && q <= c["ci_high"].as_f64().unwrap());
    }
    assert_eq!(by[2]["probability"], v["stiction_probability"]);
    // the exact answer: the CDF of the lognormal at the critical K_s
    let e = &v["exact"];
    assert_eq!(e["available"], true);
    let crit = e["critical_value"].as_f64().unwrap();
    assert!((crit / 1.299e10 - 1.0).abs() < 5e-3, "{crit}");
    let exact = e["stiction_probability"].as_f64().unwrap();
    let z = (crit / 1.25e10).ln() / 1.3f64.ln();
    let phi = 0.5 * (1.0 + erf(z / std::f64::consts::SQRT_2));
    assert!((exact - phi).abs() < 1e-6, "{exact} vs {phi}");
    assert!(lo <= exact && exact <= hi, "{exact} not in [{lo}, {hi}]");
    assert_eq!(v["driver"], "switch.k_s");
    assert!(v.get("points").is_none());
    // --confidence changes the intervals, not the samples
    let w = json(&stiction(&[
        "design",
        "probability",
        "--scene",
        &s,
        "--scatter",
        SPRING,
        "--samples",
        "30",
        "--seed",
        "5",
        "--confidence",
        "0.8",
        "--no-exact",
        "--format",
        "json",
    ]));
    assert_eq!(w["confidence"], 0.8);
    assert_eq!(w["stiction_probability"], v["stiction_probability"]);
    assert!(w["ci_high"].as_f64().unwrap() < hi && w.get("exact").is_none());
    // --target-halfwidth stops at the first block of 100 samples narrow enough
    let t = json(&stiction(&[
        "design",
        "probability",
        "--scene",
        &s,
        "--scatter",
        SPRING,
        "--samples",
        "300",
        "--seed",
        "5",
        "--target-halfwidth",
        "0.2",
        "--no-exact",
        "--format",
        "json",
    ]));
    assert_eq!(t["samples"], 100);
    assert_eq!(t["samples_requested"], 300);
    assert_eq!(t["stopping"]["rule"], "target_halfwidth");
    assert_eq!(t["stopping"]["target_met"], true);
    let half = 0.5 * (t["ci_high"].as_f64().unwrap() - t["ci_low"].as_f64().unwrap());
    assert!(half <= 0.2 && t["stopping"]["halfwidth"].as_f64() == Some(half));
}

/// The `<tag>` elements (polyline, polygon) of an SVG with exactly `points` points, in
/// drawing order, as (x, y) pixel pairs.
fn shapes(svg: &str, tag: &str, points: usize) -> Vec<Vec<(f64, f64)>> {
    svg.split(&format!("<{tag} "))
        .skip(1)
        .filter_map(|p| {
            let start = p.find("points=\"")? + "points=\"".len();
            let list = &p[start..start + p[start..].find('"')?];
            let xy: Vec<(f64, f64)> = list
                .split_whitespace()
                .map(|pair| {
                    let (x, y) = pair.split_once(',').expect("x,y");
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect();
            (xy.len() == points).then_some(xy)
        })
        .collect()
}

/// erf by its series (|x| < 3 here), to check the CDF without a statistics crate.
fn erf(x: f64) -> f64 {
    let mut term = x;
    let mut sum = x;
    for n in 1..200 {
        term *= -x * x / n as f64;
        sum += term / (2 * n + 1) as f64;
    }
    2.0 / std::f64::consts::PI.sqrt() * sum
}

#[test]
fn shards_merged_equal_one_run_byte_for_byte_on_any_thread_count() {
    let s = spring_scene();
    let dir = temp_dir("probability-shards");
    let d = |name: &str| dir.join(name).display().to_string();
    let run = |threads: usize, out: &str, shard: Option<&str>| {
        let mut args = vec![
            "design",
            "probability",
            "--scene",
            &s,
            "--scatter",
            "switch.k_s=lognormal(1.25e10,1.3)",
            "--scatter",
            "contact.work_of_adhesion=lognormal(0.5,1.2)",
            "--correlate",
            "switch.k_s,contact.work_of_adhesion=-0.3",
            "--samples",
            "12",
            "--seed",
            "9",
            "--out",
            out,
        ];
        if let Some(k) = shard {
            args.extend(["--shard", k]);
        }
        ok(&stiction_threads(threads, &args))
    };
    let whole = run(1, &d("whole"), None);
    assert!(
        whole.contains("P(stiction)") && whole.contains("drives failure"),
        "{whole}"
    );
    // the modelling choices are echoed in the table (the merged report reads them from
    // the parts' scene as well)
    let laws = |t: &str| {
        t.lines()
            .any(|l| l.starts_with("laws ") && l.contains("adhesion") && l.contains("eq 1 "))
    };
    assert!(laws(&whole), "{whole}");
    run(2, &d("part1"), Some("1/2"));
    run(2, &d("part2"), Some("2/2"));
    let merged = ok(&stiction(&[
        "design",
        "merge",
        &d("part2"),
        &d("part1"),
        "--out",
        &d("merged"),
    ]));
    assert!(merged.contains("12 run of 12"), "{merged}");
    assert!(laws(&merged), "{merged}");
    for f in ["samples.csv", "probability.json", "probability.svg"] {
        let a = std::fs::read(dir.join("whole").join(f)).unwrap();
        let b = std::fs::read(dir.join("merged").join(f)).unwrap();
        assert!(a == b, "{f} of the merged parts differs from the whole run");
    }
    let p1: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("part1/probability.json")).unwrap())
            .unwrap();
    let idx: Vec<u64> = p1["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["index"].as_u64().unwrap())
        .collect();
    assert_eq!(idx, [0, 2, 4, 6, 8, 10]);
    assert_eq!(p1["shard"]["k"], 1);
    let csv = std::fs::read_to_string(dir.join("whole/samples.csv")).unwrap();
    assert!(csv.starts_with("index,switch.k_s,contact.work_of_adhesion,status,counted,"));
    assert_eq!(csv.lines().count(), 13);
    let svg = std::fs::read_to_string(dir.join("whole/probability.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("P(stuck by cycle n)"));
    // the curve and its shaded band: the band is one polygon along the lower ends and back
    // along the upper ends, a point per cycle each way
    assert!(
        svg.contains("95 % confidence interval (Clopper-Pearson)"),
        "the band is not in the legend"
    );
    let lines = shapes(&svg, "polyline", 3);
    assert_eq!(lines.len(), 1, "the curve, one point per cycle");
    let curve = &lines[0];
    let bands = shapes(&svg, "polygon", 6);
    assert_eq!(bands.len(), 1, "one band of 2 x 3 points");
    let (lower, upper): (Vec<_>, Vec<_>) = (
        bands[0][..3].to_vec(),
        bands[0][3..].iter().rev().copied().collect(),
    );
    for n in 0..3 {
        // SVG y grows downwards: the lower end is drawn at or below the curve
        assert_eq!(curve[n].0, lower[n].0);
        assert_eq!(curve[n].0, upper[n].0);
        assert!(
            lower[n].1 >= curve[n].1 && curve[n].1 >= upper[n].1,
            "cycle {}",
            n + 1
        );
    }
    assert!(
        upper.iter().zip(&lower).any(|(u, l)| u.1 < l.1),
        "a band of some width"
    );
    // a missing part is named; a map folder and a probability folder do not merge
    fails(
        &stiction(&["design", "merge", &d("part1"), "--out", &d("half")]),
        2,
        &["missing part(s) 2/2"],
    );
    std::fs::create_dir_all(dir.join("map")).unwrap();
    std::fs::write(dir.join("map/map.json"), "{}").unwrap();
    fails(
        &stiction(&["design", "merge", &d("part1"), &d("map"), "--out", &d("x")]),
        2,
        &["do not merge"],
    );
}

#[test]
fn bad_scatter_is_refused_naming_the_field_before_anything_runs() {
    let s = spring_scene();
    let base = [
        "design",
        "probability",
        "--scene",
        s.as_str(),
        "--samples",
        "5",
    ];
    let with = |more: &[&str]| {
        let mut a: Vec<&str> = base.to_vec();
        a.extend_from_slice(more);
        stiction(&a)
    };
    fails(
        &with(&["--scatter", "surface.sigma_s=normal(5e-9,4e-9)"]),
        2,
        &[
            "--scatter",
            "surface.sigma_s",
            "below 1e-11",
            "never clipped",
        ],
    );
    fails(
        &with(&["--scatter", "contact.poisson_ratio=uniform(0.3,0.7)"]),
        2,
        &["contact.poisson_ratio", "above 5e-1"],
    );
    fails(
        &with(&["--scatter", "surface.sigma_s=gamma(1,2)"]),
        2,
        &[
            "--scatter",
            "unknown distribution `gamma`",
            "lognormal(median,factor)",
        ],
    );
    fails(
        &with(&["--scatter", "switch.impact_energy=lognormal(0.5,1.2)"]),
        2,
        &["--scatter", "switch.impact_energy"],
    );
    fails(
        &with(&["--scatter", SPRING, "--shard", "1/2"]),
        2,
        &["--shard", "--out"],
    );
    fails(
        &with(&["--scatter", SPRING, "--target-halfwidth", "0.7"]),
        2,
        &["--target-halfwidth"],
    );
    fails(
        &with(&[
            "--scatter",
            SPRING,
            "--correlate",
            "switch.k_s,contact.z0=0.2",
        ]),
        2,
        &["--correlate", "contact.z0 is not a scattered field"],
    );
}
