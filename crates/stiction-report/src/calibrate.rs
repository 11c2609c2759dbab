//! The calibration's result (`stiction calibrate`): its table, CSV and overlay plot.

use crate::plot::{self, Panel, Series};
use crate::render::{self, Render, Warning};
use crate::{Plot, ReportError};
use std::fmt::Write as _;
use stiction_model::calibration::{CalibrationResult, Selection};

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

impl Plot for CalibrationResult {
    /// The overlay: one panel per delta_max, the data as crosses and the fitted model as
    /// lines, force in uN against interference in nm.
    fn svg(&self) -> Result<String, ReportError> {
        plot_svg(self).map_err(|m| ReportError::plot("calibration.svg".as_ref(), m))
    }
}

fn plot_svg(r: &CalibrationResult) -> Result<String, String> {
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
                    ..Default::default()
                });
                panels.len() - 1
            }
        };
        panels[idx].series.push(Series {
            name: format!("FE {}", curve.branch),
            points: data,
            ..Default::default()
        });
        panels[idx].series.push(Series {
            name: format!("fit {}", curve.branch),
            points: model,
            ..Default::default()
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
            r.laws.adhesion,
            r.fit.yield_modulus.as_str()
        ),
        &panels,
    )
}

impl Render for CalibrationResult {
    fn table(&self) -> String {
        let mut s = String::new();
        let c = &self.model;
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
            self.laws.adhesion,
            c.work_of_adhesion,
            render::si(c.z0, "m", 4),
            render::si(c.radius, "m", 4),
            self.laws.yield_modulus,
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
