//! Issue 44: the switch in time through the model library: the scene keys, the JSON
//! contract, the refusals, and a result that does not depend on the accuracy mode.

use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::{SwitchModel, SwitchResult};
use stiction_model::Silent;

/// The paper's switch in time: drive B with the K_s of its E_I = 0.5 J/m^2 at 1.2 V_PI, a 2 um
/// electrode of 12.3 g/cm^3 (m'' = 0.0246 kg/m^2), dimples 0.3 um high on 20 % of a
/// (100 um)^2 electrode.
fn scene(accuracy: &str, gas: Option<f64>) -> Scene {
    let mut s = Scene::paper(Kind::Switch);
    s.remove("switch.impact_energy");
    for (k, v) in [
        ("switch.k_s", "8440183830.384662"),
        ("switch.voltage", "57.888558186414984"),
        ("switch.dimple_height", "0.3e-6"),
        ("switch.contact_area_fraction", "0.2"),
        ("switch.electrode_area", "1e-8"),
        ("dynamics.areal_mass", "0.0246"),
        ("accuracy", &format!("\"{accuracy}\"")),
        ("points", "0"),
        ("elastic_comparison", "false"),
        ("contact_state", "\"none\""),
        ("cycles", "3"),
    ] {
        s.set_text(k, v).unwrap();
    }
    if let Some(p) = gas {
        s.set_number("dynamics.gas_pressure", p).unwrap();
    }
    s
}

fn run(s: &Scene) -> SwitchResult {
    let spec = SwitchSpec::new(s, &LawRegistry::builtin()).unwrap();
    SwitchModel::build(&spec).unwrap().run(&Silent).unwrap()
}

#[test]
fn the_json_carries_the_impact_the_bounces_and_the_ledger() {
    let r = run(&scene("fast", Some(101_325.0)));
    let v = serde_json::to_value(&r).unwrap();
    let c = v["dynamics"]["squeeze_film_coefficient_at_contact"]
        .as_f64()
        .unwrap();
    // beta(1) mu_eff(h) W^2 / h^3 with Veijola's mu_eff at Kn = 68 nm / 0.3 um
    let kn: f64 = 68e-9 / 0.3e-6;
    let mu = 1.85e-5 / (1.0 + 9.638 * kn.powf(1.159));
    let by_hand = switch_dynamics::geometry_factor(1.0) * mu * 1e-8 / 0.3e-6f64.powi(3);
    assert!((c / by_hand - 1.0).abs() < 1e-12, "{c} vs {by_hand}");
    for cy in v["cycles"].as_array().unwrap() {
        for k in ["separation", "velocity", "energy", "flight_time"] {
            assert!(cy["impact"][k].as_f64().unwrap() > 0.0, "impact.{k}");
        }
        assert!(cy["bounces"].is_u64());
        let residual = cy["energy_ledger"]["residual"].as_f64().unwrap();
        assert!(residual.abs() < 1e-5, "{residual}");
        assert!(cy["energy_ledger"]["gas"].as_f64().unwrap() > 0.0);
    }
    // the gas took part of the energy the vacuum delivers
    let vac = run(&scene("fast", None));
    assert!(r.cycles[0].impact.unwrap().energy < vac.cycles[0].impact.unwrap().energy);
    assert_eq!(
        vac.dynamics
            .as_ref()
            .unwrap()
            .squeeze_film_coefficient_at_contact,
        0.0
    );
}

/// The bounce count and the verdict are the same in every accuracy mode.
#[test]
fn bounces_and_verdict_do_not_depend_on_the_mode() {
    for gas in [None, Some(101_325.0)] {
        let runs: Vec<SwitchResult> = ["fast", "balanced", "accurate"]
            .iter()
            .map(|m| run(&scene(m, gas)))
            .collect();
        for r in &runs[1..] {
            assert_eq!(r.stiction, runs[0].stiction);
            for (a, b) in r.cycles.iter().zip(&runs[0].cycles) {
                assert_eq!(a.bounces, b.bounces, "cycle {} gas {gas:?}", a.cycle);
                assert_eq!(a.release.unwrap().opens, b.release.unwrap().opens);
            }
        }
    }
}

/// Each cycle's d_e and pull-out in fast and balanced mode lie within their reported
/// error estimates of the accurate run's (in vacuum, with bounces, and in air): the
/// estimates carry the integration's tolerance, the pressure evaluations' own errors and
/// the table's misses over the approach, the energy residual, and the history's error.
#[test]
fn the_error_estimates_cover_the_difference_to_a_tighter_mode() {
    for gas in [None, Some(101_325.0)] {
        let accurate = run(&scene("accurate", gas));
        for mode in ["fast", "balanced"] {
            let r = run(&scene(mode, gas));
            for (a, b) in r.cycles.iter().zip(&accurate.cycles) {
                let (dd, pd) = (
                    (a.d_e - b.d_e).abs(),
                    (a.pull_out_pressure - b.pull_out_pressure).abs(),
                );
                let (de, pe) = (
                    a.d_e_error + b.d_e_error,
                    a.pull_out_error + b.pull_out_error,
                );
                assert!(
                    dd <= de,
                    "{mode} gas {gas:?} cycle {}: d_e {dd:e} > {de:e}",
                    a.cycle
                );
                assert!(
                    pd <= pe,
                    "{mode} gas {gas:?} cycle {}: pull-out {pd:e} > {pe:e}",
                    a.cycle
                );
            }
        }
    }
}

/// A plate under an atmosphere's squeeze film at a 50 nm dimple gap creeps into its
/// equilibrium in the contact without ever turning (an explicit integration would need
/// minutes of steps to see a turning point that never comes): it is captured at rest, the
/// same in every mode within the reported estimates, and the release comes to rest too.
#[test]
fn an_overdamped_plate_creeps_to_rest_in_the_contact() {
    let creep = |mode: &str| {
        let mut s = scene(mode, Some(101_325.0));
        s.set_text("switch.dimple_height", "50e-9").unwrap();
        s.set_text("switch.contact_area_fraction", "1").unwrap();
        s.set_text("switch.voltage", "60.0").unwrap();
        s.set_text("cycles", "2").unwrap();
        run(&s)
    };
    let accurate = creep("accurate");
    // the modes' d_e targets on the paper's sigma_s = 7.78 nm
    for (mode, target) in [("fast", 1e-4 * 7.78e-9), ("balanced", 1e-6 * 7.78e-9)] {
        let r = creep(mode);
        assert_eq!(r.stiction, accurate.stiction);
        for (a, b) in r.cycles.iter().zip(&accurate.cycles) {
            assert_eq!(a.bounces, Some(0));
            let dd = (a.d_e - b.d_e).abs();
            assert!(
                dd <= a.d_e_error + b.d_e_error,
                "{mode} cycle {}: {dd:e}",
                a.cycle
            );
            // at rest to the tolerance: the estimate is far below the mode's target
            assert!(a.d_e_error < 0.1 * target, "{mode}: {:e}", a.d_e_error);
        }
    }
}

/// The published switch of Math. Probl. Eng. 2016, art. 3479752, Table 1 (after McCarthy
/// et al., JMEMS 11 (2002) 276), as `examples/scenes/mccarthy_switch.toml` sets it up: the
/// squeeze film alone gives the free damping ratio the table states (2e-2, one significant
/// figure: [0.015, 0.025)), and in air the closure bounces a few times, fewer than in vacuum.
#[test]
fn the_published_switch_damps_and_bounces_as_published() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/scenes/mccarthy_switch.toml");
    let air = Scene::read(&path).unwrap();
    let (k, f, eps_a_2m, gap) = (42.0, 2.1e4, 1.9e-11, 3.8e-6);
    let mass = k / (2.0 * std::f64::consts::PI * f).powi(2);
    let area = 2.0 * eps_a_2m * mass / 8.854e-12;
    let film =
        switch_dynamics::SqueezeFilm::new(area.sqrt(), area.sqrt(), 1.85e-5, 68e-9, 101_325.0)
            .unwrap();
    // zeta = c''/(2 sqrt(K_s m'')) per electrode area
    let zeta = film.coefficient(gap) / (2.0 * ((k / area) * (mass / area)).sqrt());
    assert!((0.015..0.025).contains(&zeta), "{zeta}");
    let r = run(&air);
    let mut vacuum = air.clone();
    vacuum.set_number("dynamics.gas_pressure", 0.0).unwrap();
    let v = run(&vacuum);
    for (a, b) in r.cycles.iter().zip(&v.cycles) {
        let (na, nb) = (a.bounces.unwrap(), b.bounces.unwrap());
        assert!((2..=5).contains(&na), "air, cycle {}: {na}", a.cycle);
        assert!(nb > na, "cycle {}: vacuum {nb} against air {na}", a.cycle);
    }
}

#[test]
fn refusals_name_their_keys() {
    let registry = LawRegistry::builtin();
    // the impact energy is a result of the integration
    let mut s = Scene::paper(Kind::Switch);
    s.set_number("dynamics.areal_mass", 0.0246).unwrap();
    let e = SwitchSpec::new(&s, &registry).unwrap_err().to_string();
    assert!(
        e.contains("switch.impact_energy") && e.contains("[dynamics]"),
        "{e}"
    );
    // gas without dimples never closes under Reynolds' squeeze film
    let mut s = scene("fast", Some(101_325.0));
    s.set_number("switch.dimple_height", 0.0).unwrap();
    let e = SwitchSpec::new(&s, &registry).unwrap_err().to_string();
    assert!(
        e.contains("dynamics.gas_pressure") && e.contains("dimple_height"),
        "{e}"
    );
    // one mass
    let mut s = scene("fast", None);
    s.set_number("dynamics.resonance_frequency", 1e5).unwrap();
    let e = SwitchSpec::new(&s, &registry).unwrap_err().to_string();
    assert!(e.contains("dynamics.resonance_frequency"), "{e}");
}

/// Between the vacuum's dynamic pull-in and the static pull-in voltage, the squeeze film
/// stops the electrode at its equilibrium short of the contact: the switch does not close,
/// said by a note, not an error; in vacuum the same voltage closes it.
#[test]
fn the_gas_can_stop_a_switch_the_vacuum_closes() {
    let mut s = scene("fast", Some(101_325.0));
    s.set_text("switch.voltage", "47.0").unwrap();
    let r = run(&s);
    assert!(r.voltage > r.dynamic_pull_in_voltage && r.voltage < r.v_pull_in);
    assert!(!r.closes && !r.stiction && r.cycles.is_empty());
    assert!(r.warnings.iter().any(|w| w.code == "does_not_close"));
    let mut s = scene("fast", None);
    s.set_text("switch.voltage", "47.0").unwrap();
    assert!(run(&s).closes);
}

/// Section 5g's dimpled switch in air (K_s = 2e9 Pa/m, 35 V, m'' = 0.0386 kg/m^2, 5
/// cycles): its history's error, carried from cycle to cycle, took the fast run's pull-out
/// estimate 34 % over the target by the fifth cycle at fast mode's tolerance (1e-7). The
/// runner repeats such a run at a tenth of the tolerance: the result is within the targets,
/// states the tolerance it used, and carries no `estimate_above_target` warning; the
/// repeat moves d_e by less than its own estimate.
#[test]
fn a_run_in_time_that_misses_its_targets_is_repeated_tighter() {
    let mut s = Scene::paper(Kind::Switch);
    s.remove("switch.impact_energy");
    for (k, v) in [
        ("switch.k_s", "2e9"),
        ("switch.voltage", "35"),
        ("switch.dimple_height", "0.3e-6"),
        ("switch.contact_area_fraction", "0.2"),
        ("switch.electrode_area", "1e-8"),
        ("dynamics.areal_mass", "0.0386"),
        ("dynamics.gas_pressure", "101325"),
        ("accuracy", "\"fast\""),
        ("points", "0"),
        ("elastic_comparison", "false"),
        ("contact_state", "\"none\""),
        ("cycles", "5"),
    ] {
        s.set_text(k, v).unwrap();
    }
    let r = run(&s);
    let d = r.dynamics.as_ref().expect("a run in time");
    let default = switch_dynamics::DynamicsOptions::for_target(1e-4).tolerance;
    assert_eq!(default, 1e-7);
    assert!(d.tolerance < default, "tolerance {:e}", d.tolerance);
    assert!(
        r.warnings.iter().all(|w| w.code != "estimate_above_target"),
        "{:?}",
        r.warnings
    );
    let sigma = 7.78e-9;
    for c in &r.cycles {
        let pull_target = 1e-4 * c.pull_out_pressure.abs();
        assert!(
            c.d_e_error <= 1e-4 * sigma,
            "cycle {}: d_e {:e}",
            c.cycle,
            c.d_e_error
        );
        assert!(
            c.pull_out_error <= pull_target,
            "cycle {}: pull-out {:e} > {pull_target:e}",
            c.cycle,
            c.pull_out_error
        );
    }
    // the accurate run's d_e lies within the repeated fast run's estimate
    s.set_text("accuracy", "\"accurate\"").unwrap();
    let accurate = run(&s);
    for (a, b) in r.cycles.iter().zip(&accurate.cycles) {
        let dd = (a.d_e - b.d_e).abs();
        assert!(dd <= a.d_e_error + b.d_e_error, "cycle {}: {dd:e}", a.cycle);
    }
}
