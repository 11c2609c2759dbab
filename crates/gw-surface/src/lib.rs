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

// The README's example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

mod error;
mod history;
mod surface;

pub use error::GwError;
pub use history::{GwHistory, HeightTable};
pub use surface::{GreenwoodWilliamson, Quadrature, Roughness, TAIL_SIGMAS};
