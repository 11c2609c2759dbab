//! Greenwood-Williamson parameters from the spectral moments (McCool 1986, after Nayak 1971).

use serde::Serialize;

use crate::moments::Moments;

/// The three numbers a Greenwood-Williamson scene needs, plus the offset of the summits'
/// mean plane, all SI. Field names are part of the JSON contract.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GwParameters {
    /// Standard deviation of the **summit** heights (m): the model's `surface.sigma_s`.
    /// Smaller than the rms height of the surface.
    pub sigma_s: f64,
    /// Summits per unit area (1/m^2): the model's `surface.asperity_density`.
    pub asperity_density: f64,
    /// Summit radius (m), the reciprocal of the mean summit curvature: `contact.radius`.
    pub radius: f64,
    /// Height of the mean plane of the summits above the mean plane of the heights (m).
    /// The model measures separation from the summits' plane.
    pub offset: f64,
}

/// McCool's constant in sigma_s^2 = (1 - C/alpha) m0 (McCool 1986, from Nayak 1971).
pub const MCCOOL_SIGMA_CONSTANT: f64 = 0.8968;

/// The GW parameters of an isotropic Gaussian surface from its profile moments m0, m2, m4
/// (McCool 1986, Wear 107, 37-60, eqs for the "equivalent GW surface"; Nayak 1971,
/// J. Lubr. Technol. 93, 398-407):
///
/// * summit density  eta = m4 / (6 pi sqrt(3) m2)
/// * mean summit curvature kappa_m = (8/3) sqrt(m4/pi), so R = 1/kappa_m = 0.375 sqrt(pi/m4)
/// * summit height std sigma_s = sqrt(1 - 0.8968/alpha) sqrt(m0), alpha = m0 m4 / m2^2
/// * summit mean height  y_s = 4 sqrt(m0 / (pi alpha))
///
/// Density, curvature and offset are exact for a Gaussian isotropic surface (they follow from
/// the joint Gaussian statistics of height, gradient and Hessian: docs/topography.md
/// section 2); 0.8968 is McCool's fit of Nayak's exact variance. `sigma_s` is 0 when
/// alpha <= 0.8968 (outside the formula's domain; a real isotropic surface has alpha >= 1.5).
pub fn mccool(m: &Moments) -> GwParameters {
    let pi = std::f64::consts::PI;
    let alpha = m.alpha();
    let sigma_s = ((1.0 - MCCOOL_SIGMA_CONSTANT / alpha).max(0.0) * m.m0).sqrt();
    GwParameters {
        sigma_s,
        asperity_density: m.m4 / (6.0 * pi * 3f64.sqrt() * m.m2),
        radius: 0.375 * (pi / m.m4).sqrt(),
        offset: 4.0 * (m.m0 / (pi * alpha)).sqrt(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::moments::MomentMethod;
    use rand_chacha::rand_core::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn normal(rng: &mut ChaCha8Rng) -> f64 {
        // Box-Muller on (0, 1] uniforms.
        let u1 = ((rng.next_u64() >> 11) as f64 + 1.0) * (1.0 / (1u64 << 53) as f64);
        let u2 = (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }

    /// McCool's constants follow from the Gaussian statistics of an isotropic surface: at a
    /// summit (gradient 0, Hessian H negative definite, weight |det H|), E[z | H] =
    /// -(3 m2 / 4 m4) (z_xx + z_yy), and the Hessian (z_xx, z_yy, z_xy) is Gaussian with
    /// covariance m4 [[1, 1/3, 0], [1/3, 1, 0], [0, 0, 1/3]], independent of the gradient.
    /// A Monte Carlo over the Hessian gives the summit density (through E[|det H|; H < 0]
    /// = m4 / (3 sqrt 3) and the gradient density 1/(2 pi m2) at 0), the mean curvature
    /// (8/3) sqrt(m4/pi), and the constant of sigma_s^2 = m0 - (m2^2/m4)(3/2 -
    /// (9/16) var(z_xx + z_yy)/m4): 0.8968.
    #[test]
    fn mccool_constants_follow_from_gaussian_hessian_statistics() {
        let mut rng = ChaCha8Rng::seed_from_u64(26);
        let n = 2_000_000;
        let (l21, l22, lc) = (1.0 / 3.0, (8.0f64 / 9.0).sqrt(), (1.0f64 / 3.0).sqrt());
        let (mut sw, mut swl, mut swl2) = (0.0, 0.0, 0.0);
        for _ in 0..n {
            let (g1, g2, g3) = (normal(&mut rng), normal(&mut rng), normal(&mut rng));
            let (a, b, c) = (g1, l21 * g1 + l22 * g2, lc * g3);
            let det = a * b - c * c;
            if a < 0.0 && det > 0.0 {
                let lap = a + b;
                sw += det;
                swl += det * lap;
                swl2 += det * lap * lap;
            }
        }
        let e_det = sw / n as f64;
        let mean_lap = swl / sw;
        let var_lap = swl2 / sw - mean_lap * mean_lap;
        let pi = std::f64::consts::PI;
        // Monte Carlo standard errors at n = 2e6 are ~3e-4 (e_det), ~1e-3 (curvature),
        // ~4e-3 (the constant): tolerances are ~3 of them.
        assert!((e_det - 1.0 / (3.0 * 3f64.sqrt())).abs() < 1e-3, "{e_det}");
        assert!(
            (-mean_lap / 2.0 - 8.0 / 3.0 / pi.sqrt()).abs() < 3e-3,
            "{mean_lap}"
        );
        let c = 1.5 - 9.0 / 16.0 * var_lap;
        assert!((c - MCCOOL_SIGMA_CONSTANT).abs() < 1.2e-2, "{c}");
        // and the formulas use them consistently
        let m = Moments::isotropic(2.0, 3.0, 5.0, MomentMethod::Analytic);
        let gw = mccool(&m);
        let alpha = 2.0 * 5.0 / 9.0;
        assert!((gw.asperity_density * 2.0 * pi * 3.0 - 5.0 / (3.0 * 3f64.sqrt())).abs() < 1e-12);
        assert!((1.0 / gw.radius - 8.0 / 3.0 * (5.0 / pi).sqrt()).abs() < 1e-12);
        // y_s = (3 m2 / 2 m4) kappa_m, the regression of z on the Laplacian
        assert!((gw.offset - 1.5 * 3.0 / 5.0 / gw.radius).abs() < 1e-12);
        assert!((gw.sigma_s - ((1.0 - 0.8968 / alpha) * 2.0f64).sqrt()).abs() < 1e-12);
    }
}
