//! `stiction md`: the nondimensional Maugis-Kim curve (paper eqs 7-11, Kim extension).

use crate::error::Error;
use crate::render::{Format, Render};
use contact_core::Path;
use maugis_kim::{MdCurve, MdPoint};
use serde::Serialize;
use std::fmt::Write as _;

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
    pub points: usize,
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
}

impl MdCommand {
    /// The curve, or one point with --delta.
    pub fn execute(&self) -> Result<String, Error> {
        let Some(delta) = self.delta else {
            return Ok(super::show(
                &curve(self.lambda, self.points, self.delta_end)?,
                self.format,
            ));
        };
        let p = match (self.path, self.from) {
            (PathArg::Approach, None) => Path::Approach,
            (PathArg::Approach, Some(_)) => {
                return Err(Error::usage("--from", "applies to --path retract only"))
            }
            (PathArg::Retract, Some(f)) => Path::Retract { from: f },
            (PathArg::Retract, None) => return Err(Error::usage("--path retract", "needs --from")),
        };
        Ok(super::show(&point(self.lambda, delta, p)?, self.format))
    }
}

/// The curve and its landmarks.
#[derive(Debug, Clone, Serialize)]
pub struct MdReport {
    /// Transition parameter lambda.
    pub lambda: f64,
    /// Jump-in interference on approach, Delta_in = -2/(pi lambda).
    pub jump_in_delta: f64,
    /// Turning point (jump-out) interference Delta_t.
    pub turning_delta: f64,
    /// Force at the turning point.
    pub turning_force: f64,
    /// Minimum force on the stable branch (DMT -2, JKR -3/2).
    pub pull_off_load_control: f64,
    /// Force at jump-out (JKR -5/6).
    pub pull_off_displacement_control: f64,
    /// The whole curve (contact-branch points carry `s`; non-contact points omit it).
    pub curve: Vec<MdPoint>,
}

/// One point on a path.
#[derive(Debug, Clone, Serialize)]
pub struct MdPointReport {
    /// Transition parameter.
    pub lambda: f64,
    /// Interference Delta.
    pub delta: f64,
    /// `approach` or `retract`.
    pub path: &'static str,
    /// Largest interference of the excursion (retract).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub from: Option<f64>,
    /// Force Fbar.
    pub force: f64,
}

fn curve_for(lambda: f64) -> Result<MdCurve, Error> {
    if !(lambda.is_finite() && (1e-6..=1e6).contains(&lambda)) {
        return Err(Error::usage(
            "--lambda",
            format!(
                "{}: must be finite and in [1e-6, 1e6]",
                crate::scene::num(lambda)
            ),
        ));
    }
    Ok(MdCurve::new(lambda)?)
}

/// The curve of `lambda` with `points` points up to `delta_end`.
pub fn curve(lambda: f64, points: usize, delta_end: f64) -> Result<MdReport, Error> {
    let c = curve_for(lambda)?;
    if !(4..=100_000).contains(&points) {
        return Err(Error::usage(
            "--points",
            format!("{points}: must be in [4, 100000]"),
        ));
    }
    let dj = c.junction().delta;
    if !(delta_end.is_finite() && delta_end > dj && delta_end <= 1e6) {
        return Err(Error::usage(
            "--delta-end",
            format!(
                "{}: must be finite, above the junction Delta_j = {} and at most 1e6",
                crate::scene::num(delta_end),
                crate::scene::num(dj)
            ),
        ));
    }
    let t = c.pull_off_displacement_control()?;
    Ok(MdReport {
        lambda,
        jump_in_delta: c.jump_in_delta(),
        turning_delta: t.delta,
        turning_force: t.force,
        pull_off_load_control: c.pull_off_load_control()?.force,
        pull_off_displacement_control: t.force,
        curve: c.curve(points, delta_end)?,
    })
}

/// The force at `delta` on `path`.
pub fn point(lambda: f64, delta: f64, path: Path) -> Result<MdPointReport, Error> {
    let c = curve_for(lambda)?;
    if !(delta.is_finite() && delta.abs() <= 1e6) {
        return Err(Error::usage(
            "--delta",
            format!(
                "{}: must be finite, |Delta| <= 1e6",
                crate::scene::num(delta)
            ),
        ));
    }
    let (name, from) = match path {
        Path::Approach => ("approach", None),
        Path::Retract { from } => {
            if !(from.is_finite() && from.abs() <= 1e6) {
                return Err(Error::usage(
                    "--from",
                    format!(
                        "{}: must be finite, |Delta| <= 1e6",
                        crate::scene::num(from)
                    ),
                ));
            }
            ("retract", Some(from))
        }
    };
    Ok(MdPointReport {
        lambda,
        delta,
        path: name,
        from,
        force: c.force(delta, path)?,
    })
}

impl Render for MdReport {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Maugis-Kim, lambda = {} (nondimensional, eq 7)",
            self.lambda
        );
        let _ = writeln!(s, "  jump-in      Delta_in = {:.10}", self.jump_in_delta);
        let _ = writeln!(
            s,
            "  turning pt.  Delta_t  = {:.10}   Fbar_t = {:.10}",
            self.turning_delta, self.turning_force
        );
        let _ = writeln!(
            s,
            "  pull-off, load control         Fbar = {:.10}",
            self.pull_off_load_control
        );
        let _ = writeln!(
            s,
            "  pull-off, displacement control Fbar = {:.10}",
            self.pull_off_displacement_control
        );
        let _ = writeln!(
            s,
            "{:>14} {:>14} {:>12} {:>12} {:>7}",
            "Delta", "Fbar", "A", "C", "stable"
        );
        for p in &self.curve {
            let _ = writeln!(
                s,
                "{:>14.6e} {:>14.6e} {:>12.5e} {:>12.5e} {:>7}",
                p.delta, p.force, p.a, p.c, p.stable
            );
        }
        s
    }
    fn csv(&self) -> String {
        let mut s = String::from("delta,force,a,c,branch,stable\n");
        for p in &self.curve {
            let branch = match p.branch {
                maugis_kim::Branch::Contact => "contact",
                maugis_kim::Branch::NonContact => "non_contact",
            };
            let _ = writeln!(
                s,
                "{},{},{},{},{},{}",
                p.delta, p.force, p.a, p.c, branch, p.stable
            );
        }
        s
    }
}

impl Render for MdPointReport {
    fn table(&self) -> String {
        format!(
            "lambda = {}, Delta = {}, path = {}: Fbar = {}\n",
            self.lambda, self.delta, self.path, self.force
        )
    }
    fn csv(&self) -> String {
        format!(
            "lambda,delta,path,force\n{},{},{},{}\n",
            self.lambda, self.delta, self.path, self.force
        )
    }
}
