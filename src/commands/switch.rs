//! `stiction switch`: the micro-switch cycle by cycle (the paper's Fig 4, the main job).

use super::{finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::progress::Bar;
use crate::render::Format;
use std::path::PathBuf;
use stiction_model::keys::Kind;
use stiction_model::model_form::run_switch;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::SwitchResult;
use stiction_model::Accuracy;
use stiction_report::Report;

/// The accuracy modes as options.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum AccuracyArg {
    /// d_e within 1e-9 sigma_s, pull-out within 1e-8.
    Accurate,
    /// d_e within 1e-6 sigma_s, pull-out within 1e-6.
    Balanced,
    /// d_e within 1e-4 sigma_s, pull-out within 1e-4.
    Fast,
    /// Tighter than accurate: the yardstick the others are measured against.
    Reference,
}

impl From<AccuracyArg> for Accuracy {
    fn from(a: AccuracyArg) -> Self {
        match a {
            AccuracyArg::Accurate => Accuracy::Accurate,
            AccuracyArg::Balanced => Accuracy::Balanced,
            AccuracyArg::Fast => Accuracy::Fast,
            AccuracyArg::Reference => Accuracy::Reference,
        }
    }
}

/// `--model-form`: the scene's own modelling choices, or a check against the other
/// published forms.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ModelFormArg {
    /// The scene's own modelling choices only.
    Single,
    /// Also every combination of the credible published forms (plasticity law, eq-1
    /// reading, reload rule, adhesion law by the Tabor parameter): would another change
    /// the verdict? (docs/theory.md section 12)
    Check,
}

/// The model-form edit of a scene: (key, value, option).
pub fn model_form_edit(
    a: Option<ModelFormArg>,
) -> Option<(&'static str, toml::Value, &'static str)> {
    a.map(|a| {
        (
            "model_form",
            toml::Value::String(
                match a {
                    ModelFormArg::Single => "single",
                    ModelFormArg::Check => "check",
                }
                .into(),
            ),
            "--model-form",
        )
    })
}

/// The accuracy edit of a scene: (key, value, option).
pub fn accuracy_edit(a: Option<AccuracyArg>) -> Option<(&'static str, toml::Value, &'static str)> {
    a.map(|a| {
        (
            "accuracy",
            toml::Value::String(Accuracy::from(a).as_str().into()),
            "--accuracy",
        )
    })
}

/// The micro-switch cycle by cycle: d_e, pull-out pressure, accommodation, stiction.
#[derive(Debug, Clone, clap::Args)]
pub struct SwitchCommand {
    /// Scene, `--set`, `--strict`.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Number of cycles (replaces the scene's), 1..1000.
    #[arg(
        long,
        conflicts_with = "until_accommodated",
        allow_hyphen_values = true
    )]
    pub cycles: Option<i64>,
    /// Run until accommodation is detected (at most the scene's cycles, or 1000).
    #[arg(long)]
    pub until_accommodated: bool,
    /// Accuracy mode (replaces the scene's).
    #[arg(long, value_enum)]
    pub accuracy: Option<AccuracyArg>,
    /// `check`: also run every combination of the credible published model forms and say
    /// whether any changes the verdict (replaces the scene's `model_form`).
    #[arg(long, value_enum)]
    pub model_form: Option<ModelFormArg>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// JSON curves as column arrays ({"d": [...], "pressure": [...]}) instead of lists of
    /// points.
    #[arg(long)]
    pub columns: bool,
    /// Write switch.json, cycles.csv, curves.csv and switch.svg to this folder (replaced as
    /// a whole; it may hold only those files).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl SwitchCommand {
    /// The main job: the paper's switch, written to out/.
    pub fn main_job() -> Self {
        Self {
            scene: SceneArgs::default(),
            cycles: None,
            until_accommodated: false,
            accuracy: None,
            model_form: None,
            format: Format::Table,
            columns: false,
            out: Some(PathBuf::from("out")),
        }
    }

    /// Runs the command.
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        let mut edits = Vec::new();
        if let Some(n) = self.cycles {
            edits.push(("cycles", toml::Value::Integer(n), "--cycles"));
        }
        if self.until_accommodated {
            edits.push((
                "until_accommodated",
                toml::Value::Boolean(true),
                "--until-accommodated",
            ));
            if self.scene.scene.is_none() && self.cycles.is_none() {
                edits.push(("cycles", toml::Value::Integer(1000), "--until-accommodated"));
            }
        }
        edits.extend(accuracy_edit(self.accuracy));
        edits.extend(model_form_edit(self.model_form));
        let loaded = self.scene.load(Kind::Switch, &edits)?;
        let spec = SwitchSpec::new(&loaded.scene, ctx.registry).map_err(|e| loaded.blame(e))?;
        preflight(self.out.as_deref(), SwitchResult::FILES, None)?;
        let result = run_switch(&spec, ctx.registry, &Bar::new())?;
        let mut outputs = Outputs::default();
        if let Some(dir) = &self.out {
            outputs.folder = Some(result.files(dir)?);
        }
        finish(
            &result,
            self.format,
            self.columns,
            self.scene.strict,
            outputs,
        )
    }
}
