//! The failure probability of a scattered design: Monte Carlo samples of the design
//! fields from their distributions, each run through the evaluator, reduced to the
//! probability of stiction by cycle, of stiction after accommodation and of "does not
//! close", with exact binomial (Clopper-Pearson) intervals; the rank correlation of each
//! field with the pull-out ratio; sharded runs merged exactly; and, for a single scattered
//! field, the exact answer from the threshold and the distribution's CDF.
//!
//! **Denominator.** Every probability is a fraction of the *counted* samples: those whose
//! evaluator gave an answer (`ok` or `does_not_close`) inside the model's validity. Samples
//! outside validity, out of a field's domain or failed are counted apart and enter no
//! probability. A switch that does not close cannot stick: stiction, free and does not
//! close partition the counted samples.

use crate::dist::{short, Correlation, Sampler, Scatter};
use crate::map::{first_difference, point_design, read_bounded, PointIn, ValueIn};
use crate::point::{guarded, DesignPoint, PointError, Status};
use crate::shard::Shard;
use crate::stats::{clopper_pearson, spearman, spearman_interval};
use crate::threshold::{threshold, CrossingKind, ThresholdOptions};
use crate::DesignError;
use rayon::prelude::*;
use serde::{Deserialize, Serialize, Serializer};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The `format` tag of `probability.json`.
pub const PROBABILITY_FORMAT: &str = "stiction-design-probability";
/// The `version` of `probability.json` written by this crate.
pub const PROBABILITY_VERSION: u32 = 1;
/// Largest number of samples of one run.
pub const MAX_SAMPLES: usize = 1_000_000;
/// With a target half-width, the interval is checked after every this many samples (in
/// index order), so where a run stops does not depend on the thread count.
pub const STOP_CHECK_EVERY: usize = 100;
/// The exact single-field answer scans the field between its quantiles `EXACT_TAIL` and
/// `1 - EXACT_TAIL`; the tails beyond take the state of the nearest end.
pub const EXACT_TAIL: f64 = 1e-6;

/// The columns of `samples.csv` after `index` and the scattered fields, in order.
pub const SAMPLE_COLUMNS: [&str; 12] = [
    "status",
    "counted",
    "pull_out_ratio",
    "first_sticking_cycle",
    "cycles_to_accommodation",
    "sticks",
    "closes",
    "validity_holds",
    "largest_pull_out_pa",
    "restoring_pressure_pa",
    "accommodation_cause",
    "detail",
];

/// What to compute: the scattered fields, the samples, the statistics' settings, and what
/// to echo into `probability.json` (merge compares all of it but the shard).
#[derive(Debug, Clone, PartialEq)]
pub struct ProbabilityPlan {
    /// The scene as run (echoed verbatim).
    pub scene: Value,
    /// The accuracy mode's name.
    pub accuracy: String,
    /// Relative error of the pull-out ratio in that mode: a sample whose ratio is within
    /// it of 1 is counted as `near_threshold` (its verdict is as uncertain as the mode).
    pub ratio_rel_error: f64,
    /// The scattered fields and their distributions, in order (the order of the uniforms).
    pub scatter: Vec<Scatter>,
    /// Correlations between scattered fields.
    pub correlations: Vec<Correlation>,
    /// The seed.
    pub seed: u64,
    /// Samples to run (with a target half-width: the most to run).
    pub samples: usize,
    /// Confidence of the intervals, in (0, 1).
    pub confidence: f64,
    /// The scene's cycle cap: `by_cycle` runs from 1 to it.
    pub cycles: usize,
    /// Stop once the stiction interval's half-width is at most this (checked every
    /// [`STOP_CHECK_EVERY`] samples); not with a shard.
    pub target_halfwidth: Option<f64>,
    /// The part of the samples to run; `None` runs them all.
    pub shard: Option<Shard>,
    /// Count the samples outside the model's validity in the headline probabilities
    /// (`--count-outside-validity`): by default they are set apart, and the all-samples
    /// answer is given beside ([`Summary::all_samples`]).
    pub count_outside_validity: bool,
}

impl ProbabilityPlan {
    /// Checks the plan and returns its sampler: 1 to [`MAX_SAMPLES`] samples, a confidence
    /// in (0, 1), a cycle cap of at least 1, a target half-width in (0, 0.5] and not with a
    /// shard, distinct scattered fields, correlations between them that make a positive
    /// definite matrix.
    pub fn sampler(&self) -> Result<Sampler, DesignError> {
        let bad = |m: String| DesignError::Probability(m);
        if !(1..=MAX_SAMPLES).contains(&self.samples) {
            return Err(bad(format!(
                "samples = {} must be in 1..={MAX_SAMPLES}",
                self.samples
            )));
        }
        if !(self.confidence > 0.0 && self.confidence < 1.0) {
            return Err(bad(format!(
                "confidence = {} must be in (0, 1), e.g. 0.95",
                self.confidence
            )));
        }
        if self.cycles == 0 {
            return Err(bad("cycles = 0: the scene runs at least one cycle".into()));
        }
        if !(self.ratio_rel_error.is_finite() && self.ratio_rel_error >= 0.0) {
            return Err(bad(format!(
                "ratio relative error {} must be finite and >= 0",
                self.ratio_rel_error
            )));
        }
        if let Some(h) = self.target_halfwidth {
            if !(h > 0.0 && h <= 0.5) {
                return Err(bad(format!(
                    "target half-width = {h} must be in (0, 0.5] (a probability's interval)"
                )));
            }
            if self.shard.is_some() {
                return Err(bad(
                    "a target half-width cannot stop a shard: a part does not see the others' samples; give the parts a fixed --samples".into(),
                ));
            }
        }
        Sampler::new(&self.scatter, &self.correlations, self.seed)
    }

    /// The sample indices this plan runs (all, or its shard's), ascending.
    pub fn indices(&self) -> Vec<usize> {
        match self.shard {
            Some(s) => s.indices(self.samples).collect(),
            None => (0..self.samples).collect(),
        }
    }
}

/// One evaluated sample.
#[derive(Debug, Clone, PartialEq)]
pub struct SamplePoint {
    /// Sample index (its values depend on the seed and this alone).
    pub index: usize,
    /// The field values, one per scattered field.
    pub values: Vec<f64>,
    /// What became of it.
    pub status: Status,
    /// The design point, for `ok` and `does_not_close`.
    pub design: Option<DesignPoint>,
}

/// What a sample counts as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Closes and sticks at some cycle (inside validity).
    Sticks,
    /// Closes and never sticks (inside validity).
    Free,
    /// Does not close.
    DoesNotClose,
    /// Ran, but outside the model's validity: counted apart.
    OutsideValidity,
    /// Refused (a value out of a field's domain, a derived value out of its own): apart.
    OutOfDomain,
    /// Failed numerically: apart.
    Failed,
}

impl SamplePoint {
    /// What the sample counts as (outside the model's validity: apart).
    pub fn outcome(&self) -> Outcome {
        self.outcome_counting(false)
    }

    /// What the sample counts as; with `outside_validity` a sample outside the model's
    /// validity counts as its design says (sticks, free, does not close).
    pub fn outcome_counting(&self, outside_validity: bool) -> Outcome {
        match (&self.status, &self.design) {
            (Status::OutOfDomain(_), _) => Outcome::OutOfDomain,
            (Status::Failed(_), _) | (_, None) => Outcome::Failed,
            (_, Some(d)) if !d.validity_holds && !outside_validity => Outcome::OutsideValidity,
            (_, Some(d)) if !d.closes => Outcome::DoesNotClose,
            (_, Some(d)) if d.sticks => Outcome::Sticks,
            _ => Outcome::Free,
        }
    }

    /// Whether the sample is in the denominator of the probabilities (samples outside
    /// the model's validity are not).
    pub fn counted(&self) -> bool {
        self.counted_counting(false)
    }

    /// Whether the sample is in the denominator, counting those outside validity or not.
    pub fn counted_counting(&self, outside_validity: bool) -> bool {
        matches!(
            self.outcome_counting(outside_validity),
            Outcome::Sticks | Outcome::Free | Outcome::DoesNotClose
        )
    }
}

/// A probability with its exact binomial interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// Samples with the outcome.
    pub count: usize,
    /// count / denominator (absent when nothing was counted).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probability: Option<f64>,
    /// Clopper-Pearson lower end (0 when nothing was counted).
    pub ci_low: f64,
    /// Clopper-Pearson upper end (1 when nothing was counted).
    pub ci_high: f64,
}

impl Estimate {
    fn of(count: usize, n: usize, confidence: f64) -> Estimate {
        let (ci_low, ci_high) = clopper_pearson(count, n, confidence).unwrap_or((0.0, 1.0));
        Estimate {
            count,
            probability: (n > 0).then(|| count as f64 / n as f64),
            ci_low,
            ci_high,
        }
    }

    /// Half the interval's width.
    pub fn halfwidth(&self) -> f64 {
        0.5 * (self.ci_high - self.ci_low)
    }
}

/// P(stuck by cycle n).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CycleProbability {
    /// The cycle, from 1.
    pub cycle: usize,
    /// Counted samples whose first sticking cycle is at most `cycle`, over the counted.
    pub probability: f64,
    /// Clopper-Pearson lower end.
    pub ci_low: f64,
    /// Clopper-Pearson upper end.
    pub ci_high: f64,
    /// The samples stuck by this cycle.
    pub sticking: usize,
}

/// Spearman's rank correlation of one field with the pull-out ratio.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RankCorrelation {
    /// The scattered field.
    pub field: String,
    /// Spearman's rho over the counted samples that close (absent when undefined).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spearman: Option<f64>,
    /// Approximate interval (Fisher z, se = sqrt(1.06/(n-3))) at the run's confidence.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ci_low: Option<f64>,
    /// Its upper end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ci_high: Option<f64>,
    /// Pairs used.
    pub samples: usize,
}

/// The counts behind the probabilities.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Counted samples that stick at some cycle.
    pub sticks: usize,
    /// Counted samples that close and never stick.
    pub free: usize,
    /// Counted samples that do not close.
    pub does_not_close: usize,
    /// Samples outside the model's validity (apart).
    pub outside_validity: usize,
    /// Samples out of a field's domain (apart).
    pub out_of_domain: usize,
    /// Samples that failed (apart).
    pub failed: usize,
    /// Counted closing samples that reached the cycle cap before accommodating.
    pub not_accommodated: usize,
    /// Counted closing samples whose ratio is within the accuracy mode's error of 1.
    pub near_threshold: usize,
}

/// The probabilities over every sample that ran, those outside the model's validity
/// included: defined whenever a sample ran (issue 43: a run of gold contacts, every sample
/// outside validity, used to answer nothing).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AllSamples {
    /// Samples that ran (sticks, free or does not close, inside validity or not).
    pub denominator: usize,
    /// Of them, those outside the model's validity.
    pub outside_validity: usize,
    /// P(stiction) over them, with its interval.
    pub stiction: Estimate,
    /// P(does not close) over them.
    pub does_not_close: Estimate,
}

/// How the run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Stopping {
    /// `samples` (all requested samples ran) or `target_halfwidth` (stopped early).
    pub rule: &'static str,
    /// The samples requested (the cap with a target half-width).
    pub samples_requested: usize,
    /// The target half-width, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target_halfwidth: Option<f64>,
    /// The half-width reached by the stiction interval.
    pub halfwidth: f64,
    /// Whether the target was met (absent without a target).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target_met: Option<bool>,
}

/// The statistics of a run (whole, merged or one shard). Field names are a public
/// contract: `samples`, `stiction_probability`, `ci_low`, `ci_high`, `confidence`,
/// `does_not_close_probability`, `outside_validity`, `by_cycle`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Samples run (all statuses).
    pub samples: usize,
    /// P(stiction after accommodation): counted samples that stick at some cycle (until
    /// accommodated, at most the scene's cycles), over the counted samples.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiction_probability: Option<f64>,
    /// Its Clopper-Pearson lower end.
    pub ci_low: f64,
    /// Its upper end.
    pub ci_high: f64,
    /// The intervals' confidence.
    pub confidence: f64,
    /// P(does not close) over the counted samples.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub does_not_close_probability: Option<f64>,
    /// Samples outside the model's validity (counted apart unless
    /// `count_outside_validity`).
    pub outside_validity: usize,
    /// Whether the headline probabilities count the samples outside the model's validity.
    pub count_outside_validity: bool,
    /// The probabilities over every sample that ran, inside the model's validity or not:
    /// defined whenever a sample ran.
    pub all_samples: AllSamples,
    /// P(stuck by cycle n), n = 1 .. the scene's cycles (empty when nothing was counted).
    pub by_cycle: Vec<CycleProbability>,
    /// The denominator: counted samples (inside validity, `ok` or `does_not_close`).
    pub denominator: usize,
    /// The stiction estimate with its count.
    pub stiction: Estimate,
    /// The does-not-close estimate with its interval.
    pub does_not_close: Estimate,
    /// Counts by outcome.
    pub counts: Counts,
    /// Rank correlation of each scattered field with the pull-out ratio.
    pub rank_correlation: Vec<RankCorrelation>,
    /// The field with the largest |rho|: the one that drives failure most.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub driver: Option<String>,
    /// How the run stopped.
    pub stopping: Stopping,
    /// Whether the exact single-field answer lies inside the stiction interval.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exact_inside_interval: Option<bool>,
}

impl Summary {
    /// The statistics of `points` under `plan`.
    pub fn of(plan: &ProbabilityPlan, points: &[SamplePoint], exact: Option<&Exact>) -> Summary {
        let mut c = Counts {
            sticks: 0,
            free: 0,
            does_not_close: 0,
            outside_validity: 0,
            out_of_domain: 0,
            failed: 0,
            not_accommodated: 0,
            near_threshold: 0,
        };
        let mut first_cycles: Vec<usize> = Vec::new();
        let all = plan.count_outside_validity;
        // every sample that ran, inside validity or not
        let (mut ran, mut ran_sticks, mut ran_dnc, mut ran_outside) = (0, 0, 0, 0);
        for p in points {
            match p.outcome_counting(true) {
                Outcome::Sticks => ran_sticks += 1,
                Outcome::DoesNotClose => ran_dnc += 1,
                _ => {}
            }
            if p.counted_counting(true) {
                ran += 1;
                if p.outcome() == Outcome::OutsideValidity {
                    ran_outside += 1;
                }
            }
            match p.outcome_counting(all) {
                Outcome::Sticks => c.sticks += 1,
                Outcome::Free => c.free += 1,
                Outcome::DoesNotClose => c.does_not_close += 1,
                Outcome::OutsideValidity => c.outside_validity += 1,
                Outcome::OutOfDomain => c.out_of_domain += 1,
                Outcome::Failed => c.failed += 1,
            }
            if let (true, Some(d)) = (p.counted_counting(all), &p.design) {
                if d.closes {
                    if d.cycles_to_accommodation.is_none() {
                        c.not_accommodated += 1;
                    }
                    if d.pull_out_ratio > 0.0 && d.pull_out_ratio.ln().abs() <= plan.ratio_rel_error
                    {
                        c.near_threshold += 1;
                    }
                }
                if let Some(f) = d.first_sticking_cycle {
                    first_cycles.push(f);
                }
            }
        }
        let n = c.sticks + c.free + c.does_not_close;
        let conf = plan.confidence;
        let stiction = Estimate::of(c.sticks, n, conf);
        let does_not_close = Estimate::of(c.does_not_close, n, conf);
        let by_cycle = if n == 0 {
            Vec::new()
        } else {
            (1..=plan.cycles)
                .map(|cycle| {
                    let x = first_cycles.iter().filter(|&&f| f <= cycle).count();
                    let e = Estimate::of(x, n, conf);
                    CycleProbability {
                        cycle,
                        probability: x as f64 / n as f64,
                        ci_low: e.ci_low,
                        ci_high: e.ci_high,
                        sticking: x,
                    }
                })
                .collect()
        };
        // the ratio against each field, over the counted samples that close
        let closing: Vec<&SamplePoint> = points
            .iter()
            .filter(|p| p.counted_counting(all) && p.design.is_some_and(|d| d.closes))
            .collect();
        let ratios: Vec<f64> = closing
            .iter()
            .map(|p| p.design.map_or(0.0, |d| d.pull_out_ratio))
            .collect();
        let rank_correlation: Vec<RankCorrelation> = plan
            .scatter
            .iter()
            .enumerate()
            .map(|(j, s)| {
                let xs: Vec<f64> = closing.iter().map(|p| p.values[j]).collect();
                let rho = spearman(&xs, &ratios);
                let ci = rho.and_then(|r| spearman_interval(r, xs.len(), conf));
                RankCorrelation {
                    field: s.field.clone(),
                    spearman: rho,
                    ci_low: ci.map(|c| c.0),
                    ci_high: ci.map(|c| c.1),
                    samples: xs.len(),
                }
            })
            .collect();
        let driver = rank_correlation
            .iter()
            .filter_map(|r| r.spearman.map(|s| (r, s.abs())))
            .fold(None::<(&RankCorrelation, f64)>, |best, (r, a)| match best {
                Some((_, b)) if b >= a => best,
                _ => Some((r, a)),
            })
            .map(|(r, _)| r.field.clone());
        let halfwidth = stiction.halfwidth();
        let stopping = Stopping {
            rule: if plan.target_halfwidth.is_some() && points.len() < plan.indices().len() {
                "target_halfwidth"
            } else {
                "samples"
            },
            samples_requested: plan.samples,
            target_halfwidth: plan.target_halfwidth,
            halfwidth,
            target_met: plan.target_halfwidth.map(|h| n > 0 && halfwidth <= h),
        };
        let exact_inside_interval = exact
            .and_then(|e| e.stiction_probability)
            .filter(|_| n > 0)
            .map(|p| p >= stiction.ci_low && p <= stiction.ci_high);
        let all_samples = AllSamples {
            denominator: ran,
            outside_validity: ran_outside,
            stiction: Estimate::of(ran_sticks, ran, conf),
            does_not_close: Estimate::of(ran_dnc, ran, conf),
        };
        Summary {
            samples: points.len(),
            stiction_probability: stiction.probability,
            ci_low: stiction.ci_low,
            ci_high: stiction.ci_high,
            confidence: conf,
            does_not_close_probability: does_not_close.probability,
            outside_validity: ran_outside,
            count_outside_validity: all,
            all_samples,
            by_cycle,
            denominator: n,
            stiction,
            does_not_close,
            counts: c,
            rank_correlation,
            driver,
            stopping,
            exact_inside_interval,
        }
    }
}

// ------------------------------------------------------------------ the exact answer

/// A boundary of the exact single-field answer: where the ratio crosses 1 (`stiction`) or
/// where the switch stops closing (`closure`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExactBoundary {
    /// `stiction` or `closure`.
    pub kind: String,
    /// The critical value.
    pub value: f64,
    /// Its uncertainty (the threshold's).
    pub uncertainty: f64,
    /// The distribution's CDF there.
    pub cdf: f64,
    /// `stiction`: the side that is free (`above`, `below`); `closure`: the side that closes.
    pub side: String,
    /// `continuous` or `jump` for a stiction boundary.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crossing: Option<String>,
}

/// The exact answer when a single field scatters: the field's threshold located over its
/// effective range (quantiles [`EXACT_TAIL`] to 1 - [`EXACT_TAIL`]), then P = the
/// distribution's mass on the side that sticks (F(critical) or 1 - F(critical)).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Exact {
    /// The field.
    pub field: String,
    /// Whether the exact answer is given (the ratio is monotone in the field, every scan
    /// point ran and every boundary was located).
    pub available: bool,
    /// Why not, when it is not.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// Whether the ratio of the closing scan points is monotone in the field, with at most
    /// one stiction and one closure boundary.
    pub monotone: bool,
    /// `increasing`, `decreasing` or `constant` (the ratio against the field).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<String>,
    /// P(stiction) from the CDF.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiction_probability: Option<f64>,
    /// Its uncertainty: pdf x the critical value's uncertainty, summed over the boundaries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uncertainty: Option<f64>,
    /// P(does not close) from the CDF.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub does_not_close_probability: Option<f64>,
    /// Its uncertainty.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub does_not_close_uncertainty: Option<f64>,
    /// The critical value of the stiction boundary, if there is one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub critical_value: Option<f64>,
    /// Its free side (`above`, `below`); without a boundary, `whole_range`, `nowhere` or
    /// `where_it_closes`, as the threshold says.
    pub free_side: String,
    /// The boundaries, ascending.
    pub boundaries: Vec<ExactBoundary>,
    /// The scanned range: the quantiles of [`EXACT_TAIL`], within the field's domain.
    pub range: [f64; 2],
    /// The mass beyond the range (its state is that of the nearest end).
    pub tail_mass: f64,
    /// Evaluations of the threshold search.
    pub evaluations: usize,
    /// Scan points outside the model's validity (the exact answer includes them; the
    /// Monte Carlo estimate counts such samples apart).
    pub scan_outside_validity: usize,
}

/// The range the exact answer scans: the quantiles of [`EXACT_TAIL`] and 1 - [`EXACT_TAIL`]
/// of `scatter`'s distribution, clamped to [`lo`, `hi`] (the field's domain).
pub fn exact_range(scatter: &Scatter, lo: f64, hi: f64) -> (f64, f64) {
    let d = &scatter.dist;
    (
        d.quantile(EXACT_TAIL).clamp(lo, hi),
        d.quantile(1.0 - EXACT_TAIL).clamp(lo, hi),
    )
}

/// The exact answer for a single scattered field: [`threshold`] over `range` (see
/// [`exact_range`]), then the distribution's mass on each side of every boundary. The
/// tails beyond the range take the state of the nearest scan point. Not available (with
/// the reason) when a scan point failed, a boundary could not be located, or the ratio is
/// not monotone among the closing points (or crosses 1 or stops closing more than once).
pub fn exact_single_field<F, E>(
    scatter: &Scatter,
    range: (f64, f64),
    eval: F,
    options: &ThresholdOptions,
) -> Result<Exact, DesignError>
where
    F: Fn(f64) -> Result<DesignPoint, E> + Sync,
    E: Into<PointError>,
{
    let d = &scatter.dist;
    let t = threshold(&scatter.field, range.0, range.1, eval, options)?;
    let mut e = Exact {
        field: scatter.field.clone(),
        available: false,
        reason: None,
        monotone: false,
        direction: None,
        stiction_probability: None,
        uncertainty: None,
        does_not_close_probability: None,
        does_not_close_uncertainty: None,
        critical_value: t.critical_value,
        free_side: t.free_side.word().to_owned(),
        boundaries: Vec::new(),
        range: [range.0, range.1],
        tail_mass: d.cdf(range.0) + d.sf(range.1),
        evaluations: t.evaluations,
        scan_outside_validity: t
            .scan
            .iter()
            .filter(|p| p.validity_holds == Some(false))
            .count(),
    };
    for c in &t.crossings {
        e.boundaries.push(ExactBoundary {
            kind: "stiction".into(),
            value: c.critical_value,
            uncertainty: c.uncertainty,
            cdf: d.cdf(c.critical_value),
            side: c.free_side.word().into(),
            crossing: Some(c.kind.word().into()),
        });
    }
    for b in &t.closure_boundaries {
        e.boundaries.push(ExactBoundary {
            kind: "closure".into(),
            value: b.value,
            uncertainty: b.uncertainty,
            cdf: d.cdf(b.value),
            side: b.closes_side.word().into(),
            crossing: None,
        });
    }
    e.boundaries.sort_by(|a, b| a.value.total_cmp(&b.value));
    let unavailable = |mut e: Exact, why: String| {
        e.reason = Some(why);
        Ok(e)
    };
    if let Some(p) = t.failed_points().next() {
        return unavailable(
            e,
            format!(
                "the scan point {} = {} is {}: {}",
                scatter.field,
                short(p.value),
                p.status,
                p.detail.clone().unwrap_or_default()
            ),
        );
    }
    // the ratio of the closing scan points against the value
    let closing: Vec<f64> = t
        .scan
        .iter()
        .filter(|p| p.closes == Some(true))
        .filter_map(|p| p.pull_out_ratio)
        .collect();
    let up = closing.windows(2).all(|w| w[1] >= w[0]);
    let down = closing.windows(2).all(|w| w[1] <= w[0]);
    e.direction = match (up, down) {
        (true, true) => Some("constant".into()),
        (true, false) => Some("increasing".into()),
        (false, true) => Some("decreasing".into()),
        _ => None,
    };
    e.monotone = (up || down) && t.crossings.len() <= 1 && t.closure_boundaries.len() <= 1;
    if !e.monotone {
        return unavailable(
            e,
            format!(
                "the ratio is not monotone in {} over the range ({} crossing(s) of 1, {} closure boundary(ies), ratio {} along the scan): only the Monte Carlo estimate holds",
                scatter.field,
                t.crossings.len(),
                t.closure_boundaries.len(),
                if up || down { "monotone" } else { "up and down" }
            ),
        );
    }
    if t.crossings
        .iter()
        .any(|c| c.kind == CrossingKind::Unresolved)
        || t.closure_boundaries.iter().any(|b| b.detail.is_some())
    {
        return unavailable(
            e,
            "a boundary could not be located (a point failed while it was refined)".into(),
        );
    }
    // the state along the scan: 0 free, 1 sticks, 2 does not close
    let state = |p: &crate::threshold::ScanPoint| match (p.closes, p.pull_out_ratio) {
        (Some(false), _) => 2u8,
        (_, Some(r)) if r > 1.0 => 1,
        _ => 0,
    };
    // the state of the stretch between boundaries k - 1 and k (k = 0: below the first),
    // from the sides the boundaries state: a switch free of stiction just where it starts
    // to close lies between a closure boundary and a crossing with no scan point inside
    let closure = e.boundaries.iter().position(|b| b.kind == "closure");
    let crossing = e.boundaries.iter().position(|b| b.kind == "stiction");
    let closing_ratio_above_1 = t
        .scan
        .iter()
        .find(|p| p.closes == Some(true))
        .and_then(|p| p.pull_out_ratio)
        .map(|r| r > 1.0);
    let stretch_state = |k: usize| -> Option<u8> {
        // stretch k lies above boundary j when j < k
        let above = |j: usize| j < k;
        let closes = match closure {
            Some(j) => above(j) == (e.boundaries[j].side == "above"),
            None => t.scan[0].closes == Some(true),
        };
        if !closes {
            return Some(2);
        }
        let sticks = match crossing {
            // free below: above it the design sticks
            Some(j) => above(j) == (e.boundaries[j].side == "below"),
            None => closing_ratio_above_1?,
        };
        Some(u8::from(sticks))
    };
    let n_stretches = e.boundaries.len() + 1;
    let mut states = Vec::with_capacity(n_stretches);
    for k in 0..n_stretches {
        match stretch_state(k) {
            Some(s) => states.push(s),
            None => {
                return unavailable(
                    e,
                    "the switch closes only between two boundaries, where no scan point tells whether it sticks".into(),
                )
            }
        }
    }
    // every scan point must lie in a stretch of its own state
    for p in &t.scan {
        let k = e.boundaries.iter().filter(|b| b.value < p.value).count();
        if states[k] != state(p) {
            return unavailable(
                e,
                format!(
                    "the state at {} = {} is not the one its boundaries imply",
                    scatter.field,
                    short(p.value)
                ),
            );
        }
    }
    // runs of one state between cuts (None: the distribution's end)
    let mut runs: Vec<(u8, Option<usize>, Option<usize>)> = Vec::new();
    for (k, &s) in states.iter().enumerate() {
        let left = k.checked_sub(1);
        let right = (k < e.boundaries.len()).then_some(k);
        runs.push((s, left, right));
    }
    let mass = |l: Option<usize>, r: Option<usize>| {
        let lv = l.map(|k| e.boundaries[k].value);
        let rv = r.map(|k| e.boundaries[k].value);
        match (lv, rv) {
            (None, None) => 1.0,
            (None, Some(r)) => d.cdf(r),
            (Some(l), None) => d.sf(l),
            (Some(l), Some(r)) => {
                if d.cdf(l) > 0.5 {
                    d.sf(l) - d.sf(r)
                } else {
                    d.cdf(r) - d.cdf(l)
                }
            }
        }
    };
    let edge = |k: Option<usize>| {
        k.map_or(0.0, |k| {
            let b = &e.boundaries[k];
            d.pdf(b.value) * b.uncertainty
        })
    };
    let (mut stick, mut stick_u, mut dnc, mut dnc_u) = (0.0, 0.0, 0.0, 0.0);
    for &(s, l, r) in &runs {
        match s {
            1 => {
                stick += mass(l, r);
                stick_u += edge(l) + edge(r);
            }
            2 => {
                dnc += mass(l, r);
                dnc_u += edge(l) + edge(r);
            }
            _ => {}
        }
    }
    e.available = true;
    e.stiction_probability = Some(stick.clamp(0.0, 1.0));
    e.uncertainty = Some(stick_u);
    e.does_not_close_probability = Some(dnc.clamp(0.0, 1.0));
    e.does_not_close_uncertainty = Some(dnc_u);
    Ok(e)
}

// ------------------------------------------------------------------ the run

/// A probability run (whole, one shard, or merged): the plan, the samples in index order,
/// the exact single-field answer if computed, and their statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct Probability {
    plan: ProbabilityPlan,
    points: Vec<SamplePoint>,
    exact: Option<Exact>,
    summary: Summary,
}

/// Runs the samples of `plan` (all, or its shard's) through `eval` in parallel on the
/// current rayon pool, collected in index order. With a target half-width, samples run in
/// blocks of [`STOP_CHECK_EVERY`] (in index order) and the run stops after the first block
/// at which the stiction interval is narrow enough: the same samples on any thread count.
/// A sample whose evaluator errs, panics or answers inconsistently gets its status and the
/// run goes on. `progress(done, total)` is called with `done = 0` and after every sample.
pub fn run_probability<F, E, P>(
    plan: ProbabilityPlan,
    eval: F,
    progress: P,
) -> Result<Probability, DesignError>
where
    F: Fn(&[(&str, f64)]) -> Result<DesignPoint, E> + Sync,
    E: Into<PointError>,
    P: Fn(usize, usize) + Sync,
{
    let sampler = plan.sampler()?;
    let indices = plan.indices();
    let total = indices.len();
    progress(0, total);
    let done = AtomicUsize::new(0);
    let fields: Vec<&str> = plan.scatter.iter().map(|s| s.field.as_str()).collect();
    let one = |index: usize| {
        let values = sampler.values(index);
        let args: Vec<(&str, f64)> = fields.iter().copied().zip(values.iter().copied()).collect();
        let (status, design) = guarded(|| eval(&args));
        progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
        SamplePoint {
            index,
            values,
            status,
            design,
        }
    };
    let points: Vec<SamplePoint> = match plan.target_halfwidth {
        None => indices.par_iter().map(|&i| one(i)).collect(),
        Some(h) => {
            let mut points = Vec::with_capacity(total);
            for block in indices.chunks(STOP_CHECK_EVERY) {
                points.par_extend(block.par_iter().map(|&i| one(i)));
                let all = plan.count_outside_validity;
                let n = points.iter().filter(|p| p.counted_counting(all)).count();
                let x = points
                    .iter()
                    .filter(|p| p.outcome_counting(all) == Outcome::Sticks)
                    .count();
                if clopper_pearson(x, n, plan.confidence).is_some_and(|(l, u)| 0.5 * (u - l) <= h) {
                    break;
                }
            }
            points
        }
    };
    Ok(Probability::new(plan, points, None))
}

impl Probability {
    /// A run from its parts; the statistics are computed here.
    pub fn new(plan: ProbabilityPlan, points: Vec<SamplePoint>, exact: Option<Exact>) -> Self {
        let summary = Summary::of(&plan, &points, exact.as_ref());
        Probability {
            plan,
            points,
            exact,
            summary,
        }
    }

    /// The same run with the exact single-field answer.
    pub fn with_exact(self, exact: Option<Exact>) -> Self {
        Probability::new(self.plan, self.points, exact)
    }

    /// The plan.
    pub fn plan(&self) -> &ProbabilityPlan {
        &self.plan
    }

    /// The samples, ascending index.
    pub fn points(&self) -> &[SamplePoint] {
        &self.points
    }

    /// The exact single-field answer, if computed.
    pub fn exact(&self) -> Option<&Exact> {
        self.exact.as_ref()
    }

    /// The statistics.
    pub fn summary(&self) -> &Summary {
        &self.summary
    }

    /// `probability.json`: the statistics, the exact answer, the plan and every sample,
    /// pretty-printed with a final newline (no null, no NaN).
    pub fn to_json(&self) -> String {
        self.json(true)
    }

    /// The statistics, the exact answer and the plan, without the samples (what
    /// `--format json` prints).
    pub fn summary_json(&self) -> String {
        self.json(false)
    }

    fn json(&self, points: bool) -> String {
        let mut s = serde_json::to_string_pretty(&self.view(points))
            .expect("a probability run always serialises");
        s.push('\n');
        s
    }

    /// The run as JSON records: with the samples (`probability.json`) or without them (the
    /// summary `--format json` prints). `Probability` itself serialises with them.
    pub fn view(&self, points: bool) -> ProbabilityView<'_> {
        ProbabilityView { run: self, points }
    }

    fn out(&self, points: bool) -> ProbabilityOut<'_> {
        ProbabilityOut {
            format: PROBABILITY_FORMAT,
            version: PROBABILITY_VERSION,
            summary: &self.summary,
            exact: self.exact.as_ref(),
            accuracy: &self.plan.accuracy,
            ratio_rel_error: self.plan.ratio_rel_error,
            scatter: self.plan.scatter.iter().map(|s| s.to_string()).collect(),
            correlate: self
                .plan
                .correlations
                .iter()
                .map(|c| c.to_string())
                .collect(),
            seed: self.plan.seed,
            samples_requested: self.plan.samples,
            cycles: self.plan.cycles,
            target_halfwidth: self.plan.target_halfwidth,
            shard: self.plan.shard,
            scene: &self.plan.scene,
            points: points.then(|| {
                self.points
                    .iter()
                    .map(|p| PointOut {
                        index: p.index,
                        values: Named(&self.plan.scatter, &p.values),
                        status: p.status.word(),
                        detail: p.status.detail(),
                        design: p.design.as_ref(),
                    })
                    .collect()
            }),
        }
    }

    /// Reads a `probability.json` file (bounded like [`crate::Map::read_path`]).
    pub fn read_path(path: impl AsRef<Path>) -> Result<Probability, DesignError> {
        let path = path.as_ref();
        let text = read_bounded(
            path,
            "a probability.json",
            "`design probability`",
            "a probability run",
        )?;
        Probability::from_json(&text).map_err(|e| DesignError::MapFile {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
    }

    /// Reads a `probability.json` back, checking it: known format, a valid plan (the
    /// scattered fields and correlations read back to the same text), points ascending,
    /// inside the plan (and its shard), with exactly the values the seed gives them, each
    /// consistent ([`DesignPoint::check`]). The statistics are recomputed from the points.
    pub fn from_json(text: &str) -> Result<Probability, DesignError> {
        let m: ProbabilityIn =
            serde_json::from_str(text).map_err(|e| DesignError::ProbabilityJson(e.to_string()))?;
        let bad = |m: String| DesignError::ProbabilityJson(m);
        if m.format != PROBABILITY_FORMAT || m.version != PROBABILITY_VERSION {
            return Err(bad(format!(
                "format `{}` version {}, expected `{PROBABILITY_FORMAT}` version {PROBABILITY_VERSION}",
                m.format, m.version
            )));
        }
        let scatter = m
            .scatter
            .iter()
            .map(|s| Scatter::parse(s))
            .collect::<Result<Vec<_>, _>>()?;
        let correlations = m
            .correlate
            .iter()
            .map(|c| Correlation::parse(c))
            .collect::<Result<Vec<_>, _>>()?;
        if let Some(s) = m.shard {
            Shard::new(s.k, s.n)?;
        }
        let plan = ProbabilityPlan {
            scene: m.scene,
            accuracy: m.accuracy,
            ratio_rel_error: m.ratio_rel_error,
            scatter,
            correlations,
            seed: m.seed,
            samples: m.samples_requested,
            confidence: m.confidence,
            cycles: m.cycles,
            target_halfwidth: m.target_halfwidth,
            shard: m.shard,
            count_outside_validity: m.count_outside_validity,
        };
        let sampler = plan.sampler()?;
        let mut points = Vec::with_capacity(m.points.len());
        let mut last = None;
        for p in m.points {
            let i = p.index;
            if i >= plan.samples {
                return Err(bad(format!(
                    "point index {i} outside the {} samples",
                    plan.samples
                )));
            }
            if last.is_some_and(|l| i <= l) {
                return Err(bad(format!("point index {i} out of order or repeated")));
            }
            last = Some(i);
            if let Some(s) = plan.shard {
                if !s.contains(i) {
                    return Err(bad(format!("point {i} does not belong to shard {s}")));
                }
            }
            let values = sampler.values(i);
            for (s, v) in plan.scatter.iter().zip(&values) {
                if p.values.get(&s.field) != Some(&ValueIn::Number(*v)) {
                    return Err(bad(format!(
                        "point {i}: {} is not the value {v:e} that seed {} gives sample {i}",
                        s.field, plan.seed
                    )));
                }
            }
            if let Some(k) = p
                .values
                .keys()
                .find(|k| !plan.scatter.iter().any(|s| &s.field == *k))
            {
                return Err(bad(format!("point {i}: values.{k}: not a scattered field")));
            }
            let (status, design) = point_design(i, &p).map_err(bad)?;
            points.push(SamplePoint {
                index: i,
                values,
                status,
                design,
            });
        }
        if let Some(e) = &m.exact {
            if plan.scatter.len() != 1 || e.field != plan.scatter[0].field {
                return Err(bad(format!(
                    "exact: an exact answer for {} in a run that does not scatter it alone",
                    e.field
                )));
            }
        }
        Ok(Probability::new(plan, points, m.exact))
    }
}

/// Joins the shards of one probability run into exactly the run without shards (its JSON,
/// CSV and plot are byte-identical to those of the whole run). Refuses, naming the part
/// (its label, the folder it came from): no parts, an unsharded run, differing plans
/// (scene, accuracy, scattered fields, correlations, seed, samples, confidence, cycles)
/// or exact answers, differing N, a repeated or missing part, a part that does not hold
/// exactly its share of the samples.
pub fn merge_probability<I>(parts: I) -> Result<Probability, DesignError>
where
    I: IntoIterator<Item = (String, Probability)>,
{
    let parts: Vec<(String, Probability)> = parts.into_iter().collect();
    let Some((first_label, first)) = parts.first() else {
        return Err(DesignError::Merge {
            shard: "(nothing)".into(),
            reason: "no parts given".into(),
        });
    };
    let refuse = |label: &str, reason: String| DesignError::Merge {
        shard: label.to_owned(),
        reason,
    };
    let part = |label: &str, p: &Probability| {
        p.plan.shard.ok_or_else(|| {
            refuse(
                label,
                "holds an unsharded probability run (parts are made by a sharded run, --shard K/N)"
                    .into(),
            )
        })
    };
    let n = part(first_label, first)?.n;
    let mut owner: BTreeMap<usize, &str> = BTreeMap::new();
    for (label, p) in &parts {
        let s = part(label, p)?;
        if s.n != n {
            return Err(refuse(
                label,
                format!(
                    "is part {s} (of {} parts) but {first_label} is one of {n} parts",
                    s.n
                ),
            ));
        }
        let (a, b) = (&first.plan, &p.plan);
        if a.scene != b.scene {
            return Err(refuse(
                label,
                format!(
                    "its scene differs from {first_label}'s at {}",
                    first_difference(&a.scene, &b.scene, String::new())
                ),
            ));
        }
        let differs = |what: &str, x: String, y: String| {
            refuse(
                label,
                format!("{what} `{y}` differs from {first_label}'s `{x}`"),
            )
        };
        let list = |v: &[String]| v.join(" ");
        let texts = |p: &ProbabilityPlan| {
            (
                p.scatter.iter().map(|s| s.to_string()).collect::<Vec<_>>(),
                p.correlations
                    .iter()
                    .map(|c| c.to_string())
                    .collect::<Vec<_>>(),
            )
        };
        let ((sa, ca), (sb, cb)) = (texts(a), texts(b));
        if a.accuracy != b.accuracy || a.ratio_rel_error != b.ratio_rel_error {
            return Err(differs("accuracy", a.accuracy.clone(), b.accuracy.clone()));
        }
        if sa != sb {
            return Err(differs("scatter", list(&sa), list(&sb)));
        }
        if ca != cb {
            return Err(differs("correlate", list(&ca), list(&cb)));
        }
        if a.seed != b.seed {
            return Err(differs("seed", a.seed.to_string(), b.seed.to_string()));
        }
        if a.samples != b.samples {
            return Err(differs(
                "samples",
                a.samples.to_string(),
                b.samples.to_string(),
            ));
        }
        if a.confidence != b.confidence {
            return Err(differs(
                "confidence",
                a.confidence.to_string(),
                b.confidence.to_string(),
            ));
        }
        if a.cycles != b.cycles {
            return Err(differs(
                "cycles",
                a.cycles.to_string(),
                b.cycles.to_string(),
            ));
        }
        if p.exact != first.exact {
            return Err(refuse(
                label,
                format!("its exact answer differs from {first_label}'s (parts of one run compute the same)"),
            ));
        }
        if let Some(other) = owner.insert(s.k, label) {
            return Err(refuse(label, format!("part {s} is also in {other}")));
        }
        let expected: Vec<usize> = s.indices(b.samples).collect();
        let got: Vec<usize> = p.points.iter().map(|q| q.index).collect();
        if got != expected {
            return Err(refuse(
                label,
                format!(
                    "part {s} holds {} samples, expected {} (an incomplete or altered part)",
                    got.len(),
                    expected.len()
                ),
            ));
        }
    }
    if owner.len() < n {
        let missing: Vec<String> = (1..=n)
            .filter(|k| !owner.contains_key(k))
            .take(20)
            .map(|k| format!("{k}/{n}"))
            .collect();
        let more = n - owner.len() - missing.len();
        return Err(refuse(
            &parts
                .iter()
                .map(|(l, _)| l.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            format!(
                "missing part(s) {}{}",
                missing.join(", "),
                if more > 0 {
                    format!(" and {more} more")
                } else {
                    String::new()
                }
            ),
        ));
    }
    let mut plan = first.plan.clone();
    plan.shard = None;
    let exact = first.exact.clone();
    let mut points: Vec<SamplePoint> = parts.into_iter().flat_map(|(_, p)| p.points).collect();
    points.sort_by_key(|p| p.index);
    Ok(Probability::new(plan, points, exact))
}

// ------------------------------------------------------------ JSON records

/// A probability run serialised with or without its samples ([`Probability::view`]).
#[derive(Debug, Clone, Copy)]
pub struct ProbabilityView<'a> {
    run: &'a Probability,
    points: bool,
}

impl Serialize for ProbabilityView<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.run.out(self.points).serialize(s)
    }
}

impl Serialize for Probability {
    /// `probability.json`'s records, samples included.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.out(true).serialize(s)
    }
}

#[derive(Serialize)]
struct ProbabilityOut<'a> {
    format: &'static str,
    version: u32,
    #[serde(flatten)]
    summary: &'a Summary,
    #[serde(skip_serializing_if = "Option::is_none")]
    exact: Option<&'a Exact>,
    accuracy: &'a str,
    ratio_rel_error: f64,
    scatter: Vec<String>,
    correlate: Vec<String>,
    seed: u64,
    samples_requested: usize,
    cycles: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    target_halfwidth: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    shard: Option<Shard>,
    scene: &'a Value,
    #[serde(skip_serializing_if = "Option::is_none")]
    points: Option<Vec<PointOut<'a>>>,
}

#[derive(Serialize)]
struct PointOut<'a> {
    index: usize,
    values: Named<'a>,
    status: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    detail: Option<&'a str>,
    #[serde(flatten)]
    design: Option<&'a DesignPoint>,
}

/// Field values as a JSON object in the order of the scattered fields.
struct Named<'a>(&'a [Scatter], &'a [f64]);

impl Serialize for Named<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(Some(self.1.len()))?;
        for (f, v) in self.0.iter().zip(self.1) {
            m.serialize_entry(&f.field, v)?;
        }
        m.end()
    }
}

/// What is read back: the plan, the exact answer and the points (the statistics are
/// recomputed, so their keys are ignored).
#[derive(Deserialize)]
struct ProbabilityIn {
    format: String,
    version: u32,
    accuracy: String,
    ratio_rel_error: f64,
    scatter: Vec<String>,
    #[serde(default)]
    correlate: Vec<String>,
    seed: u64,
    samples_requested: usize,
    confidence: f64,
    cycles: usize,
    #[serde(default)]
    target_halfwidth: Option<f64>,
    #[serde(default)]
    shard: Option<Shard>,
    scene: Value,
    #[serde(default)]
    exact: Option<Exact>,
    points: Vec<PointIn>,
    #[serde(default)]
    count_outside_validity: bool,
}
