//! `stiction asperity`: one elasto-plastic adhesive asperity loaded to each delta_max and
//! unloaded (the paper's Fig 2 scene).

use super::Command;
use crate::accuracy::Targets;
use crate::error::Error;
use crate::guards;
use crate::model::{self, Asperity};
use crate::plot::{self, Panel, Series};
use crate::render::{self, Format, Render, Warning};
use crate::scene::{AsperityScene, Loaded};
use asperity_plastic::PULL_OFF_TOLERANCE;
use contact_core::numeric::linspace;
use contact_core::{AsperityHistory, AsperityModel, Path};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::PathBuf;

/// One elasto-plastic adhesive asperity loaded and unloaded (paper Fig 2).
#[derive(Debug, Clone, clap::Args)]
pub struct AsperityCommand {
    /// Scene file (TOML); the paper's Fig 2 scene if absent.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Maximum interference (m); repeat for several cases. Replaces the scene's list.
    #[arg(long = "delta-max", allow_hyphen_values = true)]
    pub delta_max: Vec<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write an SVG plot of the curves.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// A point of a single-asperity curve: interference (m), force (N).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ForcePoint {
    /// Interference (m).
    pub delta: f64,
    /// Force (N, compressive > 0).
    pub force: f64,
}

/// One loading/unloading case.
#[derive(Debug, Clone, Serialize)]
pub struct AsperityCase {
    /// Maximum interference (m).
    pub delta_max: f64,
    /// Residual height loss (m), eq 4.
    pub delta_res: f64,
    /// Residual radius (m), eq 5.
    pub r_res: f64,
    /// R_eff on loading at delta_max (m), eq 12 with x = 1.
    pub r_eff_loading: f64,
    /// Most tensile force on the unloading path (N).
    pub pull_off_force: f64,
    /// Where it occurs (m).
    pub pull_off_interference: f64,
    /// The same for the elastic asperity (no yield).
    pub elastic_pull_off_force: f64,
    /// delta_max beyond the fits' range (delta_max/delta_CP > 110).
    pub extrapolated: bool,
    /// Loading curve, from out of contact to delta_max.
    pub loading: Vec<ForcePoint>,
    /// Unloading curve, from delta_max to below the jump-out.
    pub unloading: Vec<ForcePoint>,
}

/// Error estimates of the reported quantities.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct AsperityErrors {
    /// Largest change of a pull-off force within its location tolerance (N): each force is
    /// solved to rounding, the minimum's location to 1e-10 of its bracket.
    pub pull_off: f64,
}

/// `stiction asperity`.
#[derive(Debug, Clone, Serialize)]
pub struct AsperityReport {
    /// Plot and table title.
    pub title: String,
    /// Yield onset delta_CP (m), eq 1.
    #[serde(serialize_with = "crate::render::number_or_name")]
    pub delta_cp: f64,
    /// Transition parameter at the initial radius.
    pub lambda: f64,
    /// Initial radius (m).
    pub radius: f64,
    /// Accuracy mode and targets (an asperity solves every point to rounding in every mode).
    pub accuracy: Targets,
    /// Error estimates.
    pub error_estimate: AsperityErrors,
    /// The cases.
    pub cases: Vec<AsperityCase>,
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// The resolved scene.
    pub scene: AsperityScene,
}

fn pull_off_error(m: &Asperity, delta_max: f64, at: f64, force: f64) -> Result<f64, Error> {
    let hist = AsperityHistory { delta_max };
    let path = Path::Retract { from: delta_max };
    let j = m.jumps(hist)?;
    let h = PULL_OFF_TOLERANCE.rel * (delta_max - j.jump_out);
    let mut worst: f64 = 0.0;
    for x in [at - h, at + h] {
        if x > j.jump_out && x <= delta_max {
            worst = worst.max((m.force(x, hist, path)? - force).abs());
        }
    }
    Ok(worst)
}

impl Command for AsperityCommand {
    type Scene = AsperityScene;
    type Report = AsperityReport;

    fn scene_path(&self) -> Option<&std::path::Path> {
        self.scene.as_deref()
    }

    fn apply(&self, scene: &mut AsperityScene) -> Result<(), Error> {
        if !self.delta_max.is_empty() {
            scene.delta_max = self.delta_max.clone();
        }
        Ok(())
    }

    fn overrides(&self) -> Vec<(&'static str, &'static str)> {
        if self.delta_max.is_empty() {
            vec![]
        } else {
            vec![("delta_max", "--delta-max")]
        }
    }

    fn run(&self, loaded: &Loaded<AsperityScene>) -> Result<AsperityReport, Error> {
        let scene = &loaded.scene;
        let c = &scene.contact;
        let plastic = model::asperity(c, false)?;
        let elastic = model::asperity(c, true)?;
        let pair = model::pair(c)?;
        let lambda = maugis_kim::Scales::lambda(pair.k(), c.work_of_adhesion, c.z0, c.radius);
        let n = scene.points;
        let mut cases = Vec::new();
        let mut error: f64 = 0.0;
        for &dmax in &scene.delta_max {
            let virgin = AsperityHistory::VIRGIN;
            let j0 = plastic.jumps(virgin)?;
            let start = j0.jump_in - 0.02 * (dmax - j0.jump_in);
            let loading = linspace(start, dmax, n)
                .map(|delta| {
                    Ok(ForcePoint {
                        delta,
                        force: plastic.force(delta, virgin, Path::Approach)?,
                    })
                })
                .collect::<Result<Vec<_>, Error>>()?;
            let hist = AsperityHistory { delta_max: dmax };
            let j = plastic.jumps(hist)?;
            let end = j.jump_out - 0.02 * (dmax - j.jump_out);
            let unloading = linspace(dmax, end, n)
                .map(|delta| {
                    Ok(ForcePoint {
                        delta,
                        force: plastic.force(delta, hist, Path::Retract { from: dmax })?,
                    })
                })
                .collect::<Result<Vec<_>, Error>>()?;
            let pull = plastic.pull_off(dmax)?;
            let epull = elastic.pull_off(dmax)?;
            error = error
                .max(pull_off_error(&plastic, dmax, pull.delta, pull.force)?)
                .max(pull_off_error(&elastic, dmax, epull.delta, epull.force)?);
            let st = plastic.plastic_state(hist);
            cases.push(AsperityCase {
                delta_max: dmax,
                delta_res: st.delta_res,
                r_res: st.r_res,
                r_eff_loading: plastic.effective(dmax, dmax).radius,
                pull_off_force: pull.force,
                pull_off_interference: pull.delta,
                elastic_pull_off_force: epull.force,
                extrapolated: st.extrapolated,
                loading,
                unloading,
            });
        }
        let dcp = plastic.delta_cp();
        let mut warnings: Vec<Warning> = guards::adhesion_yields(c, &plastic, &elastic)?
            .into_iter()
            .collect();
        warnings.extend(guards::asperity_beyond_fit(dcp, &scene.delta_max));
        Ok(AsperityReport {
            title: loaded.title(),
            delta_cp: dcp,
            lambda,
            radius: c.radius,
            accuracy: scene.accuracy.targets(),
            error_estimate: AsperityErrors { pull_off: error },
            cases,
            warnings,
            scene: scene.clone(),
        })
    }

    fn outputs(&self, report: &AsperityReport) -> Result<Option<crate::render::OutputSet>, Error> {
        if let Some(p) = &self.plot {
            super::write_plot(p, plot_svg(report))?;
        }
        Ok(None)
    }

    fn format(&self) -> Format {
        self.format
    }
}

/// The curves as the paper's Fig 2 draws them (uN against nm).
pub fn plot_svg(r: &AsperityReport) -> Result<String, String> {
    let mut series = Vec::new();
    for c in &r.cases {
        let tag = format!("{:.0} nm", c.delta_max * 1e9);
        let pts = |v: &[ForcePoint]| v.iter().map(|p| (p.delta * 1e9, p.force * 1e6)).collect();
        series.push(Series {
            name: format!("loading to {tag}"),
            points: pts(&c.loading),
        });
        series.push(Series {
            name: format!("unloading from {tag}"),
            points: pts(&c.unloading),
        });
    }
    plot::svg(
        &r.title,
        &[Panel {
            caption: format!(
                "eq 1 {}, delta_CP = {}",
                r.scene.contact.yield_modulus().as_str(),
                render::si(r.delta_cp, "m", 4)
            ),
            x_label: "interference delta [nm]".into(),
            y_label: "force [uN]".into(),
            series,
            x_range: None,
            y_range: None,
        }],
    )
}

impl Render for AsperityReport {
    fn table(&self) -> String {
        let mut s = String::new();
        let c = &self.scene.contact;
        let _ = writeln!(s, "{}", self.title);
        let _ = writeln!(
            s,
            "laws: {} adhesion, {} plasticity, eq 1 {}; accuracy {} (points solved to rounding)",
            model::adhesion_name(c.adhesion_law),
            model::plasticity_name(c.plasticity_law),
            c.yield_modulus().as_str(),
            self.accuracy.mode
        );
        let _ = writeln!(
            s,
            "R = {}, delta_CP = {}, lambda(R) = {:.4}",
            render::si(self.radius, "m", 4),
            render::si(self.delta_cp, "m", 5),
            self.lambda
        );
        let _ = writeln!(
            s,
            "{:>12} {:>10} {:>12} {:>12} {:>14} {:>14} {:>6}",
            "delta_max", "dmax/dCP", "delta_res", "R_res", "pull-off", "elastic", "extrap"
        );
        for k in &self.cases {
            let _ = writeln!(
                s,
                "{:>12} {:>10.3} {:>12} {:>12} {:>14} {:>14} {:>6}",
                render::si(k.delta_max, "m", 4),
                k.delta_max / self.delta_cp,
                render::si(k.delta_res, "m", 4),
                render::si(k.r_res, "m", 4),
                render::si(k.pull_off_force, "N", 5),
                render::si(k.elastic_pull_off_force, "N", 5),
                k.extrapolated
            );
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from("delta_max_m,branch,delta_m,force_n\n");
        for c in &self.cases {
            for (name, pts) in [("loading", &c.loading), ("unloading", &c.unloading)] {
                for p in pts {
                    let _ = writeln!(s, "{},{},{},{}", c.delta_max, name, p.delta, p.force);
                }
            }
        }
        s
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }
}
