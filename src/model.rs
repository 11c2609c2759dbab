//! Builds the concrete laws a scene asks for. Enum dispatch keeps one concrete asperity
//! type for every combination of laws, so the surface and switch code is compiled once.

use crate::accuracy::Accuracy;
use crate::error::Error;
use crate::scene::{AdhesionKind, Contact, CounterKind, PlasticityKind, Surface};
use asperity_plastic::{EffectiveRadiusFit, Elastic, ElastoPlasticAsperity, EtsionKadin};
use contact_core::{
    AdhesionLaw, Jumps, LawError, Material, MaterialProps, Pair, Path, PlasticState, PlasticityLaw,
};
use gw_surface::{GreenwoodWilliamson, Roughness};
use maugis_kim::{Dmt, DugdaleParams, Hertz, Jkr, JkrParams, MaugisKim};

/// Any of the adhesion laws of `maugis-kim`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[allow(missing_docs)]
pub enum AnyAdhesion {
    Hertz(Hertz),
    Dmt(Dmt),
    Jkr(Jkr),
    MaugisKim(MaugisKim),
}

macro_rules! each_adhesion {
    ($self:expr, $l:ident => $e:expr) => {
        match $self {
            AnyAdhesion::Hertz($l) => $e,
            AnyAdhesion::Dmt($l) => $e,
            AnyAdhesion::Jkr($l) => $e,
            AnyAdhesion::MaugisKim($l) => $e,
        }
    };
}

impl AdhesionLaw for AnyAdhesion {
    fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        each_adhesion!(self, l => l.force(radius, delta, path))
    }
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
        each_adhesion!(self, l => l.jumps(radius))
    }
    fn jump_in(&self, radius: f64) -> Result<f64, LawError> {
        each_adhesion!(self, l => l.jump_in(radius))
    }
    fn kinks(&self, radius: f64) -> Result<Vec<Option<f64>>, LawError> {
        each_adhesion!(self, l => l.kinks(radius))
    }
}

/// Either plasticity law of `asperity-plastic`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[allow(missing_docs)]
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
    fn delta_cp(&self) -> f64 {
        match self {
            AnyPlasticity::EtsionKadin(l) => l.delta_cp(),
            AnyPlasticity::Elastic(l) => l.delta_cp(),
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
    fn fit_range(&self) -> Option<(f64, f64)> {
        match self {
            AnyPlasticity::EtsionKadin(l) => PlasticityLaw::fit_range(l),
            AnyPlasticity::Elastic(l) => PlasticityLaw::fit_range(l),
        }
    }
    fn yielding_body(&self) -> Option<contact_core::YieldingBody> {
        match self {
            AnyPlasticity::EtsionKadin(l) => PlasticityLaw::yielding_body(l),
            AnyPlasticity::Elastic(l) => PlasticityLaw::yielding_body(l),
        }
    }
}

/// The asperity every scene uses.
pub type Asperity = ElastoPlasticAsperity<AnyPlasticity, AnyAdhesion>;
/// The rough surface every scene uses.
pub type RoughSurface = GreenwoodWilliamson<Asperity>;

/// The film material of a scene.
pub fn material(c: &Contact) -> Result<Material, Error> {
    Ok(Material::new(MaterialProps {
        youngs_modulus: c.youngs_modulus,
        poisson_ratio: c.poisson_ratio,
        yield_stress: c.yield_stress,
    })?)
}

/// The pair of a scene: the film against a rigid flat, itself, or another material.
pub fn pair(c: &Contact) -> Result<Pair, Error> {
    let m = material(c)?;
    let counter = match c.counter {
        CounterKind::Rigid => None,
        CounterKind::Same => Some(m),
        CounterKind::Material => Some(Material::new(MaterialProps {
            youngs_modulus: c.counter_youngs_modulus.unwrap_or(f64::NAN),
            poisson_ratio: c.counter_poisson_ratio.unwrap_or(f64::NAN),
            yield_stress: c.counter_yield_stress.unwrap_or(f64::INFINITY),
        })?),
    };
    Ok(Pair::new(m, counter, c.radius)?)
}

/// The adhesion law of a scene.
pub fn adhesion(c: &Contact) -> Result<AnyAdhesion, Error> {
    let p = pair(c)?;
    let dugdale = DugdaleParams::for_pair(&p, c.work_of_adhesion, c.z0);
    Ok(match c.adhesion_law {
        AdhesionKind::Hertz => AnyAdhesion::Hertz(Hertz::new(p.k())?),
        AdhesionKind::Dmt => AnyAdhesion::Dmt(Dmt::new(dugdale)?),
        AdhesionKind::Jkr => AnyAdhesion::Jkr(Jkr::new(JkrParams {
            k: p.k(),
            work_of_adhesion: c.work_of_adhesion,
        })?),
        AdhesionKind::MaugisKim => AnyAdhesion::MaugisKim(MaugisKim::new(dugdale)?),
    })
}

/// The plasticity law of a scene; `elastic` forces the elastic comparison law.
pub fn plasticity(c: &Contact, elastic: bool) -> Result<AnyPlasticity, Error> {
    Ok(if elastic || c.plasticity_law == PlasticityKind::Elastic {
        AnyPlasticity::Elastic(Elastic::new(c.radius)?)
    } else {
        let fit = EffectiveRadiusFit::new(c.effective_radius.c1, c.effective_radius.c2)?;
        AnyPlasticity::EtsionKadin(EtsionKadin::new(&pair(c)?, c.yield_modulus())?.with_fit(fit))
    })
}

/// The asperity of a scene; `elastic` forces the elastic comparison law.
pub fn asperity(c: &Contact, elastic: bool) -> Result<Asperity, Error> {
    Ok(ElastoPlasticAsperity::new(
        plasticity(c, elastic)?,
        adhesion(c)?,
    ))
}

/// The rough surface of a scene at an accuracy mode (`abs_floor`: a pressure error in Pa
/// that does not matter, 0 for none).
pub fn surface(
    c: &Contact,
    s: &Surface,
    accuracy: Accuracy,
    abs_floor: f64,
    elastic: bool,
) -> Result<RoughSurface, Error> {
    Ok(GreenwoodWilliamson::new(
        asperity(c, elastic)?,
        Roughness {
            sigma_s: s.sigma_s,
            asperity_density: s.asperity_density,
        },
        accuracy.quadrature(abs_floor),
    )?)
}

/// The adhesion law's name as scenes spell it.
pub fn adhesion_name(k: AdhesionKind) -> &'static str {
    match k {
        AdhesionKind::Hertz => "hertz",
        AdhesionKind::Dmt => "dmt",
        AdhesionKind::Jkr => "jkr",
        AdhesionKind::MaugisKim => "maugis_kim",
    }
}

/// The plasticity law's name as scenes spell it.
pub fn plasticity_name(k: PlasticityKind) -> &'static str {
    match k {
        PlasticityKind::EtsionKadin => "etsion_kadin",
        PlasticityKind::Elastic => "elastic",
    }
}
