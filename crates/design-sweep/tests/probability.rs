//! Probability runs on analytic stand-ins of the switch, where every answer is known: the
//! exact single-field answer against the CDF at the critical value, Monte Carlo against it,
//! the coverage of the Clopper-Pearson interval over many seeds, shards merged against one
//! run, and the same samples on any thread count.

mod common;

use common::*;
use design_sweep::{
    exact_range, exact_single_field, run_probability, DesignPoint, PointError, Probability,
    ProbabilityPlan, Scatter, Shard, ThresholdOptions,
};

/// ratio = (k0 / k)^2: sticks below k0.
fn spring(k0: f64) -> impl Fn(&[(&str, f64)]) -> Result<DesignPoint, PointError> + Sync {
    move |v| Ok(cycled((k0 / v[0].1).powi(2), v[0].1 * 2e-6))
}

#[test]
fn a_single_monotone_field_gives_the_cdf_at_the_critical_value_and_monte_carlo_agrees() {
    let k0 = 1.1e10;
    let s = "switch.k_s=lognormal(1.3e10,1.25)";
    let sc = Scatter::parse(s).unwrap();
    let range = exact_range(&sc, 0.0, 1e20);
    let options = ThresholdOptions {
        tolerance: 1e-9,
        ratio_rel_error: 1e-8,
        scan_points: None,
    };
    let f = spring(k0);
    let exact = exact_single_field(&sc, range, |k| f(&[("switch.k_s", k)]), &options).unwrap();
    assert!(exact.available && exact.monotone, "{exact:?}");
    assert_eq!(exact.direction.as_deref(), Some("decreasing"));
    assert_eq!(exact.free_side, "above");
    let crit = exact.critical_value.unwrap();
    assert!((crit / k0 - 1.0).abs() < 1e-8, "{crit}");
    let p_exact = exact.stiction_probability.unwrap();
    // P = F(critical value): the distribution's CDF at the threshold
    assert_eq!(p_exact, sc.dist.cdf(crit));
    assert!((p_exact - sc.dist.cdf(k0)).abs() < 1e-8);
    assert_eq!(exact.does_not_close_probability, Some(0.0));
    assert!(exact.uncertainty.unwrap() < 1e-7 && exact.tail_mass < 2.1e-6);

    let r = run(plan(&[s], 2000, 11), f).with_exact(Some(exact));
    let sum = r.summary();
    assert_eq!(sum.samples, 2000);
    assert_eq!(sum.denominator, 2000);
    let p = sum.stiction_probability.unwrap();
    assert!(
        sum.ci_low <= p_exact && p_exact <= sum.ci_high,
        "{p_exact} not in [{}, {}]",
        sum.ci_low,
        sum.ci_high
    );
    assert_eq!(sum.exact_inside_interval, Some(true));
    // the curve by cycle rises to the answer after accommodation
    assert_eq!(sum.by_cycle.len(), CYCLES);
    assert!(sum
        .by_cycle
        .windows(2)
        .all(|w| w[1].probability >= w[0].probability));
    assert_eq!(sum.by_cycle[CYCLES - 1].probability, p);
    // cycle 1 sticks where ratio (1/2)/(1 - 2^-10) > 1: k < k0 sqrt(g1)
    let g1 = 0.5 / (1.0 - 0.5f64.powi(10));
    let p1 = sc.dist.cdf(k0 * g1.sqrt());
    let c1 = &sum.by_cycle[0];
    assert!(
        c1.ci_low <= p1 && p1 <= c1.ci_high && c1.probability < p,
        "{c1:?} vs {p1}"
    );
    // the one field drives failure, against the ratio: rho = -1 (ratio decreasing in k)
    assert_eq!(sum.driver.as_deref(), Some("switch.k_s"));
    assert_eq!(sum.rank_correlation[0].spearman, Some(-1.0));
    let json: serde_json::Value = serde_json::from_str(&r.summary_json()).unwrap();
    for key in [
        "samples",
        "stiction_probability",
        "ci_low",
        "ci_high",
        "does_not_close_probability",
        "outside_validity",
        "by_cycle",
    ] {
        assert!(json.get(key).is_some(), "{key} missing");
    }
    assert_eq!(json["confidence"], 0.95);
    assert!(
        json.get("points").is_none(),
        "the summary leaves the samples out"
    );
    let c = &json["by_cycle"][0];
    for key in ["cycle", "probability", "ci_low", "ci_high"] {
        assert!(c.get(key).is_some(), "by_cycle.{key} missing");
    }
}

#[test]
fn a_closure_boundary_splits_the_mass_between_sticking_and_not_closing() {
    // sticks below 5, free from 5 to 8, does not close above 8
    let f = |k: f64| -> Result<DesignPoint, PointError> {
        if k > 8.0 {
            Ok(DesignPoint::does_not_close(k))
        } else {
            Ok(point((5.0 / k).powi(3), k))
        }
    };
    let sc = Scatter::parse("switch.k_s=uniform(2,10)").unwrap();
    let o = ThresholdOptions {
        tolerance: 1e-9,
        ratio_rel_error: 1e-8,
        scan_points: None,
    };
    let e = exact_single_field(&sc, exact_range(&sc, 0.0, 1e20), f, &o).unwrap();
    assert!(e.available, "{e:?}");
    assert!((e.stiction_probability.unwrap() - 3.0 / 8.0).abs() < 1e-8);
    assert!((e.does_not_close_probability.unwrap() - 2.0 / 8.0).abs() < 1e-7);
    assert_eq!(e.boundaries.len(), 2);
    assert_eq!(e.boundaries[1].kind, "closure");
    // Monte Carlo: the three outcomes partition the counted samples
    let r = run(plan(&["switch.k_s=uniform(2,10)"], 800, 5), |v| f(v[0].1));
    let s = r.summary();
    assert_eq!(
        s.counts.sticks + s.counts.free + s.counts.does_not_close,
        800
    );
    let (lo, hi) = (s.does_not_close.ci_low, s.does_not_close.ci_high);
    assert!(lo <= 0.25 && 0.25 <= hi, "[{lo}, {hi}]");
    assert!(s.ci_low <= 0.375 && 0.375 <= s.ci_high);
}

/// Sticks below 18, free from 18 to 20, does not close above 20: the free stretch holds no
/// scan point of the exact answer's threshold (the QA case of the tenth stop, where the exact
/// answer counted every closing design as sticking, 0.7956 against 0.7656 on a voltage
/// scatter). uniform(1, 100): P(stick) = 17/99, P(not closing) = 80/99.
#[test]
fn a_free_stretch_without_a_scan_point_is_counted_free_in_the_exact_answer() {
    let f = |x: f64| -> Result<DesignPoint, PointError> {
        if x > 20.0 {
            Ok(DesignPoint::does_not_close(1.0))
        } else {
            Ok(point(1.0 + (18.0 - x) / 10.0, 1.0))
        }
    };
    let sc = Scatter::parse("switch.voltage=uniform(1,100)").unwrap();
    let o = ThresholdOptions {
        tolerance: 1e-9,
        ratio_rel_error: 1e-8,
        scan_points: None,
    };
    let e = exact_single_field(&sc, exact_range(&sc, 0.0, 1e20), f, &o).unwrap();
    assert!(e.available, "{e:?}");
    assert_eq!(e.boundaries.len(), 2);
    assert_eq!(
        (e.boundaries[0].kind.as_str(), e.boundaries[1].kind.as_str()),
        ("stiction", "closure")
    );
    let p = e.stiction_probability.unwrap();
    assert!((p - 17.0 / 99.0).abs() < 1e-7, "{p}");
    let q = e.does_not_close_probability.unwrap();
    assert!((q - 80.0 / 99.0).abs() < 1e-7, "{q}");
}

#[test]
fn a_ratio_that_is_not_monotone_gives_no_exact_answer_and_says_why() {
    // sticks only inside (3, 6)
    let f = |k: f64| Ok::<_, PointError>(point(2.0 - ((k - 4.5) / 1.5).powi(2), 1.0).clamp_ratio());
    let sc = Scatter::parse("switch.k_s=uniform(1,9)").unwrap();
    let e = exact_single_field(
        &sc,
        exact_range(&sc, 0.0, 1e20),
        f,
        &ThresholdOptions::default(),
    )
    .unwrap();
    assert!(!e.available && !e.monotone);
    assert!(e.reason.unwrap().contains("not monotone"));
    assert!(e.stiction_probability.is_none());
}

trait Clamp {
    fn clamp_ratio(self) -> DesignPoint;
}
impl Clamp for DesignPoint {
    /// A ratio kept positive (the stand-in's parabola dips below 0).
    fn clamp_ratio(self) -> DesignPoint {
        let r = self.pull_out_ratio.max(1e-3);
        point(r, self.restoring_pressure_pa)
    }
}

#[test]
fn the_interval_covers_the_true_probability_in_at_least_its_confidence_over_many_seeds() {
    // a device sticks when its field is below the 0.1 quantile: p = 0.1 exactly
    let f =
        |v: &[(&str, f64)]| Ok::<_, PointError>(cycled(if v[0].1 < 0.1 { 2.0 } else { 0.5 }, 1.0));
    for (n, runs) in [(60usize, 1000u64), (400, 1000)] {
        let mut covered = 0;
        for seed in 0..runs {
            let s = run(plan(&["a.u=uniform(0,1)"], n, seed), f)
                .summary()
                .clone();
            if s.ci_low <= 0.1 && 0.1 <= s.ci_high {
                covered += 1;
            }
        }
        let c = covered as f64 / runs as f64;
        eprintln!("n = {n}: coverage {c} over {runs} seeds");
        assert!(c >= 0.93, "n = {n}: coverage {c}");
    }
    // stopping at a target half-width keeps the coverage
    let mut covered = 0;
    for seed in 0..300 {
        let mut p = plan(&["a.u=uniform(0,1)"], 20_000, 1000 + seed);
        p.target_halfwidth = Some(0.03);
        let r = run(p, f);
        let s = r.summary();
        assert!(s.stopping.target_met == Some(true) && s.ci_high - s.ci_low <= 0.06);
        assert!(s.samples.is_multiple_of(100));
        if s.ci_low <= 0.1 && 0.1 <= s.ci_high {
            covered += 1;
        }
    }
    eprintln!("target half-width 0.03: coverage {covered}/300");
    assert!(
        covered as f64 / 300.0 >= 0.93,
        "sequential coverage {covered}/300"
    );
}

#[test]
fn the_same_samples_on_any_thread_count_stopped_early_or_not() {
    let on = |threads: usize, target: Option<f64>| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut p = mixed_plan(3000);
            p.target_halfwidth = target;
            run(p, mixed).to_json()
        })
    };
    assert_eq!(on(1, None), on(4, None));
    let (a, b) = (on(1, Some(0.04)), on(3, Some(0.04)));
    assert_eq!(a, b);
    let v: serde_json::Value = serde_json::from_str(&a).unwrap();
    assert_eq!(v["stopping"]["rule"], "target_halfwidth");
    let n = v["samples"].as_u64().unwrap();
    assert!(n < 3000 && n.is_multiple_of(100), "{n}");
    // a run stopped early holds exactly the first samples of the full run
    let full: serde_json::Value = serde_json::from_str(&on(2, None)).unwrap();
    assert_eq!(
        v["points"].as_array().unwrap()[..],
        full["points"].as_array().unwrap()[..n as usize]
    );
}

#[test]
fn bad_requests_are_refused_before_any_sample_runs() {
    let e = Scatter::parse("surface.sigma_s=normal(1e-9,0)").unwrap_err();
    assert!(
        e.to_string().contains("surface.sigma_s") && e.to_string().contains("sd = 0"),
        "{e}"
    );
    let e = Scatter::parse("sigma_s=lognormal(1,2)").unwrap_err();
    assert!(e.to_string().contains("section.key"), "{e}");
    let e = Scatter::parse("surface.sigma_s").unwrap_err();
    assert!(e.to_string().contains("FIELD=DIST"), "{e}");
    let bad = |f: &dyn Fn(&mut ProbabilityPlan), frag: &str| {
        let mut p = plan(&["a.x=uniform(0,1)"], 10, 1);
        f(&mut p);
        let e = run_probability(p, spring(1.0), |_, _| panic!("no sample may run")).unwrap_err();
        assert!(e.to_string().contains(frag), "{frag}: {e}");
    };
    bad(&|p| p.samples = 0, "samples = 0");
    bad(&|p| p.confidence = 1.0, "confidence = 1");
    bad(&|p| p.target_halfwidth = Some(0.0), "target half-width");
    bad(
        &|p| {
            p.target_halfwidth = Some(0.1);
            p.shard = Some(Shard::new(1, 2).unwrap());
        },
        "cannot stop a shard",
    );
    bad(
        &|p| p.scatter.push(Scatter::parse("a.x=normal(0,1)").unwrap()),
        "scattered twice",
    );
}

/// Issue 43: a run whose every sample lies outside the model's validity (gold contacts
/// under a law that assumes plasticity uncoupled from adhesion) sets them apart, and still
/// answers over all samples; `count_outside_validity` makes that the headline. By hand:
/// ratio = (3/k)^2 sticks for k < 3, k uniform on (1.5, 10): P = (3 - 1.5)/8.5.
#[test]
fn samples_outside_validity_are_set_apart_and_answered_over_all_samples() {
    let outside = |v: &[(&str, f64)]| -> Result<DesignPoint, PointError> {
        let mut d = cycled((3.0 / v[0].1).powi(2), v[0].1 * 2e-6);
        d.validity_holds = false;
        Ok(d)
    };
    let p = plan(&["switch.k_s=uniform(1.5,10)"], 400, 7);
    let apart = run(p.clone(), outside);
    let s = apart.summary();
    assert_eq!(
        s.stiction_probability, None,
        "nothing counted inside validity"
    );
    assert_eq!(s.outside_validity, 400);
    assert_eq!(s.all_samples.denominator, 400);
    assert_eq!(s.all_samples.outside_validity, 400);
    let all = s.all_samples.stiction.probability.expect("samples ran");
    assert!((all - 1.5 / 8.5).abs() < 0.06, "{all}");
    assert!(
        s.all_samples.stiction.ci_low <= 1.5 / 8.5 && 1.5 / 8.5 <= s.all_samples.stiction.ci_high
    );
    let counted = run(
        ProbabilityPlan {
            count_outside_validity: true,
            ..p
        },
        outside,
    );
    let c = counted.summary();
    assert_eq!(c.stiction_probability, Some(all));
    assert_eq!(c.denominator, 400);
    assert_eq!(c.outside_validity, 400);
    assert_eq!(c.all_samples, s.all_samples);
    // the flag is part of the run: read back from its JSON, the statistics are the same
    let back = Probability::from_json(&counted.to_json()).unwrap();
    assert_eq!(back.summary(), c);
}
