//! `stiction surface`: the rough surface's contact law, virgin loading and (with
//! `unload_from`) unloading and reloading.

use super::switch::{accuracy_edit, AccuracyArg};
use super::{finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::render::{self, Format};
use std::path::PathBuf;
use stiction_model::keys::Kind;
use stiction_model::spec::SurfaceSpec;
use stiction_model::surface;
use stiction_report::Plot;

/// The rough surface: virgin loading and, with --unload-from, unloading and reloading.
#[derive(Debug, Clone, clap::Args)]
pub struct SurfaceCommand {
    /// Scene, `--set`, `--strict`.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Load to this separation d (m) and unload from it (replaces the scene's).
    #[arg(long, allow_hyphen_values = true)]
    pub unload_from: Option<f64>,
    /// Accuracy mode (replaces the scene's).
    #[arg(long, value_enum)]
    pub accuracy: Option<AccuracyArg>,
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

impl SurfaceCommand {
    /// Runs the command.
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        let mut edits = Vec::new();
        if let Some(u) = self.unload_from {
            edits.push(("unload_from", toml::Value::Float(u), "--unload-from"));
        }
        edits.extend(accuracy_edit(self.accuracy));
        let loaded = self.scene.load(Kind::Surface, &edits)?;
        let spec = SurfaceSpec::new(&loaded.scene, ctx.registry).map_err(|e| loaded.blame(e))?;
        preflight(None, &[], self.plot.as_deref())?;
        let mut result = surface::run(&spec)?;
        if let (Some(u), Some(_)) = (self.unload_from, loaded.scene.title()) {
            // the scene's title may name the depth it was written for
            result.title = format!(
                "{} [unloaded from {} by --unload-from]",
                result.title,
                render::si(u, "m", 4)
            );
        }
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
