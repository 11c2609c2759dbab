//! The stiction boundary of maps and the SVG they draw.

mod common;

use common::{flaky, product};
use design_sweep::{run_map, Grid, Labels, Level, Map, MapRequest};
use serde_json::json;
use stiction_report::design_table::map_table;
use stiction_report::plot::map::map_svg;

fn run<F>(specs: &[&str], eval: F) -> Map
where
    F: Fn(&[(&str, Level)]) -> Result<design_sweep::DesignPoint, design_sweep::PointError> + Sync,
{
    let request = MapRequest {
        scene: json!({"name": "test"}),
        grid: Grid::parse(specs).unwrap(),
        accuracy: "fast".into(),
        shard: None,
    };
    run_map(request, eval, |_, _| {})
}

fn ratio(x: f64, y: f64) -> f64 {
    (2e3 / x).powi(2) * (y / 1e-8)
}

fn labels() -> Labels {
    Labels::new()
        .with_unit("switch.k_s", "Pa/m")
        .with_unit("surface.sigma_s", "m")
}

/// The polylines of an SVG with the given stroke width, as point counts.
fn polylines(svg: &str, width: &str) -> Vec<usize> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke-width") == Some(width))
        .map(|n| {
            n.attribute("points")
                .unwrap_or("")
                .split_whitespace()
                .count()
        })
        .collect()
}

#[test]
fn contour_is_exact_where_log_ratio_is_linear_in_the_plotted_coordinates() {
    // both axes log: log10 ratio is linear in (log10 x, log10 y), so every vertex is exact
    let map = run(
        &[
            "switch.k_s=3e2:3e4:log:13",
            "surface.sigma_s=1e-9:9e-8:log:9",
        ],
        product,
    );
    let lines = map.boundary_2d();
    assert_eq!(lines.len(), 1);
    assert!(lines[0].len() >= 8, "{}", lines[0].len());
    for &(x, y) in &lines[0] {
        assert!(
            ratio(x, y).log10().abs() < 1e-10,
            "({x}, {y}): ratio {}",
            ratio(x, y)
        );
    }
}

#[test]
fn contour_follows_the_known_boundary_on_a_lin_axis() {
    let map = run(
        &[
            "switch.k_s=3e2:3e4:log:13",
            "surface.sigma_s=1e-9:9e-9:lin:7",
        ],
        product,
    );
    let lines = map.boundary_2d();
    assert_eq!(lines.len(), 1);
    let line = &lines[0];
    // linear interpolation of log10 y on a lin axis: within 0.05 decades of ratio = 1
    for &(x, y) in line {
        assert!(ratio(x, y).log10().abs() < 0.05, "({x}, {y})");
    }
    // it runs from the bottom to the top of the grid
    let ys: Vec<f64> = line.iter().map(|p| p.1).collect();
    let (lo, hi) = ys
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &y| (a.min(y), b.max(y)));
    assert_eq!((lo, hi), (1e-9, 9e-9));

    let svg = map_svg(&map, &labels()).unwrap();
    let contour = polylines(&svg, "3");
    assert_eq!(contour.len(), 1, "one contour polyline");
    assert_eq!(contour[0], line.len());
    assert!(svg.contains("switch.k_s [Pa/m]") && svg.contains("surface.sigma_s [m]"));
    assert!(svg.contains("log10 ratio"));
    assert!(!svg.contains("NaN"));
    let table = map_table(&map, &labels());
    assert!(table.contains("1 contour line(s)"), "{table}");
}

#[test]
fn a_map_without_a_boundary_has_no_contour() {
    let map = run(
        &[
            "switch.k_s=1e4:3e4:log:5",
            "surface.sigma_s=1e-9:2e-9:lin:3",
        ],
        product,
    );
    assert!(map.boundary_2d().is_empty());
    let svg = map_svg(&map, &labels()).unwrap();
    assert!(polylines(&svg, "3").is_empty());
}

#[test]
fn failed_and_non_closing_points_are_drawn_not_dropped() {
    let map = run(&["switch.k_s=100:2000:lin:20"], flaky);
    let svg = map_svg(&map, &labels()).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let circles = doc
        .descendants()
        .filter(|n| n.has_tag_name("circle"))
        .count();
    // 15 closing points, 2 that do not close at the floor, 1 legend marker
    assert_eq!(circles, 15 + 2 + 1, "{svg}");
    assert!(svg.contains("does not close (ratio 0)"));
    assert!(svg.contains("failed or out of domain"));
    assert!(svg.contains("switch.k_s [Pa/m]"));
    // a 2-D map with failures draws them as crossed cells
    let map2 = run(
        &[
            "switch.k_s=100:2000:lin:20",
            "surface.sigma_s=1e-9:2e-9:lin:3",
        ],
        |v: &[(&str, Level)]| flaky(&v[..1]),
    );
    let svg2 = map_svg(&map2, &labels()).unwrap();
    roxmltree::Document::parse(&svg2).unwrap();
    assert!(svg2.contains("x: failed or out of domain") && svg2.contains("grey: does not close"));
    let table = map_table(&map, &labels());
    assert!(
        table.contains("points not run: out of domain or failed (3)"),
        "{table}"
    );
    assert!(table.contains("boundary        switch.k_s ~ "), "{table}");
}

#[test]
fn one_d_svg_with_a_log_grid_is_well_formed() {
    let map = run(&["switch.k_s=1e2:1e5:log:31"], |v: &[(&str, Level)]| {
        common::power(3e3, 2.0)(common::num(v, 0))
    });
    let svg = map_svg(&map, &labels().with_title("k_s sweep")).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts = common::svg_texts(&doc);
    assert!(texts.contains(&"k_s sweep"));
    assert!(
        texts.contains(&"pull-out ratio [-] (log scale)"),
        "{texts:?}"
    );
    // decade tick labels on the log x axis and the log ratio axis
    for tick in ["100", "1000", "10000", "1e5", "0.01", "1"] {
        assert!(texts.contains(&tick), "{tick}: {texts:?}");
    }
}
