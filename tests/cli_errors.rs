//! Bad input gets a clear error naming the field and value, exit status 2 (bad input)
//! or 1 (numerical failure), and never a panic.

mod common;
use common::{stiction, temp_file};
use proptest::prelude::*;
use stiction::scene::{self, AsperityScene, SurfaceScene, SwitchScene};

/// Replaces the line of the default `kind` scene starting with `key =` by `line`
/// (appends it when `key` is empty).
fn edit(kind: &str, key: &str, line: &str) -> String {
    let base = match kind {
        "asperity" => scene::DEFAULT_ASPERITY,
        "surface" => scene::DEFAULT_SURFACE,
        _ => scene::DEFAULT_SWITCH,
    };
    if key.is_empty() {
        return format!("{base}\n{line}\n");
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
    fragment: &'static str,
    code: i32,
}

fn scene_case(
    name: &'static str,
    kind: &'static str,
    key: &str,
    line: &str,
    fragment: &'static str,
) -> Case {
    Case {
        name,
        kind,
        scene: Some(edit(kind, key, line).into_bytes()),
        args: vec![],
        fragment,
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
            "contact.youngs_modulus` = -410000000000",
        ),
        scene_case(
            "nu = 0.5",
            "asperity",
            "poisson_ratio",
            "poisson_ratio = 0.5",
            "contact.poisson_ratio` = 0.5: must be in [0, 0.5)",
        ),
        scene_case(
            "nu negative",
            "asperity",
            "poisson_ratio",
            "poisson_ratio = -0.1",
            "contact.poisson_ratio` = -0.1",
        ),
        scene_case(
            "nu wrong type",
            "asperity",
            "poisson_ratio",
            "poisson_ratio = \"abc\"",
            "invalid type: string \"abc\", expected f64",
        ),
        scene_case(
            "NaN yield stress",
            "asperity",
            "yield_stress",
            "yield_stress = nan",
            "contact.yield_stress` = NaN",
        ),
        scene_case(
            "infinite yield with Etsion-Kadin",
            "asperity",
            "yield_stress",
            "yield_stress = inf",
            "use \"elastic\" for no yield",
        ),
        scene_case(
            "misspelled key",
            "asperity",
            "radius",
            "radus = 4e-6",
            "unknown field `radus`",
        ),
        scene_case(
            "missing key",
            "asperity",
            "radius",
            "",
            "missing field `radius`",
        ),
        scene_case(
            "unknown top-level key",
            "switch",
            "",
            "colour = \"red\"",
            "unknown field `colour`",
        ),
        scene_case(
            "zero work of adhesion",
            "asperity",
            "work_of_adhesion",
            "work_of_adhesion = 0.0",
            "contact.work_of_adhesion` = 0",
        ),
        scene_case(
            "negative z0",
            "asperity",
            "z0",
            "z0 = -1e-10",
            "contact.z0` = -0.0000000001",
        ),
        scene_case(
            "unknown adhesion law",
            "asperity",
            "adhesion_law",
            "adhesion_law = \"lennard_jones\"",
            "unknown variant `lennard_jones`",
        ),
        scene_case(
            "empty delta_max",
            "asperity",
            "delta_max",
            "delta_max = []",
            "delta_max` = []",
        ),
        scene_case(
            "one point",
            "asperity",
            "points",
            "points = 1",
            "`points` = 1",
        ),
        scene_case(
            "zero roughness",
            "surface",
            "sigma_s",
            "sigma_s = 0.0",
            "surface.sigma_s` = 0",
        ),
        scene_case(
            "huge density",
            "surface",
            "asperity_density",
            "asperity_density = 1e30",
            "surface.asperity_density` = 1000000000000000000000000000000",
        ),
        scene_case(
            "unknown accuracy",
            "surface",
            "accuracy",
            "accuracy = \"perfect\"",
            "unknown variant `perfect`",
        ),
        scene_case(
            "negative impact energy",
            "switch",
            "impact_energy",
            "impact_energy = -0.5",
            "switch.impact_energy` = -0.5",
        ),
        scene_case(
            "impact energy and k_s",
            "switch",
            "impact_energy",
            "impact_energy = 0.5\nk_s = 1e9",
            "not both",
        ),
        scene_case(
            "neither impact energy nor k_s",
            "switch",
            "impact_energy",
            "",
            "switch.impact_energy` = missing",
        ),
        scene_case(
            "permittivity below one",
            "switch",
            "epsilon_r",
            "epsilon_r = 0.5",
            "switch.epsilon_r` = 0.5",
        ),
        scene_case(
            "zero cycles",
            "switch",
            "cycles",
            "cycles = 0",
            "`cycles` = 0",
        ),
        scene_case(
            "counter material without modulus",
            "asperity",
            "counter",
            "counter = \"material\"",
            "counter_youngs_modulus` = missing",
        ),
        scene_case(
            "string for a number",
            "switch",
            "d0",
            "d0 = \"2 um\"",
            "invalid type: string \"2 um\"",
        ),
        Case {
            name: "empty file",
            kind: "asperity",
            scene: Some(vec![]),
            args: vec![],
            fragment: "empty scene file",
            code: 2,
        },
        Case {
            name: "garbage bytes",
            kind: "asperity",
            scene: Some(vec![0xff, 0xfe, 0x00, 0x80, 0x13]),
            args: vec![],
            fragment: "not UTF-8",
            code: 2,
        },
        Case {
            name: "broken TOML",
            kind: "surface",
            scene: Some(b"[contact\nyoungs_modulus = ".to_vec()),
            args: vec![],
            fragment: "TOML parse error",
            code: 2,
        },
        Case {
            name: "negative lambda",
            kind: "md",
            scene: None,
            args: vec!["md", "--lambda", "-1"],
            fragment: "invalid --lambda -1",
            code: 2,
        },
        Case {
            name: "NaN lambda",
            kind: "md",
            scene: None,
            args: vec!["md", "--lambda", "NaN"],
            fragment: "invalid --lambda NaN",
            code: 2,
        },
        Case {
            name: "retract without from",
            kind: "md",
            scene: None,
            args: vec!["md", "--lambda", "1", "--delta", "0", "--path", "retract"],
            fragment: "needs --from",
            code: 2,
        },
        Case {
            name: "negative delta_max flag",
            kind: "asperity",
            scene: None,
            args: vec!["asperity", "--delta-max", "-1e-9"],
            fragment: "delta_max[0]` = -0.000000001",
            code: 2,
        },
        Case {
            name: "missing scene file",
            kind: "asperity",
            scene: None,
            args: vec!["asperity", "--scene", "/nonexistent/scene.toml"],
            fragment: "cannot read",
            code: 2,
        },
        Case {
            name: "unknown subcommand",
            kind: "md",
            scene: None,
            args: vec!["frobnicate"],
            fragment: "unrecognized subcommand",
            code: 2,
        },
        Case {
            name: "not a number",
            kind: "md",
            scene: None,
            args: vec!["md", "--lambda", "one"],
            fragment: "invalid value 'one'",
            code: 2,
        },
        // a numerical failure: a sparse, very smooth surface cannot absorb 100 J/m^2
        Case {
            name: "energy the surface cannot absorb",
            kind: "switch",
            scene: Some(
                edit("switch", "impact_energy", "impact_energy = 100.0")
                    .replace("sigma_s = 7.78e-9", "sigma_s = 1e-11")
                    .replace("asperity_density = 1e13", "asperity_density = 1e9")
                    .replace("points = 200", "points = 0")
                    .into_bytes(),
            ),
            args: vec![],
            fragment: "cannot absorb impact energy 100",
            code: 1,
        },
    ]
}

#[test]
fn bad_inputs_get_a_named_error_and_the_right_exit_status() {
    let cases = cases();
    assert!(cases.len() >= 20);
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
        assert!(
            err.contains(c.fragment),
            "{}: stderr lacks `{}`:\n{err}",
            c.name,
            c.fragment
        );
        assert!(!err.contains("panicked"), "{}: panic", c.name);
        if c.scene.is_some() && c.kind != "md" {
            assert!(
                err.contains(".toml"),
                "{}: the file is not named: {err}",
                c.name
            );
        }
    }
}

fn parse_all(text: &str) {
    if let Ok(s) = scene::parse::<AsperityScene>("fuzz", text) {
        let _ = s.validate("fuzz");
    }
    if let Ok(s) = scene::parse::<SurfaceScene>("fuzz", text) {
        let _ = s.validate("fuzz");
    }
    if let Ok(s) = scene::parse::<SwitchScene>("fuzz", text) {
        let _ = s.validate("fuzz");
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
        for base in [scene::DEFAULT_ASPERITY, scene::DEFAULT_SURFACE, scene::DEFAULT_SWITCH] {
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
