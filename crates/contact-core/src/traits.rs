use crate::error::LawError;
use std::sync::Arc;

/// Where a hysteretic law is on its loop. Adhesive contact is path dependent: between
/// jump-out and jump-in the force depends on whether the bodies came from far away or
/// from contact.
///
/// `from` is the extreme point of the current excursion in the coordinate of the law:
/// an interference (m) for sphere and asperity laws, a separation (m) for surface laws.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Path {
    /// Coming from far away (or reloading).
    Approach,
    /// Retracting after reaching `from`.
    Retract {
        /// The extreme of the excursion: the largest interference (sphere, asperity) or the
        /// smallest separation (surface) reached.
        from: f64,
    },
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
    /// `radius` (m). Declaring them only makes quadrature over asperity heights cheaper
    /// (it splits there); the error control of the quadrature does not depend on them.
    /// Keep each kind of kink at the same position for every radius, `None` where it is
    /// absent.
    fn kinks(&self, radius: f64) -> Result<Vec<Option<f64>>, LawError> {
        let _ = radius;
        Ok(Vec::new())
    }

    /// Radius a (m) of the contact (the region where the surfaces touch, not the cohesive
    /// zone around it) of a sphere of `radius` (m) at `delta` (m) on `path`; 0 out of
    /// contact. By default the Hertz geometry, a = sqrt(R delta) for delta > 0, which is
    /// the contact of Hertz and of DMT; laws whose adhesion widens the contact (JKR,
    /// Maugis-Dugdale) override it.
    fn contact_radius(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        let _ = path;
        Ok(if delta > 0.0 {
            (radius * delta).sqrt()
        } else {
            0.0
        })
    }

    /// A cheaper form of this law whose force errs by at most `rel_force` relative to
    /// max(|F|, pi w R) (R the sphere's radius; for a law without adhesion, relative to
    /// |F|), or None if it has none that accurate. A rough surface asks for it with what
    /// its quadrature tolerates (a fast accuracy mode); jumps, kinks and the contact radius
    /// must stay those of the law itself. By default None: the law is always evaluated.
    fn within(&self, rel_force: f64) -> Option<std::sync::Arc<dyn AdhesionLaw + Send + Sync>> {
        let _ = rel_force;
        None
    }

    /// An upper bound T (N, >= 0) on the tension of a sphere of `radius` (m) anywhere on
    /// the law's curves: -F(delta, path) <= T for every interference and path (for a
    /// Maugis-Dugdale law the load-controlled pull-off, at most 2 pi w R, the DMT limit).
    /// A rough surface uses it to end a pull-out scan once no asperity left in contact can
    /// pull harder than what was found. By default None (unknown): the scan runs to the
    /// end.
    fn max_tension(&self, radius: f64) -> Option<f64> {
        let _ = radius;
        None
    }
}

/// Deformed state of an asperity after loading to `delta_max` (paper eqs 4-5).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct PlasticState {
    /// Largest interference reached (m).
    pub delta_max: f64,
    /// Permanent loss of height delta_res (m); zero below yield.
    pub delta_res: f64,
    /// Tip radius after unloading R_res (m); the initial radius below yield.
    pub r_res: f64,
    /// True when delta_max lies beyond the range of the fits the law was built on.
    pub extrapolated: bool,
    /// The elastic displacement delta_a (m) the adhesive stresses added to the contact at
    /// delta_max, for a law whose state the adhesive contact drives (theory 2.8): its
    /// fits were read at the Hertz interference delta_max + delta_a. Zero for a law
    /// uncoupled from adhesion.
    pub adhesive_displacement: f64,
}

impl PlasticState {
    /// The state of a law uncoupled from adhesion (no adhesive displacement): what a user's
    /// law returns from [`PlasticityLaw::state`], proof against fields added later.
    pub fn new(delta_max: f64, delta_res: f64, r_res: f64, extrapolated: bool) -> Self {
        Self {
            delta_max,
            delta_res,
            r_res,
            extrapolated,
            adhesive_displacement: 0.0,
        }
    }
}

/// Which body of a contact pair governs plasticity: the one that yields first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum YieldingBody {
    /// Body 1, the asperity-carrying surface.
    Asperity,
    /// Body 2, the counter-surface.
    Counter,
}

/// Plasticity of one asperity of given initial radius, uncoupled from adhesion.
///
/// A law is built from the contact pair (`contact_core::Pair`: both moduli, E*, the
/// radius), so a force-based law from the literature (Kogut-Etsion, Jackson-Green) can
/// turn its published force into the effective radius the adhesion law sees through E*.
/// Besides the state, a law declares what the quadrature over asperity heights and the
/// physics guards need to know: where its state jumps or bends ([`Self::breaks`],
/// [`Self::kinks`]), the range its fits were identified on ([`Self::fit_range`]) and which
/// body yields ([`Self::yielding_body`]).
pub trait PlasticityLaw {
    /// Initial tip radius R (m).
    fn radius(&self) -> f64;
    /// Yield onset: the critical interference delta_CP (m); `f64::INFINITY` if the law
    /// never yields.
    fn delta_cp(&self) -> f64;
    /// State after loading to `delta_max` (m).
    fn state(&self, delta_max: f64) -> PlasticState;
    /// Effective radius R_eff (m) of the deformed asperity at the current interference
    /// `delta` (m) (paper eq 12); equals `state.r_res` at and below `state.delta_res`.
    fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64;

    /// The largest effective radius (m) an asperity in `state` presents on any path that
    /// does not load it further (between delta_res and delta_max), or None if the law
    /// does not know it (the default). Bounds the tension of an unloading asperity
    /// ([`AdhesionLaw::max_tension`] on that radius).
    fn radius_bound(&self, state: &PlasticState) -> Option<f64> {
        let _ = state;
        None
    }

    /// Values of delta_max (m), besides delta_CP, at which the state or the loading force
    /// jumps or has a kink (a regime boundary of a piecewise fit, such as omega = 6 of
    /// Kogut-Etsion). Declared breaks are split points of the height quadrature, which then
    /// never hunts for them; an undeclared one costs time, never accuracy.
    fn breaks(&self) -> Vec<f64> {
        Vec::new()
    }

    /// Interferences (m) where R_eff(delta) at `state` is continuous but not smooth,
    /// position-stable as in [`AdhesionLaw::kinks`] (`None` where a kind is absent); an
    /// optional speed-up like [`Self::breaks`].
    fn kinks(&self, state: &PlasticState) -> Vec<Option<f64>> {
        let _ = state;
        Vec::new()
    }

    /// The range of omega = delta_max/delta_CP over which the law's fits were identified
    /// (finite-element results); `None` for a law with no fitted range (elastic). Results
    /// beyond it are extrapolations, which the guards report.
    fn fit_range(&self) -> Option<(f64, f64)> {
        None
    }

    /// The body of the pair that yields first and governs plasticity (`None` if neither
    /// yields).
    fn yielding_body(&self) -> Option<YieldingBody> {
        None
    }

    /// The interference delta_max (m) at which the fits are read at omega delta_CP: omega
    /// delta_CP itself for a law driven by the geometric interference (the default), less
    /// the adhesive displacement for one driven by the adhesive contact. The guards' fitted
    /// range (`beyond_fit_range`) is checked through it.
    fn fit_interference(&self, omega: f64) -> f64 {
        omega * self.delta_cp()
    }

    /// Whether the law's state is driven by the adhesive contact itself (the
    /// `adhesion_coupled` law) rather than by the geometric interference alone: such a law
    /// does not assume plasticity uncoupled from adhesion (the guard
    /// `adhesion_yields_asperity` is then no breach of its validity), and an asperity in
    /// adhesive contact stays on the adhesion law's contact branch while it loads. False by
    /// default.
    fn couples_adhesion(&self) -> bool {
        false
    }
}

impl<T: AdhesionLaw + ?Sized> AdhesionLaw for &T {
    fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        (**self).force(radius, delta, path)
    }
    fn max_tension(&self, radius: f64) -> Option<f64> {
        (**self).max_tension(radius)
    }
    fn contact_radius(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        (**self).contact_radius(radius, delta, path)
    }
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
        (**self).jumps(radius)
    }
    fn jump_in(&self, radius: f64) -> Result<f64, LawError> {
        (**self).jump_in(radius)
    }
    fn kinks(&self, radius: f64) -> Result<Vec<Option<f64>>, LawError> {
        (**self).kinks(radius)
    }
}

impl<T: PlasticityLaw + ?Sized> PlasticityLaw for &T {
    fn radius(&self) -> f64 {
        (**self).radius()
    }
    fn radius_bound(&self, state: &PlasticState) -> Option<f64> {
        (**self).radius_bound(state)
    }
    fn delta_cp(&self) -> f64 {
        (**self).delta_cp()
    }
    fn state(&self, delta_max: f64) -> PlasticState {
        (**self).state(delta_max)
    }
    fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64 {
        (**self).effective_radius(state, delta)
    }
    fn breaks(&self) -> Vec<f64> {
        (**self).breaks()
    }
    fn kinks(&self, state: &PlasticState) -> Vec<Option<f64>> {
        (**self).kinks(state)
    }
    fn fit_range(&self) -> Option<(f64, f64)> {
        (**self).fit_range()
    }
    fn yielding_body(&self) -> Option<YieldingBody> {
        (**self).yielding_body()
    }
    fn couples_adhesion(&self) -> bool {
        (**self).couples_adhesion()
    }
    fn fit_interference(&self, omega: f64) -> f64 {
        (**self).fit_interference(omega)
    }
}

macro_rules! plasticity_through {
    ($ptr:ident) => {
        impl<T: PlasticityLaw + ?Sized> PlasticityLaw for $ptr<T> {
            fn radius(&self) -> f64 {
                (**self).radius()
            }
            fn radius_bound(&self, state: &PlasticState) -> Option<f64> {
                (**self).radius_bound(state)
            }
            fn delta_cp(&self) -> f64 {
                (**self).delta_cp()
            }
            fn state(&self, delta_max: f64) -> PlasticState {
                (**self).state(delta_max)
            }
            fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64 {
                (**self).effective_radius(state, delta)
            }
            fn breaks(&self) -> Vec<f64> {
                (**self).breaks()
            }
            fn kinks(&self, state: &PlasticState) -> Vec<Option<f64>> {
                (**self).kinks(state)
            }
            fn fit_range(&self) -> Option<(f64, f64)> {
                (**self).fit_range()
            }
            fn yielding_body(&self) -> Option<YieldingBody> {
                (**self).yielding_body()
            }
            fn couples_adhesion(&self) -> bool {
                (**self).couples_adhesion()
            }
            fn fit_interference(&self, omega: f64) -> f64 {
                (**self).fit_interference(omega)
            }
        }
    };
}

macro_rules! adhesion_through {
    ($ptr:ident) => {
        impl<T: AdhesionLaw + ?Sized> AdhesionLaw for $ptr<T> {
            fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
                (**self).force(radius, delta, path)
            }
            fn max_tension(&self, radius: f64) -> Option<f64> {
                (**self).max_tension(radius)
            }
            fn contact_radius(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
                (**self).contact_radius(radius, delta, path)
            }
            fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
                (**self).jumps(radius)
            }
            fn jump_in(&self, radius: f64) -> Result<f64, LawError> {
                (**self).jump_in(radius)
            }
            fn kinks(&self, radius: f64) -> Result<Vec<Option<f64>>, LawError> {
                (**self).kinks(radius)
            }
        }
    };
}

// A law behind a pointer is a law: the model library keeps the laws a registry builds as
// `Arc<dyn ... + Send + Sync>`.
plasticity_through!(Box);
plasticity_through!(Arc);
adhesion_through!(Box);
adhesion_through!(Arc);

/// History of one asperity: the largest interference it has ever reached (m). A value
/// at or below zero means it has never been pressed (it may have been in adhesive contact:
/// an adhesive sphere jumps in at a negative interference).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AsperityHistory {
    /// Largest interference reached (m).
    pub delta_max: f64,
}

impl AsperityHistory {
    /// An asperity that has never been in contact (delta_max = -infinity: not even the
    /// adhesive contact of a jump-in at a negative interference).
    pub const VIRGIN: Self = Self {
        delta_max: f64::NEG_INFINITY,
    };
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

    /// Interference delta_CP (m) at which the asperity starts to yield (infinite if never).
    fn delta_cp(&self) -> f64;

    /// Initial tip radius R (m): interferences beyond it leave contact mechanics' ground.
    fn radius(&self) -> f64;

    /// Plastic state for a history.
    fn plastic_state(&self, history: AsperityHistory) -> PlasticState;

    /// Radius (m) of the contact spot at interference `delta` (m) given the `history` and
    /// `path` (as [`Self::force`]); 0 out of contact. By default the Hertz geometry of the
    /// initial radius; composed asperities ask their adhesion law on the effective sphere.
    fn contact_radius(
        &self,
        delta: f64,
        history: AsperityHistory,
        path: Path,
    ) -> Result<f64, LawError> {
        let _ = (history, path);
        Ok(if delta > 0.0 {
            (self.radius() * delta).sqrt()
        } else {
            0.0
        })
    }

    /// Values of delta_max (m) where the asperity's state or loading force jumps or bends:
    /// delta_CP first (if it yields), then the plasticity law's declared breaks
    /// ([`PlasticityLaw::breaks`]). Split points of quadratures over heights.
    fn plastic_breaks(&self) -> Vec<f64> {
        let dcp = self.delta_cp();
        if dcp.is_finite() {
            vec![dcp]
        } else {
            Vec::new()
        }
    }

    /// The omega range of the plasticity law's fits ([`PlasticityLaw::fit_range`]).
    fn fit_range(&self) -> Option<(f64, f64)> {
        None
    }

    /// The interference (m) at which the fits are read at omega delta_CP
    /// ([`PlasticityLaw::fit_interference`]); omega delta_CP by default.
    fn fit_interference(&self, omega: f64) -> f64 {
        omega * self.delta_cp()
    }

    /// The body that yields first ([`PlasticityLaw::yielding_body`]).
    fn yielding_body(&self) -> Option<YieldingBody> {
        None
    }

    /// Jump-in and jump-out interferences (m) of an asperity with this history
    /// (including its permanent loss of height).
    fn jumps(&self, history: AsperityHistory) -> Result<Jumps, LawError>;

    /// Jump-in interference alone (m); override when it is cheaper than [`Self::jumps`].
    fn jump_in(&self, history: AsperityHistory) -> Result<f64, LawError> {
        Ok(self.jumps(history)?.jump_in)
    }

    /// Interferences (m) where the force of an asperity with this history has a kink,
    /// position-stable as in [`AdhesionLaw::kinks`]; an optional speed-up, never needed
    /// for correctness.
    fn kinks(&self, history: AsperityHistory) -> Result<Vec<Option<f64>>, LawError> {
        let _ = history;
        Ok(Vec::new())
    }

    /// The `i`-th entry of [`Self::kinks`] alone (`None` where that kind is absent or the
    /// list is shorter): what a search for one kind of kink over asperity heights
    /// evaluates many times. Override when one kink is cheaper than the list; it must
    /// equal `self.kinks(history)?.get(i).copied().flatten()`.
    fn kink(&self, i: usize, history: AsperityHistory) -> Result<Option<f64>, LawError> {
        Ok(self.kinks(history)?.get(i).copied().flatten())
    }

    /// An upper bound (N, >= 0) on the tension of an asperity with this `history` on any
    /// path that does not load it beyond `history.delta_max` (-F <= bound), or None if
    /// unknown (the default). See [`AdhesionLaw::max_tension`].
    fn max_tension(&self, history: AsperityHistory) -> Option<f64> {
        let _ = history;
        None
    }
}

/// The approach above the deepest separation a history reached
/// ([`SurfaceLaw::above_deepest`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct AboveDeepest {
    /// The deepest separation D (m).
    pub deepest: f64,
    /// The approach work above it, integral from D to the reach of p_L (J/m^2).
    pub work: Estimate,
    /// An upper bound on the approach pressure p_L(d) at every d > D (Pa).
    pub pressure_bound: f64,
}

/// The approach work over a stretch of virgin loading ([`SurfaceLaw::virgin_work`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct VirginWork {
    /// The integral of p_L over the stretch (J/m^2).
    pub work: Estimate,
    /// p_L at its lower end from the surface's tables (Pa): an approximation within the
    /// tables' tolerance, for bracketing, not an evaluation.
    pub pressure: f64,
}

/// A value with its error estimate (same units).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Its estimated absolute error (>= 0).
    pub error: f64,
}

/// The length scales (m) of a surface law that searches over the separation size their
/// samples by: nothing of interest in the law is narrower than `finest`, `roughness` is
/// the scale of its bulk (sigma_s for a Greenwood-Williamson surface), and below `deepest`
/// the law leaves its ground (asperities pressed beyond their own radius).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct LengthScales {
    /// The narrowest feature (jump distances, interaction range, elastic recovery).
    pub finest: f64,
    /// The bulk scale.
    pub roughness: f64,
    /// The deepest separation the law is meant for.
    pub deepest: f64,
}

/// The contact law of a rough surface against a flat: pressure (Pa, compressive > 0)
/// against the separation d (m) of the mean plane of asperity heights from the flat.
///
/// History is data: [`SurfaceLaw::load`] returns a new history and never mutates.
///
/// A law is `Sync` and its history `Send + Sync`: the switch model evaluates independent
/// pressures (a quadrature panel's nodes, the pull-out candidates) in parallel. A law is a
/// function of its arguments, so this costs nothing; a law that caches must do so behind a
/// lock. Histories compare with `PartialEq`: a cycle that starts from the same history as
/// the one before repeats it, and is not computed again.
pub trait SurfaceLaw: Sync {
    /// What the surface remembers of its loading.
    type History: Clone + std::fmt::Debug + PartialEq + Send + Sync;

    /// History of a surface never pressed.
    fn virgin(&self) -> Self::History;

    /// Pressure (Pa) at separation `d` (m) given `history` and `path`; on
    /// `Path::Retract { from }`, `from` is the smallest separation of the current
    /// excursion.
    fn pressure(&self, d: f64, history: &Self::History, path: Path) -> Result<f64, LawError> {
        Ok(self.pressure_estimate(d, history, path)?.value)
    }

    /// Pressure (Pa) with the estimated error of its evaluation (quadrature), so that
    /// callers can report the error of what they derive from it.
    fn pressure_estimate(
        &self,
        d: f64,
        history: &Self::History,
        path: Path,
    ) -> Result<Estimate, LawError>;

    /// A cheaper pressure (Pa) for scans that only rank samples (accurate to about 1e-3 of
    /// the forces summed); by default the pressure itself.
    fn pressure_scan(&self, d: f64, history: &Self::History, path: Path) -> Result<f64, LawError> {
        self.pressure(d, history, path)
    }

    /// A rough pressure (Pa) with its error estimate, cheaper than [`Self::pressure_scan`],
    /// for a search that needs only to know where the pressure is surely compressive
    /// (value above a few times its estimate): a pull-out scan then evaluates the
    /// compressive start of the retraction roughly. None (the default) when the surface
    /// has nothing cheaper than its scan pressure.
    fn pressure_rough(
        &self,
        d: f64,
        history: &Self::History,
        path: Path,
    ) -> Result<Option<Estimate>, LawError> {
        let _ = (d, history, path);
        Ok(None)
    }

    /// History after loading to separation `d` (m).
    fn load(&self, history: &Self::History, d: f64) -> Self::History;

    /// Separation (m) above which the pressure on `path` is zero (below the law's stated
    /// tail bound) for this history: on `Path::Approach`, where the first asperity
    /// touches; on `Path::Retract`, where the last one lets go.
    fn reach(&self, history: &Self::History, path: Path) -> Result<f64, LawError>;

    /// The law's length scales for this history (see [`LengthScales`]).
    fn length_scales(&self, history: &Self::History) -> Result<LengthScales, LawError>;

    /// Separations (m) where the approach pressure has a kink for this history (for
    /// instance the deepest separation reached, where reloading turns into virgin
    /// loading); an optional speed-up of integrals over d.
    fn kinks(&self, history: &Self::History) -> Vec<f64> {
        let _ = history;
        Vec::new()
    }

    /// The approach above the deepest separation D the `history` reached
    /// ([`AboveDeepest`]): the work of the approach pressure from the first touch down to
    /// D, integral from D to the reach of p_L(d) dd, with its error estimate, to within
    /// max(`abs`, `rel_of_abs` x the integral of |p_L|), and a bound on p_L above D. A
    /// surface that can integrate it the other way round (over its asperities, each
    /// reloading up to its own largest interference) saves eq 17 the approach above D,
    /// which every cycle after the first crosses. None (the default) when it cannot, or
    /// when the history has no single deepest separation.
    fn above_deepest(
        &self,
        history: &Self::History,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<Option<AboveDeepest>, LawError> {
        let _ = (history, abs, rel_of_abs);
        Ok(None)
    }

    /// The approach work from `lo` to `hi` (m, lo < hi), integral of p_L, where the approach
    /// is the virgin loading (at or below the deepest separation the `history` reached, or
    /// anywhere on a never-pressed surface), to within max(`abs`, `rel_of_abs` x the
    /// integral of |p_L|), with a tabulated p_L(lo) ([`VirginWork`]). A surface that
    /// tabulates its asperities' virgin loading answers without a pressure evaluation,
    /// which is what eq 17's search below the deepest point asks for. None (the default)
    /// when it cannot, or when `hi` lies above the deepest separation.
    fn virgin_work(
        &self,
        history: &Self::History,
        lo: f64,
        hi: f64,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<Option<VirginWork>, LawError> {
        let _ = (history, lo, hi, abs, rel_of_abs);
        Ok(None)
    }

    /// A bound B (Pa, >= 0) on the tension at every separation from `d` (m) outward on
    /// `path`: p(d') >= -B for all d' >= d, or None if the law cannot bound it (the
    /// default). A pull-out search stops sampling once B is below the tension it has
    /// already found: nothing further out can pull harder.
    fn tension_bound(
        &self,
        d: f64,
        history: &Self::History,
        path: Path,
    ) -> Result<Option<f64>, LawError> {
        let _ = (d, history, path);
        Ok(None)
    }

    /// Whether a long computation on this surface may go on: `Err` (a
    /// [`crate::CoreError::Cancelled`]) once the caller of the computation has stopped it.
    /// Loops that run long without evaluating the surface (the integration of a plate's
    /// flight) poll it at every step. Never stopped by default; a front end's wrapper
    /// answers for its caller.
    fn check_cancelled(&self) -> Result<(), LawError> {
        Ok(())
    }
}
