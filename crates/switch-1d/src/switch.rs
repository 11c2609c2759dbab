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
/// dielectric of thickness `t_d` on the substrate electrode, and travels s = d0 - h to
/// contact, h the dimple height ([`Switch::with_dimple_height`], 0 by default: the
/// electrode lands on the dielectric, as in the paper); the effective electrostatic gap is
/// g = d0 + t_d/eps_r at rest and g - s = h + t_d/eps_r at contact.
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
    /// The air gap at which the contact (dimples or a bump) touches (m), in [0, d0).
    dimple_height: f64,
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
        Ok(Self {
            g,
            dimple_height: 0.0,
        })
    }

    /// The same switch on contact dimples (or a bump) of height `h` (m, in [0, d0)): the
    /// contact touches when the air gap is h, so the electrode travels s = d0 - h, the
    /// electrostatic gap at contact is h + t_d/eps_r, and the spring pulls back with
    /// K_s s at release.
    pub fn with_dimple_height(self, h: f64) -> Result<Self, SwitchError> {
        if !(h.is_finite() && h >= 0.0 && h < self.g.d0) {
            return Err(CoreError::Invalid {
                field: "dimple_height",
                value: h,
                allowed: "finite, >= 0 and below d0 (the contact must touch before the electrode meets the dielectric)",
            }
            .into());
        }
        Ok(Self {
            dimple_height: h,
            ..self
        })
    }

    /// The dimple height h (m; 0 without dimples).
    pub fn dimple_height(&self) -> f64 {
        self.dimple_height
    }

    /// The electrode's travel to contact, s = d0 - h (m).
    pub fn travel(&self) -> f64 {
        self.g.d0 - self.dimple_height
    }

    /// The electrostatic gap at contact, h + t_d/eps_r (m).
    pub fn contact_gap(&self) -> f64 {
        self.dimple_height + self.g.t_d / self.g.epsilon_r
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
    /// non-negative on [0, s] (s = d0 - h the travel) iff
    /// U^2 >= K_s g max y (g - y) / eps0: U = sqrt(K_s g^3/(4 eps0)) = sqrt(27/32) V_PI
    /// when s >= g/2, and U = sqrt(K_s g s (g - s)/eps0) when the travel is shorter (a
    /// thick dielectric, or dimples that stop the electrode early; derivation:
    /// `docs/theory.md` section 6.1).
    pub fn dynamic_pull_in_voltage(&self, k_s: f64) -> f64 {
        let g = self.effective_gap();
        let y = (0.5 * g).min(self.travel());
        (k_s * g * y * (g - y) / self.g.epsilon_0).sqrt()
    }

    /// Whether the electrode released at voltage `u` reaches contact: u at or above the
    /// dynamic pull-in voltage.
    pub fn closes(&self, k_s: f64, u: f64) -> bool {
        u >= self.dynamic_pull_in_voltage(k_s)
    }

    /// Impact energy per unit area (J/m^2) released from rest at voltage `u` (V), no
    /// damping: the net work over the travel s = d0 - h,
    /// E_I = (eps0 U^2/2)(1/(g - s) - 1/g) - K_s s^2/2, g - s = h + t_d/eps_r the gap at
    /// contact (with h = 0: (eps0 U^2/2)(eps_r/t_d - 1/g) - K_s d0^2/2).
    pub fn impact_energy(&self, k_s: f64, u: f64) -> f64 {
        let g = self.effective_gap();
        let s = self.travel();
        0.5 * self.g.epsilon_0 * u * u * (1.0 / self.contact_gap() - 1.0 / g) - 0.5 * k_s * s * s
    }

    /// The K_s (Pa/m) whose impact energy at U = V_PI(K_s) is `e_i` (J/m^2); both terms
    /// are linear in K_s: K_s = E_I / [(4 g^3/27)(1/(g - s) - 1/g) - s^2/2], s = d0 - h.
    pub fn stiffness_for_impact_energy(&self, e_i: f64) -> Result<f64, SwitchError> {
        positive("impact_energy", e_i)?;
        let g = self.effective_gap();
        let s = self.travel();
        let per_ks = 4.0 * g * g * g / 27.0 * (1.0 / self.contact_gap() - 1.0 / g) - 0.5 * s * s;
        if per_ks <= 0.0 {
            return Err(CoreError::Invalid {
                field: "d0",
                value: self.g.d0,
                allowed: "small enough that release at pull-in gains energy over the travel s = d0 - dimple_height ((4 g^3/27)(1/(h + t_d/eps_r) - 1/g) > s^2/2)",
            }
            .into());
        }
        Ok(e_i / per_ks)
    }

    /// Restoring pressure of the spring at contact, K_s s = K_s (d0 - h) (Pa).
    pub fn restoring_pressure(&self, k_s: f64) -> f64 {
        k_s * self.travel()
    }

    /// Electrostatic pressure (Pa, per electrode area) of the closed switch at voltage `u`
    /// (V): the air gap down to the dimple height h,
    /// p = eps0 U^2 / (2 (h + t_d/eps_r)^2) (without dimples eps0 eps_r^2 U^2/(2 t_d^2),
    /// the same idealisation as the impact energy's; the nanometres the surfaces stay
    /// apart are neglected against h + t_d/eps_r).
    pub fn closed_electrostatic_pressure(&self, u: f64) -> f64 {
        let g = self.contact_gap();
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

    /// Dimples of height h: the travel, the energy balance and the hold all end at the air
    /// gap h. By hand (Table 2 with h = 0.5 um): g = 2.019737 um, s = 1.5 um, the gap at
    /// contact h + t_d/eps_r = 0.519737 um; E_I(U) = (eps0 U^2/2)(1/0.519737 um -
    /// 1/2.019737 um) - K_s s^2/2; with K_s = 1e10 and U = 60 V: 0.5 x 8.854e-12 x 3600 x
    /// (1.924051e6 - 4.951140e5) - 0.5e10 x 2.25e-12 = 0.0227732 - 0.01125 = 0.0115232
    /// J/m^2; the restoring pressure K_s s = 1.5e4 Pa.
    #[test]
    fn dimples_shorten_the_travel_and_keep_the_gap_open() {
        let s = table2().with_dimple_height(0.5e-6).unwrap();
        assert_eq!(s.travel(), 1.5e-6);
        let e = s.impact_energy(1e10, 60.0);
        let by_hand = 0.5
            * paper::EPSILON_0
            * 3600.0
            * (1.0 / (0.5e-6 + 0.15e-6 / 7.6) - 1.0 / (2e-6 + 0.15e-6 / 7.6))
            - 0.5e10 * 1.5e-6 * 1.5e-6;
        assert!(
            (e - by_hand).abs() < 1e-15 && (e - 0.0115232).abs() < 1e-6,
            "{e}"
        );
        assert!((s.restoring_pressure(1e10) - 1.5e4).abs() < 1e-9);
        // the work along the shorter travel closes the balance at V_PI for the derived K_s
        let k = s.stiffness_for_impact_energy(0.05).unwrap();
        assert!((s.impact_energy(k, s.pull_in_voltage(k)) - 0.05).abs() < 1e-14);
        // far less electrostatic work than landing on the dielectric
        let flat = table2();
        assert!(s.impact_energy(1e10, 60.0) < 0.1 * flat.impact_energy(1e10, 60.0));
        // the hold: the parallel-plate pressure at the dimple gap
        let g = 0.5e-6 + 0.15e-6 / 7.6;
        assert!(
            (s.closed_electrostatic_pressure(10.0) - 0.5 * paper::EPSILON_0 * 100.0 / (g * g))
                .abs()
                < 1e-9
        );
        // h = 0 is the paper's switch to the bit
        let zero = table2().with_dimple_height(0.0).unwrap();
        assert_eq!(
            zero.impact_energy(1e10, 60.0),
            flat.impact_energy(1e10, 60.0)
        );
        assert_eq!(
            zero.stiffness_for_impact_energy(0.5).unwrap(),
            flat.stiffness_for_impact_energy(0.5).unwrap()
        );
        // a dimple at or above d0 never lets the contact touch
        assert!(table2().with_dimple_height(2e-6).is_err());
        assert!(table2().with_dimple_height(-1e-9).is_err());
        assert!(table2().with_dimple_height(f64::NAN).is_err());
        // the dynamic pull-in of a travel shorter than g/2: the net work at the end of the
        // travel is zero at that voltage
        let short = table2().with_dimple_height(1.5e-6).unwrap();
        let u = short.dynamic_pull_in_voltage(1e10);
        assert!(short.impact_energy(1e10, u).abs() < 1e-12 * 0.5 * paper::EPSILON_0 * u * u / 1e-6);
        assert!(short.closes(1e10, u) && !short.closes(1e10, 0.999 * u));
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
