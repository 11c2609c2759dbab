//! The Greenwood-Williamson rough surface (paper section 2.3, eqs 14-16) with a plastic
//! history per asperity height.
//!
//! p(d) = N * integral F(h - d; delta_max(h), path) phi(h) dh, phi the Gaussian of
//! standard deviation sigma_s (eq 14), N asperities per unit area, d the separation of the
//! mean plane of asperity heights from the flat.
//!
//! The integrand jumps where asperities jump in or out and has kinks at yield onset and
//! where the effective radius switches (delta = delta_res): the height axis is split there
//! and each panel integrated with error control by globally adaptive nested Gauss-Legendre
//! rules (square-root substitution on the panel at the contact edge, where the force has
//! a square-root singularity). The split points only save work: an undeclared kink of a
//! user's law is refined around by the error control.
//!
//! ```
//! use asperity_plastic::{ElastoPlasticAsperity, Elastic};
//! use contact_core::{paper, Material, Pair, Path, SurfaceLaw};
//! use gw_surface::{GreenwoodWilliamson, Quadrature, Roughness};
//! use maugis_kim::Hertz;
//! // Hertz asperities at d = 0: p = N K sqrt(R) sigma^(3/2) F_3/2(0), with
//! // F_3/2(0) = integral of s^(3/2) phi(s) over s > 0 = 2^(1/4) Gamma(5/4) / sqrt(2 pi)
//! let ru = Material::new(paper::RU)?;
//! let pair = Pair::new(ru, Some(ru), paper::RADIUS)?;
//! let asperity = ElastoPlasticAsperity::new(Elastic::new(paper::RADIUS)?, Hertz::new(pair.k())?);
//! let rough = Roughness { sigma_s: paper::SIGMA_S, asperity_density: paper::ASPERITY_DENSITY };
//! let gw = GreenwoodWilliamson::new(asperity, rough, Quadrature::default())?;
//! let p = gw.pressure_estimate(0.0, &gw.virgin(), Path::Approach)?;
//! let classic = paper::ASPERITY_DENSITY * pair.k() * paper::RADIUS.sqrt()
//!     * paper::SIGMA_S.powf(1.5) * 0.430_019_993_662_26;
//! assert!((p.value / classic - 1.0).abs() < 1e-9 && p.error < 1e-9 * p.value);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// The README's example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

mod blocks;
mod error;
mod history;
mod reload;
mod surface;
mod virgin;

pub use error::GwError;
pub use history::{GwHistory, HeightTable};
pub use reload::ReloadTables;
pub use surface::{ContactSpots, GreenwoodWilliamson, Quadrature, Roughness, TAIL_SIGMAS};
