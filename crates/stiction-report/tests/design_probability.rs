//! Probability runs on analytic stand-ins of the switch, where every answer is known: the
//! exact single-field answer against the CDF at the critical value, Monte Carlo against it,
//! the coverage of the Clopper-Pearson interval over many seeds, shards merged against one
//! run, and the same samples on any thread count.

mod common;

use common::*;
use design_sweep::{merge_probability, stats, DesignError, Outcome, Probability, Shard};
use stiction_report::csv::samples_csv;

#[test]
fn samples_apart_stay_out_of_the_denominator() {
    let r = run(mixed_plan(600), mixed);
    let s = r.summary();
    let c = s.counts;
    assert!(c.out_of_domain > 0 && c.failed > 0 && c.outside_validity > 0 && c.does_not_close > 0);
    assert_eq!(
        c.sticks + c.free + c.does_not_close + c.outside_validity + c.out_of_domain + c.failed,
        600
    );
    assert_eq!(s.denominator, c.sticks + c.free + c.does_not_close);
    assert_eq!(s.outside_validity, c.outside_validity);
    assert_eq!(
        s.stiction_probability,
        Some(c.sticks as f64 / s.denominator as f64)
    );
    let (lo, hi) = stats::clopper_pearson(c.sticks, s.denominator, 0.95).unwrap();
    assert_eq!((s.ci_low, s.ci_high), (lo, hi));
    for p in r.points() {
        assert_eq!(
            p.counted(),
            matches!(
                p.outcome(),
                Outcome::Sticks | Outcome::Free | Outcome::DoesNotClose
            )
        );
    }
    // the panic became a failed sample with its message
    let csv = samples_csv(&r).unwrap();
    assert!(csv.contains("evaluator panicked: a bug"));
    assert!(csv.starts_with(
        "index,switch.k_s,contact.work_of_adhesion,status,counted,pull_out_ratio,first_sticking_cycle,"
    ));
    assert_eq!(csv.lines().count(), 601);
    // the spring (k in 2..9 against w's 20 % scatter) drives the ratio more than w
    assert_eq!(s.driver.as_deref(), Some("switch.k_s"));
    assert!(s.rank_correlation[0].spearman.unwrap() < -0.7);
}

#[test]
fn shards_merged_equal_one_run_bit_for_bit_and_read_back_exactly() {
    let whole = run(mixed_plan(250), mixed);
    let parts: Vec<(String, Probability)> = [2, 3, 1]
        .iter()
        .map(|&k| {
            let mut p = mixed_plan(250);
            p.shard = Some(Shard::new(k, 3).unwrap());
            let r = run(p, mixed);
            // through the file, as `design merge` reads it
            let back = Probability::from_json(&r.to_json()).unwrap();
            assert_eq!(back, r);
            (format!("part-{k}"), back)
        })
        .collect();
    let merged = merge_probability(parts.clone()).unwrap();
    assert_eq!(merged.to_json(), whole.to_json());
    assert_eq!(samples_csv(&merged).unwrap(), samples_csv(&whole).unwrap());
    assert_eq!(merged, whole);
    // a missing part, a repeated part, parts of another seed are refused by name
    let e = merge_probability(parts[..2].to_vec()).unwrap_err();
    assert!(e.to_string().contains("missing part(s) 1/3"), "{e}");
    let e =
        merge_probability(vec![parts[0].clone(), parts[0].clone(), parts[1].clone()]).unwrap_err();
    assert!(e.to_string().contains("is also in"), "{e}");
    let mut other = mixed_plan(250);
    other.seed = 43;
    other.shard = Some(Shard::new(1, 3).unwrap());
    let mut mixed_parts = parts[..2].to_vec();
    mixed_parts.push(("other".into(), run(other, mixed)));
    let e = merge_probability(mixed_parts).unwrap_err();
    assert!(
        e.to_string()
            .contains("cannot merge other: seed `43` differs"),
        "{e}"
    );
    let e = merge_probability(vec![("whole".into(), whole.clone())]).unwrap_err();
    assert!(e.to_string().contains("unsharded"), "{e}");
    // a value that the seed does not give is refused
    let text = whole.to_json();
    let v = whole.points()[3].values[0];
    let tampered = text.replacen(&format!("{v}"), "3.5", 1);
    assert_ne!(tampered, text);
    let e = Probability::from_json(&tampered).unwrap_err();
    assert!(matches!(e, DesignError::ProbabilityJson(_)), "{e}");
    assert!(e.to_string().contains("that seed 42 gives sample"), "{e}");
}
