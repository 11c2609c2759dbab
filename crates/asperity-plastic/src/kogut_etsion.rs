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
    /// C_v at nu = 0.3; 1.9 % below it at nu = 0, 1.4 % at nu = 0.5.
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
///   R_eff = min(R_L x^(2n - 3), R_res), which reproduces EKK's force where R_L x^(2n-3)
///   is below R_res and is the residual profile's radius below that kink. Where the two
///   fits contradict each other, R_L >= R_res (near yield, from Kogut-Etsion's +3 %),
///   R_eff = R_res + (R_L - R_res) x, linear between the two published radii.
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
        crate::etsion_kadin::residual_ratio(omega)
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
    /// where R_L >= EKK's R_res (R_eff then linear in x, no kink).
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
        (x > 0.0 && x < 1.0).then_some(state.delta_res + x * (state.delta_max - state.delta_res))
    }

    /// Values of omega inside a fit regime where the loading radius R_L crosses EKK's
    /// residual radius R_res (where the form of R_eff changes and its kink appears or
    /// vanishes), ascending.
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

    /// delta_res and R_res from EKK ([`KogutEtsion::residual_ratio`],
    /// [`KogutEtsion::residual_radius_ratio`]); `extrapolated` beyond omega = 110.
    fn state(&self, delta_max: f64) -> PlasticState {
        let omega = self.omega(delta_max);
        if !(omega > 1.0) {
            return PlasticState {
                delta_max: delta_max.max(0.0),
                delta_res: 0.0,
                r_res: self.radius,
                extrapolated: false,
                adhesive_displacement: 0.0,
            };
        }
        PlasticState {
            delta_max,
            delta_res: delta_max * Self::residual_ratio(omega),
            r_res: self.radius * self.residual_radius_ratio(omega),
            extrapolated: omega > KE_FULLY_PLASTIC,
            adhesive_displacement: 0.0,
        }
    }

    /// R_eff = min(R_L x^(2n - 3), r_res), x = (delta - delta_res)/(delta_max - delta_res)
    /// capped at 1; where R_L >= r_res, R_eff = r_res + (R_L - r_res) x. R_L at and above
    /// delta_max, r_res at and below delta_res; R below yield.
    fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64 {
        let omega = self.omega(state.delta_max);
        let span = state.delta_max - state.delta_res;
        if !(omega > 1.0) || !(delta > state.delta_res) || !(span > 0.0) {
            return state.r_res;
        }
        let r_load = self.loading_radius(state.delta_max);
        let x = (delta - state.delta_res) / span;
        if x >= 1.0 {
            return r_load;
        }
        if r_load < state.r_res {
            let n = Self::unloading_exponent(omega);
            (r_load * x.powf(2.0 * n - 3.0)).min(state.r_res)
        } else {
            state.r_res + (r_load - state.r_res) * x
        }
    }

    /// R_eff moves monotonically between r_res (x = 0) and R_L (x = 1) on both of its
    /// forms, so the larger end bounds it.
    fn radius_bound(&self, state: &PlasticState) -> Option<f64> {
        Some(
            state
                .r_res
                .max(self.effective_radius(state, state.delta_max)),
        )
    }

    /// 6 delta_c and 110 delta_c, where the loading force jumps, and the delta_max where
    /// R_L crosses EKK's R_res ([`KogutEtsion::radius_crossings`]), where R_eff changes
    /// form.
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

#[cfg(test)]
mod tests {
    use super::*;
    use contact_core::{paper, Material, MaterialProps};

    /// Ru of Table 1 on a rigid flat.
    fn ru(modulus: YieldModulus) -> KogutEtsion {
        let m = Material::new(paper::RU).unwrap();
        KogutEtsion::new(&Pair::new(m, None, paper::RADIUS).unwrap(), modulus).unwrap()
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    // Reference values: docs/derivations/kogut_etsion.py (independent plain Python from the
    // published formulas), block "critical_values_of_table_1_ru_by_hand".
    #[test]
    fn critical_values_of_table_1_ru_by_hand() {
        let law = ru(YieldModulus::Composite);
        assert!(close(law.delta_cp(), 1.4831702606020387e-09, 1e-12));
        assert!(close(law.critical_force(), 6.862742594014353e-05, 1e-12));
        assert!(close(law.critical_area(), 1.8638067178920893e-14, 1e-12));
        // with E* in eq 1, P_c is also (2/3) pi C S_Y R delta_c (KE's Pc)
        let s_y = paper::RU.yield_stress;
        let pc_ke = 2.0 / 3.0 * PI * law.onset_coefficient() * s_y * paper::RADIUS * law.delta_cp();
        assert!(close(law.critical_force(), pc_ke, 1e-12));
        // as printed: delta_c larger by 1/(1 - nu^2)^2, P_c still the Hertz force at it
        let printed = ru(YieldModulus::AsPrinted);
        assert!(close(printed.delta_cp(), 1.791052120036274e-09, 1e-12));
        assert!(close(
            printed.critical_force(),
            9.106962176111277e-05,
            1e-12
        ));
    }

    // KE 2002's fits evaluated by hand (docs/derivations/kogut_etsion.py, "fits at omega").
    #[test]
    fn published_fits_at_chosen_omega() {
        let law = ru(YieldModulus::Composite);
        let cases = [
            (0.5, 0.3535533905932738, 0.5),
            (1.0, 1.0, 1.0),
            (2.0, 2.765699355727343, 2.0438688446929962),
            (6.0, 13.234354282914214, 7.119717617744424),
            (20.0, 61.56429636994453, 29.11442575554431),
            (110.0, 530.1600481581794, 205.38270563435512),
            (500.0, 2600.68229079456, 1000.0),
        ];
        for (w, p, a) in cases {
            assert!(close(law.load_ratio(w), p, 1e-13), "P/Pc at {w}");
            assert!(close(KogutEtsion::area_ratio(w), a, 1e-13), "A/Ac at {w}");
        }
        // just above the boundaries the upper branches hold
        let up = |w: f64| w * (1.0 + 1e-15);
        assert!(close(law.load_ratio(up(6.0)), 13.45652941016743, 1e-13));
        assert!(close(
            KogutEtsion::area_ratio(up(6.0)),
            7.326375713731759,
            1e-13
        ));
        assert!(close(law.load_ratio(up(110.0)), 572.1501039748032, 1e-13));
        assert!(close(KogutEtsion::area_ratio(up(110.0)), 220.0, 1e-13));
        assert_eq!(law.load_ratio(0.0), 0.0);
        assert_eq!(law.load_ratio(-1.0), 0.0);
        assert_eq!(law.load_ratio(f64::NAN), 0.0);
    }

    // The jumps of KE's fits at omega = 1 (+3 % force, -7 % area), 6 (+1.68 %, +2.9 %) and
    // the fully plastic onset at 110 (+7.9 %, +7.1 %), by hand (docs/derivations).
    #[test]
    fn declared_jumps_have_the_published_sizes() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.delta_cp();
        let jump = |w: f64| {
            let (lo, hi) = (w * dcp, w * dcp * (1.0 + 1e-13));
            (
                law.loading_force(hi) / law.loading_force(lo),
                law.loading_contact_area(hi) / law.loading_contact_area(lo),
            )
        };
        for (w, f, a) in [
            (1.0, 1.03, 0.93),
            (6.0, 1.0167877572644437, 1.0290261646715149),
            (110.0, 1.0792026029922488, 1.071171008875831),
        ] {
            let (jf, ja) = jump(w);
            assert!(close(jf, f, 1e-11), "force jump at {w}: {jf}");
            assert!(close(ja, a, 1e-11), "area jump at {w}: {ja}");
        }
        let breaks = law.breaks();
        assert!(breaks.contains(&(6.0 * dcp)) && breaks.contains(&(110.0 * dcp)));
        // fully plastic: the mean pressure is the hardness 2.8 S_Y; just below, the two
        // elastic-plastic fits give 2.779 S_Y
        let s_y = paper::RU.yield_stress;
        let p_mean = |d: f64| law.loading_force(d) / law.loading_contact_area(d) / s_y;
        assert!(close(p_mean(200.0 * dcp), 2.8, 1e-12));
        assert!(close(p_mean(110.0 * dcp), 2.7791619632276485, 1e-12));
    }

    // EKK's residual state and the derived loading radius and kink, by hand
    // (docs/derivations/kogut_etsion.py, "omega ...: g n R_res/R R_L/R x_kink").
    #[test]
    fn ekk_residual_state_and_loading_radius_by_hand() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.delta_cp();
        let r = paper::RADIUS;
        let cases = [
            (
                2.0,
                0.0670611956165302,
                1.46597703230979,
                1.4534177428215027,
                1.1774988128681594,
                0.04532618208718485,
            ),
            (
                10.0,
                0.3781706758070352,
                1.3899246562406167,
                5.080759685393524,
                2.736796309110313,
                0.06019149621911988,
            ),
            (
                34.4,
                0.5739407241820761,
                1.3342314535139188,
                16.144152610238187,
                4.73715172676422,
                0.024765724270619054,
            ),
            (
                100.0,
                0.6943717275341187,
                1.2879270333503976,
                45.88835653932876,
                7.738833294930415,
                0.015047015659997106,
            ),
        ];
        for (w, g, n, rres, rl, xk) in cases {
            let dmax = w * dcp;
            let st = law.state(dmax);
            assert!(close(st.delta_res / dmax, g, 1e-12), "delta_res at {w}");
            assert!(close(KogutEtsion::unloading_exponent(w), n, 1e-13));
            assert!(close(st.r_res / r, rres, 1e-12), "R_res at {w}");
            assert!(close(law.loading_radius(dmax) / r, rl, 1e-12), "R_L at {w}");
            assert!(close(law.effective_radius(&st, dmax) / r, rl, 1e-12));
            let k = law.unloading_kink(&st).unwrap();
            assert!(close((k - st.delta_res) / (dmax - st.delta_res), xk, 1e-9));
            assert_eq!(law.kinks(&st), vec![Some(k)]);
            assert!(!st.extrapolated);
        }
    }

    // EKK's residual state is the paper's eqs 4-5: the same as the Etsion-Kadin law's.
    #[test]
    fn residual_state_is_the_one_of_the_etsion_kadin_law() {
        let m = Material::new(paper::RU).unwrap();
        let pair = Pair::new(m, None, paper::RADIUS).unwrap();
        for modulus in [YieldModulus::Composite, YieldModulus::AsPrinted] {
            let ke = KogutEtsion::new(&pair, modulus).unwrap();
            let ek = crate::EtsionKadin::new(&pair, modulus).unwrap();
            assert_eq!(ke.delta_cp(), ek.delta_cp());
            for w in [1.0 + 1e-6, 1.05, 1.2, 3.0, 17.0, 90.0, 500.0] {
                let (a, b) = (ke.state(w * ke.delta_cp()), ek.state(w * ek.delta_cp()));
                assert!(close(a.delta_res, b.delta_res, 1e-14));
                assert!(close(a.r_res, b.r_res, 1e-14));
                assert_eq!(a.extrapolated, b.extrapolated);
            }
        }
    }

    // Near yield KE's +3 % makes R_L exceed EKK's R_res: for Ru up to omega = 1.11172
    // (bisection by hand, docs/derivations); there R_eff is linear in x from EKK's R_res
    // (x = 0) to R_L (x = 1), and has no interior kink.
    #[test]
    fn the_near_yield_band_of_table_1_ru() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.delta_cp();
        let crossings = law.radius_crossings();
        assert_eq!(crossings.len(), 1, "{crossings:?}");
        assert!(close(crossings[0], 1.1117208130765417, 1e-12));
        assert!(law.breaks().contains(&(crossings[0] * dcp)));
        let inside = law.state(1.05 * dcp);
        let r_load = law.loading_radius(1.05 * dcp);
        let r_res = law.residual_radius_ratio(1.05) * paper::RADIUS;
        assert_eq!(inside.r_res, r_res);
        assert!(r_res < r_load);
        assert_eq!(law.unloading_kink(&inside), None);
        assert_eq!(law.kinks(&inside), vec![None]);
        for x in [0.0, 0.3, 0.9] {
            let d = inside.delta_res + x * (inside.delta_max - inside.delta_res);
            let r = law.effective_radius(&inside, d);
            assert!(close(r, r_res + (r_load - r_res) * x, 1e-14), "x {x}: {r}");
        }
        assert_eq!(law.effective_radius(&inside, inside.delta_max), r_load);
        let outside = law.state(1.2 * dcp);
        assert!(law.unloading_kink(&outside).is_some());
        // the two forms meet at the crossing: continuous in delta_max there
        let w = crossings[0];
        for x in [0.1, 0.5, 0.9] {
            let r_at = |w: f64| {
                let st = law.state(w * dcp);
                law.effective_radius(&st, st.delta_res + x * (st.delta_max - st.delta_res))
                    / paper::RADIUS
            };
            assert!((r_at(w * (1.0 - 1e-9)) - r_at(w * (1.0 + 1e-9))).abs() < 1e-7);
        }
    }

    #[test]
    fn kogut_etsion_2002_onset_uses_k_h() {
        let m = Material::new(paper::RU).unwrap();
        let pair = Pair::new(m, None, paper::RADIUS).unwrap();
        let law =
            KogutEtsion::with_onset(&pair, YieldModulus::Composite, YieldOnset::KogutEtsion2002)
                .unwrap();
        assert!(close(law.onset_coefficient(), 1.6156, 1e-14));
        assert!(close(law.delta_cp(), 1.4843445345016118e-09, 1e-12));
        assert_eq!(law.yield_onset().as_str(), "kogut_etsion_2002");
        // fully plastic: P/Pc = 3 omega / K
        assert!(close(
            law.load_ratio(200.0),
            3.0 * 200.0 / (0.454 + 0.41 * 0.3),
            1e-14
        ));
    }

    // A held-out second material: a steel-like sphere (E 200 GPa, nu 0.29, S_Y 1 GPa) on a
    // Ru counter-surface that can yield too; the steel yields first (delta_c 1.17 nm against
    // 13.9 nm). Values by hand, docs/derivations/kogut_etsion.py ("steel on Ru").
    #[test]
    fn the_body_that_yields_first_governs() {
        let steel = Material::new(MaterialProps {
            youngs_modulus: 200e9,
            poisson_ratio: 0.29,
            yield_stress: 1e9,
        })
        .unwrap();
        let ru = Material::new(paper::RU).unwrap();
        let pair = Pair::new(ru, Some(steel), 4e-6).unwrap();
        let law = KogutEtsion::new(&pair, YieldModulus::Composite).unwrap();
        assert_eq!(law.yielding_body(), YieldingBody::Counter);
        assert!(close(law.delta_cp(), 1.1725261870187222e-09, 1e-12));
        for (w, p, dres, rres, rl) in [
            (
                3.0,
                7.76143011236164e-05,
                4.949893708670141e-10,
                7.247713366308079e-06,
                5.672314407221471e-06,
            ),
            (
                40.0,
                0.002326679392462151,
                2.7835776816545148e-08,
                6.733041064300753e-05,
                2.0312263793191807e-05,
            ),
        ] {
            let d = w * law.delta_cp();
            let st = law.state(d);
            assert!(close(law.loading_force(d), p, 1e-12));
            assert!(close(st.delta_res, dres, 1e-12));
            assert!(close(st.r_res, rres, 1e-12));
            assert!(close(law.loading_radius(d), rl, 1e-12));
        }
        let rigid_like = Material::new(MaterialProps {
            yield_stress: f64::INFINITY,
            ..paper::RU
        })
        .unwrap();
        assert!(matches!(
            KogutEtsion::new(
                &Pair::new(rigid_like, None, 4e-6).unwrap(),
                YieldModulus::AsPrinted
            ),
            Err(PlasticError::NeverYields)
        ));
    }

    #[test]
    fn below_yield_the_asperity_is_untouched() {
        let law = ru(YieldModulus::AsPrinted);
        let dcp = law.delta_cp();
        for dmax in [0.0, -1e-9, 0.5 * dcp, dcp, f64::NAN] {
            let st = law.state(dmax);
            assert_eq!(st.delta_res, 0.0);
            assert_eq!(st.r_res, paper::RADIUS);
            assert!(!st.extrapolated);
            assert_eq!(law.effective_radius(&st, 0.3 * dcp), paper::RADIUS);
            assert_eq!(law.kinks(&st), vec![None]);
        }
        assert_eq!(law.loading_radius(dcp), paper::RADIUS);
    }

    #[test]
    fn extrapolation_is_flagged_beyond_the_fit_range() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.delta_cp();
        assert!(!law.state(110.0 * dcp).extrapolated);
        assert!(law.state(110.5 * dcp).extrapolated);
        assert_eq!(law.fit_range(), Some((1.0, 110.0)));
        assert_eq!(
            PlasticityLaw::yielding_body(&law),
            Some(YieldingBody::Asperity)
        );
    }
}
