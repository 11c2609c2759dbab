//! From a measured surface to the model: a height map (AFM, profilometer) read, detrended
//! and reduced to the Greenwood-Williamson parameters a scene needs (sigma_s of the summits,
//! their density, their mean radius), by the spectral moments (McCool 1986) and by the
//! summits found on the grid, side by side (the crate `topography`; `docs/topography.md`).
//!
//! ```
//! use stiction_model::topography::{analyze_map, scene_fragment, AnalysisOptions, Route};
//! use stiction_model::topography::{synthesize, Amplitudes, Normalization, SelfAffinePsd};
//! use stiction_model::topography::SynthesisOptions;
//! // a synthetic self-affine surface: H = 0.8, 5 nm rms, 256 x 256 points of 8 nm
//! let psd = SelfAffinePsd::new(0.8, 2e-6, None, 40e-9, Normalization::RmsHeight(5e-9))?;
//! let grid = SynthesisOptions { nx: 256, ny: 256, dx: 8e-9, dy: 8e-9, seed: 7, amplitudes: Amplitudes::Fixed };
//! let map = synthesize(&psd, &grid)?;
//! let r = analyze_map(&map, &AnalysisOptions::default())?;
//! // McCool's summits (spectral moments) spread less than the heights: sqrt(1 - 0.8968/alpha) < 1
//! assert!(r.spectral.gw.sigma_s < r.rms_height);
//! // the summits found on the grid agree with them within 10% (one realisation of a broad
//! // band: its summits spread nearly as wide as the surface, either side of McCool's value)
//! let found = r.summits.as_ref().unwrap().gw.sigma_s;
//! assert!((found / r.spectral.gw.sigma_s - 1.0).abs() < 0.1);
//! let toml = scene_fragment(&r, Route::Summits)?;
//! assert!(toml.contains("[surface]") && toml.contains("asperity_density"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::error::ModelError;
use crate::guards::{code, Warning as ModelWarning};
pub use ::topography::*;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The code of the note a scene gets when it gives a key its `surface.topography` would
/// set (`surface.sigma_s`, `surface.asperity_density`, `contact.radius`) with another
/// value: the scene's value wins, the note names both.
pub const TOPOGRAPHY_VALUE_OVERRIDDEN: &str = "topography_value_overridden";

/// `fragment` (a [`scene_fragment`]) with every value outside the domain of its scene key
/// commented out, and a warning for each: a fragment is never written with a value the
/// scenes reject (a map nearly flat gives summits of a radius of megametres, for
/// instance), and the warning says which value and why.
///
/// ```
/// use stiction_model::topography::fragment_within_domains;
/// let (text, w) = fragment_within_domains("[surface]\nsigma_s = 5e-9\n[contact]\nradius = 4.8e8 # m\n");
/// assert!(text.contains("sigma_s = 5e-9") && text.contains("# radius = 4.8e8"));
/// assert_eq!(w.len(), 1);
/// assert!(w[0].message.contains("contact.radius"));
/// ```
pub fn fragment_within_domains(fragment: &str) -> (String, Vec<ModelWarning>) {
    let mut section = String::new();
    let mut out = String::with_capacity(fragment.len() + 128);
    let mut warnings = Vec::new();
    for line in fragment.lines() {
        let body = line.split('#').next().unwrap_or("").trim();
        if let Some(name) = body.strip_prefix('[').and_then(|b| b.strip_suffix(']')) {
            section = name.trim().to_owned();
        } else if let Some((k, v)) = body.split_once('=') {
            let full = if section.is_empty() {
                k.trim().to_owned()
            } else {
                format!("{section}.{}", k.trim())
            };
            let value = v.trim().parse::<f64>().ok();
            if let (Some(key), Some(x)) = (crate::keys::key(&full), value) {
                if key.domain.is_numeric() && !key.domain.contains(x) {
                    warnings.push(ModelWarning::note(
                        code::OUTSIDE_SCENE_DOMAIN,
                        format!(
                            "{full} = {} lies outside the scene's domain {}: left out of the fragment (commented), which needs a value of your own there",
                            crate::keys::num(x),
                            key.domain.describe()
                        ),
                    ));
                    out.push_str("# ");
                    out.push_str(line);
                    out.push_str("  # outside the scene's domain: see the warning\n");
                    continue;
                }
            }
        }
        out.push_str(line);
        out.push('\n');
    }
    (out, warnings)
}

/// Reads the height map at `path` and analyses it.
pub fn analyze_file(
    path: &Path,
    read: &ReadOptions,
    options: &AnalysisOptions,
) -> Result<TopographyReport, ModelError> {
    let m = read_path(path, read)?;
    analyze_measurement(&m, options).map_err(|e| {
        ModelError::from(topography::TopographyError::InFile {
            path: path.to_path_buf(),
            source: Box::new(e),
        })
    })
}

/// Analyses a height map held in memory.
pub fn analyze_map(
    map: &HeightMap,
    options: &AnalysisOptions,
) -> Result<TopographyReport, ModelError> {
    Ok(analyze(map, options)?)
}

/// A topography question with its options in words, as every front end takes them (the
/// command line's `--file-format`, `--spacing`, `--height-unit`, `--xy-unit`, `--detrend`,
/// `--route`, `--undefined`, `--channel`, `--cutoff`, `--contact-radius`); None takes the
/// default (the format from the file, plane, summits, undefined points refused, the first
/// height channel, no cutoff unless a contact radius gives one).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TopographyRequest {
    /// One of [`Format::names`]: text, xyz, npy, gsf, gwy, x3p, nanoscope, opd, metropro,
    /// sur, plu, vk4, sdf.
    pub file_format: Option<String>,
    /// Grid spacing (m) for a format that lacks one.
    pub spacing: Option<f64>,
    /// Unit of the heights for a file that does not state it (m, mm, um, nm, pm, A).
    pub height_unit: Option<String>,
    /// Unit of x and y of an x/y/z file that does not state it.
    pub xy_unit: Option<String>,
    /// mean | plane | poly:N (N = 2..6).
    pub detrend: Option<String>,
    /// summits | spectral: the route of the scene fragment.
    pub route: Option<String>,
    /// refuse | fill: the file's undefined points (instrument markers, NaN) refused (the
    /// default) or filled by harmonic interpolation (the report's `source.undefined_points`
    /// counts them either way).
    pub undefined: Option<String>,
    /// The channel to read, by name or 0-based index (the report's `source.channels` lists
    /// them); default the first height channel.
    pub channel: Option<String>,
    /// The short-wavelength cutoff (m): the map low-pass filtered at it before the analysis
    /// (0: none, the map as sampled, also with a contact radius).
    pub cutoff: Option<f64>,
    /// The contact (asperity tip) radius R (m): without a cutoff, the cutoff is
    /// [`SPOT_CUTOFF_FACTOR`] sqrt(R sigma_s), four contact-spot radii.
    pub contact_radius: Option<f64>,
}

/// What a topography question gives: the report (the command's JSON), the `[surface]`
/// scene fragment (values outside a key's domain commented out, see
/// [`fragment_within_domains`]), its warnings, and the height map as read (SI).
#[derive(Debug, Clone)]
pub struct TopographyRun {
    /// The analysis.
    pub report: TopographyReport,
    /// The scene fragment (TOML text).
    pub fragment: String,
    /// The fragment's warnings.
    pub warnings: Vec<ModelWarning>,
    /// The height map as read, before detrending (m).
    pub map: HeightMap,
}

/// The detrending a word names: mean, plane or poly:N with N in 2..=[`Detrend::MAX_ORDER`]
/// (errors name the argument `detrend`).
pub fn detrend_of(word: &str) -> Result<Detrend, ModelError> {
    match word.trim() {
        "mean" => Ok(Detrend::Mean),
        "plane" => Ok(Detrend::Plane),
        t => match t
            .strip_prefix("poly:")
            .and_then(|n| n.parse::<usize>().ok())
        {
            Some(n) if (2..=Detrend::MAX_ORDER).contains(&n) => Ok(Detrend::Polynomial(n)),
            _ => Err(ModelError::Option {
                name: "detrend".into(),
                message: format!(
                    "`{t}`: must be mean, plane or poly:N with N in 2..={}",
                    Detrend::MAX_ORDER
                ),
            }),
        },
    }
}

/// What a request asks of the reader and the analysis, checked (errors name the option).
fn prepare(
    request: &TopographyRequest,
) -> Result<(ReadOptions, AnalysisOptions, Route), ModelError> {
    let bad = |name: &str, message: String| ModelError::Option {
        name: name.into(),
        message,
    };
    let format = match request.file_format.as_deref() {
        None => None,
        Some(w) => Some(
            Format::ALL
                .into_iter()
                .find(|f| f.name() == w)
                .ok_or_else(|| {
                    let names: Vec<&str> = Format::ALL.iter().map(|f| f.name()).collect();
                    bad(
                        "file_format",
                        format!("`{w}`: must be one of {}", names.join(", ")),
                    )
                })?,
        ),
    };
    let length = |name: &str, v: Option<f64>, zero: bool| match v {
        Some(s) if !(s.is_finite() && (s > 0.0 || (zero && s == 0.0))) => Err(bad(
            name,
            format!(
                "{s:e}: must be a finite length {} (m)",
                if zero { ">= 0" } else { "> 0" }
            ),
        )),
        v => Ok(v),
    };
    length("spacing", request.spacing, false)?;
    let cutoff = length("cutoff", request.cutoff, true)?;
    let contact_radius = length("contact_radius", request.contact_radius, false)?;
    let unit = |name: &str, t: &Option<String>| {
        t.as_deref()
            .map(|t| LengthUnit::parse(t).map_err(|e| bad(name, e.to_string())))
            .transpose()
    };
    let undefined = match request.undefined.as_deref() {
        None => Undefined::Refuse,
        Some(w) => w
            .parse::<Undefined>()
            .map_err(|_| bad("undefined", format!("`{w}`: must be refuse or fill")))?,
    };
    let channel = match request.channel.as_deref() {
        Some(c) if c.trim().is_empty() => {
            return Err(bad(
                "channel",
                "an empty name: give a channel's name or its 0-based index".to_string(),
            ))
        }
        c => c.map(str::to_string),
    };
    let read = ReadOptions {
        format,
        spacing: request.spacing,
        height_unit: unit("height_unit", &request.height_unit)?,
        xy_unit: unit("xy_unit", &request.xy_unit)?,
        channel,
        undefined,
        ..ReadOptions::default()
    };
    let detrend = match request.detrend.as_deref() {
        None => Detrend::Plane,
        Some(w) => detrend_of(w)?,
    };
    let route = match request.route.as_deref() {
        None | Some("summits") => Route::Summits,
        Some("spectral") => Route::Spectral,
        Some(w) => return Err(bad("route", format!("`{w}`: must be summits or spectral"))),
    };
    let cutoff = match (cutoff, contact_radius) {
        (Some(0.0), _) => Cutoff::None,
        (Some(c), _) => Cutoff::Wavelength(c),
        (None, Some(r)) => Cutoff::ContactRadius(r),
        (None, None) => Cutoff::None,
    };
    let options = AnalysisOptions {
        detrend,
        cutoff,
        ..AnalysisOptions::default()
    };
    Ok((read, options, route))
}

/// The analysis of the measurement read from `path`; a cutoff the map cannot take is an
/// error of the option that set it (`cutoff`, or `contact_radius` for one derived from it).
fn analyze_read(
    path: &Path,
    m: &Measurement,
    options: &AnalysisOptions,
) -> Result<TopographyReport, ModelError> {
    analyze_measurement(m, options).map_err(|e| match e {
        TopographyError::Parameter {
            name: "cutoff" | "contact radius",
            value,
            message,
        } => ModelError::Option {
            name: match options.cutoff {
                Cutoff::ContactRadius(_) => "contact_radius",
                _ => "cutoff",
            }
            .into(),
            message: format!("{}: cutoff {value}: {message}", path.display()),
        },
        e => ModelError::from(TopographyError::InFile {
            path: path.to_path_buf(),
            source: Box::new(e),
        }),
    })
}

/// The route a report's numbers are taken from: `route`, except that a map without
/// summits on its grid gives the spectral route's.
fn route_taken(report: &TopographyReport, route: Route) -> Route {
    if route == Route::Summits && report.summits.is_none() {
        Route::Spectral
    } else {
        route
    }
}

/// Reads and analyses the height map at `path` as `request` asks, and writes its scene
/// fragment: what `stiction topography FILE` computes. Option errors name the option
/// (`file_format`, `spacing`, `height_unit`, `xy_unit`, `detrend`, `route`, `undefined`,
/// `channel`, `cutoff`, `contact_radius`).
pub fn run(path: &Path, request: &TopographyRequest) -> Result<TopographyRun, ModelError> {
    let (read, options, route) = prepare(request)?;
    let m = read_path(path, &read)?;
    let report = analyze_read(path, &m, &options)?;
    let fragment = scene_fragment(&report, route_taken(&report, route))?;
    let (fragment, warnings) = fragment_within_domains(&fragment);
    Ok(TopographyRun {
        report,
        fragment,
        warnings,
        map: m.map,
    })
}

/// The GW parameters a scene takes from its `surface.topography` file.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSurface {
    /// The file, as the scene resolved it.
    pub path: PathBuf,
    /// The route the numbers come from (summits, or spectral for a map without summits).
    pub route: Route,
    /// sigma_s, asperity_density, radius (and the summits' offset), SI.
    pub gw: GwParameters,
    /// The band: the cutoff chosen and whether it filtered the map.
    pub cutoff: CutoffSummary,
}

/// What a cached analysis is of: the file (its size and time of change) and the request.
#[derive(Debug, Clone, PartialEq)]
struct SurfaceKey {
    path: PathBuf,
    len: u64,
    modified: Option<std::time::SystemTime>,
    request: TopographyRequest,
}

/// The most analyses [`scene_surface`] keeps.
const SURFACE_CACHE: usize = 32;

static SURFACES: Mutex<Vec<(SurfaceKey, Arc<SceneSurface>)>> = Mutex::new(Vec::new());

/// The GW parameters of the height map at `path` analysed as `request` asks, for a scene
/// (`surface.topography`): the route's sigma_s, density and radius and the band. The
/// analysis is kept for the process (up to 32 files and requests, keyed by the file's
/// size and time of change as well as its path), so that a design sweep, whose every
/// point validates the scene again, reads and analyses the file once per band.
pub fn scene_surface(
    path: &Path,
    request: &TopographyRequest,
) -> Result<Arc<SceneSurface>, ModelError> {
    let meta = std::fs::metadata(path).ok();
    let key = SurfaceKey {
        // the file itself, whatever the working directory of a relative path
        path: std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()),
        len: meta.as_ref().map_or(0, std::fs::Metadata::len),
        modified: meta.as_ref().and_then(|m| m.modified().ok()),
        request: request.clone(),
    };
    let cached = |k: &SurfaceKey| {
        SURFACES
            .lock()
            .ok()?
            .iter()
            .find(|(x, _)| x == k)
            .map(|(_, s)| Arc::clone(s))
    };
    if let Some(s) = cached(&key) {
        return Ok(s);
    }
    let (read, options, route) = prepare(request)?;
    // the scene needs the parameters only: no tables, no plot data
    let options = AnalysisOptions {
        coarsen: Vec::new(),
        scan_divisors: Vec::new(),
        band: Vec::new(),
        psd_bins: 0,
        plot_side: 8,
        histogram_bins: 4,
        ..options
    };
    let m = read_path(path, &read)?;
    let report = analyze_read(path, &m, &options)?;
    let route = route_taken(&report, route);
    let gw = match (route, &report.summits) {
        (Route::Summits, Some(s)) => s.gw,
        _ => report.spectral.gw,
    };
    let surface = Arc::new(SceneSurface {
        path: path.to_path_buf(),
        route,
        gw,
        cutoff: report.cutoff.clone(),
    });
    if let Ok(mut c) = SURFACES.lock() {
        if c.len() >= SURFACE_CACHE {
            c.remove(0);
        }
        c.push((key, Arc::clone(&surface)));
    }
    Ok(surface)
}

/// A reader's or the analysis' message with the command line's options named as the
/// scene keys that set them (`--undefined fill` -> `surface.topography_undefined =
/// "fill"`), for errors of a scene's `surface.topography`.
pub fn as_scene_keys(message: &str) -> String {
    message
        .replace(
            "--undefined fill",
            "surface.topography_undefined = \"fill\"",
        )
        .replace("--undefined", "surface.topography_undefined")
        .replace("--channel", "surface.topography_channel")
        .replace("--spacing", "surface.topography_spacing")
        .replace("--height-unit", "surface.topography_height_unit")
        .replace("--file-format", "surface.topography_file_format")
        .replace("--cutoff", "surface.topography_cutoff")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file_with_a_hole() -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("stiction-model-topography-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("hole.txt");
        let rows: Vec<String> = (0..12)
            .map(|j| {
                (0..12)
                    .map(|i| {
                        if (i, j) == (5, 6) {
                            "NaN".to_string()
                        } else {
                            (((i * 7 + j * 13) % 5) as f64 * 0.7).to_string()
                        }
                    })
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect();
        std::fs::write(
            &p,
            format!(
                "# spacing = 10 nm\n# height_unit = nm\n{}\n",
                rows.join("\n")
            ),
        )
        .unwrap();
        p
    }

    /// `undefined` and `channel` reach the reader; bad words are refused naming the option.
    #[test]
    fn undefined_points_and_channels_are_options_named_in_their_errors() {
        let p = file_with_a_hole();
        let option = |r: TopographyRequest| match run(&p, &r) {
            Err(ModelError::Option { name, message }) => (name, message),
            other => panic!("{other:?}"),
        };
        let (name, message) = option(TopographyRequest {
            undefined: Some("maybe".into()),
            ..TopographyRequest::default()
        });
        assert_eq!(name, "undefined");
        assert!(
            message.contains("`maybe`") && message.contains("refuse or fill"),
            "{message}"
        );
        let (name, _) = option(TopographyRequest {
            channel: Some(" ".into()),
            ..TopographyRequest::default()
        });
        assert_eq!(name, "channel");
        let e = run(&p, &TopographyRequest::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("1 of 144 heights are undefined") && e.contains("--undefined fill"),
            "{e}"
        );
        let filled = run(
            &p,
            &TopographyRequest {
                undefined: Some("fill".into()),
                channel: Some("0".into()),
                ..TopographyRequest::default()
            },
        )
        .unwrap();
        let source = filled.report.source.as_ref().unwrap();
        assert_eq!((source.undefined_points, source.channels.len()), (1, 1));
        let e = run(
            &p,
            &TopographyRequest {
                undefined: Some("fill".into()),
                channel: Some("phase".into()),
                ..TopographyRequest::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("channel") && e.contains("\"phase\""), "{e}");
    }
}
