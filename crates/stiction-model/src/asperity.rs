//! One elasto-plastic adhesive asperity loaded to each delta_max and unloaded (the
//! paper's Fig 2 scene).

use crate::accuracy::Targets;
use crate::error::ModelError;
use crate::guards::{self, Validity, Warning};
use crate::spec::{Asperity, AsperitySpec};
use crate::switch::Laws;
use asperity_plastic::PULL_OFF_TOLERANCE;
use contact_core::numeric::linspace;
use contact_core::{AsperityHistory, AsperityModel, Path};
use serde::Serialize;

/// A point of a single-asperity curve: interference (m), force (N).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ForcePoint {
    /// Interference (m).
    pub delta: f64,
    /// Force (N, compressive > 0).
    pub force: f64,
}

/// One loading/unloading case.
#[derive(Debug, Clone, Serialize)]
pub struct AsperityCase {
    /// Maximum interference (m).
    pub delta_max: f64,
    /// Residual height loss (m), eq 4.
    pub delta_res: f64,
    /// Residual radius (m), eq 5.
    pub r_res: f64,
    /// R_eff on loading at delta_max (m), eq 12 with x = 1.
    pub r_eff_loading: f64,
    /// Most tensile force on the unloading path (N).
    pub pull_off_force: f64,
    /// Where it occurs (m).
    pub pull_off_interference: f64,
    /// The same for the elastic asperity (no yield).
    pub elastic_pull_off_force: f64,
    /// delta_max beyond the plasticity fits' range.
    pub extrapolated: bool,
    /// Loading curve, from out of contact to delta_max.
    pub loading: Vec<ForcePoint>,
    /// Unloading curve, from delta_max to below the jump-out.
    pub unloading: Vec<ForcePoint>,
}

/// Error estimates of the reported quantities.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct AsperityErrors {
    /// Largest change of a pull-off force within its location tolerance (N): each force is
    /// solved to rounding, the minimum's location to 1e-10 of its bracket.
    pub pull_off: f64,
}

/// An asperity run.
#[derive(Debug, Clone, Serialize)]
pub struct AsperityResult {
    /// Plot and table title.
    pub title: String,
    /// The laws and modelling choices.
    pub laws: Laws,
    /// Yield onset delta_CP (m), eq 1 (`"inf"` if it never yields).
    #[serde(serialize_with = "number_or_name")]
    pub delta_cp: f64,
    /// Transition parameter at the initial radius.
    pub lambda: f64,
    /// Initial radius (m).
    pub radius: f64,
    /// Accuracy mode and targets (an asperity solves every point to rounding in every mode).
    pub accuracy: Targets,
    /// Error estimates.
    pub error_estimate: AsperityErrors,
    /// The cases.
    pub cases: Vec<AsperityCase>,
    /// Whether the model holds.
    pub validity: Validity,
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// The resolved scene.
    pub scene: serde_json::Value,
}

/// A float as JSON: the number when finite, else its name (`"inf"`), never `null`.
pub fn number_or_name<S: serde::Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else {
        s.serialize_str(&crate::keys::num(*v))
    }
}

fn pull_off_error(m: &Asperity, delta_max: f64, at: f64, force: f64) -> Result<f64, ModelError> {
    let hist = AsperityHistory { delta_max };
    let path = Path::Retract { from: delta_max };
    let j = m.jumps(hist)?;
    let h = PULL_OFF_TOLERANCE.rel * (delta_max - j.jump_out);
    let mut worst: f64 = 0.0;
    for x in [at - h, at + h] {
        if x > j.jump_out && x <= delta_max {
            worst = worst.max((m.force(x, hist, path)? - force).abs());
        }
    }
    Ok(worst)
}

/// Runs an asperity spec: each case loaded and unloaded, its pull-off against the elastic
/// asperity's.
pub fn run(spec: &AsperitySpec) -> Result<AsperityResult, ModelError> {
    run_inner(spec).map_err(|e| e.in_scene(spec.common.scene.file()))
}

fn run_inner(spec: &AsperitySpec) -> Result<AsperityResult, ModelError> {
    let c = &spec.contact;
    let plastic = c.asperity();
    let elastic = c.elastic_asperity();
    let n = spec.common.points;
    let mut cases = Vec::new();
    let mut error: f64 = 0.0;
    for &dmax in &spec.delta_max {
        let virgin = AsperityHistory::VIRGIN;
        let j0 = plastic.jumps(virgin)?;
        let start = j0.jump_in - 0.02 * (dmax - j0.jump_in);
        let loading = linspace(start, dmax, n)
            .map(|delta| {
                Ok(ForcePoint {
                    delta,
                    force: plastic.force(delta, virgin, Path::Approach)?,
                })
            })
            .collect::<Result<Vec<_>, ModelError>>()?;
        let hist = AsperityHistory { delta_max: dmax };
        let j = plastic.jumps(hist)?;
        let end = j.jump_out - 0.02 * (dmax - j.jump_out);
        let unloading = linspace(dmax, end, n)
            .map(|delta| {
                Ok(ForcePoint {
                    delta,
                    force: plastic.force(delta, hist, Path::Retract { from: dmax })?,
                })
            })
            .collect::<Result<Vec<_>, ModelError>>()?;
        let pull = plastic.pull_off(dmax)?;
        let epull = elastic.pull_off(dmax)?;
        error = error
            .max(pull_off_error(&plastic, dmax, pull.delta, pull.force)?)
            .max(pull_off_error(&elastic, dmax, epull.delta, epull.force)?);
        let st = plastic.plastic_state(hist);
        cases.push(AsperityCase {
            delta_max: dmax,
            delta_res: st.delta_res,
            r_res: st.r_res,
            r_eff_loading: plastic.effective(dmax, dmax).radius,
            pull_off_force: pull.force,
            pull_off_interference: pull.delta,
            elastic_pull_off_force: epull.force,
            extrapolated: st.extrapolated,
            loading,
            unloading,
        });
    }
    let mut warnings: Vec<Warning> = guards::adhesion_yields(c)?.into_iter().collect();
    warnings.extend(guards::asperity_beyond_fit(c, &spec.delta_max));
    Ok(AsperityResult {
        title: spec.common.title.clone(),
        laws: Laws::of(c),
        delta_cp: plastic.delta_cp(),
        lambda: c.lambda(),
        radius: c.radius,
        accuracy: spec.common.accuracy.targets(),
        error_estimate: AsperityErrors { pull_off: error },
        cases,
        validity: Validity::of(&warnings),
        warnings,
        scene: spec.common.echo(),
    })
}
