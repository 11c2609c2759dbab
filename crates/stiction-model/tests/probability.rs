//! The probability of stiction on the real switch model: a single scattered field whose
//! ratio is monotone (the spring of the paper's switch, spring-driven, eq 1 composite, fast
//! mode), where the exact answer is the distribution's CDF at the threshold's critical
//! value and the Monte Carlo interval must hold it; the same samples on any thread count.

use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::probability::{run, ProbabilityRequest};
use stiction_model::scene::Scene;
use stiction_model::{Accuracy, Silent};

/// The paper's switch driven by K_s = 8.44e9 Pa/m (U = V_PI), eq 1 composite, at most
/// `cycles` cycles.
fn spring_scene(cycles: i64) -> Scene {
    let mut s = Scene::paper(Kind::Switch);
    s.remove("switch.impact_energy");
    s.set_number("switch.k_s", 8.44e9).unwrap();
    s.set_text("contact.yield_modulus", "composite").unwrap();
    s.set("cycles", toml::Value::Integer(cycles)).unwrap();
    s
}

#[test]
fn a_scattered_spring_sticks_with_the_probability_of_the_cdf_at_the_critical_stiffness() {
    let scene = spring_scene(4);
    let request = ProbabilityRequest {
        scatter: vec!["switch.k_s=lognormal(1.25e10,1.3)".into()],
        samples: 40,
        seed: 3,
        accuracy: Some(Accuracy::Fast),
        ..ProbabilityRequest::default()
    };
    let registry = LawRegistry::builtin();
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run(&scene, &registry, &request, &Silent).unwrap())
    };
    let r = on(2);
    let e = r
        .probability
        .exact()
        .expect("a single field has an exact answer");
    assert!(e.available && e.monotone, "{e:?}");
    assert_eq!(e.direction.as_deref(), Some("decreasing"));
    assert_eq!(e.free_side, "above");
    let crit = e.critical_value.unwrap();
    // the paper's switch needs about 1.3e10 Pa/m (docs/design.md)
    assert!(crit > 1.2e10 && crit < 1.4e10, "{crit}");
    let dist = &r.probability.plan().scatter[0].dist;
    let p_exact = e.stiction_probability.unwrap();
    assert_eq!(p_exact, dist.cdf(crit), "P = F(critical value)");
    let s = r.probability.summary();
    assert_eq!((s.samples, s.denominator, s.outside_validity), (40, 40, 0));
    assert!(
        s.ci_low <= p_exact && p_exact <= s.ci_high,
        "{p_exact} outside [{}, {}]",
        s.ci_low,
        s.ci_high
    );
    assert_eq!(s.exact_inside_interval, Some(true));
    assert_eq!(s.by_cycle.len(), 4);
    assert_eq!(s.by_cycle[3].probability, s.stiction_probability.unwrap());
    assert_eq!(s.driver.as_deref(), Some("switch.k_s"));
    // every sample: a design point of the scene at its K_s
    for p in r.probability.points() {
        let d = p.design.unwrap();
        assert_eq!(d.sticks, p.values[0] < crit, "k_s = {}", p.values[0]);
        assert!((d.restoring_pressure_pa / (p.values[0] * 2e-6) - 1.0).abs() < 1e-12);
    }
    // the same samples, bit for bit, on one thread
    assert_eq!(on(1).probability.to_json(), r.probability.to_json());
}

/// erf by its series (|x| < 3 here), to check a CDF independently of statrs.
fn erf(x: f64) -> f64 {
    let mut term = x;
    let mut sum = x;
    for n in 1..200 {
        term *= -x * x / n as f64;
        sum += term / (2 * n + 1) as f64;
    }
    2.0 / std::f64::consts::PI.sqrt() * sum
}

/// The worked example of docs/design.md: the paper's switch (E_I = 0.5 J/m^2 at U = V_PI,
/// eq 1 composite, fast mode) with a lognormal roughness of factor 1.1 around 7.78 nm. The
/// ratio falls as the films roughen: the switch sticks below the critical sigma_s (7.896
/// nm), so P(stiction) = Phi(ln(sigma_c / 7.78 nm) / ln 1.1) = 0.5617, and the Monte Carlo
/// interval of a few samples holds it.
#[test]
fn the_papers_switch_with_scattered_roughness_sticks_with_the_documented_probability() {
    let mut scene = Scene::paper(Kind::Switch);
    scene
        .set_text("contact.yield_modulus", "composite")
        .unwrap();
    let request = ProbabilityRequest {
        scatter: vec!["surface.sigma_s=lognormal(7.78e-9,1.1)".into()],
        samples: 40,
        seed: 0,
        accuracy: Some(Accuracy::Fast),
        ..ProbabilityRequest::default()
    };
    let r = run(&scene, &LawRegistry::builtin(), &request, &Silent).unwrap();
    let e = r.probability.exact().unwrap();
    assert!(e.available && e.monotone, "{e:?}");
    assert_eq!(e.direction.as_deref(), Some("decreasing"));
    assert_eq!(e.free_side, "above");
    let crit = e.critical_value.unwrap();
    assert!((crit / 7.8959e-9 - 1.0).abs() < 1e-4, "{crit}");
    let p = e.stiction_probability.unwrap();
    let z = (crit / 7.78e-9).ln() / 1.1f64.ln();
    assert!((p - 0.5 * (1.0 + erf(z / std::f64::consts::SQRT_2))).abs() < 1e-12);
    assert!((p - 0.5617).abs() < 1e-4, "{p}");
    assert!(e.uncertainty.unwrap() < 1e-3);
    let s = r.probability.summary();
    assert_eq!((s.samples, s.denominator), (40, 40));
    assert!(
        s.ci_low <= p && p <= s.ci_high,
        "{p} not in [{}, {}]",
        s.ci_low,
        s.ci_high
    );
    for pt in r.probability.points() {
        assert_eq!(
            pt.design.unwrap().sticks,
            pt.values[0] < crit,
            "{:?}",
            pt.values
        );
    }
}
