//! A second elasto-plastic law family from the literature: Kogut-Etsion loading
//! (Kogut & Etsion 2002) with Etsion-Kligerman-Kadin unloading (Etsion, Kligerman & Kadin
//! 2005), seen by the adhesion law through an effective radius derived from the published
//! forces (`docs/theory.md` section 2.7).

use crate::error::PlasticError;
use crate::etsion_kadin::{YieldModulus, FIT_RANGE_MAX};
use crate::onset;
use contact_core::{Pair, PlasticState, PlasticityLaw, YieldingBody};
use std::f64::consts::PI;

/// delta_max/delta_c where Kogut & Etsion's first elastic-plastic fit hands over to the
/// second (the plastic zone reaches the surface); the loading force jumps there by
/// 1.40 * 6^1.263 / (1.03 * 6^1.425) - 1 = +1.68 %, the area by +2.9 %.
pub const KE_SECOND_REGIME: f64 = 6.0;

/// delta_max/delta_c where Kogut & Etsion's contact becomes fully plastic (mean pressure
/// = hardness 2.8 S_Y, area 2 pi R delta); also the upper end of the fits of both papers
/// ([`FIT_RANGE_MAX`]).
pub const KE_FULLY_PLASTIC: f64 = FIT_RANGE_MAX;

/// Hardness over yield stress, H = 2.8 S_Y, of Kogut & Etsion's fully plastic regime.
pub const KE_HARDNESS_FACTOR: f64 = 2.8;

/// Above this delta_max/delta_c the radius crossings ([`KogutEtsion::radius_crossings`])
/// are not searched: there the EKK residual radius exceeds the loading radius by far for
/// any E/S_Y below 10^8.
const CROSSING_SEARCH_MAX: f64 = 1e4;

/// At most this many crossings are kept (a handful occur for E/S_Y up to 10^4).
const MAX_CROSSINGS: usize = 8;

/// The coefficient C of the yield onset delta_c = R (pi C S_Y / (2 E_1))^2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum YieldOnset {
    /// C_v = 1.295 exp(0.736 nu), the paper's eq 1 (the Etsion-Kadin law's onset; the
    /// constant is Jackson & Green's 2005 fit): both law families then share delta_CP.
    PaperEq1,
    /// Kogut & Etsion's own K H / S_Y = 2.8 (0.454 + 0.41 nu) (their delta_c with
    /// K = 0.454 + 0.41 nu of Chang, Etsion & Bogy 1987 and H = 2.8 S_Y). Within 0.04 % of
    /// C_v at nu = 0.3; 1.9 % below it at nu = 0, 1.1 % at nu = 0.5.
    KogutEtsion2002,
}

impl YieldOnset {
    /// The coefficient C at Poisson ratio `nu`.
    pub fn coefficient(self, nu: f64) -> f64 {
        match self {
            YieldOnset::PaperEq1 => 1.295 * (0.736 * nu).exp(),
            YieldOnset::KogutEtsion2002 => KE_HARDNESS_FACTOR * (0.454 + 0.41 * nu),
        }
    }

    /// The scene spelling: `paper_eq1` or `kogut_etsion_2002`.
    pub fn as_str(self) -> &'static str {
        match self {
            YieldOnset::PaperEq1 => "paper_eq1",
            YieldOnset::KogutEtsion2002 => "kogut_etsion_2002",
        }
    }
}

/// Kogut-Etsion loading with Etsion-Kligerman-Kadin unloading, a [`PlasticityLaw`]
/// (`docs/theory.md` section 2.7). With omega = delta_max/delta_c:
///
/// * **Loading** (Kogut & Etsion 2002, J. Appl. Mech. 69:657-662): P/P_c = omega^1.5,
///   A/A_c = omega (Hertz, omega <= 1); 1.03 omega^1.425, 0.93 omega^1.136 (1 < omega <= 6);
///   1.40 omega^1.263, 0.94 omega^1.146 (6 < omega <= 110); fully plastic beyond 110,
///   P = 2.8 S_Y * 2 pi R delta, A = 2 pi R delta, i.e. P/P_c = 8.4 omega / C and
///   A/A_c = 2 omega. P_c = (4/3) E* R^(1/2) delta_c^(3/2) and A_c = pi R delta_c are the
///   Hertz values at delta_c (with E*, whatever the reading of eq 1).
/// * **Unloading** (Etsion, Kligerman & Kadin 2005, Int. J. Solids Struct. 42:3716-3729):
///   delta_res/delta_max = [1 - omega^-0.28][1 - omega^-0.69] (the paper's eq 4),
///   R_res/R = 1 + 1.275 (S_Y/E)^0.216 (omega - 1) (eq 5),
///   P/P_max = x^n, x = (delta - delta_res)/(delta_max - delta_res), n = 1.5 omega^-0.0331.
/// * **Effective radius** (derived; the adhesion law sees a Hertz sphere of radius R_eff at
///   delta - delta_res): R_L = [3 P(delta_max) / (4 E* (delta_max - delta_res)^(3/2))]^2
///   on loading, so that Hertz reproduces Kogut-Etsion's force; on unloading
///   R_eff = min(R_L x^(2n - 3), r_res), which reproduces EKK's force where R_L x^(2n-3)
///   is below r_res and is the residual profile's radius below that kink;
///   r_res = max(R_res, R_L) (the two fits contradict each other near yield, where
///   Kogut-Etsion's 3 % jump makes R_L > R_res).
///
/// The loading force jumps at omega = 1 (+3 %), 6 (+1.68 %) and 110 (+7.9 %), declared as
/// [`PlasticityLaw::breaks`]; beyond omega = 110 the state is flagged `extrapolated`.
///
/// ```
/// use asperity_plastic::{ElastoPlasticAsperity, KogutEtsion, YieldModulus};
/// use contact_core::{paper, AsperityHistory, AsperityModel, Material, Pair, Path, PlasticityLaw};
/// use maugis_kim::Hertz;
/// let pair = Pair::new(Material::new(paper::RU)?, None, paper::RADIUS)?;
/// let ke = KogutEtsion::new(&pair, YieldModulus::Composite)?;
/// let asperity = ElastoPlasticAsperity::new(ke, Hertz::new(pair.k())?);
/// // loaded to 10 delta_c through the Hertz law: Kogut-Etsion's 1.40 * 10^1.263 P_c
/// let dmax = 10.0 * ke.delta_cp();
/// let f = asperity.force(dmax, AsperityHistory::VIRGIN, Path::Approach)?;
/// let p_ke = 1.40 * 10f64.powf(1.263) * ke.critical_force();
/// assert!((f / p_ke - 1.0).abs() < 1e-12);
/// // half-way back it follows EKK's unloading curve P/P_max = x^(1.5 * 10^-0.0331)
/// let st = ke.state(dmax);
/// let back = asperity.force(0.5 * (st.delta_res + dmax), AsperityHistory::VIRGIN, Path::Retract { from: dmax })?;
/// assert!((back / f - 0.5f64.powf(1.5 * 10f64.powf(-0.0331))).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KogutEtsion {
    radius: f64,
    delta_cp: f64,
    e_star: f64,
    /// P_c = (4/3) E* R^(1/2) delta_c^(3/2) (N).
    critical_force: f64,
    /// 1.275 (S_Y/E)^0.216 of EKK's residual radius (the yielding body's own E).
    k_res: f64,
    /// C of the onset (C_v or 2.8 K) for the yielding body.
    coefficient: f64,
    body: YieldingBody,
    modulus: YieldModulus,
    onset: YieldOnset,
    /// omega where R_L crosses EKK's R_res inside a fit regime (kinks of the state),
    /// ascending; unused entries are infinite.
    crossings: [f64; MAX_CROSSINGS],
}

impl KogutEtsion {
    /// The law of `pair`, yield onset from the paper's eq 1 with the modulus chosen by
    /// `modulus` (the same delta_CP as [`crate::EtsionKadin`]). With a counter material of
    /// finite yield stress, the body with the smaller delta_c (the one that yields first)
    /// governs: its S_Y, nu and E (in eq 1 as printed, and in EKK's S_Y/E).
    pub fn new(pair: &Pair, modulus: YieldModulus) -> Result<Self, PlasticError> {
        Self::with_onset(pair, modulus, YieldOnset::PaperEq1)
    }

    /// The law with the yield-onset coefficient chosen by `onset`.
    pub fn with_onset(
        pair: &Pair,
        modulus: YieldModulus,
        onset: YieldOnset,
    ) -> Result<Self, PlasticError> {
        let o = onset::governing(pair, modulus, |nu| onset.coefficient(nu))?;
        let m = o.material;
        let radius = pair.radius();
        let e_star = pair.e_star();
        let mut law = Self {
            radius,
            delta_cp: o.delta_cp,
            e_star,
            critical_force: 4.0 / 3.0 * e_star * radius.sqrt() * o.delta_cp * o.delta_cp.sqrt(),
            k_res: 1.275 * (m.yield_stress() / m.youngs_modulus()).powf(0.216),
            coefficient: o.coefficient,
            body: o.body,
            modulus,
            onset,
            crossings: [f64::INFINITY; MAX_CROSSINGS],
        };
        law.crossings = law.find_crossings();
        Ok(law)
    }

    /// The reading of eq 1 in use.
    pub fn yield_modulus(&self) -> YieldModulus {
        self.modulus
    }

    /// The onset coefficient formula in use.
    pub fn yield_onset(&self) -> YieldOnset {
        self.onset
    }

    /// The body that yields first and governs plasticity.
    pub fn yielding_body(&self) -> YieldingBody {
        self.body
    }

    /// The onset coefficient C of the yielding body (C_v or 2.8 K).
    pub fn onset_coefficient(&self) -> f64 {
        self.coefficient
    }

    /// 1.275 (S_Y/E)^0.216 of EKK's residual radius.
    pub fn k_res(&self) -> f64 {
        self.k_res
    }

    /// E* of the pair (Pa): the modulus that turns forces into radii.
    pub fn e_star(&self) -> f64 {
        self.e_star
    }

    /// P_c = (4/3) E* R^(1/2) delta_c^(3/2) (N): the Hertz force at delta_c, in either
    /// reading of eq 1 (with E* in eq 1 it equals (2/3) pi C S_Y R delta_c).
    pub fn critical_force(&self) -> f64 {
        self.critical_force
    }

    /// A_c = pi R delta_c (m^2): the Hertz contact area at delta_c.
    pub fn critical_area(&self) -> f64 {
        PI * self.radius * self.delta_cp
    }

    /// a_c = sqrt(R delta_c) (m): the Hertz contact radius at delta_c.
    pub fn critical_contact_radius(&self) -> f64 {
        (self.radius * self.delta_cp).sqrt()
    }

    /// Kogut-Etsion's P/P_c at omega = delta/delta_c (0 for omega <= 0). Each regime
    /// includes its upper end: the value at omega = 1, 6, 110 is the lower branch's.
    pub fn load_ratio(&self, omega: f64) -> f64 {
        if !(omega > 0.0) {
            0.0
        } else if omega <= 1.0 {
            omega * omega.sqrt()
        } else if omega <= KE_SECOND_REGIME {
            1.03 * omega.powf(1.425)
        } else if omega <= KE_FULLY_PLASTIC {
            1.40 * omega.powf(1.263)
        } else {
            // P = H 2 pi R delta with H = 2.8 S_Y; P_c = (2/3) pi C S_Y R delta_c
            3.0 * KE_HARDNESS_FACTOR / self.coefficient * omega
        }
    }

    /// Kogut-Etsion's A/A_c at omega = delta/delta_c (0 for omega <= 0); regimes as in
    /// [`Self::load_ratio`].
    pub fn area_ratio(omega: f64) -> f64 {
        if !(omega > 0.0) {
            0.0
        } else if omega <= 1.0 {
            omega
        } else if omega <= KE_SECOND_REGIME {
            0.93 * omega.powf(1.136)
        } else if omega <= KE_FULLY_PLASTIC {
            0.94 * omega.powf(1.146)
        } else {
            2.0 * omega
        }
    }

    /// EKK's residual interference over the maximal one,
    /// delta_res/delta_max = [1 - omega^-0.28][1 - omega^-0.69], clamped to 0 at and below
    /// yield (omega <= 1, where the product would be positive again).
    pub fn residual_ratio(omega: f64) -> f64 {
        if !(omega > 1.0) {
            return 0.0;
        }
        ((1.0 - omega.powf(-0.28)) * (1.0 - omega.powf(-0.69))).max(0.0)
    }

    /// EKK's unloading exponent n = 1.5 omega^-0.0331 (1.5, Hertz, at and below yield).
    pub fn unloading_exponent(omega: f64) -> f64 {
        if omega > 1.0 {
            1.5 * omega.powf(-0.0331)
        } else {
            1.5
        }
    }

    /// EKK's residual radius over R, 1 + 1.275 (S_Y/E)^0.216 (omega - 1) (1 below yield).
    pub fn residual_radius_ratio(&self, omega: f64) -> f64 {
        if omega > 1.0 {
            1.0 + self.k_res * (omega - 1.0)
        } else {
            1.0
        }
    }

    /// R_L/R, the loading radius over R: the Hertz sphere at delta_max - delta_res that
    /// carries Kogut-Etsion's force, (P/P_c)^2 / (omega (1 - delta_res/delta_max))^3
    /// (exactly 1 at and below yield).
    pub fn loading_radius_ratio(&self, omega: f64) -> f64 {
        if !(omega > 1.0) {
            return 1.0;
        }
        let s = omega * (1.0 - Self::residual_ratio(omega));
        let r = self.load_ratio(omega) / (s * s.sqrt());
        r * r
    }

    /// delta/delta_c.
    pub fn omega(&self, delta: f64) -> f64 {
        delta / self.delta_cp
    }

    /// Kogut-Etsion's loading force P(delta) (N) on the virgin curve; 0 out of contact.
    pub fn loading_force(&self, delta: f64) -> f64 {
        self.critical_force * self.load_ratio(self.omega(delta))
    }

    /// Kogut-Etsion's contact area A(delta) (m^2) on the virgin curve; 0 out of contact.
    pub fn loading_contact_area(&self, delta: f64) -> f64 {
        self.critical_area() * Self::area_ratio(self.omega(delta))
    }

    /// The contact radius sqrt(A/pi) (m) of [`Self::loading_contact_area`].
    pub fn loading_contact_radius(&self, delta: f64) -> f64 {
        (self.loading_contact_area(delta) / PI).sqrt()
    }

    /// R_L (m): the radius the adhesion law sees on loading to `delta_max`
    /// ([`Self::loading_radius_ratio`]); R below yield.
    pub fn loading_radius(&self, delta_max: f64) -> f64 {
        self.radius * self.loading_radius_ratio(self.omega(delta_max))
    }

    /// EKK's published unloading force (N) at `delta` after loading to
    /// `state.delta_max`: P_max x^n with P_max Kogut-Etsion's loading force, 0 at and
    /// below delta_res (x clamped to 1 above delta_max). This is the force-level law; the
    /// radius the adhesion law sees ([`PlasticityLaw::effective_radius`]) reproduces it
    /// above the kink [`Self::unloading_kink`] and falls below it under the kink.
    pub fn unloading_force(&self, state: &PlasticState, delta: f64) -> f64 {
        let omega = self.omega(state.delta_max);
        let span = state.delta_max - state.delta_res;
        if !(delta > state.delta_res) || !(span > 0.0) {
            return 0.0;
        }
        let x = ((delta - state.delta_res) / span).min(1.0);
        self.loading_force(state.delta_max) * x.powf(Self::unloading_exponent(omega))
    }

    /// The interference (m) where R_eff = R_L x^(2n - 3) reaches `state.r_res` on the way
    /// down, x = (r_res/R_L)^(1/(2n - 3)): a kink of R_eff(delta). `None` below yield and
    /// where R_L >= EKK's R_res (R_eff = R_L all the way down).
    pub fn unloading_kink(&self, state: &PlasticState) -> Option<f64> {
        let omega = self.omega(state.delta_max);
        if !(omega > 1.0) {
            return None;
        }
        let r_load = self.loading_radius(state.delta_max);
        if !(state.r_res > r_load) {
            return None;
        }
        let n = Self::unloading_exponent(omega);
        let x = (state.r_res / r_load).powf(1.0 / (2.0 * n - 3.0));
        (x > 0.0 && x < 1.0).then(|| state.delta_res + x * (state.delta_max - state.delta_res))
    }

    /// Values of omega inside a fit regime where the loading radius R_L crosses EKK's
    /// residual radius R_res (where r_res = max(R_res, R_L) and the kink of R_eff appear
    /// or vanish), ascending.
    pub fn radius_crossings(&self) -> Vec<f64> {
        self.crossings
            .iter()
            .copied()
            .filter(|w| w.is_finite())
            .collect()
    }

    /// R_L/R - R_res/R at omega (> 1).
    fn radius_gap(&self, omega: f64) -> f64 {
        self.loading_radius_ratio(omega) - self.residual_radius_ratio(omega)
    }

    /// Sign changes of [`Self::radius_gap`] inside each regime (1, 6], (6, 110],
    /// (110, 10^4], on a geometric scan of 400 points per regime refined by bisection.
    fn find_crossings(&self) -> [f64; MAX_CROSSINGS] {
        let mut out = [f64::INFINITY; MAX_CROSSINGS];
        let mut count = 0;
        let pieces = [
            (1.0, KE_SECOND_REGIME),
            (KE_SECOND_REGIME, KE_FULLY_PLASTIC),
            (KE_FULLY_PLASTIC, CROSSING_SEARCH_MAX),
        ];
        for (lo, hi) in pieces {
            let n = 400;
            let at = |i: usize| {
                if i == 0 {
                    lo * (1.0 + 1e-12)
                } else {
                    lo * (hi / lo).powf(i as f64 / n as f64)
                }
            };
            let mut a = at(0);
            let mut fa = self.radius_gap(a);
            for i in 1..=n {
                let b = if i == n { hi } else { at(i) };
                let fb = self.radius_gap(b);
                if (fa > 0.0) != (fb > 0.0) && count < MAX_CROSSINGS {
                    let (mut l, mut r, mut fl) = (a, b, fa);
                    for _ in 0..200 {
                        let m = 0.5 * (l + r);
                        if m <= l || m >= r {
                            break;
                        }
                        let fm = self.radius_gap(m);
                        if (fm > 0.0) == (fl > 0.0) {
                            l = m;
                            fl = fm;
                        } else {
                            r = m;
                        }
                    }
                    out[count] = 0.5 * (l + r);
                    count += 1;
                }
                a = b;
                fa = fb;
            }
        }
        out
    }
}

impl PlasticityLaw for KogutEtsion {
    fn radius(&self) -> f64 {
        self.radius
    }

    fn delta_cp(&self) -> f64 {
        self.delta_cp
    }

    /// delta_res from EKK ([`KogutEtsion::residual_ratio`]); r_res = max(R_res, R_L)
    /// with EKK's R_res and the loading radius R_L; `extrapolated` beyond omega = 110.
    fn state(&self, delta_max: f64) -> PlasticState {
        let omega = self.omega(delta_max);
        if !(omega > 1.0) {
            return PlasticState {
                delta_max: delta_max.max(0.0),
                delta_res: 0.0,
                r_res: self.radius,
                extrapolated: false,
            };
        }
        let r_res = self.residual_radius_ratio(omega);
        let r_load = self.loading_radius_ratio(omega);
        PlasticState {
            delta_max,
            delta_res: delta_max * Self::residual_ratio(omega),
            r_res: self.radius * r_res.max(r_load),
            extrapolated: omega > KE_FULLY_PLASTIC,
        }
    }

    /// R_eff = min(R_L x^(2n - 3), r_res), x = (delta - delta_res)/(delta_max - delta_res)
    /// capped at 1: R_L at delta_max, r_res at and below delta_res; R below yield.
    fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64 {
        let omega = self.omega(state.delta_max);
        let span = state.delta_max - state.delta_res;
        if !(omega > 1.0) || !(delta > state.delta_res) || !(span > 0.0) {
            return state.r_res;
        }
        let x = ((delta - state.delta_res) / span).min(1.0);
        let r_load = self.loading_radius(state.delta_max);
        let n = Self::unloading_exponent(omega);
        (r_load * x.powf(2.0 * n - 3.0)).min(state.r_res)
    }

    /// 6 delta_c and 110 delta_c, where the loading force jumps, and the delta_max where
    /// R_L crosses EKK's R_res ([`KogutEtsion::radius_crossings`]), where the state bends.
    fn breaks(&self) -> Vec<f64> {
        let mut b = vec![
            KE_SECOND_REGIME * self.delta_cp,
            KE_FULLY_PLASTIC * self.delta_cp,
        ];
        b.extend(
            self.radius_crossings()
                .into_iter()
                .map(|w| w * self.delta_cp),
        );
        b.sort_by(f64::total_cmp);
        b
    }

    /// One kind: [`KogutEtsion::unloading_kink`].
    fn kinks(&self, state: &PlasticState) -> Vec<Option<f64>> {
        vec![self.unloading_kink(state)]
    }

    /// Kogut & Etsion's and EKK's finite-element range, omega from 1 to 110.
    fn fit_range(&self) -> Option<(f64, f64)> {
        Some((1.0, FIT_RANGE_MAX))
    }

    fn yielding_body(&self) -> Option<YieldingBody> {
        Some(self.body)
    }
}
