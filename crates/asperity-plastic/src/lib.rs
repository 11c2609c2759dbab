//! Plasticity of one asperity and the elasto-plastic adhesive asperity of the paper's
//! section 2.2.
//!
//! * [`EtsionKadin`]: yield onset (eq 1, Kogut-Etsion/Brizmer, with the reading of its
//!   modulus stated: [`YieldModulus`]), residual height and radius after unloading (eqs 4-5,
//!   Etsion, Kligerman & Kadin 2005) and the effective radius at the current interference
//!   (eqs 12-13, constants [`EffectiveRadiusFit`]).
//! * [`KogutEtsion`]: a second law family, Kogut & Etsion's (2002) loading force and area
//!   with Etsion, Kligerman & Kadin's (2005) residual state and unloading force, the radius
//!   the adhesion law sees derived from the published forces (`docs/theory.md` 2.7).
//! * [`AdhesionCoupled`]: either law driven by the adhesive contact itself (the Hertz
//!   interference a^2/R of the adhesion law's contact), for soft metals such as gold,
//!   where adhesion alone yields an asperity (theory 2.8).
//! * [`Elastic`]: never yields.
//! * [`ElastoPlasticAsperity`]: any [`PlasticityLaw`] composed with any
//!   [`AdhesionLaw`], implementing [`AsperityModel`], with its pull-off.
//!
//! ```
//! use asperity_plastic::{EtsionKadin, YieldModulus};
//! use contact_core::{paper, Material, Pair, PlasticityLaw};
//! let pair = Pair::new(Material::new(paper::RU)?, None, paper::RADIUS)?;
//! // the two readings of eq 1 differ by (1 - nu^2)^2 on a rigid flat
//! let printed = EtsionKadin::new(&pair, YieldModulus::AsPrinted)?;
//! let composite = EtsionKadin::new(&pair, YieldModulus::Composite)?;
//! assert!((composite.delta_cp() / printed.delta_cp() - 0.91 * 0.91).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// The README's example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

mod asperity;
mod coupled;
mod error;
mod etsion_kadin;
mod kogut_etsion;
mod onset;

pub use asperity::{EffectiveSphere, ElastoPlasticAsperity, PullOff, Reload, PULL_OFF_TOLERANCE};
pub use coupled::AdhesionCoupled;
pub use error::PlasticError;
pub use etsion_kadin::{
    EffectiveRadiusFit, Elastic, EtsionKadin, YieldModulus, YieldingBody, FIT_RANGE_MAX,
};
pub use kogut_etsion::{
    KogutEtsion, YieldOnset, KE_FULLY_PLASTIC, KE_HARDNESS_FACTOR, KE_SECOND_REGIME,
};

pub use contact_core::{AdhesionLaw, AsperityHistory, AsperityModel, PlasticState, PlasticityLaw};
