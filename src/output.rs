//! Formatting of reports: JSON, CSV, plain tables and SVG plots. Library crates never
//! print; this module is the only place that does.

use crate::run::{AsperityReport, MdReport, SurfaceReport, SwitchReport};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// Output format of a subcommand.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    Json,
    Csv,
    Table,
}

pub fn json<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_string_pretty(v).expect("reports serialise") + "\n"
}

pub fn md_csv(r: &MdReport) -> String {
    let mut s = String::from("delta,force,a,c,branch,stable\n");
    for p in &r.curve {
        let _ = writeln!(
            s,
            "{},{},{},{},{:?},{}",
            p.delta, p.force, p.a, p.c, p.branch, p.stable
        );
    }
    s
}

pub fn md_table(r: &MdReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Maugis-Kim, lambda = {}", r.lambda);
    let _ = writeln!(s, "  jump-in      Delta_in = {:.10}", r.jump_in_delta);
    let _ = writeln!(
        s,
        "  turning pt.  Delta_t  = {:.10}   Fbar_t = {:.10}",
        r.turning_delta, r.turning_force
    );
    let _ = writeln!(
        s,
        "  pull-off, load control         Fbar = {:.10}",
        r.pull_off_load_control
    );
    let _ = writeln!(
        s,
        "  pull-off, displacement control Fbar = {:.10}",
        r.pull_off_displacement_control
    );
    let _ = writeln!(
        s,
        "{:>14} {:>14} {:>12} {:>12} {:>7}",
        "Delta", "Fbar", "A", "C", "stable"
    );
    for p in &r.curve {
        let _ = writeln!(
            s,
            "{:>14.6e} {:>14.6e} {:>12.5e} {:>12.5e} {:>7}",
            p.delta, p.force, p.a, p.c, p.stable
        );
    }
    s
}

pub fn asperity_csv(r: &AsperityReport) -> String {
    let mut s = String::from("delta_max_m,branch,delta_m,force_n\n");
    for c in &r.cases {
        for (name, pts) in [("loading", &c.loading), ("unloading", &c.unloading)] {
            for p in pts {
                let _ = writeln!(s, "{},{},{},{}", c.delta_max, name, p.delta, p.force);
            }
        }
    }
    s
}

pub fn asperity_table(r: &AsperityReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Single asperity: R = {:.3} um, delta_CP = {:.4} nm, lambda(R) = {:.4}",
        r.radius * 1e6,
        r.delta_cp * 1e9,
        r.lambda
    );
    let _ = writeln!(
        s,
        "{:>12} {:>12} {:>12} {:>14} {:>14} {:>14} {:>6}",
        "dmax [nm]",
        "dmax/dCP",
        "dres [nm]",
        "R_res [um]",
        "pull-off [uN]",
        "elastic [uN]",
        "extrap"
    );
    for c in &r.cases {
        let _ = writeln!(
            s,
            "{:>12.3} {:>12.3} {:>12.4} {:>14.4} {:>14.4} {:>14.4} {:>6}",
            c.delta_max * 1e9,
            c.delta_max / r.delta_cp,
            c.delta_res * 1e9,
            c.r_res * 1e6,
            c.pull_off_force * 1e6,
            c.elastic_pull_off_force * 1e6,
            c.extrapolated
        );
    }
    s
}

pub fn surface_csv(r: &SurfaceReport) -> String {
    let mut s = String::from("branch,d_m,pressure_pa\n");
    for (name, pts) in [("loading", &r.loading), ("unloading", &r.unloading)] {
        for p in pts {
            let _ = writeln!(s, "{},{},{}", name, p.d, p.pressure);
        }
    }
    s
}

pub fn surface_table(r: &SurfaceReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Rough surface, sigma_s = {:.3} nm, accuracy {:?}",
        r.sigma_s * 1e9,
        r.accuracy
    );
    if let (Some(p), Some(d), Some(u)) = (r.pull_out_pressure, r.pull_out_separation, r.unload_from)
    {
        let _ = writeln!(
            s,
            "  unloaded from d = {:.4} nm: pull-out pressure {:.6e} Pa at d = {:.4} nm",
            u * 1e9,
            p,
            d * 1e9
        );
    }
    let _ = writeln!(
        s,
        "{:>10} {:>14} {:>14}",
        "d [nm]", "loading [Pa]", "unloading [Pa]"
    );
    for (i, p) in r.loading.iter().enumerate() {
        let u = r.unloading.get(i).map_or(String::new(), |q| {
            format!("{:>14.6e} (d = {:.4})", q.pressure, q.d * 1e9)
        });
        let _ = writeln!(s, "{:>10.4} {:>14.6e} {}", p.d * 1e9, p.pressure, u);
    }
    s
}

pub fn switch_cycles_csv(r: &SwitchReport) -> String {
    let mut s = String::from("cycle,d_e_m,pull_out_pressure_pa,pull_out_separation_m,sticks\n");
    for c in &r.cycles {
        let _ = writeln!(
            s,
            "{},{},{},{},{}",
            c.cycle, c.d_e, c.pull_out_pressure, c.pull_out_separation, c.sticks
        );
    }
    if let Some(e) = &r.elastic {
        let _ = writeln!(
            s,
            "elastic,{},{},{},{}",
            e.d_e,
            e.pull_out_pressure,
            e.pull_out_separation,
            e.pull_out_pressure > r.restoring_pressure
        );
    }
    s
}

pub fn switch_curves_csv(r: &SwitchReport) -> String {
    let mut s = String::from("curve,cycle,d_m,pressure_pa\n");
    for p in &r.loading {
        let _ = writeln!(s, "loading,1,{},{}", p.d, p.pressure);
    }
    for c in &r.cycles {
        for p in &c.unloading {
            let _ = writeln!(s, "unloading,{},{},{}", c.cycle, p.d, p.pressure);
        }
    }
    if let Some(e) = &r.elastic {
        for p in &e.unloading {
            let _ = writeln!(s, "elastic_unloading,,{},{}", p.d, p.pressure);
        }
    }
    s
}

pub fn switch_table(r: &SwitchReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Micro-switch: K_s = {:.4e} Pa/m, V_PI = {:.3} V, U = {:.3} V, E_I = {} J/m^2, accuracy {:?}",
        r.k_s, r.v_pull_in, r.voltage, r.impact_energy, r.accuracy
    );
    let _ = writeln!(
        s,
        "restoring pressure K_s d0 = {:.6} MPa",
        r.restoring_pressure * 1e-6
    );
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "{:>7} {:>12} {:>18} {:>12} {:>10}",
        "cycle", "d_e [nm]", "pull-out [MPa]", "change [%]", "verdict"
    );
    let mut prev: Option<f64> = None;
    for c in &r.cycles {
        let change = prev.map_or("-".to_string(), |p| {
            format!("{:+.4}", 100.0 * (c.pull_out_pressure - p) / p)
        });
        let _ = writeln!(
            s,
            "{:>7} {:>12.5} {:>18.8} {:>12} {:>10}",
            c.cycle,
            c.d_e * 1e9,
            c.pull_out_pressure * 1e-6,
            change,
            if c.sticks { "sticks" } else { "releases" }
        );
        prev = Some(c.pull_out_pressure);
    }
    if let Some(e) = &r.elastic {
        let _ = writeln!(
            s,
            "{:>7} {:>12.5} {:>18.8} {:>12} {:>10}",
            "elastic",
            e.d_e * 1e9,
            e.pull_out_pressure * 1e-6,
            "-",
            if e.pull_out_pressure > r.restoring_pressure {
                "sticks"
            } else {
                "releases"
            }
        );
    }
    let _ = writeln!(s);
    match r.accommodated_after {
        Some(k) => {
            let _ = writeln!(
                s,
                "accommodated after cycle {k} (next cycle changes by < {:e})",
                r.accommodation_tolerance
            );
        }
        None => {
            let _ = writeln!(
                s,
                "not accommodated within {} cycles (tolerance {:e})",
                r.cycles.len(),
                r.accommodation_tolerance
            );
        }
    }
    let worst = r
        .cycles
        .iter()
        .map(|c| c.pull_out_pressure)
        .fold(0.0, f64::max);
    let _ = writeln!(
        s,
        "verdict: {} (largest pull-out {:.6} MPa vs restoring {:.6} MPa)",
        if r.stiction {
            "STICTION - the spring cannot pull the switch open"
        } else {
            "no stiction - the spring opens the switch"
        },
        worst * 1e-6,
        r.restoring_pressure * 1e-6
    );
    s
}

/// One named line of a plot.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

/// Writes an SVG line plot.
pub fn plot(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), String> {
    let all = series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in all {
        if x.is_finite() && y.is_finite() {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if !(x0 < x1) {
        return Err("nothing to plot".into());
    }
    if !(y0 < y1) {
        y1 = y0 + 1.0;
    }
    let pad = 0.05 * (y1 - y0);
    let root = SVGBackend::new(path, (900, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()
        .map_err(|e| e.to_string())?;
    let colors = [
        BLACK,
        RED,
        BLUE,
        GREEN,
        MAGENTA,
        CYAN,
        RGBColor(200, 120, 0),
        RGBColor(120, 0, 200),
    ];
    for (i, s) in series.iter().enumerate() {
        let c = colors[i % colors.len()];
        chart
            .draw_series(LineSeries::new(s.points.iter().copied(), c.stroke_width(2)))
            .map_err(|e| e.to_string())?
            .label(s.name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerRight)
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

pub fn asperity_plot(r: &AsperityReport, path: &Path) -> Result<(), String> {
    let mut series = Vec::new();
    for c in &r.cases {
        let tag = format!("{:.0} nm", c.delta_max * 1e9);
        series.push(Series {
            name: format!("loading to {tag}"),
            points: c
                .loading
                .iter()
                .map(|p| (p.delta * 1e9, p.force * 1e6))
                .collect(),
        });
        series.push(Series {
            name: format!("unloading from {tag}"),
            points: c
                .unloading
                .iter()
                .map(|p| (p.delta * 1e9, p.force * 1e6))
                .collect(),
        });
    }
    plot(
        path,
        "Elasto-plastic adhesive asperity (paper Fig 2)",
        "interference delta [nm]",
        "force [uN]",
        &series,
    )
}

pub fn surface_plot(r: &SurfaceReport, path: &Path) -> Result<(), String> {
    let mut series = vec![Series {
        name: "virgin loading".into(),
        points: r
            .loading
            .iter()
            .map(|p| (p.d * 1e9, p.pressure * 1e-6))
            .collect(),
    }];
    if !r.unloading.is_empty() {
        series.push(Series {
            name: "unloading".into(),
            points: r
                .unloading
                .iter()
                .map(|p| (p.d * 1e9, p.pressure * 1e-6))
                .collect(),
        });
    }
    plot(
        path,
        "Rough surface contact law",
        "separation d [nm]",
        "pressure [MPa]",
        &series,
    )
}

/// Like the paper's Fig 4: loading, unloading of cycles 1, 2, 3 and the last, elastic.
/// The pressure axis is clipped to a few times the largest pull-out so that the
/// adhesive part stays readable.
pub fn switch_plot(r: &SwitchReport, path: &Path) -> Result<(), String> {
    let worst = r
        .cycles
        .iter()
        .map(|c| c.pull_out_pressure)
        .chain(r.elastic.iter().map(|e| e.pull_out_pressure))
        .fold(0.0, f64::max)
        .max(r.restoring_pressure);
    let cap = 4.0 * worst * 1e-6;
    let clip = |pts: &[switch_1d::PressurePoint]| -> Vec<(f64, f64)> {
        pts.iter()
            .filter(|p| p.pressure * 1e-6 <= cap)
            .map(|p| (p.d * 1e9, p.pressure * 1e-6))
            .collect()
    };
    let mut series = vec![Series {
        name: "loading (cycle 1)".into(),
        points: clip(&r.loading),
    }];
    let last = r.cycles.last().map_or(0, |c| c.cycle);
    for c in &r.cycles {
        if [1, 2, 3, last].contains(&c.cycle) {
            series.push(Series {
                name: format!("unloading, cycle {}", c.cycle),
                points: clip(&c.unloading),
            });
        }
    }
    if let Some(e) = &r.elastic {
        series.push(Series {
            name: "unloading, elastic asperities".into(),
            points: clip(&e.unloading),
        });
    }
    series.push(Series {
        name: "- restoring pressure K_s d0".into(),
        points: r
            .loading
            .first()
            .into_iter()
            .chain(r.loading.last())
            .map(|p| (p.d * 1e9, -r.restoring_pressure * 1e-6))
            .collect(),
    });
    plot(
        path,
        "Cyclic loading of the micro-switch (paper Fig 4)",
        "separation d [nm]",
        "pressure [MPa]",
        &series,
    )
}
