use crate::error::{positive, CoreError};
use serde::{Deserialize, Serialize};

/// An isotropic elastic-perfectly-plastic material, SI units.
///
/// Construct with [`Material::new`]; a value of this type is always valid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Material {
    youngs_modulus: f64,
    poisson_ratio: f64,
    yield_stress: f64,
}

impl Material {
    /// `youngs_modulus` E (Pa, > 0), `poisson_ratio` nu in [0, 0.5), `yield_stress` S_Y (Pa, > 0;
    /// `f64::INFINITY` for a material that never yields).
    pub fn new(
        youngs_modulus: f64,
        poisson_ratio: f64,
        yield_stress: f64,
    ) -> Result<Self, CoreError> {
        positive("youngs_modulus", youngs_modulus)?;
        if !(poisson_ratio.is_finite() && (0.0..0.5).contains(&poisson_ratio)) {
            return Err(CoreError::Invalid {
                field: "poisson_ratio",
                value: poisson_ratio,
                allowed: "in [0, 0.5)",
            });
        }
        if yield_stress.is_nan() || yield_stress <= 0.0 {
            return Err(CoreError::Invalid {
                field: "yield_stress",
                value: yield_stress,
                allowed: "> 0 (infinity for a material that never yields)",
            });
        }
        Ok(Self {
            youngs_modulus,
            poisson_ratio,
            yield_stress,
        })
    }

    /// Young's modulus E (Pa).
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }
    /// Poisson ratio nu (-).
    pub fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }
    /// Yield stress S_Y (Pa).
    pub fn yield_stress(&self) -> f64 {
        self.yield_stress
    }
    /// Plane-strain compliance (1 - nu^2)/E (1/Pa).
    pub fn compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus
    }
}

/// Two contacting bodies reduced to one sphere of radius `radius` against a flat
/// (paper eq 6): composite modulus 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
/// K = 4/3 E*, R = R1 R2 / (R1 + R2).
///
/// Body 1 carries the asperities and yields; body 2 is either a second material or
/// rigid (`counter = None`).
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

    /// Two spheres of radii `r1`, `r2` (m): R = R1 R2/(R1 + R2) (eq 6).
    pub fn two_spheres(m1: Material, r1: f64, m2: Material, r2: f64) -> Result<Self, CoreError> {
        positive("radius_1", r1)?;
        positive("radius_2", r2)?;
        Self::new(m1, Some(m2), r1 * r2 / (r1 + r2))
    }

    /// The yielding material.
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_out_of_domain_values() {
        assert!(Material::new(-1.0, 0.3, 1e9).is_err());
        assert!(Material::new(f64::NAN, 0.3, 1e9).is_err());
        assert!(Material::new(1e11, 0.5, 1e9).is_err());
        assert!(Material::new(1e11, -0.1, 1e9).is_err());
        assert!(Material::new(1e11, 0.3, 0.0).is_err());
        assert!(Material::new(1e11, 0.3, f64::INFINITY).is_ok());
        let m = Material::new(1e11, 0.3, 1e9).unwrap();
        assert!(Pair::new(m, None, 0.0).is_err());
        let msg = Material::new(1e11, 0.7, 1e9).unwrap_err().to_string();
        assert!(
            msg.contains("poisson_ratio") && msg.contains("0.7"),
            "{msg}"
        );
    }

    #[test]
    fn composite_modulus_of_identical_bodies_is_half_the_rigid_flat_value() {
        let m = Material::new(410e9, 0.3, 3.42e9).unwrap();
        let rigid = Pair::new(m, None, 4e-6).unwrap();
        let twin = Pair::new(m, Some(m), 4e-6).unwrap();
        assert!((rigid.e_star() - 410e9 / 0.91).abs() < 1e-3);
        assert!((twin.e_star() - 0.5 * rigid.e_star()).abs() < 1e-3);
        assert!((twin.k() - 4.0 / 3.0 * twin.e_star()).abs() < 1e-3);
        let two = Pair::two_spheres(m, 4e-6, m, 4e-6).unwrap();
        assert_eq!(two.radius(), 2e-6);
    }
}
