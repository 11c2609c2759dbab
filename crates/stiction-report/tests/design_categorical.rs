//! Categorical axes (`FIELD=WORD,WORD,...`): parsing, the words an evaluator receives and
//! the files carry, the crossings of each word, shards merged byte for byte, refusals, the
//! plot.

mod common;

use common::laws::{run, scale, LAWS};
use design_sweep::{merge, Labels, Level, Map, Shard, Status};
use serde_json::{json, Value};
use stiction_report::csv::map_csv;
use stiction_report::design_table::map_table;
use stiction_report::plot::map::map_svg;

fn labels() -> Labels {
    Labels::new().with_unit("switch.k_s", "Pa/m")
}

#[test]
fn the_evaluator_receives_the_words_and_the_files_carry_them() {
    let map = run(&[LAWS, "switch.k_s=1e3:1e4:log:3"], None);
    assert_eq!(map.points().len(), 9);
    let g = map.grid();
    assert_eq!(
        g.levels(4),
        [
            Level::Word("kogut_etsion"),
            Level::Number(g.axes()[1].values[1])
        ]
    );
    for p in map.points() {
        assert_eq!(p.status, Status::Ok);
        let idx = g.indices(p.index);
        let word = &g.axes()[0].words[idx[0]];
        let k = g.axes()[1].values[idx[1]];
        let want = scale(word).unwrap() * (2e3 / k).powi(2);
        assert_eq!(p.ratio(), Some(want), "{word} at {k}");
    }
    // map.csv: the word in the field's column
    let csv = map_csv(&map).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert!(rows[0].starts_with("contact.plasticity_law,switch.k_s,pull_out_ratio,"));
    assert!(rows[1].starts_with("etsion_kadin,1e3,"), "{}", rows[1]);
    assert!(rows[5].starts_with("kogut_etsion,"), "{}", rows[5]);
    assert!(rows[9].starts_with("elastic,1e4,"), "{}", rows[9]);
    // map.json: the word at every point, the words in the grid
    let v: Value = serde_json::from_str(&map.to_json()).unwrap();
    assert_eq!(
        v["grid"]["axes"][0],
        json!({"field": "contact.plasticity_law", "words": ["etsion_kadin", "kogut_etsion", "elastic"], "n": 3})
    );
    // the numeric axis keeps its keys, in their order
    let text = map.to_json();
    let at = text.find("\"field\": \"switch.k_s\"").unwrap();
    let order: Vec<usize> = ["\"from\"", "\"to\"", "\"spacing\"", "\"n\"", "\"values\""]
        .iter()
        .map(|k| at + text[at..].find(k).unwrap())
        .collect();
    assert!(order.windows(2).all(|w| w[0] < w[1]), "{text}");
    assert_eq!(v["grid"]["axes"][1].as_object().unwrap().len(), 6);
    assert_eq!(
        v["points"][3]["values"]["contact.plasticity_law"],
        "kogut_etsion"
    );
    assert_eq!(v["points"][3]["values"]["switch.k_s"], 1e3);
    // read back exactly
    assert_eq!(Map::from_json(&map.to_json()).unwrap(), map);
}

#[test]
fn each_word_has_its_own_boundary_along_the_numeric_axis() {
    // the categorical axis second this time: the boundary does not depend on the order
    for specs in [
        [LAWS, "switch.k_s=1e3:1e4:log:31"],
        ["switch.k_s=1e3:1e4:log:31", LAWS],
    ] {
        let map = run(&specs, None);
        assert!(map.boundary_1d().is_empty() && map.boundary_2d().is_empty());
        let b = map.boundary_by_word();
        let words: Vec<&str> = b.iter().map(|w| w.word.as_str()).collect();
        assert_eq!(words, ["etsion_kadin", "kogut_etsion", "elastic"]);
        for w in &b {
            assert_eq!(w.field, "contact.plasticity_law");
            assert_eq!(w.crossings.len(), 1, "{}", w.word);
            let c = w.crossings[0];
            // log10 ratio is linear in log10 k: the interpolated crossing is exact
            let exact = 2e3 * scale(&w.word).unwrap().sqrt();
            assert!(
                (c.value / exact - 1.0).abs() < 1e-12,
                "{}: {}",
                w.word,
                c.value
            );
            assert_eq!(c.free_side, design_sweep::FreeSide::Above);
        }
        let t = map_table(&map, &labels());
        assert!(
            t.contains(
                "boundary        contact.plasticity_law = kogut_etsion: switch.k_s ~ 2828 Pa/m"
            ),
            "{t}"
        );
        assert!(
            t.contains("etsion_kadin, kogut_etsion, elastic (3 words)"),
            "{t}"
        );
    }
    // 1-D over the words: no crossing between words, each word's ratio in the table
    let map = run(&[LAWS], None);
    assert!(map.boundary_1d().is_empty());
    let t = map_table(&map, &labels());
    assert!(
        t.contains("contact.plasticity_law = kogut_etsion: 8 (sticks)"),
        "{t}"
    );
    assert!(
        t.contains("contact.plasticity_law = elastic: 2 (sticks)"),
        "{t}"
    );
}

#[test]
fn shards_of_a_categorical_map_merge_into_the_whole_map_byte_for_byte() {
    let specs = [LAWS, "switch.k_s=1e3:1e4:log:5"];
    let whole = run(&specs, None);
    let files = |m: &Map| {
        (
            map_csv(m).unwrap(),
            m.to_json(),
            map_svg(m, &labels()).unwrap(),
        )
    };
    let parts: Vec<(String, Map)> = (1..=4)
        .rev()
        .map(|k| {
            let m = run(&specs, Some(Shard::new(k, 4).unwrap()));
            let back = Map::from_json(&m.to_json()).unwrap();
            assert_eq!(back, m);
            (format!("maps/part-{k}"), back)
        })
        .collect();
    assert_eq!(files(&merge(parts).unwrap()), files(&whole));
}

#[test]
fn the_plot_draws_one_curve_per_word_and_labels_the_words() {
    let map = run(&["switch.k_s=1e3:1e4:log:9", LAWS], None);
    let svg = map_svg(&map, &labels()).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
    let texts = common::svg_texts(&doc);
    for w in ["etsion_kadin", "kogut_etsion", "elastic"] {
        assert!(
            texts.contains(&format!("contact.plasticity_law = {w}").as_str()),
            "{w}: {texts:?}"
        );
    }
    assert!(texts.contains(&"switch.k_s [Pa/m]"), "{texts:?}");
    // one curve of 9 points per word, each in its own colour
    let curves: Vec<(String, usize)> = doc
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .map(|n| {
            (
                n.attribute("stroke").unwrap_or("").to_owned(),
                n.attribute("points")
                    .unwrap_or("")
                    .split_whitespace()
                    .count(),
            )
        })
        .filter(|(_, n)| *n == 9)
        .collect();
    assert_eq!(curves.len(), 3, "{curves:?}");
    assert!(curves[0].0 != curves[1].0 && curves[1].0 != curves[2].0);
    // 1-D over the words: the words are the tick labels, no line joins them
    let svg = map_svg(&run(&[LAWS], None), &labels()).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts = common::svg_texts(&doc);
    for w in ["etsion_kadin", "kogut_etsion", "elastic"] {
        assert!(texts.contains(&w), "{w}: {texts:?}");
    }
    let joined = doc
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .filter(|n| {
            n.attribute("stroke") == Some("#000000") && n.attribute("stroke-width") == Some("2")
        })
        .count();
    assert_eq!(joined, 0, "no line between words");
    // two categorical axes: a colour map labelled with the words, no contour
    let map = run(&[LAWS, "contact.reload=as_printed,bounded"], None);
    let map = Map::from_json(&map.to_json()).unwrap();
    assert!(map.boundary_2d().is_empty() && map.boundary_by_word().is_empty());
    let svg = map_svg(&map, &labels()).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts = common::svg_texts(&doc);
    assert!(
        texts.contains(&"bounded") && texts.contains(&"elastic"),
        "{texts:?}"
    );
}
