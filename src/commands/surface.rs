//! `stiction surface`: the rough surface's contact law, virgin loading and (with
//! `unload_from`) unloading and reloading.

use super::Command;
use crate::accuracy::{Accuracy, Targets};
use crate::error::Error;
use crate::guards;
use crate::model;
use crate::plot::{self, Panel, Series};
use crate::render::{self, Format, Render, Warning};
use crate::scene::{Loaded, SurfaceScene};
use asperity_plastic::FIT_RANGE_MAX;
use contact_core::numeric::linspace;
use contact_core::{Path, SurfaceLaw};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::PathBuf;
use switch_1d::PressurePoint;

/// The rough surface: virgin loading and, with --unload-from, unloading and reloading.
#[derive(Debug, Clone, clap::Args)]
pub struct SurfaceCommand {
    /// Scene file (TOML); the paper's surface if absent.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Load to this separation d (m) and unload from it (replaces the scene's).
    #[arg(long, allow_hyphen_values = true)]
    pub unload_from: Option<f64>,
    /// Accuracy mode (replaces the scene's).
    #[arg(long, value_enum)]
    pub accuracy: Option<Accuracy>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write an SVG plot of the curves.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// Error estimates of the reported quantities (Pa).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct SurfaceErrors {
    /// The largest error estimate of a curve pressure.
    pub pressure: f64,
    /// The pull-out pressure's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pull_out: Option<f64>,
}

/// `stiction surface`.
#[derive(Debug, Clone, Serialize)]
pub struct SurfaceReport {
    /// Plot and table title.
    pub title: String,
    /// sigma_s (m).
    pub sigma_s: f64,
    /// Accuracy mode and targets.
    pub accuracy: Targets,
    /// Error estimates.
    pub error_estimate: SurfaceErrors,
    /// Virgin loading (approach) from d_start to the first touch.
    pub loading: Vec<PressurePoint>,
    /// The separation unloaded from (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unload_from: Option<f64>,
    /// Unloading (retraction) from unload_from to the last contact.
    pub unloading: Vec<PressurePoint>,
    /// Reloading (approach with the history of unload_from) from the first touch down to
    /// unload_from.
    pub reloading: Vec<PressurePoint>,
    /// Magnitude of the most tensile unloading pressure (Pa).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pull_out_pressure: Option<f64>,
    /// Where it occurs (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pull_out_separation: Option<f64>,
    /// Fraction of asperities (by count) loaded beyond delta_max/delta_CP = 110.
    pub extrapolated_fraction: f64,
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// The resolved scene.
    pub scene: SurfaceScene,
}

impl Command for SurfaceCommand {
    type Scene = SurfaceScene;
    type Report = SurfaceReport;

    fn scene_path(&self) -> Option<&std::path::Path> {
        self.scene.as_deref()
    }

    fn apply(&self, scene: &mut SurfaceScene) -> Result<(), Error> {
        if self.unload_from.is_some() {
            scene.unload_from = self.unload_from;
        }
        if let Some(a) = self.accuracy {
            scene.accuracy = a;
        }
        Ok(())
    }

    fn overrides(&self) -> Vec<(&'static str, &'static str)> {
        match self.unload_from {
            Some(_) => vec![("unload_from", "--unload-from")],
            None => vec![],
        }
    }

    fn run(&self, loaded: &Loaded<SurfaceScene>) -> Result<SurfaceReport, Error> {
        let s = &loaded.scene;
        let gw = model::surface(&s.contact, &s.surface, s.accuracy, 0.0, false)?;
        let virgin = gw.virgin();
        let top = gw.reach(&virgin, Path::Approach)?;
        let start = s.d_start.or(s.unload_from).unwrap_or(0.0);
        let mut worst: f64 = 0.0;
        let mut curve = |hist: &gw_surface::GwHistory, from: f64, to: f64, path: Path| {
            linspace(from, to, s.points)
                .map(|d| {
                    let e = gw.pressure_estimate(d, hist, path)?;
                    worst = worst.max(e.error);
                    Ok(PressurePoint {
                        d,
                        pressure: e.value,
                    })
                })
                .collect::<Result<Vec<_>, Error>>()
        };
        let loading = curve(&virgin, start, top, Path::Approach)?;
        let deepest = s.unload_from.map_or(start, |u| u.min(start));
        let loaded_hist = gw.load(&virgin, deepest);
        let extrapolated_fraction = gw.fraction_beyond(&loaded_hist, FIT_RANGE_MAX);
        let mut warnings = Vec::new();
        let (mut unloading, mut reloading, mut pull, mut pull_err) =
            (Vec::new(), Vec::new(), None, None);
        if let Some(d) = s.unload_from {
            let hist = gw.load(&virgin, d);
            let path = Path::Retract { from: d };
            let reach = gw.reach(&hist, path)?;
            unloading = curve(&hist, d, reach, path)?;
            reloading = curve(&hist, gw.reach(&hist, Path::Approach)?, d, Path::Approach)?;
            let u = switch_1d::unload(&gw, &hist, d, 0, s.accuracy.precision(0.0))?;
            pull = Some((u.pull_out_pressure, u.pull_out_separation));
            pull_err = Some(u.pull_out_error);
        }
        let compressive = gw.pressure(deepest, &virgin, Path::Approach)?.max(0.0);
        warnings.extend(guards::pressure_above_hardness(
            &s.contact,
            compressive,
            pull.map_or(0.0, |p| p.0),
        ));
        let share = gw.load_share_beyond(deepest, &virgin, Path::Approach, FIT_RANGE_MAX)?;
        warnings.extend(guards::surface_beyond_fit(share, deepest));
        let plastic = model::asperity(&s.contact, false)?;
        let elastic = model::asperity(&s.contact, true)?;
        warnings.extend(guards::adhesion_yields(&s.contact, &plastic, &elastic)?);
        Ok(SurfaceReport {
            title: loaded.title(),
            sigma_s: s.surface.sigma_s,
            accuracy: s.accuracy.targets(),
            error_estimate: SurfaceErrors {
                pressure: worst,
                pull_out: pull_err,
            },
            loading,
            unload_from: s.unload_from,
            unloading,
            reloading,
            pull_out_pressure: pull.map(|p| p.0),
            pull_out_separation: pull.map(|p| p.1),
            extrapolated_fraction,
            warnings,
            scene: s.clone(),
        })
    }

    fn outputs(&self, report: &SurfaceReport) -> Result<Option<crate::render::OutputSet>, Error> {
        if let Some(p) = &self.plot {
            super::write_plot(p, plot_svg(report))?;
        }
        Ok(None)
    }

    fn format(&self) -> Format {
        self.format
    }
}

/// The contact law (MPa against nm), with a zoom on the adhesive part.
pub fn plot_svg(r: &SurfaceReport) -> Result<String, String> {
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

impl Render for SurfaceReport {
    fn table(&self) -> String {
        let mut s = String::new();
        let c = &self.scene.contact;
        let _ = writeln!(s, "{}", self.title);
        let _ = writeln!(
            s,
            "laws: {} adhesion, {} plasticity, eq 1 {}; sigma_s = {}; accuracy {} (pressures to {})",
            model::adhesion_name(c.adhesion_law),
            model::plasticity_name(c.plasticity_law),
            c.yield_modulus().as_str(),
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
                let _ = writeln!(s, "{},{},{}", name, p.d, p.pressure);
            }
        }
        s
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }
}
