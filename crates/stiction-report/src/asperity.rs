//! One asperity's result (`stiction asperity`, the paper's Fig 2): its table, CSV and
//! plot.

use crate::plot::{self, Panel, Series};
use crate::render::{self, csv_num, Render, Validity, Warning};
use crate::{Plot, ReportError};
use std::fmt::Write as _;
use stiction_model::asperity::{AsperityResult, ForcePoint};

/// A plot draws at most this many cases (evenly chosen, the first and the last included):
/// more lines than that are unreadable, and a figure of 1e5 cases would weigh 400 MB.
pub const MAX_PLOTTED_CASES: usize = 12;

impl Plot for AsperityResult {
    /// The curves as the paper's Fig 2 draws them (uN against nm).
    fn svg(&self) -> Result<String, ReportError> {
        plot_svg(self).map_err(|m| ReportError::plot("asperity.svg".as_ref(), m))
    }
}

fn plot_svg(r: &AsperityResult) -> Result<String, String> {
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
            ..Default::default()
        });
        series.push(Series {
            name: format!("unloading from {tag}"),
            points: pts(&c.unloading),
            ..Default::default()
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
            ..Default::default()
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
            crate::switch::laws_line(&self.laws),
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
