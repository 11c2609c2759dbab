use crate::error::{positive, SwitchError};

/// Vacuum permittivity of Table 2 (F/m).
pub const EPSILON_0: f64 = 8.854e-12;

/// Geometry and spring of the 1D switch (Table 2), SI units.
///
/// Assumed geometry: the movable electrode starts at rest, an air gap `d0` above the
/// dielectric of thickness `t_d` on the substrate electrode, and travels `d0` to contact;
/// the effective electrostatic gap is g = d0 + t_d/eps_r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch {
    d0: f64,
    t_d: f64,
    eps_r: f64,
    eps0: f64,
}

impl Switch {
    /// Air gap `d0` (m), dielectric thickness `t_d` (m), relative permittivity `eps_r`
    /// (>= 1), vacuum permittivity `eps0` (F/m).
    pub fn new(d0: f64, t_d: f64, eps_r: f64, eps0: f64) -> Result<Self, SwitchError> {
        positive("d0", d0)?;
        positive("t_d", t_d)?;
        positive("epsilon_0", eps0)?;
        if !(eps_r.is_finite() && eps_r >= 1.0) {
            return Err(SwitchError::Invalid {
                field: "epsilon_r",
                value: eps_r,
                allowed: "finite and >= 1".into(),
            });
        }
        Ok(Self {
            d0,
            t_d,
            eps_r,
            eps0,
        })
    }

    /// Air gap d0 (m).
    pub fn d0(&self) -> f64 {
        self.d0
    }

    /// Effective gap g = d0 + t_d/eps_r (m).
    pub fn effective_gap(&self) -> f64 {
        self.d0 + self.t_d / self.eps_r
    }

    /// Static pull-in voltage V_PI = sqrt(8 K_s g^3 / (27 eps0)) (V) for stiffness
    /// `k_s` (Pa/m).
    pub fn pull_in_voltage(&self, k_s: f64) -> f64 {
        let g = self.effective_gap();
        (8.0 * k_s * g * g * g / (27.0 * self.eps0)).sqrt()
    }

    /// Impact energy per unit area (J/m^2) released from rest at voltage `u` (V), no
    /// damping: E_I = (eps0 U^2/2)(eps_r/t_d - 1/g) - K_s d0^2/2.
    pub fn impact_energy(&self, k_s: f64, u: f64) -> f64 {
        let g = self.effective_gap();
        0.5 * self.eps0 * u * u * (self.eps_r / self.t_d - 1.0 / g) - 0.5 * k_s * self.d0 * self.d0
    }

    /// The K_s (Pa/m) whose impact energy at U = V_PI(K_s) is `e_i` (J/m^2); both terms
    /// are linear in K_s: K_s = E_I / [(4 g^3/27)(eps_r/t_d - 1/g) - d0^2/2].
    pub fn stiffness_for_impact_energy(&self, e_i: f64) -> Result<f64, SwitchError> {
        positive("impact_energy", e_i)?;
        let g = self.effective_gap();
        let per_ks =
            4.0 * g * g * g / 27.0 * (self.eps_r / self.t_d - 1.0 / g) - 0.5 * self.d0 * self.d0;
        if per_ks <= 0.0 {
            return Err(SwitchError::Invalid {
                field: "d0",
                value: self.d0,
                allowed: "small enough that release at pull-in gains energy ((4 g^3/27)(eps_r/t_d - 1/g) > d0^2/2)".into(),
            });
        }
        Ok(e_i / per_ks)
    }

    /// Restoring pressure of the spring at contact, K_s d0 (Pa).
    pub fn restoring_pressure(&self, k_s: f64) -> f64 {
        k_s * self.d0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table2() -> Switch {
        Switch::new(2e-6, 0.15e-6, 7.6, EPSILON_0).unwrap()
    }

    #[test]
    fn stiffness_for_impact_energy_closes_the_energy_balance_at_pull_in() {
        let s = table2();
        let k = s.stiffness_for_impact_energy(0.5).unwrap();
        // by hand: g = 2.019737 um, bracket = 5.9241e-11 m^2 -> K_s = 8.4402e9 Pa/m
        assert!((k / 8.440183830384662e9 - 1.0).abs() < 1e-12, "{k}");
        let v = s.pull_in_voltage(k);
        assert!((v - 48.24046515534581).abs() < 1e-9, "{v}");
        assert!((s.impact_energy(k, v) - 0.5).abs() < 1e-12);
        assert!((s.restoring_pressure(k) - 16880.367660769323).abs() < 1e-6);
    }

    #[test]
    fn pull_in_voltage_scales_as_root_stiffness() {
        let s = table2();
        assert!((s.pull_in_voltage(4e9) / s.pull_in_voltage(1e9) - 2.0).abs() < 1e-14);
    }

    #[test]
    fn rejects_bad_geometry() {
        assert!(Switch::new(-2e-6, 0.15e-6, 7.6, EPSILON_0).is_err());
        assert!(Switch::new(2e-6, 0.15e-6, 0.5, EPSILON_0).is_err());
        assert!(Switch::new(2e-6, f64::NAN, 7.6, EPSILON_0).is_err());
        assert!(table2().stiffness_for_impact_energy(-1.0).is_err());
    }
}
