//! `stiction asperity`: one elasto-plastic adhesive asperity loaded to each delta_max and
//! unloaded (the paper's Fig 2 scene).

use super::{finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::plot::{self, Panel, Series};
use crate::render::{self, csv_num, Format, Render, Validity, Warning};
use std::fmt::Write as _;
use std::path::PathBuf;
use stiction_model::asperity::{self, AsperityResult, ForcePoint};
use stiction_model::keys::Kind;
use stiction_model::spec::AsperitySpec;

/// A plot draws at most this many cases (evenly chosen, the first and the last included):
/// more lines than that are unreadable, and a figure of 1e5 cases would weigh 400 MB.
pub const MAX_PLOTTED_CASES: usize = 12;

/// One elasto-plastic adhesive asperity loaded and unloaded (paper Fig 2).
#[derive(Debug, Clone, clap::Args)]
pub struct AsperityCommand {
    /// Scene, `--set`, `--strict`.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Maximum interference (m); repeat for several cases. Replaces the scene's list.
    #[arg(long = "delta-max", allow_hyphen_values = true)]
    pub delta_max: Vec<f64>,
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

impl AsperityCommand {
    /// Runs the command.
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        let mut edits = Vec::new();
        if !self.delta_max.is_empty() {
            let list = self
                .delta_max
                .iter()
                .map(|&d| toml::Value::Float(d))
                .collect();
            edits.push(("delta_max", toml::Value::Array(list), "--delta-max"));
        }
        let loaded = self.scene.load(Kind::Asperity, &edits)?;
        let spec = AsperitySpec::new(&loaded.scene, ctx.registry).map_err(|e| loaded.blame(e))?;
        preflight(None, &[], self.plot.as_deref())?;
        let result = asperity::run(&spec)?;
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

/// The curves as the paper's Fig 2 draws them (uN against nm).
pub fn plot_svg(r: &AsperityResult) -> Result<String, String> {
    let mut series = Vec::new();
    let n = r.cases.len();
    let stride = n.div_ceil(MAX_PLOTTED_CASES).max(1);
    for (i, c) in r.cases.iter().enumerate() {
        if i % stride != 0 && i + 1 != n {
            continue;
        }
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
                "{} plasticity, eq 1 {}, reload {}, delta_CP = {}{}",
                r.laws.plasticity,
                r.laws.yield_modulus,
                r.laws.reload,
                render::si(r.delta_cp, "m", 4),
                if stride > 1 {
                    format!(" ({} of {n} cases drawn)", n.div_ceil(stride))
                } else {
                    String::new()
                }
            ),
            x_label: "interference delta [nm]".into(),
            y_label: "force [uN]".into(),
            series,
            x_range: None,
            y_range: None,
        }],
    )
}

impl Render for AsperityResult {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}", self.title);
        let _ = writeln!(
            s,
            "{}; accuracy {} (points solved to rounding)",
            super::switch::laws_line(&self.laws),
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
        if !self.validity.holds {
            let _ = writeln!(s, "{}", self.validity.words());
        }
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
                    let _ = writeln!(
                        s,
                        "{},{},{},{}",
                        csv_num(c.delta_max),
                        name,
                        csv_num(p.delta),
                        csv_num(p.force)
                    );
                }
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
