//! Plots a reader trusts (issue 46 item 3), read from the SVG a reader gets: one colour
//! per cycle across the panels of `switch.svg`, text that fits the figure, a unit on every
//! axis, whole-number cycle ticks, the hold as the scene gave it, an impossible real
//! contact area flagged with its 100 % line, map points outside validity marked, and a
//! height map at its true aspect with a colour bar.

mod common;

use design_sweep::{run_map, DesignPoint, Grid, Labels, Level, MapRequest, PointError};
use serde_json::json;
use std::collections::BTreeMap;
use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::{SwitchModel, SwitchResult};
use stiction_model::topography::{
    io, synthesize, Amplitudes, Format, Normalization, SelfAffinePsd, SynthesisOptions,
    TopographyRequest,
};
use stiction_model::Silent;
use stiction_report::plot::map::{fmt_sig, map_svg, INVALID};
use stiction_report::plot::{self, Panel, Series, CHAR_WIDTH};
use stiction_report::topography::TopographyResult;
use stiction_report::Plot;

/// The paper's switch in fast mode with `values` set (scene keys, TOML text).
fn switch(values: &[(&str, &str)]) -> SwitchResult {
    let mut scene = Scene::paper(Kind::Switch);
    scene.set_text("accuracy", "fast").unwrap();
    for (k, v) in values {
        scene.set_text(k, v).unwrap();
    }
    let spec = SwitchSpec::new(&scene, &LawRegistry::builtin()).unwrap();
    SwitchModel::build(&spec).unwrap().run(&Silent).unwrap()
}

fn doc(svg: &str) -> roxmltree::Document<'_> {
    roxmltree::Document::parse(svg).expect("well-formed SVG")
}

fn num(n: roxmltree::Node, key: &str) -> f64 {
    n.attribute(key)
        .unwrap_or_else(|| panic!("a <{}> without {key}", n.tag_name().name()))
        .parse()
        .unwrap()
}

/// Every `<text>`: (content, x, y, font size, rotated).
fn texts(svg: &str) -> Vec<(String, f64, f64, f64, bool)> {
    let d = doc(svg);
    d.descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| {
            let t = n.text()?.trim().to_owned();
            let size = n
                .attribute("font-size")
                .map_or(12.0, |s| s.trim_end_matches("px").parse().unwrap());
            let rotated = n
                .attribute("transform")
                .is_some_and(|t| t.contains("rotate"));
            Some((t, num(n, "x"), num(n, "y"), size, rotated))
        })
        .collect()
}

/// The SVG's width in pixels.
fn width(svg: &str) -> f64 {
    num(doc(svg).root_element(), "width")
}

#[test]
fn each_cycle_has_one_colour_in_both_pressure_panels() {
    let r = switch(&[("cycles", "4")]);
    let svg = r.svg().unwrap();
    let d = doc(&svg);
    // a legend's texts come first, then its sample lines (20 px, 2 points), each 30 px
    // left of its text and within a line of the text's baseline
    let samples: Vec<(f64, f64, String)> = d
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .filter_map(|n| {
            let p: Vec<f64> = n
                .attribute("points")?
                .split([' ', ','])
                .filter(|t| !t.is_empty())
                .map(|t| t.parse().unwrap())
                .collect();
            (p.len() == 4 && p[1] == p[3] && p[2] - p[0] == 20.0)
                .then(|| (p[0], p[1], n.attribute("stroke").unwrap().to_owned()))
        })
        .collect();
    let mut seen: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (t, x, y, size, _) in texts(&svg) {
        if t.starts_with("unloading, cycle") {
            let sample = samples
                .iter()
                .find(|s| s.0 == x - 30.0 && (s.1 - y).abs() <= 0.5 * size)
                .unwrap_or_else(|| panic!("no legend line for {t:?}"));
            seen.entry(t).or_default().push(sample.2.clone());
        }
    }
    assert!(seen.len() >= 2, "cycles in the legend: {seen:?}");
    let mut colours = Vec::new();
    for (cycle, strokes) in &seen {
        assert_eq!(strokes.len(), 2, "{cycle}: in both panels");
        assert_eq!(strokes[0], strokes[1], "{cycle}: one colour in both panels");
        colours.push(strokes[0].clone());
    }
    let distinct: std::collections::BTreeSet<_> = colours.iter().collect();
    assert_eq!(
        distinct.len(),
        colours.len(),
        "cycles share a colour: {seen:?}"
    );
}

#[test]
fn long_titles_captions_and_flags_are_wrapped_inside_the_figure() {
    let long = "a title much longer than the figure is wide, as a scene's name with its laws, \
                its accuracy, its reload rule and its reading of eq 1 makes it";
    let svg = plot::svg(
        long,
        &[Panel {
            caption: format!("caption: {long}"),
            flags: vec![format!("flag: {long}")],
            x_label: "d [nm]".into(),
            y_label: "p [MPa]".into(),
            series: vec![Series {
                name: "p".into(),
                points: vec![(1.0, 2.0), (2.0, 3.0)],
                colour: None,
            }],
            ..Default::default()
        }],
    )
    .unwrap();
    let w = width(&svg);
    let mut words = 0;
    for (t, x, _, size, rotated) in texts(&svg) {
        if rotated {
            continue;
        }
        // centred text (plotters' titles): half its estimated width either side
        let half = 0.5 * t.chars().count() as f64 * CHAR_WIDTH * size;
        assert!(
            x - half >= 0.0 && x + half <= w,
            "{t:?} at x = {x}, {size} px, spans {}..{} of {w}",
            x - half,
            x + half
        );
        words += t.split_whitespace().count();
    }
    // every word of the three long texts is drawn
    assert!(
        words >= 3 * long.split_whitespace().count(),
        "{words} words"
    );
    // switch.svg's own title and captions fit too
    for (t, x, _, size, rotated) in texts(&switch(&[("cycles", "2")]).svg().unwrap()) {
        let half = 0.5 * t.chars().count() as f64 * CHAR_WIDTH * size;
        assert!(rotated || x + half <= 960.0 + 1e-9, "{t:?} at {x}");
    }
}

/// The whole numbers among a figure's tick labels (texts that are numbers), and those that
/// are not whole.
fn ticks(svg: &str) -> (Vec<f64>, Vec<String>) {
    let (mut whole, mut other) = (Vec::new(), Vec::new());
    for (t, ..) in texts(svg) {
        if let Ok(v) = t.parse::<f64>() {
            if t.contains('.') || t.contains('e') {
                other.push(t);
            } else {
                whole.push(v);
            }
        }
    }
    (whole, other)
}

/// x ticks at whole cycles, evenly spaced by a whole step, from at most one step above
/// cycle 0 to at most one step below the last cycle `last`, at least four.
fn evenly_whole(ticks: &[f64], last: f64) {
    assert!(ticks.len() >= 4, "{ticks:?}");
    let step = ticks[1] - ticks[0];
    assert!(step >= 1.0 && step.fract() == 0.0, "{ticks:?}");
    for w in ticks.windows(2) {
        assert_eq!(w[1] - w[0], step, "{ticks:?}");
    }
    assert!(ticks.iter().all(|v| v.fract() == 0.0), "{ticks:?}");
    assert!(
        ticks[0] <= step && *ticks.last().unwrap() >= last - step,
        "{ticks:?}"
    );
}

#[test]
fn cycles_are_counted_in_whole_numbers() {
    // a probability against cycle under 1 (so every y tick has a decimal point): the x
    // ticks are exactly the whole cycles, none "1.0" or "1.5"
    let svg = common::against_cycle(12, true, None);
    let (whole, other) = ticks(&svg);
    evenly_whole(&whole, 12.0);
    assert!(
        other.iter().all(|t| t.parse::<f64>().unwrap() < 1.0),
        "a cycle tick with a decimal point: {other:?}"
    );
    // the band is shaded: one filled polygon, not two lines
    let d = doc(&svg);
    let shaded = d
        .descendants()
        .filter(|n| n.has_tag_name("polygon"))
        .filter(|n| n.attribute("fill").is_some_and(|f| f != "none"))
        .count();
    assert_eq!(shaded, 1, "the band as one shaded polygon");
    // 40 cycles: whole steps (5, 10, ...), still no decimals
    let svg = common::against_cycle(40, false, None);
    let (whole, other) = ticks(&svg);
    evenly_whole(&whole, 40.0);
    assert!(
        other.iter().all(|t| t.parse::<f64>().unwrap() < 1.0),
        "{other:?}"
    );
}

/// Every figure of a result kind that this crate draws from a cheap run.
fn figures() -> Vec<(&'static str, String)> {
    let r = switch(&[("cycles", "3"), ("contact.resistivity", "7.1e-8")]);
    let labels = Labels::new()
        .with_unit("switch.k_s", "Pa/m")
        .with_unit("surface.sigma_s", "m");
    let map = run_map(
        MapRequest {
            scene: json!({"name": "test"}),
            grid: Grid::parse(&[
                "switch.k_s=3e2:3e4:log:5",
                "surface.sigma_s=1e-9:9e-8:log:4",
            ])
            .unwrap(),
            accuracy: "fast".into(),
            shard: None,
        },
        common::product,
        |_, _| {},
    );
    vec![
        ("switch.svg", r.svg().unwrap()),
        ("map.svg", map_svg(&map, &labels).unwrap()),
        ("topography.svg", topography(83, 204).svg().unwrap()),
    ]
}

#[test]
fn every_axis_names_its_unit() {
    for (name, svg) in figures() {
        let all = texts(&svg);
        let vertical: Vec<_> = all.iter().filter(|t| t.4).collect();
        assert!(!vertical.is_empty(), "{name}: no vertical axis label");
        for t in &vertical {
            assert!(
                t.0.contains('[') && t.0.contains(']'),
                "{name}: the axis label {:?} has no unit",
                t.0
            );
        }
        // each vertical axis but a colour bar's has its horizontal one, with a unit
        let bars = usize::from(matches!(name, "map.svg" | "topography.svg"));
        let horizontal = all
            .iter()
            .filter(|t| !t.4 && t.0.contains('[') && t.0.contains(']'))
            .count();
        assert!(
            horizontal + bars >= vertical.len(),
            "{name}: {horizontal} horizontal axis labels with a unit, {} vertical",
            vertical.len()
        );
    }
}

fn hold_texts(svg: &str) -> Vec<String> {
    texts(svg)
        .into_iter()
        .map(|t| t.0)
        .filter(|t| t.contains("hold"))
        .collect()
}

#[test]
fn the_hold_is_named_as_the_scene_gave_it() {
    let by_force = switch(&[
        ("cycles", "2"),
        ("switch.electrode_area", "1e-8"),
        ("switch.hold_force", "2e-5"),
    ]);
    let svg = by_force.svg().unwrap();
    let n = format!("under the hold ({} N)", fmt_sig(2e-5, 4));
    assert!(svg.contains(&n), "{n} not in {:?}", hold_texts(&svg));
    assert!(
        hold_texts(&svg).iter().all(|t| !t.contains(" V)")),
        "a voltage where a force was given: {:?}",
        hold_texts(&svg)
    );
    let by_voltage = switch(&[("cycles", "2")]);
    let v = format!("under the hold ({:.4} V)", by_voltage.hold_voltage);
    assert!(by_voltage.svg().unwrap().contains(&v), "{v}");
}

#[test]
fn more_real_contact_than_contact_area_is_flagged_with_its_limit() {
    let mut r = switch(&[("cycles", "2")]);
    let ok = r.svg().unwrap();
    assert!(!ok.contains("IMPOSSIBLE"), "a possible area flagged");
    // a result that claims 26 times the contact area (a model outside its validity)
    let hold = r.cycles[1].hold.as_mut().expect("contact states");
    hold.real_contact_fraction = 26.0;
    let svg = r.svg().unwrap();
    let flagged: Vec<String> = texts(&svg)
        .into_iter()
        .map(|t| t.0)
        .filter(|t| t.contains("IMPOSSIBLE") || t.contains("100 %"))
        .collect();
    assert!(
        flagged
            .iter()
            .any(|t| t.contains("IMPOSSIBLE") && t.contains(&format!("{} %", fmt_sig(2600.0, 3)))),
        "{flagged:?}"
    );
    assert!(
        flagged.iter().any(|t| t.contains("A_r = A (100 %)")),
        "the 100 % line in the legend: {flagged:?}"
    );
}

/// ratio = (2e3 / x)^2 (y / 1e-8) as [`common::product`], outside validity where the
/// ratio exceeds 3.
fn partly_invalid(values: &[(&str, Level)]) -> Result<DesignPoint, PointError> {
    let mut p = common::product(values)?;
    p.validity_holds = p.pull_out_ratio <= 3.0;
    Ok(p)
}

/// The same along k_s alone, at sigma_s = 2e-8 m.
fn partly_invalid_1d(values: &[(&str, Level)]) -> Result<DesignPoint, PointError> {
    partly_invalid(&[values[0], ("surface.sigma_s", Level::Number(2e-8))])
}

#[test]
fn points_outside_validity_are_hollow_grey_rings() {
    let labels = Labels::new()
        .with_unit("switch.k_s", "Pa/m")
        .with_unit("surface.sigma_s", "m");
    let grey = format!("#{:02X}{:02X}{:02X}", INVALID.0, INVALID.1, INVALID.2);
    for axes in [
        vec![
            "switch.k_s=3e2:3e4:log:5",
            "surface.sigma_s=1e-9:9e-8:log:4",
        ],
        vec!["switch.k_s=3e2:3e4:log:9"],
    ] {
        let map = run_map(
            MapRequest {
                scene: json!({"name": "test"}),
                grid: Grid::parse(&axes).unwrap(),
                accuracy: "fast".into(),
                shard: None,
            },
            if axes.len() == 2 {
                partly_invalid
            } else {
                partly_invalid_1d
            },
            |_, _| {},
        );
        let invalid = map
            .points()
            .iter()
            .filter(|p| p.design.is_some_and(|d| !d.validity_holds))
            .count();
        assert!(invalid >= 1 && invalid < map.points().len(), "{axes:?}");
        let svg = map_svg(&map, &labels).unwrap();
        let d = doc(&svg);
        let rings = d
            .descendants()
            .filter(|n| n.has_tag_name("circle"))
            .filter(|n| {
                n.attribute("stroke")
                    .is_some_and(|s| s.eq_ignore_ascii_case(&grey))
                    && n.attribute("fill") == Some("none")
            })
            .count();
        // one ring a point outside validity, and the legend's
        assert!(
            rings == invalid || rings == invalid + 1,
            "{axes:?}: {rings} grey rings for {invalid} points outside validity"
        );
        let words: Vec<String> = texts(&svg).into_iter().map(|t| t.0).collect();
        assert!(
            words.join(" ").contains("outside the model's validity"),
            "{axes:?}: no legend in {words:?}"
        );
    }
}

/// The topography report of a synthetic map `nx` x `ny` um (1 um spacing).
fn topography(nx: usize, ny: usize) -> TopographyResult {
    let psd = SelfAffinePsd::new(0.8, 20e-6, None, 2e-6, Normalization::RmsHeight(6e-9)).unwrap();
    let grid = SynthesisOptions {
        nx,
        ny,
        dx: 1e-6,
        dy: 1e-6,
        seed: 3,
        amplitudes: Amplitudes::Gaussian,
    };
    let map = synthesize(&psd, &grid).unwrap();
    let dir = std::env::temp_dir().join(format!("stiction-plots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("map-{nx}x{ny}.gsf"));
    io::write_path(&path, &map, Format::Gsf).unwrap();
    let run = stiction_model::topography::run(&path, &TopographyRequest::default()).unwrap();
    let _ = std::fs::remove_file(&path);
    TopographyResult::new(run)
}

#[test]
fn a_height_map_is_drawn_at_its_true_aspect_with_a_colour_bar() {
    for (nx, ny) in [(83usize, 204usize), (204, 83), (64, 64)] {
        let svg = topography(nx, ny).svg().unwrap();
        let d = doc(&svg);
        // the map's cells: the filled rectangles of the first panel left of its colour bar
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        let mut bar = 0;
        for n in d.descendants().filter(|n| n.has_tag_name("rect")) {
            let fill = n.attribute("fill").unwrap_or("none");
            if fill == "none" || fill.eq_ignore_ascii_case("#FFFFFF") {
                continue;
            }
            let (x, y, w, h) = (num(n, "x"), num(n, "y"), num(n, "width"), num(n, "height"));
            if x + w <= 310.0 {
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x + w), y0.min(y), y1.max(y + h));
            } else if x < 400.0 {
                bar += 1;
            }
        }
        let (w, h) = (x1 - x0, y1 - y0);
        let want = nx as f64 / ny as f64;
        // cells are whole pixels: the aspect within two pixels of the longer side
        let tol = 2.0 / w.max(h) * want.max(1.0 / want) * 2.0;
        assert!(
            (w / h - want).abs() <= tol.max(0.02 * want),
            "{nx} x {ny} um drawn {w} x {h} px (aspect {} for {want})",
            w / h
        );
        assert!(bar >= 32, "{nx} x {ny}: a colour bar of {bar} steps");
        assert!(svg.contains("height [nm]"), "the colour bar's unit");
    }
}

/// The legend box (the black-bordered rectangle) of a one-panel figure: (x0, y0, x1, y1).
fn legend_box(svg: &str) -> (f64, f64, f64, f64) {
    let d = doc(svg);
    let r = d
        .descendants()
        .filter(|n| n.has_tag_name("rect"))
        .find(|n| n.attribute("fill") == Some("none") && n.attribute("stroke") == Some("#000000"))
        .expect("a legend box");
    let (x, y) = (num(r, "x"), num(r, "y"));
    (x, y, x + num(r, "width"), y + num(r, "height"))
}

/// Every point along the data's polylines (stroke width 2, more than 2 points), every px.
fn data_pixels(svg: &str) -> Vec<(f64, f64)> {
    let d = doc(svg);
    let mut out = Vec::new();
    for n in d.descendants().filter(|n| n.has_tag_name("polyline")) {
        let p: Vec<f64> = n
            .attribute("points")
            .unwrap_or("")
            .split([' ', ','])
            .filter(|t| !t.is_empty())
            .map(|t| t.parse().unwrap())
            .collect();
        if n.attribute("stroke-width") != Some("2") || p.len() < 6 {
            continue;
        }
        for w in p.chunks(2).collect::<Vec<_>>().windows(2) {
            let (a, b) = ((w[0][0], w[0][1]), (w[1][0], w[1][1]));
            let n = (a.0 - b.0).abs().max((a.1 - b.1).abs()).ceil().max(1.0) as usize;
            out.extend((0..=n).map(|k| {
                let t = k as f64 / n as f64;
                (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
            }));
        }
    }
    out
}

#[test]
fn the_legend_sits_where_it_hides_no_data() {
    // a falling line (upper left to lower right) and a rising one: only the upper right
    // and lower left corners are free; a line along the bottom leaves the top free
    let line = |pts: Vec<(f64, f64)>, name: &str| Series {
        name: name.into(),
        points: pts,
        colour: None,
    };
    let xs: Vec<f64> = (0..=50).map(|k| f64::from(k) / 50.0).collect();
    for (case, series) in [
        (
            "falling",
            vec![line(
                xs.iter().map(|&x| (x, 1.0 - x)).collect(),
                "falling line",
            )],
        ),
        (
            "along the bottom",
            vec![
                line(xs.iter().map(|&x| (x, 0.02 * x)).collect(), "low line"),
                line(
                    xs.iter().map(|&x| (x, 1.0 - 0.02 * x)).collect(),
                    "high line",
                ),
                line(xs.iter().map(|&x| (x, 0.5)).collect(), "middle line"),
            ],
        ),
    ] {
        let svg = plot::svg(
            case,
            &[Panel {
                x_label: "x [-]".into(),
                y_label: "y [-]".into(),
                series,
                x_range: Some((0.0, 1.0)),
                y_range: Some((0.0, 1.0)),
                ..Default::default()
            }],
        )
        .unwrap();
        let (x0, y0, x1, y1) = legend_box(&svg);
        let hidden = data_pixels(&svg)
            .into_iter()
            .filter(|p| (x0..=x1).contains(&p.0) && (y0..=y1).contains(&p.1))
            .count();
        assert_eq!(
            hidden, 0,
            "{case}: the legend ({x0}, {y0})-({x1}, {y1}) hides {hidden} px of data"
        );
    }
}
