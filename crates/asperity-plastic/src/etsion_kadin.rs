use crate::error::PlasticError;
use crate::onset;
pub use contact_core::YieldingBody;
use contact_core::{positive, Pair, PlasticState, PlasticityLaw};
use std::f64::consts::PI;

/// Upper end of delta_max/delta_CP covered by the finite-element fits of eqs 4-5
/// (Etsion, Kligerman & Kadin 2005); beyond it results are flagged as extrapolated.
pub const FIT_RANGE_MAX: f64 = 110.0;

/// Which modulus enters the yield onset, eq 1. There is no default: the choice moves the
/// paper switch's pull-out by about 100x (`docs/theory.md` section 2.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum YieldModulus {
    /// The Hertz composite modulus E* (Kogut-Etsion, Brizmer): keeps eq 3 equal to the
    /// Hertz force at delta_CP.
    Composite,
    /// The yielding material's own E, as eq 1 is printed in the paper (the paper's scenes).
    AsPrinted,
}

impl YieldModulus {
    /// The scene spelling: `composite` or `as_printed`.
    pub fn as_str(self) -> &'static str {
        match self {
            YieldModulus::Composite => "composite",
            YieldModulus::AsPrinted => "as_printed",
        }
    }
}

/// The constants of eq 13 as a family:
/// c1(omega) = a1 + a2 exp(-a3 omega), c2(omega) = b1/(1 + (omega/b2)^2) - b3,
/// omega = delta_max/delta_CP. The paper's Ru values are [`EffectiveRadiusFit::PAPER`];
/// `stiction calibrate` fits others to a user's finite-element curves.
///
/// ```
/// use asperity_plastic::EffectiveRadiusFit;
/// let paper = EffectiveRadiusFit::PAPER;
/// assert_eq!(paper.c2(10.0), 0.0); // c2 vanishes at omega = 10 with the paper's constants
/// assert!((paper.c1(0.0) - (0.22 + 0.6242)).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EffectiveRadiusFit {
    /// [a1, a2, a3] of c1.
    pub c1: [f64; 3],
    /// [b1, b2, b3] of c2.
    pub c2: [f64; 3],
}

impl EffectiveRadiusFit {
    /// The paper's eq 13, identified on Ru: c1 = 0.22 + 0.6242 exp(-0.092 omega),
    /// c2 = 10/(1 + (omega/10)^2) - 5.
    pub const PAPER: Self = Self {
        c1: [0.22, 0.6242, 0.092],
        c2: [10.0, 10.0, 5.0],
    };

    /// Validated constants: all finite; a3 >= 0 (c1 settles to a1 at large omega, never
    /// overflows); c1(omega) >= 0 for omega >= 1, i.e. a1 >= 0 and a1 + a2 e^(-a3) >= 0
    /// (the loading radius R [1 + 1.275 (S_Y/E)^0.216 (omega - 1) c1] stays positive);
    /// b2 > 0. Any b1, b3: the shape f of eq 12 is evaluated stably for every c2.
    pub fn new(c1: [f64; 3], c2: [f64; 3]) -> Result<Self, PlasticError> {
        let names = [
            ("c1[0]", c1[0]),
            ("c1[1]", c1[1]),
            ("c1[2]", c1[2]),
            ("c2[0]", c2[0]),
            ("c2[1]", c2[1]),
            ("c2[2]", c2[2]),
        ];
        for (field, value) in names {
            if !value.is_finite() {
                return Err(PlasticError::Fit {
                    field,
                    value,
                    allowed: "finite",
                });
            }
        }
        let bad = |field, value, allowed| {
            Err(PlasticError::Fit {
                field,
                value,
                allowed,
            })
        };
        if c1[2] < 0.0 {
            return bad(
                "c1[2]",
                c1[2],
                ">= 0 (c1 settles to a1 at large delta_max/delta_CP)",
            );
        }
        if c1[0] < 0.0 {
            return bad(
                "c1[0]",
                c1[0],
                ">= 0 (c1 >= 0 keeps the loading radius positive)",
            );
        }
        if c1[0] + c1[1] * (-c1[2]).exp() < 0.0 {
            return bad("c1[1]", c1[1], "such that c1(1) = a1 + a2 exp(-a3) >= 0");
        }
        if c2[1] <= 0.0 {
            return bad("c2[1]", c2[1], "> 0");
        }
        Ok(Self { c1, c2 })
    }

    /// c1 at omega = delta_max/delta_CP.
    pub fn c1(&self, omega: f64) -> f64 {
        self.c1[0] + self.c1[1] * (-self.c1[2] * omega).exp()
    }

    /// c2 at omega = delta_max/delta_CP.
    pub fn c2(&self, omega: f64) -> f64 {
        let r = omega / self.c2[1];
        self.c2[0] / (1.0 + r * r) - self.c2[2]
    }
}

/// The Etsion-Kadin plasticity law of one asperity (paper eqs 1-5, 12-13, as resolved in
/// `docs/theory.md`).
///
/// ```
/// use asperity_plastic::{EtsionKadin, YieldModulus};
/// use contact_core::{paper, Material, Pair, PlasticityLaw};
/// let ru = Material::new(paper::RU)?;
/// let pair = Pair::new(ru, None, paper::RADIUS)?;
/// let law = EtsionKadin::new(&pair, YieldModulus::AsPrinted)?;
/// // eq 1 with E = 410 GPa: delta_CP = 1.791 nm
/// assert!((law.delta_cp() - 1.791052120036274e-9).abs() < 1e-20);
/// // unloaded after 17 nm, the tip lost height and flattened (eqs 4-5)
/// let st = law.state(17e-9);
/// assert!(st.delta_res > 0.0 && st.r_res > paper::RADIUS);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EtsionKadin {
    radius: f64,
    delta_cp: f64,
    /// 1.275 (S_Y/E)^0.216, the coefficient of eqs 5 and 12 (the yielding body's E).
    k_res: f64,
    c_v: f64,
    yield_stress: f64,
    body: YieldingBody,
    modulus: YieldModulus,
    fit: EffectiveRadiusFit,
}

impl EtsionKadin {
    /// The law of `pair` with the modulus of eq 1 chosen by `modulus` and the paper's
    /// eq 13. With a counter material of finite yield stress, the body with the smaller
    /// delta_CP (the one that yields first) governs: its S_Y, nu (in C_v) and E (in eq 1
    /// as printed, and in S_Y/E of eqs 5 and 12).
    pub fn new(pair: &Pair, modulus: YieldModulus) -> Result<Self, PlasticError> {
        let o = onset::governing(pair, modulus, |nu| 1.295 * (0.736 * nu).exp())?;
        let m = o.material;
        Ok(Self {
            radius: pair.radius(),
            delta_cp: o.delta_cp,
            k_res: 1.275 * (m.yield_stress() / m.youngs_modulus()).powf(0.216),
            c_v: o.coefficient,
            yield_stress: m.yield_stress(),
            body: o.body,
            modulus,
            fit: EffectiveRadiusFit::PAPER,
        })
    }

    /// The same law with other constants of eq 13.
    pub fn with_fit(self, fit: EffectiveRadiusFit) -> Self {
        Self { fit, ..self }
    }

    /// The constants of eq 13 in use.
    pub fn fit(&self) -> EffectiveRadiusFit {
        self.fit
    }

    /// The reading of eq 1 in use.
    pub fn yield_modulus(&self) -> YieldModulus {
        self.modulus
    }

    /// The body that yields first and governs plasticity.
    pub fn yielding_body(&self) -> YieldingBody {
        self.body
    }

    /// C_v = 1.295 exp(0.736 nu) of the yielding body (eq 1).
    pub fn c_v(&self) -> f64 {
        self.c_v
    }

    /// 1.275 (S_Y/E)^0.216 of eqs 5 and 12.
    pub fn k_res(&self) -> f64 {
        self.k_res
    }

    /// Critical contact radius a_CP = sqrt(R delta_CP) (m; eq 2 corrected: Hertz).
    pub fn critical_contact_radius(&self) -> f64 {
        (self.radius * self.delta_cp).sqrt()
    }

    /// Critical force F_CP = (2/3) pi C_v S_Y R delta_CP (N, eq 3).
    pub fn critical_force(&self) -> f64 {
        2.0 / 3.0 * PI * self.c_v * self.yield_stress * self.radius * self.delta_cp
    }

    /// f(x) = (1 - exp(-c2 x))/(1 - exp(-c2)) of eq 12, evaluated without overflow for
    /// every c2 (for c2 < 0 as exp(-|c2| (1 - x)) expm1(-|c2| x)/expm1(-|c2|)); its limit x
    /// at c2 = 0.
    pub fn shape(c2: f64, x: f64) -> f64 {
        if c2 == 0.0 {
            x
        } else if c2 > 0.0 {
            (-c2 * x).exp_m1() / (-c2).exp_m1()
        } else {
            let k = -c2;
            (-k * (1.0 - x)).exp() * (-k * x).exp_m1() / (-k).exp_m1()
        }
    }
}

/// delta_res/delta_max = [1 - omega^-0.28][1 - omega^-0.69] of eq 4 (Etsion, Kligerman &
/// Kadin 2005), for omega = delta_max/delta_CP > 1; 0 at and below yield. One logarithm
/// and two `exp_m1` (1 - omega^-a = -expm1(-a ln omega), exact near yield where the
/// factors vanish) in place of two `powf`: the Kogut-Etsion family shares it, so both
/// families' residual interference agree to the bit.
pub(crate) fn residual_ratio(omega: f64) -> f64 {
    if !(omega > 1.0) {
        return 0.0;
    }
    let l = omega.ln();
    ((-0.28 * l).exp_m1() * (-0.69 * l).exp_m1()).max(0.0)
}

impl PlasticityLaw for EtsionKadin {
    fn radius(&self) -> f64 {
        self.radius
    }

    fn delta_cp(&self) -> f64 {
        self.delta_cp
    }

    /// delta_res = delta_max [1 - (delta_CP/delta_max)^0.28][1 - (delta_CP/delta_max)^0.69]
    /// (eq 4), R_res = R [1 + 1.275 (S_Y/E)^0.216 (delta_max/delta_CP - 1)] (eq 5).
    fn state(&self, delta_max: f64) -> PlasticState {
        if delta_max.is_nan() || delta_max <= self.delta_cp {
            return PlasticState {
                delta_max: delta_max.max(0.0),
                delta_res: 0.0,
                r_res: self.radius,
                extrapolated: false,
                adhesive_displacement: 0.0,
            };
        }
        let omega = delta_max / self.delta_cp;
        PlasticState {
            delta_max,
            delta_res: delta_max * residual_ratio(omega),
            r_res: self.radius * (1.0 + self.k_res * (omega - 1.0)),
            extrapolated: omega > FIT_RANGE_MAX,
            adhesive_displacement: 0.0,
        }
    }

    /// R_eff = R_res - 1.275 (1 - c1)(S_Y/E)^0.216 (omega - 1) R f(x),
    /// x = (delta - delta_res)/(delta_max - delta_res) capped at 1 (eq 12); R_res at x <= 0.
    fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64 {
        if state.delta_res <= 0.0 || delta <= state.delta_res {
            return state.r_res;
        }
        let omega = state.delta_max / self.delta_cp;
        let x = ((delta - state.delta_res) / (state.delta_max - state.delta_res)).min(1.0);
        state.r_res
            - self.k_res
                * (1.0 - self.fit.c1(omega))
                * (omega - 1.0)
                * self.radius
                * Self::shape(self.fit.c2(omega), x)
    }

    /// R_eff moves monotonically from R_res (x = 0) to its value at x = 1 (eq 12's
    /// shape f is monotone from 0 to 1), so the larger end bounds it.
    fn radius_bound(&self, state: &PlasticState) -> Option<f64> {
        Some(
            state
                .r_res
                .max(self.effective_radius(state, state.delta_max)),
        )
    }

    /// The finite-element range of eqs 4-5 (Etsion, Kligerman & Kadin 2005): 1 to 110.
    fn fit_range(&self) -> Option<(f64, f64)> {
        Some((1.0, FIT_RANGE_MAX))
    }

    fn yielding_body(&self) -> Option<YieldingBody> {
        Some(self.body)
    }
}

/// A plasticity law that never yields: the asperity keeps its radius and height.
///
/// ```
/// use asperity_plastic::{ElastoPlasticAsperity, Elastic};
/// use contact_core::{AsperityHistory, AsperityModel, Path, PlasticityLaw};
/// use maugis_kim::Hertz;
/// let law = Elastic::new(4e-6)?;
/// assert_eq!(law.delta_cp(), f64::INFINITY);
/// // with Hertz adhesion-free contact: F = K sqrt(R) delta^(3/2), the same on the way back
/// let asperity = ElastoPlasticAsperity::new(law, Hertz::new(1e11)?);
/// let loaded = asperity.force(1e-9, AsperityHistory::VIRGIN, Path::Approach)?;
/// assert!((loaded - 1e11 * 2e-3 * 1e-9f64.powf(1.5)).abs() < 1e-18);
/// let back = asperity.force(1e-9, AsperityHistory { delta_max: 5e-9 }, Path::Retract { from: 5e-9 })?;
/// assert_eq!(back, loaded);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    radius: f64,
}

impl Elastic {
    /// An elastic asperity of tip radius `radius` (m, > 0).
    pub fn new(radius: f64) -> Result<Self, PlasticError> {
        Ok(Self {
            radius: positive("radius", radius)?,
        })
    }
}

impl PlasticityLaw for Elastic {
    fn radius(&self) -> f64 {
        self.radius
    }
    fn delta_cp(&self) -> f64 {
        f64::INFINITY
    }
    fn state(&self, delta_max: f64) -> PlasticState {
        PlasticState {
            delta_max: delta_max.max(0.0),
            delta_res: 0.0,
            r_res: self.radius,
            extrapolated: false,
            adhesive_displacement: 0.0,
        }
    }
    fn effective_radius(&self, state: &PlasticState, _delta: f64) -> f64 {
        state.r_res
    }
    fn radius_bound(&self, state: &PlasticState) -> Option<f64> {
        Some(state.r_res)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_core::{paper, Material, MaterialProps};

    /// Ru of Table 1 on a rigid flat.
    fn ru(modulus: YieldModulus) -> EtsionKadin {
        let m = Material::new(paper::RU).unwrap();
        EtsionKadin::new(&Pair::new(m, None, paper::RADIUS).unwrap(), modulus).unwrap()
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    // Values below are recomputed independently (plain Python from the equations of
    // docs/theory.md) by docs/derivations/by_hand.py; the arithmetic in short:
    // E* = 410e9/0.91 Pa, C_v = 1.295 e^0.2208 = 1.6149608,
    // delta_CP = 4e-6 (pi 1.6149608 3.42e9 / (2 E*))^2 = 1.48317e-9 m,
    // a_CP = sqrt(4e-6 * 1.48317e-9) = 7.70239e-8 m, F_CP = (2/3) pi C_v S_Y R delta_CP;
    // as printed E = 410e9: delta_CP = 1.48317e-9 / 0.91^2 = 1.79105e-9 m.
    #[test]
    fn yield_onset_of_table_1_ru_by_hand() {
        let law = ru(YieldModulus::Composite);
        assert!(close(law.c_v(), 1.614960818115471, 1e-14));
        assert!(close(law.delta_cp(), 1.4831702606020387e-9, 1e-12));
        assert!(close(
            law.critical_contact_radius(),
            7.70238991638839e-08,
            1e-12
        ));
        assert!(close(law.critical_force(), 6.862742594014353e-05, 1e-12));
        // eq 3 equals the Hertz force at delta_CP when eq 1 uses E*
        let film = paper::RU;
        let e_star = film.youngs_modulus / (1.0 - film.poisson_ratio * film.poisson_ratio);
        let hertz = 4.0 / 3.0 * e_star * paper::RADIUS.sqrt() * law.delta_cp().powf(1.5);
        assert!(close(law.critical_force(), hertz, 1e-12));
        let printed = ru(YieldModulus::AsPrinted);
        assert!(close(printed.delta_cp(), 1.791052120036274e-09, 1e-12));
        assert!(close(
            printed.delta_cp() * 0.91 * 0.91,
            law.delta_cp(),
            1e-12
        ));
    }

    // docs/derivations/by_hand.py (block "residual_state_of_fig2_cases_by_hand");
    // by hand for delta_max = 17, 34, 51 nm with delta_CP = 1.4831703 nm (omega = 11.462,
    // 22.924, 34.386): delta_res from eq 4, R_res = R (1 + 0.45337 (omega - 1)) from eq 5
    // (0.45337 = 1.275 (3.42/410)^0.216), R_eff(x = 1) = R (1 + 0.45337 (omega - 1) c1),
    // R_eff at x = 1/2 from eq 12 with c2(omega) and f(1/2).
    #[test]
    fn residual_state_of_fig2_cases_by_hand() {
        let law = ru(YieldModulus::Composite);
        let cases = [
            (
                17e-9,
                6.849380455242463e-09,
                2.2974506442240938e-05,
                1.2300414100996561e-05,
                1.853356270183638e-05,
            ),
            (
                34e-9,
                1.7568107279114872e-08,
                4.376268385576789e-05,
                1.5759923644545714e-05,
                3.943958587730331e-05,
            ),
            (
                51e-9,
                2.926818342698817e-08,
                6.455086126929484e-05,
                1.8919113649719765e-05,
                5.961720573606344e-05,
            ),
        ];
        for (dmax, dres, rres, r_load, r_mid) in cases {
            let st = law.state(dmax);
            assert!(close(st.delta_res, dres, 1e-12), "{dmax}: {}", st.delta_res);
            assert!(close(st.r_res, rres, 1e-12));
            assert!(close(law.effective_radius(&st, dmax), r_load, 1e-12));
            assert!(close(
                law.effective_radius(&st, 0.5 * (dres + dmax)),
                r_mid,
                1e-12
            ));
            assert!(!st.extrapolated);
        }
    }

    #[test]
    fn the_paper_constants_are_eq_13() {
        let f = EffectiveRadiusFit::PAPER;
        for omega in [1.0, 3.0, 10.0, 34.4, 110.0] {
            assert_eq!(f.c1(omega), 0.22 + 0.6242 * (-0.092 * omega).exp());
            assert!((f.c2(omega) - (10.0 / (1.0 + (omega / 10.0).powi(2)) - 5.0)).abs() < 1e-15);
        }
        assert_eq!(f.c2(10.0), 0.0);
    }

    #[test]
    fn c2_vanishes_at_ten_and_the_shape_is_continuous_through_it() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.delta_cp();
        let at = law.state(10.0 * dcp);
        for x in [0.0, 0.25, 0.5, 0.9, 1.0] {
            let d = at.delta_res + x * (at.delta_max - at.delta_res);
            let r0 = law.effective_radius(&at, d);
            assert!(r0.is_finite());
            for eps in [1e-12, 1e-9, 1e-6] {
                for sgn in [-1.0, 1.0] {
                    let st = law.state(10.0 * dcp * (1.0 + sgn * eps));
                    let dd = st.delta_res + x * (st.delta_max - st.delta_res);
                    let r = law.effective_radius(&st, dd);
                    assert!(
                        (r - r0).abs() <= 50.0 * eps * r0,
                        "x {x} eps {eps}: {r} vs {r0}"
                    );
                }
            }
        }
        assert!((EtsionKadin::shape(1e-300, 0.3) - 0.3).abs() < 1e-15);
        assert!((EtsionKadin::shape(-1e-300, 0.3) - 0.3).abs() < 1e-15);
        assert!((EtsionKadin::shape(1e-9, 0.3) - 0.3).abs() < 1e-9);
    }

    #[test]
    fn the_shape_stays_finite_monotone_and_bounded_for_any_c2() {
        for c2 in [-5000.0, -800.0, -50.0, -1.0, 1e-12, 3.0, 700.0, 5000.0] {
            let mut prev = 0.0;
            for i in 0..=100 {
                let x = i as f64 / 100.0;
                let f = EtsionKadin::shape(c2, x);
                assert!(
                    f.is_finite() && (0.0..=1.0).contains(&f),
                    "c2 {c2} x {x}: {f}"
                );
                assert!(f >= prev, "c2 {c2}: not monotone at x {x}");
                prev = f;
            }
            assert_eq!(EtsionKadin::shape(c2, 0.0), 0.0);
            assert!((EtsionKadin::shape(c2, 1.0) - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn fit_constants_are_validated() {
        assert!(EffectiveRadiusFit::new([0.22, 0.6242, 0.092], [10.0, 10.0, 5.0]).is_ok());
        for (c1, c2, field) in [
            ([f64::NAN, 0.6, 0.1], [10.0, 10.0, 5.0], "c1[0]"),
            ([0.2, 0.6, -0.1], [10.0, 10.0, 5.0], "c1[2]"),
            ([-0.1, 0.6, 0.1], [10.0, 10.0, 5.0], "c1[0]"),
            ([0.1, -0.5, 0.1], [10.0, 10.0, 5.0], "c1[1]"),
            ([0.2, 0.6, 0.1], [10.0, 0.0, 5.0], "c2[1]"),
            ([0.2, 0.6, 0.1], [f64::INFINITY, 10.0, 5.0], "c2[0]"),
        ] {
            let e = EffectiveRadiusFit::new(c1, c2).unwrap_err();
            assert!(
                matches!(e, PlasticError::Fit { field: f, .. } if f == field),
                "{e}"
            );
        }
    }

    #[test]
    fn the_body_that_yields_first_governs() {
        let ru = Material::new(paper::RU).unwrap();
        // a softer counter (S_Y 1 GPa) yields first under either reading of eq 1
        let soft = Material::new(MaterialProps {
            yield_stress: 1e9,
            ..paper::RU
        })
        .unwrap();
        for modulus in [YieldModulus::Composite, YieldModulus::AsPrinted] {
            let law = EtsionKadin::new(&Pair::new(ru, Some(soft), 4e-6).unwrap(), modulus).unwrap();
            assert_eq!(law.yielding_body(), YieldingBody::Counter);
            let alone =
                EtsionKadin::new(&Pair::new(soft, Some(ru), 4e-6).unwrap(), modulus).unwrap();
            assert!(close(law.delta_cp(), alone.delta_cp(), 1e-15));
            assert!(close(law.k_res(), alone.k_res(), 1e-15));
        }
        // an elastic counter never governs; Ru on Ru picks body 1
        let rigid_like = Material::new(MaterialProps {
            yield_stress: f64::INFINITY,
            ..paper::RU
        })
        .unwrap();
        let law = EtsionKadin::new(
            &Pair::new(ru, Some(rigid_like), 4e-6).unwrap(),
            YieldModulus::AsPrinted,
        )
        .unwrap();
        assert_eq!(law.yielding_body(), YieldingBody::Asperity);
        assert!(matches!(
            EtsionKadin::new(
                &Pair::new(rigid_like, None, 4e-6).unwrap(),
                YieldModulus::AsPrinted
            ),
            Err(PlasticError::NeverYields)
        ));
    }

    #[test]
    fn effective_radius_is_r_res_at_delta_res_and_continuous_in_delta() {
        let law = ru(YieldModulus::Composite);
        for dmax in [2e-9, 17e-9, 51e-9, 500e-9] {
            let st = law.state(dmax);
            assert_eq!(law.effective_radius(&st, st.delta_res), st.r_res);
            assert_eq!(law.effective_radius(&st, st.delta_res - 1e-9), st.r_res);
            let n = 2000;
            let mut prev = law.effective_radius(&st, st.delta_res);
            for i in 1..=n {
                let d = st.delta_res + (st.delta_max - st.delta_res) * i as f64 / n as f64;
                let r = law.effective_radius(&st, d);
                assert!((r - prev).abs() < 0.01 * st.r_res, "jump at {d}");
                assert!(r > 0.0);
                prev = r;
            }
        }
    }

    #[test]
    fn below_yield_the_asperity_is_untouched() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.delta_cp();
        for dmax in [0.0, 0.5 * dcp, dcp] {
            let st = law.state(dmax);
            assert_eq!(st.delta_res, 0.0);
            assert_eq!(st.r_res, 4e-6);
            assert_eq!(law.effective_radius(&st, 0.3 * dcp), 4e-6);
        }
        // and just above yield the change starts from zero (continuity at onset)
        let st = law.state(dcp * (1.0 + 1e-9));
        assert!(st.delta_res < 1e-12 * dcp && st.r_res - 4e-6 < 1e-12);
    }

    #[test]
    fn extrapolation_is_flagged_beyond_the_fit_range() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.delta_cp();
        assert!(!law.state(109.9 * dcp).extrapolated);
        assert!(law.state(110.1 * dcp).extrapolated);
    }

    #[test]
    fn huge_plastic_interference_stays_finite() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.delta_cp();
        for omega in [200.0, 500.0, 1e3] {
            let st = law.state(omega * dcp);
            assert!(st.delta_res.is_finite() && st.delta_res > 0.0 && st.delta_res < st.delta_max);
            for x in [0.0, 0.5, 1.0] {
                let r = law.effective_radius(&st, st.delta_res + x * (st.delta_max - st.delta_res));
                assert!(r.is_finite() && r > 0.0, "omega {omega} x {x}: {r}");
            }
        }
    }

    #[test]
    fn elastic_law_never_yields() {
        let e = Elastic::new(4e-6).unwrap();
        assert_eq!(e.delta_cp(), f64::INFINITY);
        let st = e.state(1e-6);
        assert_eq!((st.delta_res, st.r_res), (0.0, 4e-6));
        assert!(Elastic::new(-1.0).is_err());
    }
}
