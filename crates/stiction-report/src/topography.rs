//! A height map's analysis (`stiction topography`): its table, the scene fragment and the
//! plot; `--out` writes topography.json, surface.toml and topography.svg.

use crate::output::OutputSet;
use crate::render::{self, Render, Validity, Warning};
use crate::{Plot, Report, ReportError};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;
use stiction_model::guards::si;
use stiction_model::topography::{TopographyReport, TopographyRun};

/// The files `--out` writes.
const FILES: &[&str] = &["topography.json", "surface.toml", "topography.svg"];

/// The report with its scene fragment.
#[derive(Debug, Clone, serde::Serialize)]
#[serde(transparent)]
pub struct TopographyResult {
    /// The analysis (the JSON of `--format json`).
    pub report: TopographyReport,
    /// The `[surface]`/`[contact]` fragment.
    #[serde(skip)]
    pub fragment: String,
    /// Printed on standard error (the report's own warnings are in its table).
    #[serde(skip)]
    pub warnings: Vec<Warning>,
}

impl Render for TopographyResult {
    fn table(&self) -> String {
        let r = &self.report;
        let mut s = String::new();
        let g = &r.grid;
        let d = &r.detrending;
        let _ = writeln!(
            s,
            "height map {} x {} points, spacing {} x {} (scan {} x {}); removed: {} (order {}), mean height {}, tilt {:.3} degrees",
            g.nx,
            g.ny,
            si(g.dx, "m", 4),
            si(g.dy, "m", 4),
            si(g.scan_x, "m", 4),
            si(g.scan_y, "m", 4),
            d.method,
            d.order,
            si(d.mean_height, "m", 4),
            d.tilt_degrees
        );
        if let Some(src) = &r.source {
            let mut line = format!("read from {} as {}", src.path, src.format);
            if src.channels.len() > 1 {
                let _ = write!(
                    line,
                    ", channel {:?} of {} ({})",
                    src.title.as_deref().unwrap_or(""),
                    src.channels.len(),
                    src.channels
                        .iter()
                        .enumerate()
                        .map(|(k, c)| format!("{k} {c:?}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                );
            }
            if src.undefined_points > 0 {
                let _ = write!(
                    line,
                    "; {} undefined points filled (harmonic interpolation)",
                    src.undefined_points
                );
            }
            let _ = writeln!(s, "{line}");
        }
        let _ = writeln!(
            s,
            "rms height {} (not sigma_s: the model needs the summits'), m2 = {:.4e}, m4 = {:.4e} 1/m^2, alpha = {:.3}",
            si(r.rms_height, "m", 4),
            r.m2,
            r.m4,
            r.alpha
        );
        let _ = writeln!(
            s,
            "\n{:<10} {:>12} {:>16} {:>12} {:>12}",
            "route", "sigma_s", "density [1/m^2]", "radius", "offset"
        );
        let mut row = |name: &str, gw: &stiction_model::topography::GwParameters| {
            let _ = writeln!(
                s,
                "{:<10} {:>12} {:>16.4e} {:>12} {:>12}",
                name,
                si(gw.sigma_s, "m", 4),
                gw.asperity_density,
                si(gw.radius, "m", 4),
                si(gw.offset, "m", 4)
            );
        };
        row("spectral", &r.spectral.gw);
        if let Some(sm) = &r.summits {
            row("summits", &sm.gw);
        }
        for (title, rows) in [
            (
                "sampling (the map coarsened; GW parameters are not intrinsic to a surface)",
                &r.sampling,
            ),
            ("scan size (tiles of the map)", &r.scan_size),
        ] {
            if rows.is_empty() {
                continue;
            }
            let _ = writeln!(s, "\n{title}:");
            let _ = writeln!(
                s,
                "  {:>6} {:>11} {:>11} {:>12} {:>12} {:>12} {:>12}",
                "factor", "dx", "scan", "sigma_s sp.", "N spectral", "sigma_s sum.", "N summits"
            );
            for row in rows.iter() {
                let (ss, ns) = row.summits.map_or(("-".to_string(), "-".to_string()), |g| {
                    (si(g.sigma_s, "m", 3), format!("{:.3e}", g.asperity_density))
                });
                let _ = writeln!(
                    s,
                    "  {:>6} {:>11} {:>11} {:>12} {:>12.3e} {:>12} {:>12}",
                    row.factor,
                    si(row.dx, "m", 3),
                    si(row.scan_x, "m", 3),
                    si(row.spectral.sigma_s, "m", 3),
                    row.spectral.asperity_density,
                    ss,
                    ns
                );
            }
        }
        let c = &r.cutoff;
        let _ = writeln!(
            s,
            "\nband: {}",
            match (c.wavelength, c.applied) {
                (Some(w), true) => format!(
                    "wavelengths longer than the cutoff {}{} (Gaussian low-pass)",
                    si(w, "m", 4),
                    match (c.contact_radius, c.spot_radius) {
                        (Some(rr), Some(a)) => format!(
                            ", 4 x the contact-spot radius {} of R = {}",
                            si(a, "m", 4),
                            si(rr, "m", 4)
                        ),
                        _ => String::new(),
                    }
                ),
                (Some(w), false) => format!(
                    "the map as sampled (the cutoff {} is at or below the Nyquist wavelength {})",
                    si(w, "m", 4),
                    si(c.nyquist_wavelength, "m", 4)
                ),
                _ => format!(
                    "the map as sampled (no cutoff; Nyquist wavelength {})",
                    si(c.nyquist_wavelength, "m", 4)
                ),
            }
        );
        if r.band.len() > 1 {
            let _ = writeln!(
                s,
                "  {:>11} {:>12} {:>12} {:>12} {:>12} {:>12} {:>12}",
                "cutoff",
                "sigma_s sp.",
                "N spectral",
                "R spectral",
                "sigma_s sum.",
                "N summits",
                "R summits"
            );
            for b in &r.band {
                let (ss, ns, rs) =
                    b.summits
                        .map_or(("-".to_string(), "-".to_string(), "-".to_string()), |g| {
                            (
                                si(g.sigma_s, "m", 3),
                                format!("{:.3e}", g.asperity_density),
                                si(g.radius, "m", 3),
                            )
                        });
                let _ = writeln!(
                    s,
                    "  {:>11} {:>12} {:>12.3e} {:>12} {:>12} {:>12} {:>12}{}",
                    b.cutoff.map_or("as sampled".to_string(), |w| si(w, "m", 3)),
                    si(b.spectral.sigma_s, "m", 3),
                    b.spectral.asperity_density,
                    si(b.spectral.radius, "m", 3),
                    ss,
                    ns,
                    rs,
                    if b.chosen { "  <- this report" } else { "" }
                );
            }
        }
        for w in &r.warnings {
            let _ = writeln!(s, "warning[{}]: {}", w.code, w.message);
        }
        let _ = writeln!(s, "\n{}", self.fragment.trim_end());
        s
    }

    fn csv(&self) -> String {
        let r = &self.report;
        let mut s = String::from("route,sigma_s_m,asperity_density_per_m2,radius_m,offset_m\n");
        let mut row = |name: &str, gw: &stiction_model::topography::GwParameters| {
            let _ = writeln!(
                s,
                "{name},{:e},{:e},{:e},{:e}",
                gw.sigma_s, gw.asperity_density, gw.radius, gw.offset
            );
        };
        row("spectral", &r.spectral.gw);
        if let Some(sm) = &r.summits {
            row("summits", &sm.gw);
        }
        s
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    fn validity(&self) -> Option<&Validity> {
        None
    }
}

/// The height map (a colour picture), the summit heights against the Gaussian the model
/// assumes, and the radially averaged PSD.
fn plot_svg(r: &TopographyReport) -> Result<String, String> {
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (1200, 420)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let panels = root.split_evenly((1, 3));
        let e = |e: &dyn std::fmt::Display| e.to_string();
        // the height map
        let m = &r.plots.height_map;
        let (zmin, zmax) =
            m.z.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
                    (a.min(z), b.max(z))
                });
        let (w, h) = (m.nx as f64 * m.dx * 1e6, m.ny as f64 * m.dy * 1e6);
        let span = (zmax - zmin).max(f64::MIN_POSITIVE);
        let colour = |v: f64| {
            let v = v.clamp(0.0, 1.0);
            let g = (255.0 * v) as u8;
            RGBColor(g, g, (64.0 + 191.0 * v) as u8)
        };
        // the map at its true aspect (1 um is as long across as up), a colour bar beside it
        let (map_area, bar_area) = panels[0].split_horizontally(310);
        let map_area = map_area
            .titled("height map (detrended)", ("sans-serif", 16))
            .map_err(|x| e(&x))?;
        let (aw, ah) = map_area.dim_in_pixel();
        let (label_x, label_y, pad) = (35u32, 55u32, 10u32);
        let room_w = f64::from(aw.saturating_sub(label_y + 2 * pad).max(10));
        let room_h = f64::from(ah.saturating_sub(label_x + 2 * pad).max(10));
        let px = (room_w / w.max(f64::MIN_POSITIVE)).min(room_h / h.max(f64::MIN_POSITIVE));
        let (extra_w, extra_h) = (
            ((room_w - px * w) / 2.0).max(0.0) as u32,
            ((room_h - px * h) / 2.0).max(0.0) as u32,
        );
        let mut c = ChartBuilder::on(&map_area)
            .margin_left(pad + extra_w)
            .margin_right(pad + extra_w)
            .margin_top(pad + extra_h)
            .margin_bottom(pad + extra_h)
            .x_label_area_size(label_x)
            .y_label_area_size(label_y)
            .build_cartesian_2d(0.0..w, 0.0..h)
            .map_err(|x| e(&x))?;
        c.configure_mesh()
            .disable_mesh()
            .x_desc("x [um]")
            .y_desc("y [um]")
            .x_labels(4)
            .y_labels(((px * h / 40.0) as usize).clamp(2, 8))
            .label_style(("sans-serif", 12))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(|x| e(&x))?;
        c.draw_series((0..m.ny).flat_map(|j| {
            (0..m.nx).map(move |i| {
                let v = (m.z[j * m.nx + i] - zmin) / span;
                Rectangle::new(
                    [
                        (i as f64 * m.dx * 1e6, j as f64 * m.dy * 1e6),
                        ((i + 1) as f64 * m.dx * 1e6, (j + 1) as f64 * m.dy * 1e6),
                    ],
                    colour(v).filled(),
                )
            })
        }))
        .map_err(|x| e(&x))?;
        // the colour bar: height in nm
        let (z0, z1) = (zmin * 1e9, zmin * 1e9 + span * 1e9);
        // as tall as the map (at least 120 px), level with it
        let title = 420u32.saturating_sub(ah);
        let (top, bottom) = (title + pad + extra_h, pad + extra_h + label_x);
        let spare = 420u32.saturating_sub(top + bottom);
        let grow = 120u32.saturating_sub(spare) / 2;
        let mut bar = ChartBuilder::on(&bar_area)
            .margin_top(top.saturating_sub(grow))
            .margin_bottom(bottom.saturating_sub(grow))
            .margin_right(8)
            .x_label_area_size(0)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..1.0, z0..z1)
            .map_err(|x| e(&x))?;
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc("height [nm]")
            .y_labels(6)
            .label_style(("sans-serif", 12))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(|x| e(&x))?;
        let steps = 64;
        bar.draw_series((0..steps).map(|k| {
            let (a, b) = (
                z0 + (z1 - z0) * k as f64 / steps as f64,
                z0 + (z1 - z0) * (k + 1) as f64 / steps as f64,
            );
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                colour((k as f64 + 0.5) / steps as f64).filled(),
            )
        }))
        .map_err(|x| e(&x))?;
        // summit heights against the Gaussian
        let hist = &r.plots.summit_heights;
        let xs: Vec<f64> = hist.centres.iter().map(|x| x * 1e9).collect();
        let ymax = hist
            .density
            .iter()
            .chain(&hist.gaussian)
            .fold(0.0f64, |a, &b| a.max(b))
            * 1e-9
            * 1.1;
        let (x0, x1) = (
            xs.first().copied().unwrap_or(-1.0),
            xs.last().copied().unwrap_or(1.0),
        );
        let mut c = ChartBuilder::on(&panels[1])
            .caption(
                "summit heights vs the Gaussian of the model",
                ("sans-serif", 16),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(55)
            .build_cartesian_2d(x0..x1.max(x0 + 1e-9), 0.0..ymax.max(1e-12))
            .map_err(|x| e(&x))?;
        c.configure_mesh()
            .disable_mesh()
            .x_desc("height above the mean plane [nm]")
            .y_desc("density [1/nm]")
            .draw()
            .map_err(|x| e(&x))?;
        let half = 0.5 * hist.width * 1e9;
        c.draw_series(xs.iter().zip(&hist.density).map(|(&x, &d)| {
            Rectangle::new(
                [(x - half, 0.0), (x + half, d * 1e-9)],
                RGBColor(120, 150, 220).filled(),
            )
        }))
        .map_err(|x| e(&x))?
        .label("summits")
        .legend(|(x, y)| {
            Rectangle::new(
                [(x, y - 4), (x + 12, y + 4)],
                RGBColor(120, 150, 220).filled(),
            )
        });
        c.draw_series(LineSeries::new(
            xs.iter().zip(&hist.gaussian).map(|(&x, &g)| (x, g * 1e-9)),
            BLACK.stroke_width(2),
        ))
        .map_err(|x| e(&x))?
        .label("N(offset, sigma_s)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 12, y)], BLACK.stroke_width(2)));
        c.configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE)
            .draw()
            .map_err(|x| e(&x))?;
        // the PSD
        let pts: Vec<(f64, f64)> = r
            .plots
            .psd
            .iter()
            .filter(|p| p.q > 0.0 && p.c > 0.0)
            .map(|p| (p.q.log10(), p.c.log10()))
            .collect();
        let (qa, qb, ca, cb) = pts.iter().fold(
            (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ),
            |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
        );
        if pts.len() >= 2 {
            let mut c = ChartBuilder::on(&panels[2])
                .caption("PSD, radially averaged", ("sans-serif", 16))
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(55)
                .build_cartesian_2d(qa..qb.max(qa + 1e-6), ca..cb.max(ca + 1e-6))
                .map_err(|x| e(&x))?;
            c.configure_mesh()
                .disable_mesh()
                .x_desc("log10 q [rad/m]")
                .y_desc("log10 C(q) [m^4]")
                .draw()
                .map_err(|x| e(&x))?;
            c.draw_series(LineSeries::new(pts, BLUE.stroke_width(2)))
                .map_err(|x| e(&x))?;
        }
        root.present().map_err(|x| e(&x))?;
    }
    Ok(crate::plot::portable(&buf))
}

impl TopographyResult {
    /// The result of a run.
    pub fn new(run: TopographyRun) -> Self {
        Self {
            report: run.report,
            fragment: run.fragment,
            warnings: run.warnings,
        }
    }
}

impl Plot for TopographyResult {
    fn svg(&self) -> Result<String, ReportError> {
        plot_svg(&self.report).map_err(|m| ReportError::plot("topography.svg".as_ref(), m))
    }
}

impl Report for TopographyResult {
    const FILES: &'static [&'static str] = FILES;

    fn files(&self, dir: &Path) -> Result<OutputSet, ReportError> {
        let mut set = OutputSet::new(dir, FILES);
        set.add("topography.json", render::json(&self.report));
        set.add("surface.toml", self.fragment.as_bytes());
        let svg = plot_svg(&self.report)
            .map_err(|message| ReportError::plot(&dir.join("topography.svg"), message))?;
        set.add("topography.svg", svg);
        Ok(set)
    }
}
