//! The nondimensional Maugis-Kim curve (paper eqs 7-11 with the Kim extension): the whole
//! curve with its landmarks, or the force at one interference on a path, vectorised.

use crate::error::ModelError;
use crate::keys::num;
use contact_core::Path;
use maugis_kim::{MdCurve, MdPoint};
use serde::Serialize;

/// The curve and its landmarks.
#[derive(Debug, Clone, Serialize)]
pub struct MdResult {
    /// Transition parameter lambda.
    pub lambda: f64,
    /// Jump-in interference on approach, Delta_in = -2/(pi lambda).
    pub jump_in_delta: f64,
    /// Turning point (jump-out) interference Delta_t.
    pub turning_delta: f64,
    /// Force at the turning point.
    pub turning_force: f64,
    /// Minimum force on the stable branch (DMT -2, JKR -3/2).
    pub pull_off_load_control: f64,
    /// Force at jump-out (JKR -5/6).
    pub pull_off_displacement_control: f64,
    /// The whole curve (contact-branch points carry `s`; non-contact points omit it).
    pub curve: Vec<MdPoint>,
}

/// One point on a path.
#[derive(Debug, Clone, Serialize)]
pub struct MdPointResult {
    /// Transition parameter.
    pub lambda: f64,
    /// Interference Delta.
    pub delta: f64,
    /// `approach` or `retract`.
    pub path: &'static str,
    /// Largest interference of the excursion (retract).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub from: Option<f64>,
    /// Force Fbar.
    pub force: f64,
}

/// The curve of `lambda` in [1e-6, 1e6] (errors name the argument `lambda`).
pub fn curve_for(lambda: f64) -> Result<MdCurve, ModelError> {
    if !(lambda.is_finite() && (1e-6..=1e6).contains(&lambda)) {
        return Err(ModelError::argument(
            "lambda",
            num(lambda),
            "finite and in [1e-6, 1e6]",
        ));
    }
    Ok(MdCurve::new(lambda)?)
}

/// The curve of `lambda` with `points` points up to `delta_end`.
pub fn curve(lambda: f64, points: usize, delta_end: f64) -> Result<MdResult, ModelError> {
    let c = curve_for(lambda)?;
    if !(4..=100_000).contains(&points) {
        return Err(ModelError::argument(
            "points",
            points.to_string(),
            "in [4, 100000]",
        ));
    }
    let dj = c.junction().delta;
    if !(delta_end.is_finite() && delta_end > dj && delta_end <= 1e6) {
        return Err(ModelError::argument(
            "delta_end",
            num(delta_end),
            format!(
                "finite, above the junction Delta_j = {} and at most 1e6",
                num(dj)
            ),
        ));
    }
    let t = c.pull_off_displacement_control()?;
    Ok(MdResult {
        lambda,
        jump_in_delta: c.jump_in_delta(),
        turning_delta: t.delta,
        turning_force: t.force,
        pull_off_load_control: c.pull_off_load_control()?.force,
        pull_off_displacement_control: t.force,
        curve: c.curve(points, delta_end)?,
    })
}

fn check_delta(name: &str, v: f64) -> Result<f64, ModelError> {
    if v.is_finite() && v.abs() <= 1e6 {
        Ok(v)
    } else {
        Err(ModelError::argument(name, num(v), "finite, |Delta| <= 1e6"))
    }
}

/// The force at `delta` on `path`.
pub fn point(lambda: f64, delta: f64, path: Path) -> Result<MdPointResult, ModelError> {
    let c = curve_for(lambda)?;
    let force = forces(&c, &[delta], path)?[0];
    let (name, from) = match path {
        Path::Approach => ("approach", None),
        Path::Retract { from } => ("retract", Some(from)),
    };
    Ok(MdPointResult {
        lambda,
        delta,
        path: name,
        from,
        force,
    })
}

/// The forces Fbar at every interference of `deltas` on `path`, on one curve (the curve's
/// landmarks are computed once).
pub fn forces(curve: &MdCurve, deltas: &[f64], path: Path) -> Result<Vec<f64>, ModelError> {
    if let Path::Retract { from } = path {
        check_delta("from", from)?;
        // retracting, the interference stays at or below the excursion's extreme: a
        // deeper point is on the approach (its force would be labelled a retraction's)
        if let Some(&delta) = deltas.iter().find(|&&d| d > from) {
            return Err(ModelError::argument(
                "delta",
                num(delta),
                format!(
                    "at most the excursion's extreme from = {} on a retraction (a deeper point is on the approach)",
                    num(from)
                ),
            ));
        }
    }
    deltas
        .iter()
        .map(|&d| Ok(curve.force(check_delta("delta", d)?, path)?))
        .collect()
}
