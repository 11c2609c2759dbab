use crate::error::PlasticError;
use contact_core::{Pair, PlasticState, PlasticityLaw};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Upper end of delta_max/delta_CP covered by the finite-element fits of eqs 4-5
/// (Etsion, Kligerman & Kadin 2005); beyond it results are flagged as extrapolated.
pub const FIT_RANGE_MAX: f64 = 110.0;

/// Which modulus enters the yield onset, eq 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum YieldModulus {
    /// The Hertz composite modulus E* (Kogut-Etsion, Brizmer): keeps eq 3 equal to the
    /// Hertz force at delta_CP. The default.
    #[default]
    Composite,
    /// The material's own E, as eq 1 is printed in the paper.
    AsPrinted,
}

/// The Etsion-Kadin plasticity law of one asperity (paper eqs 1-5, 12-13, as resolved in
/// `docs/theory.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EtsionKadin {
    radius: f64,
    delta_cp: f64,
    /// 1.275 (S_Y/E)^0.216, the coefficient of eqs 5 and 12 (material E).
    k_res: f64,
    c_v: f64,
    yield_stress: f64,
}

impl EtsionKadin {
    /// The law for the yielding body of `pair` (its radius, E, nu, S_Y), with the
    /// modulus of eq 1 chosen by `modulus`.
    pub fn new(pair: &Pair, modulus: YieldModulus) -> Result<Self, PlasticError> {
        let m = pair.asperity();
        let s_y = m.yield_stress();
        if !s_y.is_finite() {
            return Err(PlasticError::Domain {
                field: "yield_stress",
                value: s_y,
                allowed:
                    "finite for the Etsion-Kadin law (use Elastic for a material that never yields)",
            });
        }
        let c_v = 1.295 * (0.736 * m.poisson_ratio()).exp();
        let e = match modulus {
            YieldModulus::Composite => pair.e_star(),
            YieldModulus::AsPrinted => m.youngs_modulus(),
        };
        let root = PI * c_v * s_y / (2.0 * e);
        Ok(Self {
            radius: pair.radius(),
            delta_cp: pair.radius() * root * root,
            k_res: 1.275 * (s_y / m.youngs_modulus()).powf(0.216),
            c_v,
            yield_stress: s_y,
        })
    }

    /// C_v = 1.295 exp(0.736 nu) (eq 1).
    pub fn c_v(&self) -> f64 {
        self.c_v
    }

    /// Critical contact radius a_CP = sqrt(R delta_CP) (m; eq 2 corrected: Hertz).
    pub fn critical_contact_radius(&self) -> f64 {
        (self.radius * self.delta_cp).sqrt()
    }

    /// Critical force F_CP = (2/3) pi C_v S_Y R delta_CP (N, eq 3).
    pub fn critical_force(&self) -> f64 {
        2.0 / 3.0 * PI * self.c_v * self.yield_stress * self.radius * self.delta_cp
    }

    /// c1 = 0.22 + 0.6242 exp(-0.092 omega), omega = delta_max/delta_CP (eq 13).
    pub fn c1(omega: f64) -> f64 {
        0.22 + 0.6242 * (-0.092 * omega).exp()
    }

    /// c2 = 10/(1 + (omega/10)^2) - 5 (eq 13); zero at omega = 10.
    pub fn c2(omega: f64) -> f64 {
        10.0 / (1.0 + (0.1 * omega) * (0.1 * omega)) - 5.0
    }

    /// f(x) = (1 - exp(-c2 x))/(1 - exp(-c2)) of eq 12 via expm1; its limit x at c2 = 0.
    pub fn shape(c2: f64, x: f64) -> f64 {
        if c2 == 0.0 {
            x
        } else {
            (-c2 * x).exp_m1() / (-c2).exp_m1()
        }
    }
}

impl PlasticityLaw for EtsionKadin {
    fn radius(&self) -> f64 {
        self.radius
    }

    fn critical_interference(&self) -> f64 {
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
            };
        }
        let r = self.delta_cp / delta_max;
        let omega = delta_max / self.delta_cp;
        PlasticState {
            delta_max,
            delta_res: delta_max * (1.0 - r.powf(0.28)) * (1.0 - r.powf(0.69)),
            r_res: self.radius * (1.0 + self.k_res * (omega - 1.0)),
            extrapolated: omega > FIT_RANGE_MAX,
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
                * (1.0 - Self::c1(omega))
                * (omega - 1.0)
                * self.radius
                * Self::shape(Self::c2(omega), x)
    }
}

/// A plasticity law that never yields: the asperity keeps its radius and height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    radius: f64,
}

impl Elastic {
    /// An elastic asperity of tip radius `radius` (m, > 0).
    pub fn new(radius: f64) -> Result<Self, PlasticError> {
        if radius.is_finite() && radius > 0.0 {
            Ok(Self { radius })
        } else {
            Err(PlasticError::Domain {
                field: "radius",
                value: radius,
                allowed: "finite and > 0",
            })
        }
    }
}

impl PlasticityLaw for Elastic {
    fn radius(&self) -> f64 {
        self.radius
    }
    fn critical_interference(&self) -> f64 {
        f64::INFINITY
    }
    fn state(&self, delta_max: f64) -> PlasticState {
        PlasticState {
            delta_max: delta_max.max(0.0),
            delta_res: 0.0,
            r_res: self.radius,
            extrapolated: false,
        }
    }
    fn effective_radius(&self, state: &PlasticState, _delta: f64) -> f64 {
        state.r_res
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_core::Material;

    /// Ru of Table 1 on a rigid flat.
    fn ru(modulus: YieldModulus) -> EtsionKadin {
        let m = Material::new(410e9, 0.3, 3.42e9).unwrap();
        EtsionKadin::new(&Pair::new(m, None, 4e-6).unwrap(), modulus).unwrap()
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    // Values below were evaluated by hand (calculator) from the resolved equations:
    // E* = 410e9/0.91 Pa, C_v = 1.295 e^0.2208 = 1.6149608,
    // delta_CP = 4e-6 (pi 1.6149608 3.42e9 / (2 E*))^2.
    #[test]
    fn yield_onset_of_table_1_ru_by_hand() {
        let law = ru(YieldModulus::Composite);
        assert!(close(law.c_v(), 1.614960818115471, 1e-14));
        assert!(close(
            law.critical_interference(),
            1.4831702606020387e-9,
            1e-12
        ));
        assert!(close(
            law.critical_contact_radius(),
            7.70238991638839e-08,
            1e-12
        ));
        assert!(close(law.critical_force(), 6.862742594014353e-05, 1e-12));
        // eq 3 equals the Hertz force at delta_CP when eq 1 uses E*
        let e_star = 410e9 / 0.91;
        let hertz = 4.0 / 3.0 * e_star * 4e-6f64.sqrt() * law.critical_interference().powf(1.5);
        assert!(close(law.critical_force(), hertz, 1e-12));
        let printed = ru(YieldModulus::AsPrinted);
        assert!(close(
            printed.critical_interference(),
            1.791052120036274e-09,
            1e-12
        ));
    }

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
    fn c2_vanishes_at_ten_and_the_shape_is_continuous_through_it() {
        assert_eq!(EtsionKadin::c2(10.0), 0.0);
        let law = ru(YieldModulus::Composite);
        let dcp = law.critical_interference();
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
        // the limit value: f = x
        assert!((EtsionKadin::shape(1e-300, 0.3) - 0.3).abs() < 1e-15);
        assert!((EtsionKadin::shape(1e-9, 0.3) - 0.3).abs() < 1e-9);
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
        let dcp = law.critical_interference();
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
        let dcp = law.critical_interference();
        assert!(!law.state(109.9 * dcp).extrapolated);
        assert!(law.state(110.1 * dcp).extrapolated);
    }

    #[test]
    fn huge_plastic_interference_stays_finite() {
        let law = ru(YieldModulus::Composite);
        let dcp = law.critical_interference();
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
        assert_eq!(e.critical_interference(), f64::INFINITY);
        let st = e.state(1e-6);
        assert_eq!((st.delta_res, st.r_res), (0.0, 4e-6));
        assert!(Elastic::new(-1.0).is_err());
        let m = Material::new(410e9, 0.3, f64::INFINITY).unwrap();
        assert!(
            EtsionKadin::new(&Pair::new(m, None, 4e-6).unwrap(), YieldModulus::Composite).is_err()
        );
    }
}
