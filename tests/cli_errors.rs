//! Bad input gets a clear error naming the field or option and the value, exit status 2
//! (bad input) or 1 (numerical failure), and never a panic.

mod common;
use common::{stiction, temp_file};
use proptest::prelude::*;
use stiction::model::keys::{self, Domain, Kind};
use stiction::model::laws::LawRegistry;
use stiction::model::scene::{self, Scene};
use stiction::model::spec::{AsperitySpec, Spec, SurfaceSpec, SwitchSpec};

/// Replaces the line of the default `kind` scene starting with `key =` by `line`
/// (appends it when `key` is empty).
fn edit(kind: &str, key: &str, line: &str) -> String {
    let base = match kind {
        "asperity" => scene::PAPER_ASPERITY,
        "surface" => scene::PAPER_SURFACE,
        _ => scene::PAPER_SWITCH,
    };
    if key.is_empty() {
        return format!("{line}\n{base}\n");
    }
    let mut found = false;
    let text: Vec<String> = base
        .lines()
        .map(|l| {
            if !found && l.trim_start().starts_with(&format!("{key} =")) {
                found = true;
                line.to_string()
            } else {
                l.to_string()
            }
        })
        .collect();
    assert!(found, "no key {key} in the {kind} scene");
    text.join("\n")
}

struct Case {
    name: &'static str,
    kind: &'static str,
    scene: Option<Vec<u8>>,
    args: Vec<&'static str>,
    fragments: Vec<&'static str>,
    code: i32,
}

fn scene_case(
    name: &'static str,
    kind: &'static str,
    key: &str,
    line: &str,
    fragments: &[&'static str],
) -> Case {
    Case {
        name,
        kind,
        scene: Some(edit(kind, key, line).into_bytes()),
        args: vec![],
        fragments: fragments.to_vec(),
        code: 2,
    }
}

fn arg_case(name: &'static str, args: &[&'static str], fragments: &[&'static str]) -> Case {
    Case {
        name,
        kind: "",
        scene: None,
        args: args.to_vec(),
        fragments: fragments.to_vec(),
        code: 2,
    }
}

fn cases() -> Vec<Case> {
    vec![
        scene_case(
            "negative modulus",
            "asperity",
            "youngs_modulus",
            "youngs_modulus = -410e9",
            &["contact.youngs_modulus", "-4.1e11", "[1e6, 1e13]"],
        ),
        scene_case(
            "huge modulus in scientific notation",
            "switch",
            "youngs_modulus",
            "youngs_modulus = 1e308",
            &["contact.youngs_modulus", "= 1e308"],
        ),
        scene_case(
            "nu = 0.5",
            "asperity",
            "poisson_ratio",
            "poisson_ratio = 0.5",
            &["contact.poisson_ratio", "5e-1", "[0e0, 5e-1)"],
        ),
        scene_case(
            "nu negative",
            "asperity",
            "poisson_ratio",
            "poisson_ratio = -0.1",
            &["contact.poisson_ratio", "-1e-1"],
        ),
        scene_case(
            "nu wrong type",
            "asperity",
            "poisson_ratio",
            "poisson_ratio = \"abc\"",
            &[
                "invalid `contact.poisson_ratio` = \"abc\"",
                "must be a number",
            ],
        ),
        scene_case(
            "NaN yield stress",
            "asperity",
            "yield_stress",
            "yield_stress = nan",
            &["contact.yield_stress", "NaN"],
        ),
        scene_case(
            "yield stress below its lower bound",
            "switch",
            "yield_stress",
            "yield_stress = 999.999999",
            &["contact.yield_stress", "9.99999999e2", "[1e3, inf]"],
        ),
        scene_case(
            "tiny yield stress",
            "switch",
            "yield_stress",
            "yield_stress = 1e-300",
            &["contact.yield_stress", "1e-300"],
        ),
        scene_case(
            "infinite yield with Etsion-Kadin",
            "asperity",
            "yield_stress",
            "yield_stress = inf",
            &["use \"elastic\" for no yield"],
        ),
        scene_case(
            "misspelled key",
            "asperity",
            "radius",
            "radus = 4e-6",
            &[
                "unknown key `contact.radus`",
                "did you mean `contact.radius`?",
            ],
        ),
        scene_case(
            "missing key",
            "asperity",
            "radius",
            "",
            &["missing `contact.radius`"],
        ),
        scene_case(
            "missing eq-1 reading explains both",
            "switch",
            "yield_modulus",
            "",
            &["contact.yield_modulus", "as_printed", "composite", "100x"],
        ),
        scene_case(
            "unknown top-level key",
            "switch",
            "",
            "colour = \"red\"",
            &["unknown key `colour`"],
        ),
        scene_case(
            "zero work of adhesion",
            "asperity",
            "work_of_adhesion",
            "work_of_adhesion = 0.0",
            &["contact.work_of_adhesion", "= 0e0"],
        ),
        scene_case(
            "work of adhesion below 1e-6",
            "switch",
            "work_of_adhesion",
            "work_of_adhesion = 9.99999999e-07",
            &["contact.work_of_adhesion", "9.99999999e-7", "[1e-6, 1e2]"],
        ),
        scene_case(
            "tiny work of adhesion",
            "switch",
            "work_of_adhesion",
            "work_of_adhesion = 1e-300",
            &["contact.work_of_adhesion", "1e-300"],
        ),
        scene_case(
            "negative z0",
            "asperity",
            "z0",
            "z0 = -1e-10",
            &["contact.z0", "-1e-10"],
        ),
        scene_case(
            "unknown adhesion law",
            "asperity",
            "adhesion_law",
            "adhesion_law = \"lennard_jones\"",
            &[
                "invalid `contact.adhesion_law` = \"lennard_jones\"",
                "registered adhesion laws",
            ],
        ),
        scene_case(
            "bad eq-13 constant",
            "asperity",
            "c2",
            "c2 = [10.0, -1.0, 5.0]",
            &["contact.effective_radius.c2[1]", "-1e0"],
        ),
        scene_case(
            "empty delta_max",
            "asperity",
            "delta_max",
            "delta_max = []",
            &["delta_max` = []"],
        ),
        scene_case(
            "one point",
            "asperity",
            "points",
            "points = 1",
            &["`points` = 1"],
        ),
        scene_case(
            "zero roughness",
            "surface",
            "sigma_s",
            "sigma_s = 0.0",
            &["surface.sigma_s", "= 0e0"],
        ),
        scene_case(
            "huge density",
            "surface",
            "asperity_density",
            "asperity_density = 1e30",
            &["surface.asperity_density", "1e30"],
        ),
        scene_case(
            "unknown accuracy",
            "surface",
            "accuracy",
            "accuracy = \"perfect\"",
            &["invalid `accuracy` = \"perfect\""],
        ),
        scene_case(
            "negative impact energy",
            "switch",
            "impact_energy",
            "impact_energy = -0.5",
            &["switch.impact_energy", "-5e-1"],
        ),
        scene_case(
            "impact energy and k_s",
            "switch",
            "impact_energy",
            "impact_energy = 0.5\nk_s = 1e9",
            &["not both"],
        ),
        scene_case(
            "neither impact energy nor k_s",
            "switch",
            "impact_energy",
            "",
            &["switch.impact_energy", "give impact_energy"],
        ),
        scene_case(
            "voltage with impact energy",
            "switch",
            "impact_energy",
            "impact_energy = 0.5\nvoltage = 40.0",
            &["switch.voltage", "k_s"],
        ),
        scene_case(
            "derived impact energy out of range",
            "switch",
            "impact_energy",
            "k_s = 1e9\nvoltage = 3e4",
            &["switch.impact_energy", "derived from k_s", "[1e-9, 1e2]"],
        ),
        scene_case(
            "permittivity below one",
            "switch",
            "epsilon_r",
            "epsilon_r = 0.5",
            &["switch.epsilon_r", "5e-1"],
        ),
        scene_case(
            "contact fraction above one",
            "switch",
            "contact_area_fraction",
            "contact_area_fraction = 1.5",
            &["switch.contact_area_fraction", "1.5e0", "(0e0, 1e0]"],
        ),
        scene_case(
            "zero cycles",
            "switch",
            "cycles",
            "cycles = 0",
            &["`cycles` = 0"],
        ),
        scene_case(
            "counter material without modulus",
            "asperity",
            "counter",
            "counter = \"material\"",
            &["counter_youngs_modulus` = missing"],
        ),
        scene_case(
            "counter key without counter material",
            "asperity",
            "counter",
            "counter = \"rigid\"\ncounter_yield_stress = 1e9",
            &["contact.counter_yield_stress", "absent unless"],
        ),
        scene_case(
            "string for a number",
            "switch",
            "d0",
            "d0 = \"2 um\"",
            &["invalid `switch.d0` = \"2 um\"", "must be a number"],
        ),
        Case {
            name: "empty file",
            kind: "asperity",
            scene: Some(vec![]),
            args: vec![],
            fragments: vec!["empty scene file"],
            code: 2,
        },
        Case {
            name: "garbage bytes",
            kind: "asperity",
            scene: Some(vec![0xff, 0xfe, 0x00, 0x80, 0x13]),
            args: vec![],
            fragments: vec!["not UTF-8"],
            code: 2,
        },
        Case {
            name: "broken TOML",
            kind: "surface",
            scene: Some(b"[contact\nyoungs_modulus = ".to_vec()),
            args: vec![],
            fragments: vec!["TOML parse error"],
            code: 2,
        },
        Case {
            name: "scene over 1 MiB",
            kind: "switch",
            scene: Some(vec![b'#'; (1 << 20) + 10]),
            args: vec![],
            fragments: vec!["larger than 1048576 bytes"],
            code: 2,
        },
        arg_case(
            "negative lambda",
            &["md", "--lambda", "-1"],
            &["invalid --lambda", "-1e0"],
        ),
        arg_case(
            "NaN lambda",
            &["md", "--lambda", "NaN"],
            &["invalid --lambda", "NaN"],
        ),
        arg_case(
            "retract without from",
            &["md", "--lambda", "1", "--delta", "0", "--path", "retract"],
            &["--path retract", "needs --from"],
        ),
        arg_case(
            "negative points names the option",
            &["md", "--lambda", "1", "--points", "-5"],
            &["--points", "-5"],
        ),
        arg_case(
            "negative cycles names the option",
            &["switch", "--cycles", "-1"],
            &["--cycles", "-1"],
        ),
        arg_case(
            "too many cycles names the option and its domain",
            &["switch", "--cycles", "5000"],
            &["--cycles", "5000", "an integer in [1, 1000]"],
        ),
        arg_case(
            "zero cycles names the option",
            &["switch", "--cycles", "0"],
            &["invalid --cycles: 0:", "an integer in [1, 1000]"],
        ),
        arg_case(
            "negative delta_max flag names the option",
            &["asperity", "--delta-max", "-1e-9"],
            &["invalid --delta-max", "-1e-9"],
        ),
        arg_case(
            "unload_from out of range names the option",
            &["surface", "--unload-from", "1e308"],
            &["invalid --unload-from", "1e308", "[-2e-5, 2e-5]"],
        ),
        arg_case(
            "unload_from beyond 20 sigma_s names the option and the rule",
            &["surface", "--unload-from", "1e-5"],
            &["invalid --unload-from", "1e-5 m", "20 sigma_s"],
        ),
        arg_case(
            "missing scene file",
            &["asperity", "--scene", "/nonexistent/scene.toml"],
            &["cannot read"],
        ),
        arg_case(
            "unknown subcommand",
            &["frobnicate"],
            &["unrecognized subcommand"],
        ),
        arg_case(
            "not a number",
            &["md", "--lambda", "one"],
            &["invalid value 'one'", "--lambda"],
        ),
        // md's path options belong to one point, and a retraction stays within its excursion
        arg_case(
            "md --from without a point",
            &["md", "--lambda", "0.5", "--from", "3"],
            &["invalid --from", "applies to one point"],
        ),
        arg_case(
            "md retract point beyond its excursion",
            &[
                "md", "--lambda", "0.5", "--delta", "4", "--path", "retract", "--from", "3",
            ],
            &[
                "invalid --delta",
                "at most the excursion's extreme from = 3",
            ],
        ),
        // a misspelt section: the switch keys under it are unknown, and that is said
        // before "missing switch.d0" (the QA case of the tenth stop)
        Case {
            name: "misspelt section",
            kind: "switch",
            scene: Some(
                scene::PAPER_SWITCH
                    .replace("[switch]", "[switchx]")
                    .into_bytes(),
            ),
            args: vec![],
            fragments: vec!["unknown key `switchx`"],
            code: 2,
        },
        // an option replacing what --set gave would drop the --set value unread, an invalid
        // one included (the QA case of the tenth stop: exit 0 with cycles = nan)
        arg_case(
            "--set overridden by an option",
            &[
                "switch",
                "--accuracy",
                "fast",
                "--cycles",
                "2",
                "--set",
                "cycles=nan",
            ],
            &["invalid --cycles", "also set by --set cycles"],
        ),
        arg_case(
            "--set overridden by --vary",
            &[
                "design",
                "map",
                "--vary",
                "surface.sigma_s=2e-9:1e-7:log:3",
                "--set",
                "surface.sigma_s=5e-9",
                "--out",
                "/nonexistent/never-written",
            ],
            &["invalid --vary", "also set by --set surface.sigma_s"],
        ),
        arg_case(
            "--set overridden by --scatter",
            &[
                "design",
                "probability",
                "--scatter",
                "surface.sigma_s=lognormal(7.78e-9,1.1)",
                "--set",
                "surface.sigma_s=5e-9",
                "--samples",
                "10",
            ],
            &["invalid --scatter", "also set by --set surface.sigma_s"],
        ),
        // a valid but huge run is refused before it computes (../shared/repro D13)
        Case {
            name: "curve output bounded",
            kind: "switch",
            scene: Some(
                edit("switch", "points", "points = 100000")
                    .replace("cycles = 10 ", "cycles = 1000 ")
                    .into_bytes(),
            ),
            args: vec![],
            fragments: vec![
                "`points` = 100000",
                "at most 1e4 with cycles = 1000",
                "1e8 curve points",
            ],
            code: 2,
        },
        // eq 13's constants beyond any fit are refused naming the key at validation,
        // not deep in the surface law
        scene_case(
            "effective-radius constant 1e308",
            "switch",
            "c1",
            "c1 = [1e308, 0.6242, 0.092]",
            &["contact.effective_radius.c1[0]", "= 1e308", "[-1e6, 1e6]"],
        ),
        scene_case(
            "effective-radius constant -1e308",
            "switch",
            "c2",
            "c2 = [10.0, 10.0, -1e308]",
            &["contact.effective_radius.c2[2]", "= -1e308", "[-1e6, 1e6]"],
        ),
        // a numerical failure: a sparse, very smooth surface cannot absorb 100 J/m^2
        Case {
            name: "energy the surface cannot absorb",
            kind: "switch",
            scene: Some(
                edit("switch", "impact_energy", "impact_energy = 100.0")
                    .replace("sigma_s = 7.78e-9", "sigma_s = 1e-11")
                    .replace("asperity_density = 1e13", "asperity_density = 1e9")
                    .replace("points = 200", "points = 0")
                    .replace("accuracy = \"accurate\"", "accuracy = \"fast\"")
                    .into_bytes(),
            ),
            args: vec![],
            fragments: vec!["cannot absorb impact energy 1e2"],
            code: 1,
        },
    ]
}

#[test]
fn bad_inputs_get_a_named_error_and_the_right_exit_status() {
    let cases = cases();
    assert!(cases.len() >= 40);
    for (i, c) in cases.iter().enumerate() {
        let mut args: Vec<String> = c.args.iter().map(|s| s.to_string()).collect();
        if let Some(bytes) = &c.scene {
            let f = temp_file(&format!("bad-{i}"), bytes);
            args = vec![
                c.kind.to_string(),
                "--scene".into(),
                f.to_string_lossy().into(),
            ];
        }
        let argv: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = stiction(&argv);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(c.code),
            "{}: status {:?}, stderr {err}",
            c.name,
            out.status.code()
        );
        for fragment in &c.fragments {
            assert!(
                err.contains(fragment),
                "{}: stderr lacks `{fragment}`:\n{err}",
                c.name
            );
        }
        assert!(!err.contains("panicked"), "{}: panic", c.name);
        // numbers never print with hundreds of digits
        assert!(
            !err.contains("0000000000000000"),
            "{}: a number in full: {err}",
            c.name
        );
        if c.scene.is_some() {
            assert!(
                err.contains(".toml"),
                "{}: the file is not named: {err}",
                c.name
            );
        }
    }
}

/// Every numeric key's domain is checked where the scene is validated: a value just
/// outside each end of its domain is refused naming the key (the table in
/// docs/validation.md is checked against the same registry in tests/domains.rs).
#[test]
fn every_numeric_domain_is_enforced_at_both_ends() {
    let registry = LawRegistry::builtin();
    for f in keys::KEYS.iter().filter(|f| f.in_kind(Kind::Switch)) {
        let (lo, hi) = match f.domain {
            Domain::Range { lo, hi, .. } => (lo, hi),
            Domain::RangeOrInfinite { lo } => (lo, f64::INFINITY),
            _ => continue,
        };
        if f.key == "switch.k_s"
            || f.key == "switch.voltage"
            || f.key.starts_with("contact.counter")
            || f.key.starts_with("dynamics.")
        {
            // keys of the other drive, of counter = "material" (checked above) or of a
            // [dynamics] section (which takes drive B: crates/stiction-model/tests/registry.rs
            // checks their domains at both ends)
            continue;
        }
        for bad in [lo - lo.abs().max(1e-300) * 1e-6 - 1e-300, hi * (1.0 + 1e-6)] {
            if !bad.is_finite() {
                continue;
            }
            let mut s = Scene::paper(Kind::Switch);
            if s.set_number(f.key, bad).is_err() {
                continue; // an integer key refuses a fraction before validation
            }
            let e = SwitchSpec::new(&s, &registry).expect_err(f.key).to_string();
            assert!(e.contains(f.key), "{}: {e}", f.key);
        }
    }
}

/// Parses `text` as a scene and validates it as each kind of scene and as the kind it
/// says or implies: errors are expected, panics are not.
fn parse_all(text: &str) {
    let registry = LawRegistry::builtin();
    if let Ok(scene) = Scene::from_toml_str("fuzz", text) {
        let _ = AsperitySpec::new(&scene, &registry);
        let _ = SurfaceSpec::new(&scene, &registry);
        let _ = SwitchSpec::new(&scene, &registry);
        let _ = Spec::new(&scene, &registry);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn random_bytes_never_panic_the_scene_parser(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        parse_all(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn mutated_default_scenes_never_panic(line in 0usize..60, value in prop_oneof![
        Just("nan".to_string()), Just("inf".to_string()), Just("-inf".to_string()), Just("-1".to_string()),
        Just("0".to_string()), Just("1e308".to_string()), Just("\"x\"".to_string()), Just("[]".to_string()),
        Just("{}".to_string()), Just("true".to_string()), any::<f64>().prop_map(|x| format!("{x:e}")),
        any::<i64>().prop_map(|x| x.to_string()),
    ], drop in any::<bool>()) {
        for base in [scene::PAPER_ASPERITY, scene::PAPER_SURFACE, scene::PAPER_SWITCH] {
            let lines: Vec<&str> = base.lines().collect();
            let i = line % lines.len();
            let mut out: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
            if drop {
                out.remove(i);
            } else if let Some((k, _)) = lines[i].split_once('=') {
                out[i] = format!("{k}= {value}");
            }
            parse_all(&out.join("\n"));
        }
    }
}
