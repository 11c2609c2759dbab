//! Builds the concrete laws a scene asks for. Enum dispatch keeps one concrete asperity
//! type for every combination of laws, so the surface and switch code is compiled once.

use crate::scene::{Accuracy, AdhesionKind, Contact, CounterKind, PlasticityKind, Surface};
use asperity_plastic::{Elastic, ElastoPlasticAsperity, EtsionKadin};
use contact_core::{
    AdhesionLaw, Jumps, LawError, Material, Pair, Path, PlasticState, PlasticityLaw,
};
use gw_surface::{GreenwoodWilliamson, Quadrature};
use maugis_kim::{Dmt, Hertz, Jkr, MaugisKim};

/// Any of the adhesion laws of `maugis-kim`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyAdhesion {
    Hertz(Hertz),
    Dmt(Dmt),
    Jkr(Jkr),
    MaugisKim(MaugisKim),
}

impl AdhesionLaw for AnyAdhesion {
    fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        match self {
            AnyAdhesion::Hertz(l) => l.force(radius, delta, path),
            AnyAdhesion::Dmt(l) => l.force(radius, delta, path),
            AnyAdhesion::Jkr(l) => l.force(radius, delta, path),
            AnyAdhesion::MaugisKim(l) => l.force(radius, delta, path),
        }
    }
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
        match self {
            AnyAdhesion::Hertz(l) => l.jumps(radius),
            AnyAdhesion::Dmt(l) => l.jumps(radius),
            AnyAdhesion::Jkr(l) => l.jumps(radius),
            AnyAdhesion::MaugisKim(l) => l.jumps(radius),
        }
    }
    fn jump_in(&self, radius: f64) -> Result<f64, LawError> {
        match self {
            AnyAdhesion::Hertz(l) => l.jump_in(radius),
            AnyAdhesion::Dmt(l) => l.jump_in(radius),
            AnyAdhesion::Jkr(l) => l.jump_in(radius),
            AnyAdhesion::MaugisKim(l) => l.jump_in(radius),
        }
    }
    fn kinks(&self, radius: f64) -> Result<Vec<f64>, LawError> {
        match self {
            AnyAdhesion::Hertz(l) => l.kinks(radius),
            AnyAdhesion::Dmt(l) => l.kinks(radius),
            AnyAdhesion::Jkr(l) => l.kinks(radius),
            AnyAdhesion::MaugisKim(l) => l.kinks(radius),
        }
    }
}

/// Either plasticity law of `asperity-plastic`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyPlasticity {
    EtsionKadin(EtsionKadin),
    Elastic(Elastic),
}

impl PlasticityLaw for AnyPlasticity {
    fn radius(&self) -> f64 {
        match self {
            AnyPlasticity::EtsionKadin(l) => l.radius(),
            AnyPlasticity::Elastic(l) => l.radius(),
        }
    }
    fn critical_interference(&self) -> f64 {
        match self {
            AnyPlasticity::EtsionKadin(l) => l.critical_interference(),
            AnyPlasticity::Elastic(l) => l.critical_interference(),
        }
    }
    fn state(&self, delta_max: f64) -> PlasticState {
        match self {
            AnyPlasticity::EtsionKadin(l) => l.state(delta_max),
            AnyPlasticity::Elastic(l) => l.state(delta_max),
        }
    }
    fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64 {
        match self {
            AnyPlasticity::EtsionKadin(l) => l.effective_radius(state, delta),
            AnyPlasticity::Elastic(l) => l.effective_radius(state, delta),
        }
    }
}

/// The asperity every scene uses.
pub type Asperity = ElastoPlasticAsperity<AnyPlasticity, AnyAdhesion>;
/// The rough surface every scene uses.
pub type Surface_ = GreenwoodWilliamson<Asperity>;

/// A model-building failure (the scene was validated, so this is a law refusing it).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BuildError(pub String);

fn build_err(e: impl std::fmt::Display) -> BuildError {
    BuildError(e.to_string())
}

/// The pair of a scene.
pub fn pair(c: &Contact) -> Result<Pair, BuildError> {
    let m = Material::new(c.youngs_modulus, c.poisson_ratio, c.yield_stress).map_err(build_err)?;
    let counter = match c.counter {
        CounterKind::Rigid => None,
        CounterKind::Same => Some(m),
        CounterKind::Material => Some(
            Material::new(
                c.counter_youngs_modulus.unwrap_or(f64::NAN),
                c.counter_poisson_ratio.unwrap_or(f64::NAN),
                f64::INFINITY,
            )
            .map_err(build_err)?,
        ),
    };
    Pair::new(m, counter, c.radius).map_err(build_err)
}

/// The adhesion law of a scene.
pub fn adhesion(c: &Contact) -> Result<AnyAdhesion, BuildError> {
    let k = pair(c)?.k();
    Ok(match c.adhesion_law {
        AdhesionKind::Hertz => AnyAdhesion::Hertz(Hertz::new(k).map_err(build_err)?),
        AdhesionKind::Dmt => {
            AnyAdhesion::Dmt(Dmt::new(k, c.work_of_adhesion, c.z0).map_err(build_err)?)
        }
        AdhesionKind::Jkr => AnyAdhesion::Jkr(Jkr::new(k, c.work_of_adhesion).map_err(build_err)?),
        AdhesionKind::MaugisKim => {
            AnyAdhesion::MaugisKim(MaugisKim::new(k, c.work_of_adhesion, c.z0).map_err(build_err)?)
        }
    })
}

/// The asperity of a scene; `elastic` forces the elastic comparison law.
pub fn asperity(c: &Contact, elastic: bool) -> Result<Asperity, BuildError> {
    let p = pair(c)?;
    let plasticity = if elastic || c.plasticity_law == PlasticityKind::Elastic {
        AnyPlasticity::Elastic(Elastic::new(c.radius).map_err(build_err)?)
    } else {
        AnyPlasticity::EtsionKadin(EtsionKadin::new(&p, c.yield_modulus).map_err(build_err)?)
    };
    Ok(ElastoPlasticAsperity::new(plasticity, adhesion(c)?))
}

/// The quadrature of an accuracy mode.
pub fn quadrature(a: Accuracy) -> Quadrature {
    match a {
        Accuracy::Accurate => Quadrature::Adaptive { rel_tol: 1e-10 },
        Accuracy::Balanced => Quadrature::GaussLegendre {
            nodes: 12,
            panel_sigmas: 0.5,
        },
        Accuracy::Fast => Quadrature::GaussLegendre {
            nodes: 6,
            panel_sigmas: 1.0,
        },
    }
}

/// The rule of the eq-17 d-integral of an accuracy mode.
pub fn energy_rule(a: Accuracy) -> switch_1d::EnergyRule {
    match a {
        Accuracy::Accurate | Accuracy::Balanced => switch_1d::EnergyRule::DEFAULT,
        Accuracy::Fast => switch_1d::EnergyRule::COARSE,
    }
}

/// The rough surface of a scene.
pub fn surface(
    c: &Contact,
    s: &Surface,
    accuracy: Accuracy,
    elastic: bool,
) -> Result<Surface_, BuildError> {
    GreenwoodWilliamson::new(
        asperity(c, elastic)?,
        s.sigma_s,
        s.asperity_density,
        quadrature(accuracy),
    )
    .map_err(build_err)
}
