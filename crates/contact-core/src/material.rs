use crate::error::{positive, CoreError};

/// The constants of an isotropic elastic-perfectly-plastic material, SI units, before
/// validation: the argument of [`Material::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MaterialProps {
    /// Young's modulus E (Pa, > 0).
    pub youngs_modulus: f64,
    /// Poisson ratio nu, in [0, 0.5).
    pub poisson_ratio: f64,
    /// Yield stress S_Y (Pa, > 0; `f64::INFINITY` for a body that never yields).
    pub yield_stress: f64,
}

/// An isotropic elastic-perfectly-plastic material, SI units.
///
/// Construct with [`Material::new`]; a value of this type is always valid.
///
/// ```
/// use contact_core::{paper, Material};
/// let ru = Material::new(paper::RU)?;
/// assert_eq!(ru.compliance(), (1.0 - 0.3 * 0.3) / 410e9);
/// # Ok::<(), contact_core::CoreError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Material {
    props: MaterialProps,
}

impl Material {
    /// Validates `props`: E finite and > 0, nu in [0, 0.5), S_Y > 0 (infinity allowed).
    pub fn new(props: MaterialProps) -> Result<Self, CoreError> {
        positive("youngs_modulus", props.youngs_modulus)?;
        if !(props.poisson_ratio.is_finite() && (0.0..0.5).contains(&props.poisson_ratio)) {
            return Err(CoreError::Invalid {
                field: "poisson_ratio",
                value: props.poisson_ratio,
                allowed: "in [0, 0.5)",
            });
        }
        if props.yield_stress.is_nan() || props.yield_stress <= 0.0 {
            return Err(CoreError::Invalid {
                field: "yield_stress",
                value: props.yield_stress,
                allowed: "> 0 (infinity for a material that never yields)",
            });
        }
        Ok(Self { props })
    }

    /// Young's modulus E (Pa).
    pub fn youngs_modulus(&self) -> f64 {
        self.props.youngs_modulus
    }
    /// Poisson ratio nu (-).
    pub fn poisson_ratio(&self) -> f64 {
        self.props.poisson_ratio
    }
    /// Yield stress S_Y (Pa); infinite for a body that never yields.
    pub fn yield_stress(&self) -> f64 {
        self.props.yield_stress
    }
    /// Plane-strain compliance (1 - nu^2)/E (1/Pa).
    pub fn compliance(&self) -> f64 {
        (1.0 - self.props.poisson_ratio * self.props.poisson_ratio) / self.props.youngs_modulus
    }
    /// The constants this material was built from.
    pub fn props(&self) -> MaterialProps {
        self.props
    }
}

/// Two contacting bodies reduced to one sphere of radius `radius` against a flat
/// (paper eq 6): composite modulus 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
/// K = 4/3 E*.
///
/// Body 1 carries the asperities; body 2 is either a second material or rigid
/// (`counter = None`). Which body yields is the plasticity law's decision
/// (`asperity_plastic::EtsionKadin` takes the one that yields first).
///
/// ```
/// use contact_core::{paper, Material, Pair};
/// let ru = Material::new(paper::RU)?;
/// let films = Pair::new(ru, Some(ru), paper::RADIUS)?;
/// assert!((films.e_star() - 0.5 * 410e9 / 0.91).abs() < 1e-3);
/// # Ok::<(), contact_core::CoreError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair {
    asperity: Material,
    counter: Option<Material>,
    radius: f64,
}

impl Pair {
    /// A sphere of `radius` R (m) of material `asperity` against a flat of `counter`
    /// (`None` for a rigid flat).
    pub fn new(
        asperity: Material,
        counter: Option<Material>,
        radius: f64,
    ) -> Result<Self, CoreError> {
        positive("radius", radius)?;
        Ok(Self {
            asperity,
            counter,
            radius,
        })
    }

    /// Equivalent radius of two spheres, R = R1 R2/(R1 + R2) (m, eq 6).
    pub fn equivalent_radius(r1: f64, r2: f64) -> Result<f64, CoreError> {
        positive("radius_1", r1)?;
        positive("radius_2", r2)?;
        Ok(r1 * r2 / (r1 + r2))
    }

    /// The asperity-carrying material (body 1).
    pub fn asperity(&self) -> &Material {
        &self.asperity
    }
    /// The counter-surface material (`None`: rigid).
    pub fn counter(&self) -> Option<&Material> {
        self.counter.as_ref()
    }
    /// Equivalent radius R (m).
    pub fn radius(&self) -> f64 {
        self.radius
    }
    /// Hertz composite modulus E* (Pa): 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
    pub fn e_star(&self) -> f64 {
        1.0 / (self.asperity.compliance() + self.counter.map_or(0.0, |m| m.compliance()))
    }
    /// Maugis' K = 4/3 E* (Pa, eq 6).
    pub fn k(&self) -> f64 {
        4.0 / 3.0 * self.e_star()
    }
}

/// The paper's data (Tables 1 and 2), SI units: the one fixture every crate's tests and
/// examples share.
pub mod paper {
    use super::MaterialProps;

    /// Ru film of Table 1: E = 410 GPa, nu = 0.3, S_Y = 3.42 GPa.
    pub const RU: MaterialProps = MaterialProps {
        youngs_modulus: 410e9,
        poisson_ratio: 0.3,
        yield_stress: 3.42e9,
    };
    /// Asperity tip radius R (m), Table 1.
    pub const RADIUS: f64 = 4e-6;
    /// Work of adhesion w (J/m^2), Table 1.
    pub const WORK_OF_ADHESION: f64 = 1.0;
    /// Dugdale range z0 (m), Table 1.
    pub const Z0: f64 = 0.169e-9;
    /// Standard deviation of asperity heights sigma_s (m), Table 1.
    pub const SIGMA_S: f64 = 7.78e-9;
    /// Asperities per unit area N (1/m^2): 10 per um^2, Table 1.
    pub const ASPERITY_DENSITY: f64 = 1e13;
    /// Initial air gap d0 (m), Table 2.
    pub const D0: f64 = 2e-6;
    /// Dielectric thickness t_d (m), Table 2.
    pub const T_D: f64 = 0.15e-6;
    /// Relative permittivity of the dielectric, Table 2.
    pub const EPSILON_R: f64 = 7.6;
    /// Vacuum permittivity (F/m), Table 2.
    pub const EPSILON_0: f64 = 8.854e-12;
    /// Ru film thickness t_s (m), Table 2.
    pub const FILM_THICKNESS: f64 = 180e-9;
    /// Impact energy per unit area E_I (J/m^2), section 3.
    pub const IMPACT_ENERGY: f64 = 0.5;
    /// Maximum interferences of Fig 2 (m).
    pub const FIG2_DELTA_MAX: [f64; 3] = [17e-9, 34e-9, 51e-9];
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(e: f64, nu: f64, sy: f64) -> Result<Material, CoreError> {
        Material::new(MaterialProps {
            youngs_modulus: e,
            poisson_ratio: nu,
            yield_stress: sy,
        })
    }

    #[test]
    fn rejects_out_of_domain_values() {
        assert!(m(-1.0, 0.3, 1e9).is_err());
        assert!(m(f64::NAN, 0.3, 1e9).is_err());
        assert!(m(1e11, 0.5, 1e9).is_err());
        assert!(m(1e11, -0.1, 1e9).is_err());
        assert!(m(1e11, 0.3, 0.0).is_err());
        assert!(m(1e11, 0.3, f64::INFINITY).is_ok());
        let ru = Material::new(paper::RU).unwrap();
        assert!(Pair::new(ru, None, 0.0).is_err());
        let msg = m(1e11, 0.7, 1e9).unwrap_err().to_string();
        assert!(
            msg.contains("poisson_ratio") && msg.contains("7e-1"),
            "{msg}"
        );
    }

    #[test]
    fn composite_modulus_of_identical_bodies_is_half_the_rigid_flat_value() {
        let ru = Material::new(paper::RU).unwrap();
        let rigid = Pair::new(ru, None, paper::RADIUS).unwrap();
        let twin = Pair::new(ru, Some(ru), paper::RADIUS).unwrap();
        // by hand: E* = E/(1 - nu^2) = 410e9/0.91 on a rigid flat
        assert!((rigid.e_star() - 410e9 / 0.91).abs() < 1e-3);
        assert!((twin.e_star() - 0.5 * rigid.e_star()).abs() < 1e-3);
        assert!((twin.k() - 4.0 / 3.0 * twin.e_star()).abs() < 1e-3);
        assert_eq!(Pair::equivalent_radius(4e-6, 4e-6).unwrap(), 2e-6);
    }
}
