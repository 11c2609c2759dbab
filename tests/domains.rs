//! The scene-key table of docs/validation.md is the key registry's: every key with its
//! unit, domain and default, nothing more, nothing less. (`tests/cli_errors.rs` checks that
//! each numeric domain is enforced at both ends.)

use stiction::model::keys::{markdown_table, KEYS};

const BEGIN: &str = "<!-- scene fields: begin -->";
const END: &str = "<!-- scene fields: end -->";

fn documented() -> String {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/validation.md"))
        .unwrap();
    let a = doc.find(BEGIN).expect("begin marker") + BEGIN.len();
    let b = doc.find(END).expect("end marker");
    doc[a..b].trim().to_string()
}

#[test]
fn the_documented_domains_are_the_enforced_ones() {
    assert_eq!(
        documented(),
        markdown_table().trim(),
        "docs/validation.md's scene-field table is stale: run `cargo xtask docs`"
    );
}

#[test]
fn every_key_is_documented_once() {
    let doc = documented();
    for f in KEYS {
        let row = format!("| `{}` |", f.key);
        assert_eq!(
            doc.lines().filter(|l| l.starts_with(&row)).count(),
            1,
            "{}",
            f.key
        );
    }
    // header, separator and one row per key
    assert_eq!(doc.lines().count(), KEYS.len() + 2);
}
