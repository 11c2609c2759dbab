//! The report as JSON (no null, no NaN), as a table, and the overlay data.

mod common;

use asperity_plastic::{EffectiveRadiusFit, YieldModulus};
use calibrate::{Branch, FitOptions};
use common::*;

#[test]
fn json_has_the_documented_shape_and_no_null() {
    let cal = ru(YieldModulus::AsPrinted);
    for (omegas, n_unload) in [(&OMEGAS[..], 20), (&[20.0][..], 20), (&OMEGAS[..], 0)] {
        let data = cal
            .synthesize(truth(), &spec(&cal, omegas, 20, n_unload, 0.005, 9))
            .unwrap();
        let rep = cal.fit(&data, &FitOptions::default()).unwrap();
        let json = serde_json::to_string(&rep).unwrap();
        assert!(!json.contains("null") && !json.contains("NaN"), "{json}");
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        for key in [
            "c1",
            "c2",
            "standard_errors",
            "correlation",
            "residual_rms_n",
            "iterations",
            "converged",
            "rank",
            "not_determined",
            "curves",
            "scene_fragment",
            "yield_modulus",
        ] {
            assert!(v.get(key).is_some(), "missing {key}");
        }
        assert_eq!(v["c1"].as_array().unwrap().len(), 3);
        assert_eq!(v["yield_modulus"], "as_printed");
        let se = &v["standard_errors"];
        // keyed by constant name; absent (undetermined) constants are omitted
        for name in rep.not_determined.iter().map(|c| c.name()) {
            assert!(se["c2"].get(name).is_none() && se["c1"].get(name).is_none());
        }
        if rep.not_determined.is_empty() {
            assert!(
                se["c1"]["a1"].as_f64().unwrap() > 0.0 && se["c2"]["b3"].as_f64().unwrap() > 0.0
            );
        }
        assert_eq!(v["curves"][0]["branch"], "loading");
        assert!(v["curves"][0]["rms_relative"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn table_and_scene_fragment() {
    let cal = ru(YieldModulus::Composite);
    let data = cal
        .synthesize(truth(), &spec(&cal, &OMEGAS, 20, 20, 0.0, 1))
        .unwrap();
    let rep = cal.fit(&data, &FitOptions::default()).unwrap();
    let table = rep.to_table();
    for needle in [
        "yield modulus composite",
        "a1",
        "b3",
        "± ",
        "converged",
        "rank 6 of 6",
        "RMS/peak",
    ] {
        assert!(table.contains(needle), "{needle}: {table}");
    }
    assert!(table.ends_with(&rep.scene_fragment));
    assert_eq!(
        rep.scene_fragment,
        "[contact.effective_radius]\nc1 = [0.3, 0.5, 0.12]\nc2 = [8.0, 12.0, 4.0]\n"
    );
    assert_eq!(table.lines().filter(|l| l.contains("loading")).count(), 8);
}

#[test]
fn overlay_covers_each_curve_with_the_model() {
    let cal = ru(YieldModulus::AsPrinted);
    let data = cal
        .synthesize(truth(), &spec(&cal, &[10.0, 30.0], 15, 15, 0.0, 1))
        .unwrap();
    let ov = cal.overlay(truth(), &data, 50).unwrap();
    assert_eq!(ov.len(), 4);
    for (o, c) in ov.iter().zip(data.curves()) {
        assert_eq!(
            (o.delta_max_m, o.branch, o.data.len(), o.model.len()),
            (c.delta_max, c.branch, 15, 50)
        );
        // the grid starts at delta_max on unloading, ends there on loading
        let at_max = match o.branch {
            Branch::Loading => o.model[49],
            Branch::Unloading => o.model[0],
        };
        assert_eq!(at_max[0], c.delta_max);
        // model equals the data (made by the same model) where they meet
        let f = cal
            .force(truth(), c.branch, c.delta_max, c.delta_max)
            .unwrap();
        assert_eq!(at_max[1], f);
    }
    // the paper's constants differ visibly on the unloading branch at 30 delta_CP
    let paper = cal.overlay(EffectiveRadiusFit::PAPER, &data, 50).unwrap();
    let diff = paper[3]
        .model
        .iter()
        .zip(&ov[3].model)
        .map(|(a, b)| (a[1] - b[1]).abs())
        .fold(0.0, f64::max);
    assert!(diff > 0.01 * data.curves()[3].peak_force());
}
