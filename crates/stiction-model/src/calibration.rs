//! Calibration of eq 13: the constants of the effective radius on unloading fitted to
//! finite-element force-interference curves of one asperity, with the scene's material,
//! adhesion law and reading of eq 1 (the crate `calibrate`; method in
//! `docs/calibration.md`).

use crate::error::ModelError;
use crate::guards::{self, si, Warning};
use crate::spec::AsperitySpec;
use asperity_plastic::{EffectiveRadiusFit, EtsionKadin};
pub use calibrate::{Branch, CalibError, FeData, FitReport, OverlayCurve, Selection};
use calibrate::{Calibrator, FitOptions};
use serde::Serialize;
use std::io::Read as _;
use std::path::Path;

/// Finite-element CSV files are read up to this size (64 MiB, about 900 000 rows): a
/// bound, so that a wrong path (a device, a huge binary) is refused instead of read whole.
pub const MAX_FE_BYTES: u64 = 64 << 20;

/// A per-curve RMS misfit above this fraction of the curve's peak force raises the
/// `poor_fit` warning: the misfit is then model form rather than noise, and the standard
/// errors (which treat it as noise) understate the uncertainty.
pub const POOR_FIT_RMS: f64 = 0.05;

/// Points of each model curve in an overlay.
pub const OVERLAY_POINTS: usize = 200;

/// Reads a CSV of finite-element curves, refusing files larger than [`MAX_FE_BYTES`]
/// before reading them whole. Errors name the line and the column.
pub fn read_fe(path: &Path) -> Result<FeData, CalibError> {
    let io = |source| CalibError::Io {
        path: path.display().to_string(),
        source,
    };
    // the type first, from the path: opening a FIFO would wait for a writer
    let meta = std::fs::metadata(path).map_err(io)?;
    if let Some(what) = crate::scene::not_regular(&meta) {
        return Err(io(std::io::Error::other(format!(
            "it is {what}, not a finite-element curve file"
        ))));
    }
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
pub fn last_line(data: &FeData) -> usize {
    data.curves()
        .iter()
        .flat_map(|c| c.points.iter().map(|p| p.line))
        .max()
        .unwrap_or(1)
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

/// A calibration: the crate's [`FitReport`] (its keys at the top level of the JSON), the
/// data file, the guards and the resolved scene.
#[derive(Debug, Clone, Serialize)]
pub struct CalibrationResult {
    /// Plot and table title (the scene's).
    pub title: String,
    /// The laws and modelling choices of the model fitted.
    pub laws: crate::switch::Laws,
    /// The model's work of adhesion (J/m^2), Dugdale range (m) and tip radius (m).
    pub model: CalibrationModel,
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
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// The resolved scene (its `delta_max` and `points` are not used).
    pub scene: serde_json::Value,
    /// Every data point with the fitted model's force (the CSV output).
    #[serde(skip)]
    pub points: Vec<FittedPoint>,
    /// Data and fitted model per curve (empty unless asked for).
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

/// The constants of the asperity fitted, for the report.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct CalibrationModel {
    /// w (J/m^2).
    pub work_of_adhesion: f64,
    /// z0 (m).
    pub z0: f64,
    /// R (m).
    pub radius: f64,
}

/// The guards of a fit: what the report must not let pass unnoticed.
fn warnings(spec: &AsperitySpec, fit: &FitReport, data: &FeData, fe_file: &str) -> Vec<Warning> {
    let mut w = Vec::new();
    if !data.ignored_columns().is_empty() {
        w.push(Warning::note(
            "fe_columns_ignored",
            format!(
                "{fe_file}: column(s) {} ignored (only delta_max_m, delta_m, force_n, branch are read)",
                names(data.ignored_columns())
            ),
        ));
    }
    if !fit.converged {
        w.push(Warning::note(
            "not_converged",
            format!(
                "the fit did not converge (stop: {}, after {} iterations): the constants are the last accepted ones, not a minimum",
                serde_json::to_value(fit.stop)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_else(|| format!("{:?}", fit.stop)),
                fit.iterations
            ),
        ));
    }
    if !fit.not_determined.is_empty() {
        let suggestion = if fit.suggested_fit.is_empty() {
            String::new()
        } else {
            let s: Vec<&str> = fit.suggested_fit.iter().map(|c| c.name()).collect();
            format!(
                ", or fit a subset such as {} (estimated with the others held at the scene's values)",
                s.join(",")
            )
        };
        w.push(Warning::note(
            "not_determined",
            format!(
                "the data do not determine {} (rank {} of {}): no standard error is given for them and their values are the start's, moved only along what the data fix; add curves at other delta_max{suggestion}",
                names(&fit.not_determined),
                fit.rank,
                fit.fitted.len()
            ),
        ));
    }
    if !fit.at_bound.is_empty() {
        w.push(Warning::note(
            "at_bound",
            format!(
                "{} ended on a bound of the domain of eq 13: the minimum may lie beyond it and the standard errors there are not meaningful",
                names(&fit.at_bound)
            ),
        ));
    }
    if let Some(worst) = fit
        .curves
        .iter()
        .max_by(|a, b| a.rms_relative.total_cmp(&b.rms_relative))
        .filter(|c| c.rms_relative > POOR_FIT_RMS)
    {
        w.push(Warning::note(
            "poor_fit",
            format!(
                "the fitted model misses the {} curve to {} by {:.1} % RMS of its peak force: eqs 12-13 cannot describe these data well, and the standard errors (which treat the misfit as noise) understate the uncertainty; look at the plot overlay",
                worst.branch,
                si(worst.delta_max_m, "m", 4),
                100.0 * worst.rms_relative
            ),
        ));
    }
    let delta_max: Vec<f64> = data.curves().iter().map(|c| c.delta_max).collect();
    w.extend(guards::asperity_beyond_fit(&spec.contact, &delta_max));
    w
}

/// Fits the constants `select` of eq 13 to `data` from the asperity scene's constants
/// (its `etsion_kadin` parameters c1, c2); `overlay` also samples the fitted model per curve
/// for a plot. `fe_file` names the data in messages.
pub fn calibrate(
    spec: &AsperitySpec,
    data: &FeData,
    fe_file: &str,
    select: Selection,
    overlay: bool,
) -> Result<CalibrationResult, ModelError> {
    let c = &spec.contact;
    if c.plasticity.name != "etsion_kadin" {
        return Err(ModelError::argument(
            "scene",
            format!("plasticity_law = \"{}\"", c.plasticity.name),
            "plasticity_law = \"etsion_kadin\": calibrate fits the constants of eq 13 of the Etsion-Kadin law",
        ));
    }
    let start = EffectiveRadiusFit::new(
        c.plasticity
            .params
            .triple("c1")
            .unwrap_or(EffectiveRadiusFit::PAPER.c1),
        c.plasticity
            .params
            .triple("c2")
            .unwrap_or(EffectiveRadiusFit::PAPER.c2),
    )?;
    let plasticity = EtsionKadin::new(&c.pair, c.yield_modulus)?.with_fit(start);
    let cal = Calibrator::new(plasticity, c.adhesion.law.clone());
    let options = FitOptions {
        select,
        ..FitOptions::default()
    };
    // a data error found by the fit (forces off the model's scale) names the CSV file
    let fit = cal.fit(data, &options).map_err(|e| match e {
        e @ CalibError::Data { .. } => ModelError::InScene {
            file: fe_file.to_string(),
            source: Box::new(ModelError::Calibrate(e)),
        },
        e => e.into(),
    })?;
    let fitted = fit.fit();
    let model_forces = cal.predict(fitted, data)?;
    let points = data
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
    let overlay = if overlay {
        cal.overlay(fitted, data, OVERLAY_POINTS)?
    } else {
        Vec::new()
    };
    Ok(CalibrationResult {
        title: spec.common.title.clone(),
        laws: crate::switch::Laws::of(c),
        model: CalibrationModel {
            work_of_adhesion: c.work_of_adhesion,
            z0: c.z0,
            radius: c.radius,
        },
        data_points: data.len(),
        ignored_columns: data.ignored_columns().to_vec(),
        warnings: warnings(spec, &fit, data, fe_file),
        fe_file: fe_file.to_string(),
        fit,
        scene: spec.common.echo(),
        points,
        overlay,
    })
}
