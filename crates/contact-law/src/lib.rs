//! The adhesive-contact law of a rough surface, tabulated for a finite-element code.
//!
//! A rough surface loaded by a flat remembers one number, d_min, the deepest separation it
//! reached (every asperity's delta_max is h - d_min). Its law is a family of curves
//! p(d; d_min, path) in SI units (d in m, pressure in Pa, compressive positive, adhesive
//! negative; d from the mean plane of asperity heights to the flat):
//!
//! * the virgin envelope p_V(d), followed whenever d < d_min (the history deepens);
//! * the approach (reload) branch p_A(d; d_min) and the retract branch p_R(d; d_min) for
//!   d >= d_min, both starting on the envelope at d = d_min, zero beyond their reach.
//!
//! [`ContactLaw`] reads `law.json`, validates it (errors name the JSON path) and evaluates
//! p and dp/dd in about 100 ns, with a history [`State`] ([`ContactLaw::pressure`]) or
//! without ([`ContactLaw::evaluate`]). [`tabulate::tabulate`] builds the file from any model
//! implementing [`tabulate::LawSource`], refining its grids adaptively and measuring the
//! interpolation error against the model. The crate depends on no model crate: an FE code
//! takes it alone (or its C ABI, `contact-law-capi`). The law, the file format and the FE
//! recipes are in `docs/contact-law.md`.
//!
//! ```
//! use contact_law::{tabulate::{tabulate, Tabulation}, toy::ToyLaw, ContactLaw, Path, State};
//!
//! // tabulate an analytic law (sigma = 3 nm) for histories 1.5 to 15 nm deep
//! let toy = ToyLaw::default();
//! let law = tabulate(&toy, &Tabulation::adaptive(1.5e-9, 15e-9)).unwrap();
//! assert!(law.measured_error().unwrap().max() < 1e-3);
//!
//! // a file round trip gives the same law
//! let law = ContactLaw::from_json_str(&law.to_json_string()).unwrap();
//!
//! // approach to 3 nm (virgin envelope), then retract: the history is d_min = 3 nm
//! let mut state = State::VIRGIN;
//! for d in [9e-9, 6e-9, 3e-9] {
//!     law.pressure(d, &mut state).unwrap();
//! }
//! let (p, _tangent) = law.pressure(3.2e-9, &mut state).unwrap();
//! assert_eq!((state.d_min, state.path), (3e-9, Path::Retract));
//! assert!((p - toy.retract(3.2e-9, 3e-9)).abs() < 1e-3 * toy.pull_out_point(3e-9).1.abs());
//! ```

mod error;
pub mod export;
mod format;
mod json;
mod law;
mod meta;
pub mod steffen;
pub mod tabulate;
pub mod toy;

pub use error::LawError;
pub use export::{InpDialect, InpUnits, OverclosureTable, EXPORT_TOLERANCE, MAX_ROWS};
pub use format::{FORMAT_NAME, FORMAT_VERSION, MAX_FILE_BYTES, RULE_IN_D, RULE_IN_D_MIN};
pub use law::{
    BranchError, BranchSet, ContactLaw, Curve, Evaluation, Path, Point, PositiveRetractTangent,
    PositiveTangent, Region, State, MOST_TENSILE_TOLERANCE,
};
pub use meta::{ErrorStats, MeasuredError, PartialReloadError, TabulationInfo};
