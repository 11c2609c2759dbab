//! A second requirement (`--require contact_resistance<LIMIT`): the window of a threshold
//! search against the analytic answer, and the map's marks through JSON, merge and refusal.

mod common;

use design_sweep::{
    merge, run_map, threshold_with, DesignPoint, Grid, Level, Map, MapRequest, PointError,
    Requirement, Shard, ThresholdOptions,
};
use serde_json::json;

/// ratio = (3e3/x)^2 (free above 3e3), contact resistance 1e-4 x ohm (below 1 ohm below
/// x = 1e4), closes everywhere.
fn point(x: f64) -> Result<DesignPoint, PointError> {
    let mut p = common::point((3e3 / x).powi(2), x);
    p.contact_resistance = Some(1e-4 * x);
    p.real_contact_fraction = Some(0.01);
    Ok(p)
}

#[test]
fn the_window_lies_between_the_two_crossings() {
    // free above 3e3, resistance below 1 ohm below 1e4: the window is [3e3, 1e4]
    let r = Requirement::parse("contact_resistance<1").unwrap();
    let t = threshold_with(
        "switch.k_s",
        1e2,
        1e6,
        point,
        &ThresholdOptions::default(),
        Some(&r),
    )
    .unwrap();
    assert!((t.critical_value.unwrap() / 3e3 - 1.0).abs() < 1e-6);
    let req = t.requirement.unwrap();
    assert_eq!(req.crossings.len(), 1);
    assert!(
        (req.crossings[0].value / 1e4 - 1.0).abs() < 1e-6,
        "{:?}",
        req.crossings
    );
    assert_eq!(req.crossings[0].met_side.word(), "below");
    assert_eq!(req.window.len(), 1);
    assert!((req.window[0][0] / 3e3 - 1.0).abs() < 1e-6);
    assert!((req.window[0][1] / 1e4 - 1.0).abs() < 1e-6);
    // a limit nowhere met: no window; everywhere met: the free side
    let none = Requirement::parse("contact_resistance<1e-3").unwrap();
    let t = threshold_with(
        "switch.k_s",
        1e2,
        1e6,
        point,
        &ThresholdOptions::default(),
        Some(&none),
    )
    .unwrap();
    assert!(t.requirement.unwrap().window.is_empty());
    let all = Requirement::parse("contact_resistance<1e3").unwrap();
    let t = threshold_with(
        "switch.k_s",
        1e2,
        1e6,
        point,
        &ThresholdOptions::default(),
        Some(&all),
    )
    .unwrap();
    let w = t.requirement.unwrap().window;
    assert_eq!(w.len(), 1);
    assert!((w[0][0] / 3e3 - 1.0).abs() < 1e-6 && w[0][1] == 1e6);
}

fn map(shard: Option<Shard>) -> Map {
    let request = MapRequest {
        scene: json!({"name": "req"}),
        grid: Grid::parse(&["switch.k_s=1e3:1e5:log:9"]).unwrap(),
        accuracy: "fast".into(),
        shard,
    };
    run_map(
        request,
        |v: &[(&str, Level)]| point(v[0].1.number().unwrap()),
        |_, _| {},
    )
    .with_requirement(Some(Requirement::parse("contact_resistance<1").unwrap()))
}

#[test]
fn map_marks_survive_json_and_merge_and_lies_are_refused() {
    let m = map(None);
    // 1e3 .. 1e5 in quarter decades: free above 3e3, below 1 ohm below 1e4
    let inside: Vec<f64> = m.window().iter().map(|p| p.values[0]).collect();
    assert_eq!(inside.len(), 2, "{inside:?}");
    assert!(inside.iter().all(|&x| x > 3e3 && x < 1e4));
    assert_eq!(m.summary().in_window, Some(2));
    let text = m.to_json();
    assert!(text.contains("\"requirement\": \"contact_resistance<1e0\""));
    assert_eq!(text.matches("\"in_window\": true").count(), 2);
    let back = Map::from_json(&text).unwrap();
    assert_eq!(back, m);
    // merged parts keep it, and parts with different requirements are refused
    let parts = (1..=3).map(|k| (format!("part {k}"), map(Some(Shard::new(k, 3).unwrap()))));
    assert_eq!(merge(parts).unwrap().to_json(), text);
    let mut parts: Vec<(String, Map)> = (1..=2)
        .map(|k| (format!("part {k}"), map(Some(Shard::new(k, 2).unwrap()))))
        .collect();
    parts[1].1 = parts[1].1.clone().with_requirement(None);
    let e = merge(parts).unwrap_err().to_string();
    assert!(e.contains("requirement"), "{e}");
    // a point marked in the window that is not is refused
    let lie = text.replacen("\"in_window\": false", "\"in_window\": true", 1);
    let e = Map::from_json(&lie).unwrap_err().to_string();
    assert!(e.contains("in_window"), "{e}");
}
