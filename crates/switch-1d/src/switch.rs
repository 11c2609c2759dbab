use crate::error::SwitchError;
use contact_core::{positive, CoreError};

/// Vacuum permittivity of Table 2 (F/m).
pub const EPSILON_0: f64 = 8.854e-12;

/// Table 2's geometry, SI units, before validation: the argument of [`Switch::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct SwitchGeometry {
    /// Initial air gap d0 (m).
    pub d0: f64,
    /// Dielectric thickness t_d (m).
    pub t_d: f64,
    /// Relative permittivity of the dielectric eps_d/eps_0 (>= 1).
    pub epsilon_r: f64,
    /// Vacuum permittivity eps_0 (F/m).
    pub epsilon_0: f64,
}

/// Geometry of the 1D switch (Table 2), SI units.
///
/// Assumed geometry: the movable electrode starts at rest, an air gap `d0` above the
/// dielectric of thickness `t_d` on the substrate electrode, and travels `d0` to contact;
/// the effective electrostatic gap is g = d0 + t_d/eps_r.
///
/// ```
/// use switch_1d::{Switch, SwitchGeometry};
/// use contact_core::paper;
/// let sw = Switch::new(SwitchGeometry { d0: paper::D0, t_d: paper::T_D, epsilon_r: paper::EPSILON_R, epsilon_0: paper::EPSILON_0 })?;
/// // the paper's K_s: 0.5 J/m^2 at pull-in
/// let k_s = sw.stiffness_for_impact_energy(0.5)?;
/// assert!((k_s / 8.4402e9 - 1.0).abs() < 1e-4);
/// // released from rest under a step voltage, the electrode closes above sqrt(27/32) V_PI
/// let ratio = sw.dynamic_pull_in_voltage(k_s) / sw.pull_in_voltage(k_s);
/// assert!((ratio - (27.0f64 / 32.0).sqrt()).abs() < 1e-12);
/// # Ok::<(), switch_1d::SwitchError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch {
    g: SwitchGeometry,
}

impl Switch {
    /// Validated geometry: d0, t_d, eps_0 finite and > 0, eps_r finite and >= 1.
    pub fn new(g: SwitchGeometry) -> Result<Self, SwitchError> {
        positive("d0", g.d0)?;
        positive("t_d", g.t_d)?;
        positive("epsilon_0", g.epsilon_0)?;
        if !(g.epsilon_r.is_finite() && g.epsilon_r >= 1.0) {
            return Err(CoreError::Invalid {
                field: "epsilon_r",
                value: g.epsilon_r,
                allowed: "finite and >= 1",
            }
            .into());
        }
        Ok(Self { g })
    }

    /// Air gap d0 (m).
    pub fn d0(&self) -> f64 {
        self.g.d0
    }

    /// The geometry.
    pub fn geometry(&self) -> SwitchGeometry {
        self.g
    }

    /// Effective gap g = d0 + t_d/eps_r (m).
    pub fn effective_gap(&self) -> f64 {
        self.g.d0 + self.g.t_d / self.g.epsilon_r
    }

    /// Static pull-in voltage V_PI = sqrt(8 K_s g^3 / (27 eps0)) (V) for stiffness
    /// `k_s` (Pa/m).
    pub fn pull_in_voltage(&self, k_s: f64) -> f64 {
        let g = self.effective_gap();
        (8.0 * k_s * g * g * g / (27.0 * self.g.epsilon_0)).sqrt()
    }

    /// Dynamic pull-in voltage (V): the lowest step voltage at which the electrode,
    /// released from rest at d0 (undamped), reaches contact. After a travel y the net work
    /// per unit area is W(y) = (eps0 U^2/2) y/(g (g - y)) - K_s y^2/2, which stays
    /// non-negative on [0, d0] iff U^2 >= K_s g max y (g - y) / eps0:
    /// U = sqrt(K_s g^3/(4 eps0)) = sqrt(27/32) V_PI when d0 >= g/2, and
    /// U = sqrt(K_s g d0 (g - d0)/eps0) when the dielectric is so thick that d0 < g/2
    /// (derivation: `docs/theory.md` section 6.1).
    pub fn dynamic_pull_in_voltage(&self, k_s: f64) -> f64 {
        let g = self.effective_gap();
        let y = (0.5 * g).min(self.g.d0);
        (k_s * g * y * (g - y) / self.g.epsilon_0).sqrt()
    }

    /// Whether the electrode released at voltage `u` reaches contact: u at or above the
    /// dynamic pull-in voltage.
    pub fn closes(&self, k_s: f64, u: f64) -> bool {
        u >= self.dynamic_pull_in_voltage(k_s)
    }

    /// Impact energy per unit area (J/m^2) released from rest at voltage `u` (V), no
    /// damping: E_I = (eps0 U^2/2)(eps_r/t_d - 1/g) - K_s d0^2/2 (the net work W(d0)).
    pub fn impact_energy(&self, k_s: f64, u: f64) -> f64 {
        let g = self.effective_gap();
        0.5 * self.g.epsilon_0 * u * u * (self.g.epsilon_r / self.g.t_d - 1.0 / g)
            - 0.5 * k_s * self.g.d0 * self.g.d0
    }

    /// The K_s (Pa/m) whose impact energy at U = V_PI(K_s) is `e_i` (J/m^2); both terms
    /// are linear in K_s: K_s = E_I / [(4 g^3/27)(eps_r/t_d - 1/g) - d0^2/2].
    pub fn stiffness_for_impact_energy(&self, e_i: f64) -> Result<f64, SwitchError> {
        positive("impact_energy", e_i)?;
        let g = self.effective_gap();
        let per_ks = 4.0 * g * g * g / 27.0 * (self.g.epsilon_r / self.g.t_d - 1.0 / g)
            - 0.5 * self.g.d0 * self.g.d0;
        if per_ks <= 0.0 {
            return Err(CoreError::Invalid {
                field: "d0",
                value: self.g.d0,
                allowed: "small enough that release at pull-in gains energy ((4 g^3/27)(eps_r/t_d - 1/g) > d0^2/2)",
            }
            .into());
        }
        Ok(e_i / per_ks)
    }

    /// Restoring pressure of the spring at contact, K_s d0 (Pa).
    pub fn restoring_pressure(&self, k_s: f64) -> f64 {
        k_s * self.g.d0
    }

    /// Electrostatic pressure (Pa, per electrode area) of the closed switch at voltage `u`
    /// (V): the air gap closed, the dielectric alone between the electrodes,
    /// p = eps0 eps_r^2 U^2 / (2 t_d^2) (the parallel-plate pressure eps0 U^2 / (2 g^2) at
    /// g = t_d/eps_r, the same idealisation as the impact energy's, which counts the travel
    /// to a closed gap; the nanometres the surfaces stay apart are neglected against
    /// t_d/eps_r).
    pub fn closed_electrostatic_pressure(&self, u: f64) -> f64 {
        let g = self.g.t_d / self.g.epsilon_r;
        0.5 * self.g.epsilon_0 * u * u / (g * g)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_core::paper;

    fn table2() -> Switch {
        Switch::new(SwitchGeometry {
            d0: paper::D0,
            t_d: paper::T_D,
            epsilon_r: paper::EPSILON_R,
            epsilon_0: paper::EPSILON_0,
        })
        .unwrap()
    }

    #[test]
    fn stiffness_for_impact_energy_closes_the_energy_balance_at_pull_in() {
        let s = table2();
        let k = s.stiffness_for_impact_energy(0.5).unwrap();
        // docs/derivations/by_hand.py recomputes these; by hand: g = 2e-6 + 0.15e-6/7.6 = 2.019737e-6 m,
        // bracket = (4 g^3/27)(7.6/0.15e-6 - 1/g) - d0^2/2 = 5.9241e-11 m^2 -> K_s = 8.4402e9 Pa/m
        assert!((k / 8.440183830384662e9 - 1.0).abs() < 1e-12, "{k}");
        let v = s.pull_in_voltage(k);
        assert!((v - 48.24046515534581).abs() < 1e-9, "{v}");
        assert!((s.impact_energy(k, v) - 0.5).abs() < 1e-12);
        assert!((s.restoring_pressure(k) - 16880.367660769323).abs() < 1e-6);
    }

    #[test]
    fn dynamic_pull_in_is_where_the_net_work_first_touches_zero() {
        let s = table2();
        let k = 1e10;
        let u = s.dynamic_pull_in_voltage(k);
        let g = s.effective_gap();
        let w =
            |u: f64, y: f64| 0.5 * paper::EPSILON_0 * u * u * y / (g * (g - y)) - 0.5 * k * y * y;
        // at U_dyn the work is >= 0 on [0, d0] and touches 0 (at y = g/2); just below it dips
        let ys: Vec<f64> = (1..=1000).map(|i| paper::D0 * i as f64 / 1000.0).collect();
        let min_at = |u: f64| ys.iter().map(|&y| w(u, y)).fold(f64::INFINITY, f64::min);
        assert!(min_at(u) >= -1e-12 * w(u, paper::D0).abs());
        assert!(min_at(0.999 * u) < 0.0);
        assert!(s.closes(k, u) && !s.closes(k, 0.999 * u));
        // and the ratio to the static pull-in is sqrt(27/32) = 0.9186 (d0 > g/2 here)
        assert!((u / s.pull_in_voltage(k) - (27.0f64 / 32.0).sqrt()).abs() < 1e-12);
        // a thick dielectric (d0 < g/2): the maximum of y (g - y) sits at y = d0
        let thick = Switch::new(SwitchGeometry {
            d0: 1e-6,
            t_d: 3e-6,
            epsilon_r: 1.0,
            epsilon_0: paper::EPSILON_0,
        })
        .unwrap();
        let g = thick.effective_gap();
        let expect = (k * g * 1e-6 * (g - 1e-6) / paper::EPSILON_0).sqrt();
        assert!((thick.dynamic_pull_in_voltage(k) / expect - 1.0).abs() < 1e-14);
        assert!(
            thick
                .impact_energy(k, thick.dynamic_pull_in_voltage(k))
                .abs()
                < 1e-9
        );
    }

    #[test]
    fn pull_in_voltage_scales_as_root_stiffness() {
        let s = table2();
        assert!((s.pull_in_voltage(4e9) / s.pull_in_voltage(1e9) - 2.0).abs() < 1e-14);
    }

    #[test]
    fn rejects_bad_geometry() {
        let g = table2().geometry();
        assert!(Switch::new(SwitchGeometry { d0: -2e-6, ..g }).is_err());
        assert!(Switch::new(SwitchGeometry {
            epsilon_r: 0.5,
            ..g
        })
        .is_err());
        assert!(Switch::new(SwitchGeometry { t_d: f64::NAN, ..g }).is_err());
        assert!(table2().stiffness_for_impact_energy(-1.0).is_err());
    }
}
