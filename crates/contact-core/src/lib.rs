//! Shared vocabulary of the `stiction` workspace.
//!
//! * validated material and pair types in SI units ([`Material`], [`Pair`]) and the
//!   paper's data ([`paper`]),
//! * the four law traits that join the crates: [`AdhesionLaw`], [`PlasticityLaw`],
//!   [`AsperityModel`], [`SurfaceLaw`],
//! * the numeric adapters every crate shares ([`numeric`]): bracketed roots and minima
//!   with a [`numeric::Tolerance`], error-controlled adaptive quadrature, sampling.
//!
//! Sign convention everywhere: interference `delta > 0` means overlap of the undeformed
//! profiles; compressive force/pressure is positive, adhesive (tensile) negative.
//!
//! ```
//! use contact_core::{paper, Material, Pair};
//! // the two Ru films of the paper's switch, as one sphere on a flat (eq 6)
//! let ru = Material::new(paper::RU)?;
//! let pair = Pair::new(ru, Some(ru), paper::RADIUS)?;
//! // K = 4/3 E*, E* = E / (2 (1 - nu^2)) for two identical bodies
//! assert!((pair.k() / (4.0 / 3.0 * 410e9 / 1.82) - 1.0).abs() < 1e-12);
//! # Ok::<(), contact_core::CoreError>(())
//! ```

// The README's example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

mod error;
mod material;
pub mod numeric;
pub mod par;
mod traits;

pub use error::{finite, positive, Categorized, Category, CoreError, LawError};
pub use material::{paper, Material, MaterialProps, Pair};
pub use traits::{
    AboveDeepest, AdhesionLaw, AsperityHistory, AsperityModel, Estimate, Jumps, LengthScales, Path,
    PlasticState, PlasticityLaw, SurfaceLaw, VirginWork, YieldingBody,
};
