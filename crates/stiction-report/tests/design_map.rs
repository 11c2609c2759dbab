//! Maps: sharding and merging byte for byte, thread-count independence, statuses, CSV, JSON.

mod common;

use common::flaky;
use common::maps::{request, run, GRID_2D};
use design_sweep::{
    merge, run_map, DesignPoint, Labels, Level, Map, PointError, Shard, Status, CSV_COLUMNS,
};
use serde_json::Value;
use std::sync::atomic::{AtomicUsize, Ordering};
use stiction_report::csv::map_csv;
use stiction_report::design_table::map_table;
use stiction_report::plot::map::map_svg;

fn labels() -> Labels {
    Labels::new()
        .with_unit("switch.k_s", "Pa/m")
        .with_unit("surface.sigma_s", "m")
}

#[test]
fn failing_points_get_a_status_and_the_map_completes() {
    let specs = ["switch.k_s=100:2000:lin:20"];
    let calls = AtomicUsize::new(0);
    let last = AtomicUsize::new(0);
    let map = run_map(
        request(&specs, None),
        |v: &[(&str, Level)]| {
            calls.fetch_add(1, Ordering::Relaxed);
            flaky(v)
        },
        |done, total| {
            assert_eq!(total, 20);
            last.fetch_max(done, Ordering::Relaxed);
        },
    );
    assert_eq!(calls.load(Ordering::Relaxed), 20);
    assert_eq!(last.load(Ordering::Relaxed), 20);
    assert_eq!(map.points().len(), 20);
    let status = |x: f64| {
        &map.points()
            .iter()
            .find(|p| p.values[0] == x)
            .unwrap()
            .status
    };
    assert!(matches!(status(100.0), Status::OutOfDomain(m) if m.contains("below 150")));
    assert!(matches!(status(500.0), Status::Failed(m) if m.contains("did not converge")));
    assert!(
        matches!(status(900.0), Status::Failed(m) if m.contains("panicked") && m.contains("a bug"))
    );
    assert_eq!(*status(1900.0), Status::DoesNotClose);
    assert_eq!(*status(1000.0), Status::Ok);
    let s = map.summary();
    assert_eq!(
        (s.ok, s.does_not_close, s.out_of_domain, s.failed),
        (15, 2, 1, 2)
    );
    // CSV: status words, empty cells for the failed point, no detail
    let csv = map_csv(&map).unwrap();
    let row500 = csv.lines().find(|l| l.starts_with("5e2,")).unwrap();
    assert_eq!(row500, "5e2,,,,,,,,,,,,failed");
    assert!(!csv.contains("converge"));
    // JSON: detail present, no null anywhere
    let j = map.to_json();
    assert!(j.contains("\"detail\": \"solver did not converge\""));
    assert!(!j.contains("null") && !j.contains("NaN"));
    // the 1-D crossing at 1e3 is found between grid points
    let b = map.boundary_1d();
    assert_eq!(b.len(), 1);
    assert!(b[0].between[0] <= 1e3 && 1e3 <= b[0].between[1]);
    // a failed or non-finite evaluator answer is a status, never a NaN in the output
    let nan = run_map(
        request(&specs, None),
        |v: &[(&str, Level)]| -> Result<DesignPoint, PointError> {
            let mut p = common::point(1.0, common::num(v, 0));
            p.pull_out_ratio = f64::NAN;
            Ok(p)
        },
        |_, _| {},
    );
    assert!(nan.points().iter().all(
        |p| matches!(&p.status, Status::Failed(m) if m.contains("pull_out_ratio is not a number"))
    ));
    assert!(!nan.to_json().contains("NaN"));
    serde_json::from_str::<Value>(&nan.to_json()).unwrap();
}

#[test]
fn csv_header_and_rows_are_exact() {
    let map = run(&GRID_2D, None);
    let csv = map_csv(&map).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "switch.k_s,surface.sigma_s,pull_out_ratio,largest_pull_out_pa,restoring_pressure_pa,cycles_to_accommodation,first_sticking_cycle,sticks,closes,validity_holds,accommodation_cause,contact_resistance,real_contact_fraction,status"
    );
    assert_eq!(CSV_COLUMNS.len(), 12);
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 13 * 7);
    // first row: x = 300, y = 1e-9 -> ratio (2e3/300)^2 = 44.44..., sticks
    let cells: Vec<&str> = rows[0].split(',').collect();
    assert_eq!(cells[0], "3e2");
    assert_eq!(cells[1], "1e-9");
    let r: f64 = cells[2].parse().unwrap();
    assert_eq!(
        r,
        map.points()[0].design.unwrap().pull_out_ratio,
        "round trip"
    );
    assert_eq!(
        &cells[5..],
        ["3", "1", "true", "true", "true", "", "", "", "ok"]
    );
    // every number parses back bit for bit
    for (row, p) in rows.iter().zip(map.points()) {
        let c: Vec<&str> = row.split(',').collect();
        assert_eq!(c[0].parse::<f64>().unwrap(), p.values[0]);
        assert_eq!(c[1].parse::<f64>().unwrap(), p.values[1]);
        assert_eq!(
            c[3].parse::<f64>().unwrap(),
            p.design.unwrap().largest_pull_out_pa
        );
    }
}

#[test]
fn a_shard_with_more_parts_than_points_is_empty_and_merges() {
    let specs = ["switch.k_s=1e2:1e4:log:3"];
    let parts: Vec<(String, Map)> = (1..=5)
        .map(|k| {
            (
                format!("p{k}"),
                run(&specs, Some(Shard::new(k, 5).unwrap())),
            )
        })
        .collect();
    assert!(parts[4].1.points().is_empty());
    roxmltree::Document::parse(&map_svg(&parts[4].1, &labels()).unwrap()).unwrap();
    let empty_2d = run(&GRID_2D, Some(Shard::new(99, 99).unwrap()));
    roxmltree::Document::parse(&map_svg(&empty_2d, &labels()).unwrap()).unwrap();
    let merged = merge(parts).unwrap();
    assert_eq!(merged.to_json(), run(&specs, None).to_json());
}

/// A 1-D map whose switch stops closing between two grid points says so beside the
/// stiction boundary, with the side where it closes (the QA case of the tenth stop: "free
/// below" read as free down to the range's end, where the switch no longer closes).
#[test]
fn a_1d_map_names_where_the_switch_stops_closing() {
    // closes above 45, sticks above 50: free on (45, 50)
    let eval = |v: &[(&str, Level<'_>)]| -> Result<DesignPoint, PointError> {
        let Level::Number(x) = v[0].1 else {
            unreachable!()
        };
        if x < 45.0 {
            Ok(DesignPoint::does_not_close(1.0))
        } else {
            Ok(common::point(x / 50.0, 1.0))
        }
    };
    for spec in ["switch.voltage=40:60:lin:11", "switch.voltage=60:40:lin:11"] {
        let m = run_map(request(&[spec], None), eval, |_, _| {});
        let t = map_table(&m, &Labels::new().with_unit("switch.voltage", "V"));
        let closure: Vec<&str> = t.lines().filter(|l| l.starts_with("closure")).collect();
        assert_eq!(closure.len(), 1, "{t}");
        assert!(
            closure[0].contains("between 44 V and 46 V") && closure[0].contains("closes above"),
            "{t}"
        );
        assert!(
            t.lines()
                .any(|l| l.starts_with("boundary") && l.contains("free below")),
            "{t}"
        );
    }
}

/// A switch that sticks where it first closes (the user's case of the fourteenth stop:
/// the table put a "jump" stiction boundary at the midpoint between a point that does not
/// close and a sticking one, where a threshold search found the switch closing at 48.2 V
/// and free up to 51.3 V): no stiction boundary is claimed there; the closure row says
/// that the switch sticks where it closes and that the boundary lies at the closure or
/// beyond it. Over words too, each word with its own closure row.
#[test]
fn no_stiction_boundary_is_claimed_next_to_a_point_that_does_not_close() {
    // closes above 45 V; ratio x / 40 (free below 40 V: never, where it closes)
    let eval = |v: &[(&str, Level<'_>)]| -> Result<DesignPoint, PointError> {
        let x = v
            .iter()
            .find_map(|(f, l)| (*f == "switch.voltage").then(|| l.number()).flatten())
            .expect("the voltage");
        if x < 45.0 {
            Ok(DesignPoint::does_not_close(1.0))
        } else {
            Ok(common::point(x / 40.0, 1.0))
        }
    };
    let labels = Labels::new().with_unit("switch.voltage", "V");
    let m = run_map(
        request(&["switch.voltage=40:60:lin:11"], None),
        eval,
        |_, _| {},
    );
    assert!(m.boundary_1d().is_empty(), "{:?}", m.boundary_1d());
    let t = map_table(&m, &labels);
    assert!(!t.contains("jump"), "{t}");
    let closure: Vec<&str> = t.lines().filter(|l| l.starts_with("closure")).collect();
    assert_eq!(closure.len(), 1, "{t}");
    assert!(
        closure[0].contains("at 46 V, where it closes, it sticks (ratio 1.15)")
            && closure[0].contains("at the closure or between it and 46 V"),
        "{t}"
    );
    // a crossing among closing points is still found, and a free point at closure said so
    let m = run_map(
        request(&["switch.voltage=40:60:lin:11"], None),
        |v: &[(&str, Level<'_>)]| -> Result<DesignPoint, PointError> {
            let x = v[0].1.number().unwrap();
            if x < 45.0 {
                Ok(DesignPoint::does_not_close(1.0))
            } else {
                Ok(common::point(x / 50.0, 1.0))
            }
        },
        |_, _| {},
    );
    let b = m.boundary_1d();
    assert_eq!(b.len(), 1);
    assert!(
        b[0].between == [48.0, 50.0] || b[0].between == [50.0, 52.0],
        "{b:?}"
    );
    assert!(map_table(&m, &labels).contains("where it closes, it is free (ratio 0.92)"));
    // over words: each word has its closure row
    let m = run_map(
        request(
            &[
                "contact.plasticity_law=etsion_kadin,kogut_etsion",
                "switch.voltage=40:60:lin:11",
            ],
            None,
        ),
        eval,
        |_, _| {},
    );
    let t = map_table(&m, &labels);
    let closure: Vec<&str> = t.lines().filter(|l| l.starts_with("closure")).collect();
    assert_eq!(closure.len(), 2, "{t}");
    assert!(
        closure[0].contains(
            "contact.plasticity_law = etsion_kadin: the switch stops closing between 44 V and 46 V"
        ),
        "{t}"
    );
    assert!(!t.contains("jump"), "{t}");
}
