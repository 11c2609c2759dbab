//! `stiction topography`: a measured height map (AFM, profilometer) to the
//! Greenwood-Williamson parameters of a scene, by the spectral moments and by the summits on
//! the grid (the model library's `topography`; `docs/topography.md`).

use super::{finish, preflight, Outputs};
use crate::error::Error;
use crate::render::Format;
use std::path::PathBuf;
use stiction_model::topography::{Format as MapFormat, TopographyRequest};
use stiction_report::topography::TopographyResult;
use stiction_report::Report;

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
        preflight(self.out.as_deref(), TopographyResult::FILES, None)?;
        let run = stiction_model::topography::run(&self.file, &request).map_err(option_error)?;
        let result = TopographyResult::new(run);
        let mut outputs = Outputs::default();
        if let Some(dir) = &self.out {
            outputs.folder = Some(result.files(dir)?);
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
