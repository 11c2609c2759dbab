//! Shared vocabulary of the `stiction` workspace.
//!
//! * validated material and pair types in SI units ([`Material`], [`Pair`]),
//! * the four law traits that join the crates: [`AdhesionLaw`], [`PlasticityLaw`],
//!   [`AsperityModel`], [`SurfaceLaw`],
//! * the numeric adapters every crate shares: a bracketed root with a *relative*
//!   tolerance ([`numeric::brent`]) and adaptive tanh-sinh quadrature with an error
//!   check ([`numeric::integrate`]).
//!
//! Sign convention everywhere: interference `delta > 0` means overlap of the undeformed
//! profiles; compressive force/pressure is positive, adhesive (tensile) negative.

mod error;
mod material;
pub mod numeric;
mod traits;

pub use error::{CoreError, LawError};
pub use material::{Material, Pair};
pub use traits::{
    AdhesionLaw, AsperityHistory, AsperityModel, Jumps, Path, PlasticState, PlasticityLaw,
    SurfaceLaw,
};
