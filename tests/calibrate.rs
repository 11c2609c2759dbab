//! `stiction calibrate` end to end: finite-element-like curves of the paper's Ru asperity
//! made by the model itself with other constants (the crate's synthesizer), fitted through
//! the command line from the paper's constants.

mod common;
use asperity_plastic::{EffectiveRadiusFit, EtsionKadin, YieldModulus};
use calibrate::{Calibrator, FeData, SynthSpec};
use common::{has_null, json, scene_with, stiction, temp_dir};
use contact_core::{paper, Material, Pair};
use maugis_kim::{DugdaleParams, MaugisKim};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Held-out constants: neither the paper's nor the docs' worked example.
const TRUTH_C1: [f64; 3] = [0.27, 0.56, 0.105];
const TRUTH_C2: [f64; 3] = [7.0, 13.0, 3.5];
const NAMES: [&str; 6] = ["a1", "a2", "a3", "b1", "b2", "b3"];

fn truth_constants() -> EffectiveRadiusFit {
    EffectiveRadiusFit::new(TRUTH_C1, TRUTH_C2).unwrap()
}

/// The model of the paper's Fig 2 scene (the command's default): Ru (Table 1) on a rigid
/// flat, eq 1 as printed, Maugis-Kim with w = 1 J/m^2 and z0 = 0.169 nm.
fn ru() -> Calibrator<MaugisKim> {
    let pair = Pair::new(Material::new(paper::RU).unwrap(), None, paper::RADIUS).unwrap();
    Calibrator::new(
        EtsionKadin::new(&pair, YieldModulus::AsPrinted).unwrap(),
        MaugisKim::new(DugdaleParams::for_pair(
            &pair,
            paper::WORK_OF_ADHESION,
            paper::Z0,
        ))
        .unwrap(),
    )
}

/// Runs at 5, 10, 20 and 40 delta_CP, 25 points per branch (0: no unloading).
fn spec(cal: &Calibrator<MaugisKim>, omegas: &[f64], unloading: usize, noise: f64) -> SynthSpec {
    SynthSpec {
        delta_max: omegas.iter().map(|w| w * cal.delta_cp()).collect(),
        loading_points: 25,
        unloading_points: unloading,
        noise,
        seed: 16,
    }
}

fn write_csv(dir: &Path, name: &str, data: &FeData) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, data.to_csv()).unwrap();
    p
}

fn arr3(v: &Value) -> [f64; 3] {
    let a = v.as_array().expect("an array of three numbers");
    assert_eq!(a.len(), 3, "{v}");
    [0, 1, 2].map(|i| a[i].as_f64().unwrap())
}

/// The six fitted constants of a JSON report, a1 ... b3.
fn constants(v: &Value) -> [f64; 6] {
    let (c1, c2) = (arr3(&v["c1"]), arr3(&v["c2"]));
    [c1[0], c1[1], c1[2], c2[0], c2[1], c2[2]]
}

/// RMS of model - truth on each curve of `clean`, relative to the curve's peak force.
fn relative_rms(cal: &Calibrator<MaugisKim>, fit: EffectiveRadiusFit, clean: &FeData) -> Vec<f64> {
    let model = cal.predict(fit, clean).unwrap();
    clean
        .curves()
        .iter()
        .zip(&model)
        .map(|(c, m)| {
            let ss: f64 = c
                .points
                .iter()
                .zip(m)
                .map(|(p, f)| (f - p.force).powi(2))
                .sum();
            (ss / c.points.len() as f64).sqrt() / c.peak_force()
        })
        .collect()
}

fn fit_of(v: &Value) -> EffectiveRadiusFit {
    EffectiveRadiusFit::new(arr3(&v["c1"]), arr3(&v["c2"])).unwrap()
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).to_string()
}

#[test]
fn noisy_curves_are_refit_within_one_percent_and_the_constants_within_three_standard_errors() {
    let cal = ru();
    let omegas = [5.0, 10.0, 20.0, 40.0];
    let clean = cal
        .synthesize(truth_constants(), &spec(&cal, &omegas, 25, 0.0))
        .unwrap();
    let noisy = cal
        .synthesize(truth_constants(), &spec(&cal, &omegas, 25, 0.005))
        .unwrap();
    // the paper's constants, where the fit starts, miss the truth's curves by up to 3 %
    let start = relative_rms(&cal, EffectiveRadiusFit::PAPER, &clean);
    assert!(start.iter().any(|r| *r > 0.025), "{start:?}");

    let dir = temp_dir("calibrate-noisy");
    let fe = write_csv(&dir, "fe.csv", &noisy);
    let v = json(&stiction(&[
        "calibrate",
        "--fe",
        fe.to_str().unwrap(),
        "--format",
        "json",
    ]));
    for k in [
        "c1",
        "c2",
        "standard_errors",
        "correlation",
        "residual_rms_n",
        "iterations",
        "converged",
        "scene_fragment",
        "yield_modulus",
        "delta_cp_m",
        "curves",
        "not_determined",
        "scene",
        "warnings",
    ] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    assert!(!has_null(&v));
    assert_eq!(v["converged"], true);
    assert_eq!(v["rank"], 6);
    assert_eq!(
        v["warnings"].as_array().unwrap().len(),
        0,
        "{}",
        v["warnings"]
    );
    assert_eq!(v["yield_modulus"], "as_printed");
    assert_eq!(v["scene"]["contact"]["effective_radius"]["c1"][1], 0.6242);
    assert!((v["delta_cp_m"].as_f64().unwrap() - cal.delta_cp()).abs() < 1e-22);
    // every constant within three standard errors of the truth, and not trivially so
    let fitted = constants(&v);
    let truth = [TRUTH_C1, TRUTH_C2].concat();
    for (i, name) in NAMES.iter().enumerate() {
        let group = if i < 3 { "c1" } else { "c2" };
        let se = v["standard_errors"][group][name]
            .as_f64()
            .expect("a standard error");
        assert!(se > 0.0 && se < 0.2 * truth[i].abs(), "{name}: se {se}");
        let z = (fitted[i] - truth[i]) / se;
        assert!(
            z.abs() < 3.0,
            "{name}: {} vs {} ({z:.2} standard errors)",
            fitted[i],
            truth[i]
        );
    }
    let corr = &v["correlation"]["matrix"];
    for i in 0..6 {
        assert!((corr[i][i].as_f64().unwrap() - 1.0).abs() < 1e-12);
    }
    // the refit curves within 1 % RMS of each curve's peak against the noiseless truth
    let refit = relative_rms(&cal, fit_of(&v), &clean);
    assert_eq!(refit.len(), 8);
    for (k, r) in refit.iter().enumerate() {
        assert!(*r < 0.01, "curve {k}: RMS {r:.2e} of its peak");
    }
    // the misfit against the noisy data is the noise: about 0.5 % of each peak
    for c in v["curves"].as_array().unwrap() {
        let r = c["rms_relative"].as_f64().unwrap();
        assert!((0.0025..0.01).contains(&r), "{c}");
    }
}

/// The fragment of the table parses as TOML, equals the JSON's, holds the recovered
/// constants, and pasted into the asperity scene in place of its own is accepted by
/// `stiction asperity`; a fit started from the truth stays there.
#[test]
fn exact_curves_give_the_constants_back_and_the_fragment_works_in_a_scene() {
    let cal = ru();
    let clean = cal
        .synthesize(
            truth_constants(),
            &spec(&cal, &[5.0, 10.0, 20.0, 40.0], 25, 0.0),
        )
        .unwrap();
    let dir = temp_dir("calibrate-exact");
    let fe = write_csv(&dir, "fe.csv", &clean);
    let fe = fe.to_str().unwrap();

    let out = stiction(&["calibrate", "--fe", fe, "--fit", "c1,c2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let table = String::from_utf8(out.stdout).unwrap();
    assert!(table.contains("(converged)"), "{table}");
    assert!(table.contains("rank 6 of 6"), "{table}");
    let at = table
        .find("[contact.effective_radius]")
        .expect("a scene fragment");
    let fragment = &table[at..];
    let parsed: toml::Value = toml::from_str(fragment).expect("the fragment is TOML");
    let er = &parsed["contact"]["effective_radius"];
    let got: Vec<f64> = ["c1", "c2"]
        .iter()
        .flat_map(|k| {
            er[k]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_float().unwrap())
        })
        .collect();
    let truth = [TRUTH_C1, TRUTH_C2].concat();
    for i in 0..6 {
        // exact data: back to the fragment's 8 significant digits
        assert!(
            (got[i] - truth[i]).abs() <= 1e-7 * truth[i].abs(),
            "{}: {}",
            NAMES[i],
            got[i]
        );
    }
    let v = json(&stiction(&["calibrate", "--fe", fe, "--format", "json"]));
    assert_eq!(v["scene_fragment"].as_str().unwrap(), fragment);

    // pasted into the paper's asperity scene in place of its own section
    let scene = String::from_utf8(stiction(&["scene", "--print", "asperity"]).stdout).unwrap();
    let own = scene.find("[contact.effective_radius]").unwrap();
    let pasted = format!("{}{fragment}", &scene[..own]);
    let path = dir.join("fitted.toml");
    std::fs::write(&path, &pasted).unwrap();
    let a = json(&stiction(&[
        "asperity",
        "--scene",
        path.to_str().unwrap(),
        "--format",
        "json",
        "--delta-max",
        "40e-9",
    ]));
    let echoed = &a["scene"]["contact"]["effective_radius"];
    assert_eq!(arr3(&echoed["c1"]).to_vec(), got[..3].to_vec());
    assert_eq!(arr3(&echoed["c2"]).to_vec(), got[3..].to_vec());
    // the asperity command now follows the fitted law: its unloading force at delta_max
    // is the truth's (x = 1 there, R_eff of the loading branch)
    let case = &a["cases"][0];
    let top = case["unloading"][0]["force"].as_f64().unwrap();
    let expected = cal
        .force(
            truth_constants(),
            calibrate::Branch::Unloading,
            40e-9,
            40e-9,
        )
        .unwrap();
    assert!(
        (top - expected).abs() < 1e-6 * expected.abs(),
        "{top} vs {expected}"
    );

    // started from the exact truth, on exact data, the fit does not move
    let exact = scene_with(
        "asperity",
        &[
            ("c1", &format!("c1 = {TRUTH_C1:?}")),
            ("c2", &format!("c2 = {TRUTH_C2:?}")),
        ],
    );
    let path = dir.join("truth.toml");
    std::fs::write(&path, exact).unwrap();
    let v = json(&stiction(&[
        "calibrate",
        "--fe",
        fe,
        "--scene",
        path.to_str().unwrap(),
        "--format",
        "json",
    ]));
    assert_eq!(v["converged"], true);
    assert_eq!(v["iterations"], 0, "stop {}", v["stop"]);
    assert_eq!(constants(&v).to_vec(), truth);
}

#[test]
fn loading_curves_alone_leave_c2_undetermined_with_no_standard_error() {
    let cal = ru();
    let omegas = [5.0, 10.0, 20.0, 40.0];
    let noisy = cal
        .synthesize(truth_constants(), &spec(&cal, &omegas, 0, 0.005))
        .unwrap();
    let dir = temp_dir("calibrate-loading");
    let fe = write_csv(&dir, "loading.csv", &noisy);
    let out = stiction(&[
        "calibrate",
        "--fe",
        fe.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let err = stderr(&out);
    let v = json(&out);
    assert!(!has_null(&v));
    assert_eq!(v["not_determined"], serde_json::json!(["b1", "b2", "b3"]));
    assert_eq!(v["standard_errors"]["c2"], serde_json::json!({}));
    assert_eq!(
        v["correlation"]["names"],
        serde_json::json!(["a1", "a2", "a3"])
    );
    // c2 has no effect on loading: left exactly at the start (the paper's)
    assert_eq!(arr3(&v["c2"]), EffectiveRadiusFit::PAPER.c2);
    // c1 is still recovered
    let c1 = arr3(&v["c1"]);
    for i in 0..3 {
        let se = v["standard_errors"]["c1"][NAMES[i]].as_f64().unwrap();
        assert!(
            ((c1[i] - TRUTH_C1[i]) / se).abs() < 3.0,
            "{}: {} ± {se}",
            NAMES[i],
            c1[i]
        );
    }
    let codes: Vec<&str> = v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["code"].as_str().unwrap())
        .collect();
    assert_eq!(codes, ["not_determined"]);
    assert!(
        err.contains("warning[not_determined]") && err.contains("b1, b2, b3"),
        "{err}"
    );
    let table =
        String::from_utf8(stiction(&["calibrate", "--fe", fe.to_str().unwrap()]).stdout).unwrap();
    for b in ["b1", "b2", "b3"] {
        let line = table.lines().find(|l| l.starts_with(b)).unwrap();
        assert!(line.ends_with("not determined by the data"), "{line}");
        assert!(!line.contains('±'), "{line}");
    }
}

/// One delta_max: the loading branch still separates a1, a2, a3, but the unloading branch
/// sees c2 at one omega only. The report says so and suggests a subset that the data do
/// determine; fitting that subset is fully determined.
#[test]
fn one_delta_max_reports_what_it_cannot_separate_and_the_suggested_subset_fits() {
    let cal = ru();
    let noisy = cal
        .synthesize(truth_constants(), &spec(&cal, &[20.0], 25, 0.005))
        .unwrap();
    let dir = temp_dir("calibrate-one");
    let fe = write_csv(&dir, "one.csv", &noisy);
    let fe = fe.to_str().unwrap();
    let v = json(&stiction(&["calibrate", "--fe", fe, "--format", "json"]));
    assert_eq!(v["rank"], 4);
    assert_eq!(v["not_determined"], serde_json::json!(["b1", "b2", "b3"]));
    assert_eq!(v["undetermined_directions"].as_array().unwrap().len(), 2);
    let suggested: Vec<&str> = v["suggested_fit"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    assert_eq!(suggested.len(), 4);
    // what the data do fix: c2 at omega = 20, the truth's within the noise
    let c2 = arr3(&v["c2"]);
    let at20 = |b: [f64; 3]| b[0] / (1.0 + (20.0 / b[1]).powi(2)) - b[2];
    assert!(
        (at20(c2) - at20(TRUTH_C2)).abs() < 0.3,
        "{} vs {}",
        at20(c2),
        at20(TRUTH_C2)
    );
    let v = json(&stiction(&[
        "calibrate",
        "--fe",
        fe,
        "--format",
        "json",
        "--fit",
        &suggested.join(","),
    ]));
    assert_eq!(v["rank"], 4);
    assert_eq!(v["not_determined"], serde_json::json!([]));
    assert_eq!(v["converged"], true);
    let n_se = v["standard_errors"]["c1"].as_object().unwrap().len()
        + v["standard_errors"]["c2"].as_object().unwrap().len();
    assert_eq!(n_se, 4);
}

#[test]
fn bad_data_exit_2_naming_the_file_line_and_column() {
    let dir = temp_dir("calibrate-bad");
    let head = "delta_max_m,delta_m,force_n,branch\n";
    let ok = "2e-8,1e-8,1e-3,loading\n2e-8,2e-8,3e-3,loading\n";
    let cases: [(&str, String, &[&str]); 6] = [
        (
            "non-numeric",
            format!("{head}2e-8,1e-8,1e-3,loading\n2e-8,2e-8,1.2e-3N,loading\n"),
            &["line 3", "column force_n", "not a number", "1.2e-3N"],
        ),
        (
            "missing column",
            format!("delta_max_m,delta_m,force,branch\n{ok}"),
            &["line 1", "column force_n", "missing"],
        ),
        (
            "above delta_max",
            format!("# FE export\n{head}{ok}2e-8,2.1e-8,3.1e-3,loading\n"),
            &["line 5", "column delta_m", "above"],
        ),
        (
            "unknown branch",
            format!("{head}{ok}2e-8,2e-8,3e-3,unload\n"),
            &["line 4", "column branch", "unload"],
        ),
        (
            "short row",
            format!("{head}{ok}2e-8,2e-8\n"),
            &["line 4", "column force_n"],
        ),
        (
            "fewer points than constants",
            format!("{head}{ok}"),
            &["line 3", "2 points", "6 constants"],
        ),
    ];
    for (what, text, needles) in cases {
        let p = dir.join(format!("{}.csv", what.replace(' ', "_")));
        std::fs::write(&p, text).unwrap();
        let out = stiction(&["calibrate", "--fe", p.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{what}: {}", stderr(&out));
        assert!(out.stdout.is_empty(), "{what}");
        let err = stderr(&out);
        assert!(err.contains(p.to_str().unwrap()), "{what}: {err}");
        for n in needles {
            assert!(err.contains(n), "{what}: lacks {n:?}: {err}");
        }
    }
    let out = stiction(&[
        "calibrate",
        "--fe",
        dir.join("absent.csv").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("absent.csv"));
    // an unknown constant, and a scene whose asperity has no constants to fit
    let p = dir.join("ok.csv");
    std::fs::write(&p, format!("{head}{ok}{ok}{ok}")).unwrap();
    let out = stiction(&["calibrate", "--fe", p.to_str().unwrap(), "--fit", "c1,a4"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("a4"));
    let elastic = dir.join("elastic.toml");
    std::fs::write(
        &elastic,
        scene_with(
            "asperity",
            &[("plasticity_law", "plasticity_law = \"elastic\"")],
        ),
    )
    .unwrap();
    let out = stiction(&[
        "calibrate",
        "--fe",
        p.to_str().unwrap(),
        "--scene",
        elastic.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("etsion_kadin"), "{}", stderr(&out));
}

/// `--plot` draws data and fit per delta_max; `--format csv` gives the data with the
/// fitted model's force, which reads back as finite-element data (the extra column
/// ignored, with a warning) and fits to the same constants.
#[test]
fn plot_and_csv_outputs() {
    let cal = ru();
    let noisy = cal
        .synthesize(
            truth_constants(),
            &spec(&cal, &[5.0, 15.0, 40.0], 20, 0.005),
        )
        .unwrap();
    let dir = temp_dir("calibrate-plot");
    let fe = write_csv(&dir, "fe.csv", &noisy);
    let svg = dir.join("overlay.svg");
    let out = stiction(&[
        "calibrate",
        "--fe",
        fe.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
        "--format",
        "csv",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
    assert_eq!(
        text.matches("delta_max = ").count(),
        3,
        "one panel per delta_max"
    );
    for label in [
        "FE loading",
        "fit loading",
        "FE unloading",
        "fit unloading",
        "force [uN]",
        "[nm]",
    ] {
        assert!(text.contains(label), "{label}");
    }
    let csv = String::from_utf8(out.stdout).unwrap();
    assert!(csv.starts_with("delta_max_m,delta_m,force_n,branch,model_force_n\n"));
    assert_eq!(csv.lines().count(), 1 + noisy.len());
    let again = dir.join("again.csv");
    std::fs::write(&again, &csv).unwrap();
    let a = json(&stiction(&[
        "calibrate",
        "--fe",
        fe.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let b = json(&stiction(&[
        "calibrate",
        "--fe",
        again.to_str().unwrap(),
        "--format",
        "json",
    ]));
    assert_eq!(constants(&a), constants(&b));
    assert_eq!(b["ignored_columns"], serde_json::json!(["model_force_n"]));
    assert_eq!(b["warnings"][0]["code"], "fe_columns_ignored");
}
