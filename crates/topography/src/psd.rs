//! The self-affine power spectral density and its analytic moments.

use serde::Serialize;

use crate::error::{Result, TopographyError};
use crate::gw::{mccool, GwParameters};
use crate::moments::{MomentMethod, Moments};

/// How the PSD's amplitude C0 is fixed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind", content = "value")]
pub enum Normalization {
    /// Rms height sqrt(m0) (m).
    RmsHeight(f64),
    /// Rms slope of a profile, sqrt(m2) (dimensionless). For an isotropic surface the rms
    /// of the gradient magnitude is sqrt(2) times larger: see [`Normalization::RmsGradient`].
    RmsSlope(f64),
    /// Rms of the gradient magnitude |grad z|, sqrt(2 m2) (dimensionless).
    RmsGradient(f64),
}

/// An isotropic self-affine surface spectrum (Persson's convention, <z^2> = integral of
/// C over the wavevector plane):
///
/// C(q) = C0 for q_l <= q < q_r (the roll-off plateau),
/// C(q) = C0 (q / q_r)^(-2(1 + H)) for q_r <= q <= q_s, and 0 outside [q_l, q_s],
///
/// with H the Hurst exponent (0 < H <= 1), q_l = 2 pi / lambda_l the long-wavelength
/// cut-off, q_r = 2 pi / lambda_r the roll-off (q_r = q_l: no plateau) and
/// q_s = 2 pi / lambda_s the short-wavelength cut-off.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SelfAffinePsd {
    /// Hurst exponent H.
    pub hurst: f64,
    /// Long-wavelength cut-off q_l (rad/m).
    pub q_l: f64,
    /// Roll-off wavevector q_r (rad/m), q_l <= q_r < q_s.
    pub q_r: f64,
    /// Short-wavelength cut-off q_s (rad/m).
    pub q_s: f64,
    /// Plateau level C0 (m^4).
    pub c0: f64,
}

/// (r^e - 1)/e computed without cancellation, with its limit ln r at e = 0.
fn pow_integral(e: f64, ln_r: f64) -> f64 {
    let x = e * ln_r;
    if x.abs() < 1e-10 {
        ln_r * (1.0 + 0.5 * x)
    } else {
        ln_r * x.exp_m1() / x
    }
}

impl SelfAffinePsd {
    /// The spectrum of Hurst exponent `hurst` between the wavelengths `lambda_l` (longest,
    /// m), optional `lambda_r` (roll-off, m; `None` = `lambda_l`) and `lambda_s`
    /// (shortest, m), scaled to the given rms height, slope or gradient.
    ///
    /// Errors: H outside (0, 1]; wavelengths not finite and positive or not ordered
    /// lambda_l >= lambda_r > lambda_s; a normalisation value not finite and positive.
    pub fn new(
        hurst: f64,
        lambda_l: f64,
        lambda_r: Option<f64>,
        lambda_s: f64,
        norm: Normalization,
    ) -> Result<Self> {
        if !(hurst > 0.0 && hurst <= 1.0) {
            return Err(TopographyError::param(
                "hurst",
                hurst,
                "the Hurst exponent must be in (0, 1]",
            ));
        }
        let lambda_r = lambda_r.unwrap_or(lambda_l);
        for (name, v) in [
            ("lambda_l", lambda_l),
            ("lambda_r", lambda_r),
            ("lambda_s", lambda_s),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(TopographyError::param(
                    name,
                    v,
                    "a wavelength must be finite and > 0 (m)",
                ));
            }
        }
        if !(lambda_l >= lambda_r && lambda_r > lambda_s) {
            return Err(TopographyError::param(
                "wavelengths",
                format!(
                    "lambda_l = {lambda_l:e}, lambda_r = {lambda_r:e}, lambda_s = {lambda_s:e}"
                ),
                "need lambda_l >= lambda_r > lambda_s",
            ));
        }
        let tau = 2.0 * std::f64::consts::PI;
        let mut psd = SelfAffinePsd {
            hurst,
            q_l: tau / lambda_l,
            q_r: tau / lambda_r,
            q_s: tau / lambda_s,
            c0: 1.0,
        };
        let unit = psd.moments();
        let (target, value, name) = match norm {
            Normalization::RmsHeight(v) => (v * v, unit.m0, "rms height"),
            Normalization::RmsSlope(v) => (v * v, unit.m2, "rms slope"),
            Normalization::RmsGradient(v) => (0.5 * v * v, unit.m2, "rms gradient"),
        };
        let given = match norm {
            Normalization::RmsHeight(v)
            | Normalization::RmsSlope(v)
            | Normalization::RmsGradient(v) => v,
        };
        if !(given.is_finite() && given > 0.0) {
            return Err(TopographyError::param(
                name,
                given,
                "must be finite and > 0",
            ));
        }
        psd.c0 = target / value;
        Ok(psd)
    }

    /// C(q) (m^4).
    pub fn c(&self, q: f64) -> f64 {
        if q < self.q_l || q > self.q_s {
            0.0
        } else if q < self.q_r {
            self.c0
        } else {
            self.c0 * (q / self.q_r).powf(-2.0 * (1.0 + self.hurst))
        }
    }

    /// I_k = integral of q^k C(q) dq over [q_l, q_s], in closed form.
    pub fn radial_integral(&self, k: i32) -> f64 {
        let kp = (k + 1) as f64;
        let plateau = (self.q_r.powf(kp) - self.q_l.powf(kp)) / kp;
        let e = kp - 2.0 * (1.0 + self.hurst);
        let power = self.q_r.powf(kp) * pow_integral(e, (self.q_s / self.q_r).ln());
        self.c0 * (plateau + power)
    }

    /// The analytic moments of the isotropic surface. With z = sum over q of its Fourier
    /// components and <z^2> = integral C d^2q, the profile moment of order n along x is
    /// m_n = integral C(q) q_x^n d^2q = (integral_0^2pi cos^n(theta) dtheta) I_(n+1):
    ///
    /// * m0 = 2 pi I_1,  m2 = pi I_3,  m4 = (3 pi / 4) I_5.
    pub fn moments(&self) -> Moments {
        let pi = std::f64::consts::PI;
        Moments::isotropic(
            2.0 * pi * self.radial_integral(1),
            pi * self.radial_integral(3),
            0.75 * pi * self.radial_integral(5),
            MomentMethod::Analytic,
        )
    }

    /// The GW parameters of this spectrum (McCool's formulas on its analytic moments).
    pub fn gw_parameters(&self) -> GwParameters {
        mccool(&self.moments())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Composite Simpson in ln q on each piece (an independent check of the closed forms).
    fn quad(psd: &SelfAffinePsd, k: i32) -> f64 {
        let piece = |a: f64, b: f64| {
            if !(b > a) {
                return 0.0;
            }
            let n = 20_000;
            let (la, lb) = (a.ln(), b.ln());
            let h = (lb - la) / n as f64;
            let f = |t: f64| {
                let q = t.exp();
                // mid-piece value avoids the discontinuity at q_r
                q.powi(k + 1) * psd.c(q.clamp(a * (1.0 + 1e-15), b * (1.0 - 1e-15)))
            };
            let mut s = f(la) + f(lb);
            for i in 1..n {
                s += f(la + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
            }
            s * h / 3.0
        };
        piece(psd.q_l, psd.q_r) + piece(psd.q_r, psd.q_s)
    }

    #[test]
    fn closed_form_moments_match_quadrature() {
        for &(h, lr) in &[
            (0.8, Some(2e-6)),
            (0.5, None),
            (1.0, Some(5e-6)),
            (0.2, None),
        ] {
            let psd =
                SelfAffinePsd::new(h, 10e-6, lr, 20e-9, Normalization::RmsHeight(5e-9)).unwrap();
            for k in [1, 3, 5] {
                let (a, q) = (psd.radial_integral(k), quad(&psd, k));
                assert!((a / q - 1.0).abs() < 1e-9, "H {h} k {k}: {a} vs {q}");
            }
            let m = psd.moments();
            assert!((m.m0.sqrt() / 5e-9 - 1.0).abs() < 1e-12);
            assert!(m.alpha() >= 1.5);
        }
    }

    #[test]
    fn normalisations_agree() {
        let a = SelfAffinePsd::new(0.7, 4e-6, None, 40e-9, Normalization::RmsSlope(0.1)).unwrap();
        assert!((a.moments().m2.sqrt() - 0.1).abs() < 1e-14);
        let b = SelfAffinePsd::new(
            0.7,
            4e-6,
            None,
            40e-9,
            Normalization::RmsGradient(0.1 * 2f64.sqrt()),
        )
        .unwrap();
        assert!((b.c0 / a.c0 - 1.0).abs() < 1e-12);
        let c = SelfAffinePsd::new(
            0.7,
            4e-6,
            None,
            40e-9,
            Normalization::RmsHeight(a.moments().m0.sqrt()),
        )
        .unwrap();
        assert!((c.c0 / a.c0 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bad_parameters_are_refused() {
        let n = Normalization::RmsHeight(1e-9);
        assert!(SelfAffinePsd::new(0.0, 1e-6, None, 1e-8, n).is_err());
        assert!(SelfAffinePsd::new(1.2, 1e-6, None, 1e-8, n).is_err());
        assert!(SelfAffinePsd::new(0.5, 1e-8, None, 1e-6, n).is_err());
        assert!(SelfAffinePsd::new(0.5, 1e-6, Some(2e-6), 1e-8, n).is_err());
        assert!(SelfAffinePsd::new(0.5, 1e-6, None, 1e-8, Normalization::RmsHeight(-1.0)).is_err());
        assert!(SelfAffinePsd::new(0.5, f64::NAN, None, 1e-8, n).is_err());
    }
}
