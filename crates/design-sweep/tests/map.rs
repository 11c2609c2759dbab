//! Maps: sharding and merging byte for byte, thread-count independence, statuses, CSV, JSON.

mod common;

use common::maps::{request, run, scene, GRID_2D};
use common::{power, product};
use design_sweep::{merge, run_map, DesignError, Level, Map, Shard};
use serde_json::{json, Value};

/// The map as data (its CSV and plot are the presentation crate's, drawn from these
/// points: `stiction-report`'s tests compare those files byte for byte).
fn files(m: &Map) -> String {
    m.to_json()
}

/// Shards as the CLI would have them: written as JSON and read back.
fn shards(specs: &[&str], n: usize) -> Vec<(String, Map)> {
    (1..=n)
        .map(|k| {
            let m = run(specs, Some(Shard::new(k, n).unwrap()));
            let back = Map::from_json(&m.to_json()).unwrap();
            assert_eq!(back, m, "JSON round trip of shard {k}/{n}");
            (format!("maps/part-{k}"), back)
        })
        .collect()
}

#[test]
fn merged_shards_equal_the_whole_map_byte_for_byte() {
    for specs in [&GRID_2D[..], &["switch.k_s=1e2:1e5:log:17"][..]] {
        let whole = files(&run(specs, None));
        for n in [2, 3] {
            let mut parts = shards(specs, n);
            parts.reverse(); // order of the directories does not matter
            let merged = merge(parts).unwrap();
            assert_eq!(merged.shard(), None);
            let m = files(&merged);
            assert_eq!(m, whole, "map.json, {n} shards");
        }
    }
}

#[test]
fn shard_info_appears_only_in_shards() {
    let s = run(&GRID_2D, Some(Shard::new(2, 3).unwrap())).to_json();
    let v: Value = serde_json::from_str(&s).unwrap();
    assert_eq!(v["shard"], json!({"k": 2, "n": 3}));
    let whole: Value = serde_json::from_str(&run(&GRID_2D, None).to_json()).unwrap();
    assert!(whole.get("shard").is_none());
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let in_pool = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| files(&run(&GRID_2D, None)))
    };
    let one = in_pool(1);
    let two = in_pool(2);
    assert_eq!(one, two);
}

#[test]
fn json_names_the_grid_and_scene() {
    let map = run(&GRID_2D, None);
    let v: Value = serde_json::from_str(&map.to_json()).unwrap();
    assert_eq!(v["accuracy"], "balanced");
    assert_eq!(v["scene"], scene());
    let a = &v["grid"]["axes"][0];
    assert_eq!(a["field"], "switch.k_s");
    assert_eq!(a["spacing"], "log");
    assert_eq!(a["n"], 13);
    assert_eq!(a["values"].as_array().unwrap().len(), 13);
    let p = &v["points"][8];
    assert_eq!(p["index"], 8);
    assert_eq!(
        p["values"]["switch.k_s"].as_f64(),
        Some(map.grid().values(8)[0])
    );
    assert_eq!(p["status"], "ok");
    assert!(p.get("detail").is_none());
    assert_eq!(Map::from_json(&map.to_json()).unwrap(), map);
}

fn merge_err(parts: Vec<(String, Map)>) -> String {
    match merge(parts) {
        Err(e @ DesignError::Merge { .. }) => e.to_string(),
        other => panic!("expected a merge error, got {other:?}"),
    }
}

#[test]
fn merge_refuses_mismatched_missing_or_duplicate_shards() {
    let specs = &GRID_2D[..];
    // missing part
    let mut parts = shards(specs, 3);
    parts.remove(1);
    let e = merge_err(parts);
    assert!(e.contains("missing part(s) 2/3"), "{e}");

    // duplicate part
    let mut parts = shards(specs, 3);
    let dup = ("maps/copy".to_string(), parts[0].1.clone());
    parts.push(dup);
    let e = merge_err(parts);
    assert!(
        e.contains("maps/copy") && e.contains("also in maps/part-1"),
        "{e}"
    );

    // different scene
    let mut parts = shards(specs, 2);
    let mut r = request(specs, Some(Shard::new(2, 2).unwrap()));
    r.scene["switch"]["d0"] = json!(3e-6);
    parts[1].1 = run_map(r, product, |_, _| {});
    let e = merge_err(parts);
    assert!(e.contains("maps/part-2") && e.contains("/switch/d0"), "{e}");

    // different grid
    let mut parts = shards(specs, 2);
    let other = [
        "switch.k_s=3e2:3e4:log:13",
        "surface.sigma_s=1e-9:9e-9:lin:8",
    ];
    parts[1].1 = run(&other, Some(Shard::new(2, 2).unwrap()));
    let e = merge_err(parts);
    assert!(e.contains("maps/part-2") && e.contains("grid"), "{e}");

    // different accuracy
    let mut parts = shards(specs, 2);
    let mut r = request(specs, Some(Shard::new(2, 2).unwrap()));
    r.accuracy = "fast".into();
    parts[1].1 = run_map(r, product, |_, _| {});
    let e = merge_err(parts);
    assert!(e.contains("accuracy `fast`"), "{e}");

    // inconsistent N
    let mut parts = shards(specs, 2);
    parts[1].1 = run(specs, Some(Shard::new(2, 3).unwrap()));
    let e = merge_err(parts);
    assert!(e.contains("maps/part-2") && e.contains("2/3"), "{e}");

    // an unsharded map
    let e = merge_err(vec![("maps/all".into(), run(specs, None))]);
    assert!(e.contains("maps/all") && e.contains("unsharded"), "{e}");

    // a huge N is reported, not enumerated
    let big = run(specs, Some(Shard::new(1, 1_000_000_000_000).unwrap()));
    let e = merge_err(vec![("maps/big".into(), big)]);
    assert!(
        e.contains("missing part(s) 2/1000000000000, ") && e.contains("and 999999999979 more"),
        "{e}"
    );

    // nothing
    assert!(merge(Vec::new()).is_err());
}

#[test]
fn from_json_refuses_altered_maps() {
    let m = run(&GRID_2D, Some(Shard::new(1, 2).unwrap()));
    let mut v: Value = serde_json::from_str(&m.to_json()).unwrap();
    v["points"][0]["index"] = json!(1); // belongs to shard 2/2
    let e = Map::from_json(&v.to_string()).unwrap_err().to_string();
    assert!(e.contains("does not belong to shard 1/2"), "{e}");
    let e = Map::from_json("{\"format\": \"other\"}").unwrap_err();
    assert!(matches!(e, DesignError::MapJson(_)));
}

#[test]
fn power_law_evaluator_is_usable_as_a_map_evaluator() {
    let f = power(1e3, 2.0);
    let m = run_map(
        request(&["switch.k_s=1e2:1e4:log:9"], None),
        |v: &[(&str, Level)]| f(common::num(v, 0)),
        |_, _| {},
    );
    let b = m.boundary_1d();
    assert_eq!(b.len(), 1);
    // log-ratio is linear in log x: interpolation is exact
    assert!((b[0].value / 1e3 - 1.0).abs() < 1e-12, "{}", b[0].value);
}
