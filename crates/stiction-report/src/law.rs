//! The contact law's tabulation (`stiction law`): its table, CSV and plot; `--out` writes
//! law.json, law.csv and law.svg.

use crate::output::OutputSet;
use crate::plot::{self, Panel, Series};
use crate::render::{self, Render, Validity, Warning};
use crate::{Plot, Report, ReportError};
use std::fmt::Write as _;
use std::path::Path;
use stiction_model::contact_law::ContactLaw;
use stiction_model::law::{Histories, LawResult};

/// The files `stiction law --out` writes.
const FILES: &[&str] = &["law.json", "law.csv", "law.svg"];

/// The law (MPa against nm): the virgin envelope and the branches of three histories, whole
/// and zoomed on the adhesive part.
fn plot_svg(law: &ContactLaw, h: &Histories, title: &str, sigma: f64) -> Result<String, String> {
    let x_end = (h.d_min_hi + sigma)
        .min(h.d_min_lo + 3.0 * sigma)
        .min(h.virgin_reach);
    let pts = |d: &[f64], p: &[f64]| -> Vec<(f64, f64)> {
        d.iter()
            .zip(p)
            .filter(|(&d, _)| d <= x_end)
            .map(|(&d, &p)| (d * 1e9, p * 1e-6))
            .collect()
    };
    let mut series = vec![Series {
        name: "virgin envelope".into(),
        points: pts(law.virgin().d(), law.virgin().pressure()),
        ..Default::default()
    }];
    let grid = law.d_min_grid();
    let mut picks: Vec<usize> = Vec::new();
    let mut targets = vec![grid[0]];
    if let Some(d) = h.deepest_d_e {
        targets.push(d);
    }
    let top = grid[grid.len() - 1].min(x_end);
    targets.push(grid[0] + 0.5 * (top - grid[0]));
    for t in targets {
        let k = grid.partition_point(|&g| g < t).min(grid.len() - 1);
        if !picks.contains(&k) {
            picks.push(k);
        }
    }
    picks.sort_unstable();
    let mut tensile: f64 = 0.0;
    for &k in &picks {
        let b = &law.branches()[k];
        let label = render::si(b.d_min(), "m", 3);
        series.push(Series {
            name: format!("approach, d_min = {label}"),
            points: pts(b.approach().d(), b.approach().pressure()),
            ..Default::default()
        });
        series.push(Series {
            name: format!("retract, d_min = {label}"),
            points: pts(b.retract().d(), b.retract().pressure()),
            ..Default::default()
        });
        tensile = tensile.max(-b.pull_out().pressure);
    }
    let whole_y = (
        series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold(0.0, f64::min),
        law.virgin().pressure().iter().copied().fold(0.0, f64::max) * 1e-6,
    );
    let mut panels = vec![Panel {
        caption: "whole law".into(),
        x_label: "separation d [nm]".into(),
        y_label: "pressure [MPa]".into(),
        series: series.clone(),
        x_range: Some((h.d_min_lo * 1e9, x_end * 1e9)),
        y_range: (whole_y.1 > whole_y.0).then_some((1.05 * whole_y.0, 1.05 * whole_y.1)),
        ..Default::default()
    }];
    if tensile > 0.0 {
        let y = 1.5 * tensile * 1e-6;
        panels.push(Panel {
            caption: "adhesive part".into(),
            x_label: "separation d [nm]".into(),
            y_label: "pressure [MPa]".into(),
            series,
            x_range: Some((h.d_min_lo * 1e9, x_end * 1e9)),
            y_range: Some((-y, y)),
            ..Default::default()
        });
    }
    plot::svg(&format!("{title}: contact law"), &panels)
}

impl Render for LawResult {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}: contact law p(d; d_min, path)", self.title);
        let _ = writeln!(
            s,
            "{}; sigma_s = {}; accuracy {}",
            crate::switch::laws_line(&self.laws),
            render::si(self.sigma_s, "m", 4),
            self.accuracy.mode
        );
        if !self.validity.holds {
            let _ = writeln!(s, "{}", self.validity.words());
        }
        let h = &self.histories;
        let _ = writeln!(
            s,
            "histories: {} branches, d_min from {} to {} ({}); virgin reach {}",
            self.branches,
            render::si(h.d_min_lo, "m", 4),
            render::si(h.d_min_hi, "m", 4),
            h.rule,
            render::si(h.virgin_reach, "m", 4)
        );
        if let Some(d) = h.deepest_d_e {
            let _ = writeln!(
                s,
                "  deepest end of impact d_e = {} (the grid starts {} below it); first touch where p_V = {:e} x {}",
                render::si(d, "m", 4),
                render::si(h.below_deepest_d_e.unwrap_or(0.0), "m", 3),
                h.first_touch_fraction.unwrap_or(0.0),
                render::pressure(h.first_touch_reference.unwrap_or(0.0))
            );
        }
        let m = &self.measured_error;
        let _ = writeln!(
            s,
            "measured interpolation error |p_table - p_surface| / (|p_surface| + |p_pull_out(d_min)|), tolerance {:e}:",
            self.tolerance
        );
        for (name, e) in [
            ("virgin", &m.virgin),
            ("approach", &m.approach),
            ("retract", &m.retract),
        ] {
            let _ = writeln!(
                s,
                "  {name:<9} max {:.2e}  p99 {:.2e}  ({} points; worst at d = {}, d_min = {})",
                e.max,
                e.p99,
                e.samples,
                render::si(e.worst_d, "m", 4),
                render::si(e.worst_d_min, "m", 4)
            );
        }
        let r = &self.partial_reload;
        let _ = writeln!(
            s,
            "partial reload then retraction (law: the retract branch of d_min; surface: its own path from d_turn): max {:.2e}, p99 {:.2e} ({} points; worst at d = {}, d_min = {}, d_turn = {})",
            r.stats.max,
            r.stats.p99,
            r.stats.samples,
            render::si(r.stats.worst_d, "m", 4),
            render::si(r.stats.worst_d_min, "m", 4),
            render::si(r.worst_d_turn, "m", 4)
        );
        let _ = writeln!(
            s,
            "{} nodes ({} on the envelope), {} surface evaluations, converged: {}, law.json {:.2} MB, {:.1} s",
            self.nodes,
            self.virgin_nodes,
            self.source_evaluations,
            self.converged,
            self.law_json_bytes as f64 / 1e6,
            self.seconds
        );
        let _ = writeln!(
            s,
            "{:>11} {:>12} {:>11} {:>12} {:>11} {:>12}",
            "d_min", "p_V(d_min)", "pull-out d", "pull-out p", "pull-in d", "pull-in p"
        );
        let stride = self.summary.len().div_ceil(12).max(1);
        for (i, b) in self.summary.iter().enumerate() {
            if i % stride != 0 && i + 1 != self.summary.len() {
                continue;
            }
            let _ = writeln!(
                s,
                "{:>11} {:>12} {:>11} {:>12} {:>11} {:>12}",
                render::si(b.d_min, "m", 4),
                render::pressure(b.start_pressure),
                render::si(b.pull_out_d, "m", 4),
                render::pressure(b.pull_out_pressure),
                render::si(b.approach_most_tensile_d, "m", 4),
                render::pressure(b.approach_most_tensile_pressure)
            );
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from(
            "d_min_m,start_pressure_pa,pull_out_d_m,pull_out_pressure_pa,approach_most_tensile_d_m,approach_most_tensile_pressure_pa,approach_reach_m,retract_reach_m,nodes\n",
        );
        for b in &self.summary {
            let _ = writeln!(
                s,
                "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{}",
                b.d_min,
                b.start_pressure,
                b.pull_out_d,
                b.pull_out_pressure,
                b.approach_most_tensile_d,
                b.approach_most_tensile_pressure,
                b.approach_reach,
                b.retract_reach,
                b.nodes
            );
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

impl Plot for LawResult {
    fn svg(&self) -> Result<String, ReportError> {
        plot_svg(&self.law, &self.histories, &self.title, self.sigma_s)
            .map_err(|m| ReportError::plot("law.svg".as_ref(), m))
    }
}

impl Report for LawResult {
    const FILES: &'static [&'static str] = FILES;

    fn files(&self, dir: &Path) -> Result<OutputSet, ReportError> {
        let mut set = OutputSet::new(dir, FILES);
        set.add("law.json", self.law_json.as_bytes());
        let mut csv = Vec::new();
        self.law
            .write_csv(&mut csv)
            .map_err(|source| ReportError::Write {
                path: dir.join("law.csv").display().to_string(),
                source,
            })?;
        set.add("law.csv", csv);
        let svg = plot_svg(&self.law, &self.histories, &self.title, self.sigma_s)
            .map_err(|message| ReportError::plot(&dir.join("law.svg"), message))?;
        set.add("law.svg", svg);
        Ok(set)
    }
}
