//! `stiction calibrate`: the constants of eq 13 (the effective radius on unloading) fitted
//! to finite-element force-interference curves of one asperity, with the scene's material,
//! adhesion law and reading of eq 1 (the crate `calibrate`; method in
//! `docs/calibration.md`).

use super::Command;
use crate::error::Error;
use crate::guards;
use crate::model;
use crate::plot::{self, Panel, Series};
use crate::render::{self, Format, Render, Warning};
use crate::scene::{AsperityScene, Loaded, PlasticityKind};
use asperity_plastic::{EffectiveRadiusFit, EtsionKadin};
use calibrate::{
    Branch, CalibError, Calibrator, FeData, FitOptions, FitReport, OverlayCurve, Selection,
};
use serde::Serialize;
use std::fmt::Write as _;
use std::io::Read as _;
use std::path::{Path, PathBuf};

/// Finite-element CSV files are read up to this size (64 MiB, about 900 000 rows): a
/// bound, so that a wrong path (a device, a huge binary) is refused instead of read whole.
pub const MAX_FE_BYTES: u64 = 64 << 20;

/// A per-curve RMS misfit above this fraction of the curve's peak force raises the
/// `poor_fit` warning: the misfit is then model form rather than noise, and the standard
/// errors (which treat it as noise) understate the uncertainty.
pub const POOR_FIT_RMS: f64 = 0.05;

/// Points of each model curve in the `--plot` overlay.
const OVERLAY_POINTS: usize = 200;

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
    /// Asperity scene (TOML) giving the model and the starting constants
    /// ([contact.effective_radius]); its delta_max list and points are not used. The
    /// paper's Fig 2 scene (Ru, eq 13's constants) if absent.
    #[arg(long, value_name = "SCENE.toml")]
    pub scene: Option<PathBuf>,
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

/// Reads a CSV of finite-element curves, refusing files larger than [`MAX_FE_BYTES`]
/// before reading them whole. Errors name the line and the column.
pub fn read_fe(path: &Path) -> Result<FeData, CalibError> {
    let io = |source| CalibError::Io {
        path: path.display().to_string(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(MAX_FE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_FE_BYTES {
        return Err(io(std::io::Error::other(format!(
            "larger than {MAX_FE_BYTES} bytes: not a finite-element curve file"
        ))));
    }
    let text = String::from_utf8(bytes).map_err(|_| {
        io(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "not UTF-8 text",
        ))
    })?;
    FeData::parse_csv(&text)
}

/// The line of the last data point.
fn last_line(data: &FeData) -> usize {
    data.curves()
        .iter()
        .flat_map(|c| c.points.iter().map(|p| p.line))
        .max()
        .unwrap_or(1)
}

impl CalibrateCommand {
    /// Reads and checks the data (errors name the CSV file, its line and column), then runs
    /// the scene pipeline.
    pub fn execute(&self) -> Result<String, Error> {
        let in_file = |e: CalibError| Error::InScene {
            file: self.fe.display().to_string(),
            source: Box::new(Error::Calibrate(e)),
        };
        let data = read_fe(&self.fe).map_err(|e| match e {
            // the error names the path already
            e @ CalibError::Io { .. } => Error::Calibrate(e),
            e => in_file(e),
        })?;
        if data.len() < self.fit.len() {
            return Err(in_file(CalibError::TooFewPoints {
                line: last_line(&data),
                points: data.len(),
                constants: self.fit.len(),
            }));
        }
        super::pipeline(&Job { cmd: self, data })
    }
}

/// A calibration with its data read.
struct Job<'a> {
    cmd: &'a CalibrateCommand,
    data: FeData,
}

/// One data point with the fitted model's force there.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct FittedPoint {
    /// The curve's delta_max (m).
    pub delta_max: f64,
    /// The branch.
    pub branch: Branch,
    /// Interference (m).
    pub delta: f64,
    /// The data's force (N).
    pub force: f64,
    /// The model's force at the fitted constants (N).
    pub model_force: f64,
}

/// `stiction calibrate`: the crate's [`FitReport`] (its keys at the top level of the
/// JSON), the data file, the guards and the resolved scene.
#[derive(Debug, Clone, Serialize)]
pub struct CalibrateReport {
    /// Plot and table title (the scene's).
    pub title: String,
    /// The finite-element data file.
    pub fe_file: String,
    /// Points in the data.
    pub data_points: usize,
    /// Columns of the data file that were ignored.
    pub ignored_columns: Vec<String>,
    /// The fit: `c1`, `c2`, `standard_errors`, `correlation`, `residual_rms_n`,
    /// `iterations`, `converged`, the identifiability, the per-curve misfit, the eq-1
    /// reading (`yield_modulus`, `delta_cp_m`) and `scene_fragment`.
    #[serde(flatten)]
    pub fit: FitReport,
    /// Guards raised (also printed on standard error).
    pub warnings: Vec<Warning>,
    /// The resolved scene (its `delta_max` and `points` are not used).
    pub scene: AsperityScene,
    /// Every data point with the fitted model's force (the CSV output).
    #[serde(skip)]
    pub points: Vec<FittedPoint>,
    /// Data and fitted model per curve for `--plot` (empty without it).
    #[serde(skip)]
    pub overlay: Vec<OverlayCurve>,
}

fn names<T: std::fmt::Display>(items: &[T]) -> String {
    items
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The guards of a fit: what the report must not let pass unnoticed.
fn warnings(fit: &FitReport, data: &FeData, fe_file: &str) -> Vec<Warning> {
    let mut w = Vec::new();
    if !data.ignored_columns().is_empty() {
        w.push(Warning {
            code: "fe_columns_ignored",
            message: format!(
                "{fe_file}: column(s) {} ignored (only delta_max_m, delta_m, force_n, branch are read)",
                names(data.ignored_columns())
            ),
        });
    }
    if !fit.converged {
        w.push(Warning {
            code: "not_converged",
            message: format!(
                "the fit did not converge (stop: {}, after {} iterations): the constants are the last accepted ones, not a minimum",
                serde_json::to_value(fit.stop)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_else(|| format!("{:?}", fit.stop)),
                fit.iterations
            ),
        });
    }
    if !fit.not_determined.is_empty() {
        let suggestion = if fit.suggested_fit.is_empty() {
            String::new()
        } else {
            let s: Vec<&str> = fit.suggested_fit.iter().map(|c| c.name()).collect();
            format!(
                ", or fit a subset such as --fit {} (estimated with the others held at the scene's values)",
                s.join(",")
            )
        };
        w.push(Warning {
            code: "not_determined",
            message: format!(
                "the data do not determine {} (rank {} of {}): no standard error is given for them and their values are the start's, moved only along what the data fix; add curves at other delta_max{suggestion}",
                names(&fit.not_determined),
                fit.rank,
                fit.fitted.len()
            ),
        });
    }
    if !fit.at_bound.is_empty() {
        w.push(Warning {
            code: "at_bound",
            message: format!(
                "{} ended on a bound of the domain of eq 13: the minimum may lie beyond it and the standard errors there are not meaningful",
                names(&fit.at_bound)
            ),
        });
    }
    if let Some(worst) = fit
        .curves
        .iter()
        .max_by(|a, b| a.rms_relative.total_cmp(&b.rms_relative))
        .filter(|c| c.rms_relative > POOR_FIT_RMS)
    {
        w.push(Warning {
            code: "poor_fit",
            message: format!(
                "the fitted model misses the {} curve to {} by {:.1} % RMS of its peak force: eqs 12-13 cannot describe these data well, and the standard errors (which treat the misfit as noise) understate the uncertainty; look at the --plot overlay",
                worst.branch,
                render::si(worst.delta_max_m, "m", 4),
                100.0 * worst.rms_relative
            ),
        });
    }
    let delta_max: Vec<f64> = data.curves().iter().map(|c| c.delta_max).collect();
    w.extend(guards::asperity_beyond_fit(fit.delta_cp_m, &delta_max));
    w
}

impl Command for Job<'_> {
    type Scene = AsperityScene;
    type Report = CalibrateReport;

    fn scene_path(&self) -> Option<&Path> {
        self.cmd.scene.as_deref()
    }

    fn run(&self, loaded: &Loaded<AsperityScene>) -> Result<CalibrateReport, Error> {
        let scene = &loaded.scene;
        let c = &scene.contact;
        if c.plasticity_law != PlasticityKind::EtsionKadin {
            return Err(Error::usage(
                "--scene",
                "calibrate fits the constants of the Etsion-Kadin law: the scene needs plasticity_law = \"etsion_kadin\"",
            ));
        }
        let start = EffectiveRadiusFit::new(c.effective_radius.c1, c.effective_radius.c2)?;
        let plasticity = EtsionKadin::new(&model::pair(c)?, c.yield_modulus())?.with_fit(start);
        let cal = Calibrator::new(plasticity, model::adhesion(c)?);
        let options = FitOptions {
            select: self.cmd.fit,
            ..FitOptions::default()
        };
        // a data error found by the fit (forces off the model's scale) names the CSV file
        let fit = cal.fit(&self.data, &options).map_err(|e| match e {
            e @ CalibError::Data { .. } => Error::InScene {
                file: self.cmd.fe.display().to_string(),
                source: Box::new(Error::Calibrate(e)),
            },
            e => e.into(),
        })?;
        let fitted = fit.fit();
        let model_forces = cal.predict(fitted, &self.data)?;
        let points = self
            .data
            .curves()
            .iter()
            .zip(&model_forces)
            .flat_map(|(curve, forces)| {
                curve.points.iter().zip(forces).map(|(p, &m)| FittedPoint {
                    delta_max: curve.delta_max,
                    branch: curve.branch,
                    delta: p.delta,
                    force: p.force,
                    model_force: m,
                })
            })
            .collect();
        let overlay = if self.cmd.plot.is_some() {
            cal.overlay(fitted, &self.data, OVERLAY_POINTS)?
        } else {
            Vec::new()
        };
        let fe_file = self.cmd.fe.display().to_string();
        Ok(CalibrateReport {
            title: loaded.title(),
            data_points: self.data.len(),
            ignored_columns: self.data.ignored_columns().to_vec(),
            warnings: warnings(&fit, &self.data, &fe_file),
            fe_file,
            fit,
            scene: scene.clone(),
            points,
            overlay,
        })
    }

    fn outputs(&self, report: &CalibrateReport) -> Result<Option<render::OutputSet>, Error> {
        if let Some(p) = &self.cmd.plot {
            super::write_plot(p, plot_svg(report))?;
        }
        Ok(None)
    }

    fn format(&self) -> Format {
        self.cmd.format
    }
}

/// Data points drawn as small crosses: two strokes each, separated by non-finite points,
/// which end a line of [`plot::svg`].
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
pub fn plot_svg(r: &CalibrateReport) -> Result<String, String> {
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
            model::adhesion_name(r.scene.contact.adhesion_law),
            r.fit.yield_modulus.as_str()
        ),
        &panels,
    )
}

impl Render for CalibrateReport {
    fn table(&self) -> String {
        let mut s = String::new();
        let c = &self.scene.contact;
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
            model::adhesion_name(c.adhesion_law),
            c.work_of_adhesion,
            render::si(c.z0, "m", 4),
            render::si(c.radius, "m", 4),
            c.yield_modulus().as_str(),
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
