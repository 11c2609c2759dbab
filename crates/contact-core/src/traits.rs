use crate::error::LawError;
use serde::{Deserialize, Serialize};

/// Where a hysteretic law is on its loop. Adhesive contact is path dependent: between
/// jump-out and jump-in the force depends on whether the bodies came from far away or
/// from contact.
///
/// `from` is the extreme point of the current excursion in the coordinate of the law:
/// an interference (m) for sphere and asperity laws, a separation (m) for surface laws.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Path {
    /// Coming from far away (or reloading).
    Approach,
    /// Retracting after reaching `from`.
    Retract { from: f64 },
}

/// Interferences (m) at which a sphere jumps into contact on approach and out of contact
/// on retraction. The force is discontinuous there, which quadrature must know.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jumps {
    /// Approaching, the force is zero below this interference.
    pub jump_in: f64,
    /// Retracting, the force drops to zero below this interference.
    pub jump_out: f64,
}

/// An adhesive law of one *elastic* sphere of radius R against a flat.
///
/// The law holds the material constants (modulus, work of adhesion, range); the radius is
/// an argument because the elasto-plastic asperity changes it with the interference
/// (paper eq 12).
pub trait AdhesionLaw {
    /// Normal force (N, compressive > 0) at interference `delta` (m) for a sphere of
    /// `radius` (m) on `path`.
    fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError>;

    /// Jump-in and jump-out interferences (m) for a sphere of `radius` (m).
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError>;

    /// Jump-in interference alone (m); override when it is cheaper than [`Self::jumps`].
    fn jump_in(&self, radius: f64) -> Result<f64, LawError> {
        Ok(self.jumps(radius)?.jump_in)
    }

    /// Interferences (m) where the force is continuous but not smooth, for a sphere of
    /// `radius` (m). Quadrature over asperity heights splits there. Keep each kind of kink
    /// at the same position for every radius; NaN marks one that is absent.
    fn kinks(&self, radius: f64) -> Result<Vec<f64>, LawError> {
        let _ = radius;
        Ok(Vec::new())
    }
}

/// Deformed state of an asperity after loading to `delta_max` (paper eqs 4-5).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlasticState {
    /// Largest interference reached (m).
    pub delta_max: f64,
    /// Permanent loss of height delta_res (m); zero below yield.
    pub delta_res: f64,
    /// Tip radius after unloading R_res (m); the initial radius below yield.
    pub r_res: f64,
    /// True when delta_max lies beyond the range of the fits the law was built on.
    pub extrapolated: bool,
}

/// Plasticity of one asperity of given initial radius, uncoupled from adhesion.
pub trait PlasticityLaw {
    /// Initial tip radius R (m).
    fn radius(&self) -> f64;
    /// Yield onset: the critical interference delta_CP (m); `f64::INFINITY` if the law
    /// never yields.
    fn critical_interference(&self) -> f64;
    /// State after loading to `delta_max` (m).
    fn state(&self, delta_max: f64) -> PlasticState;
    /// Effective radius R_eff (m) of the deformed asperity at the current interference
    /// `delta` (m) (paper eq 12); equals `state.r_res` at and below `state.delta_res`.
    fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64;
}

/// History of one asperity: the largest interference it has ever reached (m). A value
/// at or below zero means it has never been pressed.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default, Serialize, Deserialize)]
pub struct AsperityHistory {
    pub delta_max: f64,
}

impl AsperityHistory {
    /// An asperity that has never been in contact.
    pub const VIRGIN: Self = Self { delta_max: 0.0 };
}

/// One asperity with a memory: the force at an interference, given its history and path.
pub trait AsperityModel {
    /// Force (N) at interference `delta` (m), given the `history` before the current
    /// excursion and the `path`. On `Path::Approach` an interference beyond the history
    /// loads the asperity further (it yields again); on `Path::Retract { from }` the
    /// asperity unloads from `from`, which counts as part of its history.
    fn force(&self, delta: f64, history: AsperityHistory, path: Path) -> Result<f64, LawError>;

    /// History after loading to `delta` (m). History only deepens.
    fn load(&self, history: AsperityHistory, delta: f64) -> AsperityHistory {
        AsperityHistory {
            delta_max: history.delta_max.max(delta),
        }
    }

    /// Interference (m) at which the asperity starts to yield.
    fn yield_interference(&self) -> f64;

    /// Plastic state for a history.
    fn plastic_state(&self, history: AsperityHistory) -> PlasticState;

    /// Jump-in and jump-out interferences (m) of an asperity with this history
    /// (including its permanent loss of height).
    fn jumps(&self, history: AsperityHistory) -> Result<Jumps, LawError>;

    /// Jump-in interference alone (m); override when it is cheaper than [`Self::jumps`].
    fn jump_in(&self, history: AsperityHistory) -> Result<f64, LawError> {
        Ok(self.jumps(history)?.jump_in)
    }

    /// Interferences (m) where the force of an asperity with this history has a kink.
    fn kinks(&self, history: AsperityHistory) -> Result<Vec<f64>, LawError> {
        let _ = history;
        Ok(Vec::new())
    }
}

/// The contact law of a rough surface against a flat: pressure (Pa, compressive > 0)
/// against the separation d (m) of the mean plane of asperity heights from the flat.
///
/// History is data: [`SurfaceLaw::load`] returns a new history and never mutates.
pub trait SurfaceLaw {
    /// What the surface remembers of its loading.
    type History: Clone + std::fmt::Debug;

    /// History of a surface never pressed.
    fn virgin(&self) -> Self::History;

    /// Pressure (Pa) at separation `d` (m) given `history` and `path`; on
    /// `Path::Retract { from }`, `from` is the smallest separation of the current
    /// excursion.
    fn pressure(&self, d: f64, history: &Self::History, path: Path) -> Result<f64, LawError>;

    /// History after loading to separation `d` (m).
    fn load(&self, history: &Self::History, d: f64) -> Self::History;

    /// Separation (m) above which the pressure is below the law's stated tail bound on
    /// both paths for this history: integrals over d may start there.
    fn reach(&self, history: &Self::History) -> Result<f64, LawError>;

    /// A length (m) over which the pressure changes appreciably (the roughness, for a
    /// Greenwood-Williamson surface); integrals over d size their panels by it.
    fn length_scale(&self) -> f64;

    /// Separations (m) where the pressure has a kink for this history (for instance the
    /// deepest separation reached, where reloading turns into virgin loading).
    fn kinks(&self, history: &Self::History) -> Vec<f64> {
        let _ = history;
        Vec::new()
    }
}
