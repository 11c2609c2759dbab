//! The rough surface's result (`stiction surface`): its table, CSV and plot.

use crate::plot::{self, Panel, Series};
use crate::render::{self, csv_num, Render, Validity, Warning};
use crate::{Plot, ReportError};
use std::fmt::Write as _;
use stiction_model::surface::SurfaceResult;
use stiction_model::switch_1d::PressurePoint;

impl Plot for SurfaceResult {
    /// The contact law (MPa against nm), with a zoom on the adhesive part.
    fn svg(&self) -> Result<String, ReportError> {
        plot_svg(self).map_err(|m| ReportError::plot("surface.svg".as_ref(), m))
    }
}

fn plot_svg(r: &SurfaceResult) -> Result<String, String> {
    let pts = |v: &[PressurePoint]| -> Vec<(f64, f64)> {
        v.iter().map(|p| (p.d * 1e9, p.pressure * 1e-6)).collect()
    };
    let mut series = vec![Series {
        name: "virgin loading".into(),
        points: pts(&r.loading),
        ..Default::default()
    }];
    if !r.unloading.is_empty() {
        series.push(Series {
            name: "unloading".into(),
            points: pts(&r.unloading),
            ..Default::default()
        });
        series.push(Series {
            name: "reloading".into(),
            points: pts(&r.reloading),
            ..Default::default()
        });
    }
    let mut panels = vec![Panel {
        caption: "whole curves".into(),
        x_label: "separation d [nm]".into(),
        y_label: "pressure [MPa]".into(),
        series: series.clone(),
        x_range: None,
        y_range: None,
        ..Default::default()
    }];
    if let Some(p) = r.pull_out_pressure.filter(|&p| p > 0.0) {
        let y = p * 1e-6;
        panels.push(Panel {
            caption: "adhesive part".into(),
            x_label: "separation d [nm]".into(),
            y_label: "pressure [MPa]".into(),
            series,
            x_range: None,
            y_range: Some((-1.5 * y, 1.5 * y)),
            ..Default::default()
        });
    }
    plot::svg(&r.title, &panels)
}

impl Render for SurfaceResult {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}", self.title);
        let _ = writeln!(
            s,
            "{}; sigma_s = {}; accuracy {} (pressures to {})",
            crate::switch::laws_line(&self.laws),
            render::si(self.sigma_s, "m", 4),
            self.accuracy.mode,
            render::pressure(self.error_estimate.pressure)
        );
        if let (Some(p), Some(d), Some(u)) = (
            self.pull_out_pressure,
            self.pull_out_separation,
            self.unload_from,
        ) {
            let _ = writeln!(
                s,
                "unloaded from d = {}: pull-out pressure {} at d = {}",
                render::si(u, "m", 4),
                render::pressure(p),
                render::si(d, "m", 4)
            );
        }
        if !self.validity.holds {
            let _ = writeln!(s, "{}", self.validity.words());
        }
        let _ = writeln!(
            s,
            "{:>12} {:>14} {:>12} {:>14}",
            "d", "loading", "d", "unloading"
        );
        for (i, p) in self.loading.iter().enumerate() {
            let u = self.unloading.get(i).map_or(String::new(), |q| {
                format!(
                    "{:>12} {:>14}",
                    render::si(q.d, "m", 4),
                    render::pressure(q.pressure)
                )
            });
            let _ = writeln!(
                s,
                "{:>12} {:>14} {u}",
                render::si(p.d, "m", 4),
                render::pressure(p.pressure)
            );
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from("branch,d_m,pressure_pa\n");
        for (name, pts) in [
            ("loading", &self.loading),
            ("unloading", &self.unloading),
            ("reloading", &self.reloading),
        ] {
            for p in pts {
                let _ = writeln!(s, "{},{},{}", name, csv_num(p.d), csv_num(p.pressure));
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
