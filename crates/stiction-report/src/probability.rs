//! A failure-probability run (`stiction design probability`, `design merge` of its
//! parts): its table, the statistics as JSON, the samples as CSV and the plot; `--out`
//! writes samples.csv, probability.json, probability.svg and, with a model-form check,
//! model_form.json.

use crate::output::OutputSet;
use crate::plot::{svg, Band, Panel, Series};
use crate::render::{self, Format, Render, Validity, Warning};
use crate::{Plot, Report, ReportError};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;
use stiction_model::design::Labels;
use stiction_model::probability::{Probability, ProbabilityResult};

/// The files `design probability --out` and the merge of its parts write.
const PROBABILITY_FILES: &[&str] = &[
    "samples.csv",
    "probability.json",
    "probability.svg",
    "model_form.json",
];

/// A probability run with its labels, for rendering and writing.
#[derive(Debug, Clone)]
pub struct ProbabilityReport {
    /// The run.
    pub run: Probability,
    /// Units and title.
    pub labels: Labels,
    /// Guards the samples raised (printed on standard error).
    pub warnings: Vec<Warning>,
    /// Whether the model holds at every sample (a merge does not know).
    pub validity: Option<Validity>,
    /// The model-form check, when asked for.
    pub model_form: Option<stiction_model::model_form::ProbabilityModelForm>,
}

impl Serialize for ProbabilityReport {
    /// The statistics without the samples, with the validity when known.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct Out<'a> {
            #[serde(flatten)]
            run: stiction_model::design_sweep::ProbabilityView<'a>,
            #[serde(skip_serializing_if = "Option::is_none")]
            validity: Option<&'a Validity>,
            #[serde(skip_serializing_if = "Option::is_none")]
            model_form: Option<&'a stiction_model::model_form::ProbabilityModelForm>,
        }
        Out {
            run: self.run.view(false),
            validity: self.validity.as_ref(),
            model_form: self.model_form.as_ref(),
        }
        .serialize(s)
    }
}

impl ProbabilityReport {
    /// The report of a computed run.
    pub fn new(r: ProbabilityResult) -> Self {
        Self {
            run: r.probability,
            labels: r.labels,
            warnings: r.warnings,
            validity: Some(r.validity),
            model_form: r.model_form,
        }
    }

    /// The report of a merged run: labels from the run alone (so the plot is drawn
    /// exactly as an unsharded run's).
    pub fn merged(run: Probability) -> Self {
        Self {
            labels: labels(&run),
            run,
            warnings: Vec::new(),
            validity: None,
            model_form: None,
        }
    }

    /// probability.svg: P(stuck by cycle n) with its Clopper-Pearson band, and the exact
    /// answer after accommodation when there is one. It depends on the run alone.
    fn plot_svg(&self) -> Result<String, String> {
        let s = self.run.summary();
        let cycles = self.run.plan().cycles;
        let pct = pct(s.confidence);
        let line = |f: &dyn Fn(&stiction_model::design_sweep::CycleProbability) -> f64| {
            s.by_cycle
                .iter()
                .map(|c| (c.cycle as f64, f(c)))
                .collect::<Vec<_>>()
        };
        let mut series = vec![Series {
            name: "P(stuck by cycle n)".into(),
            points: line(&|c| c.probability),
            ..Default::default()
        }];
        let band = Band {
            name: format!("{pct} confidence interval (Clopper-Pearson)"),
            points: s
                .by_cycle
                .iter()
                .map(|c| (c.cycle as f64, c.ci_low, c.ci_high))
                .collect(),
            colour: Some(crate::plot::SERIES[2]),
        };
        if let Some(p) = self.run.exact().and_then(|e| e.stiction_probability) {
            series.push(Series {
                name: "exact after accommodation (threshold + CDF)".into(),
                points: vec![(1.0, p), (cycles as f64, p)],
                ..Default::default()
            });
        }
        let top = s
            .by_cycle
            .iter()
            .map(|c| c.ci_high)
            .fold(0.0f64, f64::max)
            .max(
                self.run
                    .exact()
                    .and_then(|e| e.stiction_probability)
                    .unwrap_or(0.0),
            );
        let panel = Panel {
            caption: format!(
                "{} counted of {} samples; apart: {} outside validity, {} out of domain, {} failed",
                s.denominator,
                s.samples,
                s.counts.outside_validity,
                s.counts.out_of_domain,
                s.counts.failed
            ),
            x_label: "cycle n [count]".into(),
            y_label: "P(stuck by cycle n) [-]".into(),
            series,
            bands: vec![band],
            x_range: Some((1.0, (cycles as f64).max(2.0))),
            y_range: Some((0.0, (1.1 * top).clamp(0.05, 1.0))),
            ..Default::default()
        };
        let title = self.labels.title.clone().unwrap_or_else(|| {
            format!(
                "P(stuck by cycle n), {} ({} samples)",
                self.run.plan().accuracy,
                s.samples
            )
        });
        svg(&title, &[panel])
    }
}

impl Plot for ProbabilityReport {
    /// `probability.svg`.
    fn svg(&self) -> Result<String, ReportError> {
        self.plot_svg()
            .map_err(|m| ReportError::plot("probability.svg".as_ref(), m))
    }
}

impl Report for ProbabilityReport {
    const FILES: &'static [&'static str] = PROBABILITY_FILES;

    fn files(&self, dir: &Path) -> Result<OutputSet, ReportError> {
        let mut set = OutputSet::new(dir, PROBABILITY_FILES);
        set.add("samples.csv", crate::csv::samples_csv(&self.run)?);
        set.add("probability.json", self.run.to_json());
        let plot = self
            .plot_svg()
            .map_err(|message| ReportError::plot(&dir.join("probability.svg"), message))?;
        set.add("probability.svg", plot);
        if let Some(m) = &self.model_form {
            set.add("model_form.json", render::json(m));
        }
        Ok(set)
    }
}

/// The title and units of a run, from the run alone.
fn labels(run: &Probability) -> Labels {
    let mut l =
        stiction_model::design::field_labels(run.plan().scatter.iter().map(|s| s.field.as_str()));
    if let Some(t) = run.plan().scene.get("title").and_then(|t| t.as_str()) {
        l = l.with_title(format!(
            "{t}: P(stuck by cycle n) ({}, {} samples)",
            run.plan().accuracy,
            run.summary().samples
        ));
    }
    l
}

/// `95 %` of a confidence of 0.95.
fn pct(confidence: f64) -> String {
    format!("{} %", (confidence * 1e4).round() / 1e2)
}

fn interval(p: Option<f64>, lo: f64, hi: f64) -> String {
    match p {
        Some(p) => format!("{p:.4} [{lo:.4}, {hi:.4}]"),
        None => format!("- [{lo:.4}, {hi:.4}] (no counted sample)"),
    }
}

impl Render for ProbabilityReport {
    fn table(&self) -> String {
        let s = self.run.summary();
        let plan = self.run.plan();
        let mut t = String::new();
        let row = |t: &mut String, k: &str, v: String| {
            let _ = writeln!(t, "{k:<16}{v}");
        };
        let value = |field: &str, v: f64| match self.labels.unit(field) {
            Some(u) => format!("{} {u}", stiction_model::keys::num(v)),
            None => stiction_model::keys::num(v),
        };
        for (j, sc) in plan.scatter.iter().enumerate() {
            row(
                &mut t,
                if j == 0 { "scattered" } else { "" },
                format!(
                    "{} ~ {}{}",
                    sc.field,
                    sc.dist,
                    self.labels
                        .unit(&sc.field)
                        .map(|u| format!(" [{u}]"))
                        .unwrap_or_default()
                ),
            );
        }
        for c in &plan.correlations {
            row(&mut t, "correlated", c.to_string());
        }
        row(
            &mut t,
            "samples",
            format!(
                "{} run of {} (seed {}{}), accuracy {}{}",
                s.samples,
                s.stopping.samples_requested,
                plan.seed,
                plan.shard
                    .map(|k| format!(", part {k}"))
                    .unwrap_or_default(),
                plan.accuracy,
                match (s.stopping.target_halfwidth, s.stopping.target_met) {
                    (Some(h), Some(true)) =>
                        format!("; stopped at half-width {:.4} <= {h}", s.stopping.halfwidth),
                    (Some(h), _) => format!(
                        "; target half-width {h} not met ({:.4})",
                        s.stopping.halfwidth
                    ),
                    _ => String::new(),
                }
            ),
        );
        if let Some(l) = crate::switch::laws_line_of_echo(&plan.scene) {
            row(&mut t, "laws", l.trim_start_matches("laws: ").to_owned());
        }
        row(
            &mut t,
            "counted",
            format!(
                "{} (sticks {}, free {}, does not close {}); apart: outside validity {}, out of domain {}, failed {}",
                s.denominator,
                s.counts.sticks,
                s.counts.free,
                s.counts.does_not_close,
                s.counts.outside_validity,
                s.counts.out_of_domain,
                s.counts.failed
            ),
        );
        let pc = pct(s.confidence);
        row(
            &mut t,
            "P(stiction)",
            format!(
                "{} after accommodation ({pc}, Clopper-Pearson)",
                interval(s.stiction_probability, s.ci_low, s.ci_high)
            ),
        );
        row(
            &mut t,
            "P(not closing)",
            interval(
                s.does_not_close_probability,
                s.does_not_close.ci_low,
                s.does_not_close.ci_high,
            ),
        );
        if !s.by_cycle.is_empty() {
            let cells: Vec<String> = s
                .by_cycle
                .iter()
                .map(|c| format!("{}: {:.4}", c.cycle, c.probability))
                .collect();
            row(&mut t, "by cycle", cells.join(", "));
        }
        if let Some(e) = self.run.exact() {
            let text = match (e.available, e.stiction_probability) {
                (true, Some(p)) => {
                    let at = match e.critical_value {
                        Some(c) => format!(
                            "F at {} = {}, free {}",
                            e.field,
                            value(&e.field, c),
                            e.free_side
                        ),
                        None => format!("no crossing of ratio 1: free {}", e.free_side),
                    };
                    format!(
                        "{p:.4} +- {:.1e} ({at}; ratio {} in the field, {} evaluations){}",
                        e.uncertainty.unwrap_or(0.0),
                        e.direction.as_deref().unwrap_or("monotone"),
                        e.evaluations,
                        match s.exact_inside_interval {
                            Some(true) => "; inside the interval",
                            Some(false) => "; OUTSIDE the interval",
                            None => "",
                        }
                    )
                }
                _ => format!(
                    "not available: {}",
                    e.reason.as_deref().unwrap_or("unknown")
                ),
            };
            row(&mut t, "exact", text);
            if e.available && e.does_not_close_probability.is_some_and(|p| p > 0.0) {
                row(
                    &mut t,
                    "exact no close",
                    format!("{:.4}", e.does_not_close_probability.unwrap_or(0.0)),
                );
            }
        }
        let mut ranked: Vec<_> = s.rank_correlation.iter().collect();
        ranked.sort_by(|a, b| {
            b.spearman
                .map(f64::abs)
                .unwrap_or(-1.0)
                .total_cmp(&a.spearman.map(f64::abs).unwrap_or(-1.0))
        });
        for (j, r) in ranked.iter().enumerate() {
            let v = match (r.spearman, r.ci_low, r.ci_high) {
                (Some(rho), Some(l), Some(h)) => {
                    format!(
                        "{}: Spearman rho = {rho:+.3} [{l:+.3}, {h:+.3}] with the ratio",
                        r.field
                    )
                }
                (Some(rho), _, _) => {
                    format!("{}: Spearman rho = {rho:+.3} with the ratio", r.field)
                }
                _ => format!(
                    "{}: undefined (fewer than 3 closing samples or one value)",
                    r.field
                ),
            };
            row(&mut t, if j == 0 { "drives failure" } else { "" }, v);
        }
        if s.counts.not_accommodated > 0 || s.counts.near_threshold > 0 {
            row(
                &mut t,
                "note",
                format!(
                    "{} closing sample(s) reached the cycle cap ({}) before accommodating; {} within the accuracy mode's error of ratio 1",
                    s.counts.not_accommodated, plan.cycles, s.counts.near_threshold
                ),
            );
        }
        if let Some(v) = self.validity.as_ref().filter(|v| !v.holds) {
            row(
                &mut t,
                "validity",
                format!(
                    "{} of {} samples {} ({})",
                    s.outside_validity,
                    s.samples,
                    v.words(),
                    if s.count_outside_validity {
                        "counted above: --count-outside-validity"
                    } else {
                        "counted apart"
                    }
                ),
            );
        }
        if s.outside_validity > 0 {
            let a = &s.all_samples;
            row(
                &mut t,
                "all samples",
                format!(
                    "P(stiction) {} over the {} samples that ran, {} of them outside the model's validity",
                    interval(a.stiction.probability, a.stiction.ci_low, a.stiction.ci_high),
                    a.denominator,
                    a.outside_validity
                ),
            );
        }
        if let Some(m) = &self.model_form {
            let _ = writeln!(
                t,
                "\nmodel form: {} (other combinations in {} mode, same samples)",
                m.summary, m.accuracy
            );
            for r in &m.runs {
                let _ = writeln!(
                    t,
                    "  {:<16} {:<11} {:<11} {:<12} {}",
                    r.laws.plasticity,
                    r.laws.yield_modulus,
                    r.laws.reload,
                    r.laws.adhesion,
                    interval(r.stiction_probability, r.interval[0], r.interval[1])
                );
            }
            for e in &m.excluded {
                let _ = writeln!(t, "  left out: {} {}: {}", e.choice, e.value, e.reason);
            }
        }
        t
    }

    fn csv(&self) -> String {
        crate::csv::samples_csv(&self.run).unwrap_or_default()
    }

    fn render(&self, format: Format, _columns: bool) -> String {
        match format {
            Format::Json => render::json(self),
            Format::Csv => self.csv(),
            Format::Table => self.table(),
        }
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    fn validity(&self) -> Option<&Validity> {
        self.validity.as_ref()
    }
}
