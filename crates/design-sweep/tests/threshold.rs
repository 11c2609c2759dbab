//! Threshold searches on analytic ratios with known critical values.

mod common;

use common::{point, power};
use design_sweep::{
    threshold, CrossingKind, DesignError, DesignPoint, FreeSide, PointError, Spacing,
    ThresholdOptions,
};

fn opts(tolerance: f64) -> ThresholdOptions {
    ThresholdOptions {
        tolerance,
        ratio_rel_error: 1e-6,
        scan_points: None,
    }
}

#[test]
fn finds_a_power_law_threshold_on_a_log_range() {
    for (p, tol) in [(1.0, 1e-6), (2.5, 1e-8), (0.3, 1e-4)] {
        let t = threshold("switch.k_s", 1e1, 1e6, power(3.3e3, p), &opts(tol)).unwrap();
        assert_eq!(t.spacing, Spacing::Log);
        assert_eq!(t.crossings.len(), 1);
        let c = t.critical_value.unwrap();
        assert!((c / 3.3e3 - 1.0).abs() <= tol, "p = {p}: {c} (tol {tol})");
        assert_eq!(t.free_side, FreeSide::Above);
        assert_eq!(t.kind, Some(CrossingKind::Continuous));
        // the slope of ln ratio in ln value is -p
        let s = t.crossings[0].slope.unwrap();
        assert!((s + p).abs() < 1e-3 * p, "slope {s}");
        // uncertainty = eps/|slope| x + tol x
        let u = t.uncertainty.unwrap();
        let want = 1e-6 / p * c + tol * c;
        assert!((u / want - 1.0).abs() < 1e-3, "{u} vs {want}");
        assert!(t.ratio_at_from.unwrap() > 1.0 && t.ratio_at_to.unwrap() < 1.0);
        assert!(t.evaluations > t.scan.len() && t.evaluations < t.scan.len() + 40);
    }
}

#[test]
fn finds_a_threshold_on_a_lin_range_and_the_free_side_below() {
    // ratio = x / 0.37 rises with x: free below 0.37
    let f = |x: f64| -> Result<DesignPoint, PointError> { Ok(point(x / 0.37, 1.0)) };
    let t = threshold("surface.sigma_s", 0.1, 0.9, f, &opts(1e-7)).unwrap();
    assert_eq!(t.spacing, Spacing::Lin);
    let c = t.critical_value.unwrap();
    assert!((c / 0.37 - 1.0).abs() <= 1e-7, "{c}");
    assert_eq!(t.free_side, FreeSide::Below);
    // from > to: the same answer, end ratios swapped
    let r = threshold("surface.sigma_s", 0.9, 0.1, f, &opts(1e-7)).unwrap();
    assert_eq!(r.critical_value, t.critical_value);
    assert_eq!(r.ratio_at_from, t.ratio_at_to);
    assert_eq!(r.free_side, FreeSide::Below);
}

#[test]
fn a_failure_while_refining_leaves_an_unresolved_crossing() {
    let f = |x: f64| -> Result<DesignPoint, PointError> {
        if (2.9e3..3.2e3).contains(&x) {
            Err("solver diverged".into())
        } else {
            power(3e3, 1.0)(x)
        }
    };
    let t = threshold("switch.k_s", 1e2, 1e5, f, &opts(1e-6)).unwrap();
    let c = &t.crossings[0];
    assert_eq!(c.kind, CrossingKind::Unresolved);
    assert!(c.detail.as_deref().unwrap().contains("solver diverged"));
    assert!(c.bracket[0] <= 3e3 && 3e3 <= c.bracket[1]);
    assert!((c.critical_value - 3e3).abs() <= c.uncertainty);
}

#[test]
fn invalid_input_and_all_failed_scans_are_errors() {
    let f = power(1.0, 1.0);
    let bad = |r: Result<_, DesignError>| r.unwrap_err().to_string();
    assert!(bad(threshold("switch.k_s", 1.0, 1.0, &f, &opts(1e-6)))
        .contains("both ends of the range are 1e0"));
    assert!(bad(threshold("switch.k_s", 1.0, f64::NAN, &f, &opts(1e-6))).contains("finite"));
    assert!(bad(threshold("switch.k_s", 1.0, 2.0, &f, &opts(0.0))).contains("tolerance"));
    assert!(bad(threshold("k_s", 1.0, 2.0, &f, &opts(1e-6))).contains("section.key"));
    let fail = |_x: f64| -> Result<DesignPoint, PointError> { Err("always".into()) };
    let e = threshold("switch.k_s", 1.0, 2.0, fail, &opts(1e-6)).unwrap_err();
    assert!(
        matches!(e, DesignError::ScanFailed { points: 9, .. }),
        "{e}"
    );
}

#[test]
fn threshold_does_not_depend_on_the_thread_count() {
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| threshold("switch.k_s", 1e1, 1e6, power(3.3e3, 1.7), &opts(1e-9)).unwrap())
    };
    assert_eq!(run(1), run(2));
}

/// The QA case of the tenth stop: the switch sticks far below its closure boundary and is
/// free just below it, in a window with no scan point inside. Scan of 1..100 (log, 9
/// points: ..., 10, 17.8, 31.6, ...): 17.8 sticks (ratio 1.02), 31.6 does not close. The
/// ratio 1 + (18 - x)/10 crosses 1 at 18 and the switch stops closing at 20: free on
/// (18, 20). Before the fix the threshold refined only the closure boundary and said that
/// no closing design is free.
#[test]
fn a_free_window_between_a_crossing_and_the_closure_boundary_is_found_without_a_scan_point_in_it() {
    let f = |x: f64| -> Result<DesignPoint, PointError> {
        if x > 20.0 {
            Ok(DesignPoint::does_not_close(1.0))
        } else {
            Ok(point(1.0 + (18.0 - x) / 10.0, 1.0))
        }
    };
    for (from, to) in [(1.0, 100.0), (100.0, 1.0)] {
        let t = threshold("switch.voltage", from, to, f, &opts(1e-9)).unwrap();
        assert_eq!(t.spacing, Spacing::Log);
        assert!(
            t.scan.iter().all(|p| !(p.value > 18.0 && p.value < 20.0)),
            "the window must hold no scan point for this test to mean anything"
        );
        assert_eq!(t.crossings.len(), 1, "{t:?}");
        let c = t.critical_value.unwrap();
        assert!((c - 18.0).abs() < 1e-6, "{c}");
        assert_eq!(t.free_side, FreeSide::Above);
        assert_eq!(t.kind, Some(CrossingKind::Continuous));
        let b = t.closure_boundary.unwrap();
        assert!((b - 20.0).abs() < 1e-6, "{b}");
        assert_eq!(t.closure_boundaries[0].closes_side, FreeSide::Below);
    }
}
