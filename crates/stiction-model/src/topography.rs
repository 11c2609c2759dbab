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
//! assert!(r.summits.as_ref().unwrap().gw.sigma_s < r.rms_height);
//! let toml = scene_fragment(&r, Route::Summits)?;
//! assert!(toml.contains("[surface]") && toml.contains("asperity_density"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::error::ModelError;
pub use ::topography::*;
use std::path::Path;

/// Reads the height map at `path` and analyses it.
pub fn analyze_file(
    path: &Path,
    read: &ReadOptions,
    options: &AnalysisOptions,
) -> Result<TopographyReport, ModelError> {
    let m = read_path(path, read)?;
    Ok(analyze_measurement(&m, options)?)
}

/// Analyses a height map held in memory.
pub fn analyze_map(
    map: &HeightMap,
    options: &AnalysisOptions,
) -> Result<TopographyReport, ModelError> {
    Ok(analyze(map, options)?)
}
