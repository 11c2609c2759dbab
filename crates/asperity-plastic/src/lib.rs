//! Plasticity of one asperity and the elasto-plastic adhesive asperity of the paper's
//! section 2.2.
//!
//! * [`EtsionKadin`]: yield onset (eq 1, Kogut-Etsion/Brizmer), residual height and radius
//!   after unloading (eqs 4-5, Etsion, Kligerman & Kadin 2005) and the effective radius at
//!   the current interference (eqs 12-13).
//! * [`Elastic`]: never yields.
//! * [`ElastoPlasticAsperity`]: any [`PlasticityLaw`] composed with any
//!   [`AdhesionLaw`], implementing [`AsperityModel`].

mod asperity;
mod error;
mod etsion_kadin;

pub use asperity::ElastoPlasticAsperity;
pub use error::PlasticError;
pub use etsion_kadin::{Elastic, EtsionKadin, YieldModulus, FIT_RANGE_MAX};

pub use contact_core::{AdhesionLaw, AsperityHistory, AsperityModel, PlasticState, PlasticityLaw};
