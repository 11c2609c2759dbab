//! `stiction asperity`: one elasto-plastic adhesive asperity loaded to each delta_max and
//! unloaded (the paper's Fig 2 scene).

use super::{finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::render::Format;
use std::path::PathBuf;
use stiction_model::asperity;
use stiction_model::keys::Kind;
use stiction_model::spec::AsperitySpec;
use stiction_report::Plot;

/// One elasto-plastic adhesive asperity loaded and unloaded (paper Fig 2).
#[derive(Debug, Clone, clap::Args)]
pub struct AsperityCommand {
    /// Scene, `--set`, `--strict`.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Maximum interference (m); repeat for several cases. Replaces the scene's list.
    #[arg(long = "delta-max", allow_hyphen_values = true)]
    pub delta_max: Vec<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// JSON curves as column arrays instead of lists of points.
    #[arg(long)]
    pub columns: bool,
    /// Write an SVG plot of the curves.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

impl AsperityCommand {
    /// Runs the command.
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        let mut edits = Vec::new();
        if !self.delta_max.is_empty() {
            let list = self
                .delta_max
                .iter()
                .map(|&d| toml::Value::Float(d))
                .collect();
            edits.push(("delta_max", toml::Value::Array(list), "--delta-max"));
        }
        let loaded = self.scene.load(Kind::Asperity, &edits)?;
        let spec = AsperitySpec::new(&loaded.scene, ctx.registry).map_err(|e| loaded.blame(e))?;
        preflight(None, &[], self.plot.as_deref())?;
        let result = asperity::run(&spec)?;
        let mut outputs = Outputs::default();
        if let Some(p) = &self.plot {
            outputs.plots.push((p.clone(), result.svg()));
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
