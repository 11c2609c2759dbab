//! Adhesive elastic contact of a sphere and a flat.
//!
//! * [`md`]: the Maugis-Dugdale solution (paper eqs 8-10) parametrised along its whole
//!   curve, joined to the non-contact branch of Kim, McMeeking & Johnson (1998); jump-in,
//!   turning point, pull-off under load and displacement control. Nondimensional (eq 7).
//! * [`MaugisKim`], [`Hertz`], [`Dmt`], [`Jkr`]: the same physics as SI
//!   [`contact_core::AdhesionLaw`]s.
//!
//! Nondimensional groups (eq 7), with K = 4/3 E*, w the work of adhesion, R the radius:
//! A = a (K/(pi w R^2))^(1/3), Fbar = F/(pi w R), Delta = delta (K^2/(pi^2 w^2 R))^(1/3),
//! lambda = 2 sigma0 (R/(pi w K^2))^(1/3), sigma0 = w/z0.
//!
//! ```
//! use maugis_kim::MdCurve;
//! // near the DMT end the load-control pull-off tends to -2 pi w R ...
//! let dmt_like = MdCurve::new(1e-3)?;
//! assert!((dmt_like.pull_off_load_control()?.force + 2.0).abs() < 5e-3);
//! // ... and near the JKR end to -3/2 pi w R (jump-out at -5/6 pi w R)
//! let jkr_like = MdCurve::new(1e3)?;
//! assert!((jkr_like.pull_off_load_control()?.force + 1.5).abs() < 2e-2);
//! assert!((jkr_like.pull_off_displacement_control()?.force + 5.0 / 6.0).abs() < 2e-2);
//! # Ok::<(), maugis_kim::MkError>(())
//! ```

// The README's example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

mod error;
mod guide_data;
mod laws;
pub mod md;
mod scales;
mod table;

pub use error::MkError;
pub use laws::{Dmt, DugdaleParams, Hertz, Jkr, JkrParams, MaugisKim};
pub use md::{Branch, MdCurve, MdPoint, LAMBDA_CRITICAL};
pub use scales::Scales;
/// Largest error of the interpolated Maugis-Kim force ([`MaugisKim::interpolated`],
/// [`MdCurve::force_interpolated`]) relative to max(|Fbar|, 1), i.e. to max(|F|, pi w R).
pub use table::MAX_ERROR as INTERPOLATION_ERROR;
