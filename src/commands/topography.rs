//! `stiction topography`: a measured height map (AFM, profilometer) to the
//! Greenwood-Williamson parameters of a scene, by the spectral moments and by the summits on
//! the grid (the model library's `topography`; `docs/topography.md`).

use super::{finish, preflight, Outputs};
use crate::error::Error;
use crate::output::OutputSet;
use crate::render::{self, Format, Render, Validity, Warning};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::PathBuf;
use stiction_model::guards::si;
use stiction_model::topography::{Format as MapFormat, TopographyReport, TopographyRequest};

/// The files `--out` writes.
pub const FILES: &[&str] = &["topography.json", "surface.toml", "topography.svg"];

/// The file formats as options.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    /// Plain text matrix of heights.
    Text,
    /// x, y, z columns.
    Xyz,
    /// NumPy .npy.
    Npy,
    /// Gwyddion Simple Field .gsf.
    Gsf,
    /// Gwyddion .gwy.
    Gwy,
    /// ISO 25178-72 .x3p.
    X3p,
    /// Bruker/Veeco Nanoscope (.spm, .di, .001).
    Nanoscope,
    /// Wyko/Bruker Vision .opd.
    Opd,
    /// Zygo MetroPro .dat.
    Metropro,
    /// Digital Surf .sur (MountainsMap).
    Sur,
    /// Sensofar .plu and .plux.
    Plu,
    /// Keyence .vk4.
    Vk4,
    /// ISO 25178-71 .sdf.
    Sdf,
}

/// What to do with the file's undefined points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum UndefinedArg {
    /// Refuse the file, naming how many points are undefined.
    Refuse,
    /// Fill them by harmonic (Laplace) interpolation from their defined neighbours.
    Fill,
}

/// The route a scene fragment takes its numbers from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum RouteArg {
    /// The summits found on the grid (higher than their 8 neighbours).
    Summits,
    /// McCool's formulas on the spectral moments.
    Spectral,
}

/// Greenwood-Williamson parameters (sigma_s, asperity density, radius) from a measured
/// height map, two ways, with a `[surface]` scene fragment.
#[derive(Debug, Clone, clap::Args)]
pub struct TopographyCommand {
    /// The height map: a text matrix, x/y/z columns, .npy, Gwyddion .gwy or .gsf,
    /// ISO 25178-72 .x3p, or an instrument's file (Nanoscope, Wyko .opd, Zygo .dat,
    /// Digital Surf .sur, Sensofar .plu/.plux, Keyence .vk4, ISO 25178-71 .sdf); the format
    /// from the first bytes, else the extension.
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// Read the file as this format.
    #[arg(long = "file-format", value_enum)]
    pub file_format: Option<FormatArg>,
    /// The file's undefined points (instrument markers, NaN): refused (default), or filled
    /// by harmonic interpolation from their defined neighbours (counted in
    /// source.undefined_points either way).
    #[arg(long, value_enum, value_name = "refuse|fill")]
    pub undefined: Option<UndefinedArg>,
    /// The channel to read, by name or 0-based index (the report's source.channels lists a
    /// file's channels); default the first height channel.
    #[arg(long, value_name = "NAME|INDEX")]
    pub channel: Option<String>,
    /// Short-wavelength cutoff (m): the map is low-pass filtered at this wavelength
    /// (Gaussian, ISO 16610-61; 50% transmission at it) before the analysis, so the GW
    /// parameters describe the longer wavelengths; 0 or a cutoff at or below the Nyquist
    /// wavelength 2 dx: the map as sampled (the default without --contact-radius).
    #[arg(long, value_name = "LENGTH", allow_hyphen_values = true)]
    pub cutoff: Option<f64>,
    /// The contact's asperity tip radius R (m), for the default cutoff: 4 sqrt(R sigma_s),
    /// four contact-spot radii (docs/topography.md section 10); --cutoff wins.
    #[arg(long, value_name = "LENGTH", allow_hyphen_values = true)]
    pub contact_radius: Option<f64>,
    /// Grid spacing (m) for a format that lacks one (text, npy); overrides the file's.
    #[arg(long, allow_hyphen_values = true)]
    pub spacing: Option<f64>,
    /// Unit of the heights for a file that does not state it (m, mm, um, nm, pm, A).
    #[arg(long)]
    pub height_unit: Option<String>,
    /// Unit of x and y of an x/y/z file that does not state it.
    #[arg(long)]
    pub xy_unit: Option<String>,
    /// Form removed before the statistics: mean, plane (default) or poly:N (N = 2..6).
    #[arg(long, default_value = "plane")]
    pub detrend: String,
    /// The route of the scene fragment.
    #[arg(long, value_enum, default_value_t = RouteArg::Summits)]
    pub route: RouteArg,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write topography.json, surface.toml (a scene fragment) and topography.svg to this
    /// folder (replaced as a whole; it may hold only those files).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl TopographyCommand {
    /// Reads, analyses, writes.
    pub fn execute(&self) -> Result<String, Error> {
        let request = TopographyRequest {
            file_format: self.file_format.map(|f| {
                match f {
                    FormatArg::Text => MapFormat::Text,
                    FormatArg::Xyz => MapFormat::Xyz,
                    FormatArg::Npy => MapFormat::Npy,
                    FormatArg::Gsf => MapFormat::Gsf,
                    FormatArg::Gwy => MapFormat::Gwy,
                    FormatArg::X3p => MapFormat::X3p,
                    FormatArg::Nanoscope => MapFormat::Nanoscope,
                    FormatArg::Opd => MapFormat::Opd,
                    FormatArg::Metropro => MapFormat::Metropro,
                    FormatArg::Sur => MapFormat::Sur,
                    FormatArg::Plu => MapFormat::Plu,
                    FormatArg::Vk4 => MapFormat::Vk4,
                    FormatArg::Sdf => MapFormat::Sdf,
                }
                .name()
                .to_string()
            }),
            spacing: self.spacing,
            height_unit: self.height_unit.clone(),
            xy_unit: self.xy_unit.clone(),
            detrend: Some(self.detrend.clone()),
            route: Some(
                match self.route {
                    RouteArg::Summits => "summits",
                    RouteArg::Spectral => "spectral",
                }
                .to_string(),
            ),
            undefined: self.undefined.map(|u| {
                match u {
                    UndefinedArg::Refuse => "refuse",
                    UndefinedArg::Fill => "fill",
                }
                .to_string()
            }),
            channel: self.channel.clone(),
            cutoff: self.cutoff,
            contact_radius: self.contact_radius,
        };
        preflight(self.out.as_deref(), FILES, None)?;
        let run = stiction_model::topography::run(&self.file, &request).map_err(option_error)?;
        let result = TopographyResult {
            report: run.report,
            fragment: run.fragment,
            warnings: run.warnings,
        };
        let mut outputs = Outputs::default();
        if let Some(dir) = &self.out {
            let mut set = OutputSet::new(dir, FILES);
            set.add("topography.json", render::json(&result.report));
            set.add("surface.toml", result.fragment.as_bytes());
            let svg = plot_svg(&result.report).map_err(|message| Error::Plot {
                path: dir.join("topography.svg").display().to_string(),
                message,
            })?;
            set.add("topography.svg", svg);
            outputs.folder = Some(set);
        }
        finish(&result, self.format, false, false, outputs)
    }
}

/// A library option error as the command line's option (`detrend` -> `--detrend`).
fn option_error(e: stiction_model::ModelError) -> Error {
    match e {
        stiction_model::ModelError::Option { name, message } => {
            Error::usage(&format!("--{}", name.replace('_', "-")), message)
        }
        e => e.into(),
    }
}

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
pub fn plot_svg(r: &TopographyReport) -> Result<String, String> {
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
        let mut c = ChartBuilder::on(&panels[0])
            .caption("height map (detrended)", ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(45)
            .build_cartesian_2d(0.0..w, 0.0..h)
            .map_err(|x| e(&x))?;
        c.configure_mesh()
            .disable_mesh()
            .x_desc("x [um]")
            .y_desc("y [um]")
            .draw()
            .map_err(|x| e(&x))?;
        let span = (zmax - zmin).max(f64::MIN_POSITIVE);
        c.draw_series((0..m.ny).flat_map(|j| {
            (0..m.nx).map(move |i| {
                let v = (m.z[j * m.nx + i] - zmin) / span;
                let g = (255.0 * v) as u8;
                Rectangle::new(
                    [
                        (i as f64 * m.dx * 1e6, j as f64 * m.dy * 1e6),
                        ((i + 1) as f64 * m.dx * 1e6, (j + 1) as f64 * m.dy * 1e6),
                    ],
                    RGBColor(g, g, (64.0 + 191.0 * v) as u8).filled(),
                )
            })
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
    Ok(buf)
}
