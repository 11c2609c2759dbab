//! The whole analysis of a height map: both routes, the sampling and scan-size tables,
//! the Gaussian checks, plot data and the scene fragment.

use std::fmt::Write as _;

use serde::Serialize;

use crate::detrend::{detrend, Detrend, DetrendSummary};
use crate::error::{Result, TopographyError};
use crate::filter::{filters, lowpass, nyquist_wavelength, FILTER_METHOD};
use crate::gw::{mccool, GwParameters, MCCOOL_SIGMA_CONSTANT};
use crate::io::{Measurement, Source};
use crate::map::HeightMap;
use crate::moments::{finite_difference_moments, radial_psd, spectral_moments, Moments, PsdPoint};
use crate::stats::{histogram, shape, Histogram, Shape, EXCESS_KURTOSIS_LIMIT, SKEWNESS_LIMIT};
use crate::summits::{find_summits, summit_statistics, SummitStatistics};

/// What the analysis does besides the two routes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AnalysisOptions {
    /// Form removed first (default: the mean plane).
    pub detrend: Detrend,
    /// Coarsening factors of the sampling table (default 2, 4, 8; block averaging).
    pub coarsen: Vec<usize>,
    /// Scan-size divisors of the scan table (default 2, 4: the map cut into 2 x 2 and 4 x 4
    /// tiles, each analysed alone, the parameters averaged over the tiles).
    pub scan_divisors: Vec<usize>,
    /// Longest side of the height-map picture (default 256).
    pub plot_side: usize,
    /// Bins of the height histograms (default 40).
    pub histogram_bins: usize,
    /// Logarithmic bins of the radially averaged PSD (default 40; 0 skips the PSD and its FFT).
    pub psd_bins: usize,
    /// The short-wavelength cutoff: the map is low-pass filtered at it ([`crate::lowpass`])
    /// before everything else, so that the GW parameters describe the wavelengths longer
    /// than it (default: none, the map as sampled).
    pub cutoff: Cutoff,
    /// The band table: both routes repeated at these cutoffs, in multiples of the Nyquist
    /// wavelength 2 max(dx, dy) (default 2, 4, 8, 16, 32; cutoffs longer than a quarter of
    /// the shorter scan side are left out; empty: the table holds the map as sampled and
    /// the chosen cutoff only).
    pub band: Vec<f64>,
}

/// The short-wavelength cutoff of an analysis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind", content = "value")]
pub enum Cutoff {
    /// No filter: the map as sampled (its shortest wavelength is the Nyquist 2 dx).
    #[default]
    None,
    /// A wavelength (m), finite and > 0; at or below the Nyquist wavelength it leaves the
    /// map as sampled.
    Wavelength(f64),
    /// From the contact's own scale: the cutoff is [`SPOT_CUTOFF_FACTOR`] times the Hertz
    /// contact-spot radius a = sqrt(R sigma_s) of an asperity of this tip radius R (m)
    /// pressed sigma_s deep (sigma_s of the summits of the map as sampled; the spectral
    /// route's if the grid has none).
    ContactRadius(f64),
}

/// The cutoff wavelength in contact-spot radii (`Cutoff::ContactRadius`): 4 a. A sinusoid
/// of wavelength lambda has crests lambda/2 wide; a spot of diameter 2a fits on one crest
/// when lambda >= 4a. Shorter wavelengths put several of their crests inside one spot: they
/// are roughness of the asperity that the spot flattens or spans, not asperities of their
/// own (docs/topography.md section 10).
pub const SPOT_CUTOFF_FACTOR: f64 = 4.0;

impl Default for AnalysisOptions {
    fn default() -> Self {
        AnalysisOptions {
            detrend: Detrend::Plane,
            coarsen: vec![2, 4, 8],
            scan_divisors: vec![2, 4],
            plot_side: 256,
            histogram_bins: 40,
            psd_bins: 40,
            cutoff: Cutoff::None,
            band: vec![2.0, 4.0, 8.0, 16.0, 32.0],
        }
    }
}

/// The grid analysed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Grid {
    /// Points along x.
    pub nx: usize,
    /// Points along y.
    pub ny: usize,
    /// Sampling interval along x (m).
    pub dx: f64,
    /// Sampling interval along y (m).
    pub dy: f64,
    /// Scan size along x, nx dx (m).
    pub scan_x: f64,
    /// Scan size along y, ny dy (m).
    pub scan_y: f64,
}

impl Grid {
    fn of(m: &HeightMap) -> Self {
        Grid {
            nx: m.nx(),
            ny: m.ny(),
            dx: m.dx(),
            dy: m.dy(),
            scan_x: m.scan_x(),
            scan_y: m.scan_y(),
        }
    }
}

/// The spectral route's result (JSON object `spectral`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SpectralRoute {
    /// sigma_s, asperity_density, radius, offset (SI).
    #[serde(flatten)]
    pub gw: GwParameters,
    /// The method, stated.
    pub method: &'static str,
}

/// The summit route's result (JSON object `summits`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SummitRoute {
    /// sigma_s, asperity_density, radius, offset (SI).
    #[serde(flatten)]
    pub gw: GwParameters,
    /// Number of summits found.
    pub count: usize,
    /// Mean summit curvature (1/m).
    pub mean_curvature: f64,
    /// Median of the per-summit radii (m), for comparison with `radius`.
    pub median_radius: f64,
    /// Skewness of the summit heights (0 for a Gaussian).
    pub skewness: f64,
    /// Kurtosis of the summit heights (3 for a Gaussian).
    pub kurtosis: f64,
    /// Interior points tied with a neighbour (quantised heights).
    pub ties: usize,
    /// The method, stated.
    pub method: &'static str,
}

impl SummitRoute {
    fn from(s: SummitStatistics) -> Self {
        SummitRoute {
            gw: s.gw,
            count: s.count,
            mean_curvature: s.mean_curvature,
            median_radius: s.median_radius,
            skewness: s.skewness,
            kurtosis: s.kurtosis,
            ties: s.ties,
            method: SUMMIT_METHOD,
        }
    }
}

const SPECTRAL_METHOD: &str =
    "McCool (1986) from the profile moments m0, m2, m4 of the equivalent isotropic \
surface (finite differences on the grid, averaged over directions): density m4/(6 pi sqrt(3) m2), \
radius 0.375 sqrt(pi/m4), sigma_s sqrt(1 - 0.8968/alpha) sqrt(m0), offset 4 sqrt(m0/(pi alpha))";
const SUMMIT_METHOD: &str = "summits = interior grid points higher than their 8 neighbours (ties broken by raster \
order); sigma_s = std of their heights, offset = their mean height, density = count / interior area, radius = \
1 / mean of -(z_xx + z_yy)/2 by three-point differences";

/// One row of the sampling or scan-size table: both routes at another sampling interval
/// or scan size.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScaleRow {
    /// Coarsening factor (sampling table) or scan divisor (scan table); 1 for the map itself.
    pub factor: usize,
    /// Sampling interval along x (m).
    pub dx: f64,
    /// Sampling interval along y (m).
    pub dy: f64,
    /// Scan size along x (m).
    pub scan_x: f64,
    /// Scan size along y (m).
    pub scan_y: f64,
    /// Tiles averaged (1 in the sampling table).
    pub tiles: usize,
    /// Rms height (m).
    pub rms_height: f64,
    /// m2 (dimensionless).
    pub m2: f64,
    /// m4 (1/m^2).
    pub m4: f64,
    /// Nayak's alpha.
    pub alpha: f64,
    /// The spectral route.
    pub spectral: GwParameters,
    /// The summit route (`None` if fewer than 2 summits).
    pub summits: Option<GwParameters>,
    /// Summits found (summed over tiles).
    pub summit_count: usize,
}

/// The short-wavelength cutoff of a report (JSON object `cutoff`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CutoffSummary {
    /// The cutoff wavelength chosen (m), given or from the contact radius; `null`: none.
    pub wavelength: Option<f64>,
    /// Whether the map was filtered: false without a cutoff, or with one at or below the
    /// Nyquist wavelength in both directions (the map as sampled).
    pub applied: bool,
    /// Where the cutoff came from: `none`, `given` or `contact_radius`.
    pub from: &'static str,
    /// The contact (asperity tip) radius R the cutoff was derived from (m).
    pub contact_radius: Option<f64>,
    /// The contact-spot radius a = sqrt(R sigma_s) (m); the cutoff is 4 a.
    pub spot_radius: Option<f64>,
    /// The Nyquist wavelength 2 max(dx, dy) (m): the shortest wavelength of the map.
    pub nyquist_wavelength: f64,
    /// The filter, stated.
    pub filter: &'static str,
}

/// One row of the band table: both routes with the map low-pass filtered at `cutoff`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BandRow {
    /// The cutoff wavelength (m); `null`: the map as sampled.
    pub cutoff: Option<f64>,
    /// The cutoff in Nyquist wavelengths 2 max(dx, dy) (1 for the map as sampled).
    pub nyquist_multiple: f64,
    /// Whether this is the band of the report's parameters.
    pub chosen: bool,
    /// Rms height (m).
    pub rms_height: f64,
    /// m2 (dimensionless).
    pub m2: f64,
    /// m4 (1/m^2).
    pub m4: f64,
    /// Nayak's alpha.
    pub alpha: f64,
    /// The spectral route.
    pub spectral: GwParameters,
    /// The summit route (`None` if fewer than 2 summits).
    pub summits: Option<GwParameters>,
    /// Summits found.
    pub summit_count: usize,
}

/// A warning with a stable code (for scripts) and a message (for people).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Warning {
    /// Stable identifier: `non_gaussian_heights`, `non_gaussian_summits`, `anisotropic`,
    /// `few_summits`, `no_summits`, `narrow_band`, `alpha_below_mccool`, `routes_disagree`,
    /// `sampling_dependent`, `scan_size_dependent`, `quantized_heights`, `large_tilt`.
    pub code: &'static str,
    /// What it means for the GW parameters.
    pub message: String,
}

/// A picture-sized height map (m).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PlotMap {
    /// Points along x.
    pub nx: usize,
    /// Points along y.
    pub ny: usize,
    /// Spacing along x (m).
    pub dx: f64,
    /// Spacing along y (m).
    pub dy: f64,
    /// Detrended heights, row-major (m).
    pub z: Vec<f64>,
}

/// Data for the plots the CLI draws.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Plots {
    /// The detrended map, block-averaged to at most `plot_side` points a side.
    pub height_map: PlotMap,
    /// Summit heights against the Gaussian N(offset, sigma_s) the model assumes.
    pub summit_heights: Histogram,
    /// All heights against N(0, rms height).
    pub heights: Histogram,
    /// Radially averaged PSD C(q) (Hann-windowed periodogram).
    pub psd: Vec<PsdPoint>,
}

/// The full analysis. The top-level keys `rms_height`, `m0`, `m2`, `m4`, `alpha` and the
/// objects `spectral` and `summits` (each with `sigma_s`, `asperity_density`, `radius`,
/// `offset`) are a public contract.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TopographyReport {
    /// Rms height of the detrended map, sqrt(m0) (m). Not sigma_s.
    pub rms_height: f64,
    /// Variance of heights (m^2).
    pub m0: f64,
    /// McCool's m2: direction-averaged mean square profile slope.
    pub m2: f64,
    /// McCool's m4: direction-averaged mean square profile curvature (1/m^2).
    pub m4: f64,
    /// Nayak's bandwidth parameter m0 m4 / m2^2.
    pub alpha: f64,
    /// The spectral route.
    pub spectral: SpectralRoute,
    /// The summit route (`null` if the map has fewer than 2 summits).
    pub summits: Option<SummitRoute>,
    /// Where the map came from, if read from a file.
    pub source: Option<Source>,
    /// The grid.
    pub grid: Grid,
    /// What was removed before the statistics.
    pub detrending: DetrendSummary,
    /// All moments, with their method and the slope anisotropy.
    pub moments: Moments,
    /// The same moments from the discrete Fourier spectrum of the detrended map taken as
    /// periodic (`spectral_moments`): exact for a periodic (synthetic) map, where they
    /// exceed the finite-difference moments by the difference operators' loss near the
    /// Nyquist wavevector; biased upwards on a measured map by the jump between opposite
    /// edges. A diagnostic: the routes use `moments`.
    pub moments_fourier: Moments,
    /// Slope anisotropy (1 = isotropic).
    pub slope_anisotropy: f64,
    /// Shape of the height distribution.
    pub heights: Shape,
    /// Both routes on the map coarsened by block averaging (row 1 is the map).
    pub sampling: Vec<ScaleRow>,
    /// Both routes on smaller scans (tiles of the map), averaged over the tiles.
    pub scan_size: Vec<ScaleRow>,
    /// The short-wavelength cutoff applied before the analysis (the band of wavelengths the
    /// parameters describe).
    pub cutoff: CutoffSummary,
    /// Both routes at a few cutoffs, from the map as sampled to long wavelengths: how the
    /// GW parameters depend on the band (row `chosen` is the report's).
    pub band: Vec<BandRow>,
    /// Warnings.
    pub warnings: Vec<Warning>,
    /// Statements of what is what (heights vs summits, the methods, the caveats).
    pub notes: Vec<String>,
    /// Plot data.
    pub plots: Plots,
}

struct Core {
    map: HeightMap,
    summary: DetrendSummary,
    moments: Moments,
    spectral: GwParameters,
    summits: Option<SummitStatistics>,
}

/// The detrended heights count as flat when their rms is at most this fraction of the
/// largest height of the map as given: the detrending's own rounding is a few 1e-16 of it,
/// and an instrument resolves 1e-7 of its range at best (a 24-bit scale).
const FLAT_TO_ROUNDING: f64 = 1e-12;

/// Refuses the first of `values` that is not finite: heights (or a spacing) so large or so
/// small that `what` overflows double precision. No analysis outputs a NaN or an infinity.
fn finite(what: &str, values: &[(&str, f64)], largest: f64, dx: f64) -> Result<()> {
    match values.iter().find(|(_, v)| !v.is_finite()) {
        None => Ok(()),
        Some((name, v)) => Err(TopographyError::param(
            "height map",
            format!("{name} = {v}"),
            format!(
                "{what} overflow double precision (heights up to {largest:e} m, spacing {dx:e} m): \
                 no finite result; give the heights in their unit (--height-unit) or rescale the map"
            ),
        )),
    }
}

/// [`finite`] over many values of one name.
fn all_finite(what: &str, name: &str, values: &[f64], largest: f64, dx: f64) -> Result<()> {
    match values.iter().find(|v| !v.is_finite()) {
        None => Ok(()),
        Some(&v) => finite(what, &[(name, v)], largest, dx),
    }
}

fn core(map: &HeightMap, how: Detrend) -> Result<Core> {
    let largest = map.heights().iter().fold(0.0_f64, |m, z| m.max(z.abs()));
    let dx = map.dx();
    let (map, summary) = detrend(map, how)?;
    all_finite(
        "the detrended heights",
        "a detrended height",
        map.heights(),
        largest,
        dx,
    )?;
    finite(
        "the removed form's parameters",
        &[
            ("mean_height", summary.mean_height),
            ("tilt_x", summary.tilt_x),
            ("tilt_y", summary.tilt_y),
            ("tilt_degrees", summary.tilt_degrees),
            ("removed_rms", summary.removed_rms),
        ],
        largest,
        dx,
    )?;
    let moments = finite_difference_moments(&map);
    let m = &moments;
    finite(
        "the moments",
        &[
            ("m0", m.m0),
            ("m2", m.m2),
            ("m4", m.m4),
            ("m20", m.m20),
            ("m02", m.m02),
            ("m11", m.m11),
            ("m40", m.m40),
            ("m04", m.m04),
            ("m22", m.m22),
        ],
        largest,
        dx,
    )?;
    let rms = moments.rms_height();
    if largest > 0.0 && rms <= FLAT_TO_ROUNDING * largest {
        return Err(TopographyError::param(
            "height map",
            format!("rms height {rms:e} m after detrending, heights up to {largest:e} m"),
            format!(
                "the detrended map is flat to rounding (rms at most {FLAT_TO_ROUNDING:e} of the heights): nothing to analyse; a flat or perfectly planar map has no roughness"
            ),
        ));
    }
    if !(moments.m2 > 0.0 && moments.m4 > 0.0) {
        return Err(TopographyError::param(
            "height map",
            format!("m2 = {:e}, m4 = {:e}", moments.m2, moments.m4),
            "the detrended map is flat (no slope or curvature): nothing to analyse",
        ));
    }
    finite("the moments", &[("alpha", moments.alpha())], largest, dx)?;
    let spectral = mccool(&moments);
    finite(
        "the spectral route's parameters",
        &gw_values(&spectral),
        largest,
        dx,
    )?;
    let summits = summit_statistics(&map);
    if let Some(st) = &summits {
        finite(
            "the summit route's parameters",
            &gw_values(&st.gw),
            largest,
            dx,
        )?;
        finite(
            "the summit statistics",
            &[
                ("mean_curvature", st.mean_curvature),
                ("summit skewness", st.skewness),
                ("summit kurtosis", st.kurtosis),
            ],
            largest,
            dx,
        )?;
    }
    Ok(Core {
        map,
        summary,
        moments,
        spectral,
        summits,
    })
}

fn gw_values(g: &GwParameters) -> [(&'static str, f64); 4] {
    [
        ("sigma_s", g.sigma_s),
        ("asperity_density", g.asperity_density),
        ("radius", g.radius),
        ("offset", g.offset),
    ]
}

fn row(c: &Core, factor: usize, tiles: usize) -> ScaleRow {
    ScaleRow {
        factor,
        dx: c.map.dx(),
        dy: c.map.dy(),
        scan_x: c.map.scan_x(),
        scan_y: c.map.scan_y(),
        tiles,
        rms_height: c.moments.rms_height(),
        m2: c.moments.m2,
        m4: c.moments.m4,
        alpha: c.moments.alpha(),
        spectral: c.spectral,
        summits: c.summits.as_ref().map(|s| s.gw),
        summit_count: c.summits.as_ref().map_or(0, |s| s.count),
    }
}

fn mean_gw(v: &[GwParameters]) -> GwParameters {
    let n = v.len() as f64;
    GwParameters {
        sigma_s: v.iter().map(|g| g.sigma_s).sum::<f64>() / n,
        asperity_density: v.iter().map(|g| g.asperity_density).sum::<f64>() / n,
        radius: v.iter().map(|g| g.radius).sum::<f64>() / n,
        offset: v.iter().map(|g| g.offset).sum::<f64>() / n,
    }
}

/// The scan-size row for divisor `d`: every d x d tile analysed alone, parameters averaged.
fn tiles_row(map: &HeightMap, d: usize, how: Detrend) -> Option<ScaleRow> {
    let (wx, wy) = (map.nx() / d, map.ny() / d);
    let mut cores = Vec::new();
    for tj in 0..d {
        for ti in 0..d {
            let tile = map.crop(ti * wx, tj * wy, wx, wy)?;
            if let Ok(c) = core(&tile, how) {
                cores.push(c);
            }
        }
    }
    let first = cores.first()?;
    let n = cores.len() as f64;
    let spectral = mean_gw(&cores.iter().map(|c| c.spectral).collect::<Vec<_>>());
    let with: Vec<GwParameters> = cores
        .iter()
        .filter_map(|c| c.summits.as_ref().map(|s| s.gw))
        .collect();
    let mut r = row(first, d, cores.len());
    r.rms_height = cores.iter().map(|c| c.moments.rms_height()).sum::<f64>() / n;
    r.m2 = cores.iter().map(|c| c.moments.m2).sum::<f64>() / n;
    r.m4 = cores.iter().map(|c| c.moments.m4).sum::<f64>() / n;
    r.alpha = cores.iter().map(|c| c.moments.alpha()).sum::<f64>() / n;
    r.spectral = spectral;
    r.summits = if with.len() == cores.len() {
        Some(mean_gw(&with))
    } else {
        None
    };
    r.summit_count = cores
        .iter()
        .map(|c| c.summits.as_ref().map_or(0, |s| s.count))
        .sum();
    Some(r)
}

fn rel_change(a: f64, b: f64) -> f64 {
    (b / a - 1.0).abs()
}

/// Analyses a map read from a file (see [`analyze`]); the report carries the source.
pub fn analyze_measurement(m: &Measurement, opts: &AnalysisOptions) -> Result<TopographyReport> {
    let mut r = analyze(&m.map, opts)?;
    r.source = Some(m.source.clone());
    Ok(r)
}

/// Analyses a height map: detrending, the short-wavelength cutoff (`opts.cutoff`: the
/// detrended map low-pass filtered at it, [`crate::lowpass`]), the moments m0, m2, m4 and
/// alpha, the GW parameters by both routes, the band, sampling and scan-size tables, the
/// Gaussian checks, the warnings and the plot data.
///
/// Errors if the map is too small for the detrending order or flat after detrending, or
/// the cutoff is not a finite length > 0 or exceeds half the shorter scan side.
pub fn analyze(map: &HeightMap, opts: &AnalysisOptions) -> Result<TopographyReport> {
    let sampled = core(map, opts.detrend)?;
    let nyquist = nyquist_wavelength(map.dx().max(map.dy()));
    let half_scan = 0.5 * map.scan_x().min(map.scan_y());
    let positive = |name: &'static str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(TopographyError::param(
                name,
                format!("{v:e}"),
                "must be a finite length > 0 (m)",
            ))
        }
    };
    let mut cutoff = CutoffSummary {
        wavelength: None,
        applied: false,
        from: "none",
        contact_radius: None,
        spot_radius: None,
        nyquist_wavelength: nyquist,
        filter: FILTER_METHOD,
    };
    match opts.cutoff {
        Cutoff::None => {}
        Cutoff::Wavelength(w) => {
            cutoff.wavelength = Some(positive("cutoff", w)?);
            cutoff.from = "given";
        }
        Cutoff::ContactRadius(r) => {
            let r = positive("contact radius", r)?;
            let sigma_s = sampled
                .summits
                .as_ref()
                .map_or(sampled.spectral.sigma_s, |s| s.gw.sigma_s);
            let a = (r * sigma_s).sqrt();
            cutoff.wavelength = Some(SPOT_CUTOFF_FACTOR * a);
            cutoff.from = "contact_radius";
            cutoff.contact_radius = Some(r);
            cutoff.spot_radius = Some(a);
        }
    }
    if let Some(w) = cutoff.wavelength {
        if w > half_scan {
            let origin = match (cutoff.contact_radius, cutoff.spot_radius) {
                (Some(r), Some(a)) => format!(
                    " (from the contact radius {r:e} m: {SPOT_CUTOFF_FACTOR} x the spot radius sqrt(R sigma_s) = {a:e} m)"
                ),
                _ => String::new(),
            };
            return Err(TopographyError::param(
                "cutoff",
                format!("{w:e} m{origin}"),
                format!(
                    "must be at most half the shorter scan side ({half_scan:e} m): a longer cutoff leaves fewer than two \
                     wavelengths of the map; measure a larger scan for this contact, or give a shorter cutoff (0: the \
                     map as sampled)"
                ),
            ));
        }
        cutoff.applied = filters(w, map.dx()) || filters(w, map.dy());
    }
    // the band table, on the detrended map as sampled
    let mut band = vec![band_row(&sampled, None, 1.0, !cutoff.applied)];
    let mut cutoffs: Vec<(f64, bool)> = opts
        .band
        .iter()
        .filter(|&&f| f.is_finite() && f > 1.0)
        .map(|&f| (f * nyquist, false))
        .filter(|&(w, _)| w <= 0.5 * half_scan)
        .collect();
    if let (true, Some(w)) = (cutoff.applied, cutoff.wavelength) {
        match cutoffs.iter_mut().find(|(x, _)| (x / w - 1.0).abs() < 1e-9) {
            Some(c) => c.1 = true,
            None => cutoffs.push((w, true)),
        }
    }
    cutoffs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut chosen = None;
    for (w, is_chosen) in cutoffs {
        let filtered = lowpass(&sampled.map, w);
        match core(&filtered, opts.detrend) {
            Ok(c) => {
                band.push(band_row(&c, Some(w), w / nyquist, is_chosen));
                if is_chosen {
                    chosen = Some((filtered, c));
                }
            }
            Err(e) if is_chosen => {
                return Err(TopographyError::param(
                    "cutoff",
                    format!("{w:e} m"),
                    format!("the map filtered at it cannot be analysed: {e}"),
                ))
            }
            Err(_) => {}
        }
    }
    let mut r = match chosen {
        Some((filtered, c)) => {
            let mut r = report(&filtered, c, opts)?;
            r.detrending = sampled.summary;
            r
        }
        None => report(map, sampled, opts)?,
    };
    if let Some(w) = cutoff.wavelength {
        r.notes.push(if cutoff.applied {
            format!(
                "band: the map is low-pass filtered at the cutoff {w:.4e} m ({}) before the analysis: the GW \
                 parameters describe the wavelengths longer than it; {FILTER_METHOD}",
                match cutoff.from {
                    "contact_radius" => "4 x the contact-spot radius sqrt(R sigma_s)",
                    _ => "given",
                }
            )
        } else {
            format!(
                "band: the cutoff {w:.4e} m is at or below the Nyquist wavelength {nyquist:.4e} m: the map as sampled"
            )
        });
    }
    r.cutoff = cutoff;
    r.band = band;
    Ok(r)
}

fn band_row(c: &Core, cutoff: Option<f64>, nyquist_multiple: f64, chosen: bool) -> BandRow {
    BandRow {
        cutoff,
        nyquist_multiple,
        chosen,
        rms_height: c.moments.rms_height(),
        m2: c.moments.m2,
        m4: c.moments.m4,
        alpha: c.moments.alpha(),
        spectral: c.spectral,
        summits: c.summits.as_ref().map(|s| s.gw),
        summit_count: c.summits.as_ref().map_or(0, |s| s.count),
    }
}

/// The report of `map` whose core `c` is computed (the map as sampled, or filtered).
fn report(map: &HeightMap, c: Core, opts: &AnalysisOptions) -> Result<TopographyReport> {
    let m = c.moments;
    let largest = map.heights().iter().fold(0.0_f64, |m, z| m.max(z.abs()));
    let dx = map.dx();
    let heights_shape = shape(c.map.heights());
    finite(
        "the height distribution's moments",
        &[
            ("skewness", heights_shape.skewness),
            ("kurtosis", heights_shape.kurtosis),
        ],
        largest,
        dx,
    )?;
    let mut sampling = vec![row(&c, 1, 1)];
    for &f in &opts.coarsen {
        if f <= 1 {
            continue;
        }
        if let Some(coarse) = map.coarsen(f) {
            if let Ok(cc) = core(&coarse, opts.detrend) {
                sampling.push(row(&cc, f, 1));
            }
        }
    }
    let mut scan_size = vec![row(&c, 1, 1)];
    for &d in &opts.scan_divisors {
        if d <= 1 {
            continue;
        }
        if let Some(r) = tiles_row(map, d, opts.detrend) {
            scan_size.push(r);
        }
    }
    let summits = c.summits.clone().map(SummitRoute::from);

    // Warnings.
    let mut w = Vec::new();
    let mut warn = |code: &'static str, message: String| w.push(Warning { code, message });
    if !heights_shape.is_near_gaussian() {
        warn(
            "non_gaussian_heights",
            format!(
                "height skewness {:.2}, kurtosis {:.2} (Gaussian: 0, 3; limits |S| <= {SKEWNESS_LIMIT}, |K - 3| <= \
                 {EXCESS_KURTOSIS_LIMIT}): McCool's formulas assume a Gaussian surface; prefer the summit route",
                heights_shape.skewness, heights_shape.kurtosis
            ),
        );
    }
    match &summits {
        None => warn(
            "no_summits",
            "fewer than 2 summits on the grid: the summit route is unavailable".to_string(),
        ),
        Some(s) => {
            let sh = Shape {
                skewness: s.skewness,
                kurtosis: s.kurtosis,
            };
            if !sh.is_near_gaussian() {
                warn(
                    "non_gaussian_summits",
                    format!(
                        "summit-height skewness {:.2}, kurtosis {:.2} (Gaussian: 0, 3; limits |S| <= {SKEWNESS_LIMIT}, \
                         |K - 3| <= {EXCESS_KURTOSIS_LIMIT}): the GW model's Gaussian of summit heights misrepresents \
                         the upper tail that makes the contacts",
                        s.skewness, s.kurtosis
                    ),
                );
            }
            if s.count < 100 {
                warn(
                    "few_summits",
                    format!(
                        "only {} summits: sigma_s and the density carry a statistical error of about {:.0}%",
                        s.count,
                        100.0 / (s.count as f64).sqrt()
                    ),
                );
            }
            let interior = (c.map.nx() - 2) * (c.map.ny() - 2);
            if s.ties * 20 > interior {
                warn(
                    "quantized_heights",
                    format!(
                        "{} of {interior} interior points tie with a neighbour: the heights look quantised; summits on \
                         flat tops are counted once (raster-order tie break)",
                        s.ties
                    ),
                );
            }
            let g = (s.gw, c.spectral);
            let ratio = |a: f64, b: f64| (a / b).max(b / a);
            let worst = ratio(g.0.sigma_s, g.1.sigma_s)
                .max(ratio(g.0.asperity_density, g.1.asperity_density))
                .max(ratio(g.0.radius, g.1.radius));
            if worst > 2.0 {
                // a parameter 0 on one route (McCool's sigma_s below alpha = 0.8968) differs
                // by no finite factor
                let factor = if worst.is_finite() {
                    format!("a factor {worst:.1}")
                } else {
                    "more than any factor (a parameter is 0 on one route)".to_string()
                };
                warn(
                    "routes_disagree",
                    format!(
                        "the two routes differ by {factor} in a parameter (spectral: sigma_s {:.3e} m, \
                         N {:.3e} 1/m^2, R {:.3e} m; summits: {:.3e}, {:.3e}, {:.3e}): the surface is far from the \
                         Gaussian isotropic model, or the sampling resolves its summits poorly",
                        g.1.sigma_s, g.1.asperity_density, g.1.radius, g.0.sigma_s, g.0.asperity_density, g.0.radius
                    ),
                );
            }
        }
    }
    let aniso = m.slope_anisotropy();
    if aniso > 2.0 {
        warn(
            "anisotropic",
            format!(
                "the mean square slopes differ by a factor {aniso:.2} between principal directions: McCool's formulas \
                 are applied to the direction-averaged moments (the equivalent isotropic surface)"
            ),
        );
    }
    let alpha = m.alpha();
    if alpha <= MCCOOL_SIGMA_CONSTANT {
        warn(
            "alpha_below_mccool",
            format!("alpha = {alpha:.3} <= 0.8968: McCool's sigma_s is undefined (reported as 0)"),
        );
    } else if alpha < 2.0 {
        warn(
            "narrow_band",
            format!(
                "alpha = {alpha:.2} < 2: a narrow-band (nearly periodic) surface, whose summits are not the \
                 independent, randomly placed asperities of the GW model"
            ),
        );
    }
    if let (Some(s1), Some(s2)) = (sampling.first(), sampling.get(1)) {
        if let (Some(a), Some(b)) = (s1.summits, s2.summits) {
            let (dn, dr) = (
                rel_change(a.asperity_density, b.asperity_density),
                rel_change(a.radius, b.radius),
            );
            if dn.max(dr) > 0.25 {
                warn(
                    "sampling_dependent",
                    format!(
                        "doubling the sampling interval changes the summit density by {:+.0}% and the radius by \
                         {:+.0}%: the GW parameters describe the surface at this sampling interval, not intrinsically; \
                         choose the band of wavelengths that matters for the contact (a cutoff; the band table; \
                         docs/topography.md section 10)",
                        100.0 * (b.asperity_density / a.asperity_density - 1.0),
                        100.0 * (b.radius / a.radius - 1.0)
                    ),
                );
            }
        }
    }
    if let (Some(s1), Some(s2)) = (scan_size.first(), scan_size.get(1)) {
        let d = rel_change(s1.spectral.sigma_s, s2.spectral.sigma_s);
        if d > 0.25 {
            warn(
                "scan_size_dependent",
                format!(
                    "halving the scan size changes sigma_s by {:+.0}%: the long wavelengths of the surface are not \
                     converged in this scan",
                    100.0 * (s2.spectral.sigma_s / s1.spectral.sigma_s - 1.0)
                ),
            );
        }
    }
    if c.summary.tilt_degrees > 5.0 {
        warn(
            "large_tilt",
            format!(
                "the removed tilt is {:.1} degrees: check the sample mounting; heights measured on a steep tilt \
                 are foreshortened",
                c.summary.tilt_degrees
            ),
        );
    }

    let notes = vec![
        format!(
            "heights vs summits: the rms height {:.4e} m describes all points; the GW model needs the summits \
             (local maxima): their standard deviation sigma_s is smaller, and their mean plane lies 'offset' above \
             the mean plane of the heights; the model measures separation from the summits' plane",
            m.rms_height()
        ),
        format!("detrending: {} of total degree {} removed (least squares)", c.summary.method, c.summary.order),
        format!("spectral route: {SPECTRAL_METHOD}"),
        format!("summit route: {SUMMIT_METHOD}"),
        "sampling and scan size: GW parameters are not intrinsic to a surface; the tables give both routes on the \
         map block-averaged by 2, 4, 8 and on 2 x 2 and 4 x 4 tiles (smaller scans)"
            .to_string(),
    ];

    let (summit_list, _) = find_summits(&c.map);
    let sh: Vec<f64> = summit_list.iter().map(|s| s.height).collect();
    let (sm, ss) = summits
        .as_ref()
        .map_or((0.0, 0.0), |s| (s.gw.offset, s.gw.sigma_s));
    let pic = c.map.downsample(opts.plot_side);
    let plots = Plots {
        height_map: PlotMap {
            nx: pic.nx(),
            ny: pic.ny(),
            dx: pic.dx(),
            dy: pic.dy(),
            z: pic.into_heights(),
        },
        summit_heights: histogram(&sh, opts.histogram_bins, sm, ss),
        heights: histogram(c.map.heights(), opts.histogram_bins, 0.0, m.rms_height()),
        psd: if opts.psd_bins == 0 {
            Vec::new()
        } else {
            radial_psd(&c.map, opts.psd_bins)
        },
    };

    let moments_fourier = spectral_moments(&c.map);
    let mf = &moments_fourier;
    finite(
        "the Fourier moments",
        &[
            ("m0", mf.m0),
            ("m2", mf.m2),
            ("m4", mf.m4),
            ("m20", mf.m20),
            ("m02", mf.m02),
            ("m11", mf.m11),
            ("m40", mf.m40),
            ("m04", mf.m04),
            ("m22", mf.m22),
        ],
        largest,
        dx,
    )?;
    for r in sampling.iter().chain(scan_size.iter()) {
        let mut v = vec![
            ("rms_height", r.rms_height),
            ("m2", r.m2),
            ("m4", r.m4),
            ("alpha", r.alpha),
        ];
        v.extend(gw_values(&r.spectral));
        if let Some(g) = &r.summits {
            v.extend(gw_values(g));
        }
        finite("the sampling and scan-size tables", &v, largest, dx)?;
    }
    all_finite(
        "the plotted heights",
        "a plotted height",
        &plots.height_map.z,
        largest,
        dx,
    )?;
    for h in [&plots.summit_heights, &plots.heights] {
        finite(
            "the histograms",
            &[("width", h.width), ("mean", h.mean), ("std", h.std)],
            largest,
            dx,
        )?;
        for v in [&h.centres, &h.density, &h.gaussian] {
            all_finite("the histograms", "a histogram value", v, largest, dx)?;
        }
    }
    for p in &plots.psd {
        finite("the PSD values", &[("q", p.q), ("C(q)", p.c)], largest, dx)?;
    }

    Ok(TopographyReport {
        rms_height: m.rms_height(),
        m0: m.m0,
        m2: m.m2,
        m4: m.m4,
        alpha,
        spectral: SpectralRoute {
            gw: c.spectral,
            method: SPECTRAL_METHOD,
        },
        summits,
        source: None,
        grid: Grid::of(&c.map),
        detrending: c.summary,
        moments: m,
        moments_fourier,
        slope_anisotropy: aniso,
        heights: heights_shape,
        sampling,
        scan_size,
        cutoff: CutoffSummary {
            wavelength: None,
            applied: false,
            from: "none",
            contact_radius: None,
            spot_radius: None,
            nyquist_wavelength: nyquist_wavelength(map.dx().max(map.dy())),
            filter: FILTER_METHOD,
        },
        band: Vec::new(),
        warnings: w,
        notes,
        plots,
    })
}

/// Which route's parameters go into a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Route {
    /// McCool's formulas on the moments.
    Spectral,
    /// The summits found on the grid.
    Summits,
}

/// The `[surface]` (sigma_s, asperity_density) and `[contact]` (radius) scene fragment of
/// the report, as TOML text, with the method, the sampling and the caveats in comments.
/// Errors if `route` is `Summits` and the map had fewer than 2 summits.
pub fn scene_fragment(report: &TopographyReport, route: Route) -> Result<String> {
    let (gw, method) = match route {
        Route::Spectral => (
            report.spectral.gw,
            "spectral route (McCool 1986 from m0, m2, m4)",
        ),
        Route::Summits => match &report.summits {
            Some(s) => (s.gw, "summit route (8-neighbour maxima of the grid)"),
            None => {
                return Err(TopographyError::param(
                    "route",
                    "summits",
                    "the map has fewer than 2 summits; use the spectral route",
                ))
            }
        },
    };
    let other = match route {
        Route::Spectral => report.summits.as_ref().map(|s| ("summits", s.gw)),
        Route::Summits => Some(("spectral", report.spectral.gw)),
    };
    let g = &report.grid;
    let mut s = String::new();
    let src = report
        .source
        .as_ref()
        .map_or("a height map".to_string(), |s| s.path.clone());
    let _ = writeln!(
        s,
        "# GW parameters of {src} (stiction topography), {method}."
    );
    let _ = writeln!(
        s,
        "# Grid {} x {} at dx = {:.4e} m, dy = {:.4e} m (scan {:.4e} x {:.4e} m); {} of degree {} removed.",
        g.nx, g.ny, g.dx, g.dy, g.scan_x, g.scan_y, report.detrending.method, report.detrending.order
    );
    let _ = writeln!(
        s,
        "# rms height {:.4e} m (all points); sigma_s below is the std of the summit heights, whose mean plane",
        report.rms_height
    );
    let _ = writeln!(
        s,
        "# lies {:.4e} m above the mean plane: the model measures separation from it.",
        gw.offset
    );
    if let Some((name, o)) = other {
        let _ = writeln!(
            s,
            "# The {name} route gives sigma_s = {:.4e} m, asperity_density = {:.4e} 1/m^2, radius = {:.4e} m.",
            o.sigma_s, o.asperity_density, o.radius
        );
    }
    let c = &report.cutoff;
    match (c.wavelength, c.applied) {
        (Some(w), true) => {
            let from = match (c.contact_radius, c.spot_radius) {
                (Some(r), Some(a)) => format!(
                    "4 x the contact-spot radius sqrt(R sigma_s) = {a:.4e} m of R = {r:.4e} m"
                ),
                _ => "given".to_string(),
            };
            let _ = writeln!(
                s,
                "# Band: wavelengths longer than the cutoff {w:.4e} m ({from}; Gaussian low-pass, ISO 16610-61)."
            );
        }
        _ => {
            let _ = writeln!(
                s,
                "# Band: the map as sampled (no cutoff; its shortest wavelength is 2 dx = {:.4e} m).",
                c.nyquist_wavelength
            );
        }
    }
    let band: Vec<&BandRow> = report.band.iter().filter(|r| r.cutoff.is_some()).collect();
    if !band.is_empty() {
        let _ = writeln!(s, "# Across the band (cutoff wavelength):");
        for r in band {
            let p = match route {
                Route::Spectral => Some(r.spectral),
                Route::Summits => r.summits,
            };
            if let (Some(w), Some(p)) = (r.cutoff, p) {
                let _ = writeln!(
                    s,
                    "#   {w:.3e} m{}: sigma_s = {:.4e} m, asperity_density = {:.4e} 1/m^2, radius = {:.4e} m",
                    if r.chosen { " (this fragment)" } else { "" },
                    p.sigma_s,
                    p.asperity_density,
                    p.radius
                );
            }
        }
    }
    let _ = writeln!(
        s,
        "# GW parameters depend on the sampling interval (docs/topography.md); coarsened:"
    );
    for r in report.sampling.iter().skip(1) {
        let p = match route {
            Route::Spectral => Some(r.spectral),
            Route::Summits => r.summits,
        };
        if let Some(p) = p {
            let _ = writeln!(
                s,
                "#   x{} (dx = {:.3e} m): sigma_s = {:.4e} m, asperity_density = {:.4e} 1/m^2, radius = {:.4e} m",
                r.factor, r.dx, p.sigma_s, p.asperity_density, p.radius
            );
        }
    }
    for wng in &report.warnings {
        let _ = writeln!(s, "# warning [{}]: {}", wng.code, wng.message);
    }
    let _ = writeln!(
        s,
        "# For two rough surfaces, analyse their sum surface (or combine the moments)."
    );
    let _ = writeln!(s);
    let line =
        |key: &str, v: f64, comment: &str| format!("{:<40} # {comment}", format!("{key} = {v:e}"));
    let _ = writeln!(s, "[surface]");
    let _ = writeln!(
        s,
        "{}",
        line("sigma_s", gw.sigma_s, "std. dev. of summit heights (m)")
    );
    let _ = writeln!(
        s,
        "{}",
        line("asperity_density", gw.asperity_density, "N (1/m^2)")
    );
    let _ = writeln!(s);
    let _ = writeln!(s, "[contact]");
    let _ = writeln!(
        s,
        "{}",
        line(
            "radius",
            gw.radius,
            "summit radius R (m), 1 / mean summit curvature"
        )
    );
    Ok(s)
}

/// GW parameters of the sum surface of two independent rough surfaces analysed separately
/// (on different grids, say): the gap between two rough surfaces equals the gap between a
/// flat and their sum surface z1 + z2.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SumSurface {
    /// The moments of the sum: every moment adds (the spectra of independent surfaces add),
    /// exactly.
    pub moments: Moments,
    /// Rms height of the sum (m).
    pub rms_height: f64,
    /// Nayak's alpha of the sum.
    pub alpha: f64,
    /// McCool's parameters of the summed moments: the consistent route.
    pub spectral: GwParameters,
    /// The customary rule on the summit parameters of each: sigma_s = sqrt(s1^2 + s2^2),
    /// 1/R = 1/R1 + 1/R2, offset o1 + o2, and the density of the summed moments (no rule
    /// combines densities). An approximation: summits of the sum are not sums of summits.
    pub parameter_rule: Option<GwParameters>,
}

impl SumSurface {
    /// The sum surface of two analysed surfaces.
    pub fn from_reports(a: &TopographyReport, b: &TopographyReport) -> SumSurface {
        let moments = a.moments.sum(&b.moments);
        let spectral = mccool(&moments);
        let parameter_rule = match (&a.summits, &b.summits) {
            (Some(x), Some(y)) => Some(GwParameters {
                sigma_s: x.gw.sigma_s.hypot(y.gw.sigma_s),
                asperity_density: spectral.asperity_density,
                radius: 1.0 / (1.0 / x.gw.radius + 1.0 / y.gw.radius),
                offset: x.gw.offset + y.gw.offset,
            }),
            _ => None,
        };
        SumSurface {
            rms_height: moments.rms_height(),
            alpha: moments.alpha(),
            moments,
            spectral,
            parameter_rule,
        }
    }
}
