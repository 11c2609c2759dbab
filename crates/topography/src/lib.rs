//! Greenwood-Williamson parameters from a measured surface height map.
//!
//! Every GW scene needs sigma_s (standard deviation of the **summit** heights), the asperity
//! density N and the asperity radius R. This crate reads a height map (text matrix, x/y/z
//! columns, NumPy `.npy`, Gwyddion `.gwy` and `.gsf`, ISO 25178-72 `.x3p`, and the
//! instruments' own files: Bruker/Veeco Nanoscope, Wyko `.opd`, Zygo MetroPro `.dat`,
//! Digital Surf `.sur`, Sensofar `.plu`/`.plux`, Keyence `.vk4`, ISO 25178-71 `.sdf`;
//! [`io`]), refuses or fills its undefined points ([`fill_harmonic`]), removes its mean
//! plane (or a polynomial form), and computes the three numbers two ways, side by side:
//!
//! * **spectral**: from the profile moments m0, m2, m4 of the equivalent isotropic surface
//!   and Nayak's bandwidth parameter alpha = m0 m4 / m2^2 (McCool 1986, Nayak 1971):
//!   eta = m4 / (6 pi sqrt 3 m2), R = 0.375 sqrt(pi / m4),
//!   sigma_s = sqrt(1 - 0.8968/alpha) sqrt(m0), offset y_s = 4 sqrt(m0 / (pi alpha));
//! * **summits**: the grid points higher than their 8 neighbours, their heights (std ->
//!   sigma_s, mean -> offset), count per area and mean curvature -(z_xx + z_yy)/2.
//!
//! Both depend on the sampling interval and the scan size, so the report repeats them on the
//! map block-averaged by 2, 4, 8, on tiles of it, and across a band of short-wavelength
//! cutoffs ([`lowpass`], a Gaussian filter); a cutoff of the user's, or one from the
//! contact's own scale ([`Cutoff`]), chooses the band the parameters describe. A self-affine PSD gives the moments
//! analytically ([`SelfAffinePsd`]), and [`synthesize`] makes seeded periodic test surfaces
//! with a given spectrum. Formulas, derivations and caveats: `docs/topography.md`.
//!
//! ```
//! use topography::{analyze, synthesize, AnalysisOptions, Amplitudes, Normalization, SelfAffinePsd, SynthesisOptions};
//! // a self-affine surface, H = 0.8, wavelengths 2 um down to 40 nm, rms 5 nm
//! let psd = SelfAffinePsd::new(0.8, 2e-6, None, 40e-9, Normalization::RmsHeight(5e-9))?;
//! let opts = SynthesisOptions { nx: 256, ny: 256, dx: 8e-9, dy: 8e-9, seed: 1, amplitudes: Amplitudes::Fixed };
//! let map = synthesize(&psd, &opts)?;
//! let rms = (map.heights().iter().map(|z| z * z).sum::<f64>() / 65536.0).sqrt();
//! assert!((rms / 5e-9 - 1.0).abs() < 1e-9); // fixed amplitudes: exact rms
//! let report = analyze(&map, &AnalysisOptions::default())?; // removes the mean plane first
//! assert!(report.rms_height <= rms);
//! assert!(report.spectral.gw.sigma_s < report.rms_height); // summits spread less than heights
//! let toml = topography::scene_fragment(&report, topography::Route::Summits)?;
//! assert!(toml.contains("[surface]") && toml.contains("radius ="));
//! # Ok::<(), topography::TopographyError>(())
//! ```

#![deny(missing_docs)]

// The README's example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

mod detrend;
mod error;
mod fill;
mod filter;
mod gw;
pub mod io;
mod map;
mod moments;
mod psd;
mod report;
mod stats;
mod summits;
mod synth;

pub use detrend::{detrend, Detrend, DetrendSummary};
pub use error::{Result, TopographyError};
pub use fill::{fill_harmonic, FillSummary};
pub use filter::{
    filters, gaussian_transmission, lowpass, nyquist_wavelength, FILTER_METHOD, GAUSSIAN_ALPHA,
};
pub use gw::{mccool, GwParameters, MCCOOL_SIGMA_CONSTANT};
pub use io::{read_path, Format, Measurement, ReadOptions, Source, Undefined};
pub use map::{HeightMap, LengthUnit};
pub use moments::{
    finite_difference_moments, radial_psd, spectral_moments, MomentMethod, Moments, PsdPoint,
};
pub use psd::{Normalization, SelfAffinePsd};
pub use report::{
    analyze, analyze_measurement, scene_fragment, AnalysisOptions, BandRow, Cutoff, CutoffSummary,
    Grid, PlotMap, Plots, Route, ScaleRow, SpectralRoute, SumSurface, SummitRoute,
    TopographyReport, Warning, SPOT_CUTOFF_FACTOR,
};
pub use stats::{histogram, shape, Histogram, Shape, EXCESS_KURTOSIS_LIMIT, SKEWNESS_LIMIT};
pub use summits::{find_summits, summit_statistics, Summit, SummitStatistics};
pub use synth::{synthesize, Amplitudes, SynthesisOptions, MAX_POINTS as MAX_SYNTHETIC_POINTS};
