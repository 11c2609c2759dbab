//! The failure probability of a switch whose design fields scatter from die to die: each
//! scattered field (`FIELD=DIST`, any field `design map` may vary) is sampled from its
//! distribution, every sample is a design point ([`crate::design::Evaluator`]: the scene
//! run until accommodated), and the engine of `design-sweep` reduces them to the
//! probability of stiction by cycle, after accommodation and of "does not close", with
//! exact binomial (Clopper-Pearson) intervals, the rank correlation of each field with the
//! pull-out ratio and, when a single field scatters, the exact answer from its threshold
//! and CDF. User guide: `docs/design.md`; statistics: `docs/theory.md` section 10.
//!
//! ```no_run
//! use stiction_model::{keys::Kind, laws::LawRegistry, scene::Scene, Silent};
//! use stiction_model::probability::{run, ProbabilityRequest};
//! let mut scene = Scene::paper(Kind::Switch);
//! scene.set_text("contact.yield_modulus", "composite")?;
//! let request = ProbabilityRequest {
//!     scatter: vec!["surface.sigma_s=lognormal(7.78e-9,1.1)".into()],
//!     samples: 200,
//!     accuracy: Some(stiction_model::Accuracy::Fast),
//!     ..ProbabilityRequest::default()
//! };
//! let r = run(&scene, &LawRegistry::builtin(), &request, &Silent)?;
//! let s = r.probability.summary();
//! println!("P(stiction) = {:?} [{}, {}]", s.stiction_probability, s.ci_low, s.ci_high);
//! # Ok::<(), stiction_model::ModelError>(())
//! ```

use crate::accuracy::Accuracy;
use crate::design::{base_spec, check_field_as, field_labels, root_tolerance, Evaluator, Labels};
use crate::error::ModelError;
use crate::guards::{Validity, Warning};
use crate::keys::num;
use crate::laws::LawRegistry;
use crate::scene::Scene;
use crate::Progress;
pub use design_sweep::{
    Correlation, Dist, Exact, Probability, ProbabilityPlan, Scatter, Shard, Summary,
    ThresholdOptions, EXACT_TAIL, MAX_SAMPLES, STOP_CHECK_EVERY,
};
use design_sweep::{DesignPoint, PointError};
use serde::Serialize;
use std::sync::Mutex;

/// The largest mass a distribution may put outside its field's domain. A distribution
/// with more is refused before any sample runs (values are never clipped); below it, a
/// sample that still lands outside is refused on its own (status `out_of_domain`, counted
/// apart), which shifts the estimate by at most this much.
pub const MAX_OUTSIDE_MASS: f64 = 1e-6;

/// A probability question. Options as the command line writes them, so that every front
/// end (CLI, Python) parses them the same way.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbabilityRequest {
    /// Scattered fields, `FIELD=DIST` (`surface.sigma_s=lognormal(7.78e-9,1.2)`); DIST is
    /// `normal(mean,sd)`, `lognormal(median,factor)`, `uniform(lo,hi)` or
    /// `weibull(scale,shape)`, in the field's SI unit.
    pub scatter: Vec<String>,
    /// Correlations `A,B=RHO` between scattered fields (Gaussian copula).
    pub correlate: Vec<String>,
    /// Samples to run (with `target_halfwidth`: the most).
    pub samples: usize,
    /// The seed: sample i's values depend on (seed, i) alone.
    pub seed: u64,
    /// Confidence of the intervals, in (0, 1).
    pub confidence: f64,
    /// Part `K/N` of the samples (merge the parts with `design merge`).
    pub shard: Option<String>,
    /// Stop once the stiction interval's half-width is at most this.
    pub target_halfwidth: Option<f64>,
    /// Accuracy mode of the design points (else the scene's).
    pub accuracy: Option<Accuracy>,
    /// With a single scattered field, also compute the exact answer (a threshold search,
    /// 10 to 40 design points).
    pub exact: bool,
    /// Count the samples outside the model's validity in the headline probabilities
    /// (`--count-outside-validity`); by default they are set apart and the all-samples
    /// answer is given beside (`all_samples`).
    pub count_outside_validity: bool,
}

impl Default for ProbabilityRequest {
    /// No field, 1000 samples, seed 0, 95 %, no shard, no target, the scene's accuracy,
    /// the exact answer on.
    fn default() -> Self {
        ProbabilityRequest {
            scatter: Vec::new(),
            correlate: Vec::new(),
            samples: 1000,
            seed: 0,
            confidence: 0.95,
            shard: None,
            target_halfwidth: None,
            accuracy: None,
            exact: true,
            count_outside_validity: false,
        }
    }
}

/// A computed probability run (whole or one shard) with the guards its samples raised.
#[derive(Debug, Clone)]
pub struct ProbabilityResult {
    /// The run: plan, samples, exact answer, statistics.
    pub probability: Probability,
    /// Units of the scattered fields, and the plot title.
    pub labels: Labels,
    /// Guards the samples raised, one per kind with its count.
    pub warnings: Vec<Warning>,
    /// Whether the model holds at every sample (those outside are counted apart).
    pub validity: Validity,
    /// The model-form check (`model_form = "check"`): P(stiction) under every combination
    /// of the credible published forms.
    pub model_form: Option<crate::model_form::ProbabilityModelForm>,
}

impl Serialize for ProbabilityResult {
    /// The statistics, the exact answer and the plan (no samples), with the validity.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct Out<'a> {
            #[serde(flatten)]
            run: design_sweep::ProbabilityView<'a>,
            validity: &'a Validity,
            #[serde(skip_serializing_if = "Option::is_none")]
            model_form: Option<&'a crate::model_form::ProbabilityModelForm>,
        }
        Out {
            run: self.probability.view(false),
            validity: &self.validity,
            model_form: self.model_form.as_ref(),
        }
        .serialize(s)
    }
}

/// The checked plan of a request: the scene with the design settings, every scattered
/// field known, fitting the drive and with a distribution inside its domain (at most
/// [`MAX_OUTSIDE_MASS`] outside), correlations, shard, samples and statistics settings
/// valid. Nothing runs. Errors name the arguments `scatter`, `correlate`, `shard`,
/// `samples`, `confidence`, `target_halfwidth`.
pub fn plan(
    scene: &Scene,
    registry: &LawRegistry,
    request: &ProbabilityRequest,
) -> Result<(Scene, ProbabilityPlan), ModelError> {
    let (base, spec) = base_spec(scene, registry, request.accuracy)?;
    if request.scatter.is_empty() {
        return Err(ModelError::argument(
            "scatter",
            "(none)",
            "at least one FIELD=DIST, e.g. surface.sigma_s=lognormal(7.78e-9,1.2)",
        ));
    }
    let mut scatter = Vec::with_capacity(request.scatter.len());
    for option in &request.scatter {
        let s = Scatter::parse(option)?;
        let f = check_field_as(&s.field, &spec, "scatter")?;
        if let Some((lo, hi)) = f.domain.bounds() {
            let (below, above) = (
                if lo == f64::NEG_INFINITY {
                    0.0
                } else {
                    s.dist.cdf(lo)
                },
                if hi == f64::INFINITY {
                    0.0
                } else {
                    s.dist.sf(hi)
                },
            );
            if below + above > MAX_OUTSIDE_MASS {
                let mut parts = Vec::new();
                if below > 0.0 {
                    parts.push(format!("{below:.2e} of its mass below {}", num(lo)));
                }
                if above > 0.0 {
                    parts.push(format!("{above:.2e} above {}", num(hi)));
                }
                return Err(ModelError::argument(
                    "scatter",
                    option,
                    format!(
                        "a distribution inside the domain of {} ({}): {} puts {} (at most {} may lie outside; values are never clipped). {}arrow the distribution",
                        f.key,
                        f.domain.describe(),
                        s.dist,
                        parts.join(" and "),
                        num(MAX_OUTSIDE_MASS),
                        if lo >= 0.0 {
                            "For a positive field give lognormal(median,factor) or weibull(scale,shape), or n"
                        } else {
                            "N"
                        }
                    ),
                ));
            }
        }
        scatter.push(s);
    }
    let correlations = request
        .correlate
        .iter()
        .map(|c| Correlation::parse(c))
        .collect::<Result<Vec<_>, _>>()?;
    let shard = request.shard.as_deref().map(Shard::parse).transpose()?;
    let accuracy = spec.common.accuracy;
    let plan = ProbabilityPlan {
        scene: spec.common.echo(),
        accuracy: accuracy.as_str().into(),
        ratio_rel_error: accuracy.targets().pull_out_tolerance,
        scatter,
        correlations,
        seed: request.seed,
        samples: request.samples,
        confidence: request.confidence,
        cycles: spec.cycles,
        target_halfwidth: request.target_halfwidth,
        shard,
        count_outside_validity: request.count_outside_validity,
    };
    // the plan's own checks, named as the request's arguments
    if !(1..=MAX_SAMPLES).contains(&request.samples) {
        return Err(ModelError::argument(
            "samples",
            request.samples.to_string(),
            format!("in 1..={MAX_SAMPLES}"),
        ));
    }
    if !(request.confidence > 0.0 && request.confidence < 1.0) {
        return Err(ModelError::argument(
            "confidence",
            request.confidence.to_string(),
            "in (0, 1), e.g. 0.95",
        ));
    }
    if let Some(h) = request.target_halfwidth {
        if !(h > 0.0 && h <= 0.5) {
            return Err(ModelError::argument(
                "target_halfwidth",
                h.to_string(),
                "in (0, 0.5] (half the width of a probability's interval)",
            ));
        }
        if shard.is_some() {
            return Err(ModelError::argument(
                "target_halfwidth",
                h.to_string(),
                "given without --shard: a part cannot see the other parts' samples (give the parts a fixed number of samples)",
            ));
        }
    }
    plan.sampler()?;
    Ok((base, plan))
}

/// Runs a probability question: the samples of the plan in parallel (each reported to
/// `progress`), then, when a single field scatters and `request.exact`, the exact answer
/// from the field's threshold over its effective range and its CDF.
pub fn run(
    scene: &Scene,
    registry: &LawRegistry,
    request: &ProbabilityRequest,
    progress: &dyn Progress,
) -> Result<ProbabilityResult, ModelError> {
    run_answered(scene, registry, request, progress, None)
}

/// A sample's design point computed elsewhere (a cluster's worker, `Evaluator::result`
/// reduced by `design::design_point`) with the guards it raised.
pub type Answer = (Result<DesignPoint, PointError>, Vec<Warning>);

/// The key of a sample's answer: the bits of its scattered values, in the plan's order.
pub fn answer_key(values: &[f64]) -> Vec<u64> {
    values.iter().map(|v| v.to_bits()).collect()
}

/// The samples of a plan to run elsewhere (a cluster): the design scene (the base of every
/// sample, as TOML text) and each sample's index and (field, value) pairs, checked as
/// [`run`] checks them before any sample runs.
#[allow(clippy::type_complexity)]
pub fn samples_to_run(
    scene: &Scene,
    registry: &LawRegistry,
    request: &ProbabilityRequest,
) -> Result<(String, Vec<(usize, Vec<(String, f64)>)>), ModelError> {
    let (base, plan) = plan(scene, registry, request)?;
    let sampler = plan.sampler()?;
    let fields: Vec<String> = plan.scatter.iter().map(|s| s.field.clone()).collect();
    let points = plan
        .indices()
        .into_iter()
        .map(|i| (i, fields.iter().cloned().zip(sampler.values(i)).collect()))
        .collect();
    Ok((crate::scenegen::to_toml(&base), points))
}

/// [`run`] with the samples' design points given (`answers`, by [`answer_key`]) instead of
/// evaluated here: the same engine records them, so the result equals a local run's (a
/// sample without an answer is `failed`). None evaluates them here.
pub fn run_answered(
    scene: &Scene,
    registry: &LawRegistry,
    request: &ProbabilityRequest,
    progress: &dyn Progress,
    answers: Option<&std::collections::HashMap<Vec<u64>, Answer>>,
) -> Result<ProbabilityResult, ModelError> {
    let (base, plan) = plan(scene, registry, request)?;
    crate::check_cancelled(progress)?;
    let ev = Evaluator::new(base.clone(), registry).stopped_by(progress);
    let fields: Vec<String> = plan.scatter.iter().map(|s| s.field.clone()).collect();
    let single = (plan.scatter.len() == 1 && request.exact).then(|| plan.scatter[0].clone());
    let accuracy = [
        Accuracy::Accurate,
        Accuracy::Balanced,
        Accuracy::Fast,
        Accuracy::Reference,
    ]
    .into_iter()
    .find(|a| a.as_str() == plan.accuracy);
    let total = plan.indices().len();
    progress.start(total as u64, "samples");
    let done = Mutex::new(0u64);
    let run = design_sweep::run_probability(
        plan,
        |values: &[(&str, f64)]| match answers {
            None => ev.point(values),
            Some(answers) => {
                let key = answer_key(&values.iter().map(|v| v.1).collect::<Vec<_>>());
                match answers.get(&key) {
                    Some((r, w)) => {
                        ev.record(values, w);
                        r.clone()
                    }
                    None => Err(PointError::Failed(
                        "no answer came back for this sample".into(),
                    )),
                }
            }
        },
        |n, _| {
            if let Ok(mut d) = done.lock() {
                *d = (*d).max(n as u64);
                progress.set(*d);
            }
        },
    );
    // a stopped run is no answer: its samples after the stop failed for that reason alone
    crate::check_cancelled(progress)?;
    let run = run?;
    progress.finish();
    let evaluated = run.points().len();
    let exact = single.map(|s| exact(&base, registry, &s, accuracy, progress));
    crate::check_cancelled(progress)?;
    let run = run.with_exact(exact);
    let warnings = ev.warnings(evaluated);
    let mut labels = field_labels(fields.iter().map(String::as_str));
    if let Some(t) = run.plan().scene.get("title").and_then(|t| t.as_str()) {
        labels = labels.with_title(format!(
            "{t}: P(stuck by cycle n) ({}, {} samples)",
            run.plan().accuracy,
            run.summary().samples
        ));
    }
    // a run answered elsewhere gets its check from the front end that ran it there
    let model_form = match answers {
        None => model_form_check(scene, registry, request, &run, progress)?,
        Some(_) => None,
    };
    Ok(ProbabilityResult {
        validity: Validity::of(&warnings),
        labels,
        probability: run,
        warnings,
        model_form,
    })
}

/// The model-form check of a probability run whose scene asks for it: the same samples
/// (the same seed) under every other combination of the credible published forms, in the
/// check's mode, without the exact answer; None when the scene does not ask.
fn model_form_check(
    scene: &Scene,
    registry: &LawRegistry,
    request: &ProbabilityRequest,
    own: &Probability,
    progress: &dyn Progress,
) -> Result<Option<crate::model_form::ProbabilityModelForm>, ModelError> {
    use crate::model_form::{check_accuracy, each_form, ProbabilityFormRun, ProbabilityModelForm};
    let (_, spec) = crate::design::base_spec(scene, registry, request.accuracy)?;
    if !spec.model_form.check {
        return Ok(None);
    }
    let mode = check_accuracy(spec.common.accuracy);
    let of = |laws: crate::switch::Laws, p: &Probability| {
        let s = p.summary();
        ProbabilityFormRun {
            laws,
            stiction_probability: s.stiction_probability,
            interval: [s.ci_low, s.ci_high],
            sticking: s.stiction.count,
            counted: s.denominator,
        }
    };
    let alternative = ProbabilityRequest {
        accuracy: Some(mode),
        exact: false,
        ..request.clone()
    };
    let (_, ran, excluded) = each_form(&spec, registry, scene, progress, |s| {
        run(s, registry, &alternative, &crate::CancelOnly(progress))
    });
    crate::check_cancelled(progress)?;
    let mut runs = vec![of(crate::switch::Laws::of(&spec.contact), own)];
    runs.extend(ran.iter().map(|(form, r)| of(form.laws(), &r.probability)));
    Ok(Some(ProbabilityModelForm::of(
        mode,
        own.summary().confidence,
        runs,
        excluded,
    )))
}

/// The exact single-field answer on the design scene `base`: the threshold of the field
/// over its quantiles [`EXACT_TAIL`] .. 1 - [`EXACT_TAIL`] (within its domain), in the
/// plan's accuracy mode (root to a tenth of the mode's ratio error). A search that cannot
/// run is an unavailable answer with the reason, never an error of the run (a stopped
/// search is the caller's to discard: `progress` stops its points).
fn exact(
    base: &Scene,
    registry: &LawRegistry,
    s: &Scatter,
    accuracy: Option<Accuracy>,
    progress: &dyn Progress,
) -> Exact {
    let (lo, hi) = crate::keys::key(&s.field)
        .and_then(|k| k.domain.bounds())
        .unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    let range = design_sweep::exact_range(s, lo, hi);
    let a = accuracy.unwrap_or(Accuracy::Accurate);
    let options = ThresholdOptions {
        tolerance: root_tolerance(a),
        ratio_rel_error: a.targets().pull_out_tolerance,
        scan_points: None,
    };
    let ev = Evaluator::new(base.clone(), registry).stopped_by(progress);
    match design_sweep::exact_single_field(s, range, |x| ev.point(&[(&s.field, x)]), &options) {
        Ok(e) => e,
        Err(e) => Exact {
            field: s.field.clone(),
            available: false,
            reason: Some(e.to_string()),
            monotone: false,
            direction: None,
            stiction_probability: None,
            uncertainty: None,
            does_not_close_probability: None,
            does_not_close_uncertainty: None,
            critical_value: None,
            free_side: "unknown".into(),
            boundaries: Vec::new(),
            range: [range.0, range.1],
            tail_mass: s.dist.cdf(range.0) + s.dist.sf(range.1),
            evaluations: 0,
            scan_outside_validity: 0,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::keys::Kind;

    fn request(scatter: &[&str]) -> ProbabilityRequest {
        ProbabilityRequest {
            scatter: scatter.iter().map(|s| s.to_string()).collect(),
            samples: 10,
            ..ProbabilityRequest::default()
        }
    }

    fn refused(r: &ProbabilityRequest) -> String {
        let scene = Scene::paper(Kind::Switch);
        plan(&scene, &LawRegistry::builtin(), r)
            .map(|_| ())
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn a_distribution_with_mass_outside_the_domain_is_refused_naming_the_field() {
        let e = refused(&request(&["surface.sigma_s=normal(5e-9,5e-9)"]));
        assert!(
            e.contains("surface.sigma_s") && e.contains("below 1e-11"),
            "{e}"
        );
        assert!(
            e.contains("never clipped") && e.contains("lognormal"),
            "{e}"
        );
        let e = refused(&request(&["contact.poisson_ratio=uniform(0.2,0.6)"]));
        assert!(
            e.contains("contact.poisson_ratio") && e.contains("above 5e-1"),
            "{e}"
        );
        let e = refused(&request(&["contact.work_of_adhesion=normal(0.5,0.5)"]));
        assert!(e.contains("contact.work_of_adhesion"), "{e}");
        // a sliver far below the limit is accepted
        let scene = Scene::paper(Kind::Switch);
        let ok = request(&[
            "surface.sigma_s=normal(7.78e-9,1e-9)",
            "contact.work_of_adhesion=lognormal(0.5,1.3)",
            "contact.yield_stress=weibull(2.5e8,10)",
        ]);
        let (_, p) = plan(&scene, &LawRegistry::builtin(), &ok).unwrap();
        assert_eq!(p.scatter.len(), 3);
        assert_eq!(p.cycles, 10);
    }

    #[test]
    fn unknown_fields_drive_conflicts_and_bad_settings_are_refused_before_running() {
        let e = refused(&request(&["surface.sigma=lognormal(1e-8,1.2)"]));
        assert!(
            e.contains("invalid scatter: unknown field `surface.sigma`"),
            "{e}"
        );
        // the paper's scene gives the impact energy: k_s cannot scatter
        let e = refused(&request(&["switch.k_s=lognormal(1e10,1.2)"]));
        assert!(e.contains("k_s = <Pa/m>"), "{e}");
        let e = refused(&ProbabilityRequest {
            samples: 0,
            ..request(&["surface.sigma_s=lognormal(7.78e-9,1.1)"])
        });
        assert!(e.contains("samples = 0"), "{e}");
        let e = refused(&ProbabilityRequest {
            confidence: 95.0,
            ..request(&["surface.sigma_s=lognormal(7.78e-9,1.1)"])
        });
        assert!(e.contains("confidence = 95"), "{e}");
        let e = refused(&ProbabilityRequest {
            correlate: vec!["surface.sigma_s,contact.z0=0.5".into()],
            ..request(&["surface.sigma_s=lognormal(7.78e-9,1.1)"])
        });
        assert!(e.contains("contact.z0 is not a scattered field"), "{e}");
        let e = refused(&request(&[]));
        assert!(e.contains("at least one FIELD=DIST"), "{e}");
    }
}
