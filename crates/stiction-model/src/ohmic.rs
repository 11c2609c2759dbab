//! The ohmic switch: the contact resistance of the spots through which the current flows.
//!
//! Each contact spot of radius a between two films of resistivity rho and electron mean free
//! path lambda constricts the current: diffusively (Holm 1967; Maxwell's spreading
//! resistance of a circular spot between two half-spaces) when a >> lambda, ballistically
//! (Sharvin 1965) when a << lambda, and in between as Wexler (1966) interpolated,
//!
//!   R_M = rho / (2a),   R_S = 4 rho lambda / (3 pi a^2),   R_W = R_S + Gamma(K) R_M,
//!   Gamma(K) ~ (1 + 0.83 K) / (1 + 1.33 K),  K = lambda / a
//!
//! (Gamma as approximated by Nikolic & Allen 1999, Phys. Rev. B 60, 3963; Gamma -> 1 as
//! K -> 0, Gamma -> 0.624 as K -> infinity). The spots conduct in parallel (each spot's
//! current spreads before it meets its neighbours' when the spots are sparse, Greenwood
//! 1966); Greenwood's (1966) interaction of the spots of one apparent contact,
//! (rho / (pi n^2)) sum_(i != j) 1/s_ij, is for many spots scattered uniformly over a circle
//! of radius alpha 16 rho / (3 pi^2 alpha) (the mean inverse distance of two points of a
//! disk is 16 / (3 pi alpha)), reported beside (`docs/theory.md` section 6.5). Films,
//! contamination layers, tunnelling and heating are left out.

use crate::error::ModelError;
use crate::keys::num;
use serde::Serialize;

/// The conducting films: resistivity and electron mean free path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Conduction {
    /// Resistivity rho (ohm m).
    pub resistivity: f64,
    /// Electron mean free path lambda (m).
    pub mean_free_path: f64,
}

impl Conduction {
    /// Checked constants (both finite and > 0).
    pub fn new(resistivity: f64, mean_free_path: f64) -> Result<Self, ModelError> {
        for (name, v) in [
            ("resistivity", resistivity),
            ("mean_free_path", mean_free_path),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ModelError::argument(name, num(v), "finite and > 0"));
            }
        }
        Ok(Self {
            resistivity,
            mean_free_path,
        })
    }

    /// Holm's (Maxwell's) diffusive spreading resistance of a spot of radius `a` (m)
    /// between two half-spaces of the film: rho / (2a) (ohm).
    pub fn holm(&self, a: f64) -> f64 {
        self.resistivity / (2.0 * a)
    }

    /// Sharvin's ballistic resistance of a spot of radius `a` (m):
    /// 4 rho lambda / (3 pi a^2) (ohm).
    pub fn sharvin(&self, a: f64) -> f64 {
        4.0 * self.resistivity * self.mean_free_path / (3.0 * std::f64::consts::PI * a * a)
    }

    /// Wexler's interpolation of a spot of radius `a` (m) across the Knudsen number
    /// K = lambda/a: R_S + Gamma(K) R_M (ohm).
    pub fn spot_resistance(&self, a: f64) -> f64 {
        let k = self.mean_free_path / a;
        let gamma = (1.0 + 0.83 * k) / (1.0 + 1.33 * k);
        self.sharvin(a) + gamma * self.holm(a)
    }

    /// The conductance of a spot of radius `a` (S): 1 / [`Self::spot_resistance`].
    pub fn spot_conductance(&self, a: f64) -> f64 {
        if a > 0.0 {
            1.0 / self.spot_resistance(a)
        } else {
            0.0
        }
    }

    /// Greenwood's (1966) interaction term of many spots scattered uniformly over an
    /// apparent contact of area `area` (m^2), taken as a circle of radius
    /// alpha = sqrt(area / pi): (rho / (pi n^2)) sum_(i != j) 1/s_ij -> 16 rho / (3 pi^2 alpha)
    /// (ohm), to add to the spots in parallel. (Holm's rho / (2 alpha), the equipotential
    /// disk, is 8 % lower.)
    pub fn interaction_resistance(&self, area: f64) -> f64 {
        let alpha = (area / std::f64::consts::PI).sqrt();
        16.0 * self.resistivity / (3.0 * std::f64::consts::PI.powi(2) * alpha)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wexler_joins_holm_and_sharvin() {
        // gold: rho = 2.2e-8 ohm m, lambda = 37.7 nm (Gall 2016)
        let c = Conduction::new(2.2e-8, 37.7e-9).unwrap();
        // a >> lambda: diffusive, Holm's rho/2a
        let a = 1e-3;
        assert!((c.spot_resistance(a) / c.holm(a) - 1.0).abs() < 1e-4);
        // a << lambda: ballistic, Sharvin plus 0.624 of a vanishing Holm term
        let a = 1e-12;
        let r = c.spot_resistance(a);
        assert!(
            (r / c.sharvin(a) - 1.0).abs() < 2e-4,
            "{}",
            r / c.sharvin(a)
        );
        // in between, R_S + R_M bounds it above and each alone below
        let a = 30e-9;
        let r = c.spot_resistance(a);
        assert!(r < c.sharvin(a) + c.holm(a) && r > c.sharvin(a) && r > 0.624 * c.holm(a));
    }

    /// Greenwood's pair sum over spots scattered uniformly at random over a disk (a fixed
    /// xorshift sequence, 3,000 spots, 4.5 million pairs) agrees with the closed form
    /// 16 rho / (3 pi^2 alpha) of its expectation. (On a square lattice the sum is about
    /// 2 % lower at 2,809 spots: the lattice keeps neighbours apart.)
    #[test]
    fn greenwood_interaction_matches_its_pair_sum() {
        let c = Conduction::new(7.1e-8, 6.6e-9).unwrap();
        let alpha = 50e-6;
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut spots = Vec::new();
        while spots.len() < 3000 {
            let (x, y) = (2.0 * next() - 1.0, 2.0 * next() - 1.0);
            if x * x + y * y < 1.0 {
                spots.push((alpha * x, alpha * y));
            }
        }
        let n = spots.len() as f64;
        let mut sum = 0.0;
        for (k, a) in spots.iter().enumerate() {
            for b in &spots[k + 1..] {
                sum += 2.0 / ((a.0 - b.0).hypot(a.1 - b.1));
            }
        }
        // the pairs i != j of n spots: n (n - 1) of the n^2 in Greenwood's normalisation
        let pair = c.resistivity / (std::f64::consts::PI * n * (n - 1.0)) * sum;
        let closed = c.interaction_resistance(std::f64::consts::PI * alpha * alpha);
        assert!((pair / closed - 1.0).abs() < 0.01, "{pair} vs {closed}");
    }

    #[test]
    fn the_constants_are_checked_by_name() {
        let e = Conduction::new(-1.0, 1e-9).unwrap_err().to_string();
        assert!(e.contains("resistivity"), "{e}");
        let e = Conduction::new(1e-8, f64::NAN).unwrap_err().to_string();
        assert!(e.contains("mean_free_path"), "{e}");
    }
}
