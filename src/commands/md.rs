//! `stiction md`: the nondimensional Maugis-Kim curve (paper eqs 7-11, Kim extension).

use super::argument_error;
use crate::error::Error;
use crate::render::{Format, Render};
use stiction_model::contact_core::Path;
use stiction_model::md;

/// A path option of `md --delta`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PathArg {
    /// Coming from far away.
    Approach,
    /// Retracting after `--from`.
    Retract,
}

/// Maugis-Dugdale curve with the Kim extension, nondimensional (paper eq 7).
#[derive(Debug, Clone, clap::Args)]
pub struct MdCommand {
    /// Transition parameter lambda.
    #[arg(long, allow_hyphen_values = true)]
    pub lambda: f64,
    /// Points on the curve.
    #[arg(long, default_value_t = 200, allow_hyphen_values = true)]
    pub points: i64,
    /// Largest interference Delta of the curve.
    #[arg(long, default_value_t = 5.0, allow_hyphen_values = true)]
    pub delta_end: f64,
    /// Print the force at this one interference Delta instead of the curve.
    #[arg(long, allow_hyphen_values = true)]
    pub delta: Option<f64>,
    /// Path for --delta.
    #[arg(long, value_enum, default_value_t = PathArg::Approach, requires = "delta")]
    pub path: PathArg,
    /// Largest interference of the excursion for --path retract.
    #[arg(long, allow_hyphen_values = true)]
    pub from: Option<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Json)]
    pub format: Format,
    /// JSON curves as column arrays instead of lists of points.
    #[arg(long)]
    pub columns: bool,
}

impl MdCommand {
    /// The curve, or one point with --delta.
    pub fn execute(&self) -> Result<String, Error> {
        let Some(delta) = self.delta else {
            // the path options choose the branch of one point: the curve has every branch
            if self.from.is_some() {
                return Err(Error::usage(
                    "--from",
                    "applies to one point (--delta D --path retract --from F); the curve without --delta shows every branch",
                ));
            }
            if self.path == PathArg::Retract {
                return Err(Error::usage(
                    "--path retract",
                    "applies to one point (--delta D --from F); the curve without --delta shows every branch",
                ));
            }
            if self.points < 0 {
                return Err(Error::usage(
                    "--points",
                    format!("{}: must be in [4, 100000]", self.points),
                ));
            }
            let r = md::curve(self.lambda, self.points as usize, self.delta_end)
                .map_err(argument_error)?;
            return Ok(r.render(self.format, self.columns));
        };
        let p = match (self.path, self.from) {
            (PathArg::Approach, None) => Path::Approach,
            (PathArg::Approach, Some(_)) => {
                return Err(Error::usage("--from", "applies to --path retract only"))
            }
            (PathArg::Retract, Some(f)) => Path::Retract { from: f },
            (PathArg::Retract, None) => return Err(Error::usage("--path retract", "needs --from")),
        };
        let r = md::point(self.lambda, delta, p).map_err(argument_error)?;
        Ok(r.render(self.format, self.columns))
    }
}
