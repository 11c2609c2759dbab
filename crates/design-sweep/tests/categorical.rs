//! Categorical axes (`FIELD=WORD,WORD,...`): parsing, the words an evaluator receives and
//! the files carry, the crossings of each word, shards merged byte for byte, refusals, the
//! plot.

mod common;

use common::laws::{run, LAWS};
use design_sweep::{merge, Axis, DesignError, Level, Map, Shard};

fn axis_err(option: &str) -> String {
    match Axis::parse(option) {
        Err(e @ DesignError::Axis { .. }) => e.to_string(),
        other => panic!("{option}: expected an axis error, got {other:?}"),
    }
}

#[test]
fn a_word_list_parses_as_a_categorical_axis_in_its_order() {
    let a = Axis::parse(LAWS).unwrap();
    assert!(a.is_categorical());
    assert_eq!(a.field, "contact.plasticity_law");
    assert_eq!(a.words, ["etsion_kadin", "kogut_etsion", "elastic"]);
    assert_eq!(a.n, 3);
    // laid out as the codes of the words
    assert_eq!(a.values, [0.0, 1.0, 2.0]);
    assert_eq!(a.level(1), Level::Word("kogut_etsion"));
    assert_eq!(a.describe(), LAWS);
    // spaces around the words are dropped; one word is an axis of one value
    let b = Axis::parse("contact.reload= bounded , as_printed").unwrap();
    assert_eq!(b.words, ["bounded", "as_printed"]);
    assert_eq!(Axis::parse("contact.reload=bounded").unwrap().n, 1);
    assert_eq!(
        Axis::categorical("contact.reload", &["bounded", "as_printed"]).unwrap(),
        b
    );
    // a numeric axis has no words
    let k = Axis::parse("switch.k_s=1e9:1e11:log:3").unwrap();
    assert!(!k.is_categorical() && k.words.is_empty());
    assert_eq!(k.level(2), Level::Number(1e11));
}

#[test]
fn a_word_list_that_is_not_one_is_refused_with_the_option_and_the_word() {
    // numbers are varied as FROM:TO:lin|log:N: a list of them is not a categorical axis
    let e = axis_err("switch.k_s=1e9,2e9");
    assert!(
        e.contains("switch.k_s=1e9,2e9") && e.contains("`1e9` is a number"),
        "{e}"
    );
    assert!(e.contains("FIELD=FROM:TO:lin|log:N"), "{e}");
    let e = axis_err("contact.reload=bounded,inf");
    assert!(e.contains("`inf` is a number"), "{e}");
    let e = axis_err("contact.plasticity_law=etsion_kadin,,elastic");
    assert!(e.contains("word 2") && e.contains("empty"), "{e}");
    let e = axis_err("contact.plasticity_law=");
    assert!(e.contains("word 1") && e.contains("empty"), "{e}");
    let e = axis_err("contact.plasticity_law=etsion_kadin,etsion_kadin");
    assert!(e.contains("`etsion_kadin` is listed twice"), "{e}");
    let e = axis_err("contact.plasticity_law=etsion-kadin");
    assert!(e.contains("`etsion-kadin`") && e.contains("letters"), "{e}");
    let e = axis_err("plasticity_law=etsion_kadin");
    assert!(e.contains("section.key"), "{e}");
    // with a colon it is the numeric form, and its own errors
    let e = axis_err("contact.plasticity_law=etsion_kadin:kogut_etsion:lin:2");
    assert!(e.contains("FROM `etsion_kadin` is not a number"), "{e}");
    let e = axis_err("contact.plasticity_law etsion_kadin");
    assert!(e.contains("FIELD=WORD,WORD"), "{e}");
}

#[test]
fn a_map_file_whose_word_is_not_the_grids_is_refused() {
    let map = run(&[LAWS], None);
    let text = map.to_json();
    let bad = text.replacen(
        "\"contact.plasticity_law\": \"kogut_etsion\"",
        "\"contact.plasticity_law\": \"elastic\"",
        1,
    );
    assert_ne!(bad, text);
    let e = Map::from_json(&bad).unwrap_err().to_string();
    assert!(
        e.contains("point 1") && e.contains("contact.plasticity_law") && e.contains("kogut_etsion"),
        "{e}"
    );
    // a number where the grid has a word
    let bad = text.replacen(
        "\"contact.plasticity_law\": \"etsion_kadin\"",
        "\"contact.plasticity_law\": 0.0",
        1,
    );
    assert!(Map::from_json(&bad).is_err());
    // an axis with both forms, or words that do not match n
    let bad = text.replacen("\"n\": 3", "\"n\": 2", 1);
    assert!(Map::from_json(&bad)
        .unwrap_err()
        .to_string()
        .contains("3 words for n = 2"));
    let bad = text.replacen(
        "\"words\"",
        "\"values\": [0.0, 1.0, 2.0],\n      \"words\"",
        1,
    );
    assert!(Map::from_json(&bad)
        .unwrap_err()
        .to_string()
        .contains("either"));
}

#[test]
fn merge_refuses_parts_whose_word_lists_differ() {
    let part = |laws: &str, k: usize| {
        let m = run(
            &[laws, "switch.k_s=1e3:1e4:log:3"],
            Some(Shard::new(k, 2).unwrap()),
        );
        Map::from_json(&m.to_json()).unwrap()
    };
    let refuse = |other: &str| match merge(vec![
        ("maps/a".to_string(), part(LAWS, 1)),
        ("maps/b".to_string(), part(other, 2)),
    ]) {
        Err(e @ DesignError::Merge { .. }) => e.to_string(),
        r => panic!("{other}: expected a refusal, got {r:?}"),
    };
    // another word, another order, one word fewer
    for other in [
        "contact.plasticity_law=etsion_kadin,kogut_etsion,my_law",
        "contact.plasticity_law=kogut_etsion,etsion_kadin,elastic",
        "contact.plasticity_law=etsion_kadin,kogut_etsion",
    ] {
        let e = refuse(other);
        assert!(e.contains("maps/b"), "{e}");
        assert!(
            e.contains("the words of contact.plasticity_law")
                && e.contains("etsion_kadin, kogut_etsion, elastic"),
            "{e}"
        );
    }
    // numbers where the other part has words
    let e = refuse("contact.plasticity_law=0:2:lin:3");
    assert!(
        e.contains("numbers, contact.plasticity_law=0e0:2e0:lin:3"),
        "{e}"
    );
}
