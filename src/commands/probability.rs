//! `stiction design probability`: the fraction of devices that stick, and by which cycle,
//! when design fields scatter from die to die (the model library's `probability`). User
//! guide: `docs/design.md`, "How many switches stick".

use super::switch::AccuracyArg;
use super::{finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::progress::Bar;
use crate::render::Format;
use std::path::PathBuf;
use stiction_model::keys::Kind;
use stiction_model::probability::{self, ProbabilityRequest};
use stiction_report::probability::ProbabilityReport;
use stiction_report::Report;

/// The output formats of `design probability`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ProbabilityFormat {
    /// A table for people.
    Table,
    /// The statistics as pretty-printed JSON (samples, stiction_probability, ci_low,
    /// ci_high, does_not_close_probability, outside_validity, by_cycle, ...), without the
    /// samples (those are in probability.json and samples.csv).
    Json,
    /// Every sample, as samples.csv.
    Csv,
}

/// `stiction design probability`.
#[derive(Debug, Clone, clap::Args)]
pub struct ProbabilityCommand {
    /// The switch scene, `--set`, `--strict`.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// A scattered field and its distribution, FIELD=DIST, DIST one of normal(mean,sd),
    /// lognormal(median,factor) (factor = exp(sigma)), uniform(lo,hi), weibull(scale,shape),
    /// in the field's SI unit (repeatable; FIELD as in `design map`).
    #[arg(long, value_name = "FIELD=DIST", required = true)]
    pub scatter: Vec<String>,
    /// A correlation between two scattered fields, A,B=RHO with RHO in (-1, 1): the
    /// correlation of their normal scores (Gaussian copula; repeatable).
    #[arg(long, value_name = "A,B=RHO", allow_hyphen_values = true)]
    pub correlate: Vec<String>,
    /// Samples to run (with --target-halfwidth, the most to run).
    #[arg(long, value_name = "N")]
    pub samples: usize,
    /// Seed of the samples: sample i's values depend on (seed, i) alone.
    #[arg(long, value_name = "K", default_value_t = 0)]
    pub seed: u64,
    /// Confidence of the intervals.
    #[arg(long, default_value_t = 0.95)]
    pub confidence: f64,
    /// Run part K of N interleaved parts of the samples (sample i is in part i % N + 1);
    /// needs --out; join the parts with `design merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Stop once half the width of the stiction interval is at most this (checked every
    /// 100 samples); --samples caps the run.
    #[arg(long, value_name = "H")]
    pub target_halfwidth: Option<f64>,
    /// Accuracy mode of the design points (replaces the scene's).
    #[arg(long, value_enum)]
    pub accuracy: Option<AccuracyArg>,
    /// Skip the exact single-field answer (a threshold search of 10 to 40 design points).
    #[arg(long)]
    pub no_exact: bool,
    /// Count the samples outside the model's validity in the headline probabilities
    /// (by default they are set apart; the answer over all samples is given beside).
    #[arg(long)]
    pub count_outside_validity: bool,
    /// `check`: the same samples under every combination of the credible published model
    /// forms, and the range of P(stiction) they give (replaces the scene's `model_form`).
    #[arg(long, value_enum)]
    pub model_form: Option<super::switch::ModelFormArg>,
    /// Output format on standard output.
    #[arg(long, value_enum, default_value_t = ProbabilityFormat::Table)]
    pub format: ProbabilityFormat,
    /// Write samples.csv, probability.json and probability.svg to this folder (replaced as
    /// a whole; it may hold only those files).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl ProbabilityCommand {
    /// Runs the samples (or one part of them).
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        if self.shard.is_some() && self.out.is_none() {
            return Err(Error::usage(
                "--shard",
                "a part is written to its own folder: give --out DIR (join the parts with `design merge`)",
            ));
        }
        let edits: Vec<_> = super::switch::model_form_edit(self.model_form)
            .into_iter()
            .collect();
        let loaded = self.scene.load(Kind::Switch, &edits)?;
        for v in &self.scatter {
            loaded.refuse_set_of(v.split('=').next().unwrap_or(v), "--scatter")?;
        }
        let request = ProbabilityRequest {
            scatter: self.scatter.clone(),
            correlate: self.correlate.clone(),
            samples: self.samples,
            seed: self.seed,
            confidence: self.confidence,
            shard: self.shard.clone(),
            target_halfwidth: self.target_halfwidth,
            accuracy: self.accuracy.map(Into::into),
            exact: !self.no_exact,
            count_outside_validity: self.count_outside_validity,
        };
        // everything checked before the first sample runs, the output folder included
        probability::plan(&loaded.scene, ctx.registry, &request).map_err(|e| loaded.blame(e))?;
        preflight(self.out.as_deref(), ProbabilityReport::FILES, None)?;
        let r = probability::run(&loaded.scene, ctx.registry, &request, &Bar::new())
            .map_err(|e| loaded.blame(e))?;
        let report = ProbabilityReport::new(r);
        let folder = match &self.out {
            Some(dir) => Some(report.files(dir)?),
            None => None,
        };
        let format = match self.format {
            ProbabilityFormat::Table => Format::Table,
            ProbabilityFormat::Json => Format::Json,
            ProbabilityFormat::Csv => Format::Csv,
        };
        finish(
            &report,
            format,
            false,
            self.scene.strict,
            Outputs {
                folder,
                plots: Vec::new(),
            },
        )
    }
}
