//! `stiction surface`: the rough surface's contact law, virgin loading and (with
//! `unload_from`) unloading and reloading.

use super::switch::{accuracy_edit, AccuracyArg};
use super::{finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::plot::{self, Panel, Series};
use crate::render::{self, csv_num, Format, Render, Validity, Warning};
use std::fmt::Write as _;
use std::path::PathBuf;
use stiction_model::keys::Kind;
use stiction_model::spec::SurfaceSpec;
use stiction_model::surface::{self, SurfaceResult};
use stiction_model::switch_1d::PressurePoint;

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
            outputs.plots.push((p.clone(), plot_svg(&result)));
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

/// The contact law (MPa against nm), with a zoom on the adhesive part.
pub fn plot_svg(r: &SurfaceResult) -> Result<String, String> {
    let pts = |v: &[PressurePoint]| -> Vec<(f64, f64)> {
        v.iter().map(|p| (p.d * 1e9, p.pressure * 1e-6)).collect()
    };
    let mut series = vec![Series {
        name: "virgin loading".into(),
        points: pts(&r.loading),
    }];
    if !r.unloading.is_empty() {
        series.push(Series {
            name: "unloading".into(),
            points: pts(&r.unloading),
        });
        series.push(Series {
            name: "reloading".into(),
            points: pts(&r.reloading),
        });
    }
    let mut panels = vec![Panel {
        caption: "whole curves".into(),
        x_label: "separation d [nm]".into(),
        y_label: "pressure [MPa]".into(),
        series: series.clone(),
        x_range: None,
        y_range: None,
    }];
    if let Some(p) = r.pull_out_pressure.filter(|&p| p > 0.0) {
        let y = p * 1e-6;
        panels.push(Panel {
            caption: "adhesive part".into(),
            x_label: "separation d [nm]".into(),
            y_label: "pressure [MPa]".into(),
            series,
            x_range: None,
            y_range: Some((-1.5 * y, 1.5 * y)),
        });
    }
    plot::svg(&r.title, &panels)
}

impl Render for SurfaceResult {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}", self.title);
        let _ = writeln!(
            s,
            "{}; sigma_s = {}; accuracy {} (pressures to {})",
            super::switch::laws_line(&self.laws),
            render::si(self.sigma_s, "m", 4),
            self.accuracy.mode,
            render::pressure(self.error_estimate.pressure)
        );
        if let (Some(p), Some(d), Some(u)) = (
            self.pull_out_pressure,
            self.pull_out_separation,
            self.unload_from,
        ) {
            let _ = writeln!(
                s,
                "unloaded from d = {}: pull-out pressure {} at d = {}",
                render::si(u, "m", 4),
                render::pressure(p),
                render::si(d, "m", 4)
            );
        }
        if !self.validity.holds {
            let _ = writeln!(s, "{}", self.validity.words());
        }
        let _ = writeln!(
            s,
            "{:>12} {:>14} {:>12} {:>14}",
            "d", "loading", "d", "unloading"
        );
        for (i, p) in self.loading.iter().enumerate() {
            let u = self.unloading.get(i).map_or(String::new(), |q| {
                format!(
                    "{:>12} {:>14}",
                    render::si(q.d, "m", 4),
                    render::pressure(q.pressure)
                )
            });
            let _ = writeln!(
                s,
                "{:>12} {:>14} {u}",
                render::si(p.d, "m", 4),
                render::pressure(p.pressure)
            );
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from("branch,d_m,pressure_pa\n");
        for (name, pts) in [
            ("loading", &self.loading),
            ("unloading", &self.unloading),
            ("reloading", &self.reloading),
        ] {
            for p in pts {
                let _ = writeln!(s, "{},{},{}", name, csv_num(p.d), csv_num(p.pressure));
            }
        }
        s
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    fn validity(&self) -> Option<&Validity> {
        Some(&self.validity)
    }
}
