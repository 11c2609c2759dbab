//! The accuracy modes hold where users go: random switch scenes drawn by a seeded
//! generator over the documented domains (plausible MEMS contacts and the wide ranges a
//! scene accepts), every adhesion law, every plasticity law, both readings of eq 1, both
//! reload rules, and a user law that declares no kinks. Each mode is measured against the
//! accurate mode, the accurate mode against the reference; the pull-out does not depend on
//! the curve asked for; d_e never jumps up between cycles. The distribution over many more
//! scenes is in docs/performance.md (`cargo xtask accuracy`).

// The user law of the workspace's example, which names the crates as the root crate
// `stiction` re-exports them: the same re-exports are this crate's.
extern crate stiction_model as stiction;

#[path = "../../../examples/custom_law.rs"]
#[allow(dead_code)]
mod custom_law;

use stiction_model::laws::LawRegistry;
use stiction_model::scenegen::{self, Domain, Rng};
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::{SwitchModel, SwitchResult};
use stiction_model::{Accuracy, ModelError, Silent};

fn run(s: &SwitchSpec, accuracy: Accuracy, points: usize) -> Result<SwitchResult, ModelError> {
    let s = s.with_values(&[
        ("accuracy", stiction_model::spec::accuracy_value(accuracy)),
        ("points", stiction_model::spec::count_value(points)),
    ])?;
    SwitchModel::build(&s)?.run(&Silent)
}

/// Worst (d_e error in sigma_s, pull-out error relative with the 1e-9 K_s d0 floor).
fn errors(a: &SwitchResult, b: &SwitchResult, sigma: f64) -> (f64, f64) {
    let floor = 1e-9 * a.restoring_pressure / a.contact_area_fraction;
    a.cycles
        .iter()
        .zip(&b.cycles)
        .fold((0.0f64, 0.0f64), |(de, po), (x, y)| {
            (
                de.max((x.d_e - y.d_e).abs() / sigma),
                po.max(
                    (x.pull_out_pressure - y.pull_out_pressure).abs()
                        / x.pull_out_pressure.abs().max(floor),
                ),
            )
        })
}

/// A rise of d_e between cycles is allowed only where theory 6.3 expects one, and only
/// when the run reports it: the `non_deepening_impact` warning with an accommodation cause
/// of `non_deepening`, and either the reload as printed (the eq-12 overshoot) or a run
/// outside the model's validity (as with the Kogut-Etsion regime jumps pressed a hundred
/// sigma_s deep under an adhesion that yields the asperities).
fn explained_rise(r: &SwitchResult) -> bool {
    let reported = r.warnings.iter().any(|w| w.code == "non_deepening_impact")
        && r.cycles.iter().any(|c| !c.deepened);
    reported && (r.laws.reload == "as_printed" || !r.validity.holds)
}

fn scenes(domain: Domain, seed: u64, n: usize) -> Vec<SwitchSpec> {
    let registry = LawRegistry::builtin();
    let mut rng = Rng::new(seed);
    let mut out = Vec::new();
    while out.len() < n {
        let mut scene = scenegen::switch_scene(&mut rng, domain, "generated");
        scene.set_number("cycles", 2.0).unwrap();
        if let Ok(spec) = SwitchSpec::new(&scene, &registry) {
            out.push(spec);
        }
    }
    out
}

/// The scene as a file, to rerun a failing one alone.
fn toml(s: &SwitchSpec) -> String {
    scenegen::to_toml(s.common().scene())
}

#[test]
fn every_mode_meets_its_targets_on_random_mems_scenes() {
    let mut failures = Vec::new();
    let mut worst = [(0.0f64, 0.0f64); 3];
    for (i, s) in scenes(Domain::Mems, 2026, 16).into_iter().enumerate() {
        let sigma = s.roughness().sigma_s();
        let accurate = run(&s, Accuracy::Accurate, 0).unwrap_or_else(|e| {
            panic!(
                "scene {i}: a plausible MEMS scene failed: {e}\n{}",
                toml(&s)
            )
        });
        for (k, mode) in [Accuracy::Balanced, Accuracy::Fast].into_iter().enumerate() {
            let r = run(&s, mode, 0).unwrap_or_else(|e| panic!("scene {i} {mode}: {e}"));
            let t = mode.targets();
            let (de, po) = errors(&accurate, &r, sigma);
            worst[k + 1] = (worst[k + 1].0.max(de), worst[k + 1].1.max(po));
            if de > t.d_e_tolerance_sigma || po > t.pull_out_tolerance {
                failures.push(format!(
                    "scene {i} {mode}: d_e {de:e} sigma, pull-out {po:e}\n{}",
                    toml(&s)
                ));
            }
            // the verdict may only differ where the ratio is within the mode's tolerance of 1
            let closeness = (accurate.pull_out_ratio - 1.0).abs()
                / accurate.pull_out_ratio.max(f64::MIN_POSITIVE);
            if closeness > 2.0 * t.pull_out_tolerance {
                assert_eq!(
                    r.stiction, accurate.stiction,
                    "scene {i} {mode}: verdict at ratio {}",
                    accurate.pull_out_ratio
                );
            }
        }
        // no spurious jump of d_e between cycles: a rise is a documented artefact, and
        // then the run says so (theory 6.3)
        for w in accurate.cycles.windows(2) {
            let rise = (w[1].d_e - w[0].d_e) / sigma;
            assert!(
                rise < 1e-3 || explained_rise(&accurate),
                "scene {i}: d_e rose by {rise} sigma_s unreported"
            );
            assert!(w[1].contact_pressure > 0.0);
        }
        if i % 4 == 0 {
            let reference = run(&s, Accuracy::Reference, 0).unwrap();
            let (de, po) = errors(&reference, &accurate, sigma);
            worst[0] = (worst[0].0.max(de), worst[0].1.max(po));
            let t = Accuracy::Accurate.targets();
            if de > t.d_e_tolerance_sigma || po > t.pull_out_tolerance {
                failures.push(format!(
                    "scene {i} accurate: d_e {de:e} sigma, pull-out {po:e}\n{}",
                    toml(&s)
                ));
            }
        }
    }
    eprintln!(
        "worst (d_e, pull-out): accurate {:?} balanced {:?} fast {:?}",
        worst[0], worst[1], worst[2]
    );
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn modes_meet_their_targets_on_the_wide_ranges_where_the_model_has_an_answer() {
    let mut failures = Vec::new();
    let mut answered = 0;
    for (i, s) in scenes(Domain::Wide, 7, 10).into_iter().enumerate() {
        let Ok(accurate) = run(&s, Accuracy::Accurate, 0) else {
            continue; // e.g. adhesion stronger than any compression: an error, not a number
        };
        answered += 1;
        let sigma = s.roughness().sigma_s();
        for w in accurate.cycles.windows(2) {
            let rise = (w[1].d_e - w[0].d_e) / sigma;
            assert!(
                rise < 1e-3 || explained_rise(&accurate),
                "wide scene {i}: d_e rose by {rise} sigma_s unreported"
            );
        }
        for mode in [Accuracy::Balanced, Accuracy::Fast] {
            let r = run(&s, mode, 0).unwrap_or_else(|e| {
                panic!(
                    "wide scene {i} {mode} failed where accurate did not: {e}\n{}",
                    toml(&s)
                )
            });
            let t = mode.targets();
            let (de, po) = errors(&accurate, &r, sigma);
            if de > t.d_e_tolerance_sigma || po > t.pull_out_tolerance {
                failures.push(format!(
                    "wide scene {i} {mode}: d_e {de:e} sigma, pull-out {po:e}\n{}",
                    toml(&s)
                ));
            }
        }
    }
    assert!(answered >= 4, "too few wide scenes answered: {answered}");
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn the_pull_out_does_not_depend_on_the_curves_written() {
    for (i, s) in scenes(Domain::Mems, 99, 4).into_iter().enumerate() {
        let a = run(&s, Accuracy::Fast, 0).unwrap();
        let b = run(&s, Accuracy::Fast, 300).unwrap();
        for (x, y) in a.cycles.iter().zip(&b.cycles) {
            assert_eq!(
                x.pull_out_pressure, y.pull_out_pressure,
                "scene {i} cycle {}",
                x.cycle
            );
            assert_eq!(x.d_e, y.d_e);
            // and no written sample lies below the pull-out found
            let lowest = y.unloading.iter().map(|p| p.pressure).fold(0.0, f64::min);
            assert!(-lowest <= y.pull_out_pressure * (1.0 + 1e-9), "scene {i}");
        }
    }
}

/// A user law that declares no kinks, on the paper's surface under the paper's impact:
/// the fast and balanced modes stay within their targets of the accurate one.
#[test]
fn a_user_law_without_declared_kinks_meets_the_targets() {
    use stiction_model::contact_core::{paper, SurfaceLaw};
    use stiction_model::gw_surface::{GreenwoodWilliamson, Roughness};
    use stiction_model::switch_1d::{run_cycles, CycleOptions, Impact, ImpactFilm};
    let rough = Roughness {
        sigma_s: paper::SIGMA_S,
        asperity_density: paper::ASPERITY_DENSITY,
    };
    let impact = Impact {
        energy: 0.5,
        film: ImpactFilm {
            thickness: paper::FILM_THICKNESS,
            youngs_modulus: 410e9,
        },
        contact_area_fraction: 1.0,
        restoring_pressure: 16_880.0,
    };
    let solve = |mode: Accuracy| {
        let gw =
            GreenwoodWilliamson::new(custom_law::ru_asperity(0.5e-9), rough, mode.quadrature(0.0))
                .unwrap();
        let opts = CycleOptions {
            cycles: 2,
            unloading_points: 0,
            loading_points: 0,
            precision: mode.precision(),
            ..Default::default()
        };
        run_cycles(&gw, gw.virgin(), impact, opts, &mut |_| {}).unwrap()
    };
    let accurate = solve(Accuracy::Accurate);
    for mode in [Accuracy::Balanced, Accuracy::Fast] {
        let r = solve(mode);
        let t = mode.targets();
        for (a, b) in accurate.cycles.iter().zip(&r.cycles) {
            let de = (a.d_e() - b.d_e()).abs() / paper::SIGMA_S;
            let po = (a.unloading.pull_out_pressure - b.unloading.pull_out_pressure).abs()
                / a.unloading.pull_out_pressure;
            assert!(
                de <= t.d_e_tolerance_sigma && po <= t.pull_out_tolerance,
                "{mode}: d_e {de:e}, pull-out {po:e}"
            );
        }
    }
}

/// Every cycle's error of `r` against `yardstick` within the mode's targets and within the
/// two runs' error estimates together; the failures, in words.
fn per_cycle(name: &str, yardstick: &SwitchResult, r: &SwitchResult, sigma: f64) -> Vec<String> {
    let targets = r.accuracy;
    let t = targets.mode;
    let floor = 1e-9 * yardstick.restoring_pressure / yardstick.contact_area_fraction;
    let mut out = Vec::new();
    assert_eq!(yardstick.cycles.len(), r.cycles.len(), "{name}: cycles run");
    for (y, c) in yardstick.cycles.iter().zip(&r.cycles) {
        let dd = (c.d_e - y.d_e).abs();
        let dp = (c.pull_out_pressure - y.pull_out_pressure).abs();
        let rel = dp / y.pull_out_pressure.abs().max(floor);
        if dd / sigma > targets.d_e_tolerance_sigma || rel > targets.pull_out_tolerance {
            out.push(format!(
                "{name} {t} cycle {}: d_e {:.2e} sigma_s, pull-out {rel:.2e} (targets {:e}, {:e})",
                c.cycle,
                dd / sigma,
                targets.d_e_tolerance_sigma,
                targets.pull_out_tolerance
            ));
        }
        if dd > c.d_e_error + y.d_e_error || dp > c.pull_out_error + y.pull_out_error {
            out.push(format!(
                "{name} {t} cycle {}: errors d_e {dd:.2e} m, pull-out {dp:.2e} Pa beyond the estimates {:.2e} m, {:.2e} Pa",
                c.cycle,
                c.d_e_error + y.d_e_error,
                c.pull_out_error + y.pull_out_error
            ));
        }
    }
    out
}

/// Issue 41: on soft films (gold-like: E below 100 GPa, S_Y below 0.5 GPa) fast mode
/// missed its targets from cycle 2 on (the reload tables' cycles), 1.3e-3 sigma_s on the
/// QA's repro (its Newton on the tabulated virgin loading stopped after six steps from a
/// far start), and its estimates did not cover the error the history carries into later
/// cycles (220x short). The repro's film and random soft films, every cycle against the
/// accurate mode (itself within 1e-9 of the reference, measured in performance.md).
#[test]
fn fast_and_balanced_modes_meet_their_targets_on_soft_films_at_every_cycle() {
    let registry = LawRegistry::builtin();
    // the QA's repro (../shared/repro/2026-11-28/R2_fast_mode_soft_film.toml)
    let repro = stiction_model::scene::Scene::from_toml_str(
        "R2",
        r#"
cycles = 3
points = 0
elastic_comparison = false
contact_state = "none"
[contact]
youngs_modulus = 81178081745.26855
yield_stress = 228848166.40098476
poisson_ratio = 0.25059211185696706
radius = 8.444083683934808e-06
work_of_adhesion = 0.7697122983558029
z0 = 3.8213241138894935e-10
counter = "same"
adhesion_law = "maugis_kim"
plasticity_law = "etsion_kadin"
yield_modulus = "as_printed"
reload = "as_printed"
[surface]
sigma_s = 7.268982457521034e-09
asperity_density = 6028195558853.958
[switch]
d0 = 4.484554620234818e-07
t_d = 4.97310750554912e-07
epsilon_r = 3.5714627715423752
film_thickness = 1.612725346157318e-06
impact_energy = 0.010124400610215594
contact_area_fraction = 0.9467404331859421
"#,
    )
    .unwrap();
    let mut specs = vec![(
        "R2".to_string(),
        SwitchSpec::new(&repro, &registry).unwrap(),
    )];
    let mut rng = Rng::new(41);
    while specs.len() < 7 {
        let mut scene = scenegen::switch_scene(&mut rng, Domain::Soft, "generated");
        scene.set_number("cycles", 4.0).unwrap();
        if let Ok(spec) = SwitchSpec::new(&scene, &registry) {
            specs.push((format!("soft {}", specs.len()), spec));
        }
    }
    let mut failures = Vec::new();
    let mut compared = 0;
    for (name, s) in &specs {
        let sigma = s.roughness().sigma_s();
        let Ok(accurate) = run(s, Accuracy::Accurate, 0) else {
            // a film that cannot absorb its impact: no answer to compare
            continue;
        };
        for mode in [Accuracy::Balanced, Accuracy::Fast] {
            let r = run(s, mode, 0).unwrap_or_else(|e| panic!("{name} {mode}: {e}\n{}", toml(s)));
            let found = per_cycle(name, &accurate, &r, sigma);
            if !found.is_empty() {
                failures.push(format!("{}\n{}", found.join("\n"), toml(s)));
            }
            compared += 1;
        }
    }
    assert!(compared >= 8, "too few soft films answered: {compared}");
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
