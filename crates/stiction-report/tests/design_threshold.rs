//! Threshold searches on analytic ratios with known critical values.

mod common;

use common::{point, power};
use design_sweep::{
    threshold, CrossingKind, DesignPoint, FreeSide, Labels, PointError, ThresholdOptions,
};
use serde_json::Value;
use std::sync::atomic::{AtomicUsize, Ordering};
use stiction_report::design_table::threshold_table;

fn opts(tolerance: f64) -> ThresholdOptions {
    ThresholdOptions {
        tolerance,
        ratio_rel_error: 1e-6,
        scan_points: None,
    }
}

#[test]
fn no_crossing_is_an_answer_not_an_error() {
    let t = threshold("switch.k_s", 1e4, 1e6, power(3e3, 2.0), &opts(1e-6)).unwrap();
    assert!(t.crossings.is_empty());
    assert_eq!(t.critical_value, None);
    assert_eq!(t.free_side, FreeSide::WholeRange);
    assert_eq!(t.evaluations, t.scan.len());
    let v: Value = serde_json::from_str(&t.to_json()).unwrap();
    assert_eq!(v["free_side"], "whole_range");
    // no crossing: critical_value is null (a public contract), and no closure boundary
    assert!(v["critical_value"].is_null() && v["closure_boundary"].is_null());
    assert!(v["ratio_at_from"].as_f64().unwrap() < 1.0);
    let t = threshold("switch.k_s", 10.0, 100.0, power(3e3, 2.0), &opts(1e-6)).unwrap();
    assert_eq!(t.free_side, FreeSide::Nowhere);
    assert!(
        threshold_table(&t, &Labels::new()).contains("sticks (ratio >= 1) over the whole range")
    );
}

#[test]
fn reports_two_crossings() {
    // a valley: ratio = 0.25 (ln x - ln 1e3)^2 + 0.5 in decades; crosses 1 at 1e3 * 10^(+-sqrt 2)
    let f = |x: f64| -> Result<DesignPoint, PointError> {
        let d = (x / 1e3).log10();
        Ok(point(0.25 * d * d + 0.5, 1.0))
    };
    let t = threshold("switch.k_s", 1.0, 1e6, f, &opts(1e-8)).unwrap();
    assert_eq!(t.crossings.len(), 2);
    let r2 = 2f64.sqrt();
    let want = [1e3 * 10f64.powf(-r2), 1e3 * 10f64.powf(r2)];
    for (c, w) in t.crossings.iter().zip(want) {
        assert!(
            (c.critical_value / w - 1.0).abs() < 1e-8,
            "{} vs {w}",
            c.critical_value
        );
    }
    assert_eq!(t.crossings[0].free_side, FreeSide::Above);
    assert_eq!(t.crossings[1].free_side, FreeSide::Below);
    assert_eq!(t.critical_value, Some(t.crossings[0].critical_value));
    let v: Value = serde_json::from_str(&t.to_json()).unwrap();
    for key in [
        "parameter",
        "critical_value",
        "free_side",
        "ratio_at_from",
        "ratio_at_to",
        "evaluations",
        "uncertainty",
        "kind",
        "crossings",
    ] {
        assert!(v.get(key).is_some(), "{key}");
    }
    assert_eq!(v["crossings"].as_array().unwrap().len(), 2);
    // the one null: no closure boundary (the switch closes everywhere)
    assert_eq!(t.to_json().matches("null").count(), 1);
    assert!(v["closure_boundary"].is_null());
    let table = threshold_table(&t, &Labels::new().with_unit("switch.k_s", "Pa/m"));
    assert!(
        table.contains("crossings (2)") && table.contains("Pa/m"),
        "{table}"
    );
}

#[test]
fn where_the_switch_stops_closing_is_a_closure_boundary_never_a_free_side() {
    // below 2.5e3 the switch closes and sticks with ratio 1.8; above it does not close: no
    // closing design is free, and the boundary is where it stops closing (issue 22)
    let f = |x: f64| -> Result<DesignPoint, PointError> {
        if x > 2.5e3 {
            Ok(DesignPoint::does_not_close(x))
        } else {
            Ok(point(1.8, x))
        }
    };
    let t = threshold("switch.voltage", 1e3, 1e4, f, &opts(1e-6)).unwrap();
    assert!(t.crossings.is_empty(), "{:?}", t.crossings);
    assert_eq!(t.critical_value, None);
    assert_eq!(t.free_side, FreeSide::Nowhere);
    assert_eq!(t.closure_boundaries.len(), 1);
    let b = &t.closure_boundaries[0];
    assert_eq!(b.closes_side, FreeSide::Below);
    assert_eq!(t.closure_boundary, Some(b.value));
    assert!(b.bracket[0] <= 2.5e3 && 2.5e3 <= b.bracket[1]);
    assert!(
        (b.bracket[1] / b.bracket[0] - 1.0) <= 1.01e-6,
        "{:?}",
        b.bracket
    );
    assert!((b.value - 2.5e3).abs() <= b.uncertainty);
    // bisection from a 1/8-decade scan bracket to 1e-6 in ln: about 18 halvings
    assert!(b.evaluations <= 22, "{}", b.evaluations);
    let v: Value = serde_json::from_str(&t.to_json()).unwrap();
    assert!(v["critical_value"].is_null());
    assert!((v["closure_boundary"].as_f64().unwrap() - 2.5e3).abs() <= b.uncertainty);
    let table = threshold_table(&t, &Labels::new());
    assert!(
        table.contains("no closing design is free") && table.contains("stops closing"),
        "{table}"
    );

    // free where it closes: ratio 0.5 below, does not close above
    let h = |x: f64| -> Result<DesignPoint, PointError> {
        if x > 2.5e3 {
            Ok(DesignPoint::does_not_close(x))
        } else {
            Ok(point(0.5, x))
        }
    };
    let t = threshold("switch.voltage", 1e3, 1e4, h, &opts(1e-6)).unwrap();
    assert_eq!(t.free_side, FreeSide::WhereItCloses);
    assert_eq!(t.critical_value, None);
    assert!(t.closure_boundary.is_some());

    // a finite jump (0.5 -> 2) is a jump too, found to the tolerance
    let g = |x: f64| -> Result<DesignPoint, PointError> {
        Ok(point(if x < 0.61 { 0.5 } else { 2.0 }, 1.0))
    };
    let t = threshold("surface.w", 0.0, 1.0, g, &opts(1e-6)).unwrap();
    let c = &t.crossings[0];
    assert_eq!(c.kind, CrossingKind::Jump);
    assert_eq!(c.free_side, FreeSide::Below);
    assert!(
        (c.critical_value - 0.61).abs() <= 1e-6,
        "{}",
        c.critical_value
    );
    assert!(c.evaluations <= 40, "{}", c.evaluations);
}

#[test]
fn failing_scan_points_are_reported_and_the_scan_goes_on() {
    let calls = AtomicUsize::new(0);
    let f = |x: f64| -> Result<DesignPoint, PointError> {
        calls.fetch_add(1, Ordering::Relaxed);
        // scan points are 10^(1 + 5i/16): 86.6 fails, 4.87e5 and 1e6 are out of domain
        if x > 4e5 {
            Err(PointError::OutOfDomain(format!("k_s = {x} too stiff")))
        } else if (80.0..100.0).contains(&x) {
            Err(PointError::Failed("no convergence".into()))
        } else {
            power(3e3, 2.0)(x)
        }
    };
    let t = threshold("switch.k_s", 1e1, 1e6, f, &opts(1e-6)).unwrap();
    assert_eq!(calls.load(Ordering::Relaxed), t.evaluations);
    assert!((t.critical_value.unwrap() / 3e3 - 1.0).abs() < 1e-6);
    let failed: Vec<_> = t.failed_points().collect();
    assert_eq!(t.scan.len(), 17);
    assert_eq!(failed.len(), 3, "{failed:?}");
    assert!(failed.iter().any(|p| p.status == "failed"));
    assert!(failed.iter().any(|p| p.status == "out_of_domain"));
    assert_eq!(t.ratio_at_to, None);
    let json = t.to_json();
    // the one null: no closure boundary
    assert!(json.contains("too stiff") && json.matches("null").count() == 1);
    assert!(threshold_table(&t, &Labels::new()).contains("failed scan points (3)"));
}
