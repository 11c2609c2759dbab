//! `stiction calibrate`: the constants of eq 13 (the effective radius on unloading) fitted
//! to finite-element force-interference curves of one asperity, with the scene's material,
//! adhesion law and reading of eq 1 (the model library's `calibration`; method in
//! `docs/calibration.md`).

use super::{argument_error, finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::render::Format;
use std::path::PathBuf;
use stiction_model::calibration::{self, CalibError, Selection};
use stiction_model::keys::Kind;
use stiction_model::spec::AsperitySpec;
use stiction_model::ModelError;
use stiction_report::Plot;

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
            outputs.plots.push((p.clone(), result.svg()));
        }
        finish(&result, self.format, false, self.scene.strict, outputs)
    }
}
