//! A user's own law, registered in a program of theirs (`examples/user_law.rs`), is named
//! by a scene and runs in every command: switch, design threshold, law.

#[path = "../examples/user_law.rs"]
#[allow(dead_code)]
mod user_law;

use clap::Parser;
use stiction::cli::{execute, Cli};
use stiction::commands::Ctx;

mod common;

/// The paper's switch with the flat-top law of the example, as a scene file.
fn scene(delta_cp: f64, hardening: f64) -> std::path::PathBuf {
    use stiction::model::{keys::Kind, scene::Scene, scenegen::to_toml};
    let mut s = Scene::paper(Kind::Switch);
    s.remove("contact.effective_radius");
    s.set_text("contact.plasticity_law", "flat_top").unwrap();
    s.set_number("contact.plasticity.delta_cp", delta_cp)
        .unwrap();
    s.set_number("contact.plasticity.hardening", hardening)
        .unwrap();
    s.set_text("accuracy", "fast").unwrap();
    common::temp_file(
        &format!("user-law-{delta_cp:e}-{hardening}"),
        to_toml(&s).as_bytes(),
    )
}

fn run(args: &[&str]) -> String {
    let registry = user_law::registry();
    let cli = Cli::try_parse_from(std::iter::once("stiction").chain(args.iter().copied()))
        .expect("valid arguments");
    execute(
        cli.command,
        Ctx {
            registry: &registry,
        },
    )
    .unwrap_or_else(|e| panic!("{args:?}: {e}"))
}

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&run(args)).expect("JSON")
}

#[test]
fn a_user_law_that_never_yields_in_range_reproduces_the_elastic_surface() {
    // delta_CP = 1 um: no asperity of a 7.78 nm rough surface reaches it
    let s = scene(1e-6, 0.5);
    let r = json(&[
        "switch",
        "--scene",
        s.to_str().unwrap(),
        "--cycles",
        "2",
        "--format",
        "json",
    ]);
    assert_eq!(r["laws"]["plasticity"], "flat_top");
    let elastic = r["elastic"]["pull_out_pressure"].as_f64().unwrap();
    for c in r["cycles"].as_array().unwrap() {
        let p = c["pull_out_pressure"].as_f64().unwrap();
        assert!((p / elastic - 1.0).abs() < 1e-3, "{p} vs elastic {elastic}");
    }
}

#[test]
fn a_user_law_with_its_parameters_runs_the_design_and_law_commands() {
    let s = scene(2e-9, 0.8);
    let path = s.to_str().unwrap();
    // a flat top that hardens sticks harder than the elastic asperities of the same surface
    let r = json(&[
        "switch", "--scene", path, "--cycles", "3", "--format", "json",
    ]);
    let elastic = r["elastic"]["pull_out_pressure"].as_f64().unwrap();
    let largest = r["largest_pull_out"].as_f64().unwrap();
    assert!(largest > 10.0 * elastic, "{largest} vs {elastic}");
    // the critical work of adhesion: free below it, sticks above it
    let t = json(&[
        "design",
        "threshold",
        "--scene",
        path,
        "--vary",
        "contact.work_of_adhesion",
        "--from",
        "1e-6",
        "--to",
        "1",
        "--format",
        "json",
    ]);
    let c = t["critical_value"]
        .as_f64()
        .unwrap_or_else(|| panic!("a crossing in the range: {t}"));
    assert_eq!(t["free_side"], "below", "{t}");
    for p in t["scan"].as_array().unwrap() {
        if p["status"] != "ok" {
            continue;
        }
        let v = p["value"].as_f64().unwrap();
        let ratio = p["pull_out_ratio"].as_f64().unwrap();
        assert_eq!(ratio < 1.0, v < c, "value {v} ratio {ratio} critical {c}");
    }
    // the tabulated law names the user's law and reads back
    let dir = common::temp_dir("user-law-table");
    let out = dir.join("law");
    run(&[
        "law",
        "--scene",
        path,
        "--d-min",
        "8e-9:6e-9:3",
        "--points",
        "8",
        "--out",
        out.to_str().unwrap(),
    ]);
    let law = stiction::model::contact_law::ContactLaw::from_path(out.join("law.json"))
        .expect("the written law reads back");
    let text = std::fs::read_to_string(out.join("law.json")).unwrap();
    assert!(text.contains("\"flat_top\""));
    assert_eq!(law.branches().len(), 3);
}

#[test]
fn a_user_laws_parameters_are_checked_like_scene_keys() {
    let s = scene(2e-9, 0.8);
    let text = std::fs::read_to_string(&s)
        .unwrap()
        .replace("hardening = 0.8", "hardening = 42.0");
    let bad = common::temp_file("user-law-bad", text.as_bytes());
    let registry = user_law::registry();
    let cli =
        Cli::try_parse_from(["stiction", "switch", "--scene", bad.to_str().unwrap()]).unwrap();
    let e = execute(
        cli.command,
        Ctx {
            registry: &registry,
        },
    )
    .unwrap_err();
    assert_eq!(e.exit_code(), 2);
    let m = e.to_string();
    assert!(
        m.contains("contact.plasticity.hardening")
            && m.contains("4.2e1")
            && m.contains("[0e0, 1e1]"),
        "{m}"
    );
}
