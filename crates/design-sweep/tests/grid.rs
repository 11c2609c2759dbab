//! Grid and shard parsing, values and order.

use design_sweep::{Axis, DesignError, Grid, Shard, Spacing};

fn axis_err(option: &str) -> String {
    match Axis::parse(option) {
        Err(e @ DesignError::Axis { .. }) => e.to_string(),
        other => panic!("{option}: expected an axis error, got {other:?}"),
    }
}

#[test]
fn parses_lin_and_log_axes() {
    let a = Axis::parse("switch.k_s=1e2:1e5:log:4").unwrap();
    assert_eq!(a.field, "switch.k_s");
    assert_eq!(a.spacing, Spacing::Log);
    assert_eq!(a.n, 4);
    assert_eq!(a.values.len(), 4);
    // exact end points, geometric interior
    assert_eq!(a.values[0], 1e2);
    assert_eq!(a.values[3], 1e5);
    for (v, want) in a.values.iter().zip([1e2, 1e3, 1e4, 1e5]) {
        assert!((v / want - 1.0).abs() < 1e-14, "{v} vs {want}");
    }
    let b: Axis = "surface.sigma_s=2e-9:1e-9:lin:3".parse().unwrap();
    assert_eq!((b.values[0], b.values[2]), (2e-9, 1e-9));
    assert!((b.values[1] / 1.5e-9 - 1.0).abs() < 1e-15);
    // whole-number grids come out exact
    let c = Axis::parse("switch.k_s=100:2000:lin:20").unwrap();
    assert!(c
        .values
        .iter()
        .enumerate()
        .all(|(i, &v)| v == 100.0 * (i + 1) as f64));
}

#[test]
fn same_spec_gives_bit_identical_values() {
    let a = Axis::parse("surface.sigma_s=3.7e-10:8.1e-9:log:37").unwrap();
    let b = Axis::new("surface.sigma_s", 3.7e-10, 8.1e-9, Spacing::Log, 37).unwrap();
    let bits = |x: &Axis| x.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(a.values[36], 8.1e-9);
    // strictly increasing with a constant ratio
    let r = a.values[1] / a.values[0];
    for w in a.values.windows(2) {
        assert!(w[1] > w[0]);
        assert!((w[1] / w[0] / r - 1.0).abs() < 1e-12);
    }
}

#[test]
fn one_point_axis_is_from_only() {
    let a = Axis::parse("switch.d0=2e-6:3e-6:lin:1").unwrap();
    assert_eq!(a.values, vec![2e-6]);
}

#[test]
fn axis_errors_name_the_option_and_the_value() {
    let e = axis_err("switch.k_s=1:1:lin:5");
    assert!(
        e.contains("switch.k_s=1:1:lin:5") && e.contains("both 1"),
        "{e}"
    );
    let e = axis_err("switch.k_s=0:10:log:5");
    assert!(e.contains("FROM = 0") && e.contains("log"), "{e}");
    let e = axis_err("switch.k_s=-1:10:log:5");
    assert!(e.contains("FROM = -1"), "{e}");
    let e = axis_err("switch.k_s=1:10:lin:0");
    assert!(e.contains("N = 0"), "{e}");
    let e = axis_err("switch.k_s=1:10:cubic:5");
    assert!(e.contains("`cubic`"), "{e}");
    let e = axis_err("switch.k_s=1:abc:lin:5");
    assert!(e.contains("TO `abc`"), "{e}");
    let e = axis_err("switch.k_s=1:inf:lin:5");
    assert!(e.contains("TO = inf"), "{e}");
    let e = axis_err("switch.k_s=NaN:2:lin:5");
    assert!(e.contains("FROM = NaN"), "{e}");
    let e = axis_err("switch.k_s=1:2:lin:2.5");
    assert!(e.contains("N `2.5`"), "{e}");
    let e = axis_err("switch.k_s=1:2:lin");
    assert!(e.contains("3 part(s)"), "{e}");
    let e = axis_err("k_s=1:2:lin:3");
    assert!(e.contains("section.key"), "{e}");
    let e = axis_err("switch.k_s 1:2:lin:3");
    assert!(e.contains("FIELD=FROM:TO"), "{e}");
}

#[test]
fn grid_orders_first_axis_slowest() {
    let g = Grid::parse(&["switch.k_s=1:3:lin:3", "surface.sigma_s=10:20:lin:2"]).unwrap();
    assert_eq!(g.len(), 6);
    assert_eq!(g.dim(), 2);
    let pts: Vec<Vec<f64>> = (0..6).map(|i| g.values(i)).collect();
    assert_eq!(
        pts,
        vec![
            vec![1.0, 10.0],
            vec![1.0, 20.0],
            vec![2.0, 10.0],
            vec![2.0, 20.0],
            vec![3.0, 10.0],
            vec![3.0, 20.0]
        ]
    );
    for i in 0..6 {
        assert_eq!(g.index(&g.indices(i)), i);
    }
}

#[test]
fn grid_refuses_bad_dimensions() {
    let none: [&str; 0] = [];
    assert!(matches!(Grid::parse(&none), Err(DesignError::Grid(_))));
    let three = ["a.x=1:2:lin:2", "a.y=1:2:lin:2", "a.z=1:2:lin:2"];
    assert!(Grid::parse(&three)
        .unwrap_err()
        .to_string()
        .contains("1-D or 2-D"));
    let twice = ["a.x=1:2:lin:2", "a.x=3:4:lin:2"];
    assert!(Grid::parse(&twice)
        .unwrap_err()
        .to_string()
        .contains("a.x is varied twice"));
    let huge = ["a.x=1:2:lin:100000", "a.y=1:2:lin:100"];
    assert!(Grid::parse(&huge)
        .unwrap_err()
        .to_string()
        .contains("at most"));
}

#[test]
fn shards_partition_the_grid() {
    let n = 3;
    let len = 10;
    let mut seen = vec![0; len];
    for k in 1..=n {
        let s = Shard::new(k, n).unwrap();
        for i in s.indices(len) {
            assert!(s.contains(i));
            assert_eq!(i % n, k - 1);
            seen[i] += 1;
        }
    }
    assert!(seen.iter().all(|&c| c == 1));
    assert_eq!("2/8".parse::<Shard>().unwrap(), Shard { k: 2, n: 8 });
    assert_eq!(Shard::new(2, 8).unwrap().to_string(), "2/8");
}

#[test]
fn shard_errors_name_the_option() {
    for (opt, want) in [
        ("0/4", "K = 0"),
        ("5/4", "K = 5 must be in 1..=4"),
        ("1/0", "N = 0"),
        ("3", "expected K/N"),
        ("a/4", "K `a`"),
        ("1/-2", "N `-2`"),
    ] {
        let e = Shard::parse(opt).unwrap_err().to_string();
        assert!(
            e.contains(&format!("`{opt}`")) && e.contains(want),
            "{opt}: {e}"
        );
    }
}
