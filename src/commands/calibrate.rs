//! `stiction calibrate`: the constants of eq 13 (the effective radius on unloading) fitted
//! to finite-element force-interference curves of one asperity, with the scene's material,
//! adhesion law and reading of eq 1 (the model library's `calibration`; method in
//! `docs/calibration.md`).

use super::{argument_error, finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::plot::{self, Panel, Series};
use crate::render::{self, Format, Render, Warning};
use std::fmt::Write as _;
use std::path::PathBuf;
use stiction_model::calibration::{self, CalibError, CalibrationResult, Selection};
use stiction_model::keys::Kind;
use stiction_model::spec::AsperitySpec;
use stiction_model::ModelError;

/// Fit the effective-radius constants of eq 13 to finite-element curves of one asperity.
#[derive(Debug, Clone, clap::Args)]
#[command(
    after_long_help = "Fits c1 = [a1, a2, a3] and c2 = [b1, b2, b3] of eq 13 by Levenberg-Marquardt \
                  from the scene's constants (method and worked example: docs/calibration.md). \
                  Loading curves see only c1; both branches at three or more delta_max determine \
                  all six constants.\n\n\
                  The model is the scene's asperity: material, radius, counter-surface, adhesion law \
                  and reading of eq 1 (yield_modulus) must be those of the FE runs. Prints the \
                  constants with standard errors, what the data do not determine, the misfit per \
                  curve, and a [contact.effective_radius] fragment to paste into a scene (in place \
                  of its own). Exit status: 0 (also when the fit did not converge: converged = false \
                  and a warning), 2 for bad data (the message names the line and column) or options, \
                  1 for a numerical failure."
)]
pub struct CalibrateCommand {
    /// Finite-element curves, CSV with a header holding delta_max_m, delta_m, force_n
    /// (SI: m, m, N; compressive force > 0) and branch (loading | unloading), any order,
    /// other columns ignored; rows with the same delta_max_m and branch form one curve.
    #[arg(long, value_name = "FILE.csv")]
    pub fe: PathBuf,
    /// Asperity scene giving the model and the starting constants
    /// ([contact.effective_radius] or [contact.plasticity]); its delta_max list and points
    /// are not used. The paper's Fig 2 scene (Ru, eq 13's constants) if absent.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Constants to fit, comma-separated: c1 (a1, a2, a3), c2 (b1, b2, b3), all, or single
    /// names a1 ... b3; the others are held at the scene's values.
    #[arg(long, default_value = "c1,c2", value_parser = parse_selection)]
    pub fit: Selection,
    /// Output format: table (with the scene fragment), json (the fit report, the scene
    /// echoed), or csv (the data with the fitted model's force at each point).
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write an SVG overlay of the data and the fitted model, one panel per delta_max
    /// (force in uN against interference in nm).
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

fn parse_selection(text: &str) -> Result<Selection, String> {
    text.parse::<Selection>().map_err(|e| match e {
        CalibError::Selection { reason, .. } => reason,
        other => other.to_string(),
    })
}

impl CalibrateCommand {
    /// Reads and checks the data (errors name the CSV file, its line and column), then fits.
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        let fe_file = self.fe.display().to_string();
        let in_file = |e: CalibError| {
            Error::Model(ModelError::InScene {
                file: fe_file.clone(),
                source: Box::new(ModelError::Calibrate(e)),
            })
        };
        let data = calibration::read_fe(&self.fe).map_err(|e| match e {
            // the error names the path already
            e @ CalibError::Io { .. } => Error::Model(e.into()),
            e => in_file(e),
        })?;
        if data.len() < self.fit.len() {
            return Err(in_file(CalibError::TooFewPoints {
                line: calibration::last_line(&data),
                points: data.len(),
                constants: self.fit.len(),
            }));
        }
        let loaded = self.scene.load(Kind::Asperity, &[])?;
        let spec = AsperitySpec::new(&loaded.scene, ctx.registry).map_err(|e| loaded.blame(e))?;
        preflight(None, &[], self.plot.as_deref())?;
        let result = calibration::calibrate(&spec, &data, &fe_file, self.fit, self.plot.is_some())
            .map_err(|e| match e {
                ModelError::Argument { value, allowed, .. } => {
                    Error::usage("--scene", format!("{value}: must be {allowed}"))
                }
                e => argument_error(e),
            })?;
        let mut outputs = Outputs::default();
        if let Some(p) = &self.plot {
            outputs.plots.push((p.clone(), plot_svg(&result)));
        }
        finish(&result, self.format, false, self.scene.strict, outputs)
    }
}

fn crosses(points: &[(f64, f64)], hx: f64, hy: f64) -> Vec<(f64, f64)> {
    let gap = (f64::NAN, f64::NAN);
    points
        .iter()
        .flat_map(|&(x, y)| {
            [
                (x - hx, y - hy),
                (x + hx, y + hy),
                gap,
                (x - hx, y + hy),
                (x + hx, y - hy),
                gap,
            ]
        })
        .collect()
}

/// The overlay: one panel per delta_max, the data as crosses and the fitted model as
/// lines, force in uN against interference in nm.
pub fn plot_svg(r: &CalibrationResult) -> Result<String, String> {
    let mut panels: Vec<Panel> = Vec::new();
    let mut keys: Vec<f64> = Vec::new();
    for curve in &r.overlay {
        let nm_un = |v: &[[f64; 2]]| -> Vec<(f64, f64)> {
            v.iter().map(|p| (p[0] * 1e9, p[1] * 1e6)).collect()
        };
        let data = nm_un(&curve.data);
        let model = nm_un(&curve.model);
        let idx = match keys.iter().position(|&k| k == curve.delta_max_m) {
            Some(i) => i,
            None => {
                keys.push(curve.delta_max_m);
                let omega = curve.delta_max_m / r.fit.delta_cp_m;
                panels.push(Panel {
                    caption: format!(
                        "delta_max = {} (omega = {omega:.2}): FE data (x) and fitted eq 13",
                        render::si(curve.delta_max_m, "m", 4)
                    ),
                    x_label: "interference delta [nm]".into(),
                    y_label: "force [uN]".into(),
                    series: Vec::new(),
                    x_range: None,
                    y_range: None,
                });
                panels.len() - 1
            }
        };
        panels[idx].series.push(Series {
            name: format!("FE {}", curve.branch),
            points: data,
        });
        panels[idx].series.push(Series {
            name: format!("fit {}", curve.branch),
            points: model,
        });
    }
    // crosses sized on each panel's own ranges
    for panel in &mut panels {
        let all = || panel.series.iter().flat_map(|s| s.points.iter());
        let span = |f: fn(&(f64, f64)) -> f64| {
            let (lo, hi) = all()
                .map(f)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    (a.min(v), b.max(v))
                });
            if hi > lo {
                hi - lo
            } else {
                1.0
            }
        };
        let (hx, hy) = (0.004 * span(|p| p.0), 0.008 * span(|p| p.1));
        for s in panel.series.iter_mut().step_by(2) {
            s.points = crosses(&s.points, hx, hy);
        }
    }
    if panels.is_empty() {
        return Err("no curves to draw".into());
    }
    plot::svg(
        &format!(
            "eq 13 fitted to {} ({}, eq 1 {})",
            r.fe_file,
            r.laws.adhesion,
            r.fit.yield_modulus.as_str()
        ),
        &panels,
    )
}

impl Render for CalibrationResult {
    fn table(&self) -> String {
        let mut s = String::new();
        let c = &self.model;
        let omegas = self
            .fit
            .curves
            .iter()
            .map(|k| k.omega)
            .fold((f64::INFINITY, 0.0f64), |(a, b), w| (a.min(w), b.max(w)));
        let range = if omegas.0 < omegas.1 {
            format!("{:.3} to {:.3}", omegas.0, omegas.1)
        } else {
            format!("{:.3}", omegas.1)
        };
        let _ = writeln!(s, "{}", self.title);
        let _ = writeln!(
            s,
            "data: {}, {} points in {} curves, delta_max/delta_CP {range}",
            self.fe_file,
            self.data_points,
            self.fit.curves.len(),
        );
        let _ = writeln!(
            s,
            "model: {} adhesion (w = {} J/m^2, z0 = {}), R = {}, eq 1 {}; fitting {}",
            self.laws.adhesion,
            c.work_of_adhesion,
            render::si(c.z0, "m", 4),
            render::si(c.radius, "m", 4),
            self.laws.yield_modulus,
            Selection::of(&self.fit.fitted)
        );
        s.push_str(&self.fit.to_table());
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from("delta_max_m,delta_m,force_n,branch,model_force_n\n");
        for p in &self.points {
            let _ = writeln!(
                s,
                "{:e},{:e},{:e},{},{:e}",
                p.delta_max, p.delta, p.force, p.branch, p.model_force
            );
        }
        s
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }
}
