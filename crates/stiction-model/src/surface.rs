//! The rough surface's contact law: virgin loading and (with `unload_from`) unloading and
//! reloading.

use crate::accuracy::Targets;
use crate::error::ModelError;
use crate::guards::{self, Validity, Warning};
use crate::spec::SurfaceSpec;
use crate::switch::{rough_surface, Laws};
use contact_core::numeric::linspace;
use contact_core::{Path, SurfaceLaw};
use serde::Serialize;
use switch_1d::PressurePoint;

/// Error estimates of the reported quantities (Pa).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct SurfaceErrors {
    /// The largest error estimate of a curve pressure.
    pub pressure: f64,
    /// The pull-out pressure's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pull_out: Option<f64>,
}

/// A surface run.
#[derive(Debug, Clone, Serialize)]
pub struct SurfaceResult {
    /// Plot and table title.
    pub title: String,
    /// The laws and modelling choices.
    pub laws: Laws,
    /// sigma_s (m).
    pub sigma_s: f64,
    /// Accuracy mode and targets.
    pub accuracy: Targets,
    /// Error estimates.
    pub error_estimate: SurfaceErrors,
    /// Virgin loading (approach) from d_start to the first touch.
    pub loading: Vec<PressurePoint>,
    /// The separation unloaded from (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unload_from: Option<f64>,
    /// Unloading (retraction) from unload_from to the last contact.
    pub unloading: Vec<PressurePoint>,
    /// Reloading (approach with the history of unload_from) from the first touch down to
    /// unload_from.
    pub reloading: Vec<PressurePoint>,
    /// Magnitude of the most tensile unloading pressure (Pa).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pull_out_pressure: Option<f64>,
    /// Where it occurs (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pull_out_separation: Option<f64>,
    /// Fraction of asperities (by count) loaded beyond the plasticity fits' range.
    pub extrapolated_fraction: f64,
    /// Whether the model holds.
    pub validity: Validity,
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// The resolved scene.
    pub scene: serde_json::Value,
}

/// Runs a surface spec.
pub fn run(spec: &SurfaceSpec) -> Result<SurfaceResult, ModelError> {
    run_inner(spec).map_err(|e| e.in_scene(spec.common.scene.file()))
}

fn run_inner(s: &SurfaceSpec) -> Result<SurfaceResult, ModelError> {
    let c = &s.contact;
    let accuracy = s.common.accuracy;
    let points = s.common.points;
    let gw = rough_surface(c, s.roughness, accuracy, 0.0, false)?;
    let virgin = gw.virgin();
    let top = gw.reach(&virgin, Path::Approach)?;
    let start = s.d_start.or(s.unload_from).unwrap_or(0.0);
    let mut worst: f64 = 0.0;
    let mut curve = |hist: &gw_surface::GwHistory, from: f64, to: f64, path: Path| {
        linspace(from, to, points)
            .map(|d| {
                let e = gw.pressure_estimate(d, hist, path)?;
                worst = worst.max(e.error);
                Ok(PressurePoint {
                    d,
                    pressure: e.value,
                })
            })
            .collect::<Result<Vec<_>, ModelError>>()
    };
    let loading = curve(&virgin, start, top, Path::Approach)?;
    let deepest = s.unload_from.map_or(start, |u| u.min(start));
    let loaded_hist = gw.load(&virgin, deepest);
    let extrapolated_fraction =
        guards::fit_range_max(c).map_or(0.0, |hi| gw.fraction_beyond(&loaded_hist, hi));
    let mut warnings = Vec::new();
    let (mut unloading, mut reloading, mut pull, mut pull_err) =
        (Vec::new(), Vec::new(), None, None);
    if let Some(d) = s.unload_from {
        let hist = gw.load(&virgin, d);
        let path = Path::Retract { from: d };
        let reach = gw.reach(&hist, path)?;
        unloading = curve(&hist, d, reach, path)?;
        reloading = curve(&hist, gw.reach(&hist, Path::Approach)?, d, Path::Approach)?;
        let u = switch_1d::unload(&gw, &hist, d, 0, accuracy.precision())?;
        pull = Some((u.pull_out_pressure, u.pull_out_separation));
        pull_err = Some(u.pull_out_error);
    }
    let compressive = gw.pressure(deepest, &virgin, Path::Approach)?.max(0.0);
    warnings.extend(guards::pressures(c, compressive, pull.map_or(0.0, |p| p.0)));
    if let Some(hi) = guards::fit_range_max(c) {
        let share = gw.load_share_beyond(deepest, &virgin, Path::Approach, hi)?;
        warnings.extend(guards::surface_beyond_fit(c, share, deepest));
    }
    warnings.extend(guards::adhesion_yields(c)?);
    // the scene's own notes (a key that overrides its height map's value)
    warnings.extend(s.common.notes.iter().cloned());
    Ok(SurfaceResult {
        title: s.common.title.clone(),
        laws: Laws::of(c),
        sigma_s: s.roughness.sigma_s,
        accuracy: accuracy.targets(),
        error_estimate: SurfaceErrors {
            pressure: worst,
            pull_out: pull_err,
        },
        loading,
        unload_from: s.unload_from,
        unloading,
        reloading,
        pull_out_pressure: pull.map(|p| p.0),
        pull_out_separation: pull.map(|p| p.1),
        extrapolated_fraction,
        validity: Validity::of(&warnings),
        warnings,
        scene: s.common.echo(),
    })
}
