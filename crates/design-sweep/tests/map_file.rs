//! `map.json` as untrusted input: the values of every point must agree with each other
//! (as a switch run makes them), and `Map::read_path` reads only regular files up to a cap.

mod common;

use common::{flaky, point};
use design_sweep::{
    run_map, DesignError, DesignPoint, Grid, Level, Map, MapRequest, PointError, Shard, Status,
    MAX_MAP_BYTES,
};
use serde_json::{json, Value};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// A shard of a map holding every kind of point: ok and sticking, ok and free,
/// does_not_close, failed and out_of_domain (the `flaky` evaluator).
fn mixed() -> Map {
    let request = MapRequest {
        scene: json!({"name": "mixed"}),
        grid: Grid::parse(&["switch.k_s=100:2000:lin:20"]).unwrap(),
        accuracy: "fast".into(),
        shard: Some(Shard::new(1, 1).unwrap()),
    };
    run_map(request, |v: &[(&str, Level)]| flaky(v), |_, _| {})
}

/// The position in `points` of the first point satisfying `pred`, and its grid index.
fn find(v: &Value, pred: impl Fn(&Value) -> bool) -> (usize, u64) {
    let pts = v["points"].as_array().unwrap();
    let k = pts.iter().position(pred).expect("the map has such a point");
    (k, pts[k]["index"].as_u64().unwrap())
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("design-sweep-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn every_kind_of_point_written_reads_back() {
    let m = mixed();
    let words: Vec<&str> = m.points().iter().map(|p| p.status.word()).collect();
    for w in ["ok", "does_not_close", "failed", "out_of_domain"] {
        assert!(words.contains(&w), "{words:?}");
    }
    assert!(m
        .points()
        .iter()
        .any(|p| p.design.is_some_and(|d| d.sticks)));
    assert!(m
        .points()
        .iter()
        .any(|p| p.design.is_some_and(|d| d.closes && !d.sticks)));
    assert_eq!(Map::from_json(&m.to_json()).unwrap(), m);
}

#[test]
fn from_json_refuses_points_whose_values_contradict_each_other() {
    let text = mixed().to_json();
    let base: Value = serde_json::from_str(&text).unwrap();
    let sticking = |p: &Value| p["status"] == "ok" && p["sticks"] == true;
    let free = |p: &Value| p["status"] == "ok" && p["sticks"] == false;
    let open = |p: &Value| p["status"] == "does_not_close";
    let failed = |p: &Value| p["status"] == "failed";
    type Edit = Box<dyn Fn(&mut Value)>;
    type Which<'a> = &'a dyn Fn(&Value) -> bool;
    let set = |key: &'static str, v: Value| -> Edit { Box::new(move |p| p[key] = v.clone()) };
    let remove = |key: &'static str| -> Edit {
        Box::new(move |p| {
            p.as_object_mut().unwrap().remove(key);
        })
    };
    // (which point, the change, the key the error must name)
    let cases: Vec<(Which, Edit, &str)> = vec![
        (
            &sticking,
            set("pull_out_ratio", json!(-5.0)),
            "pull_out_ratio",
        ),
        (&sticking, set("pull_out_ratio", json!(0.5)), "sticks"),
        (&sticking, set("pull_out_ratio", json!(1.0)), "sticks"),
        (&free, set("sticks", json!(true)), "sticks"),
        (
            &free,
            set("first_sticking_cycle", json!(2)),
            "first_sticking_cycle",
        ),
        (
            &sticking,
            remove("first_sticking_cycle"),
            "first_sticking_cycle",
        ),
        (
            &sticking,
            set("first_sticking_cycle", json!(0)),
            "first_sticking_cycle",
        ),
        (
            &free,
            set("cycles_to_accommodation", json!(0)),
            "cycles_to_accommodation",
        ),
        (
            &free,
            set("largest_pull_out_pa", json!(-1.0)),
            "largest_pull_out_pa",
        ),
        (
            &free,
            set("largest_pull_out_pa", json!(0.0)),
            "largest_pull_out_pa",
        ),
        (
            &free,
            set("restoring_pressure_pa", json!(0.0)),
            "restoring_pressure_pa",
        ),
        (
            &free,
            set("restoring_pressure_pa", json!(-3.0)),
            "restoring_pressure_pa",
        ),
        (&free, set("closes", json!(false)), "closes"),
        (&open, set("closes", json!(true)), "closes"),
        (&open, set("pull_out_ratio", json!(0.5)), "pull_out_ratio"),
        (
            &open,
            set("largest_pull_out_pa", json!(7.0)),
            "largest_pull_out_pa",
        ),
        (&open, set("sticks", json!(true)), "sticks"),
        (
            &open,
            set("cycles_to_accommodation", json!(3)),
            "cycles_to_accommodation",
        ),
        (
            &open,
            set("first_sticking_cycle", json!(1)),
            "first_sticking_cycle",
        ),
        (&free, set("detail", json!("why")), "detail"),
        (&failed, remove("detail"), "detail"),
        (
            &failed,
            set("cycles_to_accommodation", json!(3)),
            "does not match",
        ),
        (
            &free,
            Box::new(|p| p["values"]["switch.d0"] = json!(1e-6)),
            "values.switch.d0",
        ),
    ];
    for (which, edit, key) in cases {
        let mut v = base.clone();
        let (k, index) = find(&v, which);
        edit(&mut v["points"][k]);
        let e = Map::from_json(&v.to_string())
            .expect_err(&format!("accepted {}", v["points"][k]))
            .to_string();
        assert!(
            e.contains(&format!("point {index}:")) && e.contains(key),
            "{key}: {e}"
        );
    }
}

#[test]
fn an_evaluator_answer_that_contradicts_itself_is_a_failed_point() {
    let request = MapRequest {
        scene: json!({}),
        grid: Grid::parse(&["switch.k_s=1:4:lin:4"]).unwrap(),
        accuracy: "fast".into(),
        shard: None,
    };
    let m = run_map(
        request,
        |v: &[(&str, Level)]| -> Result<DesignPoint, PointError> {
            let x = common::num(v, 0);
            let mut p = point(2.0 / x, 1.0);
            if x == 3.0 {
                p.sticks = true; // ratio 2/3 marked as sticking
            }
            Ok(p)
        },
        |_, _| {},
    );
    match &m.points()[2].status {
        Status::Failed(msg) => assert!(msg.contains("sticks"), "{msg}"),
        s => panic!("expected a failed point, got {s:?}"),
    }
    assert_eq!(m.points()[0].status, Status::Ok);
    // what the crate writes, it reads
    assert_eq!(Map::from_json(&m.to_json()).unwrap(), m);
}

#[test]
fn read_path_reads_a_map_and_names_the_file_in_errors() {
    let dir = temp_dir("read");
    let m = mixed();
    let path = dir.join("map.json");
    std::fs::write(&path, m.to_json()).unwrap();
    assert_eq!(Map::read_path(&path).unwrap(), m);

    let missing = dir.join("nowhere").join("map.json");
    let e = Map::read_path(&missing).unwrap_err();
    assert!(matches!(e, DesignError::MapFile { .. }));
    assert!(
        e.to_string().contains(&missing.display().to_string()),
        "{e}"
    );

    let mut v: Value = serde_json::from_str(&m.to_json()).unwrap();
    let (k, index) = find(&v, |p| p["status"] == "ok");
    v["points"][k]["pull_out_ratio"] = json!(-1.0);
    std::fs::write(&path, v.to_string()).unwrap();
    let e = Map::read_path(&path).unwrap_err().to_string();
    assert!(
        e.contains(&path.display().to_string())
            && e.contains(&format!("point {index}: pull_out_ratio")),
        "{e}"
    );

    std::fs::write(&path, b"{\"format\": \"\xff\"}").unwrap();
    let e = Map::read_path(&path).unwrap_err().to_string();
    assert!(e.contains("not UTF-8"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn read_path_refuses_a_file_above_the_cap_unread() {
    let dir = temp_dir("big");
    let path = dir.join("map.json");
    // sparse: no disk space, and read_path must not read it
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(MAX_MAP_BYTES + 1).unwrap();
    let t = Instant::now();
    let e = Map::read_path(&path).unwrap_err().to_string();
    assert!(t.elapsed() < Duration::from_secs(2), "{:?}", t.elapsed());
    assert!(
        e.contains(&path.display().to_string()) && e.contains("larger than"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn read_path_refuses_devices_and_fifos_without_reading_them() {
    let dir = temp_dir("special");
    // a part whose map.json is a link to /dev/zero (endless) or a FIFO (blocks on open)
    let zero = dir.join("zero.json");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let t = Instant::now();
    let e = Map::read_path(&zero).unwrap_err().to_string();
    assert!(t.elapsed() < Duration::from_secs(2), "{:?}", t.elapsed());
    assert!(
        e.contains(&zero.display().to_string()) && e.contains("not a regular file"),
        "{e}"
    );
    let fifo = dir.join("fifo.json");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        let e = Map::read_path(&fifo).unwrap_err().to_string();
        assert!(e.contains("a FIFO"), "{e}");
    }
    let e = Map::read_path(&dir).unwrap_err().to_string();
    assert!(e.contains("a folder"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
